//! Bindings of the defaults and limits of a solve (`drillstring_core::options`,
//! `drillstring_core::model::default_section`).

use drillstring_core::{model, options};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

use crate::convert::{no_panic, to_vec};

/// The number of steps of a fixed-step method over `span` with the step `dt`.
#[pyfunction]
pub(crate) fn fixed_steps(span: f64, dt: f64) -> u64 {
    options::fixed_steps(span, dt)
}

/// `(index, rate in rad/s)` of the fastest linear mode `max sqrt(|K_i / M_i|)`; None without modes.
#[pyfunction]
pub(crate) fn fastest_mode(
    mass: PyReadonlyArray1<'_, f64>,
    stiffness: PyReadonlyArray1<'_, f64>,
) -> PyResult<Option<(usize, f64)>> {
    let (m, k) = (to_vec(&mass), to_vec(&stiffness));
    no_panic(|| options::fastest_mode(&m, &k))
}

/// The default step of the fixed-step methods on a modal system, s.
#[pyfunction]
pub(crate) fn default_fixed_dt(mass: PyReadonlyArray1<'_, f64>, stiffness: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
    let (m, k) = (to_vec(&mass), to_vec(&stiffness));
    no_panic(|| options::default_fixed_dt(&m, &k))
}

/// The section the paper reports, `z_k = 2 l / 3` (m).
#[pyfunction]
pub(crate) fn default_section(length: f64) -> f64 {
    model::default_section(length)
}
