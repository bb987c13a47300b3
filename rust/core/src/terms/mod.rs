//! The model as composable physics terms, written once and discretised by each system.
//!
//! A [`ModelTerms`] is the inertia `k1`, the conservative terms ([`EnergyTerm`], each an energy
//! monomial `weight th^p th_z^r` with its paper equation, [`energy`]), the viscous damping
//! ([`ViscousDamping`], [`damping`]) and the [`Boundary`] ([`boundary`]). The discretisations
//! take a `ModelTerms` and discretise term by term:
//! [`crate::sweep::GalerkinIntegrals::discretise`] (the modal system) and
//! [`crate::pde::PdeSystem::discretise`] (the finite differences). A model variant
//! ([`crate::model`]) is a set of coefficients: [`ModelTerms::from_coefficients`] keeps the
//! terms whose coefficient is not zero.

pub mod boundary;
pub mod damping;
pub mod energy;

pub use boundary::Boundary;
pub use damping::ViscousDamping;
pub use energy::{EnergyTerm, TermSpec, EQ18_TERMS};

use crate::error::{Error, Num, Result};
use crate::pde::PdeCoefficients;

/// The inertia, the conservative terms, the damping and the boundary of one model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelTerms {
    inertia: f64,
    conservative: Vec<EnergyTerm>,
    damping: ViscousDamping,
    boundary: Boundary,
}

impl ModelTerms {
    /// The model of inertia `k1` (finite, `> 0`, field `"k1"`) and the given conservative
    /// terms, undamped, with free ends.
    pub fn new(k1: f64, conservative: Vec<EnergyTerm>) -> Result<Self> {
        if !k1.is_finite() {
            return Err(Error::invalid("k1", Num(k1), "a finite number"));
        }
        if k1 <= 0.0 {
            return Err(Error::invalid("k1", Num(k1), "a finite number > 0"));
        }
        Ok(ModelTerms { inertia: k1, conservative, damping: ViscousDamping::default(), boundary: Boundary::Free })
    }

    /// Eq. 18 with the coefficients `k1 .. k6`: the terms of [`EQ18_TERMS`] whose coefficient is
    /// not 0, in that order. Errors name the first non-finite `k` (`"k1"` .. `"k6"`), then
    /// `"k1"` unless `k1 > 0`.
    pub fn from_coefficients(k: impl Into<PdeCoefficients>) -> Result<Self> {
        let k = k.into().to_array();
        if let Some(j) = k.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(format!("k{}", j + 1), Num(k[j]), "a finite number"));
        }
        let mut conservative = Vec::with_capacity(EQ18_TERMS.len());
        for (spec, &coef) in EQ18_TERMS.iter().zip(&k[1..]) {
            if coef != 0.0 {
                conservative.push(spec.with(coef)?);
            }
        }
        ModelTerms::new(k[0], conservative)
    }

    /// The same model with the viscous damping rate `c` (1/s, field `"damping_rate"`).
    pub fn with_damping(mut self, c: f64) -> Result<Self> {
        self.damping = ViscousDamping::new(c)?;
        Ok(self)
    }

    /// The same model with other boundary conditions.
    pub fn with_boundary(mut self, boundary: Boundary) -> Self {
        self.boundary = boundary;
        self
    }

    /// `k1`, the inertia per unit length (`rho I_p`).
    pub fn inertia(&self) -> f64 {
        self.inertia
    }

    /// The conservative terms.
    pub fn conservative(&self) -> &[EnergyTerm] {
        &self.conservative
    }

    pub fn damping(&self) -> ViscousDamping {
        self.damping
    }

    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// The potential energy per unit length, the sum of the terms' densities.
    pub fn potential_density(&self, th: f64, th_z: f64) -> f64 {
        self.conservative.iter().map(|t| t.density(th, th_z)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_coefficients_are_no_term() {
        let m = ModelTerms::from_coefficients([2.0, 3.0, 0.0, 0.0, 5.0, 0.0]).unwrap();
        let names: Vec<_> = m.conservative().iter().map(|t| t.spec().coefficient).collect();
        assert_eq!(names, ["k2", "k5"]);
        assert_eq!((m.inertia(), m.boundary(), m.damping().is_active()), (2.0, Boundary::Free, false));
        let full = ModelTerms::from_coefficients([2.0, 3.0, 1.0, 1.0, 5.0, 1.0]).unwrap().with_damping(0.5).unwrap();
        assert_eq!(full.conservative().len(), 5);
        assert_eq!(full.damping().rate(), 0.5);
        // the density of eq. 18's energy H (without the kinetic term)
        let (th, thz): (f64, f64) = (0.3, -0.2);
        let h = 1.5 * thz * thz + 0.25 * th.powi(4) + 0.5 * th * th * thz * thz + 1.25 * thz.powi(4) - 0.5 * th * th;
        assert!((full.potential_density(th, thz) - h).abs() < 1e-15);
    }

    #[test]
    fn refusals_name_the_coefficient() {
        let field = |k: [f64; 6]| ModelTerms::from_coefficients(k).unwrap_err().field().to_string();
        assert_eq!(field([1.0, 1.0, f64::NAN, 1.0, 1.0, 1.0]), "k3");
        assert_eq!(field([0.0, 1.0, 1.0, 1.0, 1.0, 1.0]), "k1");
        assert_eq!(field([0.0, f64::INFINITY, 1.0, 1.0, 1.0, 1.0]), "k2");
        assert_eq!(ModelTerms::new(1.0, vec![]).unwrap().with_damping(-1.0).unwrap_err().field(), "damping_rate");
    }
}
