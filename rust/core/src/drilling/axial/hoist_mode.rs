//! The hoist's modes (`hoist.mode`): what a mode's setpoint means, where it starts, what it
//! imposes at the top of the axial field each step and what it holds in steady drilling. One
//! implementation of [`HoistRule`] per mode, registered in [`rule`] (dispatched once per step,
//! outside the cell loops); the state the modes share (the ramped setpoint, the autodriller's
//! integral, the loads the modes are referred to) is [`super::hoist::HoistState`]'s.
//!
//! A new mode is one type implementing [`HoistRule`] here, its line in [`rule`], and its
//! `hoist.mode` name and keys in `config/hoist.rs`.

use super::hoist::{HoistCommand, HoistMeasurement};
use crate::drilling::config::{AutodrillerTarget, Hoist, HoistMode};

/// The loads the modes are referred to, N: the static hook load of the string hanging off bottom
/// (the string's tension at the top, without the travelling block) and the travelling block's
/// weight (`torque_drag.block_weight`), which the weight indicator's hook load includes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HoistReference {
    /// The hanging string's static hook load, N.
    pub hanging: f64,
    /// The travelling block's weight, N.
    pub block_weight: f64,
}

/// Where the hoist and the bit are during a run (SI, down positive): what a mode changed to
/// during a run starts from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HoistReading {
    /// The block velocity, m/s.
    pub block: f64,
    /// The hook load as the weight indicator reads it (the travelling block with it), N.
    pub hook_load: f64,
    /// The weight on bit, N.
    pub weight_on_bit: f64,
    /// The rate of penetration, m/s.
    pub rop: f64,
}

/// What a mode holds in steady drilling at its target (the steady start,
/// [`crate::drilling::start`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Steady {
    /// A block velocity, m/s: the rate of penetration.
    Rate(f64),
    /// A weight on bit measured at the bit, N.
    WeightAtBit(f64),
    /// A weight on bit as the surface sets it, N: the bit gets it less the drag of the moving
    /// string below the surface.
    WeightAtSurface(f64),
}

/// One mode of the hoist.
pub trait HoistRule: Sync {
    /// The mode's target before any `hoist.steps` entry: its own key of `[hoist]`.
    fn base(&self, p: &Hoist) -> f64;

    /// The setpoint of a hoist at rest at `t = 0` (the mode's unit): 0 but for a hook load, which
    /// starts at the hanging string's.
    fn at_rest(&self, _reference: HoistReference) -> f64 {
        0.0
    }

    /// The setpoint of this mode where the hoist is now, when the mode is changed to it during a
    /// run (`hoist.mode` set in a session).
    fn current(&self, p: &Hoist, now: HoistReading, reference: HoistReference) -> f64;

    /// The autodriller's integral when the mode is changed to this one during a run, the hoist
    /// at `setpoint` and the block at `block` m/s (0 for a mode without an integral).
    fn integral_on_change(&self, _p: &Hoist, _setpoint: f64, _block: f64) -> f64 {
        0.0
    }

    /// The command for a step of `dt` at the ramped `setpoint`, from what the autodriller
    /// measures, updating the `integral` of a mode that has one.
    fn command(&self, p: &Hoist, setpoint: f64, step: StepInput, integral: &mut f64) -> HoistCommand;

    /// What the mode holds in steady drilling at its target `target`.
    fn steady(&self, p: &Hoist, target: f64, reference: HoistReference) -> Steady;

    /// The integral of a mode that has one in steady drilling at the rate `rop` (m/s); `None`
    /// leaves it as it is.
    fn steady_integral(&self, _p: &Hoist, _rop: f64) -> Option<f64> {
        None
    }
}

/// A step's inputs to [`HoistRule::command`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInput {
    /// The step, s.
    pub dt: f64,
    /// What the autodriller measures.
    pub measured: HoistMeasurement,
    /// The loads the modes are referred to.
    pub reference: HoistReference,
}

/// The rule of `hoist.mode`: the registry of the modes.
pub fn rule(mode: HoistMode) -> &'static dyn HoistRule {
    match mode {
        HoistMode::Velocity => &BlockVelocity,
        HoistMode::HookLoad => &HookLoad,
        HoistMode::WeightOnBit => &WeightIndicator,
        HoistMode::Autodriller => &AutodrillerPi,
    }
}

/// `velocity`: the block velocity `hoist.speed`, imposed.
pub struct BlockVelocity;

impl HoistRule for BlockVelocity {
    fn base(&self, p: &Hoist) -> f64 {
        p.speed
    }
    fn current(&self, _p: &Hoist, now: HoistReading, _r: HoistReference) -> f64 {
        now.block
    }
    fn command(&self, _p: &Hoist, setpoint: f64, _step: StepInput, _integral: &mut f64) -> HoistCommand {
        HoistCommand::Speed(setpoint)
    }
    fn steady(&self, _p: &Hoist, target: f64, _r: HoistReference) -> Steady {
        Steady::Rate(target)
    }
}

/// `hook_load`: the hook load `hoist.hook_load` as the weight indicator reads it, held: the
/// string's tension at the top is the setpoint less the travelling block's weight.
pub struct HookLoad;

impl HoistRule for HookLoad {
    fn base(&self, p: &Hoist) -> f64 {
        p.hook_load
    }
    fn at_rest(&self, r: HoistReference) -> f64 {
        r.hanging + r.block_weight
    }
    fn current(&self, _p: &Hoist, now: HoistReading, _r: HoistReference) -> f64 {
        now.hook_load
    }
    fn command(&self, _p: &Hoist, setpoint: f64, step: StepInput, _integral: &mut f64) -> HoistCommand {
        HoistCommand::HookLoad(setpoint - step.reference.block_weight)
    }
    fn steady(&self, _p: &Hoist, target: f64, r: HoistReference) -> Steady {
        Steady::WeightAtSurface(r.hanging + r.block_weight - target)
    }
}

/// `weight_on_bit`: the weight on bit `hoist.weight_on_bit` as a weight indicator sets it, the
/// hook load held at the hanging string's less the (ramped) weight.
pub struct WeightIndicator;

impl HoistRule for WeightIndicator {
    fn base(&self, p: &Hoist) -> f64 {
        p.weight_on_bit
    }
    fn current(&self, _p: &Hoist, now: HoistReading, r: HoistReference) -> f64 {
        r.hanging + r.block_weight - now.hook_load
    }
    fn command(&self, _p: &Hoist, setpoint: f64, step: StepInput, _integral: &mut f64) -> HoistCommand {
        HoistCommand::HookLoad(step.reference.hanging - setpoint)
    }
    fn steady(&self, _p: &Hoist, target: f64, _r: HoistReference) -> Steady {
        Steady::WeightAtSurface(target)
    }
}

/// `autodriller`: the block velocity of the PI `[hoist.autodriller]` on the weight on bit or the
/// rate of penetration (see [`super::hoist`] for the law and its anti-windup).
pub struct AutodrillerPi;

impl AutodrillerPi {
    /// The feed-forward block velocity at `setpoint`: the ROP setpoint itself on `rop`, 0 on
    /// `weight_on_bit`.
    fn feed_forward(p: &Hoist, setpoint: f64) -> f64 {
        if p.autodriller.target == AutodrillerTarget::Rop {
            setpoint
        } else {
            0.0
        }
    }
}

impl HoistRule for AutodrillerPi {
    fn base(&self, p: &Hoist) -> f64 {
        p.autodriller.setpoint
    }
    fn current(&self, p: &Hoist, now: HoistReading, _r: HoistReference) -> f64 {
        match p.autodriller.target {
            AutodrillerTarget::WeightOnBit => now.weight_on_bit,
            AutodrillerTarget::Rop => now.rop,
        }
    }
    fn integral_on_change(&self, p: &Hoist, setpoint: f64, block: f64) -> f64 {
        let a = &p.autodriller;
        if a.ki > 0.0 {
            (block - Self::feed_forward(p, setpoint)) / a.ki
        } else {
            0.0
        }
    }
    fn command(&self, p: &Hoist, setpoint: f64, step: StepInput, integral: &mut f64) -> HoistCommand {
        let a = &p.autodriller;
        let e = match a.target {
            AutodrillerTarget::WeightOnBit => setpoint - step.measured.weight_on_bit,
            AutodrillerTarget::Rop => setpoint - step.measured.rop,
        };
        let raw = Self::feed_forward(p, setpoint) + a.kp * e + a.ki * *integral;
        let out = raw.clamp(a.min_speed, a.max_speed);
        if !((raw > a.max_speed && e > 0.0) || (raw < a.min_speed && e < 0.0)) {
            *integral += e * step.dt;
        }
        HoistCommand::Speed(out)
    }
    fn steady(&self, p: &Hoist, target: f64, _r: HoistReference) -> Steady {
        match p.autodriller.target {
            AutodrillerTarget::WeightOnBit => Steady::WeightAtBit(target),
            AutodrillerTarget::Rop => Steady::Rate(target),
        }
    }
    fn steady_integral(&self, p: &Hoist, rop: f64) -> Option<f64> {
        let a = &p.autodriller;
        (a.target == AutodrillerTarget::WeightOnBit && a.ki > 0.0).then(|| rop / a.ki)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::axial::hoist::HoistState;
    use crate::drilling::config::Autodriller;
    use proptest::prelude::*;

    const MODES: [(HoistMode, AutodrillerTarget); 5] = [
        (HoistMode::Velocity, AutodrillerTarget::WeightOnBit),
        (HoistMode::HookLoad, AutodrillerTarget::WeightOnBit),
        (HoistMode::WeightOnBit, AutodrillerTarget::WeightOnBit),
        (HoistMode::Autodriller, AutodrillerTarget::WeightOnBit),
        (HoistMode::Autodriller, AutodrillerTarget::Rop),
    ];

    /// The string's tension at the top and the block velocity a command holds, given where the
    /// string is now: a hook load is the tension, a speed moves the block.
    fn held(c: HoistCommand) -> (Option<f64>, Option<f64>) {
        match c {
            HoistCommand::Speed(v) => (None, Some(v)),
            HoistCommand::HookLoad(h) => (Some(h), None),
        }
    }

    proptest! {
        /// A mode changed to during a run starts where the hoist is: with no ramp and no new
        /// target its first command holds the present block velocity (a speed) or the present
        /// tension at the top (a hook load: the weight indicator's reading less the block).
        #[test]
        fn a_mode_changed_to_commands_what_the_hoist_does(
            block in -0.05f64..0.05,
            tension in 0.0f64..2e6,
            block_weight in 0.0f64..4e5,
            hanging in 0.0f64..2e6,
            weight_on_bit in 0.0f64..3e5,
            rop in 0.0f64..0.02,
            kp in 1e-9f64..1e-6,
            ki in 1e-10f64..1e-7,
        ) {
            let reference = HoistReference { hanging, block_weight };
            let now = HoistReading { block, hook_load: tension + block_weight, weight_on_bit, rop };
            let measured = HoistMeasurement { weight_on_bit, rop };
            for (mode, target) in MODES {
                let autodriller = Autodriller { target, kp, ki, min_speed: -1.0, max_speed: 1.0, ..Autodriller::default() };
                let p = Hoist { mode, ramp_time: 0.0, autodriller, ..Hoist::default() };
                let r = rule(mode);
                let setpoint = r.current(&p, now, reference);
                let mut h = HoistState::new(p.clone(), setpoint).referred_to(reference);
                h.integral = r.integral_on_change(&p, setpoint, block);
                // no ramp: the setpoint must be the target, so the target is set to it
                h.params.steps = vec![[0.0, setpoint]];
                let (t, v) = held(h.step(1e-3, measured));
                if let Some(t) = t {
                    prop_assert!((t - tension).abs() <= 1e-9 * (tension + hanging + block_weight + 1.0), "{mode:?}: {t} vs {tension}");
                }
                if let Some(v) = v {
                    prop_assert!((v - block).abs() <= 1e-12, "{mode:?} {target:?}: {v} vs {block}");
                }
            }
        }
    }

    #[test]
    fn each_mode_targets_its_own_key_and_starts_at_rest() {
        let p = Hoist {
            speed: 0.01,
            hook_load: 8e5,
            weight_on_bit: 5e4,
            autodriller: Autodriller { setpoint: 6e4, ..Autodriller::default() },
            ..Hoist::default()
        };
        let reference = HoistReference { hanging: 9e5, block_weight: 2e5 };
        let expected = [
            (HoistMode::Velocity, 0.01, 0.0),
            (HoistMode::HookLoad, 8e5, 1.1e6),
            (HoistMode::WeightOnBit, 5e4, 0.0),
            (HoistMode::Autodriller, 6e4, 0.0),
        ];
        for (mode, base, rest) in expected {
            assert_eq!(rule(mode).base(&p), base, "{mode:?}");
            assert_eq!(rule(mode).at_rest(reference), rest, "{mode:?}");
        }
        // in steady drilling: a hook load of 1.0 MN is 100 kN set down at surface
        let hold = rule(HoistMode::HookLoad).steady(&p, 1.0e6, reference);
        assert_eq!(hold, Steady::WeightAtSurface(1e5));
        assert_eq!(rule(HoistMode::Velocity).steady(&p, 0.004, reference), Steady::Rate(0.004));
    }
}
