//! The reference of the drilling configuration: one entry per key (`sections[].outer_diameter`,
//! `top_drive.controller.kp`, `bit.weight_on_bit`), with its type, SI unit, axis label, default
//! and description, for the documentation, the axes of figures and the unit conversion at the
//! Python edge.
//!
//! Nothing here is written twice: the keys, types and defaults come from the configuration
//! structs of [`super::config`] (their JSON Schema, derived by `schemars` from the serde
//! attributes and the `Default` impls), the description of a key is the first paragraph of its
//! field's doc comment (or of its type's), the unit and label are the field's
//! `#[schemars(extend("unit" = ..., "label" = ...))]`. Units are written as pint parses them
//! (`m`, `N*m*s/rad`, `deg/(30 m)`, `""` for a dimensionless number); a list of `[a, b]` pairs
//! (`top_drive.steps`) gives its entries' units and labels as `item_units`, `item_labels`,
//! reported as the keys `top_drive.steps[][0]` and `top_drive.steps[][1]`.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{Map, Value};

use super::config::{DrillConfig, REQUIRED_SECTION, REQUIRED_TOP};

/// One key of the configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeyDoc {
    /// `number`, `integer`, `string`, `boolean`, `array` or `table`.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// The SI unit as pint parses it (`""`: dimensionless); None for what is not a number or a
    /// list of numbers of one unit.
    pub unit: Option<String>,
    /// A short name of the quantity, for axes (`weight on bit`).
    pub label: String,
    /// The default as JSON; null when the key is required, computed (see the description) or a
    /// table (its keys have theirs).
    pub default: Value,
    /// What the key means, its allowed range in words and what null means.
    pub description: String,
}

/// Every key of the drilling configuration, by dotted path (`[]` for any index of a list),
/// sorted by path.
pub fn config_schema() -> BTreeMap<String, KeyDoc> {
    let root = serde_json::to_value(schemars::schema_for!(DrillConfig)).unwrap_or(Value::Null);
    let defs = root.get("$defs").and_then(Value::as_object).cloned().unwrap_or_default();
    let mut out = BTreeMap::new();
    children(&resolve(&root, &defs), &defs, "", &mut out);
    out
}

/// The schema `node` with its `$ref` and its one non-null alternative (an `Option` of a type)
/// resolved: the definition's keys with the node's own (doc comment, unit, label, default) on
/// top.
fn resolve(node: &Value, defs: &Map<String, Value>) -> Map<String, Value> {
    let mut out = Map::new();
    let reference = node.get("$ref").and_then(Value::as_str).and_then(|r| r.strip_prefix("#/$defs/"));
    if let Some(def) = reference.and_then(|name| defs.get(name)) {
        out = resolve(def, defs);
    }
    if node.get("type").is_none() {
        let mut any = node.get("anyOf").and_then(Value::as_array).into_iter().flatten();
        if let Some(first) = any.find(|a| a.get("type") != Some(&Value::from("null"))) {
            out.extend(resolve(first, defs));
        }
    }
    if let Value::Object(own) = node {
        out.extend(own.iter().filter(|(k, _)| *k != "$ref" && *k != "anyOf").map(|(k, v)| (k.clone(), v.clone())));
    }
    out
}

/// The names of a string enum (`oneOf` of `const`s and `enum`s, or one `enum`).
fn names(node: &Map<String, Value>) -> Vec<String> {
    let one = |v: &Value| -> Vec<String> {
        let listed = v.get("enum").and_then(Value::as_array).into_iter().flatten();
        listed.chain(v.get("const")).filter_map(|x| x.as_str().map(str::to_string)).collect()
    };
    match node.get("oneOf").and_then(Value::as_array) {
        Some(alternatives) => alternatives.iter().flat_map(one).collect(),
        None => one(&Value::Object(node.clone())),
    }
}

/// The configuration's word for the JSON Schema type of `node`.
fn kind(node: &Map<String, Value>) -> &'static str {
    let ty = match node.get("type") {
        Some(Value::String(t)) => t.as_str(),
        Some(Value::Array(types)) => types.iter().filter_map(Value::as_str).find(|t| *t != "null").unwrap_or("null"),
        _ if !names(node).is_empty() => "string",
        _ => "null",
    };
    match ty {
        "object" => "table",
        "number" => "number",
        "integer" => "integer",
        "boolean" => "boolean",
        "array" => "array",
        _ => "string",
    }
}

/// The first paragraph of a doc comment as one line, intra-doc links as code.
fn first_paragraph(doc: &str) -> String {
    let paragraph = doc.split("\n\n").next().unwrap_or("");
    paragraph.split_whitespace().collect::<Vec<_>>().join(" ").replace("[`", "`").replace("`]", "`")
}

fn text(node: &Map<String, Value>, key: &str) -> Option<String> {
    node.get(key).and_then(Value::as_str).map(str::to_string)
}

/// The entry of the key `path` (schema `node`) and of the keys below it.
fn entry(node: &Map<String, Value>, defs: &Map<String, Value>, path: String, required: bool, out: &mut Schema) {
    let kind = kind(node);
    let mut description = first_paragraph(&text(node, "description").unwrap_or_default());
    let choices = names(node);
    if !choices.is_empty() {
        description = format!("{description} One of: {}.", choices.join(", ")).trim_start().to_string();
    }
    let default = match node.get("default") {
        Some(v) if !required && kind != "table" => v.clone(),
        _ => Value::Null,
    };
    let label = text(node, "label").unwrap_or_default();
    out.insert(path.clone(), KeyDoc { kind, unit: text(node, "unit"), label: label.clone(), default, description });
    match kind {
        "table" => children(node, defs, &path, out),
        "array" => {
            let items = resolve(node.get("items").unwrap_or(&Value::Null), defs);
            match self::kind(&items) {
                "table" => children(&items, defs, &format!("{path}[]"), out),
                "array" => {
                    let list = |key: &str| node.get(key).and_then(Value::as_array).cloned().unwrap_or_default();
                    for (i, (unit, label)) in list("item_units").iter().zip(list("item_labels")).enumerate() {
                        let label = label.as_str().unwrap_or_default().to_string();
                        let description = format!("Entry {i} of each pair of `{path}`: the {label}.");
                        let unit = unit.as_str().map(str::to_string);
                        let doc = KeyDoc { kind: "number", unit, label, default: Value::Null, description };
                        out.insert(format!("{path}[][{i}]"), doc);
                    }
                }
                _ => {}
            }
        }
        _ => {}
    }
}

type Schema = BTreeMap<String, KeyDoc>;

/// The entries of the keys of the table `node` at `path`.
fn children(node: &Map<String, Value>, defs: &Map<String, Value>, path: &str, out: &mut Schema) {
    let Some(Value::Object(properties)) = node.get("properties") else { return };
    for (key, child) in properties {
        let required = (path.is_empty() && REQUIRED_TOP.contains(&key.as_str()))
            || (path == "sections[]" && REQUIRED_SECTION.contains(&key.as_str()));
        let full = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
        entry(&resolve(child, defs), defs, full, required, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::config::FrictionInterval;
    use crate::well::plan::SegmentSpec;

    /// The dotted keys of a configuration's JSON: tables and their keys, `[]` for a list's items
    /// (the first item's keys), `[][i]` for the entries of a list of pairs.
    fn keys(value: &Value, path: &str, out: &mut Vec<String>) {
        match value {
            Value::Object(map) => {
                for (k, v) in map {
                    let full = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                    out.push(full.clone());
                    keys(v, &full, out);
                }
            }
            Value::Array(items) => match items.first() {
                Some(Value::Object(_)) => keys(&items[0], &format!("{path}[]"), out),
                Some(Value::Array(pair)) => out.extend((0..pair.len()).map(|i| format!("{path}[][{i}]"))),
                _ => {}
            },
            _ => {}
        }
    }

    /// The default configuration with one item in each list that is empty by default.
    fn every_key() -> Value {
        let mut cfg = DrillConfig::default();
        cfg.well.plan = Some(vec![SegmentSpec {
            hold: Some(1.0),
            build: Some(1.0),
            drop: Some(1.0),
            turn: Some(1.0),
            inclination: Some(1.0),
            azimuth: Some(1.0),
        }]);
        cfg.well.survey = Some("survey.csv".into());
        cfg.friction.intervals = vec![FrictionInterval { top_md: 0.0, bottom_md: 1.0, static_coefficient: 0.2 }];
        cfg.well.hole_sections =
            vec![super::super::pipe::HoleSection { bottom_md: 1.0, diameter: 0.3, friction: Some(0.2) }];
        cfg.top_drive.steps = vec![[10.0, 60.0]];
        cfg.top_drive.speed_series = vec![[0.0, 0.0]];
        cfg.hoist = Some(super::super::config::Hoist { steps: vec![[10.0, 0.01]], ..Default::default() });
        cfg.changes = vec![super::super::config::Change {
            time: 10.0,
            key: "top_drive.rpm".into(),
            value: serde_json::json!(60.0),
        }];
        serde_json::to_value(&cfg).unwrap()
    }

    #[test]
    fn the_schema_has_every_key_of_the_configuration_and_no_other() {
        let mut accepted = Vec::new();
        keys(&every_key(), "", &mut accepted);
        accepted.sort();
        let schema: Vec<String> = config_schema().into_keys().collect();
        assert_eq!(schema, accepted);
        for key in ["sections[].outer_diameter", "top_drive.controller.kp", "bit.diameter", "well.plan[].build"] {
            assert!(schema.contains(&key.to_string()), "{key}");
        }
    }

    #[test]
    fn every_entry_has_its_type_unit_label_and_description() {
        // the units a pint registry parses, as the Python edge converts to them
        let si: Vec<&str> =
            "|m|m^2|m^4|m^6|Pa|kg|kg/m^3|m/s|m/s^2|deg|deg/(30 m)|rad/s|s/rad|rpm|s|1/s|Hz|N|N/m|N*m|kg*m^2|N*m*s/rad|N*m/rad"
                .split('|')
                .collect();
        let schema = config_schema();
        let numeric_list = ["well.md", "well.inclination_deg", "well.azimuth_deg", "metrics.window"];
        for (key, doc) in &schema {
            assert!(!doc.label.is_empty(), "{key} has no label");
            assert!(doc.description.len() > 10 && doc.description.ends_with('.'), "{key}: {:?}", doc.description);
            match doc.kind {
                "number" | "integer" => {
                    let unit = doc.unit.as_deref().unwrap_or_else(|| panic!("{key} has no unit"));
                    // the autodriller's setpoint and gains, the hoist's step values: one unit per
                    // target, "N or m/s"
                    let gains = ["m/(N*s)", "m/(N*s^2)", "1"];
                    assert!(
                        unit.split(" or ").all(|u| si.contains(&u) || (unit.contains(" or ") && gains.contains(&u))),
                        "{key}: {unit}"
                    );
                }
                "array" if numeric_list.contains(&key.as_str()) || key == "torque_drag.friction_factors" => {
                    assert!(doc.unit.as_deref().is_some_and(|u| si.contains(&u)), "{key}")
                }
                _ => assert_eq!(doc.unit, None, "{key}"),
            }
        }
        let doc = |k: &str| schema[k].clone();
        assert_eq!((doc("bit.weight_on_bit").kind, doc("bit.weight_on_bit").unit.as_deref()), ("number", Some("N")));
        assert_eq!(doc("bit.weight_on_bit").label, "weight on bit");
        assert_eq!(doc("numerics.cells").kind, "integer");
        assert_eq!(doc("top_drive.controller").kind, "table");
        assert_eq!(doc("top_drive.steps[][1]").unit.as_deref(), Some("rpm"));
        assert_eq!(doc("top_drive.controller.kp").unit.as_deref(), Some("N*m*s/rad"));
        assert_eq!(doc("well.plan[].turn").unit.as_deref(), Some("deg/(30 m)"));
        assert!(doc("top_drive.controller.type").description.ends_with("One of: speed, pi, soft_torque, z_torque."));
        assert_eq!(doc("sections").kind, "array");
        assert_eq!(doc("friction.static").unit.as_deref(), Some(""));
    }

    #[test]
    fn defaults_are_the_default_configuration_s_and_null_when_required() {
        let schema = config_schema();
        let d = DrillConfig::default();
        assert_eq!(schema["top_drive.rpm"].default, Value::from(d.top_drive.rpm));
        assert_eq!(schema["numerics.cells"].default, Value::from(d.numerics.cells));
        assert_eq!(schema["friction.model"].default, Value::from("set_valued"));
        assert_eq!(schema["torque_drag.friction_factors"].default, serde_json::json!([0.1, 0.2, 0.3, 0.4]));
        assert_eq!(schema["sections[].shear_modulus"].default, Value::from(79.3e9));
        for required in ["sections", "sections[].length", "sections[].outer_diameter", "sections[].inner_diameter"] {
            assert_eq!(schema[required].default, Value::Null, "{required}");
        }
        assert_eq!(schema["bit.diameter"].default, Value::Null);
        assert_eq!(schema["top_drive"].default, Value::Null);
        let kp = &schema["top_drive.controller.kp"].description;
        assert_eq!(
            kp,
            "`pi`: the proportional gain, >= 0: the motor torque per rad/s of speed error, i.e. the \
             damping the top drive presents to the string."
        );
    }
}
