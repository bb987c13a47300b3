//! Parsing a configuration from JSON with errors that name the dotted field
//! (`sections[1].length`, `top_drive.controller.type`, `initial_velocities[2]`), the value found
//! there and what the field takes, in the words of the configuration (`a number`,
//! `true or false`, `one of pi, speed`). The one parser of the drilling configuration, the
//! paper model's parameters and the lumped model's parameters.

use serde::de::DeserializeOwned;
use serde_json::Value;

use crate::error::{Error, Result};

/// `path.key` (`key` at the top).
pub(crate) fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// What kind of JSON value `v` is, for messages.
pub(crate) fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// `v` as JSON, at most 60 characters.
pub(crate) fn shown(v: &Value) -> String {
    let s = v.to_string();
    if s.len() > 60 {
        format!("{}...", &s[..s.char_indices().take(57).last().map_or(0, |(i, c)| i + c.len_utf8())])
    } else {
        s
    }
}

/// What serde's `expected ...` text means in the words of the configuration; `found` is the
/// value at the field (a non-finite number arrives from Python as its text, `"nan"`).
fn expected_text(serde: &str, found: Option<&Value>) -> String {
    let serde = serde.trim();
    if let Some(names) = serde.strip_prefix("one of ") {
        return format!("one of {}", names.replace('`', ""));
    }
    if let Some((a, b)) = serde.strip_prefix('`').and_then(|s| s.strip_suffix('`')).and_then(|s| s.split_once("` or `"))
    {
        return format!("one of {a}, {b}"); // serde's words for two names
    }
    match serde {
        "f64" if found.and_then(Value::as_str).is_some_and(|s| ["nan", "inf", "-inf"].contains(&s)) => {
            "a finite number".into()
        }
        "f64" => "a number".into(),
        "usize" | "u64" => "an integer >= 0".into(),
        "a boolean" => "true or false".into(),
        "a string" | "string or map" => "a string".into(),
        "a sequence" => "an array".into(),
        "an array of length 2" | "fewer elements in array" => "an array of 2 numbers".into(),
        s if s.starts_with("struct ") => "an object".into(),
        s => s.replace('`', ""),
    }
}

/// `T` from the JSON value `user`. An error names the dotted field: an unknown key (the
/// allowed ones listed), a value of the wrong type (what the field takes), a missing field.
pub(crate) fn parse<T: DeserializeOwned>(user: &Value) -> Result<T> {
    serde_path_to_error::deserialize(user).map_err(|error| {
        let mut field = String::new();
        let mut node = Some(user);
        for segment in error.path().iter() {
            match segment {
                serde_path_to_error::Segment::Seq { index } => {
                    field = format!("{field}[{index}]");
                    node = node.and_then(|n| n.get(*index));
                }
                serde_path_to_error::Segment::Map { key } => {
                    field = join(&field, key);
                    node = node.and_then(|n| n.get(key));
                }
                _ => {}
            }
        }
        let message = error.inner().to_string();
        if let Some(rest) = message.strip_prefix("unknown field `") {
            let (key, expected) = rest.split_once('`').unwrap_or((rest, ""));
            if field != key && !field.ends_with(&format!(".{key}")) {
                field = join(&field, key);
            }
            let allowed = expected.trim_start_matches(", expected ");
            return Error::invalid(field, "an unknown field", expected_text(allowed, None));
        }
        if let Some(rest) = message.strip_prefix("missing field `") {
            let key = rest.split_once('`').map_or(rest, |(k, _)| k);
            return Error::invalid(join(&field, key), "missing", "a value (required)");
        }
        // a non-finite number arrives from Python as its text: shown as the number it was
        let value = match node.and_then(Value::as_str) {
            Some(s @ ("nan" | "inf" | "-inf")) => s.to_string(),
            _ => node.map_or_else(|| "nothing".to_string(), shown),
        };
        let allowed = message.rsplit_once(", expected ").map_or(message.as_str(), |(_, e)| e);
        let field = if field.is_empty() { "config".to_string() } else { field };
        Error::invalid(field, value, expected_text(allowed, node))
    })
}

#[cfg(test)]
mod tests {
    use crate::drilling::DrillConfig;
    use crate::model::Parameters;

    fn message(json: &str) -> String {
        DrillConfig::from_json(json).unwrap_err().to_string()
    }

    #[test]
    fn errors_name_the_dotted_field_and_what_it_takes() {
        let pipe = r#"{"length": 1000, "outer_diameter": 0.127, "inner_diameter": 0.1}"#;
        let with = |rest: &str| format!(r#"{{"sections": [{pipe}, {pipe}]{rest}}}"#);
        assert_eq!(
            message(&with(r#", "top_drive": {"rmp": 1}"#)),
            "invalid top_drive.rmp: got an unknown field, expected one of inertia, torque_limit, rpm, ramp_time, \
             steps, controller, control_interval, motor_bandwidth, mode, speed_series"
        );
        assert_eq!(
            message(&with(r#", "weather": {"wind": 3}"#)).split(", expected").next(),
            Some("invalid weather: got an unknown field")
        );
        let pipe_bad = r#"{"sections": [{"length": "long", "outer_diameter": 0.1, "inner_diameter": 0}]}"#;
        assert_eq!(message(pipe_bad), r#"invalid sections[0].length: got "long", expected a number"#);
        assert_eq!(
            message(&with(r#", "numerics": {"cells": 2.5}"#)),
            "invalid numerics.cells: got 2.5, expected an integer >= 0"
        );
        assert_eq!(
            message(&with(r#", "bit": {"on_bottom": 1}"#)),
            "invalid bit.on_bottom: got 1, expected true or false"
        );
        assert_eq!(
            message(&with(r#", "nonlinearity": "cubic""#)),
            r#"invalid nonlinearity: got "cubic", expected one of linear, consistent"#
        );
        assert_eq!(
            message(&with(r#", "top_drive": {"controller": {"type": "fuzzy"}}"#)),
            r#"invalid top_drive.controller.type: got "fuzzy", expected one of speed, pi, soft_torque, z_torque"#
        );
        assert_eq!(
            message(&with(r#", "top_drive": {"steps": [[0, 1], [1, 2, 3]]}"#)),
            "invalid top_drive.steps[1]: got [1,2,3], expected [time s, rpm]"
        );
        assert_eq!(
            message(&with(r#", "well": {"md": [0, "x"]}"#)),
            r#"invalid well.md[1]: got "x", expected a number"#
        );
        assert_eq!(
            message(&with(r#", "top_drive": {"rpm": "nan"}"#)),
            "invalid top_drive.rpm: got nan, expected a finite number"
        );
        // a non-finite value where a range is checked: the range, in the words of the check
        assert_eq!(
            message(&with(r#", "bit": {"bha_mass": "nan"}"#)),
            "invalid bit.bha_mass: got nan, expected a finite number >= 0 (kg)"
        );
        assert_eq!(
            message(r#"{"sections": [{"length": 1000, "outer_diameter": "inf", "inner_diameter": 0.1}]}"#),
            "invalid sections[0].outer_diameter: got inf, expected a finite number > 0 m, at most 10 m (in metres: 5 in = 0.127 m)"
        );
        assert_eq!(message(&with(r#", "numerics": 3"#)), "invalid numerics: got 3, expected an object");
        assert_eq!(message("[1]"), "invalid config: got an array, expected a JSON object");
    }

    #[test]
    fn parameters_are_validated_naming_the_field() {
        let message = |json: &str| Parameters::from_json(json).unwrap_err().to_string();
        assert_eq!(Parameters::from_json("{}").unwrap(), Parameters::default());
        assert_eq!(message(r#"{"length": -1}"#), "invalid length: got -1, expected 0 < length < inf");
        assert_eq!(
            message(r#"{"initial_velocities": [0.1, "x"]}"#),
            r#"invalid initial_velocities[1]: got "x", expected a finite real number (rad/s)"#
        );
        assert_eq!(message(r#"{"model": 2}"#), "invalid model: got 2, expected one of 'paper', 'consistent'");
        assert_eq!(
            message(r#"{"model": "exact"}"#),
            r#"invalid model: got "exact", expected one of 'paper', 'consistent'"#
        );
        assert_eq!(
            message(r#"{"colour": 1}"#).split(", expected").next(),
            Some("invalid colour: got an unknown field")
        );
    }
}
