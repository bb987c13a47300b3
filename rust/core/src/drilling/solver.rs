//! The drilling system's entry points: [`solve`] a configuration, its [`friction_profile`], the
//! run's warnings. The time stepping (fields, kernels, boundaries, sources, controllers,
//! sampling, energy ledger, run loop) is the engine of [`super::engine`].

use serde::Serialize;

use crate::error::{Num, Result};
use crate::interrupt::Interrupt;

use super::config::DrillConfig;
use super::grid::{breakoff_torque, static_torque, Grid};

pub use super::engine::{DrillRun, DrillStats, EnergyBalance, Simulation, RUNAWAY_FACTOR};

/// The friction profile of a configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Profile {
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
pub fn friction_profile(cfg: &DrillConfig) -> Result<Profile> {
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
    Ok(Profile {
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

/// The warnings of a configuration with the wall break-off torque `breakoff` (see
/// [`DrillRun::warnings`]).
pub(crate) fn run_warnings(cfg: &DrillConfig, breakoff: f64) -> Vec<String> {
    let mut out = Vec::new();
    let needed = static_torque(cfg, breakoff);
    let limit = cfg.top_drive.torque_limit;
    if limit < needed {
        out.push(format!(
            "top_drive.torque_limit = {} N m is below the static torque of the string, {} N m (the wall's \
             break-off torque{}): the motor may never break it free",
            Num(limit),
            Num(needed),
            if needed > breakoff { " and the bit's" } else { "" }
        ));
    }
    out.extend(plausibility_warnings(cfg));
    out
}

/// Drilling practice's ranges, beyond which a value is more likely a mistake (a unit, a digit)
/// than a well: the bound, the field and the likely mistake.
pub const PLAUSIBLE_OUTER_DIAMETER: f64 = 1.0;
pub const PLAUSIBLE_BIT_RADIUS: f64 = 0.25;
pub const PLAUSIBLE_STRING_LENGTH: f64 = 15_000.0;
pub const PLAUSIBLE_RPM: f64 = 400.0;

/// Warnings (not errors) for values far outside drilling practice: a pipe over
/// [`PLAUSIBLE_OUTER_DIAMETER`] m across, a bit over 2 [`PLAUSIBLE_BIT_RADIUS`] m, a string
/// longer than [`PLAUSIBLE_STRING_LENGTH`] m, a top-drive speed over [`PLAUSIBLE_RPM`] rpm.
pub fn plausibility_warnings(cfg: &DrillConfig) -> Vec<String> {
    let mut out = Vec::new();
    for (i, s) in cfg.sections.iter().enumerate() {
        if s.outer_diameter > PLAUSIBLE_OUTER_DIAMETER {
            out.push(format!(
                "sections[{i}].outer_diameter = {} m is over {} m: a diameter in mm or inches? (the configuration is in m)",
                Num(s.outer_diameter),
                Num(PLAUSIBLE_OUTER_DIAMETER)
            ));
        }
    }
    if cfg.bit.radius > PLAUSIBLE_BIT_RADIUS {
        out.push(format!(
            "bit.radius = {} m is a bit over {} m across: a diameter or inches? (bit.radius is half the diameter, in m)",
            Num(cfg.bit.radius),
            Num(2.0 * PLAUSIBLE_BIT_RADIUS)
        ));
    }
    let length: f64 = cfg.sections.iter().map(|s| s.length).sum();
    if length > PLAUSIBLE_STRING_LENGTH {
        out.push(format!(
            "the string is {} m long, over the {} m of the deepest wells: a length in feet? (the configuration is in m)",
            Num(length),
            Num(PLAUSIBLE_STRING_LENGTH)
        ));
    }
    let rpm = std::iter::once(cfg.top_drive.rpm).chain(cfg.top_drive.steps.iter().map(|s| s[1]));
    if let Some(fast) = rpm.map(f64::abs).filter(|r| *r > PLAUSIBLE_RPM).reduce(f64::max) {
        out.push(format!(
            "a top-drive speed of {} rpm is over the {} rpm of top drives: rad/s or a digit too many? \
             (top_drive.rpm and top_drive.steps are in rpm)",
            Num(fast),
            Num(PLAUSIBLE_RPM)
        ));
    }
    out
}
