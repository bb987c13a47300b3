//! The sources along the string, one place each: viscous damping and wall friction with its
//! stick phase, per cell, evaluated at the transported speed (see [`super`]).
//!
//! A source is a change of a cell's speed over the step (`dd`, `df`) added to both invariants,
//! and a set-valued flag (the cell stops exactly, its load kept). Its work goes to the energy
//! ledger as `4 e delta (omega* + delta / 2)` per cell. Both schemes (the linear transport and
//! the `consistent` Godunov update, [`super::kernel`]) call [`source`]. A coupled run's wall
//! friction (against the sliding velocity of both fields, `friction.coupling =
//! "axial_torsional"`) is [`super::coupled_friction`], applied after both fields' transport;
//! the kernel then gets zero limits.

use crate::drilling::config::{DrillConfig, FrictionModel};
use crate::drilling::grid::Grid;

use super::field::Field;

/// The wall's friction per cell of a field: the speed change that stops a cell in one step at
/// the static limit, `dt limit / m` per padded index (0 at the ghosts), and the kinetic one
/// `-kinetic_ratio dt limit / m`.
#[derive(Clone)]
pub struct WallFriction {
    pub stop: Vec<f64>,
    pub slip: Vec<f64>,
}

impl WallFriction {
    /// The torsional wall friction of a grid: the limit per metre of [`Grid::limit`] over `rho J`.
    pub fn torsional(cfg: &DrillConfig, grid: &Grid, field: &Field) -> Self {
        let dt = grid.dt;
        let mut stop = Vec::with_capacity(field.padded_len());
        let mut cell = 0;
        for (s, p) in grid.props.iter().enumerate() {
            stop.push(0.0);
            for _ in 0..grid.counts[s] {
                stop.push(dt * grid.limit[cell] / p.inertia_per_length);
                cell += 1;
            }
            stop.push(0.0);
        }
        let slip = stop.iter().map(|&lim| -(cfg.friction.kinetic_ratio * lim)).collect();
        WallFriction { stop, slip }
    }
}

/// The per-step constants of the sources.
#[derive(Clone)]
pub struct Sources {
    /// `dt d`.
    pub damping: f64,
    pub stick_speed: f64,
    pub kinetic_ratio: f64,
    /// `Some(v_r)` for the regularised friction.
    pub regularised: Option<f64>,
}

impl Sources {
    /// The sources of a configuration over a step `dt`.
    pub fn new(cfg: &DrillConfig, dt: f64) -> Self {
        let fr = &cfg.friction;
        Sources {
            damping: dt * cfg.damping_rate,
            stick_speed: fr.stick_speed,
            kinetic_ratio: fr.kinetic_ratio,
            regularised: (fr.model == FrictionModel::Regularised).then_some(fr.regularisation_speed),
        }
    }
}

/// The constants of a cell update and [`source`].
pub(super) struct Consts {
    /// The Courant number.
    pub c: f64,
    pub damping: f64,
    /// A cell is slow below this speed: the stick speed, or with stick speed 0 the least
    /// positive double (then only a cell exactly at rest is slow, and the sign taken in
    /// [`source`] is never that of a zero).
    pub slow_below: f64,
    pub kr: f64,
    pub inv_vr: f64,
}

impl Consts {
    pub fn new(c: f64, src: &Sources) -> Self {
        Consts {
            c,
            damping: src.damping,
            slow_below: if src.stick_speed > 0.0 { src.stick_speed } else { f64::from_bits(1) },
            kr: src.kinetic_ratio,
            inv_vr: src.regularised.map_or(0.0, |v| 1.0 / v),
        }
    }
}

/// The sources of a cell whose transported speed is `w1`, with the stop limit `lim`
/// (`dt limit / m`) and `slip = -kinetic_ratio lim`: the damping change `dd = -dt d w1`,
/// the friction change `df` and whether the cell sticks (see [`super`]).
#[inline(always)]
pub(super) fn source<const REGULARISED: bool>(w1: f64, lim: f64, slip: f64, k: &Consts) -> (f64, f64, bool) {
    let dd = -k.damping * w1;
    let wd = w1 + dd;
    // Friction never reverses a cell within a step: a change larger than the speed after
    // damping (`wd`, of the sign of `w1` since `dt d <= 1`) stops the cell instead.
    let (df, stuck) = if REGULARISED {
        let df = -k.kr * lim * (w1 * k.inv_vr).tanh();
        (if df.abs() > wd.abs() { -wd } else { df }, false)
    } else {
        // One threshold for both phases: a slow cell (|w1| < stick speed, or w1 = 0,
        // `slow_below`) is held by up to the static limit `lim`, a sliding one by up to the
        // kinetic limit `-slip`. The change is the speed after damping clipped to it,
        // `-min(|wd|, thr) copysign w1`, and the cell sticks where `|wd| <= thr`. Each
        // comparison feeds one select directly, with no logic between flags, so that the
        // flags stay full-width lane masks on every instruction set (a flag narrowed for
        // such logic costs a pack and a widening per vector on AVX2).
        let awd = wd.abs();
        let thr = if w1.abs() < k.slow_below { lim } else { -slip };
        let mag = if thr < awd { thr } else { awd };
        (f64::from_bits((-mag).to_bits() ^ (w1.to_bits() & SIGN_BIT)), awd <= thr)
    };
    (dd, df, stuck)
}

/// The sign bit of an `f64`.
const SIGN_BIT: u64 = 1 << 63;

#[cfg(test)]
mod tests {
    use super::*;

    /// The stick phase written out phase by phase (the static limit's clip of `wd` for a slow
    /// cell, the kinetic limit against the sign of `w1` for a sliding one, the stuck flag of
    /// each), against [`source`]'s one threshold: the same change and flag on slow, stuck
    /// and sliding cells, at signed zeros, at the limits exactly, with and without damping up
    /// to `dt d = 1`. The bits of the change are the same wherever the cell does not stick;
    /// a stuck cell's change may differ only in the sign of a zero (its speed is set to 0
    /// and its work is a zero either way).
    #[test]
    fn one_threshold_gives_the_phases_written_out() {
        let written_out = |w1: f64, lim: f64, slip: f64, k: &Consts| -> (f64, f64, bool) {
            let dd = -k.damping * w1;
            let wd = w1 + dd;
            let slow = w1.abs() < k.slow_below;
            let clipped = wd.clamp(-lim, lim);
            let room = -wd.abs();
            let stops = slip <= room;
            let kinetic = if stops { room } else { slip };
            let kinetic = if w1.is_sign_negative() { -kinetic } else { kinetic };
            let df = if slow { -clipped } else { kinetic };
            (dd, df, if slow { wd.abs() <= lim } else { stops })
        };
        let speeds = [0.0, -0.0, 1e-300, -1e-300, 0.3, -0.3, 0.65, -0.65, 1.0, -1.0, 1.4999, -1.5, 1.5, 2.0, -7.0];
        let limits = [0.0, 1e-300, 0.3, 0.65, 1.0, 2.0, 1e3];
        let mut seen = [0usize; 3];
        for damping in [0.0, 1e-3, 0.5, 1.0 - f64::EPSILON, 1.0] {
            for stick_speed in [0.0, 1.5] {
                for kinetic_ratio in [0.0, 0.65, 1.0] {
                    let src = Sources { damping, stick_speed, kinetic_ratio, regularised: None };
                    let k = Consts::new(0.9, &src);
                    for &w1 in &speeds {
                        for &lim in &limits {
                            let slip = -(kinetic_ratio * lim);
                            let (dd, df, stuck) = source::<false>(w1, lim, slip, &k);
                            let (dd0, df0, stuck0) = written_out(w1, lim, slip, &k);
                            let case = format!("w1 {w1:e} lim {lim:e} damping {damping} stick {stick_speed} kr {kinetic_ratio}");
                            assert_eq!(dd.to_bits(), dd0.to_bits(), "{case}");
                            assert_eq!(stuck, stuck0, "{case}");
                            assert_eq!(df, df0, "{case}");
                            if !stuck {
                                assert_eq!(df.to_bits(), df0.to_bits(), "{case}");
                            }
                            seen[usize::from(stuck) + usize::from(w1.abs() < k.slow_below)] += 1;
                        }
                    }
                }
            }
        }
        assert!(seen.iter().all(|&s| s > 50), "{seen:?}");
    }
}
