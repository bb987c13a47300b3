//! The metrics window (`[metrics]`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};
use crate::metrics::STICK_SPEED;

use super::{nonneg, DrillConfig};

/// The metrics window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MetricsConfig {
    /// `[t_start, t_end]` of the metrics window, `t_start < t_end`, holding at least two samples.
    /// Null: the last half of the run.
    #[schemars(extend("unit" = "s", "label" = "metrics window"))]
    pub window: Option<[f64; 2]>,
    /// The bit counts as stuck at or below this speed, >= 0.
    #[schemars(extend("unit" = "rad/s", "label" = "stick speed"))]
    pub stick_speed: f64,
}

impl Default for MetricsConfig {
    fn default() -> Self {
        MetricsConfig { window: None, stick_speed: STICK_SPEED }
    }
}

impl DrillConfig {
    /// `metrics`: the window holds at least two of the run's samples.
    pub(super) fn validate_metrics(&self) -> Result<()> {
        let m = &self.metrics;
        if let Some([a, b]) = m.window {
            if !(a.is_finite() && b.is_finite() && a < b) {
                return Err(Error::invalid(
                    "metrics.window",
                    format!("[{}, {}]", Num(a), Num(b)),
                    "[t_start, t_end] with t_start < t_end (s), or null for the last half of the run",
                ));
            }
            // at least two series samples t = k output_interval inside the window (the samples
            // the metrics are computed from, as `metrics::stick_slip` selects them)
            let dt = self.numerics.output_interval;
            let last = self.series_samples().saturating_sub(1) as f64;
            let mut lo = (a.max(0.0) / dt).floor();
            while lo * dt < a {
                lo += 1.0;
            }
            let mut hi = (b / dt).floor().min(last);
            while hi >= 0.0 && hi * dt > b {
                hi -= 1.0;
            }
            if hi - lo < 1.0 {
                return Err(Error::invalid(
                    "metrics.window",
                    format!("[{}, {}]", Num(a), Num(b)),
                    format!(
                        "a window holding at least 2 samples of the run's series (0 to numerics.duration = {} s \
                         every {} s)",
                        Num(self.numerics.duration),
                        Num(dt)
                    ),
                ));
            }
        }
        nonneg("metrics.stick_speed", m.stick_speed, "rad/s")?;
        Ok(())
    }
}
