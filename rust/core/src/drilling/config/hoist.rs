//! The hoist (`[hoist]`): what it imposes at the top of a coupled run's axial field.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::super::engine::bit_law;
use super::{finite, nonneg, DrillConfig, MAX_CUT_SURFACE_CELLS};

/// What the hoist imposes at the top of the axial field (`hoist.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HoistMode {
    /// The block velocity `hoist.speed`.
    Velocity,
    /// The hook load `hoist.hook_load`.
    HookLoad,
    /// The weight on bit `hoist.weight_on_bit`: the hook load held at the static hook load of
    /// the string hanging off bottom less this weight (what a rig's weight indicator shows).
    WeightOnBit,
    /// The block velocity of the autodriller `[hoist.autodriller]` (a PI on the weight on bit or
    /// the rate of penetration).
    Autodriller,
}

/// The hoist at the top of the string. With a `[hoist]` table the run is coupled axial-torsional
/// with the bit on bottom (`bit.law` `detournay` or `rgd`); without it, torsion only.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Hoist {
    /// What the hoist imposes: `velocity` (the block velocity `speed`, default), `hook_load`
    /// (the force `hook_load` holding the string up), `weight_on_bit` (the hook load held at the
    /// static hook load of the string hanging off bottom less `weight_on_bit`) or `autodriller`
    /// (the block velocity of the PI `[hoist.autodriller]`).
    #[schemars(extend("label" = "hoist mode"))]
    pub mode: HoistMode,
    /// Block velocity of `velocity` mode, down positive (default 30 m/h).
    #[schemars(extend("unit" = "m/s", "label" = "block velocity"))]
    pub speed: f64,
    /// Hook load of `hook_load` mode, >= 0.
    #[schemars(extend("unit" = "N", "label" = "hook load"))]
    pub hook_load: f64,
    /// Weight on bit of `weight_on_bit` mode, >= 0: the static hook load of the hanging string
    /// less the hook load held (ramped from 0 with `ramp_time`).
    #[schemars(extend("unit" = "N", "label" = "hoist weight on bit"))]
    pub weight_on_bit: f64,
    /// Time constant of the hoist setpoint's approach to its target, >= 0 (0: a step). The
    /// block velocity starts at 0, the hook load at the static hook load of the hanging string,
    /// the weight on bit at 0.
    #[schemars(extend("unit" = "s", "label" = "hoist ramp time"))]
    pub ramp_time: f64,
    /// `[time, value]` changes of the mode's target at increasing times, approached with
    /// `ramp_time` as the top drive's `steps`: the block velocity (m/s), the hook load (N) or the
    /// autodriller's setpoint (N or m/s). Plain numbers are SI in either unit system.
    #[schemars(extend("label" = "hoist steps", "item_units" = ["s", "m/s or N"], "item_labels" = ["step time", "hoist target"]))]
    pub steps: Vec<[f64; 2]>,
    /// The autodriller of `mode = "autodriller"`.
    #[schemars(extend("label" = "autodriller"))]
    pub autodriller: Autodriller,
}

impl Default for Hoist {
    fn default() -> Self {
        Hoist {
            mode: HoistMode::Velocity,
            speed: 30.0 / 3600.0,
            hook_load: 0.0,
            weight_on_bit: 0.0,
            ramp_time: 1.0,
            steps: Vec::new(),
            autodriller: Autodriller::default(),
        }
    }
}

impl Hoist {
    /// Refuses non-finite values, a negative ramp time or gain, limits out of order, or steps
    /// out of time order, naming `<prefix>.<field>`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        let finite = [
            ("speed", self.speed),
            ("hook_load", self.hook_load),
            ("weight_on_bit", self.weight_on_bit),
            ("autodriller.setpoint", self.autodriller.setpoint),
            ("autodriller.min_speed", self.autodriller.min_speed),
            ("autodriller.max_speed", self.autodriller.max_speed),
        ];
        for (name, value) in finite {
            if !value.is_finite() {
                return Err(Error::invalid(format!("{prefix}.{name}"), Num(value), "a finite number"));
            }
        }
        let non_negative = [
            ("ramp_time", self.ramp_time),
            ("autodriller.kp", self.autodriller.kp),
            ("autodriller.ki", self.autodriller.ki),
        ];
        for (name, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::invalid(format!("{prefix}.{name}"), Num(value), "a finite number >= 0"));
            }
        }
        let a = &self.autodriller;
        if self.mode == HoistMode::Autodriller && a.kp == 0.0 && a.ki == 0.0 {
            return Err(Error::invalid(
                format!("{prefix}.autodriller.kp"),
                "kp = ki = 0",
                "kp > 0 or ki > 0 in autodriller mode (with no gain the block never answers the weight on bit \
                 or ROP); (m/s)/N and (m/s)/(N s) on weight_on_bit, 1 and 1/s on rop",
            ));
        }
        if a.max_speed < a.min_speed {
            return Err(Error::invalid(
                format!("{prefix}.autodriller.max_speed"),
                Num(a.max_speed),
                format!("a number >= autodriller.min_speed ({})", Num(a.min_speed)),
            ));
        }
        let mut last = f64::NEG_INFINITY;
        for (i, s) in self.steps.iter().enumerate() {
            if !(s[0].is_finite() && s[1].is_finite() && s[0] >= last) {
                return Err(Error::invalid(
                    format!("{prefix}.steps[{i}]"),
                    format!("[{}, {}]", Num(s[0]), Num(s[1])),
                    "[time, value], finite, in increasing time",
                ));
            }
            last = s[0];
        }
        Ok(())
    }
}

/// The autodriller's controlled quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum AutodrillerTarget {
    /// Weight on bit, N.
    WeightOnBit,
    /// Rate of penetration, m/s.
    Rop,
}

/// The autodriller (`hoist.mode = "autodriller"`): a PI on the weight on bit or the rate of
/// penetration giving the block velocity, `u = u_ff + kp e + ki int e` within
/// `[min_speed, max_speed]` (no integration while saturated in the error's direction), `e` the
/// setpoint less the measured value, `u_ff` the setpoint itself with `target = "rop"` (0 with
/// `weight_on_bit`). `kp` and `ki` are not both 0 in autodriller mode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Autodriller {
    /// The controlled quantity: `weight_on_bit` (default) or `rop` (the rate of penetration).
    #[schemars(extend("label" = "autodriller target"))]
    pub target: AutodrillerTarget,
    /// The target's setpoint: N with `weight_on_bit`, m/s with `rop` (finite; approached with
    /// `hoist.ramp_time`, changed by `hoist.steps`). A plain number is SI in either unit system.
    #[schemars(extend("unit" = "N or m/s", "label" = "autodriller setpoint"))]
    pub setpoint: f64,
    /// Proportional gain, >= 0: block velocity per unit of error, (m/s)/N with
    /// `weight_on_bit`, dimensionless with `rop`.
    #[schemars(extend("unit" = "m/(N*s) or 1", "label" = "autodriller proportional gain"))]
    pub kp: f64,
    /// Integral gain, >= 0: block velocity per unit of integrated error, (m/s)/(N s) with
    /// `weight_on_bit`, 1/s with `rop`.
    #[schemars(extend("unit" = "m/(N*s^2) or 1/s", "label" = "autodriller integral gain"))]
    pub ki: f64,
    /// The least block velocity, down positive (negative: the block may pull up).
    #[schemars(extend("unit" = "m/s", "label" = "autodriller least block velocity"))]
    pub min_speed: f64,
    /// The largest block velocity, >= `min_speed` (default 100 m/h).
    #[schemars(extend("unit" = "m/s", "label" = "autodriller largest block velocity"))]
    pub max_speed: f64,
}

impl Default for Autodriller {
    /// Weight on bit 80 kN, limits 0 to 100 m/h; gains set by the user for the string.
    fn default() -> Self {
        Autodriller {
            target: AutodrillerTarget::WeightOnBit,
            setpoint: 80e3,
            kp: 0.0,
            ki: 0.0,
            min_speed: 0.0,
            max_speed: 100.0 / 3600.0,
        }
    }
}

impl DrillConfig {
    /// The coupled run's keys: `bit.law` `detournay` or `rgd` with a `[hoist]` table and the
    /// reverse, the Detournay law's and the hoist's ranges.
    pub(super) fn validate_coupled(&self) -> Result<()> {
        // (whether the law needs the axial field, as the law declares it)
        let coupled = bit_law::axial_need(self.bit.law) == bit_law::AxialNeed::DepthOfCut;
        match (&self.hoist, coupled) {
            (None, true) => {
                return Err(Error::invalid(
                    "bit.law",
                    self.bit.law.name(),
                    "velocity_weakening without a [hoist] table (detournay and rgd need the hoist's axial field)",
                ))
            }
            (Some(_), false) => {
                return Err(Error::invalid(
                    "hoist",
                    "a [hoist] table with bit.law = velocity_weakening",
                    "bit.law = detournay or rgd with a [hoist] table (the coupled run), or no [hoist] table",
                ))
            }
            _ => {}
        }
        if coupled && self.bit.on_bottom {
            // the velocity-weakening law's keys: a coupled bit meets the rock through the hoist
            return Err(Error::invalid(
                "bit.on_bottom",
                format!("true with bit.law = {}", self.bit.law.name()),
                "false (a coupled run's bit reaches the rock through the [hoist] table: hoist.weight_on_bit, \
                 hoist.speed or hoist.hook_load; bit.on_bottom and bit.weight_on_bit belong to the velocity-weakening law)",
            ));
        }
        if let Some(h) = &self.hoist {
            finite("hoist.speed", h.speed, "m/s")?;
            nonneg("hoist.hook_load", h.hook_load, "N")?;
            nonneg("hoist.weight_on_bit", h.weight_on_bit, "N")?;
            nonneg("hoist.ramp_time", h.ramp_time, "s")?;
            h.validate("hoist")?;
            bit_law::validate(self)?;
            let cells = self.bit.detournay.cut_surface_cells;
            if !(1..=MAX_CUT_SURFACE_CELLS).contains(&cells) {
                return Err(Error::invalid(
                    "bit.detournay.cut_surface_cells",
                    cells,
                    format!("an integer in 1..={MAX_CUT_SURFACE_CELLS}"),
                ));
            }
        }
        Ok(())
    }
}
