//! Bindings of the lumped two-inertia model (`drillstring_core::drilling::lumped`) and of the
//! minimum cycle torque implied by break-off: JSON parameters in, dicts out.

use drillstring_core::drilling::{self, lumped};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{no_panic, stick_slip_dict, validation_error, SignalCheck};
use crate::drilling::Fraction;

/// The default parameters and numerics as JSON objects.
#[pyfunction]
pub(crate) fn lumped_defaults() -> (String, String) {
    (lumped::LumpedParams::default().to_json(), lumped::LumpedNumerics::default().to_json())
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
) -> PyResult<Bound<'py, PyDict>> {
    let p = parse(py, params_json)?;
    let num = lumped::LumpedNumerics::from_json(numerics_json).map_err(|e| validation_error(py, e))?;
    let signals = SignalCheck::with_progress(py, progress);
    let hook = Fraction { signals: &signals, duration: num.duration };
    let solved = py.detach(|| no_panic(|| lumped::solve_lumped(&p, &num, &hook, &mut |_| {})))?;
    signals.finish()?;
    let run = solved.map_err(|e| validation_error(py, e))?;

    let d = PyDict::new(py);
    d.set_item("t", PyArray1::from_vec(py, run.t))?;
    d.set_item("top_speed", PyArray1::from_vec(py, run.top_speed))?;
    d.set_item("bit_speed", PyArray1::from_vec(py, run.bit_speed))?;
    d.set_item("spring_torque", PyArray1::from_vec(py, run.spring_torque))?;
    d.set_item("bit_torque", PyArray1::from_vec(py, run.bit_torque))?;
    d.set_item("status", run.status.name())?;
    d.set_item("message", run.message)?;
    d.set_item("window", (run.window[0], run.window[1]))?;
    d.set_item("metrics", stick_slip_dict(py, run.metrics.as_ref())?)?;
    let e = PyDict::new(py);
    let en = run.energy;
    e.set_item("motor_work", en.motor_work)?;
    e.set_item("initial", en.initial)?;
    e.set_item("kinetic_top", en.kinetic_top)?;
    e.set_item("kinetic_bit", en.kinetic_bit)?;
    e.set_item("spring", en.spring)?;
    e.set_item("viscous_loss", en.viscous_loss)?;
    e.set_item("friction_loss", en.friction_loss)?;
    e.set_item("balance_error", en.balance_error)?;
    d.set_item("energy", e)?;
    let st = PyDict::new(py);
    st.set_item("steps", run.steps)?;
    st.set_item("sticks", run.sticks)?;
    st.set_item("slips", run.slips)?;
    d.set_item("stats", st)?;
    Ok(d)
}

/// The steady rotations of the lumped model, their eigenvalues and stability, and the regime.
#[pyfunction]
pub(crate) fn lumped_equilibria<'py>(py: Python<'py>, params_json: &str) -> PyResult<Bound<'py, PyDict>> {
    let p = parse(py, params_json)?;
    let eq = no_panic(|| lumped::equilibria(&p))?.map_err(|e| validation_error(py, e))?;
    let rotations = PyList::empty(py);
    for r in &eq.rotations {
        let d = PyDict::new(py);
        d.set_item("speed", r.speed)?;
        d.set_item("twist", r.twist)?;
        let eig: Vec<(f64, f64)> = r.eigenvalues.to_vec();
        d.set_item("eigenvalues", eig)?;
        d.set_item("stable", r.stable)?;
        rotations.append(d)?;
    }
    let d = PyDict::new(py);
    d.set_item("rotations", rotations)?;
    d.set_item("stuck_possible", eq.stuck_possible)?;
    d.set_item("regime", eq.regime.name())?;
    d.set_item("static_limit", p.static_limit())?;
    Ok(d)
}

/// The minimum motor torque of a stick-slip cycle implied by break-off,
/// `drilling::grid::min_cycle_torque_from`.
#[pyfunction]
#[pyo3(signature = (breakoff_torque, kinetic_ratio, bit_static=0.0, bit_kinetic=0.0))]
pub(crate) fn min_cycle_torque(breakoff_torque: f64, kinetic_ratio: f64, bit_static: f64, bit_kinetic: f64) -> f64 {
    drilling::min_cycle_torque_from(breakoff_torque, kinetic_ratio, bit_static, bit_kinetic)
}
