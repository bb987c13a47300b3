//! Bindings of the lumped two-inertia model (`drillstring_core::drilling::lumped`) and of the
//! minimum cycle torque implied by break-off: JSON parameters in, dicts out (by [`to_python`]).

use drillstring_core::drilling::{self, lumped};
use pyo3::prelude::*;
use serde::Serialize;

use crate::convert::stick_slip_report;
use crate::convert::{no_panic, to_json_object, to_python, validation_error, SignalCheck};
use crate::drilling::Fraction;
use drillstring_core::outputs::{MetricsView, Report};

/// The default parameters and numerics as dicts of JSON values.
#[pyfunction]
pub(crate) fn lumped_defaults(py: Python<'_>) -> PyResult<(Bound<'_, PyAny>, Bound<'_, PyAny>)> {
    let params = to_json_object(py, &lumped::LumpedParams::default())?;
    Ok((params, to_json_object(py, &lumped::LumpedNumerics::default())?))
}

/// A lumped run as `lumped_solve` returns it.
#[derive(Serialize)]
struct RunOutput<'a> {
    #[serde(flatten)]
    run: &'a lumped::LumpedRun,
    metrics: MetricsView<'a>,
    stats: RunStats,
}

#[derive(Serialize)]
struct RunStats {
    steps: u64,
    sticks: u64,
    slips: u64,
}

/// The equilibria as `lumped_equilibria` returns them.
#[derive(Serialize)]
struct EquilibriaOutput<'a> {
    #[serde(flatten)]
    equilibria: &'a lumped::Equilibria,
    static_limit: f64,
}

fn parse(py: Python<'_>, params_json: &str) -> PyResult<lumped::LumpedParams> {
    lumped::LumpedParams::from_json(params_json).map_err(|e| validation_error(py, e))
}

/// Runs the lumped model; see `_core.pyi` for the keys. Runs without the GIL; Ctrl-C (or an
/// exception of `progress`) stops it.
#[pyfunction]
#[pyo3(signature = (params_json, numerics_json, progress=None))]
pub(crate) fn lumped_solve<'py>(
    py: Python<'py>,
    params_json: &str,
    numerics_json: &str,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let p = parse(py, params_json)?;
    let num = lumped::LumpedNumerics::from_json(numerics_json).map_err(|e| validation_error(py, e))?;
    let signals = SignalCheck::with_progress(py, progress);
    let hook = Fraction { signals: &signals, duration: num.duration };
    let solved = py.detach(|| no_panic(|| lumped::solve_lumped(&p, &num, &hook, &mut |_| {})))?;
    signals.finish()?;
    let run = solved.map_err(|e| validation_error(py, e))?;

    let stats = RunStats { steps: run.steps, sticks: run.sticks, slips: run.slips };
    to_python(py, &RunOutput { run: &run, metrics: stick_slip_report(run.metrics.as_ref(), Report::Lumped), stats })
}

/// The steady rotations of the lumped model, their eigenvalues and stability, and what they predict (`equilibrium`).
#[pyfunction]
pub(crate) fn lumped_equilibria<'py>(py: Python<'py>, params_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let p = parse(py, params_json)?;
    let eq = no_panic(|| lumped::equilibria(&p))?.map_err(|e| validation_error(py, e))?;
    to_python(py, &EquilibriaOutput { equilibria: &eq, static_limit: p.static_limit() })
}

/// The minimum motor torque of a stick-slip cycle implied by break-off,
/// `drilling::grid::min_cycle_torque_from`.
#[pyfunction]
#[pyo3(signature = (breakoff_torque, kinetic_ratio, bit_static=0.0, bit_kinetic=0.0))]
pub(crate) fn min_cycle_torque(breakoff_torque: f64, kinetic_ratio: f64, bit_static: f64, bit_kinetic: f64) -> f64 {
    drilling::min_cycle_torque_from(breakoff_torque, kinetic_ratio, bit_static, bit_kinetic)
}
