//! Conversions shared by the bindings: core errors to Python exceptions, panics to
//! `RuntimeError`, numpy arrays to vectors, solutions to dicts, and Python's signal handlers
//! (Ctrl-C) polled during a solve that runs without the GIL.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use drillstring_core as core;
use drillstring_core::integrators::{self, Method, SolveOptions};
use drillstring_core::interrupt::Interrupt;
use drillstring_core::{Output, SecondOrderSystem, Solution};
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

/// An integer argument as `T` (`u64`, `usize`), or a `ValidationError` naming `field` (instead of
/// the `OverflowError` a negative or huge Python int gives when extracted directly).
pub(crate) fn integer<'py, T: for<'a> FromPyObject<'a, 'py>>(
    py: Python<'py>,
    field: &str,
    value: &Bound<'py, PyAny>,
    allowed: &str,
) -> PyResult<T> {
    value.extract::<T>().map_err(|_| {
        let shown = value.repr().map(|r| r.to_string()).unwrap_or_else(|_| "?".into());
        validation_error(py, core::Error::invalid(field, shown, allowed))
    })
}

/// An optional `max_steps` argument (`None` or an int in `1..=2^64-1`; 0 is refused by the core).
pub(crate) fn max_steps_arg(py: Python<'_>, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    match value {
        Some(v) if !v.is_none() => integer(py, "max_steps", v, "None or an integer in 1..=2**64 - 1").map(Some),
        _ => Ok(None),
    }
}

pub(crate) fn to_vec(a: &PyReadonlyArray1<'_, f64>) -> Vec<f64> {
    match a.as_slice() {
        Ok(contiguous) => contiguous.to_vec(),
        Err(_) => a.as_array().iter().copied().collect(),
    }
}

/// The dict every solve returns: `t` (samples,), `y` (samples, dim), `status`, `message`,
/// `nfev`, `naccept`, `nreject`, `dissipated` (samples,), or None for a system whose forces do
/// not depend on the velocity (`dissipative` false).
pub(crate) fn solution_dict<'py>(py: Python<'py>, sol: Solution, dissipative: bool) -> PyResult<Bound<'py, PyDict>> {
    let samples = sol.len();
    let dim = sol.dim;
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, sol.t))?;
    out.set_item("y", PyArray1::from_vec(py, sol.y).reshape([samples, dim])?)?;
    out.set_item("status", sol.status.name())?;
    out.set_item("message", sol.message)?;
    out.set_item("nfev", sol.stats.nfev)?;
    out.set_item("naccept", sol.stats.naccept)?;
    out.set_item("ndense", sol.stats.ndense)?;
    out.set_item("nreject", sol.stats.nreject)?;
    if dissipative {
        out.set_item("dissipated", PyArray1::from_vec(py, sol.dissipated))?;
    } else {
        out.set_item("dissipated", py.None())?;
    }
    Ok(out)
}

/// How often a solve running without the GIL re-attaches to run Python's signal handlers.
const SIGNAL_CHECK_INTERVAL: Duration = Duration::from_millis(20);

/// The interrupt hook of a solve started from Python: at most every
/// [`SIGNAL_CHECK_INTERVAL`] it re-attaches to the interpreter briefly, calls
/// `PyErr_CheckSignals` (`Python::check_signals`), which runs the Python-level signal handlers,
/// and reports the solve time reached to the `progress` callable, if any. An exception they
/// raise (`KeyboardInterrupt` for Ctrl-C, or the callable's) is stored and stops the solve;
/// [`SignalCheck::finish`] then raises it.
///
/// Python runs signal handlers only in the main thread, so a solve started from another thread
/// only re-attaches to report progress (solves on several threads keep running in parallel).
pub(crate) struct SignalCheck {
    main_thread: bool,
    progress: Option<Py<PyAny>>,
    last: Mutex<Instant>,
    error: Mutex<Option<PyErr>>,
}

impl SignalCheck {
    /// A hook for a solve about to be started by the current thread.
    pub(crate) fn new(py: Python<'_>) -> Self {
        Self::with_progress(py, None)
    }

    /// A hook that also calls `progress(t)` with the time reached (every ~20 ms).
    pub(crate) fn with_progress(py: Python<'_>, progress: Option<Py<PyAny>>) -> Self {
        SignalCheck {
            main_thread: is_main_thread(py),
            progress: progress.filter(|p| !p.is_none(py)),
            last: Mutex::new(Instant::now()),
            error: Mutex::new(None),
        }
    }

    /// Raises the exception a signal handler or the progress callable raised during the
    /// solve, if any.
    pub(crate) fn finish(self) -> PyResult<()> {
        match self.error.into_inner() {
            Ok(Some(err)) => Err(err),
            _ => Ok(()),
        }
    }
}

impl Interrupt for SignalCheck {
    fn interrupted(&self) -> bool {
        self.interrupted_at(f64::NAN)
    }

    fn interrupted_at(&self, t: f64) -> bool {
        let report = self.progress.as_ref().filter(|_| t.is_finite());
        if !self.main_thread && report.is_none() {
            return false;
        }
        {
            let Ok(mut last) = self.last.lock() else { return false };
            if last.elapsed() < SIGNAL_CHECK_INTERVAL {
                return false;
            }
            *last = Instant::now();
        }
        let checked = Python::try_attach(|py| -> PyResult<()> {
            if self.main_thread {
                py.check_signals()?;
            }
            if let Some(progress) = report {
                progress.call1(py, (t,))?;
            }
            Ok(())
        });
        match checked {
            Some(Err(err)) => {
                if let Ok(mut slot) = self.error.lock() {
                    *slot = Some(err);
                }
                true
            }
            // Handled, no signal, or the interpreter is finalizing.
            _ => false,
        }
    }
}

/// Whether the current thread is Python's main thread (the only one that runs signal handlers).
fn is_main_thread(py: Python<'_>) -> bool {
    let check = || -> PyResult<bool> {
        let threading = py.import("threading")?;
        let current = threading.call_method0("current_thread")?;
        let main = threading.call_method0("main_thread")?;
        Ok(current.is(&main))
    };
    check().unwrap_or(false)
}

/// The arguments every `solve_*` binding takes after its system.
pub(crate) struct SolveArgs<'a, 'py> {
    pub q0: PyReadonlyArray1<'py, f64>,
    pub v0: PyReadonlyArray1<'py, f64>,
    pub t_end: f64,
    pub t_eval: Option<PyReadonlyArray1<'py, f64>>,
    pub method: &'a str,
    pub rtol: f64,
    pub atol: f64,
    pub dt: Option<f64>,
    pub max_steps: Option<&'a Bound<'py, PyAny>>,
    pub first_step: Option<f64>,
    pub max_step: f64,
    /// Called with the solve time reached, every ~20 ms (None: no report).
    pub progress: Option<Py<PyAny>>,
}

/// Solves `sys` from `(q0, v0)` at `t = 0` without the GIL and returns [`solution_dict`].
///
/// Ctrl-C (any exception raised by a Python signal handler) stops the solve within ~20 ms
/// through [`SignalCheck`] and is raised here; core input errors become `ValidationError`.
pub(crate) fn solve_to_dict<'py, S: SecondOrderSystem + Sync + ?Sized>(
    py: Python<'py>,
    sys: &S,
    args: SolveArgs<'_, 'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let method =
        Method::resolve(args.method, sys.velocity_dependent(), args.rtol).map_err(|e| validation_error(py, e))?;
    let (q0, v0) = (to_vec(&args.q0), to_vec(&args.v0));
    let output = match &args.t_eval {
        Some(t) => Output::Times(to_vec(t)),
        None => Output::EveryStep,
    };
    let max_steps = max_steps_arg(py, args.max_steps)?;
    let opts = SolveOptions {
        method,
        rtol: args.rtol,
        atol: args.atol,
        dt: args.dt,
        max_steps,
        first_step: args.first_step,
        max_step: args.max_step,
    };
    let t_end = args.t_end;
    let signals = SignalCheck::with_progress(py, args.progress);
    let solved = py.detach(|| {
        no_panic(|| integrators::solve_second_order_with(sys, 0.0, &q0, &v0, t_end, &output, &opts, &signals))
    })?;
    signals.finish()?;
    let sol = solved.map_err(|e| validation_error(py, e))?;
    solution_dict(py, sol, sys.velocity_dependent())
}

/// The stick-slip metrics of a run as a dict (`t_start`, `t_end`, `severity`, `stuck_fraction`,
/// `rpm_min`, `rpm_max`, `rpm_mean`, `torque_min`, `torque_max`, `cycle_period`,
/// `period_cycles`, `periodicity`, `slip_period`, `slip_onsets`, `stick_slip`, `settled`,
/// `warnings`); NaN, 0, false and no warnings when the run has none.
pub(crate) fn stick_slip_dict<'py>(
    py: Python<'py>,
    m: Option<&drillstring_core::metrics::StickSlip>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let nan = f64::NAN;
    d.set_item("t_start", m.map_or(nan, |s| s.t_start))?;
    d.set_item("t_end", m.map_or(nan, |s| s.t_end))?;
    d.set_item("severity", m.map_or(nan, |s| s.severity))?;
    d.set_item("stuck_fraction", m.map_or(nan, |s| s.stuck_fraction))?;
    d.set_item("rpm_min", m.map_or(nan, |s| s.rpm_min))?;
    d.set_item("rpm_max", m.map_or(nan, |s| s.rpm_max))?;
    d.set_item("rpm_mean", m.map_or(nan, |s| s.rpm_mean))?;
    d.set_item("torque_min", m.map_or(nan, |s| s.torque_min))?;
    d.set_item("torque_max", m.map_or(nan, |s| s.torque_max))?;
    d.set_item("cycle_period", m.map_or(nan, |s| s.cycle_period))?;
    d.set_item("period_cycles", m.map_or(nan, |s| s.period_cycles))?;
    d.set_item("periodicity", m.map_or(nan, |s| s.periodicity))?;
    d.set_item("slip_period", m.map_or(nan, |s| s.slip_period))?;
    d.set_item("slip_onsets", m.map_or(0, |s| s.slip_onsets))?;
    d.set_item("stick_slip", m.is_some_and(|s| s.stick_slip))?;
    d.set_item("settled", m.is_some_and(|s| s.settled))?;
    d.set_item("warnings", m.map_or_else(Vec::new, |s| s.warnings()))?;
    Ok(d)
}
