//! What a configuration may ask for beyond each value's own range, checked before a run or an
//! analysis allocates anything sized by it:
//!
//! * loads: every hoist step and autodriller setpoint in the range of its mode's scalar key
//!   (a hook load or a weight on bit `>= 0`), and no `bit.weight_on_bit` above the string's
//!   buoyed weight along the hole ([`hanging_hook_load`]: a hoist holds the string up, it cannot
//!   push it down); a weight the hoist is asked to hold above it is warned about
//!   ([`load_warnings`]: the coupled model's hoist then pushes, a negative hook load);
//! * the hole ([`check_hole`]): no dogleg at or near 180 degrees within one survey interval
//!   (minimum curvature is undefined there) and no point of the hole above the rig floor
//!   (TVD < 0), naming the station;
//! * the torque and drag ([`validate_torque_drag`]): at least one friction factor, each in
//!   `[0, 10]`, and no more elements ([`crate::well::torque_drag::MAX_ELEMENTS`]) nor broomstick
//!   work ([`MAX_BROOMSTICK_WORK`]) than a bounded run;
//! * the work of a run's upwind cut surface ([`check_cut_surface_work`]), counted with the
//!   string's cells against [`MAX_CELL_STEPS`];
//! * warnings ([`load_warnings`]) for a hoist's weight on bit above the buoyed weight, and for
//!   one the top drive cannot turn the bit at.

use std::f64::consts::TAU;

use crate::error::{Error, Num, Result, Short};
use crate::well::torque_drag::MAX_ELEMENTS;
use crate::well::Trajectory;

use super::axial::section::{static_tension, AxialSection};
use super::config::AutodrillerTarget;
use super::config::{nonneg, within, BitRockLaw, CutSurfaceScheme, DrillConfig, HoistMode, TopMode, MAX_CELL_STEPS};
use super::grid::Grid;

/// The largest dogleg within one survey interval, degrees: at 180 degrees the two directions
/// are opposite and the minimum-curvature arc (its plane, its ratio factor `tan(beta / 2) /
/// (beta / 2)`) is undefined; near it the arc's plane is lost in the rounding of the angles.
pub const MAX_DOGLEG_DEG: f64 = 179.0;

/// The most friction factors of a broomstick plot.
pub const MAX_FRICTION_FACTORS: usize = 100;

/// The most element evaluations of a broomstick plot (bit depths x friction factors x three
/// operations x elements above the bit): about a minute of one core.
pub const MAX_BROOMSTICK_WORK: f64 = 1e9;

/// The bit's peak speed in stick-slip as a multiple of the top drive's largest speed, for the
/// cost of an upwind cut surface, whose sub-steps follow the bit's speed (a bit slipping out
/// of a stick turns at about twice the mean speed).
pub const BIT_SPEED_PEAK: f64 = 2.0;

/// The buoyed weight of the BHA mass `bit.bha_mass` along the hole at the bit, N (0 without).
pub fn bha_weight(cfg: &DrillConfig) -> f64 {
    let Some(last) = cfg.sections.last() else { return 0.0 };
    let bit: f64 = cfg.sections.iter().map(|s| s.length).sum();
    let (mud, g) = (cfg.well.mud_density, cfg.well.gravity);
    let inclination = inclination_of(cfg);
    cfg.bit.bha_mass * AxialSection::from_section(last).buoyed_gravity(mud, g, inclination(bit))
}

/// The inclination (rad) at a measured depth of the configuration's one trajectory
/// ([`super::well::trajectory`]); a configuration whose trajectory is refused (the refusal is
/// its validation's) counts as vertical here, the heaviest hanging string.
fn inclination_of(cfg: &DrillConfig) -> impl Fn(f64) -> f64 {
    let traj = super::well::trajectory(cfg).ok();
    move |md: f64| traj.as_ref().map_or(0.0, |t| t.at(md).inc)
}

/// The hook load of the string hanging at rest off bottom (without the block's weight), N: the
/// static tension at the top of the buoyed string along the hole with the BHA hanging
/// ([`static_tension`]).
pub fn hanging_hook_load(cfg: &DrillConfig) -> f64 {
    let parts: Vec<AxialSection> = cfg.sections.iter().map(AxialSection::from_section).collect();
    let (mud, g) = (cfg.well.mud_density, cfg.well.gravity);
    static_tension(&parts, mud, g, &inclination_of(cfg), -bha_weight(cfg), &[0.0])[0]
}

/// The weights on bit a configuration asks for, with the field of each: `bit.weight_on_bit`
/// (the velocity-weakening law and the torque and drag's rotating on bottom), the hoist's
/// `weight_on_bit` and its steps, the autodriller's weight setpoint and its steps.
fn asked_weights(cfg: &DrillConfig) -> Vec<(String, f64)> {
    let mut out = vec![("bit.weight_on_bit".to_string(), cfg.bit.weight_on_bit)];
    let Some(h) = &cfg.hoist else { return out };
    let steps = |out: &mut Vec<(String, f64)>| {
        out.extend(h.steps.iter().enumerate().map(|(i, s)| (format!("hoist.steps[{i}][1]"), s[1])));
    };
    match h.mode {
        HoistMode::WeightOnBit => {
            out.push(("hoist.weight_on_bit".into(), h.weight_on_bit));
            steps(&mut out);
        }
        HoistMode::Autodriller if h.autodriller.target == AutodrillerTarget::WeightOnBit => {
            out.push(("hoist.autodriller.setpoint".into(), h.autodriller.setpoint));
            steps(&mut out);
        }
        _ => {}
    }
    out
}

/// The loads: each hoist step and the autodriller's setpoint in the range of the mode's scalar
/// key (hook load and weight on bit `>= 0` N, a rate of penetration `>= 0` m/s), and
/// `bit.weight_on_bit` (the velocity-weakening bit's, the torque and drag's rotating on bottom)
/// at most the string's buoyed weight along the hole.
pub fn validate_loads(cfg: &DrillConfig) -> Result<()> {
    if let Some(h) = &cfg.hoist {
        let unit = match h.mode {
            HoistMode::Velocity => None,
            HoistMode::HookLoad => Some("N, a hook load as hoist.hook_load"),
            HoistMode::WeightOnBit => Some("N, a weight on bit as hoist.weight_on_bit"),
            HoistMode::Autodriller => Some(match h.autodriller.target {
                AutodrillerTarget::WeightOnBit => "N, a weight on bit as hoist.autodriller.setpoint",
                AutodrillerTarget::Rop => "m/s, a rate of penetration as hoist.autodriller.setpoint",
            }),
        };
        if let Some(unit) = unit {
            if h.mode == HoistMode::Autodriller {
                nonneg("hoist.autodriller.setpoint", h.autodriller.setpoint, unit)?;
            }
            for (i, s) in h.steps.iter().enumerate() {
                nonneg(format!("hoist.steps[{i}][1]"), s[1], unit)?;
            }
        }
    }
    let hanging = hanging_hook_load(cfg).max(0.0);
    let w = cfg.bit.weight_on_bit;
    if w > hanging * (1.0 + 1e-12) {
        return Err(Error::invalid(
            "bit.weight_on_bit",
            Num(w),
            format!(
                "a weight on bit of at most {} N, the string's buoyed weight along the hole (the hook load of the \
                 string hanging off bottom, without the block): a hoist holds the string up, it cannot push it down \
                 (a weight in N? 80 kN = 80e3)",
                Short(hanging)
            ),
        ));
    }
    Ok(())
}

/// The hoist's weights on bit above the string's buoyed weight along the hole: the largest,
/// warned about with both numbers.
fn above_buoyed_weight(cfg: &DrillConfig, weights: &[(String, f64)]) -> Option<String> {
    let hanging = hanging_hook_load(cfg).max(0.0);
    let (field, w) = weights.iter().filter(|(_, w)| *w > hanging * (1.0 + 1e-12)).max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(format!(
        "{field} = {} N is above the string's buoyed weight along the hole, {} N (the hook load of the string \
         hanging off bottom): the hoist pushes the string down with a negative hook load, which a rig cannot (a \
         weight in N? a longer or heavier string, bit.bha_mass?)",
        Num(*w),
        Short(hanging)
    ))
}

/// Warnings for loads the run can be asked for but not drill: a hoist's weight on bit above the
/// string's buoyed weight along the hole ([`hanging_hook_load`]), and with the Detournay law under the
/// top drive's controller, a weight on bit (the hoist's, a step's, the autodriller's setpoint or
/// the hanging load less a hook load) whose bit torque
/// ([`crate::drilling::axial::bitrock::DetournayBit::torque_at_weight`]) with the wall's
/// break-off torque `breakoff` exceeds `top_drive.torque_limit`: the bit stalls, and the
/// run's rate of penetration is the string's compression, not drilling.
pub fn load_warnings(cfg: &DrillConfig, breakoff: f64) -> Vec<String> {
    let Some(h) = &cfg.hoist else { return Vec::new() };
    let mut weights = asked_weights(cfg);
    weights.remove(0); // bit.weight_on_bit: not the coupled run's
    let mut out: Vec<String> = above_buoyed_weight(cfg, &weights).into_iter().collect();
    if cfg.bit.law == BitRockLaw::VelocityWeakening || cfg.top_drive.mode == TopMode::MeasuredSpeed {
        return out;
    }
    if h.mode == HoistMode::HookLoad {
        // (a hook load as the weight indicator reads it, the block's weight with it)
        let hanging = hanging_hook_load(cfg) + cfg.torque_drag.block_weight;
        weights.push(("hoist.hook_load".into(), hanging - h.hook_load));
        weights.extend(h.steps.iter().enumerate().map(|(i, s)| (format!("hoist.steps[{i}][1]"), hanging - s[1])));
    }
    let law = cfg.bit.detournay.law(cfg.bit.radius);
    let limit = cfg.top_drive.torque_limit;
    let worst = weights
        .into_iter()
        .map(|(field, w)| (field, w, law.torque_at_weight(w.max(0.0))))
        .filter(|(_, _, t)| t + breakoff > limit)
        .max_by(|a, b| a.2.total_cmp(&b.2));
    worst
        .map(|(field, w, t)| {
            let weight = if field.starts_with("hoist.hook_load") || h.mode == HoistMode::HookLoad {
                format!("{field} gives a weight on bit of {} N", Short(w))
            } else {
                format!("{field} = {} N", Num(w))
            };
            format!(
                "{weight}: the bit cannot drill it; the Detournay bit's torque at this weight, {} N m, with the wall's \
                 break-off torque, {} N m, is over top_drive.torque_limit = {} N m, so the bit stalls and the run's \
                 rate of penetration is the string's compression, not drilling (a weight in N? a smaller weight, or a \
                 larger torque limit)",
                Short(t),
                Short(breakoff),
                Num(limit)
            )
        })
        .into_iter()
        .for_each(|w| out.push(w));
    out
}

/// The station a message names: the survey file's row (1 = the header), the plan's station by
/// depth, `well.md[j]` (a first station below the surface is continued up to md 0, one station
/// more in the survey) or the constant inclination.
fn station(cfg: &DrillConfig, traj: &Trajectory, j: usize) -> String {
    let w = &cfg.well;
    if w.survey.is_some() {
        format!("well.survey, row {}", j + 2)
    } else if w.plan.is_some() {
        format!("well.plan (the station at md {} m)", Num(traj.survey.md[j]))
    } else if let Some(md) = &w.md {
        let shift = usize::from(md.first().is_some_and(|&d| d > 0.0));
        format!("well.md[{}]", j.saturating_sub(shift))
    } else {
        "well.inclination_deg".into()
    }
}

/// The hole of a configuration's trajectory down to `bit` m: every interval's dogleg below
/// [`MAX_DOGLEG_DEG`], and the hole nowhere above the rig floor (TVD >= 0 at every station, on
/// every arc and on the straight continuation below the last station). Names the station.
pub fn check_hole(cfg: &DrillConfig, traj: &Trajectory, bit: f64) -> Result<()> {
    let md = &traj.survey.md;
    for j in 1..md.len() {
        let beta = traj.dogleg[j].to_degrees();
        if beta >= MAX_DOGLEG_DEG {
            return Err(Error::invalid(
                station(cfg, traj, j),
                format!("a dogleg of {} deg from the station above (md {} m)", Short(beta), Num(md[j - 1])),
                format!(
                    "a dogleg below {MAX_DOGLEG_DEG} deg within one survey interval (the hole turned back on itself: \
                     minimum curvature is undefined at 180 deg); add stations between"
                ),
            ));
        }
    }
    let tolerance = |d: f64| -1e-9 * d.abs().max(1.0);
    let above = |j: usize, d: f64, tvd: f64| {
        Error::invalid(
            station(cfg, traj, j),
            format!("a hole {} m above the rig floor at md {} m", Short(-tvd), Short(d)),
            "a hole below the rig floor (TVD >= 0 everywhere; inclination 0 points down, over 90 deg up)",
        )
    };
    for j in 1..md.len() {
        let (a, b) = (traj.tangent[j - 1][2], traj.tangent[j][2]);
        let mut points = vec![md[j]];
        if a < 0.0 || b < 0.0 {
            // the arc may rise between the stations: sample it
            points.extend((1..64).map(|k| md[j - 1] + (md[j] - md[j - 1]) * f64::from(k) / 64.0));
        }
        for d in points {
            let tvd = traj.at_on(d, j).position[2];
            if tvd < tolerance(d) {
                return Err(above(j, d, tvd));
            }
        }
    }
    let last = md.len() - 1;
    if bit > md[last] {
        let tvd = traj.at(bit).position[2];
        if tvd < tolerance(bit) {
            return Err(above(last, bit, tvd));
        }
    }
    Ok(())
}

/// An inclination in `[0, 180)` degrees (180 points straight up: no hole from the surface).
pub fn check_inclination(field: impl Into<String>, x: f64) -> Result<()> {
    if x.is_finite() && (0.0..180.0).contains(&x) {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), "a number in [0, 180) (degrees; 0 points down, 90 is horizontal)"))
    }
}

/// `torque_drag`: the loads, at least one and at most [`MAX_FRICTION_FACTORS`] friction
/// factors each in `[0, 10]`, the element length (at most [`MAX_ELEMENTS`] elements over the
/// string) and the broomstick's points and work ([`MAX_BROOMSTICK_WORK`]).
pub fn validate_torque_drag(cfg: &DrillConfig) -> Result<()> {
    let tdc = &cfg.torque_drag;
    nonneg("torque_drag.bit_torque", tdc.bit_torque, "N m")?;
    nonneg("torque_drag.block_weight", tdc.block_weight, "N")?;
    let n = tdc.friction_factors.len();
    if !(1..=MAX_FRICTION_FACTORS).contains(&n) {
        return Err(Error::invalid(
            "torque_drag.friction_factors",
            format!("{n} factors"),
            format!("1 to {MAX_FRICTION_FACTORS} friction factors, each in [0, 10]"),
        ));
    }
    for (j, m) in tdc.friction_factors.iter().enumerate() {
        within(format!("torque_drag.friction_factors[{j}]"), *m, 0.0, 10.0, "-")?;
    }
    let length: f64 = cfg.sections.iter().map(|s| s.length).sum();
    let min_step = length / MAX_ELEMENTS as f64;
    if !(tdc.step.is_finite() && tdc.step > 0.0 && tdc.step >= min_step) {
        return Err(Error::invalid(
            "torque_drag.step",
            Num(tdc.step),
            format!(
                "a finite element length of at least {} m (at most {MAX_ELEMENTS} elements over the string's {} m)",
                Short(min_step),
                Num(length)
            ),
        ));
    }
    let points = tdc.broomstick_points;
    if !(2..=100_000).contains(&points) {
        return Err(Error::invalid("torque_drag.broomstick_points", points, "an integer in 2..=100000"));
    }
    // the bit depths are evenly spaced: on average half the string's elements above the bit
    let per_point = 3.0 * n as f64 * (0.5 * length / tdc.step + 1.0);
    let work = points as f64 * per_point;
    if work > MAX_BROOMSTICK_WORK {
        let most = (MAX_BROOMSTICK_WORK / per_point).floor().max(1.0);
        return Err(Error::invalid(
            "torque_drag.broomstick_points",
            points,
            format!(
                "an integer in 2..={} with {n} friction factors and elements of {} m (a broomstick of at most {} \
                 element evaluations; this one needs {}): fewer points or factors, or a longer torque_drag.step",
                Num(most),
                Num(tdc.step),
                Num(MAX_BROOMSTICK_WORK),
                Short(work)
            ),
        ));
    }
    Ok(())
}

/// The largest top-drive speed a run asks for, rpm: the setpoint and its steps, or the measured
/// speed series.
pub fn peak_rpm(cfg: &DrillConfig) -> f64 {
    let td = &cfg.top_drive;
    let speeds: Vec<f64> = match td.mode {
        TopMode::MeasuredSpeed => td.speed_series.iter().map(|p| p[1]).collect(),
        TopMode::Controller => std::iter::once(td.rpm).chain(td.steps.iter().map(|s| s[1])).collect(),
    };
    speeds.into_iter().map(f64::abs).fold(0.0, f64::max)
}

/// The work of a coupled run's upwind cut surface (`bit.law = "rgd"`, `bit.detournay.cut_surface
/// = "upwind"`), counted with the string's cells against [`MAX_CELL_STEPS`]: per time step its
/// `cells` times its sub-steps `ceil(dt cells n omega / 2 pi)` at the bit's peak speed
/// ([`BIT_SPEED_PEAK`] times [`peak_rpm`]): a cost quadratic in the cells. Refused naming
/// `bit.detournay.cut_surface_cells` with the largest count this run allows.
pub fn check_cut_surface_work(cfg: &DrillConfig, grid: &Grid) -> Result<()> {
    let d = &cfg.bit.detournay;
    if cfg.hoist.is_none() || cfg.bit.law != BitRockLaw::Rgd || d.cut_surface != CutSurfaceScheme::Upwind {
        return Ok(());
    }
    let steps = (cfg.numerics.duration / grid.dt).ceil();
    let omega = BIT_SPEED_PEAK * peak_rpm(cfg) * TAU / 60.0;
    // sub-steps per cell: dt n omega / 2 pi
    let k = grid.dt * f64::from(d.blades.max(1)) * omega / TAU;
    let cost = |cells: f64| cells * (k * cells).ceil().max(1.0);
    let cells = f64::from(d.cut_surface_cells);
    let string = grid.cells() as f64;
    let work = steps * (string + cost(cells));
    if work <= MAX_CELL_STEPS {
        return Ok(());
    }
    let budget = (MAX_CELL_STEPS / steps - string).max(0.0);
    // the largest count within the budget: cost is increasing in the cells
    let (mut lo, mut hi) = (0.0f64, cells);
    while hi - lo > 1.0 {
        let mid = (0.5 * (lo + hi)).floor();
        if cost(mid) <= budget {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Err(Error::invalid(
        "bit.detournay.cut_surface_cells",
        d.cut_surface_cells,
        format!(
            "an integer in 1..={} for this run: the upwind cut surface costs its cells times their sub-steps every \
             time step (quadratic in the cells at {} rpm), {} cell updates with the string's {} cells over {} steps, \
             over the {} of a run (about {} h); fewer cells, a shorter numerics.duration or cut_surface = \
             \"exact_delay\"",
            Num(lo.max(1.0)),
            Num(peak_rpm(cfg)),
            Short(work),
            grid.cells(),
            Num(steps),
            Num(MAX_CELL_STEPS),
            Num((work / 6e8 / 3600.0 * 10.0).round() / 10.0)
        ),
    ))
}

#[cfg(test)]
#[path = "limits_tests.rs"]
mod tests;
