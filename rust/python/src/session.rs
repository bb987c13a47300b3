//! The binding of a drilling session (`drillstring_core::drilling::engine::Session`): a
//! `DrillSession` pyclass that forwards each call; its step runs without the GIL and stops on
//! Ctrl-C as `drill_solve` does.

use drillstring_core::drilling::config::{changes_from_json, SETTABLE};
use drillstring_core::drilling::engine::Session;
use drillstring_core::drilling::DrillConfig;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;

use crate::convert::{no_panic, to_dict, to_json_object, validation_error, SignalCheck};
use crate::drilling::run_dict;

/// A drilling run stepped in chunks; see `_core.pyi`.
#[pyclass(module = "drillstring._core")]
pub(crate) struct DrillSession {
    inner: Session,
}

/// The series' rows from an index on, by `series.csv`'s column names (a coupled run's too).
#[derive(Serialize)]
struct Rows<'a> {
    t: &'a [f64],
    surface_rpm: &'a [f64],
    bit_rpm: &'a [f64],
    motor_torque: &'a [f64],
    bit_torque: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    bit_axial_speed: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    rop: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    weight_on_bit: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    hook_load: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    bit_depth: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    depth_of_cut: &'a [f64],
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    block_position: &'a [f64],
}

#[pymethods]
impl DrillSession {
    /// A session of the JSON configuration `config_json` (validated) at its initial state.
    #[new]
    #[pyo3(signature = (config_json, keep_fields=false))]
    fn new(py: Python<'_>, config_json: &str, keep_fields: bool) -> PyResult<Self> {
        let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
        let inner = py.detach(|| no_panic(|| Session::new(&cfg, keep_fields)))?.map_err(|e| validation_error(py, e))?;
        Ok(DrillSession { inner })
    }

    /// The session of `config_json` that `steps` steps with the changes `changes_json` (JSON
    /// `[{time, key, value}, ...]`, a session's `changes`) reach, stepped there without the GIL.
    #[staticmethod]
    #[pyo3(signature = (config_json, changes_json, steps, keep_fields=false))]
    fn resume(py: Python<'_>, config_json: &str, changes_json: &str, steps: u64, keep_fields: bool) -> PyResult<Self> {
        let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
        let applied = changes_from_json(changes_json, "changes").map_err(|e| validation_error(py, e))?;
        let signals = SignalCheck::new(py);
        let resumed = py.detach(|| no_panic(|| Session::resume(&cfg, &applied, steps, keep_fields, &signals)))?;
        signals.finish()?;
        Ok(DrillSession { inner: resumed.map_err(|e| validation_error(py, e))? })
    }

    /// Steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.inner.steps()
    }

    /// Advances by `seconds` (whole steps, to the step end nearest `t + seconds`, at least
    /// one) without the GIL; `progress(t)` is called with the time reached about every 20 ms.
    /// Ctrl-C stops it within ~20 ms at the step reached (raised as `KeyboardInterrupt`).
    #[pyo3(signature = (seconds, progress=None))]
    fn step(&mut self, py: Python<'_>, seconds: f64, progress: Option<Py<PyAny>>) -> PyResult<()> {
        let signals = SignalCheck::with_progress(py, progress);
        let count = self.inner.steps_for(seconds);
        let session = &mut self.inner;
        py.detach(|| no_panic(|| session.advance(count, &signals, &mut |_| {})))?;
        signals.finish()
    }

    /// Sets the dotted `key` to the JSON value `value_json` from the next step.
    fn set(&mut self, py: Python<'_>, key: &str, value_json: &str) -> PyResult<()> {
        self.inner.set_json(key, value_json).map_err(|e| validation_error(py, e))
    }

    /// The time reached, s.
    #[getter]
    fn t(&self) -> f64 {
        self.inner.t()
    }

    /// The `numerics.duration` of the configuration that repeats what was stepped, s.
    #[getter]
    fn replay_duration(&self) -> f64 {
        self.inner.replay_duration()
    }

    /// The time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt()
    }

    /// `"success"` while the session can be stepped, else how it ended.
    #[getter]
    fn status<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_json_object(py, &self.inner.status())
    }

    #[getter]
    fn message(&self) -> &str {
        self.inner.message()
    }

    /// The keys `set` accepts.
    #[staticmethod]
    fn settable() -> Vec<&'static str> {
        SETTABLE.to_vec()
    }

    /// Every change made: `(time, key, value as JSON text)`.
    fn changes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items: Vec<(f64, String, String)> =
            self.inner.applied().iter().map(|c| (c.time, c.key.clone(), c.value.to_string())).collect();
        PyList::new(py, items)
    }

    /// The configuration as it stands (with the changes made), as JSON values.
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_json_object(py, self.inner.config())
    }

    /// The state at the time reached (the core's `SessionState`).
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_dict(py, &self.inner.state())
    }

    /// The series' rows from index `start` on.
    #[pyo3(signature = (start=0))]
    fn rows<'py>(&self, py: Python<'py>, start: usize) -> PyResult<Bound<'py, PyDict>> {
        let r = self.inner.run();
        let cut = |v: &[f64]| start.min(v.len());
        let rows = Rows {
            t: &r.t[cut(&r.t)..],
            surface_rpm: &r.surface_rpm[cut(&r.surface_rpm)..],
            bit_rpm: &r.bit_rpm[cut(&r.bit_rpm)..],
            motor_torque: &r.motor_torque[cut(&r.motor_torque)..],
            bit_torque: &r.bit_torque[cut(&r.bit_torque)..],
            bit_axial_speed: &r.bit_axial_speed[cut(&r.bit_axial_speed)..],
            rop: &r.rop[cut(&r.rop)..],
            weight_on_bit: &r.weight_on_bit[cut(&r.weight_on_bit)..],
            hook_load: &r.hook_load[cut(&r.hook_load)..],
            bit_depth: &r.bit_depth[cut(&r.bit_depth)..],
            depth_of_cut: &r.depth_of_cut[cut(&r.depth_of_cut)..],
            block_position: &r.block_position[cut(&r.block_position)..],
        };
        to_dict(py, &rows)
    }

    /// The number of series rows so far.
    fn __len__(&self) -> usize {
        self.inner.run().t.len()
    }

    /// The result of what was stepped, as `drill_solve` returns a run (metrics over `window`,
    /// default the last half of what was stepped).
    #[pyo3(signature = (window=None))]
    fn result<'py>(&self, py: Python<'py>, window: Option<(f64, f64)>) -> PyResult<Bound<'py, PyDict>> {
        let session = &self.inner;
        let run = py.detach(|| no_panic(|| session.result(window.map(|(a, b)| [a, b]))))?;
        run_dict(py, run)
    }

    /// An independent copy that continues bit for bit as this one would (a snapshot).
    fn copy(&self) -> Self {
        DrillSession { inner: self.inner.clone() }
    }
}
