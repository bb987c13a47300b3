//! The hoist (`[hoist]`): what it imposes at the top of a coupled run's axial field.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

use super::super::axial::hoist::{Autodriller, HoistMode, HoistParams};
use super::{finite, nonneg, BitRockLaw, DrillConfig, MAX_CUT_SURFACE_CELLS};

/// What the hoist imposes at the top of the axial field (`hoist.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HoistKind {
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
    pub mode: HoistKind,
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
        let p = HoistParams::default();
        Hoist {
            mode: HoistKind::Velocity,
            speed: p.speed,
            hook_load: p.hook_load,
            weight_on_bit: p.weight_on_bit,
            ramp_time: p.ramp_time,
            steps: p.steps,
            autodriller: p.autodriller,
        }
    }
}

impl Hoist {
    /// The hoist part's parameters.
    pub fn params(&self) -> HoistParams {
        HoistParams {
            mode: match self.mode {
                HoistKind::Velocity => HoistMode::Velocity,
                HoistKind::HookLoad => HoistMode::HookLoad,
                HoistKind::WeightOnBit => HoistMode::WeightOnBit,
                HoistKind::Autodriller => HoistMode::Autodriller,
            },
            speed: self.speed,
            hook_load: self.hook_load,
            weight_on_bit: self.weight_on_bit,
            ramp_time: self.ramp_time,
            steps: self.steps.clone(),
            autodriller: self.autodriller,
        }
    }
}

impl DrillConfig {
    /// The coupled run's keys: `bit.law` `detournay` or `rgd` with a `[hoist]` table and the
    /// reverse, the Detournay law's and the hoist's ranges.
    pub(super) fn validate_coupled(&self) -> Result<()> {
        let coupled = self.bit.law != BitRockLaw::VelocityWeakening;
        match (&self.hoist, coupled) {
            (None, true) => {
                return Err(Error::invalid(
                    "bit.law",
                    if self.bit.law == BitRockLaw::Rgd { "rgd" } else { "detournay" },
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
                format!("true with bit.law = {}", if self.bit.law == BitRockLaw::Rgd { "rgd" } else { "detournay" }),
                "false (a coupled run's bit reaches the rock through the [hoist] table: hoist.weight_on_bit, \
                 hoist.speed or hoist.hook_load; bit.on_bottom and bit.weight_on_bit belong to the velocity-weakening law)",
            ));
        }
        if let Some(h) = &self.hoist {
            finite("hoist.speed", h.speed, "m/s")?;
            nonneg("hoist.hook_load", h.hook_load, "N")?;
            nonneg("hoist.weight_on_bit", h.weight_on_bit, "N")?;
            nonneg("hoist.ramp_time", h.ramp_time, "s")?;
            h.params().validate("hoist")?;
            self.bit.detournay.law(self.bit.radius).validate("bit.detournay")?;
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
