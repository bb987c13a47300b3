//! Dotted-path overrides of a JSON configuration (`set_path`, `apply_overrides`): Python's
//! `with_overrides`, the command line's `--set` and the axes of a map.

use serde_json::Value;

use crate::error::{Error, Result};
use crate::schema::{join, shown};

use super::parse::{bit_size_override, constant_inclination};
use super::DrillConfig;

/// its JSON value.
pub type Override = (String, Value);

/// The tokens of a dotted path with indices: `sections[1].length` -> `sections`, `1`, `length`.
enum Token<'a> {
    Key(&'a str),
    Index(usize),
}

fn tokens(path: &str) -> Option<Vec<Token<'_>>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (name, mut rest) = part.split_once('[').map_or((part, ""), |(n, r)| (n, r));
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return None;
        }
        out.push(Token::Key(name));
        while !rest.is_empty() {
            let (index, after) = rest.split_once(']')?;
            out.push(Token::Index(index.parse().ok()?));
            rest = match after.strip_prefix('[') {
                Some(r) => r,
                None if after.is_empty() => "",
                None => return None,
            };
        }
    }
    Some(out)
}

/// The form of an override's path, as errors state it.
pub const PATH_FORM: &str = "a dotted key with indices of the configuration (top_drive.rpm, sections[0].length)";

/// Sets `path` to `value` in the JSON configuration `config`: a table given for a table is
/// merged into it (its other keys kept), `null` sets null (an optional field's None; a
/// required number refuses it when parsed). The path goes through the tables and lists of
/// `config`; a key missing from a table is added (the parse names an unknown one and lists the
/// allowed keys). `field` names a malformed path in the error (`--set`, `axis`).
pub fn set_path(config: &mut Value, path: &str, value: &Value, field: &str) -> Result<()> {
    let toks = tokens(path).ok_or_else(|| Error::invalid(field, path, PATH_FORM))?;
    let mut node = config;
    let mut at = String::new();
    for (i, tok) in toks.iter().enumerate() {
        let last = i + 1 == toks.len();
        match tok {
            Token::Key(name) => {
                let here = join(&at, name);
                let map = match node {
                    Value::Object(map) => map,
                    Value::Array(items) => {
                        let allowed = format!("an index first: {at} is a list of {} ({at}[0].{name})", items.len());
                        return Err(Error::invalid(here, shown(value), allowed));
                    }
                    other => {
                        let allowed = format!("a key of a table: {at} is {}, not a table", shown(other));
                        return Err(Error::invalid(here, shown(value), allowed));
                    }
                };
                at = here;
                if last {
                    match (map.get_mut(*name), value) {
                        (Some(Value::Object(old)), Value::Object(new)) => {
                            old.extend(new.iter().map(|(k, v)| (k.clone(), v.clone())))
                        }
                        _ => {
                            map.insert((*name).to_string(), value.clone());
                        }
                    }
                    if path == "top_drive.controller.preset" && !value.is_null() {
                        // a preset set now replaces the controller's keys (set again after it to override)
                        for k in crate::drilling::tuning::PRESET_KEYS {
                            map.remove(k);
                        }
                    }
                    return Ok(());
                }
                node = map.entry((*name).to_string()).or_insert_with(|| Value::Object(Default::default()));
            }
            Token::Index(k) => {
                let here = format!("{at}[{k}]");
                let Value::Array(items) = node else {
                    let allowed = format!("a key without an index: {at} is not a list");
                    return Err(Error::invalid(here, shown(value), allowed));
                };
                let len = items.len();
                let Some(item) = items.get_mut(*k) else {
                    let allowed = match len {
                        0 => format!("no index: {at} is empty"),
                        n => format!("an index 0..{} of {at}", n - 1),
                    };
                    return Err(Error::invalid(here, shown(value), allowed));
                };
                at = here;
                if last {
                    *item = value.clone();
                    return Ok(());
                }
                node = item;
            }
        }
    }
    Ok(())
}

/// Sets `overrides` in order in the JSON configuration `config` ([`set_path`]); one number for
/// `well.inclination_deg` without a `well.md` override drops the survey depths (the
/// constant-inclination rule of [`DrillConfig::from_json`]); a `bit.radius` override replaces a
/// `bit.diameter` and the reverse. `field` names a malformed path.
pub fn apply_overrides(config: &mut Value, overrides: &[Override], field: &str) -> Result<()> {
    for (path, v) in overrides {
        set_path(config, path, v, field)?;
    }
    bit_size_override(config, overrides);
    if overrides.iter().any(|(p, _)| p == "well.inclination_deg") {
        let md_given = overrides.iter().any(|(p, _)| p == "well.md");
        if let Some(Value::Object(well)) = config.get_mut("well") {
            constant_inclination(well, md_given);
        }
    }
    Ok(())
}

/// Overrides from JSON `[[path, value], ...]` (`items`, the parsed list); errors name `field`.
pub(crate) fn override_pairs(items: Vec<Value>, field: &str, form: &str) -> Result<Vec<Override>> {
    items
        .into_iter()
        .map(|pair| match pair {
            Value::Array(mut kv) if kv.len() == 2 && kv[0].is_string() => {
                let v = kv.pop().unwrap_or(Value::Null);
                let k = kv.pop().and_then(|k| k.as_str().map(str::to_string)).unwrap_or_default();
                Ok((k, v))
            }
            other => Err(Error::invalid(field, shown(&other), form)),
        })
        .collect()
}

/// The JSON configuration `config_json` with `overrides_json` (a JSON list of
/// `[dotted path, value]` pairs) set ([`apply_overrides`]), not parsed: errors name a path that
/// does not go through the configuration's tables and lists; `field` names a malformed path or
/// list.
pub fn override_value(config_json: &str, overrides_json: &str, field: &str) -> Result<Value> {
    let mut config: Value = serde_json::from_str(config_json)
        .map_err(|e| Error::invalid("config", format!("text that is not JSON ({e})"), "a JSON object"))?;
    let form = "a list of [dotted path, value] pairs";
    let items: Value = serde_json::from_str(overrides_json)
        .map_err(|e| Error::invalid(field, format!("text that is not JSON ({e})"), form))?;
    let Value::Array(items) = items else { return Err(Error::invalid(field, shown(&items), form)) };
    apply_overrides(&mut config, &override_pairs(items, field, form)?, field)?;
    Ok(config)
}

/// [`override_value`] parsed and, when `validate`, validated: the configuration (every default
/// filled in). Errors name the dotted field.
pub fn override_json(config_json: &str, overrides_json: &str, field: &str, validate: bool) -> Result<DrillConfig> {
    let cfg = DrillConfig::from_value(override_value(config_json, overrides_json, field)?)?;
    if validate {
        cfg.validate()?;
    }
    Ok(cfg)
}
