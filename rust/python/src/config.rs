//! Bindings of the configuration schemas of the core: the drilling configuration's dotted-path
//! overrides (`drillstring_core::drilling::config`), the paper model's parameters and the lumped
//! model's parameters. JSON in, the normalised configuration out as a dict of JSON values; errors are `ValidationError`s naming the
//! dotted field.

use drillstring_core::drilling::config::{override_json, override_value};
use drillstring_core::drilling::schema_doc::config_schema;
use drillstring_core::model::Parameters;
use pyo3::prelude::*;

use crate::convert::{to_json_object, validation_error};

/// The configuration `config_json` with `overrides_json` (a JSON list of `[dotted path, value]`
/// pairs: `sections[1].length`, `top_drive.controller`, ...) set in order, parsed and, with
/// `validate`, validated: the normalised configuration as a dict of JSON values. One inclination
/// number without a `well.md` override drops the survey depths. `field` names a malformed path
/// or list. Without `parse`, the configuration with the values set (only the paths checked).
#[pyfunction]
#[pyo3(signature = (config_json, overrides_json, field="overrides", validate=true, parse=true))]
pub(crate) fn drill_config_override<'py>(
    py: Python<'py>,
    config_json: &str,
    overrides_json: &str,
    field: &str,
    validate: bool,
    parse: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let err = |e| validation_error(py, e);
    if !parse {
        return to_json_object(py, &override_value(config_json, overrides_json, field).map_err(err)?);
    }
    to_json_object(py, &override_json(config_json, overrides_json, field, validate).map_err(err)?)
}

/// The reference of the drilling configuration: a dict keyed by dotted path
/// (`sections[].outer_diameter`, `top_drive.controller.kp`), each entry a dict with exactly
/// `type`, `unit` (SI, as pint parses it; None for what is not a number), `label`, `default` and
/// `description` (`drillstring_core::drilling::schema_doc`).
#[pyfunction]
pub(crate) fn drill_config_schema(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_json_object(py, &config_schema())
}

/// The paper model's default parameters as a dict (Table 1 of the paper, aluminium reference).
#[pyfunction]
pub(crate) fn parameters_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_json_object(py, &Parameters::default())
}

/// The paper model's parameters `params_json` (a JSON object of some fields) validated, every
/// default filled in, as a dict; raises `ValidationError` naming the field of the first invalid
/// value (`initial_velocities[2]`).
#[pyfunction]
pub(crate) fn parameters_validate<'py>(py: Python<'py>, params_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let p = Parameters::from_json(params_json).map_err(|e| validation_error(py, e))?;
    to_json_object(py, &p)
}
