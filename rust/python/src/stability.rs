//! Bindings of the linear model (`drillstring_core::stability`): frequencies, wave speed and
//! critical speeds of eq. 18, the one-mode Duffing coefficients, the Jacobian, eigenvalues and
//! classification of the equilibrium of a modal system, and the mode shapes of the basis.

use drillstring_core as core;
use drillstring_core::stability;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{to_dict, to_vec, validation_error};

/// Mode numbers as `u32`, or a `ValidationError` naming `indices`.
fn mode_numbers(py: Python<'_>, indices: &PyReadonlyArray1<'_, i64>) -> PyResult<Vec<u32>> {
    indices
        .as_array()
        .iter()
        .enumerate()
        .map(|(p, &i)| {
            u32::try_from(i).map_err(|_| {
                validation_error(py, core::Error::invalid(format!("indices[{p}]"), i, "non-negative mode numbers"))
            })
        })
        .collect()
}

/// `w_i^2 = (k2 (i pi / l)^2 - k6) / k1` (rad^2/s^2) for each mode number `i` of `indices`.
#[pyfunction]
pub(crate) fn frequency_squared<'py>(
    py: Python<'py>,
    k1: f64,
    k2: f64,
    k6: f64,
    length: f64,
    indices: PyReadonlyArray1<'py, f64>,
) -> Bound<'py, PyArray1<f64>> {
    let out = indices.as_array().iter().map(|&i| stability::frequency_squared(k1, k2, k6, length, i)).collect();
    PyArray1::from_vec(py, out)
}

/// `sqrt(w^2)` (rad/s) of each `w^2 >= 0`, NaN for a negative one.
#[pyfunction]
pub(crate) fn linear_frequencies<'py>(
    py: Python<'py>,
    frequency_squared: PyReadonlyArray1<'py, f64>,
) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, frequency_squared.as_array().iter().map(|&w2| stability::linear_frequency(w2)).collect())
}

/// The linear torsional wave speed `sqrt(k2 / k1)` (m/s), NaN for `k2 < 0`.
#[pyfunction]
pub(crate) fn wave_speed(k1: f64, k2: f64) -> f64 {
    stability::wave_speed(k1, k2)
}

/// The critical speeds `(i pi / l) sqrt(k2 / (k6 / Omega^2))` (rad/s) of the mode numbers
/// `indices`; `inf` when `k6_per_omega_squared == 0`, NaN for `k2 < 0`.
#[pyfunction]
pub(crate) fn critical_speeds<'py>(
    py: Python<'py>,
    k2: f64,
    k6_per_omega_squared: f64,
    length: f64,
    indices: PyReadonlyArray1<'py, f64>,
) -> Bound<'py, PyArray1<f64>> {
    let out =
        indices.as_array().iter().map(|&i| stability::critical_speed(k2, k6_per_omega_squared, length, i)).collect();
    PyArray1::from_vec(py, out)
}

/// The squared wave speed `k2 / k1` that the rates `K_ii / M_ii` of a paper-family modal model
/// (`k6 = k1 Omega^2`) of the mode numbers `indices` on `[0, length]` imply at the rotation
/// speed `omega` (the mean over the elastic modes), NaN without an elastic mode.
#[pyfunction]
pub(crate) fn wave_speed_squared_of_rates(
    py: Python<'_>,
    rates: PyReadonlyArray1<'_, f64>,
    indices: PyReadonlyArray1<'_, i64>,
    length: f64,
    omega: f64,
) -> PyResult<f64> {
    let modes = mode_numbers(py, &indices)?;
    Ok(stability::wave_speed_squared_of_rates(&to_vec(&rates), &modes, length, omega))
}

/// `K_ii / M_ii` (1/s^2) of a modal system's diagonals.
#[pyfunction]
pub(crate) fn modal_rates<'py>(
    py: Python<'py>,
    mass: PyReadonlyArray1<'py, f64>,
    stiffness: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let rates = stability::rates(&to_vec(&mass), &to_vec(&stiffness)).map_err(|e| validation_error(py, e))?;
    Ok(PyArray1::from_vec(py, rates))
}

/// `(a1, a2, a3)` of the one-mode Duffing equation (eq. 19, corrected eq. 20) of the modal model
/// of the single mode `i = 1`: its mass, stiffness and quartic coefficients on `[0, length]`.
#[pyfunction]
pub(crate) fn duffing(
    py: Python<'_>,
    indices: PyReadonlyArray1<'_, i64>,
    mass: PyReadonlyArray1<'_, f64>,
    stiffness: PyReadonlyArray1<'_, f64>,
    quartic_coef: PyReadonlyArray1<'_, f64>,
    length: f64,
) -> PyResult<(f64, f64, f64)> {
    let modes = mode_numbers(py, &indices)?;
    let [a1, a2, a3] = stability::duffing(&modes, &to_vec(&mass), &to_vec(&stiffness), &to_vec(&quartic_coef), length)
        .map_err(|e| validation_error(py, e))?;
    Ok((a1, a2, a3))
}

/// The Jacobian `[[0, I], [-M^-1 K, -c I]]` (2m, 2m) at `q = qdot = 0`.
#[pyfunction]
pub(crate) fn modal_jacobian<'py>(
    py: Python<'py>,
    mass: PyReadonlyArray1<'py, f64>,
    stiffness: PyReadonlyArray1<'py, f64>,
    damping_rate: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let m = mass.len()?;
    let jac =
        stability::jacobian(&to_vec(&mass), &to_vec(&stiffness), damping_rate).map_err(|e| validation_error(py, e))?;
    PyArray1::from_vec(py, jac).reshape([2 * m, 2 * m])
}

/// The linear stability of the equilibrium of a modal system: a dict with `rates` (m,),
/// `mode_eigenvalues_real`, `mode_eigenvalues_imag` (m,), `eigenvalues_real`,
/// `eigenvalues_imag` (2m,, sorted by imaginary then real part), `mode_classification` (list of
/// m names) and `classification`.
#[pyfunction]
pub(crate) fn modal_stability<'py>(
    py: Python<'py>,
    mass: PyReadonlyArray1<'py, f64>,
    stiffness: PyReadonlyArray1<'py, f64>,
    damping_rate: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s =
        stability::analyse(&to_vec(&mass), &to_vec(&stiffness), damping_rate).map_err(|e| validation_error(py, e))?;
    to_dict(py, &s)
}

/// The mode shapes `cos(i pi z / l)` (`slope=False`) or their slopes `-(i pi / l) sin(i pi z / l)`
/// as a `(len(z), len(indices))` array.
#[pyfunction]
#[pyo3(signature = (indices, length, z, slope=false))]
pub(crate) fn mode_shapes<'py>(
    py: Python<'py>,
    indices: PyReadonlyArray1<'py, i64>,
    length: f64,
    z: PyReadonlyArray1<'py, f64>,
    slope: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let modes = mode_numbers(py, &indices)?;
    let shape = if slope { core::sweep::mode_slope } else { core::sweep::mode_shape };
    let z = z.as_array();
    let out: Vec<f64> = z.iter().flat_map(|&z| modes.iter().map(move |&i| shape(i, z, length))).collect();
    PyArray1::from_vec(py, out).reshape([z.len(), modes.len()])
}
