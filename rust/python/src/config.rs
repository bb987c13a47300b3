//! Bindings of the configuration schemas of the core: the drilling configuration's dotted-path
//! overrides (`drillstring_core::drilling::config`), the paper model's parameters and the lumped
//! model's parameters. JSON in, normalised JSON out; errors are `ValidationError`s naming the
//! dotted field.

use drillstring_core::drilling::config::{override_json, override_value};
use drillstring_core::model::Parameters;
use pyo3::prelude::*;

use crate::convert::validation_error;

/// The configuration `config_json` with `overrides_json` (a JSON list of `[dotted path, value]`
/// pairs: `sections[1].length`, `top_drive.controller`, ...) set in order, parsed and, with
/// `validate`, validated: the normalised configuration as JSON. One inclination number without
/// a `well.md` override drops the survey depths. `field` names a malformed path or list.
/// Without `parse`, the configuration with the values set, as JSON (only the paths checked).
#[pyfunction]
#[pyo3(signature = (config_json, overrides_json, field="overrides", validate=true, parse=true))]
pub(crate) fn drill_config_override(
    py: Python<'_>,
    config_json: &str,
    overrides_json: &str,
    field: &str,
    validate: bool,
    parse: bool,
) -> PyResult<String> {
    let err = |e| validation_error(py, e);
    if !parse {
        return Ok(override_value(config_json, overrides_json, field).map_err(err)?.to_string());
    }
    Ok(override_json(config_json, overrides_json, field, validate).map_err(err)?.to_json())
}

/// The paper model's default parameters as JSON (Table 1 of the paper, aluminium reference).
#[pyfunction]
pub(crate) fn parameters_defaults() -> String {
    Parameters::default().to_json()
}

/// The paper model's parameters `params_json` (a JSON object of some fields) validated, every
/// default filled in, as JSON; raises `ValidationError` naming the field of the first invalid
/// value (`initial_velocities[2]`).
#[pyfunction]
pub(crate) fn parameters_validate(py: Python<'_>, params_json: &str) -> PyResult<String> {
    let p = Parameters::from_json(params_json).map_err(|e| validation_error(py, e))?;
    Ok(p.to_json())
}
