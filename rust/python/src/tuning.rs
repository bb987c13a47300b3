//! Bindings of the controller tuning (`drillstring_core::drilling::tuning`): the recommended
//! settings of every controller preset for a configuration's string.

use drillstring_core::drilling::{tuning, DrillConfig};
use pyo3::prelude::*;

use crate::convert::{to_python, validation_error};

/// The recommended controller settings of every preset (`stiff`, `soft_torque`, `z_torque`)
/// for the configuration `config_json`, with the string's numbers they were computed from;
/// see `_core.pyi` for the keys. Raises `ValidationError` for an invalid configuration.
#[pyfunction]
pub(crate) fn recommend_controllers<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
    let rec = tuning::recommend(&cfg).map_err(|e| validation_error(py, e))?;
    to_python(py, &rec)
}
