//! Warnings (not errors) for what makes a run doubtful: values far outside drilling practice
//! (more likely a unit or a digit than a well), a top-drive torque limit below the torque that
//! breaks the string free, a motor at its torque limit for a share of the metrics window, a
//! transient still decaying inside the metrics window, and metrics that are not finite. Each names the value and the likely mistake.

use crate::error::{Num, Short};
use crate::metrics::StickSlip;

use super::config::{DrillConfig, HoistMode};
use super::grid::static_torque;

/// The warnings of a configuration with the wall break-off torque `breakoff` (see
/// [`super::DrillRun::warnings`]): [`torque_limit_warning`] and [`plausibility_warnings`].
pub fn run_warnings(cfg: &DrillConfig, breakoff: f64) -> Vec<String> {
    let mut out: Vec<String> = torque_limit_warning(cfg, breakoff).into_iter().collect();
    out.extend(plausibility_warnings(cfg));
    out.extend(super::limits::load_warnings(cfg, breakoff));
    out
}

/// A section of the axial field with at most this many cells at a Courant number below
/// [`AXIAL_EXACT_COURANT`] gets [`axial_resolution_warning`].
pub const AXIAL_FEW_CELLS: usize = 2;
/// At or above this Courant number the axial transport is (near) the exact shift, whatever the
/// number of cells.
pub const AXIAL_EXACT_COURANT: f64 = 0.9;

/// The axial sections, each `(length m, cells, Courant number)`, resolved by
/// [`AXIAL_FEW_CELLS`] cells or fewer at a Courant number below [`AXIAL_EXACT_COURANT`]: the
/// first-order upwind transport smears a wave across such a section, so the loads at its ends
/// (hook load, drag of a short section in a build) carry an error of the order of its weight.
/// Measured: 150 m of collars in one cell at Courant number 0.54 moved a coarse pick-up's hook
/// load by about 3 kN (a 1.5 % error that `--check-grid` flags); more cells remove it.
pub fn axial_resolution_warning(sections: &[(f64, usize, f64)]) -> Option<String> {
    let coarse: Vec<String> = sections
        .iter()
        .enumerate()
        .filter(|(_, &(_, cells, courant))| cells <= AXIAL_FEW_CELLS && courant < AXIAL_EXACT_COURANT)
        .map(|(i, &(length, cells, courant))| {
            format!(
                "sections[{i}] ({} m) in {cells} axial cell{} at Courant number {courant:.2}",
                Num(length),
                if cells == 1 { "" } else { "s" }
            )
        })
        .collect();
    (!coarse.is_empty()).then(|| {
        format!(
            "the axial field resolves {}: the first-order transport smears waves across a section this coarse, \
             so the loads at its ends (hook load, weight on bit) may be off by a share of its weight; \
             more numerics.cells (or check with --check-grid)",
            coarse.join(", ")
        )
    })
}

/// A top-drive torque limit below the break-off torque of the string,
/// [`static_torque`]`(cfg, breakoff)`: the wall's static friction torque `breakoff`
/// ([`super::grid::breakoff_torque`]) plus, with the bit on bottom, its static torque
/// `W r mu_s`. The likely mistake: a limit in kN m where N m are asked (a limit below 1 % of
/// the static torque that a thousand times would cover), else a motor too small for the
/// string or friction factors too high.
pub fn torque_limit_warning(cfg: &DrillConfig, breakoff: f64) -> Option<String> {
    if cfg.top_drive.mode == super::config::TopMode::MeasuredSpeed {
        return None; // an imposed speed: the limit is not used
    }
    let needed = static_torque(cfg, breakoff);
    let limit = cfg.top_drive.torque_limit;
    if limit.partial_cmp(&needed) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let likely = if limit < 0.01 * needed && 1e3 * limit >= needed {
        "a limit in kN m? (top_drive.torque_limit is in N m)"
    } else {
        "a motor too small for this string, or friction.static / bit.mu_static too high?"
    };
    Some(format!(
        "top_drive.torque_limit = {} N m is below the static torque of the string, {} N m (the wall's \
         break-off torque{}): the motor may never break it free; {likely}",
        Num(limit),
        Short(needed),
        if needed > breakoff { " and the bit's" } else { "" }
    ))
}

/// Drilling practice's ranges, beyond which a value is more likely a mistake (a unit, a digit)
/// than a well: the bound, the field and the likely mistake.
pub const PLAUSIBLE_OUTER_DIAMETER: f64 = 1.0;
pub const PLAUSIBLE_BIT_RADIUS: f64 = 0.25;
pub const PLAUSIBLE_STRING_LENGTH: f64 = 15_000.0;
pub const PLAUSIBLE_RPM: f64 = 400.0;
/// The fastest block a hoist moves, m/s (tripping runs below about 1.5 m/s; 30 m/h of drilling
/// is 0.0083 m/s).
pub const PLAUSIBLE_BLOCK_SPEED: f64 = 3.0;

/// Warnings (not errors) for values far outside drilling practice: a pipe over
/// [`PLAUSIBLE_OUTER_DIAMETER`] m across, a bit over 2 [`PLAUSIBLE_BIT_RADIUS`] m, a string
/// longer than [`PLAUSIBLE_STRING_LENGTH`] m, a top-drive speed over [`PLAUSIBLE_RPM`] rpm (the
/// setpoint, its steps or the measured speed series), a block velocity over
/// [`PLAUSIBLE_BLOCK_SPEED`] m/s (the hoist's speed, its steps in `velocity` mode, the
/// autodriller's speed limits and rate-of-penetration setpoint).
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
    let td = &cfg.top_drive;
    let mut rpm: Vec<(String, f64)> = vec![("top_drive.rpm".into(), td.rpm)];
    rpm.extend(td.steps.iter().enumerate().map(|(i, s)| (format!("top_drive.steps[{i}][1]"), s[1])));
    rpm.extend(td.speed_series.iter().enumerate().map(|(i, s)| (format!("top_drive.speed_series[{i}][1]"), s[1])));
    if let Some((field, fast)) = fastest(rpm, PLAUSIBLE_RPM) {
        out.push(format!(
            "a top-drive speed of {} rpm is over the {} rpm of top drives ({field}): rad/s or a digit too many? \
             (top_drive.rpm, top_drive.steps and top_drive.speed_series are in rpm)",
            Num(fast),
            Num(PLAUSIBLE_RPM)
        ));
    }
    if let Some(h) = &cfg.hoist {
        let mut speeds: Vec<(String, f64)> = Vec::new();
        if h.mode == HoistMode::Velocity {
            speeds.push(("hoist.speed".into(), h.speed));
            speeds.extend(h.steps.iter().enumerate().map(|(i, s)| (format!("hoist.steps[{i}][1]"), s[1])));
        }
        if h.mode == HoistMode::Autodriller {
            let a = &h.autodriller;
            speeds.push(("hoist.autodriller.max_speed".into(), a.max_speed));
            speeds.push(("hoist.autodriller.min_speed".into(), a.min_speed));
            if a.target == super::config::AutodrillerTarget::Rop {
                speeds.push(("hoist.autodriller.setpoint".into(), a.setpoint));
                speeds.extend(h.steps.iter().enumerate().map(|(i, s)| (format!("hoist.steps[{i}][1]"), s[1])));
            }
        }
        if let Some((field, fast)) = fastest(speeds, PLAUSIBLE_BLOCK_SPEED) {
            out.push(format!(
                "{field} = {} m/s is over the {} m/s of a hoisting block: m/h or ft/h? (block speeds are in m/s, \
                 30 m/h = 0.008333 m/s)",
                Num(fast),
                Num(PLAUSIBLE_BLOCK_SPEED)
            ));
        }
    }
    out
}

/// The value of largest magnitude over `bound` in magnitude (its field and value), if any.
fn fastest(values: Vec<(String, f64)>, bound: f64) -> Option<(String, f64)> {
    values.into_iter().filter(|(_, v)| v.abs() > bound).max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
}

/// [`transient_warning`]: the relative change of an oscillation's peak-to-peak amplitude
/// between the two halves of the metrics window above which it is still growing or decaying.
pub const TRANSIENT_AMPLITUDE_CHANGE: f64 = 0.25;
/// [`transient_warning`]: the relative change of the mean motor torque between the halves
/// above which the mean is still drifting.
pub const TRANSIENT_MEAN_CHANGE: f64 = 0.1;
/// [`transient_warning`]: oscillations with a peak-to-peak amplitude below this fraction of the
/// series' mean magnitude are not judged (a ripple, or no oscillation).
pub const TRANSIENT_MIN_AMPLITUDE: f64 = 0.05;

/// Mean, min and max of `x` over the samples of `t` in `[a, b)` (`[a, b]` when `closed`), with
/// their count.
fn half(t: &[f64], x: &[f64], a: f64, b: f64, closed: bool) -> (usize, f64, f64, f64) {
    let (mut n, mut sum, mut lo, mut hi) = (0usize, 0.0, f64::INFINITY, f64::NEG_INFINITY);
    for (&ti, &xi) in t.iter().zip(x) {
        if ti >= a && (ti < b || (closed && ti <= b)) {
            n += 1;
            sum += xi;
            lo = lo.min(xi);
            hi = hi.max(xi);
        }
    }
    (n, sum / n as f64, lo, hi)
}

/// A transient still decaying (or growing) inside the metrics window `[a, b]`, judged on the
/// two halves `[a, m)` and `[m, b]`, `m = (a + b) / 2`, of the surface speed and the motor
/// torque sampled at `t`:
///
/// * an oscillation whose peak-to-peak amplitude (max - min over a half) changes by more than
///   [`TRANSIENT_AMPLITUDE_CHANGE`] of the larger of the two, when that one exceeds
///   [`TRANSIENT_MIN_AMPLITUDE`] of the series' mean magnitude over the window (a steady cycle
///   shorter than a half has the same amplitude in both);
/// * a mean motor torque that moves by more than [`TRANSIENT_MEAN_CHANGE`] of the larger mean
///   magnitude and by more than half the torque's peak-to-peak amplitude in either half (a
///   steady cycle moves the mean of a half by less: a part of one cycle over at least one).
///
/// None with fewer than 2 samples in a half or non-finite values. The likely mistake: a run too
/// short, or a window that starts too early.
pub fn transient_warning(t: &[f64], surface_rpm: &[f64], motor_torque: &[f64], window: [f64; 2]) -> Option<String> {
    let found = transient_changes(
        t,
        &[("surface speed", "rpm", surface_rpm, false), ("motor torque", "N m", motor_torque, true)],
        window,
    )?;
    let [a, b] = window;
    (!found.is_empty()).then(|| {
        format!(
            "a transient is still decaying in the metrics window [{}, {}] s: between its halves {}; the metrics \
             describe the approach, not the steady state: a run too short or a window that starts too early? \
             (lengthen numerics.duration or move metrics.window later)",
            Num(a),
            Num(b),
            found.join(" and ")
        )
    })
}

/// The changes between the halves of the window `[a, b]` of each series `(name, unit, x, mean)`
/// sampled at `t` that make a transient by the criteria of [`transient_warning`] (the mean's
/// only where `mean`), each described in a few words; None with fewer than 2 samples in a half
/// or non-finite values.
pub fn transient_changes(t: &[f64], series: &[(&str, &str, &[f64], bool)], window: [f64; 2]) -> Option<Vec<String>> {
    let [a, b] = window;
    let m = 0.5 * (a + b);
    let mut found = Vec::new();
    for &(name, unit, x, judge_mean) in series {
        let (n1, mean1, lo1, hi1) = half(t, x, a, m, false);
        let (n2, mean2, lo2, hi2) = half(t, x, m, b, true);
        if n1 < 2 || n2 < 2 || ![mean1, mean2, lo1, lo2, hi1, hi2].iter().all(|v| v.is_finite()) {
            return None;
        }
        let (p1, p2) = (hi1 - lo1, hi2 - lo2);
        let level = 0.5 * (mean1.abs() + mean2.abs());
        let big = p1.max(p2);
        if big > TRANSIENT_MIN_AMPLITUDE * level && (p2 - p1).abs() > TRANSIENT_AMPLITUDE_CHANGE * big {
            // a change from next to nothing is no percentage
            let change = if p2 > 10.0 * p1 {
                format!("{}-fold", Short(p2 / p1.max(f64::MIN_POSITIVE)))
            } else {
                format!("{:+.0} %", 100.0 * (p2 - p1) / p1)
            };
            found.push(format!(
                "the {name}'s peak-to-peak amplitude went from {} to {} {unit} ({change})",
                Short(p1),
                Short(p2),
            ));
        }
        let moved = (mean2 - mean1).abs();
        if judge_mean && moved > TRANSIENT_MEAN_CHANGE * mean1.abs().max(mean2.abs()) && moved > 0.5 * big {
            found.push(format!("the mean {name} went from {} to {} {unit}", Short(mean1), Short(mean2)));
        }
    }
    Some(found)
}

/// A coupled run's axial transient in the metrics window: the criteria of [`transient_warning`]
/// (amplitude and mean) on the rate of penetration (m/h) and the weight on bit (N) sampled at
/// `t`. The string of a coupled run compresses over minutes (the hoist lowers the top at its
/// rate while the bit drills slower until the string carries the weight): a window inside that
/// approach describes no steady regime. The reason, or None (also without samples to judge).
pub fn axial_transient(t: &[f64], rop: &[f64], weight_on_bit: &[f64], window: [f64; 2]) -> Option<String> {
    let found =
        transient_changes(t, &[("ROP", "m/h", rop, true), ("weight on bit", "N", weight_on_bit, true)], window)?;
    (!found.is_empty())
        .then(|| format!("the axial transient is still decaying: between the window's halves {}", found.join(" and ")))
}

/// [`torque_limit_share`]: a motor torque within this fraction of `top_drive.torque_limit` is
/// at the limit (the controller clamps its command to the limit exactly; the tolerance only
/// absorbs the rounding of a limit reached through a sum).
pub const TORQUE_LIMIT_TOLERANCE: f64 = 1e-3;
/// [`torque_limit_verdict`]: the share of the metrics window's samples with the motor at its
/// torque limit above which the run says so and its stick-slip verdict is `undetermined`. A
/// stick-slip cycle whose wind-up peak touches the limit spends a few per cent of the window
/// there (2 % for a 2000 m string at 40 rpm with a limit 8 % above the break-off torque); 5 %
/// is above that and below a motor that chatters between its limits (`z_torque` tuned to the bare
/// pipe on `examples/s-well-3d.toml` at 40 rpm without its BHA inertia: 12 %; on the corrected
/// Well B: 8 %).
pub const TORQUE_LIMIT_SHARE: f64 = 0.05;

/// The share of the samples of `t` in the window `[a, b]` whose motor torque is at the limit
/// `limit` (`|tau| >= (1 - TORQUE_LIMIT_TOLERANCE) limit`); NaN without samples.
pub fn torque_limit_share(t: &[f64], motor_torque: &[f64], window: [f64; 2], limit: f64) -> f64 {
    let [a, b] = window;
    let at = (1.0 - TORQUE_LIMIT_TOLERANCE) * limit;
    let (mut n, mut hits) = (0usize, 0usize);
    for (&ti, &tau) in t.iter().zip(motor_torque) {
        if ti >= a && ti <= b {
            n += 1;
            hits += usize::from(tau.abs() >= at);
        }
    }
    if n == 0 {
        f64::NAN
    } else {
        hits as f64 / n as f64
    }
}

/// A motor at its torque limit for more than [`TORQUE_LIMIT_SHARE`] of the metrics window
/// (`share` from [`torque_limit_share`]): the motion is set by the motor's limit, not by the
/// controller or the string, so that no stick-slip verdict follows from it (a motor chattering
/// between its limits makes the bit stop and go at the chatter's rate). Returns the warning
/// and the verdict's reason, None otherwise (and with an imposed top speed,
/// `top_drive.mode = "measured_speed"`, where the limit is not used). A run does not ask it
/// when the limit is below the string's static torque: [`torque_limit_warning`] says that.
pub fn torque_limit_verdict(cfg: &DrillConfig, share: f64) -> Option<(String, String)> {
    if cfg.top_drive.mode == super::config::TopMode::MeasuredSpeed || share.is_nan() || share <= TORQUE_LIMIT_SHARE {
        return None;
    }
    let percent = format!("{:.0} %", 100.0 * share);
    let warning = format!(
        "the motor torque is at its limit, top_drive.torque_limit = {} N m, {percent} of the metrics window \
         (more than {:.0} %): the motion is the motor's limit, not the controller's, and the stick-slip verdict \
         is undetermined; a limit too low for the string, or a controller that chatters between its limits \
         (a preset on a string it cannot tune?)",
        Num(cfg.top_drive.torque_limit),
        100.0 * TORQUE_LIMIT_SHARE
    );
    Some((warning, format!("motor torque at its limit {percent} of the window")))
}

/// The headline metrics a run reports as its result (the drilling names) with their values:
/// the severity (`ssi`), the stuck fraction, the bit speed's min, max and mean and the motor
/// torque's min and max; each is finite in a run that has metrics. (The period and what depends
/// on it are NaN by definition without a periodic motion.)
fn headline(m: &StickSlip) -> [(&'static str, f64); 7] {
    [
        ("ssi", m.severity),
        ("stuck_fraction", m.stuck_fraction),
        ("bit_rpm_min", m.rpm_min),
        ("bit_rpm_max", m.rpm_max),
        ("bit_rpm_mean", m.rpm_mean),
        ("motor_torque_min_Nm", m.torque_min),
        ("motor_torque_max_Nm", m.torque_max),
    ]
}

/// The names of the headline metrics ([`headline`]) that are not finite.
pub fn non_finite_metrics(m: &StickSlip) -> Vec<&'static str> {
    headline(m).into_iter().filter(|(_, v)| !v.is_finite()).map(|(name, _)| name).collect()
}

/// The warning of [`non_finite_metrics`] (None when all are finite): the run is not a success
/// ([`super::DrillRun::metrics_finite`] false).
pub fn non_finite_metrics_warning(m: &StickSlip) -> Option<String> {
    let bad: Vec<String> =
        headline(m).into_iter().filter(|(_, v)| !v.is_finite()).map(|(n, v)| format!("{n} = {}", Num(v))).collect();
    (!bad.is_empty()).then(|| {
        format!(
            "not a result: {} {} not finite; the run reached its end but these metrics are undefined (a bit that \
             never turns: a torque limit too low or a setpoint of 0 rpm?)",
            bad.join(", "),
            if bad.len() == 1 { "is" } else { "are" },
        )
    })
}

/// Whether the top drive is asked to turn at some time: a setpoint or step other than 0 rpm, or
/// a measured speed series that is not all 0.
pub fn rotation_commanded(cfg: &DrillConfig) -> bool {
    let td = &cfg.top_drive;
    if td.mode == super::config::TopMode::MeasuredSpeed {
        return td.speed_series.iter().any(|p| p[1] != 0.0);
    }
    td.rpm != 0.0 || td.steps.iter().any(|s| s[1] != 0.0)
}

/// The note of a coupled run without rotation ([`rotation_commanded`] false) whose torsional
/// metrics are undefined: in place of [`non_finite_metrics_warning`], whose likely mistakes do
/// not apply.
pub const NO_ROTATION: &str = "no rotation: top_drive.rpm is 0, so the torsional metrics (ssi, stuck_fraction, \
     bit_rpm_*, the period) are undefined; a run without rotation (a pick-up or slack-off) is read by its axial \
     series and coupled metrics (hook_load_mean_N)";

/// Whether the hoist only lifts the string (`velocity` mode, every block velocity upward): without
/// rotation a pick-up, its bit off bottom on purpose, and [`off_bottom_warning`] does not apply.
pub fn lifting(hoist: &super::config::Hoist) -> bool {
    hoist.mode == HoistMode::Velocity && hoist.speed < 0.0 && hoist.steps.iter().all(|s| s[1] < 0.0)
}

/// A coupled run whose bit never touched bottom in the metrics window `[a, b]` s: every sample
/// there has no weight on bit (`bounce_fraction` 1), so the window's ROP, weight and torque on
/// bit are 0 and its MSE is undefined. Says what to change for the hoist's mode `mode`: the bit
/// is lowered by a larger downward block velocity, a smaller hook load, or an autodriller
/// allowed to move down; or the window comes later in a longer run.
pub fn off_bottom_warning(bounce_fraction: f64, window: [f64; 2], mode: HoistMode) -> Option<String> {
    if bounce_fraction < 1.0 {
        return None;
    }
    let change = match mode {
        HoistMode::Velocity => "a larger downward hoist.speed (down is positive)",
        HoistMode::HookLoad => "a smaller hoist.hook_load (below the static hook load of the hanging string)",
        HoistMode::Autodriller => "a positive hoist.autodriller.max_speed and a larger setpoint",
        HoistMode::WeightOnBit => "a positive hoist.weight_on_bit",
    };
    Some(format!(
        "the bit never touched bottom in the metrics window [{}, {}] s (no weight on bit in any sample): its ROP, \
         weight and torque on bit are 0 and its MSE undefined; lower the bit with {change}, or use a longer \
         numerics.duration and a later metrics.window",
        Num(window[0]),
        Num(window[1])
    ))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::interrupt::Never;

    fn series(f: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
        let t: Vec<f64> = (0..=6000).map(|k| k as f64 * 0.01).collect();
        let x = t.iter().map(|&t| f(t)).collect();
        (t, x)
    }

    #[test]
    fn a_steady_cycle_is_no_transient_a_decaying_or_drifting_one_is() {
        let w = [30.0, 60.0];
        // a steady cycle of period 7 s (4.3 cycles per half): the halves' means differ by the
        // partial cycle, amplitudes are equal
        let (t, speed) = series(|t| 40.0 + 20.0 * (2.0 * PI * t / 7.0).sin());
        let (_, torque) = series(|t| 10e3 + 5e3 * (2.0 * PI * t / 7.0).cos());
        assert_eq!(transient_warning(&t, &speed, &torque, w), None);
        // a decaying oscillation: amplitude exp(-t / 20) over 15 s between the halves' starts
        let (_, decaying) = series(|t| 40.0 + 20.0 * (-t / 20.0).exp() * (2.0 * PI * t / 7.0).sin());
        let msg = transient_warning(&t, &decaying, &torque, w).expect("decaying");
        assert!(msg.contains("surface speed's peak-to-peak") && msg.contains("[30, 60]"), "{msg}");
        // a ripple of 1 % of the mean speed decaying is not judged
        let (_, ripple) = series(|t| 40.0 + 0.2 * (-t / 20.0).exp() * (2.0 * PI * t / 7.0).sin());
        assert_eq!(transient_warning(&t, &ripple, &torque, w), None);
        // a mean torque still drifting, 200 N m/s with a small ripple: the halves' means differ
        // by 200 * 15 = 3 kN m, over 10 % of 20.5 kN m and over half the halves' 3.1 kN m ranges
        let (_, drifting) = series(|t| 10e3 + 200.0 * t + 50.0 * (2.0 * PI * t / 7.0).sin());
        let (_, steady) = series(|_| 40.0);
        let msg = transient_warning(&t, &steady, &drifting, w).expect("drifting");
        assert!(msg.contains("mean motor torque went from"), "{msg}");
        // 100 N m/s: 1.5 kN m between the halves, under 10 % of 15.25 kN m
        let (_, slow) = series(|t| 10e3 + 100.0 * t + 50.0 * (2.0 * PI * t / 7.0).sin());
        assert_eq!(transient_warning(&t, &steady, &slow, w), None);
        // a window with fewer than 2 samples in a half: nothing to judge
        assert_eq!(transient_warning(&t, &decaying, &torque, [59.995, 60.0]), None);
    }

    /// A motor at its torque limit over more than 5 % of the window: a warning naming
    /// `top_drive.torque_limit` with the share, and the verdict undetermined with the reason.
    #[test]
    fn a_motor_at_its_torque_limit_makes_the_verdict_undetermined() {
        let mut cfg = DrillConfig::from_json(
            r#"{"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                "numerics": {"cells": 100, "duration": 20.0}}"#,
        )
        .unwrap();
        let run = super::super::solve(&cfg, &Never, &mut |_| {}).unwrap();
        let m = run.metrics.as_ref().unwrap();
        let free = torque_limit_share(&run.t, &run.motor_torque, run.window, cfg.top_drive.torque_limit);
        assert_eq!((m.verdict, free), (crate::metrics::Verdict::Yes, 0.0), "{:?}", m.verdict_reason);
        assert!(!run.warnings.iter().any(|w| w.contains("at its limit")), "{:?}", run.warnings);
        // a limit of 4.2 kN m, just over the break-off torque (4.17 kN m): the wind-up rests on it
        cfg.top_drive.torque_limit = 4200.0;
        let run = super::super::solve(&cfg, &Never, &mut |_| {}).unwrap();
        let share = torque_limit_share(&run.t, &run.motor_torque, run.window, 4200.0);
        assert!(share > TORQUE_LIMIT_SHARE, "{share}");
        let m = run.metrics.as_ref().unwrap();
        let percent = format!("{:.0} %", 100.0 * share);
        assert_eq!(m.verdict, crate::metrics::Verdict::Undetermined);
        assert_eq!(m.verdict_reason, format!("motor torque at its limit {percent} of the window"));
        let w = run.warnings.iter().find(|w| w.contains("top_drive.torque_limit = 4200 N m,")).expect("warned");
        assert!(w.contains(&percent), "{w}");
        // an imposed speed does not use the limit
        cfg.top_drive.mode = super::super::config::TopMode::MeasuredSpeed;
        assert_eq!(torque_limit_verdict(&cfg, 0.5), None);
    }

    #[test]
    fn a_section_of_one_or_two_axial_cells_below_the_exact_shift_is_warned_about() {
        // one cell at 0.54: warned; two cells at 0.95 (near the exact shift) and many cells: not
        let w = axial_resolution_warning(&[(2800.0, 60, 0.7), (150.0, 1, 0.54), (100.0, 2, 0.95)]).unwrap();
        assert!(w.contains("sections[1] (150 m) in 1 axial cell at Courant number 0.54"), "{w}");
        assert!(!w.contains("sections[0]") && !w.contains("sections[2]"), "{w}");
        assert!(axial_resolution_warning(&[(2800.0, 60, 0.7), (100.0, 3, 0.5), (100.0, 2, 0.9)]).is_none());
        let two = axial_resolution_warning(&[(90.0, 2, 0.3), (10.0, 1, 0.2)]).unwrap();
        assert!(
            two.contains("sections[0] (90 m) in 2 axial cells") && two.contains("sections[1] (10 m) in 1 axial cell ")
        );
    }

    #[test]
    fn non_finite_metrics_are_not_a_result() {
        let mut cfg = DrillConfig::default();
        cfg.numerics.duration = 4.0;
        cfg.numerics.cells = 100;
        let run = super::super::solve(&cfg, &Never, &mut |_| {}).unwrap();
        assert!(run.metrics_finite, "{:?}", run.warnings);
        cfg.top_drive.rpm = 0.0;
        let run = super::super::solve(&cfg, &Never, &mut |_| {}).unwrap();
        assert_eq!(run.status, crate::solution::Status::Success);
        let m = run.metrics.as_ref().unwrap();
        assert!(m.severity.is_nan());
        assert_eq!(non_finite_metrics(m), vec!["ssi"]);
        assert!(!run.metrics_finite);
        assert!(
            run.warnings.iter().any(|w| w.starts_with("not a result: ssi = nan is not finite")),
            "{:?}",
            run.warnings
        );
    }
}
