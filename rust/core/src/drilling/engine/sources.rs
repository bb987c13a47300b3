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
        // Slow: |w1| < stick speed, or w1 = 0 (`slow_below`). Selects and bit operations
        // only, so that the loop vectorises.
        let slow = w1.abs() < k.slow_below;
        let clipped = if wd > lim { lim } else { wd };
        let clipped = if clipped < -lim { -lim } else { clipped };
        // Kinetic: -min(kinetic_ratio lim, |wd|) copysign w1, i.e. the larger of `slip` (<= -0)
        // and -|wd|, with its sign flipped when w1 is negative; at -|wd| it stops the cell.
        let room = -wd.abs();
        let stops = slip <= room;
        let kinetic = if stops { room } else { slip };
        let kinetic = f64::from_bits(kinetic.to_bits() ^ (w1.to_bits() & SIGN_BIT));
        let df = if slow { -clipped } else { kinetic };
        (df, (slow & (wd.abs() <= lim)) | (!slow & stops))
    };
    (dd, df, stuck)
}

/// The sign bit of an `f64`.
const SIGN_BIT: u64 = 1 << 63;
