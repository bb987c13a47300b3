//! Bindings of the exact dimensionless Galerkin integrals (`drillstring_core::galerkin`).

use drillstring_core::galerkin;
use drillstring_core::terms::Boundary;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{no_panic, validation_error};

/// The dimensionless quartic integrals of the free-end basis `cos(i pi s)` with `modes` elastic
/// modes and the rigid mode first if `rigid_mode`: a dict of `indices` (m,) and `quartic_index`
/// (T, 4) (int64), `cos4`, `mixed`, `sin4` (T,). Generated without the GIL.
#[pyfunction]
pub(crate) fn galerkin_integrals(py: Python<'_>, modes: u32, rigid_mode: bool) -> PyResult<Bound<'_, PyDict>> {
    let g = py
        .detach(|| no_panic(|| galerkin::integrals(Boundary::Free, modes, rigid_mode)))?
        .map_err(|e| validation_error(py, e))?;
    let terms = g.quartic_index.len();
    let out = PyDict::new(py);
    out.set_item("indices", PyArray1::from_vec(py, g.indices.iter().map(|&i| i64::from(i)).collect()))?;
    let flat: Vec<i64> = g.quartic_index.iter().flat_map(|q| q.map(i64::from)).collect();
    out.set_item("quartic_index", PyArray1::from_vec(py, flat).reshape([terms, 4])?)?;
    out.set_item("cos4", PyArray1::from_vec(py, g.cos4))?;
    out.set_item("mixed", PyArray1::from_vec(py, g.mixed))?;
    out.set_item("sin4", PyArray1::from_vec(py, g.sin4))?;
    Ok(out)
}
