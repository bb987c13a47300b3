//! Bindings of the stick-slip maps (`drillstring_core::drilling::map`): a base configuration
//! and per-run overrides as JSON in, columns of one row per run out.

use drillstring_core::drilling::map::{self, MapRow};
use drillstring_core::metrics::StickSlip;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{no_panic, validation_error, SignalCheck};

/// Solves a map: `config_json` (a configuration) with each run's overrides
/// (`runs_json`: a list of runs, each a list of `[dotted path, value]` pairs; `null` unsets a
/// field) on `threads` threads. Returns columns (one entry per run, in order): `status`,
/// `message` (lists of str), `metrics` (dict of arrays under the names of `drill_solve`'s
/// metrics), `stats` (dict of arrays: cells, steps, dt, balance_error) and `interrupt`: the
/// exception that stopped the map (Ctrl-C, or raised by `progress`), or None; the caller raises
/// it once it has kept the finished rows. `progress(finished_runs)` is called about every 20 ms.
#[pyfunction]
#[pyo3(signature = (config_json, runs_json, threads=None, memory_budget=None, progress=None))]
pub(crate) fn drill_map<'py>(
    py: Python<'py>,
    config_json: &str,
    runs_json: &str,
    threads: Option<usize>,
    memory_budget: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let runs = map::parse_runs(runs_json).map_err(|e| validation_error(py, e))?;
    let signals = SignalCheck::with_progress(py, progress);
    let solved = py
        .detach(|| no_panic(|| map::solve_map(config_json, &runs, threads, memory_budget, &signals, &mut |_, _| {})))?;
    let interrupt = signals.finish().err().map(|e| e.into_value(py));
    let rows = solved.map_err(|e| validation_error(py, e))?;
    columns(py, &rows, interrupt)
}

fn columns<'py>(
    py: Python<'py>,
    rows: &[MapRow],
    interrupt: Option<Py<pyo3::exceptions::PyBaseException>>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("status", rows.iter().map(|r| r.status.name()).collect::<Vec<_>>())?;
    d.set_item("message", rows.iter().map(|r| r.message.as_str()).collect::<Vec<_>>())?;
    let metric = |f: fn(&StickSlip) -> f64| -> Vec<f64> {
        rows.iter().map(|r| r.metrics.as_ref().map_or(f64::NAN, f)).collect()
    };
    let row = |f: fn(&MapRow) -> f64| -> Vec<f64> { rows.iter().map(f).collect() };
    let m = PyDict::new(py);
    m.set_item("t_start", PyArray1::from_vec(py, metric(|s| s.t_start)))?;
    m.set_item("t_end", PyArray1::from_vec(py, metric(|s| s.t_end)))?;
    m.set_item("window_start", PyArray1::from_vec(py, row(|r| r.window[0])))?;
    m.set_item("window_end", PyArray1::from_vec(py, row(|r| r.window[1])))?;
    m.set_item("severity", PyArray1::from_vec(py, metric(|s| s.severity)))?;
    m.set_item("stuck_fraction", PyArray1::from_vec(py, metric(|s| s.stuck_fraction)))?;
    m.set_item("rpm_min", PyArray1::from_vec(py, metric(|s| s.rpm_min)))?;
    m.set_item("rpm_max", PyArray1::from_vec(py, metric(|s| s.rpm_max)))?;
    m.set_item("rpm_mean", PyArray1::from_vec(py, metric(|s| s.rpm_mean)))?;
    m.set_item("torque_min", PyArray1::from_vec(py, metric(|s| s.torque_min)))?;
    m.set_item("torque_max", PyArray1::from_vec(py, metric(|s| s.torque_max)))?;
    m.set_item("cycle_period", PyArray1::from_vec(py, metric(|s| s.cycle_period)))?;
    m.set_item("period_cycles", PyArray1::from_vec(py, metric(|s| s.period_cycles)))?;
    m.set_item("periodicity", PyArray1::from_vec(py, metric(|s| s.periodicity)))?;
    m.set_item("slip_period", PyArray1::from_vec(py, metric(|s| s.slip_period)))?;
    // the verdicts as 1 / 0 (NaN without metrics), like every other column of a map
    m.set_item("stick_slip", PyArray1::from_vec(py, metric(|s| f64::from(u8::from(s.stick_slip)))))?;
    m.set_item("settled", PyArray1::from_vec(py, metric(|s| f64::from(u8::from(s.settled)))))?;
    m.set_item("breakoff_torque", PyArray1::from_vec(py, row(|r| r.breakoff_torque)))?;
    m.set_item("min_cycle_torque", PyArray1::from_vec(py, row(|r| r.min_cycle_torque)))?;
    d.set_item("metrics", m)?;
    let st = PyDict::new(py);
    st.set_item("cells", PyArray1::from_vec(py, rows.iter().map(|r| r.stats.cells as u64).collect::<Vec<_>>()))?;
    st.set_item("steps", PyArray1::from_vec(py, rows.iter().map(|r| r.stats.steps).collect::<Vec<_>>()))?;
    st.set_item("dt", PyArray1::from_vec(py, row(|r| r.stats.dt)))?;
    st.set_item("balance_error", PyArray1::from_vec(py, row(|r| r.balance_error)))?;
    st.set_item("courant_peak", PyArray1::from_vec(py, row(|r| r.stats.courant_peak)))?;
    d.set_item("stats", st)?;
    d.set_item("interrupt", interrupt)?;
    Ok(d)
}
