//! Bindings of the method-of-lines PDE system and its solve.

use drillstring_core as core;
use drillstring_core::pde::{PdeCoefficients, PdeSystem as CorePdeSystem};
use drillstring_core::SecondOrderSystem;
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::convert::{integer, no_panic, solve_binding, to_vec, validation_error};

/// The torsion PDE discretised on `nodes` grid points `z_j = j l / (nodes - 1)` (lumped-mass
/// linear finite elements: the discrete energy `H_h` is conserved by the semi-discrete system).
#[pyclass(frozen, module = "drillstring._core")]
pub(crate) struct PdeSystem {
    inner: CorePdeSystem,
}

#[pymethods]
impl PdeSystem {
    #[new]
    #[pyo3(signature = (k1, k2, k3, k4, k5, k6, length, nodes, damping_rate=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        k1: f64,
        k2: f64,
        k3: f64,
        k4: f64,
        k5: f64,
        k6: f64,
        length: f64,
        nodes: &Bound<'_, PyAny>,
        damping_rate: f64,
    ) -> PyResult<Self> {
        let allowed = format!("an integer in 3..={}", core::pde::MAX_NODES);
        let nodes: usize = integer(py, "nodes", nodes, &allowed)?;
        let k = PdeCoefficients { k1, k2, k3, k4, k5, k6 };
        let inner = CorePdeSystem::new(k, length, nodes)
            .and_then(|sys| sys.with_damping(damping_rate))
            .map_err(|e| validation_error(py, e))?;
        Ok(PdeSystem { inner })
    }

    /// Number of grid nodes `N` (the unknowns `theta(z_j)`).
    #[getter]
    fn nodes(&self) -> usize {
        self.inner.nodes()
    }

    /// The string length `l`.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }

    /// The node spacing `h = l / (N - 1)`.
    #[getter]
    fn spacing(&self) -> f64 {
        self.inner.spacing()
    }

    /// The viscous damping rate `c` (1/s): force `-k1 c theta_t` per unit length.
    #[getter]
    fn damping_rate(&self) -> f64 {
        self.inner.damping_rate()
    }

    /// Whether the forces depend on the velocity (damping), see `resolve_method`.
    #[getter]
    fn velocity_dependent(&self) -> bool {
        drillstring_core::SecondOrderSystem::velocity_dependent(&self.inner)
    }

    /// `(k1, k2, k3, k4, k5, k6)`.
    #[getter]
    fn coefficients(&self) -> (f64, f64, f64, f64, f64, f64) {
        let [k1, k2, k3, k4, k5, k6] = self.inner.coefficients().to_array();
        (k1, k2, k3, k4, k5, k6)
    }

    /// Node positions `z_j`, shape (N,).
    #[getter]
    fn z<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.positions())
    }

    /// Trapezoid node weights `w_j` (`h/2` at the ends, `h` inside), shape (N,).
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.weights())
    }

    /// Accelerations `theta_j'' = -(dV_h/dtheta_j) / (w_j k1)` at one state `q` (shape (N,)),
    /// without the damping term.
    fn acceleration<'py>(&self, py: Python<'py>, q: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        self.check_len(py, "q", q.len())?;
        let mut acc = vec![0.0; q.len()];
        no_panic(|| self.inner.acceleration(&q, &mut acc))?;
        Ok(PyArray1::from_vec(py, acc))
    }

    /// The discrete energy `H_h` of each sample: `q` and `qdot` of shape (N, samples).
    fn energy<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qdot: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (q, v) = (q.as_array(), qdot.as_array());
        let n = self.inner.nodes();
        if q.nrows() != n || v.shape() != q.shape() {
            return Err(validation_error(
                py,
                core::Error::invalid(
                    "q",
                    format!("shapes {:?} and {:?}", q.shape(), v.shape()),
                    format!("q and qdot of equal shape ({n}, samples)"),
                ),
            ));
        }
        let (q, v): (Vec<f64>, Vec<f64>) = (q.iter().copied().collect(), v.iter().copied().collect());
        let out =
            no_panic(|| core::system::energy_history(&self.inner, &q, &v))?.map_err(|e| validation_error(py, e))?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// Nodal velocities `sum_i c[i-1] cos(i pi z_j / l)` of modal amplitudes `c` (mode 1 first).
    fn initial_velocity_from_modes<'py>(
        &self,
        py: Python<'py>,
        c: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let c = to_vec(&c);
        let v = no_panic(|| self.inner.initial_velocity_from_modes(&c))?;
        Ok(PyArray1::from_vec(py, v))
    }

    /// The lowest `count` squared linear frequencies `w^2` (ascending; the first, `-k6/k1`, is
    /// the uniform twist). Costs `O(N^2)`; runs without the GIL.
    fn linear_frequencies_squared<'py>(
        &self,
        py: Python<'py>,
        count: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let nodes = self.inner.nodes();
        let count: usize = integer(py, "count", count, &format!("an integer in 1..={nodes} (the number of nodes)"))?;
        let sys = &self.inner;
        let w2 = py.detach(|| no_panic(|| sys.linear_frequencies_squared(count)))?;
        Ok(PyArray1::from_vec(py, w2.map_err(|e| validation_error(py, e))?))
    }

    /// The default step of the fixed-step methods: half the CFL limit `h / c`, s.
    fn default_dt(&self) -> f64 {
        self.inner.default_dt()
    }

    /// The mode the default output times resolve, `(i, w_i in rad/s)`: the highest cosine mode
    /// of the initial nodal `twist` and `velocity` (at least mode 3).
    fn fastest_mode(
        &self,
        py: Python<'_>,
        twist: PyReadonlyArray1<'_, f64>,
        velocity: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<(usize, f64)> {
        let (q, v) = (to_vec(&twist), to_vec(&velocity));
        let sys = &self.inner;
        py.detach(|| no_panic(|| sys.fastest_mode(&q, &v)))?.map_err(|e| validation_error(py, e))
    }

    fn __repr__(&self) -> String {
        format!("PdeSystem(nodes={}, length={})", self.inner.nodes(), self.inner.length())
    }
}

impl PdeSystem {
    fn check_len(&self, py: Python<'_>, field: &str, len: usize) -> PyResult<()> {
        let n = self.inner.nodes();
        if len != n {
            return Err(validation_error(
                py,
                core::Error::invalid(field, format!("length {len}"), format!("length {n} (the number of nodes)")),
            ));
        }
        Ok(())
    }
}

solve_binding! {
    /// Integrates the PDE system from nodal `(q0, v0) = (theta, theta_t)(z_j, 0)` to `t_end`.
    ///
    /// Returns a dict with `t` (samples,), `y` (samples, 2N) holding `[theta, theta_t]` at the
    /// nodes, `status`, `message`, `nfev`, `naccept`, `nreject`, `dissipated` (samples,) (the
    /// energy the damping took out, None without damping). `t_eval=None` samples every step. Any
    /// method (`"dop853"`, `"dopri5"`, `"rkn12"`, `"rk4"`, `"central"`, `"verlet"`, or `"auto"`,
    /// see `resolve_method`; with damping only `"dop853"`, `"dopri5"`, `"rk4"` and `"auto"`); the
    /// fixed-step ones need `dt`.
    ///
    /// Runs without the GIL; Ctrl-C (any exception raised by a Python signal handler) stops it
    /// within ~20 ms and is raised here.
    solve_pde,
    PdeSystem
}
