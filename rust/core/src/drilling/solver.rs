//! The drilling system's entry points: [`solve`] a configuration, its [`friction_profile`], the
//! run's warnings. The time stepping (fields, kernels, boundaries, sources, controllers,
//! sampling, energy ledger, run loop) is the engine of [`super::engine`].

use serde::Serialize;

use crate::error::Result;
use crate::interrupt::Interrupt;

use super::config::DrillConfig;
use super::grid::{breakoff_torque, static_torque, Grid};

pub use super::engine::{DrillRun, DrillStats, EnergyBalance, Simulation, RUNAWAY_FACTOR};

/// The friction profile of a configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrictionProfile {
    /// Cell centres, m.
    pub z: Vec<f64>,
    /// Static friction limit per metre, N m/m.
    pub limit_per_m: Vec<f64>,
    /// Static friction torque of the string below each cell centre (from the bit up), N m.
    pub cumulative: Vec<f64>,
    /// The integral of the limit over the string, N m.
    pub breakoff_torque: f64,
    /// The bit's static torque (on bottom; 0 off bottom), N m ([`super::grid::bit_static_torque`]).
    pub bit_static_torque: f64,
    /// The static torque the motor must exceed to break the string free: `breakoff_torque` plus
    /// `bit_static_torque`, N m ([`static_torque`]).
    pub static_torque: f64,
    /// The static torque the string holds at each cell centre at break-off: `cumulative` plus
    /// `bit_static_torque` (the bit's torque is carried along the whole string), N m.
    pub holding: Vec<f64>,
    /// The well at the cell centres (minimum curvature): inclination and azimuth, degrees,
    /// true vertical depth, m, and the curvature as a dogleg severity, degrees per 30 m.
    pub inclination_deg: Vec<f64>,
    pub azimuth_deg: Vec<f64>,
    pub tvd: Vec<f64>,
    pub dls_deg_per_30m: Vec<f64>,
    /// The static friction factor at the cell centres (`friction.static` or an interval's).
    pub friction_factor: Vec<f64>,
}

/// The friction profile at the cell centres and the break-off torque of a valid configuration.
pub fn friction_profile(cfg: &DrillConfig) -> Result<FrictionProfile> {
    cfg.validate()?;
    let grid = Grid::new(cfg)?;
    let n = grid.cells();
    let mut cumulative = vec![0.0; n];
    let mut below = 0.0;
    for j in (0..n).rev() {
        let piece = grid.limit[j] * grid.spacing[grid.section_of[j]];
        cumulative[j] = below + 0.5 * piece;
        below += piece;
    }
    let traj = super::well::trajectory(cfg)?;
    let points: Vec<_> = grid.z.iter().map(|&z| traj.at(z)).collect();
    let breakoff = breakoff_torque(cfg)?;
    let bit = super::grid::bit_static_torque(cfg);
    Ok(FrictionProfile {
        inclination_deg: points.iter().map(|p| p.inc.to_degrees()).collect(),
        azimuth_deg: points.iter().map(|p| p.azi.to_degrees()).collect(),
        tvd: points.iter().map(|p| p.position[2]).collect(),
        dls_deg_per_30m: points.iter().map(|p| p.curvature.to_degrees() * 30.0).collect(),
        friction_factor: grid.z.iter().map(|&z| super::well::friction_factor(cfg, z)).collect(),
        z: grid.z,
        limit_per_m: grid.limit,
        holding: cumulative.iter().map(|c| c + bit).collect(),
        cumulative,
        breakoff_torque: breakoff,
        bit_static_torque: bit,
        static_torque: static_torque(cfg, breakoff),
    })
}

/// Runs a configuration (validated first) from rest; see [`Simulation`].
pub fn solve(cfg: &DrillConfig, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> Result<DrillRun> {
    Ok(Simulation::new(cfg)?.run(interrupt, progress))
}
