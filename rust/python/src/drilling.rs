//! Bindings of the drilling-system solver (`drillstring_core::drilling`): JSON configuration
//! in, dicts of numpy arrays and floats out.

use drillstring_core::drilling::{self, DrillConfig};
use drillstring_core::interrupt::Interrupt;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{no_panic, stick_slip_dict, validation_error, SignalCheck};

fn parse(py: Python<'_>, config_json: &str) -> PyResult<DrillConfig> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
    cfg.validate().map_err(|e| validation_error(py, e))?;
    Ok(cfg)
}

/// The default configuration as JSON (`sections` holds one template section).
#[pyfunction]
pub(crate) fn drill_defaults() -> String {
    DrillConfig::default().to_json()
}

/// The configuration `config_json` with every default filled in, as JSON; raises
/// `ValidationError` naming the dotted field of the first invalid value.
#[pyfunction]
pub(crate) fn drill_validate(py: Python<'_>, config_json: &str) -> PyResult<String> {
    Ok(parse(py, config_json)?.to_json())
}

/// The friction profile: `z` (cell centres, m), `limit_per_m` (N m/m), `cumulative` (static
/// friction torque below each cell centre, from the bit up, N m) and `breakoff_torque` (N m).
#[pyfunction]
pub(crate) fn drill_profile<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyDict>> {
    let cfg = parse(py, config_json)?;
    let profile = py.detach(|| no_panic(|| drilling::friction_profile(&cfg)))?.map_err(|e| validation_error(py, e))?;
    let d = PyDict::new(py);
    d.set_item("z", PyArray1::from_vec(py, profile.z))?;
    d.set_item("limit_per_m", PyArray1::from_vec(py, profile.limit_per_m))?;
    d.set_item("cumulative", PyArray1::from_vec(py, profile.cumulative))?;
    d.set_item("breakoff_torque", profile.breakoff_torque)?;
    Ok(d)
}

/// The interrupt hook of a drilling solve: Python's signal handlers (Ctrl-C) and the progress
/// callable, which receives the fraction done (the solve time over the duration).
pub(crate) struct Fraction<'a> {
    pub(crate) signals: &'a SignalCheck,
    pub(crate) duration: f64,
}

impl Interrupt for Fraction<'_> {
    fn interrupted(&self) -> bool {
        self.signals.interrupted()
    }

    fn interrupted_at(&self, t: f64) -> bool {
        self.signals.interrupted_at((t / self.duration).clamp(0.0, 1.0))
    }
}

/// Runs the drilling system; see `_core.pyi` for the keys. Runs without the GIL; Ctrl-C stops
/// it within ~20 ms (raised here as `KeyboardInterrupt`), as does an exception of `progress`.
#[pyfunction]
#[pyo3(signature = (config_json, progress=None))]
pub(crate) fn drill_solve<'py>(
    py: Python<'py>,
    config_json: &str,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let cfg = parse(py, config_json)?;
    let signals = SignalCheck::with_progress(py, progress);
    let hook = Fraction { signals: &signals, duration: cfg.numerics.duration };
    let solved = py.detach(|| no_panic(|| drilling::solve(&cfg, &hook, &mut |_| {})))?;
    signals.finish()?;
    let run = solved.map_err(|e| validation_error(py, e))?;
    run_dict(py, run)
}

fn run_dict(py: Python<'_>, run: drilling::DrillRun) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let (nt, nz) = (run.field_t.len(), run.z.len());
    d.set_item("t", PyArray1::from_vec(py, run.t))?;
    d.set_item("surface_rpm", PyArray1::from_vec(py, run.surface_rpm))?;
    d.set_item("bit_rpm", PyArray1::from_vec(py, run.bit_rpm))?;
    d.set_item("motor_torque", PyArray1::from_vec(py, run.motor_torque))?;
    d.set_item("bit_torque", PyArray1::from_vec(py, run.bit_torque))?;
    d.set_item("field_t", PyArray1::from_vec(py, run.field_t))?;
    d.set_item("z", PyArray1::from_vec(py, run.z))?;
    d.set_item("omega_field", PyArray1::from_vec(py, run.omega_field).reshape([nt, nz])?)?;
    d.set_item("torque_field", PyArray1::from_vec(py, run.torque_field).reshape([nt, nz])?)?;
    d.set_item("status", run.status.name())?;
    d.set_item("message", run.message)?;
    d.set_item("warnings", run.warnings)?;

    let m = stick_slip_dict(py, run.metrics.as_ref())?;
    m.set_item("window_start", run.window[0])?;
    m.set_item("window_end", run.window[1])?;
    m.set_item("breakoff_torque", run.breakoff_torque)?;
    m.set_item("min_cycle_torque", run.min_cycle_torque)?;
    d.set_item("metrics", m)?;

    let e = PyDict::new(py);
    let en = run.energy;
    e.set_item("motor_work", en.motor_work)?;
    e.set_item("initial", en.initial)?;
    e.set_item("kinetic", en.kinetic)?;
    e.set_item("elastic", en.elastic)?;
    e.set_item("top_drive", en.top_drive)?;
    e.set_item("bha", en.bha)?;
    e.set_item("friction_loss", en.friction_loss)?;
    e.set_item("damping_loss", en.damping_loss)?;
    e.set_item("bit_loss", en.bit_loss)?;
    e.set_item("numerical_loss", en.numerical_loss)?;
    e.set_item("upwind_loss", en.upwind_loss)?;
    e.set_item("inertia_loss", en.inertia_loss)?;
    e.set_item("balance_error", en.balance_error)?;
    d.set_item("energy", e)?;

    let st = PyDict::new(py);
    let s = run.stats;
    st.set_item("cells", s.cells)?;
    st.set_item("steps", s.steps)?;
    st.set_item("dt", s.dt)?;
    st.set_item("courant_min", s.courant_min)?;
    st.set_item("courant_max", s.courant_max)?;
    st.set_item("courant_peak", s.courant_peak)?;
    st.set_item("kp", s.kp)?;
    st.set_item("ki", s.ki)?;
    st.set_item("first_mode_hz", s.first_mode_hz)?;
    d.set_item("stats", st)?;
    Ok(d)
}
