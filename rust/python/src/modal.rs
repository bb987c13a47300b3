//! Bindings of the modal Galerkin system and its solve.

use drillstring_core as core;
use drillstring_core::modal::{ModalSystem as CoreModalSystem, QuarticEvaluation, QuarticTerm};
use drillstring_core::SecondOrderSystem;
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::convert::{no_panic, solve_binding, to_vec, validation_error};

/// The quartic evaluation (`"terms"` or `"spectral"`) that `evaluation` (`"auto"`, `"terms"`
/// or `"spectral"`) means for a system of `modes` retained modes; a `ValidationError` naming
/// `"evaluation"` for another name.
#[pyfunction]
pub(crate) fn resolve_evaluation(py: Python<'_>, evaluation: &str, modes: usize) -> PyResult<&'static str> {
    let chosen = QuarticEvaluation::from_name(evaluation).map_err(|e| validation_error(py, e))?;
    Ok(chosen.resolve(modes).name())
}

/// The integration method a name selects (the core's `Method::resolve`): a method name as
/// given, or for `"auto"` `"rkn12"` when the forces do not depend on the velocity and
/// `rtol <= AUTO_RKN12_MAX_RTOL`, else `"dop853"`; a `ValidationError` naming `"method"` for
/// another name.
#[pyfunction]
pub(crate) fn resolve_method(
    py: Python<'_>,
    method: &str,
    velocity_dependent: bool,
    rtol: f64,
) -> PyResult<&'static str> {
    let chosen =
        core::integrators::Method::resolve(method, velocity_dependent, rtol).map_err(|e| validation_error(py, e))?;
    Ok(chosen.name())
}

/// The modal system `M q'' + K q + grad V(q) = 0` (diagonal M and K, quartic potential terms).
#[pyclass(frozen, module = "drillstring._core")]
pub(crate) struct ModalSystem {
    inner: CoreModalSystem,
}

#[pymethods]
impl ModalSystem {
    #[new]
    #[pyo3(signature = (mass, stiffness, quartic_index, quartic_coef, damping_rate=0.0))]
    fn new(
        py: Python<'_>,
        mass: PyReadonlyArray1<'_, f64>,
        stiffness: PyReadonlyArray1<'_, f64>,
        quartic_index: PyReadonlyArray2<'_, i64>,
        quartic_coef: PyReadonlyArray1<'_, f64>,
        damping_rate: f64,
    ) -> PyResult<Self> {
        let idx = quartic_index.as_array();
        let coef = quartic_coef.as_array();
        if idx.ncols() != 4 || idx.nrows() != coef.len() {
            return Err(validation_error(
                py,
                core::Error::invalid(
                    "quartic_index",
                    format!("shape {:?} with {} coefficients", idx.shape(), coef.len()),
                    "shape (T, 4) with T = len(quartic_coef)",
                ),
            ));
        }
        let mut terms = Vec::with_capacity(coef.len());
        for (t, row) in idx.outer_iter().enumerate() {
            let mut four = [0u32; 4];
            for (k, &i) in row.iter().enumerate() {
                four[k] = u32::try_from(i).map_err(|_| {
                    validation_error(
                        py,
                        core::Error::invalid(format!("quartic_index[{t}]"), i, "non-negative mode positions"),
                    )
                })?;
            }
            terms.push(QuarticTerm { idx: four, coef: coef[t] });
        }
        let inner = CoreModalSystem::new(to_vec(&mass), to_vec(&stiffness), terms)
            .and_then(|sys| sys.with_damping(damping_rate))
            .map_err(|e| validation_error(py, e))?;
        Ok(ModalSystem { inner })
    }

    /// The modal system of eq. 18 with `k = (k1, ..., k6)` on the cosine basis of the mode
    /// numbers `indices` (strictly increasing) of `[0, length]`, its quartic force and potential
    /// evaluated pseudo-spectrally (exact quadrature of the quartic density, O(n log n); no
    /// quartic coefficients). M and K are those of the term-sum system of the same model.
    #[staticmethod]
    #[pyo3(signature = (k, length, indices, damping_rate=0.0))]
    fn spectral(
        py: Python<'_>,
        k: PyReadonlyArray1<'_, f64>,
        length: f64,
        indices: PyReadonlyArray1<'_, i64>,
        damping_rate: f64,
    ) -> PyResult<Self> {
        let k = to_vec(&k);
        let k: [f64; 6] = k.try_into().map_err(|k: Vec<f64>| {
            validation_error(py, core::Error::invalid("k", format!("length {}", k.len()), "length 6"))
        })?;
        let mut modes = Vec::with_capacity(indices.len()?);
        for (p, &i) in indices.as_array().iter().enumerate() {
            modes.push(u32::try_from(i).map_err(|_| {
                validation_error(py, core::Error::invalid(format!("indices[{p}]"), i, "non-negative mode numbers"))
            })?);
        }
        let inner = core::terms::ModelTerms::from_coefficients(k)
            .and_then(|model| model.with_damping(damping_rate))
            .and_then(|model| core::sweep::discretise_spectral(&modes, &model, length))
            .map_err(|e| validation_error(py, e))?;
        Ok(ModalSystem { inner })
    }

    /// How the quartic force is evaluated: `"terms"` (the merged monomials of the quartic
    /// coefficients) or `"spectral"`.
    #[getter]
    fn evaluation(&self) -> &'static str {
        self.inner.evaluation().name()
    }

    /// Number of modal coordinates.
    #[getter]
    fn modes(&self) -> usize {
        self.inner.modes()
    }

    /// The viscous damping rate `c` (1/s): damping force `-c M qdot`.
    #[getter]
    fn damping_rate(&self) -> f64 {
        self.inner.damping_rate()
    }

    /// Whether the forces depend on the velocity (damping): then only `"dop853"`, `"dopri5"`
    /// and `"rk4"` apply, and `"auto"` is `"dop853"` ([`resolve_method`]).
    #[getter]
    fn velocity_dependent(&self) -> bool {
        self.inner.velocity_dependent()
    }

    /// Accelerations `q'' = -M^{-1} (K q + grad V(q))` at one state `q` (shape (m,)), without
    /// the damping term.
    fn acceleration<'py>(&self, py: Python<'py>, q: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        self.check_len(py, "q", q.len())?;
        let mut acc = vec![0.0; q.len()];
        no_panic(|| self.inner.acceleration(&q, &mut acc))?;
        Ok(PyArray1::from_vec(py, acc))
    }

    /// The cubic force `grad V(q)` at one state `q` (shape (m,)).
    fn quartic_gradient<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        self.check_len(py, "q", q.len())?;
        let mut force = vec![0.0; q.len()];
        no_panic(|| self.inner.quartic_gradient(&q, &mut force))?;
        Ok(PyArray1::from_vec(py, force))
    }

    /// The energy H of each sample: `q` and `qdot` of shape (m, samples).
    fn energy<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qdot: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (q, v) = (q.as_array(), qdot.as_array());
        let m = self.inner.modes();
        if q.nrows() != m || v.shape() != q.shape() {
            return Err(validation_error(
                py,
                core::Error::invalid(
                    "q",
                    format!("shapes {:?} and {:?}", q.shape(), v.shape()),
                    format!("q and qdot of equal shape ({m}, samples)"),
                ),
            ));
        }
        let (q, v): (Vec<f64>, Vec<f64>) = (q.iter().copied().collect(), v.iter().copied().collect());
        let out =
            no_panic(|| core::system::energy_history(&self.inner, &q, &v))?.map_err(|e| validation_error(py, e))?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// The quartic potential V of each sample: `q` of shape (m, samples).
    fn potential<'py>(&self, py: Python<'py>, q: PyReadonlyArray2<'py, f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = q.as_array();
        let m = self.inner.modes();
        if q.nrows() != m {
            return Err(validation_error(
                py,
                core::Error::invalid("q", format!("shape {:?}", q.shape()), format!("shape ({m}, samples)")),
            ));
        }
        let q: Vec<f64> = q.iter().copied().collect();
        let out =
            no_panic(|| core::system::potential_history(&self.inner, &q))?.map_err(|e| validation_error(py, e))?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// The quartic energy share `max_t |V(t)| / |H(0)|` of the samples `q` (m, samples) of a
    /// run whose first sample has the energy `energy0` (NaN when `energy0 == 0`).
    fn quartic_share<'py>(&self, py: Python<'py>, q: PyReadonlyArray2<'py, f64>, energy0: f64) -> PyResult<f64> {
        let q = q.as_array();
        let m = self.inner.modes();
        if q.nrows() != m {
            return Err(validation_error(
                py,
                core::Error::invalid("q", format!("shape {:?}", q.shape()), format!("shape ({m}, samples)")),
            ));
        }
        let q: Vec<f64> = q.iter().copied().collect();
        no_panic(|| core::metrics::quartic_share_of(&self.inner, &q, energy0))?.map_err(|e| validation_error(py, e))
    }
}

impl ModalSystem {
    fn check_len(&self, py: Python<'_>, field: &str, len: usize) -> PyResult<()> {
        let m = self.inner.modes();
        if len != m {
            return Err(validation_error(
                py,
                core::Error::invalid(field, format!("length {len}"), format!("length {m}")),
            ));
        }
        Ok(())
    }
}

solve_binding! {
    /// Integrates a modal system from `(q0, v0)` at `t = 0` to `t_end`.
    ///
    /// Returns a dict with `t` (samples,), `y` (samples, 2m) holding `[q, qdot]`, `status`,
    /// `message`, `nfev`, `naccept`, `nreject`, and `dissipated` (samples,), the energy the
    /// damping took out up to each sample (None without damping). `t_eval=None` samples every
    /// step. `method` is a name of `resolve_method` (`"auto"` is resolved here by the same rule).
    /// With damping only `"dop853"`, `"dopri5"`, `"rk4"` and `"auto"` apply.
    ///
    /// Runs without the GIL; Ctrl-C (any exception raised by a Python signal handler) stops it
    /// within ~20 ms and is raised here.
    solve_modal,
    ModalSystem
}
