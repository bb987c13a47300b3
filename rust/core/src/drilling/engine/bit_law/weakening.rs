//! The Detournay law with velocity-weakening friction on the wear flats (`bit.law =
//! "detournay_weakening"`, `[bit.weakening]`): a drag (PDC) bit's cutting and frictional
//! contact (Detournay & Defourny, "A phenomenological model for the drilling action of drag
//! bits", Int. J. Rock Mech. Min. Sci. 29 (1992) 13-23; in the form of Richard, Germay &
//! Detournay, J. Sound Vib. 305 (2007) 432-456, [`crate::drilling::axial::bitrock`]) whose
//! wear-flat friction coefficient falls with the bit's angular speed `w` as in the
//! velocity-weakening bit law of Navarro-Lopez & Cortes, J. Sound Vib. 307 (2007) 152-171
//! ([`crate::drilling::bit::friction_coefficient`]):
//!
//! * cutting: `W_c = a zeta eps d`, `T_c = a^2 eps d / 2` (unchanged);
//! * contact: `W_f <= a l sigma`, `T_f = gamma mu(w) a W_f / 2` with
//!   `mu(w) = mu + (mu_0 - mu) exp(-decay |w|)`, from `mu_0` (`bit.weakening.static_friction`)
//!   at rest down to `mu` (`bit.detournay.friction`) fast.
//!
//! The friction coefficient of a step is the one at the bit's speed at the step start (as the
//! velocity-weakening law of the torsion-only bit): a bit at rest must overcome the static
//! contact torque `gamma mu_0 a W_f / 2 + T_c` to break free, a turning bit meets the lower
//! kinetic one, the negative slope of the torque against the speed that feeds torsional
//! stick-slip. The phases (cutting, stick, lift-off), the depth of cut (the rate form
//! `2 pi v / omega`) and the energy are those of the Detournay law at that coefficient. With
//! `mu_0 = mu` the law is the Detournay law (`bit.law = "detournay"`) to the bit.
//!
//! Steady drilling at `(V, Omega)`: `d = 2 pi V / Omega`, `W = a zeta eps d + a l sigma`,
//! `T = a^2 eps d / 2 + gamma mu(Omega) a^2 l sigma / 2`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{AxialNeed, BitEnds, BitRock};
use crate::drilling::axial::bit_boundary::BitContact;
use crate::drilling::axial::bitrock::{DetournayBit, SteadyDrilling};
use crate::drilling::bit::friction_coefficient;
use crate::drilling::config::Detournay;
use crate::error::{Error, Num, Result};

/// The velocity weakening of the wear flats' friction (`bit.law = "detournay_weakening"`):
/// `mu(w) = mu + (mu_0 - mu) exp(-decay |w|)` with `mu` the kinetic friction
/// `bit.detournay.friction`. Defaults: no weakening (`static_friction` = the default
/// `bit.detournay.friction`, 0.6).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Weakening {
    /// Friction coefficient `mu_0` at the wear-flat/rock contact of a bit at rest, at least
    /// `bit.detournay.friction` (the coefficient of a fast bit).
    #[schemars(extend("unit" = "", "label" = "wear-flat static friction"))]
    pub static_friction: f64,
    /// Rate `decay` of the friction's fall with the bit's speed, `exp(-decay |w|)`, >= 0.
    #[schemars(extend("unit" = "s/rad", "label" = "wear-flat friction decay"))]
    pub decay: f64,
}

impl Default for Weakening {
    fn default() -> Self {
        Weakening { static_friction: DetournayBit::PUBLISHED.detournay.friction, decay: 1.0 }
    }
}

impl Weakening {
    /// Refuses non-finite values, a negative decay or a static friction below the kinetic one
    /// `kinetic` (`bit.detournay.friction`).
    pub fn validate(&self, kinetic: f64) -> Result<()> {
        if !(self.static_friction.is_finite() && self.static_friction >= kinetic) {
            return Err(Error::invalid(
                "bit.weakening.static_friction",
                Num(self.static_friction),
                format!("a finite number >= bit.detournay.friction = {}", Num(kinetic)),
            ));
        }
        if !(self.decay.is_finite() && self.decay >= 0.0) {
            return Err(Error::invalid("bit.weakening.decay", Num(self.decay), "a finite number >= 0"));
        }
        Ok(())
    }
}

/// The Detournay law `cut` with the wear flats' friction weakening by `weakening`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetournayWeakening {
    pub cut: DetournayBit,
    pub weakening: Weakening,
}

impl DetournayWeakening {
    /// The wear flats' friction coefficient `mu(w)` at the bit speed `omega`, rad/s.
    #[inline]
    pub fn friction(&self, omega: f64) -> f64 {
        friction_coefficient(self.weakening.static_friction, self.cut.detournay.friction, self.weakening.decay, omega)
    }

    /// The Detournay law at the friction of the bit speed `omega`.
    #[inline]
    pub fn at(&self, omega: f64) -> DetournayBit {
        DetournayBit { detournay: Detournay { friction: self.friction(omega), ..self.cut.detournay }, ..self.cut }
    }
}

impl BitRock for DetournayWeakening {
    const AXIAL: AxialNeed = AxialNeed::DepthOfCut;

    /// The Detournay law at the friction of the speed at the step start.
    #[inline]
    fn resolve(&self, ends: &BitEnds) -> BitContact {
        self.at(ends.omega).resolve(ends)
    }

    /// The Detournay law's steady drilling at the friction of `omega`.
    fn steady(&self, rop: f64, omega: f64) -> Option<(SteadyDrilling, BitContact)> {
        self.at(omega).steady(rop, omega)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::axial::bit_boundary::{BitPhase, Port};
    use crate::drilling::engine::bit_law::AxialEnd;
    use crate::drilling::engine::boundary::EndLine;

    const CUT: DetournayBit = DetournayBit::PUBLISHED;

    fn law(static_friction: f64, decay: f64) -> DetournayWeakening {
        DetournayWeakening { cut: CUT, weakening: Weakening { static_friction, decay } }
    }

    /// The ends of a string pushing with `hold_w` N and turning with `hold_t` N m at rest
    /// (impedances of Aarsnes & van de Wouw's pipe), the bit at `omega` at the step start.
    fn ends(hold_w: f64, hold_t: f64, omega: f64, depth: f64) -> BitEnds {
        let (za, zt) = (1.4e5, 2.2e3);
        BitEnds {
            torsion: EndLine { drive: hold_t, denom: zt },
            omega,
            axial: Some(AxialEnd { port: Port { free_speed: hold_w / za, impedance: za }, depth }),
        }
    }

    #[test]
    fn the_contact_torque_follows_the_friction_at_the_speed_by_hand() {
        // a = 0.108 m, l = 11 mm, sigma = 60 MPa: W_f = 71280 N; d = 1 mm: W_c = 3888 N,
        // T_c = 349.92 N m. mu_0 = 0.9, mu = 0.6, decay = 0.5 s/rad at w = 2 rad/s:
        // mu = 0.6 + 0.3 exp(-1), T = 349.92 + mu * 0.108 * 71280 / 2.
        let l = law(0.9, 0.5);
        let mu = 0.6 + 0.3 * (-1.0f64).exp();
        let c = l.resolve(&ends(2e5, 2e4, 2.0, 1e-3));
        assert_eq!(c.phase, BitPhase::Cutting);
        assert!((c.weight_on_bit - (3888.0 + 71280.0)).abs() < 1e-8);
        let expected = 349.92 + mu * 0.108 * 71280.0 / 2.0;
        assert!((c.torque_on_bit - expected).abs() < 1e-9 * expected, "{} {expected}", c.torque_on_bit);
        // At rest the threshold is the static one: 349.92 + 0.9 * 3849.12 = 3814.128 N m.
        let breakaway = 349.92 + 0.9 * 0.108 * 71280.0 / 2.0;
        let below = l.resolve(&ends(2e5, breakaway - 1.0, 0.0, 1e-3));
        assert_eq!((below.phase, below.angular_speed), (BitPhase::Stick, 0.0));
        let above = l.resolve(&ends(2e5, breakaway + 1.0, 0.0, 1e-3));
        assert_eq!(above.phase, BitPhase::Cutting);
        assert!((above.torque_on_bit - breakaway).abs() < 1e-9 * breakaway);
        // The same drive on a bit turning fast slips: the kinetic threshold is lower.
        let fast = l.resolve(&ends(2e5, breakaway - 1.0, 100.0, 1e-3));
        assert_eq!(fast.phase, BitPhase::Cutting);
        assert!(fast.angular_speed > 0.0);
    }

    #[test]
    fn without_weakening_it_is_the_detournay_law_to_the_bit() {
        let l = law(CUT.detournay.friction, 3.0);
        for (w, t, omega, d) in [(2e5, 2e4, 2.0, 1e-3), (5e4, 1e3, 0.0, 2e-3), (-1e4, 3e3, 5.0, -1e-3)] {
            let e = ends(w, t, omega, d);
            assert_eq!(l.resolve(&e), CUT.resolve(&e));
        }
        assert_eq!(l.steady(0.01, 3.0), CUT.steady(0.01, 3.0));
    }

    #[test]
    fn steady_drilling_by_hand() {
        // 30 rpm (pi rad/s), 30 m/h: d = 1/60 m; T = 349.92e3 / 60 + mu(pi) * 3849.12.
        let l = law(0.8, 0.2);
        let (s, c) = l.steady(30.0 / 3600.0, std::f64::consts::PI).unwrap();
        let mu = 0.6 + 0.2 * (-0.2 * std::f64::consts::PI).exp();
        assert!((s.depth - 1.0 / 60.0).abs() < 1e-16);
        assert!((s.weight_on_bit - (3888.0e3 / 60.0 + 71280.0)).abs() < 1e-8);
        assert!((s.torque_on_bit - (349.92e3 / 60.0 + mu * 3849.12)).abs() < 1e-9);
        assert_eq!((c.torque_on_bit, c.phase), (s.torque_on_bit, BitPhase::Cutting));
        // The torque falls with the speed at a given depth of cut (velocity weakening).
        let slow = l.at(1.0).steady_state(0.01, 3.0).torque_on_bit;
        let fast = l.at(10.0).steady_state(0.01, 3.0).torque_on_bit;
        assert!(slow > fast);
    }

    #[test]
    fn validation_names_the_field() {
        assert!(Weakening::default().validate(0.6).is_ok());
        let e = Weakening { static_friction: 0.5, decay: 1.0 }.validate(0.6).unwrap_err();
        assert_eq!(e.field(), "bit.weakening.static_friction");
        let e = Weakening { static_friction: 0.7, decay: -1.0 }.validate(0.6).unwrap_err();
        assert_eq!(e.field(), "bit.weakening.decay");
        let e = Weakening { static_friction: f64::NAN, decay: 1.0 }.validate(0.6).unwrap_err();
        assert_eq!(e.field(), "bit.weakening.static_friction");
    }
}
