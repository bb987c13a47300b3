//! Bindings of the metrics of a sampled run (`drillstring_core::metrics`).

use drillstring_core as core;
use drillstring_core::metrics::FrequencyEstimator;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyBool;

use drillstring_core::outputs::Report;

use crate::convert::{integer, no_panic, stick_slip_report, to_python, to_vec, validation_error};

/// `(frequencies, amplitudes)` of spectral peaks.
type Peaks<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A positive integer argument (`bool` refused), or a `ValidationError` naming `field`.
fn count_arg(py: Python<'_>, field: &str, value: &Bound<'_, PyAny>) -> PyResult<usize> {
    let allowed = "an integer >= 1";
    let refused = || {
        let shown = value.repr().map(|r| r.to_string()).unwrap_or_else(|_| "?".into());
        validation_error(py, core::Error::invalid(field, shown, allowed))
    };
    if value.is_instance_of::<PyBool>() {
        return Err(refused());
    }
    match integer::<usize>(py, field, value, allowed)? {
        0 => Err(refused()),
        n => Ok(n),
    }
}

/// The `count` strongest peaks of the Hann-windowed, `pad`-times zero-padded spectrum of the
/// record `x` sampled every `dt` seconds, strongest first: `(frequencies in Hz, sine
/// amplitudes)`, each (peaks,). Runs without the GIL.
#[pyfunction]
pub(crate) fn spectral_peaks<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    dt: f64,
    count: &Bound<'py, PyAny>,
    pad: &Bound<'py, PyAny>,
    threshold: f64,
) -> PyResult<Peaks<'py>> {
    let count = count_arg(py, "count", count)?;
    let pad = count_arg(py, "pad", pad)?;
    let x = to_vec(&x);
    let peaks = py.detach(|| {
        no_panic(|| {
            FrequencyEstimator::with_pad(x.len(), pad).map(|est| {
                let mut buf = est.buffers();
                est.spectral_peaks(&x, dt, count, threshold, &mut buf)
            })
        })
    })?;
    let peaks = peaks.map_err(|e| validation_error(py, e))?;
    let frequencies = peaks.iter().map(|p| p.frequency).collect();
    let amplitudes = peaks.iter().map(|p| p.amplitude).collect();
    Ok((PyArray1::from_vec(py, frequencies), PyArray1::from_vec(py, amplitudes)))
}

/// `max |H + D - H(0)| / |H(0)|` of the energies `energy` of the samples and the energies
/// `dissipated` the damping took out up to each (None undamped); 0 when `H(0) = 0`.
#[pyfunction]
#[pyo3(signature = (energy, dissipated=None))]
pub(crate) fn energy_drift(
    py: Python<'_>,
    energy: PyReadonlyArray1<'_, f64>,
    dissipated: Option<PyReadonlyArray1<'_, f64>>,
) -> PyResult<f64> {
    let energy = to_vec(&energy);
    let dissipated = dissipated.map(|d| to_vec(&d)).unwrap_or_default();
    if !dissipated.is_empty() && dissipated.len() != energy.len() {
        return Err(validation_error(
            py,
            core::Error::invalid(
                "dissipated",
                format!("length {}", dissipated.len()),
                format!("None or length {} (one per sample)", energy.len()),
            ),
        ));
    }
    no_panic(|| core::metrics::energy_drift(&energy, &dissipated))
}

/// The quadratic energy `(M_i qdot_i^2 + K_i q_i^2) / 2` of each mode (rows) at each sample
/// (columns): `q` and `qdot` of shape (m, samples), `mass` and `stiffness` (m,).
#[pyfunction]
pub(crate) fn modal_energies<'py>(
    py: Python<'py>,
    mass: PyReadonlyArray1<'py, f64>,
    stiffness: PyReadonlyArray1<'py, f64>,
    q: PyReadonlyArray2<'py, f64>,
    qdot: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (qa, va) = (q.as_array(), qdot.as_array());
    let m = mass.len()?;
    if qa.nrows() != m || va.shape() != qa.shape() {
        return Err(validation_error(
            py,
            core::Error::invalid(
                "q",
                format!("shapes {:?} and {:?}", qa.shape(), va.shape()),
                format!("q and qdot of equal shape ({m}, samples)"),
            ),
        ));
    }
    let samples = qa.ncols();
    let (q, v): (Vec<f64>, Vec<f64>) = (qa.iter().copied().collect(), va.iter().copied().collect());
    let energies = no_panic(|| core::metrics::modal_energy_history(&to_vec(&mass), &to_vec(&stiffness), &q, &v))?
        .map_err(|e| validation_error(py, e))?;
    PyArray1::from_vec(py, energies).reshape([m, samples])
}

/// The stick-slip metrics (`drillstring_core::metrics::stickslip`) of the bit speed
/// `omega_bit` (rad/s) and optionally the motor torque sampled at the strictly increasing
/// times `t`, over the samples in `window = (t_start, t_end)` (None: all), as a dict.
#[pyfunction]
#[pyo3(signature = (t, omega_bit, motor_torque=None, *, window=None, stick_speed=core::metrics::STICK_SPEED))]
pub(crate) fn stick_slip_metrics<'py>(
    py: Python<'py>,
    t: PyReadonlyArray1<'py, f64>,
    omega_bit: PyReadonlyArray1<'py, f64>,
    motor_torque: Option<PyReadonlyArray1<'py, f64>>,
    window: Option<(f64, f64)>,
    stick_speed: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let (t, omega) = (to_vec(&t), to_vec(&omega_bit));
    let torque = motor_torque.map(|m| to_vec(&m));
    let m = no_panic(|| core::metrics::stick_slip(&t, &omega, torque.as_deref(), window, stick_speed))?
        .map_err(|e| validation_error(py, e))?;
    to_python(py, &stick_slip_report(Some(&m), Report::Series))
}

/// The static break-off torque of a well, N m: the trapezoidal integral of the friction limit
/// per metre `limit` (N m/m) over the strictly increasing measured depths `depth` (m).
#[pyfunction]
pub(crate) fn break_off_torque(
    py: Python<'_>,
    depth: PyReadonlyArray1<'_, f64>,
    limit: PyReadonlyArray1<'_, f64>,
) -> PyResult<f64> {
    let (depth, limit) = (to_vec(&depth), to_vec(&limit));
    no_panic(|| core::metrics::break_off_torque(&depth, &limit))?.map_err(|e| validation_error(py, e))
}
