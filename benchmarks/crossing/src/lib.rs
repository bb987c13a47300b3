//! The crossing of one drilling run's result to Python by the bindings' serializer
//! (`rust/python/src/convert.rs`, `to_python`: numeric sequences as numpy arrays) against
//! pythonize (lists), on the same `DrillRun`: `benchmarks/crossing_time.py` times both.
#![allow(dead_code, unused_imports, unused_macros)]
#[path = "../../../rust/python/src/convert.rs"]
mod convert;

use std::sync::Mutex;
use drillstring_core::drilling::{self, DrillConfig, DrillRun};
use drillstring_core::metrics::StickSlip;
use drillstring_core::outputs::{MetricsView, Report, RunValues};
use pyo3::prelude::*;
use serde::Serialize;

/// The run both serializers cross (`solve` sets it).
static RUN: Mutex<Option<DrillRun>> = Mutex::new(None);

#[derive(Serialize)]
struct RunOutput<'a> {
    #[serde(flatten)]
    run: &'a DrillRun,
    metrics: MetricsView<'a>,
}

fn with_output<R>(f: impl FnOnce(&RunOutput) -> R) -> R {
    let guard = RUN.lock().unwrap();
    let run = guard.as_ref().unwrap();
    let values = RunValues {
        metrics: run.metrics.as_ref().unwrap_or(&StickSlip::UNDEFINED),
        window: run.window,
        breakoff_torque: run.breakoff_torque,
        min_cycle_torque: run.min_cycle_torque,
    };
    let metrics = MetricsView { run: values, report: Report::Drilling, warnings: run.metric_warnings() };
    f(&RunOutput { run, metrics })
}

#[pyfunction]
fn solve(config_json: &str) -> PyResult<usize> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    let run = drilling::solve(&cfg, &drillstring_core::interrupt::Never, &mut |_| {}).unwrap();
    let n = run.t.len();
    *RUN.lock().unwrap() = Some(run);
    Ok(n)
}

#[pyfunction]
fn cross_today(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    with_output(|o| convert::to_python(py, o))
}

#[pyfunction]
fn cross_pythonize(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    with_output(|o| pythonize::pythonize(py, o).map_err(PyErr::from))
}

#[pymodule]
fn result_crossing(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(cross_today, m)?)?;
    m.add_function(wrap_pyfunction!(cross_pythonize, m)?)?;
    Ok(())
}
