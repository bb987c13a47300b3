//! What an engineer checks after the torque and drag: where the string buckles, whether a
//! string lowered without rotation locks up and how much weight then reaches the bit, and how
//! close the loads come to the pipe's limits (von Mises utilisation, the tool joints' make-up
//! torque, the overpull margin at the surface).
//!
//! Lock-up: lowering the string (slack-off, sliding) the wall's friction holds back the weight;
//! the string locks up when the bit's load needs the surface to push, the surface's effective
//! tension below 0 (all the string's weight set down and more), which a helically buckled
//! string's contact, growing with the square of the compression, reaches in a finite length.
//! The largest surface set-down that still reaches the bit is the slack-off's surface tension
//! with the bit free (the whole weight at the hook), and the weight it puts on the bit is the
//! bit load at which the surface tension reaches 0.

use std::collections::BTreeMap;

use serde::Serialize;

use super::buckling::Mode;
use super::torque_drag::{piece_at, Elements, Operation, Profile, ProfileMethod, Setup};
use super::Trajectory;

/// The first depths of each kind of buckling of one operation, m (None: none).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FirstBuckling {
    pub sinusoidal_md: Option<f64>,
    pub helical_md: Option<f64>,
}

/// The buckling, lock-up and limits of an analysis (flattened into `torque_drag.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Limits {
    /// Whether a hole diameter was given (else no critical loads, no buckling).
    pub buckling_evaluated: bool,
    /// By operation name.
    pub first_buckling: BTreeMap<&'static str, FirstBuckling>,
    /// By operation name: whether the operation's bit load needs the surface to push.
    pub lockup: BTreeMap<&'static str, bool>,
    /// The largest surface set-down that still reaches the bit, N (0 when the string locks up
    /// with the bit free).
    #[serde(rename = "max_set_down_N")]
    pub max_set_down_n: f64,
    /// The weight on bit that set-down gives, N (None: not reached within the bound of the search).
    #[serde(rename = "max_weight_on_bit_N")]
    pub max_weight_on_bit_n: Option<f64>,
    /// The largest von Mises utilisation over the operations, its depth and operation (None
    /// without a grade or yield strength).
    pub max_utilisation: Option<f64>,
    pub max_utilisation_md: Option<f64>,
    pub max_utilisation_operation: Option<&'static str>,
    /// The largest torque over the tool joints' make-up torque (None without one).
    pub max_torque_over_makeup: Option<f64>,
    pub max_torque_over_makeup_md: Option<f64>,
    pub max_torque_over_makeup_operation: Option<&'static str>,
    /// The top section's tensile yield load `Y A` less the pick-up's surface tension, N.
    #[serde(rename = "overpull_margin_N")]
    pub overpull_margin_n: Option<f64>,
    /// The limit the loads come closest to: `utilisation`, `makeup_torque` or `overpull`.
    pub closest_limit: Option<&'static str>,
    /// Its ratio (1: at the limit).
    pub closest_limit_ratio: Option<f64>,
}

/// The largest finite value of `values` with its index.
fn largest(values: impl Iterator<Item = f64>) -> Option<(f64, usize)> {
    values.enumerate().filter(|(_, v)| v.is_finite()).fold(None, |best, (k, v)| match best {
        Some((b, _)) if b >= v => best,
        _ => Some((v, k)),
    })
}

/// The surface tension of the slack-off with the bit carrying the compression `f`, N.
fn set_down_tension(traj: &Trajectory, setup: &Setup, el: &Elements, scheme: ProfileMethod, f: f64) -> f64 {
    setup.profile_on(traj, el, Operation::SlackOff, scheme, None, (-f, 0.0)).surface_tension()
}

/// The bit load at which the slack-off's surface tension reaches 0, N (doubling then bisection).
fn max_weight_on_bit(traj: &Trajectory, setup: &Setup, el: &Elements, scheme: ProfileMethod, free: f64) -> Option<f64> {
    if free.is_nan() || free < 0.0 {
        return Some(0.0);
    }
    let (mut lo, mut hi) = (0.0, free.max(1.0));
    let mut found = false;
    for _ in 0..64 {
        let t = set_down_tension(traj, setup, el, scheme, hi);
        if t.is_nan() || t < 0.0 {
            found = true;
            break;
        }
        (lo, hi) = (hi, 2.0 * hi);
    }
    if !found {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi || hi - lo <= 1e-9 * hi {
            break;
        }
        if set_down_tension(traj, setup, el, scheme, mid) >= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// The limits of the profiles of [`Operation::ALL`] (in that order) of a string all in the hole,
/// on its elements `el` ([`Setup::elements`] at the string's depth).
pub fn limits(traj: &Trajectory, setup: &Setup, el: &Elements, scheme: ProfileMethod, profiles: &[Profile]) -> Limits {
    let ops = Operation::ALL;
    let mut first_buckling = BTreeMap::new();
    let mut lockup = BTreeMap::new();
    for (op, p) in ops.iter().zip(profiles) {
        first_buckling.insert(
            op.name(),
            FirstBuckling {
                sinusoidal_md: p.first_buckled(Mode::Sinusoidal),
                helical_md: p.first_buckled(Mode::Helical),
            },
        );
        lockup.insert(op.name(), matches!(op, Operation::SlackOff | Operation::Sliding) && p.locked_up());
    }
    let free = profiles[1].surface_tension();
    let max_set_down = if free >= 0.0 { free } else { 0.0 };
    let max_wob = max_weight_on_bit(traj, setup, el, scheme, free);
    // the body at each node of a profile: the element below it, the bit's the one above
    let body = |p: &Profile, k: usize| {
        let at = if k + 1 < p.md.len() { 0.5 * (p.md[k] + p.md[k + 1]) } else { p.md[k] };
        piece_at(&setup.pieces, at).body
    };
    // a locked-up operation is not carried out as asked (the bit's load would need the surface
    // to push, and its compression below the lock-up grows without bound): not a load the string
    // reaches, so not in the limits' maxima
    let best = |value: &dyn Fn(&Profile, usize) -> f64| {
        let mut out: Option<(f64, f64, &'static str)> = None;
        for (op, p) in ops.iter().zip(profiles) {
            if lockup[op.name()] {
                continue;
            }
            if let Some((v, k)) = largest((0..p.md.len()).map(|k| value(p, k))) {
                if out.is_none_or(|o| v > o.0) {
                    out = Some((v, p.md[k], op.name()));
                }
            }
        }
        out
    };
    let utilisation = best(&|p, k| p.utilisation.get(k).copied().unwrap_or(f64::NAN));
    let makeup = best(&|p, k| body(p, k).makeup_torque.map_or(f64::NAN, |m| p.torque[k].abs() / m));
    let top = setup.pieces[0].body;
    let pickup = profiles[0].surface_tension();
    let overpull = top.yield_strength.map(|y| y * top.area - pickup);
    let overpull_ratio = top.yield_strength.map(|y| pickup / (y * top.area));
    let mut closest: Option<(&'static str, f64)> = None;
    for (name, r) in [
        ("utilisation", utilisation.map(|u| u.0)),
        ("makeup_torque", makeup.map(|m| m.0)),
        ("overpull", overpull_ratio),
    ] {
        if let Some(r) = r.filter(|r| r.is_finite()) {
            if closest.is_none_or(|c| r > c.1) {
                closest = Some((name, r));
            }
        }
    }
    Limits {
        buckling_evaluated: setup.hole.is_some(),
        first_buckling,
        lockup,
        max_set_down_n: max_set_down,
        max_weight_on_bit_n: max_wob,
        max_utilisation: utilisation.map(|u| u.0),
        max_utilisation_md: utilisation.map(|u| u.1),
        max_utilisation_operation: utilisation.map(|u| u.2),
        max_torque_over_makeup: makeup.map(|u| u.0),
        max_torque_over_makeup_md: makeup.map(|u| u.1),
        max_torque_over_makeup_operation: makeup.map(|u| u.2),
        overpull_margin_n: overpull,
        closest_limit: closest.map(|c| c.0),
        closest_limit_ratio: closest.map(|c| c.1),
    }
}
