//! The bit as the bottom boundary of the coupled axial and torsional fields: the Detournay law
//! ([`super::bitrock`]) as a set-valued problem with three phases, cutting, stick and lift-off.
//!
//! # The problem
//!
//! Each field meets the bit through its incoming Riemann invariant: with the characteristic
//! arriving at the bit (`alpha = v + F / Z_a`, `alpha = omega + tau / Z_t`, [`super::section`])
//! the bit's speeds and the forces the rock returns are related by
//! `v = v_in - W / Z_a`, `omega = omega_in - T / Z_t` (Aarsnes & van de Wouw 2019, the bit
//! boundary of their `waveStep_transportBRI.m`, `AbetaPp1 = Aalpha(P) - 2 wb c_a / (A_p E)`).
//! A lumped BHA of mass `M` (inertia `I`) stepped semi-implicitly, `M (v' - v) / dt = Z_a (v_in - v') + F - W`,
//! has the same form with `Z = Z_a + M / dt` and `v_in = (M v / dt + Z_a v_in + F) / Z`
//! ([`Port::lumped`]; the bit step of `drilling/solver.rs` does the same for the torsional BHA).
//! `Z v_in` is the force that would hold the bit at rest (`W_hold`, `T_hold`).
//!
//! Given the depth of cut per revolution `d` of the step ([`super::cut_surface`]), the phases
//! (Richard, Germay & Detournay, J. Sound Vib. 305 (2007) 432-456, the bit-rock
//! interaction and its stick phase: contact
//! set-valued in the axial speed, the bit stuck when its angular speed vanishes, no rotation
//! backwards in contact, loss of contact for `d <= 0`; Germay, Denoël & Detournay, "Multiple
//! mode analysis of the self-excited vibrations of rotary drilling systems", J. Sound Vib. 325
//! (2009) 362-381, for the bit bounce):
//!
//! * **lift-off** (bit bounce), `d <= 0`: no contact, `W = T = 0`, `v = v_in`,
//!   `omega = omega_in` (the bit may turn either way);
//! * **cutting**, `d > 0` and `T_hold > T*`: `W = W_c + W_f`, `T = T_c + T_f(W_f)`,
//!   `omega = omega_in - T / Z_t > 0`, with the contact weight set-valued in the axial speed:
//!   `W_f = clamp(W_hold - W_c, 0, a l sigma)`, i.e. `W_f = a l sigma` while the bit advances
//!   (`v > 0`), `W_f` in `[0, a l sigma]` holding it at `v = 0`, `W_f = 0` while it rises
//!   (`v < 0`, the wear flats leave the rock; the cutters still cut);
//!   `T* = T_c + T_f(W_f)` is this torque;
//! * **stick**, `d > 0` and `T_hold <= T*`: `omega = 0`, `T = T_hold` (any torque below the
//!   threshold is held, negative ones too: no backward rotation in contact), and the bit stops
//!   axially with its rotation, the rock holding it (`v = 0`, `W = W_hold`) unless the string
//!   pulls it up (`W_hold < 0`: `W = 0`, `v = v_in`): the cutters cannot advance without turning
//!   (Richard et al. 2007; the published code's `g_wt` likewise).
//!
//! Every input has one solution, exact (no thresholds on speeds); `omega` and `T` are continuous
//! from cutting into stick (`omega -> 0` as `T_hold -> T*`), `W`, `T`, `v` and `omega` from
//! cutting into lift-off on a rising bit (`W_f = 0`, `W_c, T_c -> 0` as `d -> 0`). The axial
//! speed jumps to 0 when the bit sticks while advancing (the rigid stop of the law).
//!
//! # Energy
//!
//! The power into the rock is `P = W v + T omega`. Lift-off and stick: `P = 0`. Cutting:
//! `P = eps a d (zeta v + a omega / 2) + W_f v + T_f omega`; the contact part is `>= 0` in every
//! phase (`W_f > 0` only with `v >= 0`); the cutting part is `>= 0` unless the bit rises faster
//! than `a omega / (2 zeta)` while still cutting, when the rate-independent law returns energy
//! to the axial motion (taken from the rotation: the regenerative coupling). In steady drilling
//! its torque part `T_c omega` is the intrinsic specific energy times the drilled volume rate,
//! `eps pi a^2 V`.

use serde::Serialize;

use super::bitrock::{DetournayBit, SteadyDrilling};
use crate::drilling::engine::bit_law::{AxialNeed, BitEnds, BitRock};
use crate::drilling::engine::boundary::EndLine;

/// One field's end at the bit: `speed = free_speed - load / impedance`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Port {
    /// The speed the bit would have with no load, m/s or rad/s.
    pub free_speed: f64,
    /// N s/m or N m s.
    pub impedance: f64,
}

impl Port {
    /// The string's end without a lumped body: the incoming invariant `alpha` (the speed the end
    /// would have unloaded) and the section's impedance.
    pub fn string(incoming: f64, impedance: f64) -> Port {
        Port { free_speed: incoming, impedance }
    }

    /// The string's end carrying a lumped body of inertia `inertia` (kg, or kg m^2) that moved
    /// at `previous_speed` and is pushed by the constant `applied` load (N or N m, e.g. the BHA's
    /// buoyed weight), stepped over `dt` semi-implicitly:
    /// `I (v' - v) / dt = Z (alpha - v') + applied - load`, so
    /// `Z_eff = Z + I / dt`, `free = (I v / dt + Z alpha + applied) / Z_eff`.
    pub fn lumped(incoming: f64, impedance: f64, inertia: f64, previous_speed: f64, dt: f64, applied: f64) -> Port {
        let z = impedance + inertia / dt;
        Port { free_speed: (inertia * previous_speed / dt + impedance * incoming + applied) / z, impedance: z }
    }

    /// The end of a momentum balance's line [`EndLine`] (`(I / dt + Z) w' = I w / dt + Z alpha -
    /// load`): [`Port::lumped`] with no applied load, to the same bits.
    #[inline]
    pub fn of_line(line: EndLine) -> Port {
        Port { free_speed: (line.drive + 0.0) / line.denom, impedance: line.denom }
    }

    /// The speed under the load `load`.
    #[inline]
    pub fn speed(&self, load: f64) -> f64 {
        self.free_speed - load / self.impedance
    }

    /// The load that holds the end at rest, `Z free_speed`.
    #[inline]
    pub fn hold(&self) -> f64 {
        self.impedance * self.free_speed
    }
}

/// The phase of the bit in a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BitPhase {
    /// In contact and turning: the law's forces.
    Cutting,
    /// In contact and not turning (`omega = 0`): the torque held below the threshold.
    Stick,
    /// Off the rock (`d <= 0`): no forces (bit bounce).
    LiftOff,
}

/// The bit's state after [`solve_bit`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BitContact {
    /// Axial speed, m/s (down positive).
    pub axial_speed: f64,
    /// Angular speed, rad/s.
    pub angular_speed: f64,
    /// Weight on bit `W`, N (the rock's push on the bit, `>= 0`).
    pub weight_on_bit: f64,
    /// Torque on bit `T`, N m.
    pub torque_on_bit: f64,
    /// The frictional-contact part `W_f` of the weight while cutting (0 otherwise), N.
    pub contact_weight: f64,
    /// The frictional-contact part `T_f` of the torque while cutting (0 otherwise), N m.
    pub contact_torque: f64,
    pub phase: BitPhase,
}

impl BitContact {
    /// A law of the torsional field alone: the angular speed and torque in `phase`, no axial
    /// speed nor weight.
    #[inline]
    pub fn torsional(angular_speed: f64, torque_on_bit: f64, phase: BitPhase) -> Self {
        BitContact {
            axial_speed: 0.0,
            angular_speed,
            weight_on_bit: 0.0,
            torque_on_bit,
            contact_weight: 0.0,
            contact_torque: 0.0,
            phase,
        }
    }

    /// The power into the rock, `W v + T omega`, W.
    pub fn power(&self) -> f64 {
        self.weight_on_bit * self.axial_speed + self.torque_on_bit * self.angular_speed
    }

    /// The power of the frictional contact, `W_f v + T_f omega >= 0`, W.
    pub fn contact_power(&self) -> f64 {
        self.contact_weight * self.axial_speed + self.contact_torque * self.angular_speed
    }
}

/// The bit's speeds, weight and torque and its phase for the depth of cut per revolution
/// `depth` (m) with the fields' ends `axial` and `torsion` (see the module).
pub fn solve_bit(law: &DetournayBit, axial: Port, torsion: Port, depth: f64) -> BitContact {
    if depth.is_nan() || depth <= 0.0 {
        return BitContact {
            axial_speed: axial.free_speed,
            angular_speed: torsion.free_speed,
            weight_on_bit: 0.0,
            torque_on_bit: 0.0,
            contact_weight: 0.0,
            contact_torque: 0.0,
            phase: BitPhase::LiftOff,
        };
    }
    let (wc, tc) = (law.cutting_weight(depth), law.cutting_torque(depth));
    let hold_w = axial.hold();
    let wf = (hold_w - wc).clamp(0.0, law.contact_weight());
    let tf = law.contact_torque(wf);
    let threshold = tc + tf;
    let hold_t = torsion.hold();
    if hold_t > threshold {
        let w = wc + wf;
        BitContact {
            axial_speed: axial.speed(w),
            angular_speed: torsion.speed(threshold).max(0.0),
            weight_on_bit: w,
            torque_on_bit: threshold,
            contact_weight: wf,
            contact_torque: tf,
            phase: BitPhase::Cutting,
        }
    } else {
        let w = hold_w.max(0.0);
        BitContact {
            axial_speed: if w > 0.0 { 0.0 } else { axial.free_speed },
            angular_speed: 0.0,
            weight_on_bit: w,
            torque_on_bit: hold_t,
            contact_weight: 0.0,
            contact_torque: 0.0,
            phase: BitPhase::Stick,
        }
    }
}

impl BitRock for DetournayBit {
    const AXIAL: AxialNeed = AxialNeed::DepthOfCut;

    /// [`solve_bit`] at the ends' depth of cut (lift-off without an axial end).
    #[inline]
    fn resolve(&self, ends: &BitEnds) -> BitContact {
        let torsion = Port::of_line(ends.torsion);
        match ends.axial {
            Some(a) => solve_bit(self, a.port, torsion, a.depth),
            None => solve_bit(self, Port::string(0.0, 1.0), torsion, f64::NAN),
        }
    }

    /// [`DetournayBit::steady_state`], the wear flats' contact fully mobilised.
    fn steady(&self, rop: f64, omega: f64) -> Option<(SteadyDrilling, BitContact)> {
        let s = self.steady_state(rop, omega);
        let wf = self.contact_weight();
        let contact = BitContact {
            axial_speed: rop,
            angular_speed: omega,
            weight_on_bit: s.weight_on_bit,
            torque_on_bit: s.torque_on_bit,
            contact_weight: wf,
            contact_torque: self.contact_torque(wf),
            phase: BitPhase::Cutting,
        };
        Some((s, contact))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Aarsnes & van de Wouw's pipe: Z_a = A sqrt(E rho), Z_t = J sqrt(G rho).
    fn ports(v_in: f64, w_in: f64) -> (Port, Port) {
        let (ro, ri) = (0.0635f64, 0.054f64);
        let a = std::f64::consts::PI * (ro * ro - ri * ri);
        let j = std::f64::consts::PI / 2.0 * (ro.powi(4) - ri.powi(4));
        (Port::string(v_in, a * (200e9f64 * 8e3).sqrt()), Port::string(w_in, j * (77e9f64 * 8e3).sqrt()))
    }

    /// The dimensional case of Aarsnes & van de Wouw (the default): a = 0.108 m, 4 blades,
    /// eps = sigma = 60 MPa, zeta = 0.6, l = 11 mm, mu = 0.6, gamma = 1.
    const LAW: DetournayBit = DetournayBit::PUBLISHED;

    #[test]
    fn cutting_with_full_contact_is_the_law() {
        // Strings pushing and turning hard: v > 0 and omega > 0.
        // The invariants carry the static load: alpha = v + W / Z_a (Z_a = 1.4e5 N s/m).
        let (a, t) = ports(0.6, 15.0);
        let d = 2e-3;
        let s = solve_bit(&LAW, a, t, d);
        assert_eq!(s.phase, BitPhase::Cutting);
        // W = a zeta eps d + a l sigma = 0.108*0.6*60e6*2e-3 + 71280 = 7776 + 71280.
        assert!((s.weight_on_bit - (7776.0 + 71280.0)).abs() < 1e-8);
        // T = a^2 eps d / 2 + mu a W_f / 2 = 699.84 + 2309.472.
        assert!((s.torque_on_bit - (699.84 + 2309.472)).abs() < 1e-9);
        assert!((s.axial_speed - (0.6 - s.weight_on_bit / a.impedance)).abs() < 1e-15);
        assert!((s.angular_speed - (15.0 - s.torque_on_bit / t.impedance)).abs() < 1e-15);
        assert!(s.axial_speed > 0.0 && s.angular_speed > 0.0);
        assert!((s.contact_weight - 71280.0).abs() < 1e-8);
    }

    #[test]
    fn partial_contact_holds_the_bit_axially_and_a_rising_bit_loses_it() {
        let d = 1e-3;
        let (wc, wf0) = (3888.0, 71280.0);
        // W_hold between W_c and W_c + W_f: v = 0 and W = W_hold.
        let (a, t) = ports(0.0, 15.0);
        let a = Port { free_speed: (wc + 0.5 * wf0) / a.impedance, ..a };
        let s = solve_bit(&LAW, a, t, d);
        assert_eq!(s.phase, BitPhase::Cutting);
        assert!(s.axial_speed.abs() < 1e-16);
        assert!((s.weight_on_bit - (wc + 0.5 * wf0)).abs() < 1e-8);
        assert!((s.contact_weight - 0.5 * wf0).abs() < 1e-8);
        assert!((s.torque_on_bit - (349.92 + 0.5 * 2309.472)).abs() < 1e-9);
        // W_hold below W_c: the bit rises while cutting, W = W_c, no contact.
        let a = Port { free_speed: -0.01, ..a };
        let s = solve_bit(&LAW, a, t, d);
        assert_eq!(s.phase, BitPhase::Cutting);
        assert_eq!((s.contact_weight, s.weight_on_bit), (0.0, LAW.cutting_weight(d)));
        assert!((s.axial_speed - (-0.01 - wc / a.impedance)).abs() < 1e-15);
        assert!((s.torque_on_bit - 349.92).abs() < 1e-12);
    }

    #[test]
    fn stick_holds_the_torque_and_stops_the_bit() {
        let d = 1e-3;
        let (a, t) = ports(0.6, 0.0);
        // Available torque 1000 N m < threshold 349.92 + 2309.472.
        let t = Port { free_speed: 1000.0 / t.impedance, ..t };
        let s = solve_bit(&LAW, a, t, d);
        assert_eq!(s.phase, BitPhase::Stick);
        assert_eq!((s.angular_speed, s.axial_speed), (0.0, 0.0));
        assert!((s.torque_on_bit - 1000.0).abs() < 1e-9);
        assert!((s.weight_on_bit - 0.6 * a.impedance).abs() < 1e-9);
        assert_eq!(s.power(), 0.0);
        // A string winding backwards is held too (no reverse rotation in contact).
        let t2 = Port { free_speed: -0.3, ..t };
        let s = solve_bit(&LAW, a, t2, d);
        assert_eq!((s.phase, s.angular_speed), (BitPhase::Stick, 0.0));
        assert!((s.torque_on_bit + 0.3 * t.impedance).abs() < 1e-9);
        // Stuck and pulled up: no weight, the bit rises, the torque still held (threshold T_c).
        let a2 = Port { free_speed: -0.02, ..a };
        let t3 = Port { free_speed: 300.0 / t.impedance, ..t };
        let s = solve_bit(&LAW, a2, t3, d);
        assert_eq!((s.phase, s.weight_on_bit, s.axial_speed), (BitPhase::Stick, 0.0, -0.02));
        assert!((s.torque_on_bit - 300.0).abs() < 1e-9);
        assert_eq!(s.power(), 0.0);
    }

    #[test]
    fn lift_off_frees_both_fields() {
        let (a, t) = ports(-0.1, 3.0);
        for d in [0.0, -1e-3, f64::NAN] {
            let s = solve_bit(&LAW, a, t, d);
            assert_eq!(s.phase, BitPhase::LiftOff);
            assert_eq!((s.axial_speed, s.angular_speed, s.weight_on_bit, s.torque_on_bit), (-0.1, 3.0, 0.0, 0.0));
            assert_eq!(s.power(), 0.0);
        }
        // Off bottom the bit may turn backwards.
        let (a, t) = ports(0.1, -2.0);
        let s = solve_bit(&LAW, a, t, -1e-4);
        assert_eq!((s.phase, s.angular_speed), (BitPhase::LiftOff, -2.0));
    }

    #[test]
    fn continuous_between_phases() {
        let d = 1e-3;
        let (a, t) = ports(0.6, 0.0);
        // Cutting -> stick as the available torque falls to the threshold: omega -> 0, T continuous.
        let threshold = 349.92 + 2309.472;
        for eps in [1e-3, 1e-6, 1e-9] {
            let above = solve_bit(&LAW, a, Port { free_speed: (threshold + eps) / t.impedance, ..t }, d);
            let below = solve_bit(&LAW, a, Port { free_speed: (threshold - eps) / t.impedance, ..t }, d);
            assert_eq!((above.phase, below.phase), (BitPhase::Cutting, BitPhase::Stick));
            assert!(above.angular_speed <= 1.01 * eps / t.impedance);
            assert!((above.torque_on_bit - below.torque_on_bit).abs() <= 2.01 * eps);
        }
        // Cutting -> lift-off on a rising bit as d -> 0: W, T -> 0, speeds -> the free ones.
        let (a, t) = ports(-0.05, 5.0);
        let off = solve_bit(&LAW, a, t, 0.0);
        for d in [1e-6, 1e-9, 1e-12] {
            let s = solve_bit(&LAW, a, t, d);
            assert_eq!(s.phase, BitPhase::Cutting);
            assert!(s.weight_on_bit <= LAW.cutting_weight(d) * 1.000001);
            assert!((s.axial_speed - off.axial_speed).abs() <= s.weight_on_bit / a.impedance * 1.000001);
            assert!((s.angular_speed - off.angular_speed).abs() <= LAW.cutting_torque(d) / t.impedance * 1.000001);
            assert!(s.torque_on_bit <= LAW.cutting_torque(d) * 1.000001);
        }
        // The contact weight is continuous in the axial drive (full, partial, none).
        let mut prev: Option<BitContact> = None;
        let (a0, t0) = ports(0.0, 15.0);
        for k in 0..=2000 {
            let hold = -20e3 + 100.0 * k as f64;
            let s = solve_bit(&LAW, Port { free_speed: hold / a0.impedance, ..a0 }, t0, d);
            if let Some(p) = prev {
                assert!((s.weight_on_bit - p.weight_on_bit).abs() <= 100.0 + 1e-9);
                assert!((s.axial_speed - p.axial_speed).abs() <= 100.0 / a0.impedance + 1e-15);
            }
            prev = Some(s);
        }
    }

    /// A deterministic spread of inputs (a linear congruential sequence in [0, 1)).
    fn spread(n: usize) -> impl Iterator<Item = [f64; 3]> {
        let mut s: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = move || {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n).map(move |_| [next(), next(), next()])
    }

    #[test]
    fn relations_hold_and_the_contact_dissipates_in_every_phase() {
        let (a0, t0) = ports(0.0, 0.0);
        let (a_, zeta, eps) = (LAW.radius, LAW.detournay.cutting_ratio, LAW.detournay.intrinsic_specific_energy);
        let mut seen = [0usize; 3];
        for [x, y, z] in spread(20_000) {
            let a = Port { free_speed: -0.1 + x, ..a0 };
            let t = Port { free_speed: -2.0 + 22.0 * y, ..t0 };
            let d = -2e-3 + 6e-3 * z;
            let s = solve_bit(&LAW, a, t, d);
            seen[s.phase as usize] += 1;
            // The port relations, W >= 0, no backward rotation in contact.
            assert!((s.axial_speed - a.speed(s.weight_on_bit)).abs() < 1e-12);
            assert!(s.weight_on_bit >= 0.0);
            if s.phase != BitPhase::Stick {
                assert!((s.angular_speed - t.speed(s.torque_on_bit)).abs() < 1e-12);
            }
            assert!(s.contact_power() >= 0.0);
            match s.phase {
                BitPhase::LiftOff | BitPhase::Stick => assert_eq!(s.power(), 0.0),
                BitPhase::Cutting => {
                    assert!(d > 0.0 && s.angular_speed > 0.0);
                    // P = eps a d (zeta v + a omega / 2) + contact.
                    let cut = eps * a_ * d * (zeta * s.axial_speed + 0.5 * a_ * s.angular_speed);
                    let p = cut + s.contact_power();
                    assert!((s.power() - p).abs() <= 1e-9 * p.abs().max(1.0));
                    if zeta * s.axial_speed >= -0.5 * a_ * s.angular_speed {
                        assert!(s.power() >= 0.0);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&n| n > 1000), "every phase met: {seen:?}");
    }

    #[test]
    fn a_lumped_bha_is_the_semi_implicit_step() {
        let (z, m, dt, v0, alpha, weight) = (1.6e5, 12e3, 1e-4, 0.01, 0.02, 5e3);
        let p = Port::lumped(alpha, z, m, v0, dt, weight);
        let s = solve_bit(&LAW, p, Port::string(10.0, 1e3), 1e-3);
        let v1 = s.axial_speed;
        // M (v1 - v0) / dt = Z (alpha - v1) + weight - W.
        let residual = m * (v1 - v0) / dt - (z * (alpha - v1) + weight - s.weight_on_bit);
        assert!(residual.abs() < 1e-6 * s.weight_on_bit, "{residual}");
        let massless = Port::lumped(alpha, z, 0.0, v0, dt, 0.0);
        assert_eq!(massless.impedance, z);
        assert!((massless.free_speed - alpha).abs() < 1e-17);
    }
}
