//! The bit-rock interaction law of a drag (PDC) bit with a depth of cut: cutting plus
//! frictional contact, and the mechanical specific energy.
//!
//! Detournay & Defourny, "A phenomenological model for the drilling action of drag bits",
//! Int. J. Rock Mech. Min. Sci. 29 (1992) 13-23, in the form of Richard, Germay & Detournay,
//! "A simplified model to explore the root cause of stick-slip vibrations in drilling systems
//! with drag bits", J. Sound Vib. 305 (2007) 432-456 (the bit-rock interaction law):
//!
//! * cutting: `W_c = a zeta eps d`, `T_c = a^2 eps d / 2`;
//! * frictional contact on the wear flats: `W_f = a l sigma`, `T_f = gamma mu a W_f / 2`;
//!
//! with `a` the bit radius, `eps` the rock's intrinsic specific energy, `zeta` the ratio of the
//! vertical to the horizontal cutting force, `l` the total wear-flat length, `sigma` the contact
//! strength, `mu` the friction coefficient on the flats and `gamma` the bit's geometry factor.
//!
//! # Convention taken: the depth of cut
//!
//! `d` is the depth of cut **per revolution**, `d = n d_n`, with `d_n` the depth of cut of one
//! blade (the axial advance of the bit since the previous blade passed the same place, an angle
//! `2 pi / n` earlier, [`super::cut_surface`]) and `n` the number of blades (Richard et al. 2007). In steady drilling at the rate of penetration `V` and rotary speed `Omega` (rad/s)
//! `d_n = 2 pi V / (n Omega)` and `d = 2 pi V / Omega`, the advance per revolution.
//!
//! # Where the published code differs (Aarsnes & van de Wouw 2019)
//!
//! Aarsnes & van de Wouw, "Axial and torsional self-excited vibrations of a distributed
//! drill-string", J. Sound Vib. 444 (2019) 127-151, code github ulfjakob/AxialTorsionalDrillString
//! (commit 9344814), `Coupled/parameters.m`, `waveStep_transportBRI.m`, `waveStep_delayBRI.m`:
//!
//! * the contact torque is `p.Tf * p.Wf` with `p.Tf = gamma mu a`, i.e. `T_f = gamma mu a W_f`,
//!   twice Richard et al.'s `gamma mu a W_f / 2` (to reproduce it, pass `2 gamma` as
//!   [`Detournay::geometry`]);
//! * `waveStep_transportBRI.m` uses `d = N max(l, 0)`, per revolution as here;
//!   `waveStep_delayBRI.m` uses the blade's `d_n` itself in `W_c = K_a d` (a factor `n` less)
//!   and the first sample of the history more than a blade angle back (no interpolation);
//! * the set-valued contact is decided with thresholds on the last cell's speeds
//!   (`vb > 0.001`, `ob < 0.1`) instead of the exact phases of [`super::bit`].

use serde::Serialize;

use crate::drilling::config::Detournay;

use crate::error::{Error, Num, Result};

/// The Detournay cutting + frictional-contact law (SI units) of a bit of radius `radius`: the
/// configuration's keys `bit.detournay` ([`Detournay`], the one type of the law's parameters)
/// with the bit's radius `bit.radius`. Defaults: the dimensional case of Aarsnes & van de Wouw
/// (2019), `Coupled/parameters.m`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DetournayBit {
    /// Bit radius `a`, m.
    pub radius: f64,
    /// The law's parameters: blades `n`, intrinsic specific energy `eps`, cutting force ratio
    /// `zeta`, contact strength `sigma`, wear-flat length `l`, friction `mu`, geometry `gamma`.
    pub detournay: Detournay,
}

impl Default for DetournayBit {
    fn default() -> Self {
        DetournayBit::PUBLISHED
    }
}

impl DetournayBit {
    /// The dimensional case of Aarsnes & van de Wouw (2019), `Coupled/parameters.m`: their bit
    /// radius and [`Detournay::PUBLISHED`].
    pub const PUBLISHED: DetournayBit = DetournayBit { radius: 0.108, detournay: Detournay::PUBLISHED };

    /// Refuses non-finite or out-of-range fields, naming `<prefix>.<field>` (e.g. `bit.radius`).
    pub fn validate(&self, prefix: &str) -> Result<()> {
        let positive =
            [("radius", self.radius), ("intrinsic_specific_energy", self.detournay.intrinsic_specific_energy)];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(format!("{prefix}.{name}"), Num(value), "a finite number > 0"));
            }
        }
        let non_negative = [
            ("cutting_ratio", self.detournay.cutting_ratio),
            ("contact_strength", self.detournay.contact_strength),
            ("wear_flat_length", self.detournay.wear_flat_length),
            ("friction", self.detournay.friction),
            ("geometry", self.detournay.geometry),
        ];
        for (name, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::invalid(format!("{prefix}.{name}"), Num(value), "a finite number >= 0"));
            }
        }
        if self.detournay.blades == 0 {
            return Err(Error::invalid(format!("{prefix}.blades"), self.detournay.blades, "an integer >= 1"));
        }
        Ok(())
    }

    /// The cutting weight `W_c = a zeta eps d`, N, at the depth of cut per revolution `d` (m,
    /// `> 0`; Richard et al. 2007).
    #[inline]
    pub fn cutting_weight(&self, depth: f64) -> f64 {
        self.radius * self.detournay.cutting_ratio * self.detournay.intrinsic_specific_energy * depth
    }

    /// The cutting torque `T_c = a^2 eps d / 2`, N m, at the depth of cut per revolution `d`
    /// (m; Richard et al. 2007). `T_c Omega = eps pi a^2 V` in steady drilling: the
    /// intrinsic specific energy times the volume drilled per second.
    #[inline]
    pub fn cutting_torque(&self, depth: f64) -> f64 {
        0.5 * self.radius * self.radius * self.detournay.intrinsic_specific_energy * depth
    }

    /// The full contact weight `W_f = a l sigma`, N, of the wear flats pressed on the rock while
    /// the bit advances (Richard et al. 2007; at rest axially any value in `[0, W_f]`).
    #[inline]
    pub fn contact_weight(&self) -> f64 {
        self.radius * self.detournay.wear_flat_length * self.detournay.contact_strength
    }

    /// The contact torque `T_f = gamma mu a W_f / 2`, N m, of the contact weight `W_f` (N;
    /// Richard et al. 2007).
    #[inline]
    pub fn contact_torque(&self, contact_weight: f64) -> f64 {
        0.5 * self.detournay.geometry * self.detournay.friction * self.radius * contact_weight
    }

    /// The torque on bit, N m, of steady drilling at the weight on bit `w` (N, `>= 0`): below the
    /// full contact weight `W_f` the wear flats alone, `gamma mu a w / 2`; above it the depth of
    /// cut `d = (w - W_f) / (a zeta eps)` adds the cutting torque `a^2 eps d / 2` (the inverse of
    /// [`DetournayBit::steady_state`]'s weight).
    pub fn torque_at_weight(&self, w: f64) -> f64 {
        let wf = self.contact_weight();
        if w <= wf {
            return self.contact_torque(w);
        }
        let depth = (w - wf) / (self.radius * self.detournay.cutting_ratio * self.detournay.intrinsic_specific_energy);
        self.cutting_torque(depth) + self.contact_torque(wf)
    }

    /// The depth of cut per blade `d_n = d / n`, m, of the depth per revolution `d`.
    #[inline]
    pub fn per_blade(&self, depth: f64) -> f64 {
        depth / f64::from(self.detournay.blades)
    }

    /// The bit's angle between two blades, `2 pi / n`, rad: the delay of the cut surface.
    #[inline]
    pub fn blade_angle(&self) -> f64 {
        std::f64::consts::TAU / f64::from(self.detournay.blades)
    }

    /// Steady drilling at the rate of penetration `rop` (m/s, `>= 0`) and the rotary speed
    /// `omega` (rad/s, `> 0`): the depth of cut per revolution `d = 2 pi V / Omega`, the weight
    /// on bit `W = a zeta eps d + a l sigma` and the torque on bit
    /// `T = a^2 eps d / 2 + gamma mu a W_f / 2` (Richard et al. 2007, with the
    /// contact mobilised fully by the advancing bit).
    pub fn steady_state(&self, rop: f64, omega: f64) -> SteadyDrilling {
        let depth = std::f64::consts::TAU * rop / omega;
        let wf = self.contact_weight();
        SteadyDrilling {
            depth,
            weight_on_bit: self.cutting_weight(depth) + wf,
            torque_on_bit: self.cutting_torque(depth) + self.contact_torque(wf),
        }
    }
}

/// Steady drilling by [`DetournayBit::steady_state`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyDrilling {
    /// Depth of cut per revolution, m.
    pub depth: f64,
    /// N.
    pub weight_on_bit: f64,
    /// N m.
    pub torque_on_bit: f64,
}

/// The bit's face area `pi a^2`, m^2, of its radius `a` (m).
#[inline]
pub fn bit_area(radius: f64) -> f64 {
    std::f64::consts::PI * radius * radius
}

/// The mechanical specific energy, Pa (J/m^3): the energy spent per volume of rock drilled,
/// `MSE = WOB / A_bit + 2 pi N T / (A_bit ROP)` (Teale, "The concept of specific energy in rock
/// drilling", Int. J. Rock Mech. Min. Sci. 2 (1965) 57-73), here with SI inputs:
/// `weight_on_bit` N, `torque` N m, `rotary_speed` rad/s (`2 pi N` with `N` in rev/s), `rop` m/s,
/// `bit_area` m^2. `rop <= 0` (no rock drilled) gives `+inf` while torque work is spent and the
/// first term alone otherwise.
pub fn mechanical_specific_energy(weight_on_bit: f64, torque: f64, rotary_speed: f64, rop: f64, bit_area: f64) -> f64 {
    let rotary = torque * rotary_speed;
    let thrust = weight_on_bit / bit_area;
    if rop > 0.0 {
        thrust + rotary / (bit_area * rop)
    } else if rotary > 0.0 {
        f64::INFINITY
    } else {
        thrust
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn forces_by_hand() {
        let b = DetournayBit::default();
        // d = 1 mm per revolution: W_c = 0.108 * 0.6 * 60e6 * 1e-3 = 3888 N,
        // T_c = 0.108^2 * 60e6 * 1e-3 / 2 = 349.92 N m.
        assert!((b.cutting_weight(1e-3) - 3888.0).abs() < 1e-9);
        assert!((b.cutting_torque(1e-3) - 349.92).abs() < 1e-9);
        // W_f = 0.108 * 0.011 * 60e6 = 71280 N, T_f = 0.6 * 0.108 * 71280 / 2 = 2309.472 N m.
        assert!((b.contact_weight() - 71280.0).abs() < 1e-8);
        assert!((b.contact_torque(71280.0) - 2309.472).abs() < 1e-9);
        assert!((b.blade_angle() - PI / 2.0).abs() < 1e-15);
        assert_eq!(b.per_blade(4e-3), 1e-3);
    }

    #[test]
    fn steady_state_by_hand() {
        // 30 rpm, 30 m/h (their nominal point): d = 2 pi V / Omega = (30 / 3600) / 0.5 = 1/60 m.
        let b = DetournayBit::default();
        let s = b.steady_state(30.0 / 3600.0, PI);
        assert!((s.depth - 1.0 / 60.0).abs() < 1e-16);
        assert!((s.weight_on_bit - (3888.0e3 / 60.0 + 71280.0)).abs() < 1e-8);
        assert!((s.torque_on_bit - (349.92e3 / 60.0 + 2309.472)).abs() < 1e-9);
        // The cutting power is eps times the volume rate: T_c Omega = eps pi a^2 V.
        let v = 30.0 / 3600.0;
        assert!((b.cutting_torque(s.depth) * PI - 60e6 * PI * 0.108 * 0.108 * v).abs() < 1e-9);
    }

    #[test]
    fn mse_by_hand() {
        // WOB 100 kN, T 5 kN m, 120 rpm (4 pi rad/s), ROP 20 m/h = 1/180 m/s, A = 0.1 m^2:
        // 1e6 + 4 pi 5000 * 180 / 0.1 = 1e6 + 3.6e7 pi Pa.
        let mse = mechanical_specific_energy(100e3, 5e3, 4.0 * PI, 20.0 / 3600.0, 0.1);
        assert!((mse - (1e6 + 3.6e7 * PI)).abs() < 1e-6, "{mse}");
        assert_eq!(mechanical_specific_energy(100e3, 5e3, 4.0 * PI, 0.0, 0.1), f64::INFINITY);
        assert_eq!(mechanical_specific_energy(100e3, 0.0, 0.0, 0.0, 0.1), 1e6);
        assert!((bit_area(0.1) - 0.01 * PI).abs() < 1e-18);
        // Steady drilling with the Detournay law: MSE = W / A + eps + T_f Omega / (A V).
        let b = DetournayBit::default();
        let (v, w) = (20.0 / 3600.0, 4.0 * PI);
        let s = b.steady_state(v, w);
        let a = bit_area(b.radius);
        let mse = mechanical_specific_energy(s.weight_on_bit, s.torque_on_bit, w, v, a);
        let expect = s.weight_on_bit / a + 60e6 + b.contact_torque(b.contact_weight()) * w / (a * v);
        assert!((mse - expect).abs() < 1e-9 * expect);
    }

    #[test]
    fn validation_names_the_field() {
        assert!(DetournayBit::default().validate("bit").is_ok());
        let bad = Detournay { blades: 0, ..Detournay::PUBLISHED }.law(0.108);
        assert_eq!(bad.validate("bit").unwrap_err().field(), "bit.blades");
        let bad = Detournay { wear_flat_length: -1.0, ..Detournay::PUBLISHED }.law(0.108);
        assert_eq!(bad.validate("bit").unwrap_err().field(), "bit.wear_flat_length");
        let bad = DetournayBit { radius: f64::NAN, ..DetournayBit::default() };
        assert_eq!(bad.validate("bit").unwrap_err().field(), "bit.radius");
    }
}
