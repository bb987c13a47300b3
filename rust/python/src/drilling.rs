//! Bindings of the drilling-system solver (`drillstring_core::drilling`): JSON configuration
//! in, dicts of numpy arrays and floats out (by [`to_python`]).

use std::collections::BTreeMap;

use drillstring_core::drilling::{self, compare, DrillConfig, DrillRun};
use drillstring_core::interrupt::Interrupt;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

use drillstring_core::metrics::StickSlip;
use drillstring_core::outputs::{self, MetricsView, Report, RunValues};

use crate::convert::{no_panic, reshape, to_dict, to_json_object, to_python, validation_error, SignalCheck};

fn parse(py: Python<'_>, config_json: &str) -> PyResult<DrillConfig> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
    cfg.validate().map_err(|e| validation_error(py, e))?;
    Ok(cfg)
}

/// The default configuration as a dict of JSON values (`sections` holds one template section).
#[pyfunction]
pub(crate) fn drill_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_json_object(py, &DrillConfig::default())
}

/// The configuration `config_json` with every default filled in, as a dict of JSON values;
/// raises `ValidationError` naming the dotted field of the first invalid value.
#[pyfunction]
pub(crate) fn drill_validate<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyAny>> {
    to_json_object(py, &parse(py, config_json)?)
}

/// The friction profile: `z` (cell centres, m), `limit_per_m` (N m/m), `cumulative` (static
/// friction torque below each cell centre, from the bit up, N m) and `breakoff_torque` (N m).
#[pyfunction]
pub(crate) fn drill_profile<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let cfg = parse(py, config_json)?;
    let profile = py.detach(|| no_panic(|| drilling::friction_profile(&cfg)))?.map_err(|e| validation_error(py, e))?;
    to_python(py, &profile)
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

/// A run as `drill_solve` returns it: the run's series, status, energy and stats, and under
/// `metrics` its metrics of the registry (`drillstring_core::outputs`: the stick-slip metrics,
/// the window asked for and the static torques) with their warnings.
#[derive(Serialize)]
struct RunOutput<'a> {
    #[serde(flatten)]
    run: &'a DrillRun,
    metrics: MetricsView<'a>,
}

pub(crate) fn run_dict(py: Python<'_>, run: DrillRun) -> PyResult<Bound<'_, PyDict>> {
    let values = RunValues {
        metrics: run.metrics.as_ref().unwrap_or(&StickSlip::UNDEFINED),
        window: run.window,
        breakoff_torque: run.breakoff_torque,
        min_cycle_torque: run.min_cycle_torque,
    };
    let metrics = MetricsView { run: values, report: Report::Drilling, warnings: run.metric_warnings() };
    let d = to_dict(py, &RunOutput { run: &run, metrics })?;
    let shape = [run.field_t.len(), run.z.len()];
    reshape(&d, "omega_field", shape)?;
    reshape(&d, "torque_field", shape)?;
    if !run.axial_z.is_empty() {
        let shape = [run.field_t.len(), run.axial_z.len()];
        reshape(&d, "axial_speed_field", shape)?;
        reshape(&d, "axial_force_field", shape)?;
    }
    Ok(d)
}

/// The metrics of one run as `drill_compare` takes them: a dict of names to a number, a text or
/// None (undefined); `field` names the argument in the error of another value.
fn metric_values(py: Python<'_>, field: &str, d: &Bound<'_, PyDict>) -> PyResult<BTreeMap<String, compare::Value>> {
    let mut out = BTreeMap::new();
    for (k, v) in d.iter() {
        let name: String = k.extract()?;
        let value = if v.is_none() {
            compare::Value::Number(f64::NAN)
        } else if let Ok(text) = v.extract::<String>() {
            compare::Value::Text(text)
        } else if let Ok(x) = v.extract::<f64>() {
            compare::Value::Number(x)
        } else {
            let shown = v.repr().map_or_else(|_| "?".to_string(), |r| r.to_string());
            return Err(validation_error(
                py,
                drillstring_core::error::Error::invalid(
                    format!("{field}[{name:?}]"),
                    shown,
                    "a number, a text or None",
                ),
            ));
        };
        out.insert(name, value);
    }
    Ok(out)
}

/// Two runs' metrics (dicts of names to numbers, texts or None) compared with the core's
/// tolerances (`drilling::compare`): a list of dicts `metric`, `value`, `other`, `change`,
/// `kind`, `tolerance`, `within`, one per metric both give.
#[pyfunction]
pub(crate) fn drill_compare<'py>(
    py: Python<'py>,
    metrics: &Bound<'py, PyDict>,
    other: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b) = (metric_values(py, "metrics", metrics)?, metric_values(py, "other", other)?);
    to_python(py, &compare::compare(&a, &b))
}

/// Every output of a run, once (`drillstring_core::outputs::OUTPUTS`): a list of dicts with
/// `name`, `unit` (SI as pint parses it, `""` dimensionless, None for a verdict, count or text),
/// `definition`, `runs` (of `torsional`, `coupled`, `lumped`), `map_column`, `kind` (`number`,
/// `verdict`, `count`, `text`, `series`), `tolerance` (`(kind, tolerance, floor)` of the grid and
/// start checks, or None), `headline` and `stick_slip` (a metric of `stick_slip_metrics`).
#[pyfunction]
pub(crate) fn drill_outputs(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_python(py, &outputs::describe())
}

/// The tolerances of `drill_compare`: a list of `(metric, kind, tolerance, floor)`, kind `rel`,
/// `abs` or `equal`, the floor a change that is within whatever its relative size.
#[pyfunction]
pub(crate) fn drill_compare_tolerances(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_python(py, &compare::tolerances())
}
