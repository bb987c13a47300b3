//! The bit-rock torque law, shared by the distributed string ([`super::solver`]) and the lumped
//! two-inertia model ([`super::lumped`]).
//!
//! Navarro-Lopez & Cortes, "Avoiding harmful oscillations in a drillstring through dynamical
//! analysis", J. Sound Vib. 307 (2007) 152-171: while the bit slips at speed `w`,
//! `T = W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)` with `W` the weight on bit, `r`
//! the bit radius and `decay = gamma_b / v_f` (the paper's `gamma_b` over its velocity scale
//! `v_f`); at rest the torque is whatever holds the bit, up to the static limit `W r mu_s`.
//!
//! [`VelocityWeakening`] is the law at the string's bit with its stick phase, a
//! [`BitRock`] law of the torsional field alone (the weight on bit `bit.weight_on_bit` given).

use super::axial::bit_boundary::{BitContact, BitPhase};
use super::engine::bit_law::{AxialNeed, BitEnds, BitRock};
use super::engine::boundary::EndLine;

/// The slipping bit's friction coefficient at the speed `speed` (rad/s):
/// `mu_kinetic + (mu_static - mu_kinetic) exp(-decay |speed|)`, from `mu_static` at rest down to
/// `mu_kinetic` fast (`decay` in 1/(rad/s)).
#[inline]
pub fn friction_coefficient(mu_static: f64, mu_kinetic: f64, decay: f64, speed: f64) -> f64 {
    mu_kinetic + (mu_static - mu_kinetic) * (-decay * speed.abs()).exp()
}

/// The torque of the slipping bit, N m: `W r mu(|speed|) sign(speed)` with `W r` given as
/// `weight_radius` (N m) and `mu` the [`friction_coefficient`].
#[inline]
pub fn slip_torque(weight_radius: f64, mu_static: f64, mu_kinetic: f64, decay: f64, speed: f64) -> f64 {
    (weight_radius * friction_coefficient(mu_static, mu_kinetic, decay, speed)).copysign(speed)
}

/// The Navarro-Lopez velocity-weakening torque `W r mu(|w|) sign(w)` ([`slip_torque`]) at the
/// string's bit with a stick phase: below `stick_speed`, or when the slip torque would reverse
/// the bit, the torque that stops it in this step if within `W r mu_s`, else `W r mu_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityWeakening {
    /// `W r`, N m.
    pub weight_radius: f64,
    pub mu_static: f64,
    pub mu_kinetic: f64,
    /// 1/(rad/s).
    pub decay: f64,
    /// rad/s.
    pub stick_speed: f64,
}

impl VelocityWeakening {
    /// The bit's new speed and torque on the line `line`, from the speed `w` at the step start.
    #[inline]
    pub fn resolve_line(&self, line: EndLine, w: f64) -> (f64, f64) {
        let VelocityWeakening { weight_radius: wr, mu_static, mu_kinetic, decay, stick_speed } = *self;
        // Stick: the torque that stops the bit in this step, if within the static limit.
        let stick = || {
            let hold = wr * mu_static;
            if line.drive.abs() <= hold {
                (0.0, line.drive)
            } else {
                let tb = hold.copysign(line.drive);
                (line.speed(tb), tb)
            }
        };
        if w.abs() < stick_speed {
            stick()
        } else {
            let tb = slip_torque(wr, mu_static, mu_kinetic, decay, w);
            let w1 = line.speed(tb);
            // A slip torque that would reverse the bit stops it instead (set-valued at 0).
            if w1 * w < 0.0 {
                stick()
            } else {
                (w1, tb)
            }
        }
    }
}

impl BitRock for VelocityWeakening {
    const AXIAL: AxialNeed = AxialNeed::None;

    #[inline]
    fn resolve(&self, ends: &BitEnds) -> BitContact {
        let (w1, torque) = self.resolve_line(ends.torsion, ends.omega);
        let phase = if w1 == 0.0 { BitPhase::Stick } else { BitPhase::Cutting };
        BitContact::torsional(w1, torque, phase)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_static_at_rest_to_kinetic_fast_and_odd() {
        assert_eq!(friction_coefficient(0.8, 0.5, 0.9, 0.0), 0.8);
        assert!((friction_coefficient(0.8, 0.5, 0.9, 1e3) - 0.5).abs() < 1e-15);
        let x = 1.7;
        let expected = 0.5 + 0.3 * (-0.9f64 * x).exp();
        assert!((friction_coefficient(0.8, 0.5, 0.9, -x) - expected).abs() < 1e-15);
        assert_eq!(slip_torque(100.0, 0.8, 0.5, 0.9, -x), -slip_torque(100.0, 0.8, 0.5, 0.9, x));
        assert!((slip_torque(100.0, 0.8, 0.5, 0.9, x) - 100.0 * expected).abs() < 1e-12);
    }
}
