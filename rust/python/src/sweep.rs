//! Bindings of the batch solve of a parameter sweep (`drillstring.sweep`).

use drillstring_core as core;
use drillstring_core::integrators::{Method, SolveOptions};
use drillstring_core::sweep::{self, GalerkinIntegrals, RunSpec, SweepOptions};
use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use serde::Serialize;

use crate::convert::{integer, no_panic, reshape, to_dict, to_python, to_vec, validation_error, SignalCheck};

fn invalid(py: Python<'_>, field: &str, value: impl std::fmt::Display, allowed: impl Into<String>) -> PyErr {
    validation_error(py, core::Error::invalid(field, value, allowed))
}

/// Mode numbers / positions as `u32`.
fn to_u32(py: Python<'_>, field: &str, values: impl Iterator<Item = i64>) -> PyResult<Vec<u32>> {
    values
        .enumerate()
        .map(|(j, v)| u32::try_from(v).map_err(|_| invalid(py, &format!("{field}[{j}]"), v, "a non-negative integer")))
        .collect()
}

/// The dimensionless integrals of `drillstring.galerkin.GalerkinIntegrals` from its arrays.
fn integrals_from_arrays(
    py: Python<'_>,
    indices: &PyReadonlyArray1<'_, i64>,
    quartic_index: &PyReadonlyArray2<'_, i64>,
    cos4: &PyReadonlyArray1<'_, f64>,
    mixed: &PyReadonlyArray1<'_, f64>,
    sin4: &PyReadonlyArray1<'_, f64>,
) -> PyResult<GalerkinIntegrals> {
    let idx = quartic_index.as_array();
    if idx.ncols() != 4 {
        return Err(invalid(py, "quartic_index", format!("shape {:?}", idx.shape()), "shape (T, 4)"));
    }
    let flat = to_u32(py, "quartic_index", idx.iter().copied())?;
    let quads = flat.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
    GalerkinIntegrals::new(
        to_u32(py, "indices", indices.as_array().iter().copied())?,
        quads,
        to_vec(cos4),
        to_vec(mixed),
        to_vec(sin4),
    )
    .map_err(|e| validation_error(py, e))
}

/// The modal system of a Galerkin model as the batch solve builds it for each run: the
/// integrals scaled by `k` (6,) = k1..k6 and `length`. Returns a dict of `mass`, `stiffness`
/// (m,) and `quartic_coef` (T,) in the order of `quartic_index` (`drillstring.galerkin.project`
/// builds every single-solve model with it).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn scale_integrals<'py>(
    py: Python<'py>,
    k: PyReadonlyArray1<'py, f64>,
    length: f64,
    indices: PyReadonlyArray1<'py, i64>,
    quartic_index: PyReadonlyArray2<'py, i64>,
    cos4: PyReadonlyArray1<'py, f64>,
    mixed: PyReadonlyArray1<'py, f64>,
    sin4: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let integrals = integrals_from_arrays(py, &indices, &quartic_index, &cos4, &mixed, &sin4)?;
    let k = to_vec(&k);
    let k: [f64; 6] =
        k.try_into().map_err(|k: Vec<f64>| invalid(py, "k", format!("length {}", k.len()), "length 6"))?;
    let (mass, stiffness, terms) = drillstring_core::terms::ModelTerms::from_coefficients(k)
        .and_then(|model| integrals.coefficients(&model, length))
        .map_err(|e| validation_error(py, e))?;
    let quartic_coef: Vec<f64> = terms.iter().map(|t| t.coef).collect();
    to_python(py, &ScaledSystem { mass, stiffness, quartic_coef })
}

/// What `scale_integrals` returns.
#[derive(Serialize)]
struct ScaledSystem {
    mass: Vec<f64>,
    stiffness: Vec<f64>,
    quartic_coef: Vec<f64>,
}

/// What `batch_plan` returns.
#[derive(Serialize)]
struct BatchPlan {
    threads: usize,
    bytes: u64,
}

fn threads_allowed() -> String {
    format!("an integer in 1..={} (or None for all cores)", sweep::MAX_THREADS)
}

/// Checks a planned batch before any work: `threads` (1..=`MAX_THREADS`, or None for every
/// core) and the memory `runs` runs of `modes` coordinates with `samples` samples would need
/// against `memory_budget` bytes. Returns `{"threads": resolved count, "bytes": the estimate}`;
/// raises ValidationError naming `threads` or `samples`.
#[pyfunction]
#[pyo3(signature = (modes, samples, runs, threads=None, keep_trajectories=false, memory_budget=None))]
pub(crate) fn batch_plan<'py>(
    py: Python<'py>,
    modes: usize,
    samples: &Bound<'py, PyAny>,
    runs: usize,
    threads: Option<&Bound<'py, PyAny>>,
    keep_trajectories: bool,
    memory_budget: Option<u64>,
) -> PyResult<Bound<'py, PyAny>> {
    let samples: usize = integer(py, "samples", samples, "an integer >= 4")?;
    let threads: Option<usize> = match threads {
        Some(t) if !t.is_none() => Some(integer(py, "threads", t, &threads_allowed())?),
        _ => None,
    };
    let threads = sweep::resolve_threads(threads).map_err(|e| validation_error(py, e))?;
    let opts = SweepOptions {
        solve: SolveOptions::new(Method::Dop853),
        t_end: 1.0,
        samples,
        keep_trajectories,
        memory_budget,
    };
    opts.check_memory(modes, runs, threads).map_err(|e| validation_error(py, e))?;
    to_python(py, &BatchPlan { threads, bytes: opts.memory_bytes(modes, runs, threads) })
}

/// Solves `R` runs of one Galerkin basis in parallel (GIL released) and returns columns.
///
/// Inputs: `k` (R, 6) = k1..k6, `length` (R,), `initial_velocities` (R, m) = qdot(0) per
/// retained coordinate, `z` (R,); the dimensionless integrals of the basis (`indices` (m,),
/// `quartic_index` (T, 4), `cos4`, `mixed`, `sin4` (T,)); the shared solver options;
/// `damping_rate` (R,), the viscous damping rate of each run (None: all 0, undamped). With
/// damping `energy_drift` is the error of the energy balance `H + dissipated - H(0)`.
///
/// Returns a dict: `status`, `message` (lists of str), `max_theta`, `rms_theta`,
/// `dominant_frequency_hz`, `energy_drift` (R,) float (NaN unless successful),
/// `unstable_modes` (R,) int (-1 for an invalid run), `nfev` (R,) int, `max_share` (R, m);
/// with `keep_trajectories`, also `t` (S,), `y` (R, S, 2m) and `theta` (R, S), NaN past the
/// end of a run that stopped early.
///
/// Ctrl-C (an exception raised by a Python signal handler) stops the runs under way within a
/// few tens of ms; the dict is still returned, with status `"interrupted"` for the runs that
/// did not finish, and the exception under `"interrupt"` (None otherwise) for the caller to
/// raise once it has kept the finished runs.
#[pyfunction]
#[pyo3(signature = (k, length, initial_velocities, z, indices, quartic_index, cos4, mixed, sin4, t_end, samples, method, rtol, atol, dt=None, max_steps=None, first_step=None, max_step=f64::INFINITY, keep_trajectories=false, threads=None, memory_budget=None, damping_rate=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn batch_solve<'py>(
    py: Python<'py>,
    k: PyReadonlyArray2<'py, f64>,
    length: PyReadonlyArray1<'py, f64>,
    initial_velocities: PyReadonlyArray2<'py, f64>,
    z: PyReadonlyArray1<'py, f64>,
    indices: PyReadonlyArray1<'py, i64>,
    quartic_index: PyReadonlyArray2<'py, i64>,
    cos4: PyReadonlyArray1<'py, f64>,
    mixed: PyReadonlyArray1<'py, f64>,
    sin4: PyReadonlyArray1<'py, f64>,
    t_end: f64,
    samples: usize,
    method: &str,
    rtol: f64,
    atol: f64,
    dt: Option<f64>,
    max_steps: Option<u64>,
    first_step: Option<f64>,
    max_step: f64,
    keep_trajectories: bool,
    threads: Option<usize>,
    memory_budget: Option<u64>,
    damping_rate: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let method = Method::parse(method).map_err(|e| validation_error(py, e))?;
    let opts = SweepOptions {
        solve: SolveOptions { method, rtol, atol, dt, max_steps, first_step, max_step },
        t_end,
        samples,
        keep_trajectories,
        memory_budget,
    };
    let integrals = integrals_from_arrays(py, &indices, &quartic_index, &cos4, &mixed, &sin4)?;
    let m = integrals.modes();

    let (k, length, c, z) = (k.as_array(), length.as_array(), initial_velocities.as_array(), z.as_array());
    let r = length.len();
    if k.shape() != [r, 6] || c.shape() != [r, m] || z.len() != r {
        return Err(invalid(
            py,
            "runs",
            format!(
                "k {:?}, length {:?}, initial_velocities {:?}, z {:?}",
                k.shape(),
                length.shape(),
                c.shape(),
                z.shape()
            ),
            format!("k (R, 6), length (R,), initial_velocities (R, {m}), z (R,) for one R"),
        ));
    }
    let damping = match &damping_rate {
        Some(c) => to_vec(c),
        None => vec![0.0; r],
    };
    if damping.len() != r {
        return Err(invalid(
            py,
            "damping_rate",
            format!("length {}", damping.len()),
            format!("length {r} (one per run)"),
        ));
    }
    let runs: Vec<RunSpec> = (0..r)
        .map(|i| RunSpec {
            k: [k[(i, 0)], k[(i, 1)], k[(i, 2)], k[(i, 3)], k[(i, 4)], k[(i, 5)]],
            length: length[i],
            initial_velocities: c.row(i).to_vec(),
            z: z[i],
            damping_rate: damping[i],
        })
        .collect();
    let signals = SignalCheck::new(py);
    let solved = py.detach(|| no_panic(|| sweep::batch_solve_with(&integrals, &runs, &opts, threads, &signals)))?;
    let records = solved.map_err(|e| validation_error(py, e))?;

    let interrupt = signals.finish().err().map(|e| e.into_value(py));
    let s = samples;
    let columns = sweep::batch::BatchColumns::new(&records, m, keep_trajectories.then(|| opts.times()));
    let out = to_dict(py, &columns)?;
    out.set_item("interrupt", interrupt)?;
    reshape(&out, "max_share", [r, m])?;
    reshape(&out, "y", [r, s, 2 * m])?;
    reshape(&out, "theta", [r, s])?;
    Ok(out)
}
