//! The top drive (`[top_drive]`): inertia, torque limit, setpoint, controller and its presets,
//! a measured surface speed.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::{finite, nonneg, pos, DrillConfig, DEFAULT_TORQUE_LIMIT};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ControllerKind {
    /// Ideal speed control: the top speed is the setpoint (motor torque inferred).
    Speed,
    /// Motor torque `kp e + ki int e` in a zero-order hold.
    Pi,
    /// PI tuned from the string impedance and a tuning frequency (SoftTorque).
    SoftTorque,
    /// Impedance matching (ZTorque): the top drive acts as a damper `z_factor Z` to the string.
    ZTorque,
}

impl ControllerKind {
    pub const NAMES: [&'static str; 4] = ["speed", "pi", "soft_torque", "z_torque"];
}

/// A named controller tuning (`top_drive.controller.preset`): it fills in the controller's
/// `type` and gains from the string ([`super::tuning::preset_controller`]; the rules and their
/// sources are in [`super::tuning`]); keys given beside it keep their values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ControllerPreset {
    /// A high-gain speed PI (`type = "pi"`): `kp = 50 Z`, `ki = 5 1/s^2 I_TD`.
    Stiff,
    /// SoftTorque / SoftSpeed (`type = "soft_torque"`): `kp = 4 Z`, `ki = (2 pi f1)^2 I_TD`.
    SoftTorque,
    /// ZTorque impedance matching (`type = "z_torque"`): `z_factor = 4`, the torque high-pass
    /// an octave below the first mode, `torque_highpass_time = 1 / (pi f1)`.
    ZTorque,
}

impl ControllerPreset {
    pub const NAMES: [&'static str; 3] = ["stiff", "soft_torque", "z_torque"];
    pub const ALL: [ControllerPreset; 3] =
        [ControllerPreset::Stiff, ControllerPreset::SoftTorque, ControllerPreset::ZTorque];

    /// The preset's name in the configuration.
    pub fn name(self) -> &'static str {
        match self {
            ControllerPreset::Stiff => "stiff",
            ControllerPreset::SoftTorque => "soft_torque",
            ControllerPreset::ZTorque => "z_torque",
        }
    }
}

/// The top-drive controller. `Z = J sqrt(G rho)` below is the characteristic impedance of the
/// top section (N m s = N m per rad/s: the torque a wave of 1 rad/s carries), `f1` the string's
/// first natural frequency (top fixed, bit free or with the BHA inertia), `I_TD` the top-drive
/// inertia. `drillstring tune CONFIG.toml` prints the gains of each preset for a string.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Controller {
    /// `speed` (ideal speed source), `pi` (a speed PI; a stiff one reflects the torsional waves
    /// back down the string), `soft_torque` (a PI tuned to absorb them at `tuning_frequency`),
    /// `z_torque` (the top drive lowers its speed by the high-passed string torque over
    /// `z_factor Z`, a damper to the waves).
    #[serde(rename = "type")]
    #[schemars(extend("label" = "controller"))]
    pub kind: ControllerKind,
    /// A named tuning, `stiff`, `soft_torque` or `z_torque`, that fills in `type` and the gains
    /// from the string; keys given beside it keep their values. Null: the keys as given.
    ///
    /// The rules and their sources: [`ControllerPreset`], [`super::tuning`].
    #[schemars(extend("label" = "controller preset"))]
    pub preset: Option<ControllerPreset>,
    /// `pi`: the proportional gain, >= 0: the motor torque per rad/s of speed error, i.e. the
    /// damping the top drive presents to the string.
    ///
    /// Compare it with `Z` (`kp >> Z`: a stiff top that reflects torque waves, `kp = Z`: a
    /// matched top that absorbs them). The Aarsnes & Shor default 38e3 is about 130 `Z` of a
    /// 5-in pipe. `soft_torque` computes it: `z_factor Z`.
    #[schemars(extend("unit" = "N*m*s/rad", "label" = "proportional gain"))]
    pub kp: f64,
    /// `pi`: the integral gain, >= 0: the motor torque per radian of accumulated speed error (a
    /// torsional spring to the setpoint's angle).
    ///
    /// `ki / kp` (1/s) is the corner below which the loop removes a steady speed error.
    /// `soft_torque` computes it: `(2 pi f)^2 I_TD`, so that at `f` this spring cancels the top
    /// drive's inertia.
    #[schemars(extend("unit" = "N*m/rad", "label" = "integral gain"))]
    pub ki: f64,
    /// `soft_torque`: the frequency at which the top drive's inertia is cancelled and it presents
    /// the pure damping `kp` (the stick-slip frequency), > 0. Null: the string's first natural
    /// frequency (fixed top, bit free or with the BHA inertia).
    #[schemars(extend("unit" = "Hz", "label" = "tuning frequency"))]
    pub tuning_frequency: Option<f64>,
    /// `soft_torque`, `z_torque`: the damping the top drive presents, in units of the top
    /// section's impedance `Z = J sqrt(G rho)`, > 0.
    ///
    /// Default 4, the published defaults of Simulator4nDOF (NORCE): its SoftTorque proportional gain `4 Z` and its ZTorque factor
    /// `0.25 / Z` on the high-passed torque (`1 / (z_factor Z)` here). On
    /// `examples/on-bottom-3000m.toml` at 40 rpm (300 cells) both then remove the stick-slip the
    /// PI controller leaves (SSI 0.21 and 0.03 against 1.12); at 1 `soft_torque` made it worse
    /// (1.47). Dimensionless; 1 matches the pipe (a torque wave is absorbed completely), larger
    /// is stiffer.
    #[schemars(extend("unit" = "", "label" = "impedance factor"))]
    pub z_factor: f64,
    /// `z_torque`: time constant of the low-pass that takes the mean string torque out of the
    /// impedance feedback (so that only the torque waves reduce the speed), > 0.
    ///
    /// Default `20 / (2 pi)` s: the torque high-pass of the ZTorque controller of Simulator4nDOF.
    /// While the string winds up before break-off its torque rises at `k Omega` (`k` the
    /// string's torsional stiffness), which the high-pass passes as `T k Omega`: the top drive
    /// turns at about `setpoint / (1 + T k / (z_factor Z))` until the mean torque has caught up
    /// (33 of 60 rpm for 15 s on `examples/on-bottom-3000m.toml` with the default; 14 rpm for
    /// 25 s at `z_factor = 1`). The `z_torque` preset ties `T` to the string, `1 / (pi f1)`.
    #[schemars(extend("unit" = "s", "label" = "torque high-pass time"))]
    pub torque_highpass_time: f64,
}

impl Default for Controller {
    /// Aarsnes & Shor (2018), MAIN.m: PI with `kp = 38e3`, `ki = 100e3`.
    fn default() -> Self {
        Controller {
            kind: ControllerKind::Pi,
            preset: None,
            kp: 38e3,
            ki: 100e3,
            tuning_frequency: None,
            z_factor: 4.0,
            torque_highpass_time: 20.0 / (2.0 * std::f64::consts::PI),
        }
    }
}

/// The top drive: inertia, setpoint and controller.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct TopDrive {
    /// Rotor inertia of the top drive, > 0.
    #[schemars(extend("unit" = "kg*m^2", "label" = "top-drive inertia"))]
    pub inertia: f64,
    /// The motor torque is clipped to `[-limit, limit]` (anti-windup), for every controller; > 0,
    /// a very large value (1e12) for no limit.
    ///
    /// Default 60 kN m: the continuous rating of a large top drive, as Simulator4nDOF (NORCE) sets
    /// its maximum top-drive torque; a run whose static torque exceeds it is warned that the
    /// string may never break free.
    #[schemars(extend("unit" = "N*m", "label" = "motor torque limit"))]
    pub torque_limit: f64,
    /// The top drive's speed setpoint (finite; negative turns the other way).
    #[schemars(extend("unit" = "rpm", "label" = "top-drive speed setpoint"))]
    pub rpm: f64,
    /// Time constant of the first-order approach of the setpoint from 0, >= 0 (0: a step).
    #[schemars(extend("unit" = "s", "label" = "ramp time"))]
    pub ramp_time: f64,
    /// `[time, rpm]` changes of the setpoint target at increasing times (approached with
    /// `ramp_time` too).
    #[schemars(extend("label" = "setpoint steps", "item_units" = ["s", "rpm"], "item_labels" = ["step time", "top-drive speed setpoint"]))]
    pub steps: Vec<[f64; 2]>,
    /// The speed controller.
    #[schemars(extend("label" = "controller"))]
    pub controller: Controller,
    /// Period of the zero-order hold of `pi` and `soft_torque`, > 0.
    #[schemars(extend("unit" = "s", "label" = "control interval"))]
    pub control_interval: f64,
    /// `speed`, `z_torque`: the bandwidth of the motor's speed loop, > 0.
    ///
    /// The top speed follows
    /// the speed these controllers ask for as a first-order lag of time constant
    /// `1 / (2 pi motor_bandwidth)` (exact over each step), so that the motor torque is the
    /// torque of a real drive and converges as the grid is refined (an ideal speed source asks
    /// the top-drive inertia times the jump of the speed over one step, a torque that grows as
    /// `1 / dt`). Default 10 Hz, the order of a variable-frequency drive's speed loop, well above
    /// a string's torsional modes (0.1-2 Hz).
    #[schemars(extend("unit" = "Hz", "label" = "motor bandwidth"))]
    pub motor_bandwidth: f64,
    /// What drives the top: `controller` (default: the controller of `controller` follows the
    /// setpoint `rpm`, `ramp_time`, `steps`) or `measured_speed` (the top speed is the series
    /// `speed_series`, imposed exactly, and the motor torque is the torque that imposes it:
    /// [`crate::drilling::engine::boundary::imposing_torque`]; the controller, setpoint and
    /// torque limit are then not used).
    #[schemars(extend("label" = "top boundary"))]
    pub mode: TopMode,
    /// `measured_speed`: the top-drive speed as `[time, rpm]` pairs, linearly interpolated;
    /// times finite and strictly increasing, covering the run (the first at or before 0, the
    /// last at or after `numerics.duration`). Empty with `controller`.
    #[schemars(extend("label" = "measured surface speed", "item_units" = ["s", "rpm"], "item_labels" = ["time", "top-drive speed"]))]
    pub speed_series: Vec<[f64; 2]>,
}

/// What drives the top of the string (`top_drive.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TopMode {
    /// The top drive with its controller and setpoint.
    #[default]
    Controller,
    /// The top speed follows `top_drive.speed_series` (a measured surface speed).
    MeasuredSpeed,
}

impl TopMode {
    pub const NAMES: [&'static str; 2] = ["controller", "measured_speed"];
}

impl Default for TopDrive {
    /// Aarsnes & Shor (2018): `I_TD = 2900` kg m^2, 40 rpm reached with a 1 s time constant,
    /// controller period 0.01 s.
    fn default() -> Self {
        TopDrive {
            inertia: 2900.0,
            torque_limit: DEFAULT_TORQUE_LIMIT,
            rpm: 40.0,
            ramp_time: 1.0,
            steps: Vec::new(),
            controller: Controller::default(),
            control_interval: 0.01,
            motor_bandwidth: 10.0,
            mode: TopMode::Controller,
            speed_series: Vec::new(),
        }
    }
}

impl DrillConfig {
    /// `top_drive`: inertia, bandwidth, torque limit, setpoint, controller, speed series.
    pub(super) fn validate_top_drive(&self) -> Result<()> {
        let td = &self.top_drive;
        pos("top_drive.inertia", td.inertia, "kg m^2")?;
        pos("top_drive.motor_bandwidth", td.motor_bandwidth, "Hz")?;
        if td.torque_limit.is_nan() || td.torque_limit <= 0.0 {
            return Err(Error::invalid(
                "top_drive.torque_limit",
                Num(td.torque_limit),
                "a number > 0 N m (a very large value, 1e12, for no limit)",
            ));
        }
        finite("top_drive.rpm", td.rpm, "rpm")?;
        nonneg("top_drive.ramp_time", td.ramp_time, "s")?;
        for (i, [t, rpm]) in td.steps.iter().enumerate() {
            nonneg(format!("top_drive.steps[{i}][0]"), *t, "s")?;
            if i > 0 && *t < td.steps[i - 1][0] {
                return Err(Error::invalid(format!("top_drive.steps[{i}][0]"), Num(*t), "times in increasing order"));
            }
            finite(format!("top_drive.steps[{i}][1]"), *rpm, "rpm")?;
        }
        let c = &td.controller;
        nonneg("top_drive.controller.kp", c.kp, "N m s/rad")?;
        nonneg("top_drive.controller.ki", c.ki, "N m/rad")?;
        if let Some(f) = c.tuning_frequency {
            pos("top_drive.controller.tuning_frequency", f, "Hz, or null for the string's first mode")?;
        }
        pos("top_drive.controller.z_factor", c.z_factor, "-")?;
        pos("top_drive.controller.torque_highpass_time", c.torque_highpass_time, "s")?;
        pos("top_drive.control_interval", td.control_interval, "s")?;
        self.validate_speed_series()?;
        Ok(())
    }

    /// `top_drive.speed_series`: with `mode = "measured_speed"` at least two `[time s, rpm]`
    /// pairs, finite, times strictly increasing and covering `[0, numerics.duration]`; with
    /// `controller` empty (a series that would be ignored is refused).
    fn validate_speed_series(&self) -> Result<()> {
        let td = &self.top_drive;
        let v = &td.speed_series;
        if td.mode == TopMode::Controller {
            if !v.is_empty() {
                return Err(Error::invalid(
                    "top_drive.speed_series",
                    format!("{} pairs", v.len()),
                    "empty with top_drive.mode = \"controller\" (set top_drive.mode = \"measured_speed\" to impose it)",
                ));
            }
            return Ok(());
        }
        if v.len() < 2 {
            return Err(Error::invalid(
                "top_drive.speed_series",
                format!("{} pairs", v.len()),
                "at least 2 [time s, rpm] pairs with top_drive.mode = \"measured_speed\"",
            ));
        }
        for (i, [t, rpm]) in v.iter().enumerate() {
            finite(format!("top_drive.speed_series[{i}][0]"), *t, "s")?;
            finite(format!("top_drive.speed_series[{i}][1]"), *rpm, "rpm")?;
            if i > 0 && *t <= v[i - 1][0] {
                return Err(Error::invalid(
                    format!("top_drive.speed_series[{i}][0]"),
                    Num(*t),
                    format!("times strictly increasing (after {} s)", Num(v[i - 1][0])),
                ));
            }
        }
        let (first, last, end) = (v[0][0], v[v.len() - 1][0], self.numerics.duration);
        if first > 0.0 {
            return Err(Error::invalid("top_drive.speed_series[0][0]", Num(first), "a time <= 0 s (covering the run)"));
        }
        if last < end {
            return Err(Error::invalid(
                format!("top_drive.speed_series[{}][0]", v.len() - 1),
                Num(last),
                format!("a time >= numerics.duration = {} s (covering the run)", Num(end)),
            ));
        }
        Ok(())
    }
}
