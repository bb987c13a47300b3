//! Reading a configuration: JSON to [`DrillConfig`], the required keys, the rules of the
//! well's and the bit's alternative forms, the errors of the schema parse in the configuration's
//! own words.

use serde_json::{Map, Value};

use crate::error::{Error, Result};
use crate::schema::{self, join, kind, shown};

use super::{pos, DrillConfig, Override};

/// Keys that must be present in a configuration's JSON.
pub(crate) const REQUIRED_TOP: [&str; 1] = ["sections"];
pub(crate) const REQUIRED_SECTION: [&str; 3] = ["length", "outer_diameter", "inner_diameter"];

/// A drilling configuration's error of the schema parse, in its own words: a top-drive step
/// names the step (`top_drive.steps[1]`, `[time s, rpm]`), the inclination its two forms, a
/// non-finite number the field's range ([`finite_range`], when `probe`).
fn refine(user: &Value, error: Error, probe: bool) -> Error {
    let Error::InvalidInput { field, value, allowed } = error;
    for key in ["steps", "speed_series"] {
        if let Some(rest) = field.strip_prefix(&format!("top_drive.{key}[")) {
            let index = rest.split(']').next().unwrap_or("");
            let step = user.pointer(&format!("/top_drive/{key}/{index}")).map_or(value, shown);
            return Error::invalid(format!("top_drive.{key}[{index}]"), step, "[time s, rpm]");
        }
    }
    if allowed.contains("untagged enum Inclination") {
        return Error::invalid(field, value, "a number or an array of numbers (degrees)");
    }
    if allowed == "a finite number" && probe {
        if let Some(range) = finite_range(user, &field) {
            return Error::invalid(field, value, range);
        }
    }
    Error::InvalidInput { field, value, allowed }
}

/// The range a numeric field takes, in the words of its own check, for the message of a
/// non-finite value there (`nan`, `inf`, which the parser refuses before any range is checked):
/// the configuration is checked again with a finite value at `field` far out of every range,
/// `-1e308` and then `1e308`, and the first error that names `field` gives the range. None when
/// both pass, or another field fails first.
fn finite_range(user: &Value, field: &str) -> Option<String> {
    let pointer: String = field.replace('[', ".").replace(']', "").split('.').map(|k| format!("/{k}")).collect();
    for probe in [-1e308, 1e308] {
        let mut copy = user.clone();
        *copy.pointer_mut(&pointer)? = Value::from(probe);
        match DrillConfig::parse_value(copy, false).and_then(|c| c.validate()) {
            Err(Error::InvalidInput { field: f, allowed, .. }) if f == field => return Some(allowed),
            Err(_) => return None,
            Ok(()) => {}
        }
    }
    None
}

/// The constant-inclination rule, the one place it lives: one inclination number
/// (`well.inclination_deg = 20`) with no survey depths given means no survey (`well.md` null;
/// the default depths are the default table's).
pub(super) fn constant_inclination(well: &mut Map<String, Value>, md_given: bool) {
    if !md_given && well.get("inclination_deg").is_some_and(Value::is_number) {
        well.insert("md".into(), Value::Null);
    }
}

/// The error of a bit given by both its radius and its diameter.
pub(super) fn bit_size_conflict() -> Error {
    Error::invalid(
        "bit.diameter",
        "both bit.radius and bit.diameter",
        "one of bit.radius or bit.diameter (the diameter is twice the radius)",
    )
}

/// After overrides: a bit radius set by an override replaces the configuration's diameter and a
/// diameter its radius (a table `bit` counts by its keys); both set is refused by the parse.
pub(super) fn bit_size_override(config: &mut Value, overrides: &[Override]) {
    let sets = |key: &str| {
        overrides.iter().any(|(p, v): &Override| {
            (p == "bit" && v.get(key).is_some_and(|x| !x.is_null()))
                || (p.strip_prefix("bit.") == Some(key) && !v.is_null())
        })
    };
    let (radius, diameter) = (sets("radius"), sets("diameter"));
    if let Some(Value::Object(bit)) = config.get_mut("bit") {
        if diameter && !radius {
            bit.remove("radius");
        } else if radius && !diameter {
            bit.remove("diameter");
        }
    }
}

fn require(path: &str, map: &Map<String, Value>, keys: &[&str]) -> Result<()> {
    for k in keys {
        if !map.contains_key(*k) {
            return Err(Error::invalid(join(path, k), "missing", "a value (required)"));
        }
    }
    Ok(())
}

impl DrillConfig {
    /// Parses a configuration (JSON object), filling defaults; an error names the dotted field
    /// of an unknown key, a wrong type or a missing required value. Does not validate ranges
    /// ([`DrillConfig::validate`]).
    pub fn from_json(json: &str) -> Result<DrillConfig> {
        let user: Value = serde_json::from_str(json)
            .map_err(|e| Error::invalid("config", format!("text that is not JSON ({e})"), "a JSON object"))?;
        DrillConfig::from_value(user)
    }

    /// [`DrillConfig::from_json`] of a parsed JSON value.
    pub fn from_value(user: Value) -> Result<DrillConfig> {
        DrillConfig::parse_value(user, true)
    }

    /// [`DrillConfig::from_value`]; `probe`: a non-finite number's error names the field's
    /// range ([`finite_range`], which parses without probing).
    fn parse_value(mut user: Value, probe: bool) -> Result<DrillConfig> {
        let Value::Object(map) = &mut user else {
            return Err(Error::invalid("config", kind(&user), "a JSON object"));
        };
        require("", map, &REQUIRED_TOP)?;
        if let Some(Value::Array(sections)) = map.get("sections") {
            for (i, s) in sections.iter().enumerate() {
                if let Value::Object(s) = s {
                    require(&format!("sections[{i}]"), s, &REQUIRED_SECTION)?;
                }
            }
        }
        // a survey file or a plan replaces the stations: refuse both, and an inclination beside them
        let well_value = |key: &str| map.get("well").and_then(|w| w.get(key)).is_some_and(|v| !v.is_null());
        let sources: Vec<&str> = ["survey", "plan", "md"].into_iter().filter(|k| well_value(k)).collect();
        if sources.len() > 1 {
            return Err(Error::invalid(
                format!("well.{}", sources[1]),
                format!("both well.{} and well.{}", sources[0], sources[1]),
                "one of well.survey (a file), well.plan (segments), well.md with well.inclination_deg",
            ));
        }
        let stations_replaced = well_value("survey") || well_value("plan");
        let placeholder = map.get("well").and_then(|w| w.get("inclination_deg")).and_then(Value::as_f64) == Some(0.0);
        if stations_replaced && well_value("inclination_deg") && !placeholder {
            return Err(Error::invalid(
                "well.inclination_deg",
                "a value with a survey file or plan",
                "no value, or 0 (the survey file or plan gives the inclinations)",
            ));
        }
        if let Some(Value::Object(well)) = map.get_mut("well") {
            let md_given = well.contains_key("md");
            constant_inclination(well, md_given);
            if stations_replaced {
                well.insert("md".into(), Value::Null);
                well.insert("inclination_deg".into(), Value::from(0.0));
            }
        }
        if let Some(Value::Object(bit)) = map.get("bit") {
            let given = |key: &str| bit.get(key).is_some_and(|v| !v.is_null());
            if given("radius") && given("diameter") {
                return Err(bit_size_conflict());
            }
        }
        let mut cfg: DrillConfig = schema::parse(&user).map_err(|e| refine(&user, e, probe))?;
        if let Some(d) = cfg.bit.diameter.take() {
            // the normalised configuration gives the bit by its radius
            pos("bit.diameter", d, "m, or null to give bit.radius")?;
            cfg.bit.radius = d / 2.0;
        }
        crate::drilling::well::load_survey(&mut cfg)?;
        let given: Vec<String> = user
            .pointer("/top_drive/controller")
            .and_then(Value::as_object)
            .map_or_else(Vec::new, |c| c.keys().cloned().collect());
        crate::drilling::tuning::apply_preset(&mut cfg, &given)?;
        Ok(cfg)
    }

    /// The configuration as JSON, every default filled in.
    pub fn to_json(&self) -> String {
        // with a survey file or a plan, `well.md` is null and `well.inclination_deg` the
        // placeholder 0, which parse back to the same configuration
        serde_json::to_string(self).unwrap_or_else(|_| "{}".into())
    }
}
