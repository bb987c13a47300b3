//! Bindings of the signal metrics of a response (`drillstring_core::metrics::signal`).

use drillstring_core::metrics::signal;
use drillstring_core::Result;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::convert::{integer, no_panic, to_vec, validation_error};

/// A core result as a Python value, or the `ValidationError` naming the field.
fn checked<T>(py: Python<'_>, f: impl FnOnce() -> Result<T>) -> PyResult<T> {
    no_panic(f)?.map_err(|e| validation_error(py, e))
}

type Arrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// `(times, phases)` of the zero crossings of `x(t)`, each led by `t[0]` and its phase.
#[pyfunction]
pub(crate) fn crossing_phase<'py>(
    py: Python<'py>,
    t: PyReadonlyArray1<'py, f64>,
    x: PyReadonlyArray1<'py, f64>,
) -> PyResult<Arrays<'py>> {
    let (t, x) = (to_vec(&t), to_vec(&x));
    let (times, phases) = checked(py, || signal::crossing_phase(&t, &x))?;
    Ok((PyArray1::from_vec(py, times), PyArray1::from_vec(py, phases)))
}

/// The accumulated phase (rad) of `x` minus that of `x_ref` at each time of `at`.
#[pyfunction]
pub(crate) fn phase_shift<'py>(
    py: Python<'py>,
    t: PyReadonlyArray1<'py, f64>,
    x_ref: PyReadonlyArray1<'py, f64>,
    x: PyReadonlyArray1<'py, f64>,
    at: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (t, x_ref, x, at) = (to_vec(&t), to_vec(&x_ref), to_vec(&x), to_vec(&at));
    Ok(PyArray1::from_vec(py, checked(py, || signal::phase_shift(&t, &x_ref, &x, &at))?))
}

/// `max |x|` over the last half of the record over that of the first half.
#[pyfunction]
pub(crate) fn amplitude_growth(py: Python<'_>, x: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
    let x = to_vec(&x);
    checked(py, || signal::amplitude_growth(&x))
}

/// Finite, growth `<= factor` and `max |x| <= limit` (when given).
#[pyfunction]
#[pyo3(signature = (x, factor=signal::BOUNDED_GROWTH, limit=None))]
pub(crate) fn is_bounded(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    factor: f64,
    limit: Option<f64>,
) -> PyResult<bool> {
    let x = to_vec(&x);
    checked(py, || signal::is_bounded(&x, factor, limit))
}

/// `1 - min/max` of the half-cycle peaks of each sign (the larger), NaN without enough cycles.
#[pyfunction]
pub(crate) fn modulation_depth(x: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
    let x = to_vec(&x);
    no_panic(|| signal::modulation_depth(&x))
}

/// Area of the convex hull of the points `(x_k, y_k)`.
#[pyfunction]
pub(crate) fn hull_area(py: Python<'_>, x: PyReadonlyArray1<'_, f64>, y: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
    let (x, y) = (to_vec(&x), to_vec(&y));
    checked(py, || signal::hull_area(&x, &y))
}

/// Share of the cells of a `bins x bins` grid (None: `PHASE_FILL_BINS`) over the trajectory's
/// hull that it passes through.
#[pyfunction]
#[pyo3(signature = (x, y, bins=None))]
pub(crate) fn phase_fill<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray1<'py, f64>,
    bins: Option<&Bound<'py, PyAny>>,
) -> PyResult<f64> {
    let bins: usize = match bins {
        Some(b) if !b.is_none() => integer(py, "bins", b, "an integer >= 1")?,
        _ => signal::PHASE_FILL_BINS,
    };
    let (x, y) = (to_vec(&x), to_vec(&y));
    checked(py, || signal::phase_fill(&x, &y, bins))
}

/// The complete elliptic integral of the first kind `K(m)`, `m < 1`.
#[pyfunction]
pub(crate) fn ellipk(py: Python<'_>, m: f64) -> PyResult<f64> {
    checked(py, || signal::ellipk(m))
}

/// The turning point of `x'' + omega2 x + beta x^3 = 0` started at `x = 0`, `x' = velocity`.
#[pyfunction]
pub(crate) fn duffing_amplitude(py: Python<'_>, omega2: f64, beta: f64, velocity: f64) -> PyResult<f64> {
    checked(py, || signal::duffing_amplitude(omega2, beta, velocity))
}

/// The exact frequency (Hz) of `x'' + omega2 x + beta x^3 = 0` at amplitude `amplitude`.
#[pyfunction]
pub(crate) fn duffing_frequency(py: Python<'_>, omega2: f64, beta: f64, amplitude: f64) -> PyResult<f64> {
    checked(py, || signal::duffing_frequency(omega2, beta, amplitude))
}
