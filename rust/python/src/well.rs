//! Bindings of the well and its torque and drag (`drillstring_core::drilling::well`): a
//! drilling configuration (JSON) in, the core's tables out (through the one serializer).

use drillstring_core::drilling::{well, DrillConfig};
use pyo3::prelude::*;

use crate::convert::{no_panic, to_python, validation_error};

fn parse(py: Python<'_>, config_json: &str) -> PyResult<DrillConfig> {
    let cfg = DrillConfig::from_json(config_json).map_err(|e| validation_error(py, e))?;
    cfg.validate().map_err(|e| validation_error(py, e))?;
    Ok(cfg)
}

/// The survey stations and their minimum-curvature trajectory: `md` (m), `inc_deg`,
/// `azi_deg`, `north`, `east`, `tvd` (m), `dls_deg_per_30m` (of the interval ending at each
/// station).
#[pyfunction]
pub(crate) fn well_trajectory<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let cfg = parse(py, config_json)?;
    let table = py
        .detach(|| no_panic(|| well::trajectory(&cfg).map(|t| well::TrajectoryTable::new(&t))))?
        .map_err(|e| validation_error(py, e))?;
    to_python(py, &table)
}

/// The static soft-string torque and drag of the configuration's string: the summary
/// (`hook_load_pickup_N`, ..., `max_normal_force_N_per_m`, `max_normal_force_md`,
/// `max_normal_force_operation`), `profiles` (per operation: `md`, `tension_N`, `torque_Nm`,
/// `normal_force_N_per_m`) and `broomstick` (`depth_m`, `friction_factors`, and the `pickup`,
/// `slackoff` and `rotating` hook loads, N, as 2-D arrays `[factor, depth]`).
#[pyfunction]
pub(crate) fn well_torque_drag<'py>(py: Python<'py>, config_json: &str) -> PyResult<Bound<'py, PyAny>> {
    let cfg = parse(py, config_json)?;
    let report = py.detach(|| no_panic(|| well::report(&cfg)))?.map_err(|e| validation_error(py, e))?;
    to_python(py, &report)
}
