//! The hoist at the top of the axial field: an imposed block velocity, a hook load, or an
//! autodriller (PI on weight on bit or on rate of penetration) giving the block velocity; or a
//! weight on bit as a rig's weight indicator reads it (the hook load held at the hanging
//! string's static hook load less the weight).
//!
//! The setpoint of every mode approaches its target (the mode's value, then `[time, value]`
//! steps) as a first-order lag of time constant `ramp_time`, exactly over each step, the rule of
//! the top drive's speed setpoint (`drilling/solver.rs`, `Simulation::step`). The autodriller is
//! the PI of the top drive's `pi` controller on another measurement: `u = u_ff + kp e + ki int e`
//! clamped to `[min_speed, max_speed]`, with conditional integration as anti-windup (no
//! integration while the output is saturated in the error's direction; Åström & Hägglund,
//! *Advanced PID Control*, ISA 2006, on integrator windup), `e` the setpoint less the measured weight on
//! bit or rate of penetration and `u_ff` the ROP setpoint itself in `rop` mode (0 in
//! `weight_on_bit` mode): in steady drilling the block moves at the rate of penetration.
//! Speeds are down positive (m/s), forces in N.

use serde::Serialize;

use super::hoist_mode::{rule, HoistReference, StepInput};
use crate::drilling::config::Hoist;

impl Hoist {
    /// The target at time `t`: the last step at or before `t`, else the mode's value.
    pub fn target(&self, t: f64) -> f64 {
        self.steps.iter().rev().find(|s| s[0] <= t).map_or_else(|| rule(self.mode).base(self), |s| s[1])
    }
}

/// The setpoint after a step `dt` from `value` towards `target`: the first-order lag of time
/// constant `ramp_time`, exact over the step, `target + (value - target) exp(-dt / ramp_time)`
/// (`target` at once for `ramp_time = 0`).
#[inline]
pub fn ramp(value: f64, target: f64, dt: f64, ramp_time: f64) -> f64 {
    ramp_by(value, target, ramp_time, lag(dt, ramp_time))
}

/// The factor of [`ramp`] over `dt`, `1 - exp(-dt / ramp_time)` (unused without a ramp).
fn lag(dt: f64, ramp_time: f64) -> f64 {
    1.0 - (-dt / ramp_time).exp()
}

/// [`ramp`] with its factor `lag` ([`lag`]) computed once for its step and ramp time.
#[inline]
fn ramp_by(value: f64, target: f64, ramp_time: f64, lag: f64) -> f64 {
    if ramp_time > 0.0 {
        value + (target - value) * lag
    } else {
        target
    }
}

/// What the hoist imposes on the top of the axial field for the next step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HoistCommand {
    /// The block (top) speed, m/s, down positive.
    Speed(f64),
    /// The hook load, N, holding the string up.
    HookLoad(f64),
}

impl HoistCommand {
    /// The invariant entering the string's first cell, `alpha_0 = v + F / Z` (`F` the compression
    /// carried down, [`super::section`]), from the invariant `beta_1 = v - F / Z` leaving it and
    /// the top section's impedance `Z` (N s/m): an imposed speed gives `alpha_0 = 2 v - beta_1`,
    /// a hook load `H` (the top's tension, `F = -H`) gives `v = beta_1 - H / Z` and
    /// `alpha_0 = beta_1 - 2 H / Z` (the boundary rule of Aarsnes & van de Wouw's
    /// `waveStep_transportBRI.m`, `Aalpha0 = -Abeta(1) + 2 V0` in their variables).
    pub fn incoming(&self, beta_1: f64, impedance: f64) -> f64 {
        match *self {
            HoistCommand::Speed(v) => 2.0 * v - beta_1,
            HoistCommand::HookLoad(h) => beta_1 - 2.0 * h / impedance,
        }
    }
}

/// What the autodriller measures (SI).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HoistMeasurement {
    /// Weight on bit, N.
    pub weight_on_bit: f64,
    /// Rate of penetration, m/s.
    pub rop: f64,
}

/// The hoist's state: time, the ramped setpoint and the autodriller's integral; what the
/// setpoint means and what it commands is the mode's ([`super::hoist_mode`]).
#[derive(Debug, Clone, PartialEq)]
pub struct HoistState {
    /// The `[hoist]` table.
    pub params: Hoist,
    /// Time of the state, s.
    pub time: f64,
    /// The ramped setpoint (mode's unit).
    pub setpoint: f64,
    /// `int e dt` of the autodriller.
    pub integral: f64,
    /// The loads the modes are referred to: the hanging string's static hook load (the
    /// `weight_on_bit` mode holds the hook load at it less its ramped weight on bit) and the
    /// travelling block's weight (in the `hook_load` mode's setpoint, not in the string).
    pub reference: HoistReference,
    /// The step and ramp time the ramp's factor was computed for, and the factor ([`lag`]):
    /// the exponential once per run (again when `params.ramp_time` changes), not every step.
    lag: (f64, f64, f64),
}

impl HoistState {
    /// A hoist at time 0 whose setpoint starts at `initial` (the mode's unit: a block at rest
    /// starts at 0 m/s, a hook at its static load, a weight on bit at 0 N;
    /// [`super::hoist_mode::HoistRule::at_rest`]).
    pub fn new(params: Hoist, initial: f64) -> Self {
        HoistState {
            params,
            time: 0.0,
            setpoint: initial,
            integral: 0.0,
            reference: HoistReference::default(),
            // (a step is never 0: computed at the first)
            lag: (0.0, 0.0, 0.0),
        }
    }

    /// The same hoist referred to `reference`.
    pub fn referred_to(self, reference: HoistReference) -> Self {
        HoistState { reference, ..self }
    }

    /// Advances by `dt` (s): the setpoint towards the target at the step's middle (a step at
    /// `T` takes effect from the step starting at the step boundary nearest `T`, as the top
    /// drive's), then the mode's command for the step (the autodriller's from `measured`).
    pub fn step(&mut self, dt: f64, measured: HoistMeasurement) -> HoistCommand {
        let t1 = self.time + dt;
        let p = &self.params;
        if (self.lag.0.to_bits(), self.lag.1.to_bits()) != (dt.to_bits(), p.ramp_time.to_bits()) {
            self.lag = (dt, p.ramp_time, lag(dt, p.ramp_time));
        }
        self.setpoint = ramp_by(self.setpoint, p.target(self.time + 0.5 * dt), p.ramp_time, self.lag.2);
        self.time = t1;
        let step = StepInput { dt, measured, reference: self.reference };
        rule(p.mode).command(p, self.setpoint, step, &mut self.integral)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::config::{Autodriller, AutodrillerTarget, HoistMode};

    fn speed(c: HoistCommand) -> f64 {
        match c {
            HoistCommand::Speed(v) => v,
            HoistCommand::HookLoad(_) => panic!("a speed expected"),
        }
    }

    #[test]
    fn velocity_ramps_and_steps_as_a_first_order_lag() {
        let params = Hoist {
            mode: HoistMode::Velocity,
            speed: 0.01,
            ramp_time: 2.0,
            steps: vec![[10.0, 0.02]],
            ..Hoist::default()
        };
        let mut h = HoistState::new(params, 0.0);
        let dt = 1.0 / 128.0;
        // The step starting at 10 s heads for the new target (as the top drive's).
        let ts = 10.0;
        for k in 1..=2000 {
            let t = k as f64 * dt;
            let v = speed(h.step(dt, HoistMeasurement::default()));
            // 0.01 (1 - exp(-t/2)), then from its value at ts towards 0.02.
            let exact = if t <= ts {
                0.01 * (1.0 - (-t / 2.0).exp())
            } else {
                0.02 + (0.01 * (1.0 - (-ts / 2.0).exp()) - 0.02) * (-(t - ts) / 2.0).exp()
            };
            assert!((v - exact).abs() < 1e-14, "t {t}: {v} vs {exact}");
        }
        // Without a ramp the steps are taken at once.
        let mut h = HoistState::new(Hoist { ramp_time: 0.0, steps: vec![[0.25, -0.003]], ..Hoist::default() }, 0.0);
        assert_eq!(speed(h.step(0.25, HoistMeasurement::default())), 30.0 / 3600.0);
        assert_eq!(speed(h.step(0.25, HoistMeasurement::default())), -0.003);
    }

    #[test]
    fn commands_give_the_incoming_invariant() {
        // alpha = v + F / Z, beta = v - F / Z, F the compression: a string hanging still from
        // the hook load H has v = 0, F = -H at the top.
        let (z, h) = (1.4e5, 9e5);
        let beta = h / z;
        let alpha = HoistCommand::HookLoad(h).incoming(beta, z);
        assert!(((alpha + beta) / 2.0).abs() < 1e-12 && ((alpha - beta) / 2.0 * z + h).abs() < 1e-6);
        // The same top lowered at 0.01 m/s under this load.
        let beta = 0.01 + h / z;
        let alpha = HoistCommand::Speed(0.01).incoming(beta, z);
        assert!(((alpha + beta) / 2.0 - 0.01).abs() < 1e-15 && ((alpha - beta) / 2.0 * z + h).abs() < 1e-6);
        let alpha = HoistCommand::HookLoad(h).incoming(beta, z);
        assert!(((alpha + beta) / 2.0 - 0.01).abs() < 1e-15);
    }

    #[test]
    fn hook_load_mode_commands_the_load() {
        let params = Hoist { mode: HoistMode::HookLoad, hook_load: 900e3, ramp_time: 0.0, ..Hoist::default() };
        let mut h = HoistState::new(params, 950e3);
        assert_eq!(h.step(0.1, HoistMeasurement::default()), HoistCommand::HookLoad(900e3));
    }

    #[test]
    fn weight_on_bit_mode_commands_the_hanging_load_less_the_weight() {
        // A string hanging at 900 kN: 60 kN on the bit is a hook load of 840 kN, reached as the
        // first-order lag of the weight from 0 (the hook from the hanging load).
        let params = Hoist { mode: HoistMode::WeightOnBit, weight_on_bit: 60e3, ramp_time: 2.0, ..Hoist::default() };
        let mut h = HoistState::new(params, 0.0).referred_to(HoistReference { hanging: 900e3, block_weight: 0.0 });
        let HoistCommand::HookLoad(first) = h.step(1.0, HoistMeasurement::default()) else { panic!("a hook load") };
        assert!((first - (900e3 - 60e3 * (1.0 - (-0.5f64).exp()))).abs() < 1e-6, "{first}");
        let HoistCommand::HookLoad(last) = h.step(1e3, HoistMeasurement::default()) else { panic!("a hook load") };
        assert!((last - 840e3).abs() < 1e-6, "{last}");
        let p = Hoist { weight_on_bit: f64::NAN, ..Hoist::default() };
        assert_eq!(p.validate("hoist").unwrap_err().field(), "hoist.weight_on_bit");
    }

    /// The plant of a drilling string in a few lines (see [`drill_from`]), from no weight.
    fn drill(h: &mut HoistState, k: f64, r: f64, seconds: f64) -> ((f64, f64, f64), (f64, f64)) {
        drill_from(h, k, r, 0.0, seconds)
    }

    #[test]
    fn autodriller_reaches_its_weight_and_rop_setpoints() {
        // k = 2e5 N/m (a 3000 m string: E A / L), r = 80e3 N / (20 m/h).
        let (k, r) = (2e5, 80e3 / (20.0 / 3600.0));
        let ad = Autodriller {
            target: AutodrillerTarget::WeightOnBit,
            setpoint: 60e3,
            kp: 2e-7,
            ki: 2e-8,
            min_speed: 0.0,
            max_speed: 0.05,
        };
        let params = Hoist { mode: HoistMode::Autodriller, ramp_time: 5.0, autodriller: ad, ..Hoist::default() };
        let mut h = HoistState::new(params, 0.0);
        let ((w, rop, v), _) = drill(&mut h, k, r, 600.0);
        // Steady state: W = 60 kN, ROP = W / r = 15 m/h, block speed = ROP.
        assert!((w - 60e3).abs() < 1e-3 * 60e3, "{w}");
        assert!((rop - 60e3 / r).abs() < 1e-3 * rop);
        assert!((v - rop).abs() < 1e-3 * rop);
        // On ROP: 10 m/h.
        let ad = Autodriller { target: AutodrillerTarget::Rop, setpoint: 10.0 / 3600.0, kp: 5.0, ki: 0.5, ..ad };
        let params = Hoist { mode: HoistMode::Autodriller, ramp_time: 0.0, autodriller: ad, ..Hoist::default() };
        let mut h = HoistState::new(params, 0.0);
        let ((w, rop, _), _) = drill(&mut h, k, r, 600.0);
        assert!((rop - 10.0 / 3600.0).abs() < 1e-3 * rop, "{}", rop * 3600.0);
        assert!((w - r * 10.0 / 3600.0).abs() < 1e-3 * w);
    }

    #[test]
    fn autodriller_is_the_discrete_pi_by_hand() {
        // kp 1e-6 (m/s)/N, ki 1e-7 (m/s)/(N s), 50 kN, no ramp, steps of 0.5 s, block within
        // [0, 0.06] m/s; the output uses the integral before the step's error is added.
        let ad = Autodriller {
            target: AutodrillerTarget::WeightOnBit,
            setpoint: 50e3,
            kp: 1e-6,
            ki: 1e-7,
            min_speed: 0.0,
            max_speed: 0.06,
        };
        let params = Hoist { mode: HoistMode::Autodriller, ramp_time: 0.0, autodriller: ad, ..Hoist::default() };
        let mut h = HoistState::new(params, 0.0);
        let w = |weight_on_bit: f64| HoistMeasurement { weight_on_bit, rop: 0.0 };
        // W 0: e 5e4, u = 0.05 + 0, int 25e3.
        assert!((speed(h.step(0.5, w(0.0))) - 0.05).abs() < 1e-15);
        assert!((h.integral - 25e3).abs() < 1e-9);
        // W 10 kN: e 4e4, u = 0.04 + 1e-7 25e3 = 0.0425, int 45e3.
        assert!((speed(h.step(0.5, w(10e3))) - 0.0425).abs() < 1e-15);
        assert!((h.integral - 45e3).abs() < 1e-9);
        // W 60 kN: e -1e4, u = -0.01 + 0.0045 < 0: held at 0, saturated in the error's
        // direction: the integral stays.
        assert_eq!(speed(h.step(0.5, w(60e3))), 0.0);
        assert!((h.integral - 45e3).abs() < 1e-9);
        // W 0: u = 0.05 + 0.0045 = 0.0545, int 70e3; again u = 0.05 + 0.007 = 0.057, int 95e3.
        assert!((speed(h.step(0.5, w(0.0))) - 0.0545).abs() < 1e-15);
        assert!((speed(h.step(0.5, w(0.0))) - 0.057).abs() < 1e-15);
        // u = 0.05 + 0.0095 = 0.0595, int 120e3; then over the limit: u = 0.05 + 0.012 > 0.06,
        // held at 0.06, the integral stays 120e3.
        assert!((speed(h.step(0.5, w(0.0))) - 0.0595).abs() < 1e-15);
        assert_eq!(speed(h.step(0.5, w(0.0))), 0.06);
        assert!((h.integral - 120e3).abs() < 1e-9);
        // On ROP with a setpoint step at 0.5 s (no ramp): u = setpoint + kp e + ki int e.
        let ad = Autodriller { target: AutodrillerTarget::Rop, setpoint: 0.01, kp: 2.0, ki: 0.5, ..ad };
        let params = Hoist {
            mode: HoistMode::Autodriller,
            ramp_time: 0.0,
            steps: vec![[0.5, 0.004]],
            autodriller: ad,
            ..Hoist::default()
        };
        let mut h = HoistState::new(params, 0.0);
        let r = |rop: f64| HoistMeasurement { weight_on_bit: 0.0, rop };
        // ROP 0.008: e 0.002, u = 0.01 + 0.004 = 0.014, int 0.001.
        assert!((speed(h.step(0.5, r(0.008))) - 0.014).abs() < 1e-15);
        // The step starting at 0.5 s takes the new setpoint 0.004: e = -0.004, u = 0.004 - 0.008
        // + 0.5 0.001 = -0.0035 < 0: held at 0, the integral stays.
        assert_eq!(speed(h.step(0.5, r(0.008))), 0.0);
        assert!((h.integral - 0.001).abs() < 1e-15);
        // ROP 0.003: e 0.001, u = 0.004 + 0.002 + 0.0005 = 0.0065.
        assert!((speed(h.step(0.5, r(0.003))) - 0.0065).abs() < 1e-15);
    }

    #[test]
    fn autodriller_limits_hold_and_do_not_wind_up() {
        let (k, r) = (2e5, 80e3 / (20.0 / 3600.0));
        // 200 kN would need 50 m/h: out of reach at 25 m/h.
        let max_speed = 25.0 / 3600.0;
        let ad = Autodriller {
            target: AutodrillerTarget::WeightOnBit,
            setpoint: 200e3,
            kp: 2e-7,
            ki: 2e-8,
            min_speed: 0.0,
            max_speed,
        };
        let params = Hoist {
            mode: HoistMode::Autodriller,
            ramp_time: 0.0,
            steps: vec![[1000.0, 60e3]],
            autodriller: ad,
            ..Hoist::default()
        };
        let mut h = HoistState::new(params, 0.0);
        let ((w, _, v), range) = drill(&mut h, k, r, 1000.0);
        assert!(range.0 >= 0.0 && range.1 <= max_speed);
        assert_eq!(v, max_speed);
        // At the limit the weight settles where ROP = max speed: W = r max_speed = 100 kN.
        assert!((w - r * max_speed).abs() < 1e-3 * w, "{w}");
        // Saturated from the first step in the error's direction (kp e >= kp 100 kN > the limit):
        // the integral never grew (without the anti-windup it would hold ~1e8 N s, 2 m/s).
        assert_eq!(h.integral, 0.0);
        // Then 60 kN: the controller leaves the limit and settles within a few hundred seconds.
        let ((w, _, _), range) = drill_from(&mut h, k, r, w, 600.0);
        assert!(range.0 >= 0.0 && range.1 <= max_speed);
        assert!((w - 60e3).abs() < 1e-3 * 60e3, "{w}");
    }

    /// The plant of a drilling string in a few lines: the string a spring of stiffness `k`
    /// between block and bit, `W' = k (v_block - ROP)`, and the rock `ROP = W / r` (steady
    /// drilling, linear in the weight on bit at a fixed rotary speed), from the weight `w0`.
    /// Returns the last `(weight, rop, block speed)` and the range of the block speed.
    fn drill_from(h: &mut HoistState, k: f64, r: f64, w0: f64, seconds: f64) -> ((f64, f64, f64), (f64, f64)) {
        let dt = 1e-3;
        let mut w: f64 = w0;
        let mut range = (f64::INFINITY, f64::NEG_INFINITY);
        let mut last = (0.0, 0.0, 0.0);
        for _ in 0..(seconds / dt) as usize {
            let rop = w / r;
            let v = speed(h.step(dt, HoistMeasurement { weight_on_bit: w, rop }));
            range = (range.0.min(v), range.1.max(v));
            w = (w + dt * k * (v - rop)).max(0.0);
            last = (w, rop, v);
        }
        (last, range)
    }

    #[test]
    fn validation_names_the_field() {
        assert!(Hoist::default().validate("hoist").is_ok());
        let mut p = Hoist::default();
        p.autodriller.max_speed = -1.0;
        assert_eq!(p.validate("hoist").unwrap_err().field(), "hoist.autodriller.max_speed");
        let p = Hoist { ramp_time: -1.0, ..Hoist::default() };
        assert_eq!(p.validate("hoist").unwrap_err().field(), "hoist.ramp_time");
        let p = Hoist { steps: vec![[2.0, 0.0], [1.0, 0.0]], ..Hoist::default() };
        assert_eq!(p.validate("hoist").unwrap_err().field(), "hoist.steps[1]");
        let p: Hoist = serde_json::from_str(r#"{"mode": "autodriller", "autodriller": {"target": "rop"}}"#).unwrap();
        assert_eq!((p.mode, p.autodriller.target), (HoistMode::Autodriller, AutodrillerTarget::Rop));
    }
}
