//! Viscous damping, the one dissipative term.
//!
//! Every discretisation here has a diagonal mass: the Galerkin modal masses `M_i` (the basis
//! is orthogonal) and the lumped masses of the finite differences. A term whose force per unit
//! length is proportional to `k1` (the mass per unit length, `rho I_p`) is then the same
//! operation on every coordinate, whatever the discretisation, and lives here once; each
//! system holds the term and calls it from its acceleration and its power.

use crate::error::{Error, Num, Result};

/// Viscous damping: the force per unit length `-rho I_p c th_t` (`-k1 c th_t`), the convention
/// of the Aarsnes-Shor torsional model, with the damping rate `c` in 1/s.
///
/// On a coordinate of mass `m_i` it is the force `-c m_i v_i`, the acceleration `-c v_i`; it
/// takes out the power `c sum_i m_i v_i^2` (twice the kinetic energy times `c`), and every
/// linear mode decays as `exp(-c t / 2)`. `c = 0` (the default) is no term at all.
///
/// ```
/// use drillstring_core::terms::ViscousDamping;
/// let damping = ViscousDamping::new(2.0).unwrap();
/// let mut acc = [1.0, 1.0];
/// damping.add_acceleration(&[0.5, -1.0], &mut acc);
/// assert_eq!(acc, [0.0, 3.0]);
/// assert_eq!(damping.power([1.0, 3.0], &[0.5, -1.0]), 2.0 * (0.25 + 3.0));
/// assert!(ViscousDamping::new(-1.0).is_err() && !ViscousDamping::default().is_active());
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ViscousDamping {
    rate: f64,
}

impl ViscousDamping {
    /// The term of damping rate `c` (1/s): finite and `>= 0`, else an error naming
    /// `"damping_rate"`.
    pub fn new(c: f64) -> Result<Self> {
        if c.is_finite() && c >= 0.0 {
            Ok(ViscousDamping { rate: c })
        } else {
            Err(Error::invalid("damping_rate", Num(c), "a finite number >= 0 (1/s)"))
        }
    }

    /// The damping rate `c`, 1/s.
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// Whether the term acts (`c != 0`): a system with an active term is velocity-dependent.
    pub fn is_active(&self) -> bool {
        self.rate != 0.0
    }

    /// Adds the accelerations `-c v_i` to `acc` (nothing when the term is not active).
    #[inline]
    pub fn add_acceleration(&self, v: &[f64], acc: &mut [f64]) {
        if self.is_active() {
            let c = self.rate;
            for (a, &vi) in acc.iter_mut().zip(v) {
                *a -= c * vi;
            }
        }
    }

    /// The power taken out, `c sum_i m_i v_i^2`, for the coordinates' masses `m_i`.
    pub fn power(&self, masses: impl IntoIterator<Item = f64>, v: &[f64]) -> f64 {
        self.rate * masses.into_iter().zip(v).map(|(m, vi)| m * vi * vi).sum::<f64>()
    }
}
