//! Conversions shared by the bindings: core errors to Python exceptions, panics to
//! `RuntimeError`, numpy arrays to vectors, results to Python objects (one serde serializer,
//! [`to_python`], for every result), the one `solve_*` binding of a system
//! ([`solve_binding`]), and Python's signal handlers (Ctrl-C) polled during a solve that runs
//! without the GIL.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use drillstring_core as core;
use drillstring_core::integrators::{self, Method, SolveOptions};
use drillstring_core::interrupt::Interrupt;
use drillstring_core::metrics::StickSlip;
use drillstring_core::outputs::{MetricsView, Report, RunValues};
use drillstring_core::solution::LIST;
use drillstring_core::{Output, SecondOrderSystem, Solution};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use pyo3::IntoPyObjectExt;
use serde::ser::{self, Impossible};
use serde::Serialize;

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
/// `nfev`, `naccept`, `ndense`, `nreject`, `dissipated` (samples,), or None for a system whose
/// forces do not depend on the velocity (`dissipative` false).
pub(crate) fn solution_dict<'py>(
    py: Python<'py>,
    mut sol: Solution,
    dissipative: bool,
) -> PyResult<Bound<'py, PyDict>> {
    // the samples, the large part, are handed to numpy as they are (no copy); the rest is
    // serialised
    let (samples, dim) = (sol.len(), sol.dim);
    let (t, y) = (std::mem::take(&mut sol.t), std::mem::take(&mut sol.y));
    let out = to_dict(py, &sol)?;
    out.set_item("t", PyArray1::from_vec(py, t))?;
    out.set_item("y", PyArray1::from_vec(py, y).reshape([samples, dim])?)?;
    if !dissipative {
        out.set_item("dissipated", py.None())?;
    }
    Ok(out)
}

/// Stick-slip metrics as Python sees them: the registry's metrics of a series alone or the lumped
/// model (`drillstring_core::outputs`), or [`StickSlip::UNDEFINED`]'s for a window without any,
/// and their `warnings`.
pub(crate) fn stick_slip_report(metrics: Option<&StickSlip>, report: Report) -> MetricsView<'_> {
    let warnings = metrics.map_or_else(Vec::new, StickSlip::warnings);
    MetricsView { run: RunValues::of(metrics.unwrap_or(&StickSlip::UNDEFINED)), report, warnings }
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

/// Defines the `solve_*` binding `$name` of the system pyclass `$system` (its core system in
/// its field `inner`): one signature and one behaviour for every system, [`solve_to_dict`].
macro_rules! solve_binding {
    ($(#[$doc:meta])* $name:ident, $system:ty) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = (system, q0, v0, t_end, t_eval, method, rtol, atol, dt=None, max_steps=None, first_step=None, max_step=f64::INFINITY, progress=None))]
        #[allow(clippy::too_many_arguments)]
        pub(crate) fn $name<'py>(
            py: Python<'py>,
            system: &Bound<'py, $system>,
            q0: numpy::PyReadonlyArray1<'py, f64>,
            v0: numpy::PyReadonlyArray1<'py, f64>,
            t_end: f64,
            t_eval: Option<numpy::PyReadonlyArray1<'py, f64>>,
            method: &str,
            rtol: f64,
            atol: f64,
            dt: Option<f64>,
            max_steps: Option<&Bound<'py, PyAny>>,
            first_step: Option<f64>,
            max_step: f64,
            progress: Option<Py<PyAny>>,
        ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
            let args = $crate::convert::SolveArgs {
                q0, v0, t_end, t_eval, method, rtol, atol, dt, max_steps, first_step, max_step, progress,
            };
            $crate::convert::solve_to_dict(py, &system.get().inner, args)
        }
    };
}
pub(crate) use solve_binding;

/// How [`to_python`] writes sequences.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Sequences {
    /// A sequence of numbers becomes a numpy array (float64, int64 for integers of up to 32
    /// bits, uint64 for 64-bit unsigned ones; float64 when empty), a serde tuple (a Rust tuple
    /// or fixed-size array) a tuple, anything else and a sequence marked with
    /// `drillstring_core::solution::serialize_list` a list.
    Arrays,
    /// As `json.loads` of the value's serde_json text: lists, and None for a non-finite float.
    Json,
}

/// Any `Serialize` value as a Python object: structs and maps become dicts, numeric sequences
/// numpy arrays (see [`Sequences::Arrays`]), `Option` None None, unit variants their serde
/// names. The one way the bindings return a result.
pub(crate) fn to_python<'py, T: Serialize + ?Sized>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    value.serialize(ToPython { py, seq: Sequences::Arrays, list: false }).map_err(|e| e.0)
}

/// [`to_python`] as a dict (for a struct or a map).
pub(crate) fn to_dict<'py, T: Serialize + ?Sized>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyDict>> {
    Ok(to_python(py, value)?.cast_into::<PyDict>()?)
}

/// A `Serialize` value as `json.loads` of its serde_json text would give it (lists, no arrays;
/// non-finite floats None), without the text.
pub(crate) fn to_json_object<'py, T: Serialize + ?Sized>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    value.serialize(ToPython { py, seq: Sequences::Json, list: false }).map_err(|e| e.0)
}

/// Reshapes the flat numpy array `dict[key]` to `shape` (row-major).
pub(crate) fn reshape<const N: usize>(dict: &Bound<'_, PyDict>, key: &str, shape: [usize; N]) -> PyResult<()> {
    if let Some(flat) = dict.get_item(key)? {
        dict.set_item(key, flat.call_method1("reshape", (shape.to_vec(),))?)?;
    }
    Ok(())
}

/// The error of [`ToPython`]: the Python exception to raise.
#[derive(Debug)]
struct SerError(PyErr);

impl std::fmt::Display for SerError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for SerError {}

impl ser::Error for SerError {
    fn custom<M: std::fmt::Display>(msg: M) -> Self {
        SerError(PyRuntimeError::new_err(format!("internal error in drillstring._core: {msg}")))
    }
}

impl From<PyErr> for SerError {
    fn from(err: PyErr) -> Self {
        SerError(err)
    }
}

/// The serde serializer of [`to_python`]; `list` forces the next sequence to a list.
#[derive(Clone, Copy)]
struct ToPython<'py> {
    py: Python<'py>,
    seq: Sequences,
    list: bool,
}

type SerResult<'py> = Result<Bound<'py, PyAny>, SerError>;

impl<'py> ToPython<'py> {
    fn element(self) -> Self {
        ToPython { list: false, ..self }
    }

    fn object(self, value: impl IntoPyObject<'py>) -> SerResult<'py> {
        Ok(value.into_bound_py_any(self.py)?)
    }
}

/// The methods of [`ToPython`] for scalars Python converts as they are.
macro_rules! python_scalars {
    ($($name:ident($ty:ty);)*) => {
        $(fn $name(self, v: $ty) -> SerResult<'py> {
            self.object(v)
        })*
    };
}

impl<'py> ser::Serializer for ToPython<'py> {
    type Ok = Bound<'py, PyAny>;
    type Error = SerError;
    type SerializeSeq = Collect<'py>;
    type SerializeTuple = Collect<'py>;
    type SerializeTupleStruct = Collect<'py>;
    type SerializeTupleVariant = Impossible<Self::Ok, SerError>;
    type SerializeMap = Dict<'py>;
    type SerializeStruct = Dict<'py>;
    type SerializeStructVariant = Impossible<Self::Ok, SerError>;

    python_scalars! {
        serialize_bool(bool);
        serialize_i8(i8);
        serialize_i16(i16);
        serialize_i32(i32);
        serialize_i64(i64);
        serialize_u8(u8);
        serialize_u16(u16);
        serialize_u32(u32);
        serialize_u64(u64);
        serialize_char(char);
        serialize_str(&str);
        serialize_bytes(&[u8]);
    }
    fn serialize_f32(self, v: f32) -> SerResult<'py> {
        self.serialize_f64(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> SerResult<'py> {
        if self.seq == Sequences::Json && !v.is_finite() {
            return self.serialize_none();
        }
        self.object(v)
    }
    fn serialize_none(self) -> SerResult<'py> {
        Ok(self.py.None().into_bound(self.py))
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> SerResult<'py> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> SerResult<'py> {
        self.serialize_none()
    }
    fn serialize_unit_struct(self, _name: &'static str) -> SerResult<'py> {
        self.serialize_none()
    }
    fn serialize_unit_variant(self, _name: &'static str, _index: u32, variant: &'static str) -> SerResult<'py> {
        self.object(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, name: &'static str, value: &T) -> SerResult<'py> {
        value.serialize(ToPython { list: name == LIST, ..self })
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> SerResult<'py> {
        let d = PyDict::new(self.py);
        d.set_item(variant, value.serialize(self.element())?)?;
        Ok(d.into_any())
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Collect<'py>, SerError> {
        let arrays = self.seq == Sequences::Arrays && !self.list;
        Ok(Collect {
            to: self.element(),
            items: if arrays { Items::Empty } else { Items::Objects(Vec::new()) },
            tuple: false,
            len: len.unwrap_or(0),
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Collect<'py>, SerError> {
        let tuple = self.seq == Sequences::Arrays && !self.list;
        Ok(Collect { to: self.element(), items: Items::Objects(Vec::new()), tuple, len })
    }
    fn serialize_tuple_struct(self, _name: &'static str, len: usize) -> Result<Collect<'py>, SerError> {
        self.serialize_tuple(len)
    }
    fn serialize_tuple_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleVariant, SerError> {
        Err(ser::Error::custom(format_args!("{name}::{variant}: tuple variants are not converted")))
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<Dict<'py>, SerError> {
        Ok(Dict { to: self.element(), dict: PyDict::new(self.py), key: None })
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<Dict<'py>, SerError> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeStructVariant, SerError> {
        Err(ser::Error::custom(format_args!("{name}::{variant}: struct variants are not converted")))
    }
}

/// The numbers of a sequence so far, of one kind (the first number's), flat.
enum Numbers {
    Float(Vec<f64>),
    Int(Vec<i64>),
    Unsigned(Vec<u64>),
}

impl Numbers {
    /// Numbers starting with `first`, with room for `capacity`.
    fn new(first: Num, capacity: usize) -> Self {
        fn start<T>(x: T, capacity: usize) -> Vec<T> {
            let mut v = Vec::with_capacity(capacity.max(1));
            v.push(x);
            v
        }
        match first {
            Num::Float(x) => Numbers::Float(start(x, capacity)),
            Num::Int(x) => Numbers::Int(start(x, capacity)),
            Num::Unsigned(x) => Numbers::Unsigned(start(x, capacity)),
        }
    }

    /// Appends `x`; false (nothing appended) when it is of another kind.
    #[inline]
    fn push(&mut self, x: Num) -> bool {
        match (self, x) {
            (Numbers::Float(v), Num::Float(x)) => v.push(x),
            (Numbers::Int(v), Num::Int(x)) => v.push(x),
            (Numbers::Unsigned(v), Num::Unsigned(x)) => v.push(x),
            _ => return false,
        }
        true
    }

    fn len(&self) -> usize {
        match self {
            Numbers::Float(v) => v.len(),
            Numbers::Int(v) => v.len(),
            Numbers::Unsigned(v) => v.len(),
        }
    }

    /// A numpy array of shape (len,), or (len / cols, cols) for rows of `cols` numbers.
    fn array<'py>(self, py: Python<'py>, cols: Option<usize>) -> PyResult<Bound<'py, PyAny>> {
        let rows = cols.map(|c| [self.len() / c.max(1), c]);
        let flat = match self {
            Numbers::Float(v) => PyArray1::from_vec(py, v).into_any(),
            Numbers::Int(v) => PyArray1::from_vec(py, v).into_any(),
            Numbers::Unsigned(v) => PyArray1::from_vec(py, v).into_any(),
        };
        match rows {
            Some(shape) => flat.call_method1("reshape", (shape.to_vec(),)),
            None => Ok(flat),
        }
    }

    fn objects<'py>(self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        match self {
            Numbers::Float(v) => v.into_iter().map(|x| x.into_bound_py_any(py)).collect(),
            Numbers::Int(v) => v.into_iter().map(|x| x.into_bound_py_any(py)).collect(),
            Numbers::Unsigned(v) => v.into_iter().map(|x| x.into_bound_py_any(py)).collect(),
        }
    }
}

/// The elements of a sequence so far: numbers (or rows of as many numbers) of one kind while
/// they are, else Python objects.
enum Items<'py> {
    Empty,
    /// `cols`: None for numbers, the row length for rows.
    Numbers {
        numbers: Numbers,
        cols: Option<usize>,
    },
    Objects(Vec<Bound<'py, PyAny>>),
}

/// One number of a numeric sequence ([`Number`]).
enum Num {
    Float(f64),
    Int(i64),
    Unsigned(u64),
}

/// A sequence, tuple or list being built ([`ToPython::serialize_seq`]).
struct Collect<'py> {
    to: ToPython<'py>,
    items: Items<'py>,
    tuple: bool,
    /// The length serde announced (0 if none).
    len: usize,
}

impl<'py> Collect<'py> {
    /// Appends `value` to the numbers when it is a number or a row of numbers that fits them.
    #[inline]
    fn push_number<T: Serialize + ?Sized>(&mut self, value: &T) -> bool {
        let (row, cols) = match value.serialize(Number) {
            // the common case, one number into numbers of its kind
            Ok(Probe::One(x)) => match &mut self.items {
                Items::Numbers { numbers, cols: None } => return numbers.push(x),
                _ => (vec![x], None),
            },
            Ok(Probe::Row(row)) => {
                let cols = Some(row.len());
                (row, cols)
            }
            Err(NotNumber) => return false,
        };
        match &mut self.items {
            Items::Empty => {
                let row_len = row.len();
                let mut it = row.into_iter();
                let Some(first) = it.next() else { return false };
                let capacity = if cols.is_some() { self.len.saturating_mul(row_len) } else { self.len };
                let mut numbers = Numbers::new(first, capacity);
                if !it.all(|x| numbers.push(x)) {
                    return false;
                }
                self.items = Items::Numbers { numbers, cols };
                true
            }
            Items::Numbers { numbers, cols: have } if *have == cols => {
                let before = numbers.len();
                if row.into_iter().all(|x| numbers.push(x)) {
                    return true;
                }
                // a number of another kind: back to the elements before it
                match numbers {
                    Numbers::Float(v) => v.truncate(before),
                    Numbers::Int(v) => v.truncate(before),
                    Numbers::Unsigned(v) => v.truncate(before),
                }
                false
            }
            _ => false,
        }
    }

    fn push<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        if !matches!(self.items, Items::Objects(_)) {
            if self.push_number(value) {
                return Ok(());
            }
            let py = self.to.py;
            self.items = Items::Objects(match std::mem::replace(&mut self.items, Items::Empty) {
                Items::Numbers { numbers, cols: None } => numbers.objects(py)?,
                Items::Numbers { numbers, cols: Some(c) } => {
                    let flat = numbers.array(py, Some(c))?;
                    flat.call_method0("tolist")?.extract::<Vec<Bound<'py, PyAny>>>()?
                }
                _ => Vec::new(),
            });
        }
        if let Items::Objects(v) = &mut self.items {
            v.push(value.serialize(self.to)?);
        }
        Ok(())
    }

    fn finish(self) -> SerResult<'py> {
        let py = self.to.py;
        Ok(match self.items {
            Items::Empty => PyArray1::<f64>::zeros(py, [0], false).into_any(),
            Items::Numbers { numbers, cols } => numbers.array(py, cols)?,
            Items::Objects(v) if self.tuple => PyTuple::new(py, v)?.into_any(),
            Items::Objects(v) => PyList::new(py, v)?.into_any(),
        })
    }
}

/// The `serde::ser` traits of a sequence, a tuple and a tuple struct, all one [`Collect`].
macro_rules! collect_impls {
    ($($trait:ident :: $method:ident),*) => {$(
        impl<'py> ser::$trait for Collect<'py> {
            type Ok = Bound<'py, PyAny>;
            type Error = SerError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
                self.push(value)
            }
            fn end(self) -> SerResult<'py> {
                self.finish()
            }
        }
    )*};
}

collect_impls!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field
);

/// A dict being built from a struct or a map.
struct Dict<'py> {
    to: ToPython<'py>,
    dict: Bound<'py, PyDict>,
    key: Option<Bound<'py, PyAny>>,
}

impl<'py> ser::SerializeMap for Dict<'py> {
    type Ok = Bound<'py, PyAny>;
    type Error = SerError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), SerError> {
        self.key = Some(key.serialize(self.to)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        let key = self.key.take().ok_or_else(|| <SerError as ser::Error>::custom("a map value without a key"))?;
        self.dict.set_item(key, value.serialize(self.to)?)?;
        Ok(())
    }
    fn end(self) -> SerResult<'py> {
        Ok(self.dict.into_any())
    }
}

impl<'py> ser::SerializeStruct for Dict<'py> {
    type Ok = Bound<'py, PyAny>;
    type Error = SerError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), SerError> {
        self.dict.set_item(key, value.serialize(self.to)?)?;
        Ok(())
    }
    fn end(self) -> SerResult<'py> {
        Ok(self.dict.into_any())
    }
}

/// The serializer that tells whether a value is a number or a tuple or sequence of numbers
/// ([`Probe`]); anything else is an error ([`NotNumber`]), and the sequence it is in becomes a
/// list.
struct Number;

/// What [`Number`] found.
enum Probe {
    One(Num),
    Row(Vec<Num>),
}

/// Not a number ([`Number`]).
#[derive(Debug)]
struct NotNumber;

impl std::fmt::Display for NotNumber {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("not a number")
    }
}

impl std::error::Error for NotNumber {}

impl ser::Error for NotNumber {
    fn custom<M: std::fmt::Display>(_msg: M) -> Self {
        NotNumber
    }
}

/// A row of numbers being gathered by [`Number`].
struct Row(Vec<Num>);

impl Row {
    fn push<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NotNumber> {
        match value.serialize(Number)? {
            Probe::One(x) => self.0.push(x),
            Probe::Row(_) => return Err(NotNumber),
        }
        Ok(())
    }
}

macro_rules! row_impls {
    ($($trait:ident :: $method:ident),*) => {$(
        impl ser::$trait for Row {
            type Ok = Probe;
            type Error = NotNumber;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NotNumber> {
                self.push(value)
            }
            fn end(self) -> Result<Probe, NotNumber> {
                Ok(Probe::Row(self.0))
            }
        }
    )*};
}

row_impls!(SerializeSeq::serialize_element, SerializeTuple::serialize_element);

/// The methods of [`Number`] for a number (`$num` of the value) and for what is not one.
macro_rules! number_methods {
    ($($name:ident($ty:ty) => $num:expr;)*) => {
        $(fn $name(self, v: $ty) -> Result<Probe, NotNumber> {
            Ok(Probe::One($num(v)))
        })*
    };
    ($($name:ident($($arg:ty),*);)*) => {
        $(fn $name(self, $(_: $arg),*) -> Result<Probe, NotNumber> {
            Err(NotNumber)
        })*
    };
}

impl ser::Serializer for Number {
    type Ok = Probe;
    type Error = NotNumber;
    type SerializeSeq = Row;
    type SerializeTuple = Row;
    type SerializeTupleStruct = Impossible<Probe, NotNumber>;
    type SerializeTupleVariant = Impossible<Probe, NotNumber>;
    type SerializeMap = Impossible<Probe, NotNumber>;
    type SerializeStruct = Impossible<Probe, NotNumber>;
    type SerializeStructVariant = Impossible<Probe, NotNumber>;

    number_methods! {
        serialize_i8(i8) => |v| Num::Int(i64::from(v));
        serialize_i16(i16) => |v| Num::Int(i64::from(v));
        serialize_i32(i32) => |v| Num::Int(i64::from(v));
        serialize_i64(i64) => Num::Int;
        serialize_u8(u8) => |v| Num::Int(i64::from(v));
        serialize_u16(u16) => |v| Num::Int(i64::from(v));
        serialize_u32(u32) => |v| Num::Int(i64::from(v));
        serialize_u64(u64) => Num::Unsigned;
        serialize_f32(f32) => |v| Num::Float(f64::from(v));
        serialize_f64(f64) => Num::Float;
    }
    number_methods! {
        serialize_bool(bool);
        serialize_char(char);
        serialize_str(&str);
        serialize_bytes(&[u8]);
        serialize_none();
        serialize_unit();
        serialize_unit_struct(&'static str);
        serialize_unit_variant(&'static str, u32, &'static str);
    }
    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<Probe, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, _: &T) -> Result<Probe, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<Probe, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Row, NotNumber> {
        Ok(Row(Vec::with_capacity(len.unwrap_or(0))))
    }
    fn serialize_tuple(self, len: usize) -> Result<Row, NotNumber> {
        Ok(Row(Vec::with_capacity(len)))
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeTupleStruct, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeStruct, NotNumber> {
        Err(NotNumber)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, NotNumber> {
        Err(NotNumber)
    }
}
