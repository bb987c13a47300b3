//! Bindings of the stick-slip maps (`drillstring_core::drilling::map`): a base configuration
//! and per-run overrides as JSON in, columns of one row per run out.

use drillstring_core::drilling::map;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{no_panic, to_dict, validation_error, SignalCheck};

/// The coupled regime's constants: `COUPLED_REGIME_CRITERION` (how a run's regime is decided)
/// and `COUPLED_REGIMES` (their names, in a map legend's order).
pub(crate) fn add_constants(m: &Bound<'_, PyModule>) -> PyResult<()> {
    use drillstring_core::drilling::axial::regime::{Regime, REGIME_CRITERION};
    m.add("COUPLED_REGIME_CRITERION", REGIME_CRITERION)?;
    m.add("COUPLED_REGIMES", Regime::ALL.map(Regime::name).to_vec())?;
    Ok(())
}

/// Solves a map: `config_json` (a configuration) with each run's overrides
/// (`runs_json`: a list of runs, each a list of `[dotted path, value]` pairs; `null` unsets a
/// field) on `threads` threads. Returns columns (one entry per run, in order): `status`,
/// `message` (lists of str), `metrics` (dict of arrays under the names of `drill_solve`'s
/// metrics), `stats` (dict of arrays: cells, steps, dt, balance_error), `coupled` (dict of
/// arrays under the names of a coupled run's metrics, NaN without them; `regime` a list of str)
/// and `interrupt`: the
/// exception that stopped the map (Ctrl-C, or raised by `progress`), or None; the caller raises
/// it once it has kept the finished rows. `progress(finished_runs)` is called about every 20 ms.
/// An axis without effect in every run refuses the map (ValidationError naming it), unless
/// `check_axes` is false (a part of a map checked whole by `drill_map_check_axes`).
#[pyfunction]
#[pyo3(signature = (config_json, runs_json, threads=None, memory_budget=None, progress=None, check_axes=true))]
pub(crate) fn drill_map<'py>(
    py: Python<'py>,
    config_json: &str,
    runs_json: &str,
    threads: Option<usize>,
    memory_budget: Option<u64>,
    progress: Option<Py<PyAny>>,
    check_axes: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let runs = map::parse_runs(runs_json).map_err(|e| validation_error(py, e))?;
    let signals = SignalCheck::with_progress(py, progress);
    let solved = py.detach(|| {
        no_panic(|| {
            map::solve_map_part(config_json, &runs, check_axes, threads, memory_budget, &signals, &mut |_, _| {})
        })
    })?;
    let interrupt = signals.finish().err().map(|e| e.into_value(py));
    let rows = solved.map_err(|e| validation_error(py, e))?;
    let d = to_dict(py, &map::MapColumns::new(&rows))?;
    d.set_item("interrupt", interrupt)?;
    Ok(d)
}

/// Refuses a map (`config_json` with the runs `runs_json`, as `drill_map`) with an axis that
/// changes nothing in any run: ValidationError naming the key and why
/// (`drilling::map::check_axes`).
#[pyfunction]
pub(crate) fn drill_map_check_axes(py: Python<'_>, config_json: &str, runs_json: &str) -> PyResult<()> {
    let runs = map::parse_runs(runs_json).map_err(|e| validation_error(py, e))?;
    let base = map::map_base(config_json).map_err(|e| validation_error(py, e))?;
    map::check_axes(&base, &runs).map_err(|e| validation_error(py, e))
}
