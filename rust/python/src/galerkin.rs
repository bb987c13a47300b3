//! Bindings of the exact dimensionless Galerkin integrals (`drillstring_core::galerkin`).

use drillstring_core::galerkin;
use drillstring_core::terms::Boundary;
use pyo3::prelude::*;

use crate::convert::{no_panic, to_python, validation_error};

/// The dimensionless quartic integrals of the free-end basis `cos(i pi s)` with `modes` elastic
/// modes and the rigid mode first if `rigid_mode`: a dict of `indices` (m,) and `quartic_index`
/// (T, 4) (int64), `cos4`, `mixed`, `sin4` (T,). Generated without the GIL.
#[pyfunction]
pub(crate) fn galerkin_integrals(py: Python<'_>, modes: u32, rigid_mode: bool) -> PyResult<Bound<'_, PyAny>> {
    let g = py
        .detach(|| no_panic(|| galerkin::integrals(Boundary::Free, modes, rigid_mode)))?
        .map_err(|e| validation_error(py, e))?;
    to_python(py, &g)
}
