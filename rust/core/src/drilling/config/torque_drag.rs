//! The static torque-and-drag analysis's table (`[torque_drag]`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The static torque-and-drag analysis (`drillstring torque-drag`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct TorqueDragConfig {
    /// The torque on bit when drilling (rotating on bottom), >= 0.
    #[schemars(extend("unit" = "N*m", "label" = "torque on bit"))]
    pub bit_torque: f64,
    /// The travelling block's weight (with hook and top drive), added to hook loads, >= 0.
    #[schemars(extend("unit" = "N", "label" = "block weight"))]
    pub block_weight: f64,
    /// The longest element of the stepped solution, > 0 and at least the string's length over
    /// a million (the elements' count is bounded).
    #[schemars(extend("unit" = "m", "label" = "element length"))]
    pub step: f64,
    /// The friction factors of the broomstick plot (uniform along the hole), 1 to 100, each in [0, 10].
    #[schemars(extend("unit" = "", "label" = "friction factor"))]
    pub friction_factors: Vec<f64>,
    /// Bit depths of the broomstick plot, evenly spaced to the string's length, 2 to 100000.
    #[schemars(extend("unit" = "", "label" = "broomstick points"))]
    pub broomstick_points: usize,
}

impl Default for TorqueDragConfig {
    fn default() -> Self {
        TorqueDragConfig {
            bit_torque: 0.0,
            block_weight: 0.0,
            step: crate::well::torque_drag::DEFAULT_STEP,
            friction_factors: vec![0.1, 0.2, 0.3, 0.4],
            broomstick_points: 100,
        }
    }
}
