//! Values changed during a run (`[[changes]]`): the keys that may change ([`SETTABLE`]), a
//! change's table ([`Change`]) and the check of a changed configuration ([`settable_config`]),
//! shared by a session's `set` and the batch run's `[[changes]]`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::error::{Error, Num, Result};
use crate::schema::shown;

use super::{set_path, DrillConfig};

/// The keys that may change during a run, by dotted path: the top drive's speed, controller and
/// torque limit, the velocity-weakening bit's weight, the wall friction's factors and the
/// hoist's mode and targets (a coupled run's).
pub const SETTABLE: &[&str] = &[
    "top_drive.rpm",
    "top_drive.torque_limit",
    "top_drive.controller.type",
    "top_drive.controller.kp",
    "top_drive.controller.ki",
    "top_drive.controller.z_factor",
    "bit.weight_on_bit",
    "friction.static",
    "friction.kinetic_ratio",
    "hoist.mode",
    "hoist.speed",
    "hoist.hook_load",
    "hoist.weight_on_bit",
    "hoist.autodriller.setpoint",
    "hoist.autodriller.kp",
    "hoist.autodriller.ki",
];

/// A value changed during a run (`[[changes]]`): from the step starting at the step boundary
/// nearest `time` on, `key` is `value`, as a session's `set` at that time makes it (a recorded
/// session's changes replayed by `drillstring drill`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Change {
    /// Time the change takes effect from, in [0, numerics.duration].
    #[schemars(extend("unit" = "s", "label" = "change time"))]
    pub time: f64,
    /// The dotted key changed, one of those that may change during a run: the top drive's speed,
    /// controller type, gains and torque limit, the bit's weight, the wall friction's factors,
    /// the hoist's mode and targets (`DrillSession.settable` lists them).
    #[schemars(extend("label" = "changed key"))]
    pub key: String,
    /// The new value, as the key takes it in the configuration (SI).
    #[schemars(extend("label" = "new value"))]
    pub value: Value,
}

/// Changes from JSON text (a list of `{time, key, value}` tables), naming `field` in the error.
pub fn changes_from_json(text: &str, field: &str) -> Result<Vec<Change>> {
    serde_json::from_str(text).map_err(|e| {
        Error::invalid(field, format!("text that is not a list of changes ({e})"), "[{time, key, value}, ...]")
    })
}

/// `cfg` with `key` set to `value`, checked as a whole ([`DrillConfig::validate_values`]);
/// refused naming the key when it may not change during a run ([`SETTABLE`]; a hoist key
/// without a hoist) or the value is out of its range.
pub fn settable_config(cfg: &DrillConfig, key: &str, value: &Value) -> Result<DrillConfig> {
    if !SETTABLE.contains(&key) {
        return Err(Error::invalid(
            key,
            shown(value),
            format!("a key that may change during a run ({}): {key} cannot change during a run", SETTABLE.join(", ")),
        ));
    }
    if key.starts_with("hoist.") && cfg.hoist.is_none() {
        return Err(Error::invalid(
            key,
            shown(value),
            "a configuration with a [hoist]: a torsion-only run has no hoist, and a hoist cannot be added during a run",
        ));
    }
    let mut json = serde_json::to_value(cfg).map_err(|e| Error::invalid("config", e, "a configuration"))?;
    if let Value::Object(map) = &mut json {
        map.remove("changes");
    }
    set_path(&mut json, key, value, "key")?;
    let mut out = DrillConfig::from_value(json)?;
    out.validate_values()?;
    out.changes.clone_from(&cfg.changes);
    Ok(out)
}

impl DrillConfig {
    /// Checks `[[changes]]`: each key one of [`SETTABLE`], each time in [0, numerics.duration],
    /// each value accepted by the configuration as changed by the changes before it (in time
    /// order), naming `changes[i]`'s field.
    pub(super) fn validate_changes(&self) -> Result<()> {
        if self.changes.is_empty() {
            return Ok(());
        }
        let duration = self.numerics.duration;
        let mut order: Vec<usize> = (0..self.changes.len()).collect();
        for (i, c) in self.changes.iter().enumerate() {
            if !(c.time.is_finite() && (0.0..=duration).contains(&c.time)) {
                return Err(Error::invalid(
                    format!("changes[{i}].time"),
                    Num(c.time),
                    format!("a time in [0, {}] (numerics.duration, s)", Num(duration)),
                ));
            }
            if !SETTABLE.contains(&c.key.as_str()) {
                return Err(Error::invalid(
                    format!("changes[{i}].key"),
                    shown(&Value::String(c.key.clone())),
                    format!("a key that may change during a run: one of {}", SETTABLE.join(", ")),
                ));
            }
        }
        order.sort_by(|&a, &b| self.changes[a].time.total_cmp(&self.changes[b].time));
        let mut cfg = self.clone();
        cfg.changes.clear();
        for i in order {
            let c = &self.changes[i];
            cfg = settable_config(&cfg, &c.key, &c.value).map_err(|e| match e {
                Error::InvalidInput { field, value, allowed } => Error::invalid(
                    format!("changes[{i}].value"),
                    value,
                    format!("a value of {field} the run accepts at t = {} s: {allowed}", Num(c.time)),
                ),
            })?;
        }
        Ok(())
    }
}
