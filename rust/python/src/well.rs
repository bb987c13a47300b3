//! Bindings of the well and its torque and drag (`drillstring_core::drilling::well`): a
//! drilling configuration (JSON) in, dicts of numpy arrays and floats out.

use drillstring_core::drilling::{well, DrillConfig};
use drillstring_core::well::torque_drag::Operation;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{no_panic, validation_error};

fn parse(py: Python<'_>, config_json: &str) -> PyResult<DrillConfig> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
    cfg.validate().map_err(|e| validation_error(py, e))?;
    Ok(cfg)
}

/// The survey stations and their minimum-curvature trajectory: `md` (m), `inc_deg`,
/// `azi_deg`, `north`, `east`, `tvd` (m), `dls_deg_per_30m` (of the interval ending at each
/// station).
#[pyfunction]
pub(crate) fn well_trajectory<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyDict>> {
    let cfg = parse(py, config_json)?;
    let traj = py.detach(|| no_panic(|| well::trajectory(&cfg)))?.map_err(|e| validation_error(py, e))?;
    let d = PyDict::new(py);
    let column = |k: usize| traj.position.iter().map(|p| p[k]).collect::<Vec<f64>>();
    d.set_item("md", PyArray1::from_slice(py, &traj.survey.md))?;
    d.set_item("inc_deg", PyArray1::from_slice(py, &traj.survey.inc_deg))?;
    d.set_item("azi_deg", PyArray1::from_slice(py, &traj.survey.azi_deg))?;
    d.set_item("north", PyArray1::from_vec(py, column(0)))?;
    d.set_item("east", PyArray1::from_vec(py, column(1)))?;
    d.set_item("tvd", PyArray1::from_vec(py, column(2)))?;
    d.set_item("dls_deg_per_30m", PyArray1::from_vec(py, traj.dls_deg_per_30m()))?;
    Ok(d)
}

/// The static soft-string torque and drag of the configuration's string: the summary
/// (`hook_load_pickup_N`, ..., `max_normal_force_N_per_m`, `max_normal_force_md`,
/// `max_normal_force_operation`), `profiles` (per operation: `md`, `tension_N`, `torque_Nm`,
/// `normal_force_N_per_m`) and `broomstick` (`depth_m`, `friction_factors`, and per friction
/// factor the `pickup`, `slackoff` and `rotating` hook loads, N, as 2-D arrays
/// `[factor, depth]`).
#[pyfunction]
pub(crate) fn well_torque_drag<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyDict>> {
    let cfg = parse(py, config_json)?;
    let (td, broom) = py
        .detach(|| no_panic(|| well::torque_drag(&cfg).and_then(|td| Ok((td, well::broomstick(&cfg)?)))))?
        .map_err(|e| validation_error(py, e))?;
    let d = PyDict::new(py);
    d.set_item("hook_load_pickup_N", td.hook_load_pickup_n)?;
    d.set_item("hook_load_slackoff_N", td.hook_load_slackoff_n)?;
    d.set_item("hook_load_rotating_N", td.hook_load_rotating_n)?;
    d.set_item("hook_load_rotating_on_bottom_N", td.hook_load_rotating_on_bottom_n)?;
    d.set_item("surface_torque_off_bottom_Nm", td.surface_torque_off_bottom_nm)?;
    d.set_item("surface_torque_on_bottom_Nm", td.surface_torque_on_bottom_nm)?;
    d.set_item("max_normal_force_N_per_m", td.max_normal_force_n_per_m)?;
    d.set_item("max_normal_force_md", td.max_normal_force_md)?;
    d.set_item("max_normal_force_operation", td.max_normal_force_operation)?;
    let profiles = PyDict::new(py);
    for (op, p) in Operation::ALL.iter().zip(td.profiles) {
        let one = PyDict::new(py);
        one.set_item("md", PyArray1::from_vec(py, p.md))?;
        one.set_item("tension_N", PyArray1::from_vec(py, p.tension))?;
        one.set_item("torque_Nm", PyArray1::from_vec(py, p.torque))?;
        one.set_item("normal_force_N_per_m", PyArray1::from_vec(py, p.normal_force))?;
        profiles.set_item(op.name(), one)?;
    }
    d.set_item("profiles", profiles)?;
    let b = PyDict::new(py);
    let n = broom.depths.len();
    b.set_item("depth_m", PyArray1::from_vec(py, broom.depths))?;
    b.set_item("friction_factors", PyArray1::from_slice(py, &broom.friction_factors))?;
    for (k, name) in ["pickup", "slackoff", "rotating"].iter().enumerate() {
        let flat: Vec<f64> = broom.hook_loads.iter().flat_map(|row| row.iter().map(move |r| r[k])).collect();
        let rows = broom.friction_factors.len();
        let array = PyArray1::from_vec(py, flat).reshape([rows, n])?;
        b.set_item(*name, array)?;
    }
    d.set_item("broomstick", b)?;
    Ok(d)
}
