//! Where a run starts (`numerics.initial_state`): at rest (the default), or in the bit law's
//! steady drilling state, where Aarsnes & van de Wouw's published code starts its coupled runs.
//!
//! The steady drilling state of a coupled run ([`steady_point`], [`Wall`]): the string turns at
//! the top drive's setpoint everywhere and moves down at the rate of penetration `V` everywhere;
//! the bit cuts at the depth of cut per revolution `d = 2 pi V / Omega` with the weight and torque
//! of the Detournay law's steady state ([`DetournayBit::steady_state`]). The rate is the hoist's:
//! `velocity` its block speed, an autodriller on ROP its setpoint; with a weight imposed
//! (`weight_on_bit`, `hook_load` as the hanging string's hook load less it, an autodriller on
//! weight on bit) the law's rate at the weight that reaches the bit, the imposed one less the
//! wall's axial drag and the axial damping of the moving string (found by bisection: both grow
//! with the rate). The torque along the string is the torque on bit plus the wall's kinetic
//! friction torque and the viscous damping torque below each point; the axial force is the static
//! tension of the hanging string less the weight on bit, less the wall's axial drag and the axial
//! damping below each point (the wall's kinetic force `mu_k N` splits between the two by the
//! direction of the contact's sliding velocity `(V, r Omega)`, [`super::engine::coupled_friction`];
//! with `friction.coupling = "torsion_only"` all of it is torque). The top drive's controller holds
//! the top torque (its integral, or `z_torque`'s low-passed torque), the hoist its setpoint.
//!
//! The fields are set by `Simulation::new` ([`super::engine::Simulation`]) and
//! `Axial::set_steady`; the state is the continuum's, so the discrete scheme starts within a
//! cell's error of its own steady state and settles there or, where the steady state is
//! unstable, leaves it (which is what `--check-start` compares).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::axial::bitrock::{DetournayBit, SteadyDrilling};
use super::axial::hoist_mode::{rule, HoistReference, Steady};
use super::axial::section::AxialSection;
use super::config::DrillConfig;
use super::engine::bit_law::Law;
use super::grid::Grid;
use crate::error::{Error, Num, Result};

/// Where a run starts (`numerics.initial_state`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InitialState {
    /// At rest: no rotation, the string hanging under its static tension, the bit just touching
    /// flat rock; the setpoints ramp up from there.
    #[default]
    Rest,
    /// A coupled run's steady drilling state at the setpoints of `t = 0` (see the module).
    Steady,
}

/// The field of the refusals.
const FIELD: &str = "numerics.initial_state";

/// The wall's kinetic friction and the viscous damping along the torsional cells, for the
/// steady profiles.
#[derive(Debug, Clone)]
pub struct Wall {
    /// Per torsional cell: top and bottom measured depth, m; the kinetic friction force per
    /// length `mu_k N`, N/m; the contact radius, m; the damping torque per length and rad/s,
    /// `damping_rate rho J`, N m s/rad/m.
    cells: Vec<[f64; 5]>,
    /// Per section: top and bottom measured depth, m, and the damping force per length and m/s,
    /// `damping_rate rho A`, N s/m^2.
    sections: Vec<[f64; 3]>,
    /// `friction.coupling = "axial_torsional"`: the kinetic force splits by the sliding direction.
    coupled: bool,
}

impl Wall {
    /// The wall of `cfg`'s string on `grid` (`coupled`: the coupled wall friction of a coupled run).
    pub fn new(cfg: &DrillConfig, grid: &Grid, coupled: bool) -> Self {
        let kr = cfg.friction.kinetic_ratio;
        let cells = (0..grid.cells())
            .map(|j| {
                let p = &grid.props[grid.section_of[j]];
                let h = grid.spacing[grid.section_of[j]];
                let r = p.contact_radius;
                let force = if r > 0.0 { kr * grid.limit[j] / r } else { 0.0 };
                [grid.z[j] - 0.5 * h, grid.z[j] + 0.5 * h, force, r, cfg.damping_rate * p.inertia_per_length]
            })
            .collect();
        let mut top = 0.0;
        let sections = cfg
            .sections
            .iter()
            .map(|s| {
                let m = AxialSection::from_section(s).mass_per_length();
                let row = [top, top + s.length, cfg.damping_rate * m];
                top += s.length;
                row
            })
            .collect();
        Wall { cells, sections, coupled }
    }

    /// The share of the kinetic force along the axis and around it at the rates `v` (m/s) and
    /// `omega` (rad/s) of a contact of radius `r`: `(v, r omega) / |(v, r omega)|`, or `(0, 1)`
    /// without the coupled friction.
    fn split(&self, v: f64, omega: f64, r: f64) -> (f64, f64) {
        let s = v.hypot(r * omega);
        if !self.coupled {
            (0.0, 1.0)
        } else if s > 0.0 {
            (v / s, r * omega / s)
        } else {
            (0.0, 0.0)
        }
    }

    /// The torque at each torsional cell centre (top to bottom) and at the top of the string,
    /// N m, in steady drilling at `v`, `omega` with the torque on bit `tob`: `tob` plus the
    /// kinetic friction torque and the damping torque below.
    pub fn torques(&self, v: f64, omega: f64, tob: f64) -> (Vec<f64>, f64) {
        let mut out = vec![0.0; self.cells.len()];
        let mut below = tob;
        for (j, &[top, bottom, force, r, damping]) in self.cells.iter().enumerate().rev() {
            let (_, tangential) = self.split(v, omega, r);
            let piece = (force * r * tangential + damping * omega) * (bottom - top);
            out[j] = below + 0.5 * piece;
            below += piece;
        }
        (out, below)
    }

    /// The wall's axial drag and the axial damping on the string below the measured depth `z`,
    /// N, in steady drilling at `v`, `omega` (upward on a string moving down).
    pub fn axial_resistance_below(&self, z: f64, v: f64, omega: f64) -> f64 {
        let overlap = |top: f64, bottom: f64| (bottom - top.max(z)).max(0.0);
        let drag: f64 = self
            .cells
            .iter()
            .map(|&[top, bottom, force, r, _]| force * self.split(v, omega, r).0 * overlap(top, bottom))
            .sum();
        let damping: f64 = self.sections.iter().map(|&[top, bottom, c]| c * v * overlap(top, bottom)).sum();
        drag + damping
    }
}

/// A coupled run's steady drilling point: the rotary speed, rad/s, the rate of penetration, m/s,
/// and the bit's depth of cut, weight and torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyPoint {
    pub omega: f64,
    pub rop: f64,
    pub bit: SteadyDrilling,
}

/// The buoyed weight of `cfg`'s lumped BHA along the hole at the bit, N, and the hook load of
/// the string hanging off bottom, N (the static tension at the top with the BHA hanging).
pub fn hanging(cfg: &DrillConfig) -> Result<(f64, f64)> {
    Ok((super::limits::bha_weight(cfg), super::limits::hanging_hook_load(cfg)))
}

/// The steady drilling point of a coupled configuration turning at `omega` (rad/s) with the wall
/// `wall` (see the module); refused, naming `numerics.initial_state`, without a hoist, without
/// rotation, or when the hoist does not drill at `t = 0` (a block moving up or at rest, a weight
/// below the wear flats' contact force `a l sigma`).
pub fn steady_point(cfg: &DrillConfig, wall: &Wall, omega: f64) -> Result<SteadyPoint> {
    let Some(hoist) = &cfg.hoist else {
        return Err(Error::invalid(
            FIELD,
            "\"steady\"",
            "\"rest\" for a run without a [hoist]: the steady state is a coupled run's steady drilling",
        ));
    };
    if omega.is_nan() || omega <= 0.0 {
        return Err(Error::invalid(
            FIELD,
            "\"steady\"",
            format!(
                "\"rest\" for a top drive not turning forward at t = 0 ({} rpm): steady drilling turns",
                Num(omega * 60.0 / std::f64::consts::TAU)
            ),
        ));
    }
    let law: DetournayBit = cfg.bit.detournay.law(cfg.bit.radius);
    let p = hoist;
    let target = p.target(0.0);
    let wf = law.contact_weight();
    let slope = law.cutting_weight(1.0);
    let rop_at = |w: f64| (w - wf) / slope * omega / std::f64::consts::TAU;
    let reference = HoistReference { hanging: hanging(cfg)?.1, block_weight: cfg.torque_drag.block_weight };
    let rop = match rule(p.mode).steady(p, target, reference) {
        Steady::Rate(rop) => rop,
        Steady::WeightAtBit(w) | Steady::WeightAtSurface(w) if w <= wf => {
            return Err(Error::invalid(
                FIELD,
                "\"steady\"",
                format!(
                    "\"rest\" for a weight on bit of {} N at t = 0, not above the wear flats' contact force \
                     {} N: the bit does not cut",
                    Num(w),
                    Num(wf)
                ),
            ))
        }
        Steady::WeightAtBit(w) => rop_at(w),
        Steady::WeightAtSurface(w) => {
            // the weight reaching the bit: the imposed one less the drag of the moving string
            let (mut lo, mut hi) = (wf, w);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid + wall.axial_resistance_below(0.0, rop_at(mid), omega) > w {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            rop_at(0.5 * (lo + hi))
        }
    };
    if !(rop > 0.0 && rop.is_finite()) {
        return Err(Error::invalid(
            FIELD,
            "\"steady\"",
            format!(
                "\"rest\" for a hoist that does not drill down at t = 0 (a rate of {} m/s): steady drilling \
                 advances",
                Num(rop)
            ),
        ));
    }
    let Some((bit, _)) = Law::new(cfg).steady(rop, omega) else {
        return Err(Error::invalid(FIELD, "\"steady\"", "\"rest\" for a bit law without a steady drilling state"));
    };
    Ok(SteadyPoint { omega, rop, bit })
}

#[cfg(test)]
#[path = "start_tests.rs"]
mod tests;
