//! Conversions shared by the bindings: core errors to Python exceptions, panics to
//! `RuntimeError`, numpy arrays to vectors, solutions to dicts.

use std::panic::{catch_unwind, AssertUnwindSafe};

use drillstring_core as core;
use drillstring_core::Solution;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Raises `drillstring.errors.ValidationError(field, value, allowed)` for a core input error.
pub(crate) fn validation_error(py: Python<'_>, err: core::Error) -> PyErr {
    let core::Error::InvalidInput { field, value, allowed } = err;
    let raised = py
        .import("drillstring.errors")
        .and_then(|m| m.getattr("ValidationError"))
        .and_then(|cls| cls.call1((field.clone(), value.clone(), allowed.clone())));
    match raised {
        Ok(exc) => PyErr::from_value(exc),
        Err(_) => {
            PyErr::new::<pyo3::exceptions::PyValueError, _>(format!("invalid {field}: got {value}, expected {allowed}"))
        }
    }
}

/// Runs `f`, turning a Rust panic into a Python `RuntimeError` instead of aborting.
pub(crate) fn no_panic<T>(f: impl FnOnce() -> T) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        PyRuntimeError::new_err(format!("internal error in drillstring._core: {what}"))
    })
}

pub(crate) fn to_vec(a: &PyReadonlyArray1<'_, f64>) -> Vec<f64> {
    a.as_array().iter().copied().collect()
}

/// The dict every solve returns: `t` (samples,), `y` (samples, dim), `status`, `message`,
/// `nfev`, `naccept`, `nreject`.
pub(crate) fn solution_dict<'py>(py: Python<'py>, sol: Solution) -> PyResult<Bound<'py, PyDict>> {
    let samples = sol.len();
    let dim = sol.dim;
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, sol.t))?;
    out.set_item("y", PyArray1::from_vec(py, sol.y).reshape([samples, dim])?)?;
    out.set_item("status", sol.status.name())?;
    out.set_item("message", sol.message)?;
    out.set_item("nfev", sol.stats.nfev)?;
    out.set_item("naccept", sol.stats.naccept)?;
    out.set_item("nreject", sol.stats.nreject)?;
    Ok(out)
}
