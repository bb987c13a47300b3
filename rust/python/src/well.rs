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

/// The implied friction factors of measured points.
#[derive(serde::Serialize)]
struct Implied {
    friction_factor: Vec<f64>,
    #[serde(serialize_with = "drillstring_core::solution::serialize_list")]
    reason: Vec<String>,
}

/// For each measured point (bit depth `depths[k]`, m; operation `operations[k]`, a name of
/// the torque and drag's profiles; the hook load `hook_loads[k]`, N, and the surface torque
/// `torques[k]`, N m, NaN where not measured), the friction factor in [0, 1] that reproduces
/// it (`friction_factor`, NaN where none does) and why none does (`reason`, empty otherwise).
#[pyfunction]
pub(crate) fn well_implied_friction<'py>(
    py: Python<'py>,
    config_json: &str,
    depths: Vec<f64>,
    operations: Vec<String>,
    hook_loads: Vec<f64>,
    torques: Vec<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    use drillstring_core::well::torque_drag::Operation;
    let cfg = parse(py, config_json)?;
    let given = |x: f64| if x.is_nan() { None } else { Some(x) };
    let out = py
        .detach(|| {
            no_panic(|| -> drillstring_core::Result<Implied> {
                let traj = well::trajectory(&cfg)?;
                let mut out = Implied { friction_factor: Vec::new(), reason: Vec::new() };
                for (k, name) in operations.iter().enumerate() {
                    let op = Operation::ALL.iter().copied().find(|o| o.name() == name).ok_or_else(|| {
                        drillstring_core::Error::invalid(
                            format!("operations[{k}]"),
                            format!("{name:?}"),
                            "one of pickup, slackoff, rotating, rotating_on_bottom, sliding",
                        )
                    })?;
                    let (h, t) = (hook_loads.get(k).copied().and_then(given), torques.get(k).copied().and_then(given));
                    match well::implied_friction(&cfg, &traj, depths.get(k).copied().unwrap_or(f64::NAN), op, h, t) {
                        Ok(mu) => {
                            out.friction_factor.push(mu);
                            out.reason.push(String::new());
                        }
                        Err(why) => {
                            out.friction_factor.push(f64::NAN);
                            out.reason.push(why);
                        }
                    }
                }
                Ok(out)
            })
        })?
        .map_err(|e| validation_error(py, e))?;
    to_python(py, &out)
}
