//! The sources along the string, one place each: viscous damping and wall friction with its
//! stick phase, per cell, evaluated at the transported speed (see [`super`]).
//!
//! A source is a change of a cell's speed over the step (`dd`, `df`) added to both invariants,
//! and a set-valued flag (the cell stops exactly, its load kept). Its work goes to the energy
//! ledger as `4 e delta (omega* + delta / 2)` per cell. Both schemes (the linear transport and
//! the `consistent` Godunov update, [`super::kernel`]) call [`source`]: the damping, common to
//! every law, then the wall friction's [`WallLaw`] (one zero-sized type per `friction.model`,
//! [`SetValued`], [`Regularised`], the kernels compiled once per law, the one match from the
//! model to its law in [`Sources::with_law`]).
//!
//! A source of a step rather than of a cell, applied once per step after both fields'
//! transport, is a [`StepSource`]: a coupled run's wall friction (against the sliding velocity
//! of both fields, `friction.coupling = "axial_torsional"`, [`super::coupled_friction`]); the
//! kernel then gets zero limits.

use crate::drilling::config::{DrillConfig, FrictionModel};
use crate::drilling::grid::Grid;

use super::axial_field::Axial;
use super::coupled_friction::CoupledFriction;
use super::energy::Ledger;
use super::field::Field;
use super::kernel::Wall;

/// The wall's friction per cell of a field: the speed change that stops a cell in one step at
/// the static limit, `dt limit / m` per padded index (0 at the ghosts), and the kinetic one
/// `-kinetic_ratio dt limit / m`.
#[derive(Clone)]
pub struct WallFriction {
    stop: Vec<f64>,
    slip: Vec<f64>,
    /// Whether every `stop` is `+0` and every `slip` `-0` (no friction anywhere: the kernel
    /// takes them as constants, [`Wall::Off`]); kept with them.
    off: bool,
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
        let slip: Vec<f64> = stop.iter().map(|&lim| -(cfg.friction.kinetic_ratio * lim)).collect();
        let off = stop.iter().all(|x| x.to_bits() == 0.0_f64.to_bits())
            && slip.iter().all(|x| x.to_bits() == (-0.0_f64).to_bits());
        WallFriction { stop, slip, off }
    }

    /// No friction (the values of a zero limit; a coupled run's friction applies it instead,
    /// [`StepSource`]).
    pub fn off(&mut self) {
        self.stop.fill(0.0);
        self.slip.fill(-0.0);
        self.off = true;
    }

    /// The limits of the padded range `r` as the transport kernel reads them.
    #[inline]
    pub fn wall(&self, r: std::ops::Range<usize>) -> Wall<'_> {
        if self.off {
            Wall::Off
        } else {
            Wall::Cells { stop: &self.stop[r.clone()], slip: &self.slip[r] }
        }
    }

    /// The limits per padded index, `(stop, slip)`.
    pub fn limits(&self) -> (&[f64], &[f64]) {
        (&self.stop, &self.slip)
    }
}

/// The per-step constants of the sources.
#[derive(Clone)]
pub struct Sources {
    /// `dt d`.
    pub damping: f64,
    pub stick_speed: f64,
    pub kinetic_ratio: f64,
    /// The wall friction's law per cell (`friction.model`), run as its [`WallLaw`] by
    /// [`Sources::with_law`].
    pub model: FrictionModel,
    /// `v_r` of the regularised friction (unused by the set-valued one).
    pub regularisation_speed: f64,
}

impl Sources {
    /// The sources of a configuration over a step `dt`.
    pub fn new(cfg: &DrillConfig, dt: f64) -> Self {
        let fr = &cfg.friction;
        Sources {
            damping: dt * cfg.damping_rate,
            stick_speed: fr.stick_speed,
            kinetic_ratio: fr.kinetic_ratio,
            model: fr.model,
            regularisation_speed: fr.regularisation_speed,
        }
    }

    /// Runs `kernel` with the [`WallLaw`] of `friction.model`: the one place a model's name
    /// meets its law (matched once per call, outside the cell loops; the kernel is compiled
    /// once per law).
    #[inline(always)]
    pub fn with_law<K: WithWallLaw>(&self, kernel: K) -> K::Output {
        match self.model {
            FrictionModel::SetValued => kernel.run::<SetValued>(),
            FrictionModel::Regularised => kernel.run::<Regularised>(),
        }
    }

    /// Whether the wall friction's law has a stick phase ([`WallLaw::STICKS`]).
    pub fn sticks(&self) -> bool {
        struct Sticks;
        impl WithWallLaw for Sticks {
            type Output = bool;
            fn run<L: WallLaw>(self) -> bool {
                L::STICKS
            }
        }
        self.with_law(Sticks)
    }
}

/// A kernel generic over the wall friction's law, run by [`Sources::with_law`].
pub trait WithWallLaw {
    type Output;
    fn run<L: WallLaw>(self) -> Self::Output;
}

/// The constants of a cell update and [`source`].
pub struct Consts {
    /// The Courant number.
    pub c: f64,
    pub damping: f64,
    /// A cell is slow below this speed: the stick speed, or with stick speed 0 the least
    /// positive double (then only a cell exactly at rest is slow, and the sign taken in
    /// [`SetValued`] is never that of a zero).
    pub slow_below: f64,
    pub kr: f64,
    /// `1 / v_r` of the regularised friction (unused by the set-valued one).
    pub inv_vr: f64,
}

impl Consts {
    pub fn new(c: f64, src: &Sources) -> Self {
        Consts {
            c,
            damping: src.damping,
            slow_below: if src.stick_speed > 0.0 { src.stick_speed } else { f64::from_bits(1) },
            kr: src.kinetic_ratio,
            inv_vr: 1.0 / src.regularisation_speed,
        }
    }
}

/// The wall friction's law in a cell: one zero-sized implementation per `friction.model`,
/// matched to its name in [`Sources::with_law`]; the kernels are generic over it.
pub trait WallLaw {
    /// The friction's speed change `df` over the step of a cell whose transported speed is
    /// `w1` and speed after damping `wd`, with the stop limit `lim` (`dt limit / m`) and
    /// `slip = -kinetic_ratio lim`, and whether the cell sticks (it is then set to rest, its
    /// load kept). Friction never reverses a cell within a step: a change larger than `wd` (of
    /// the sign of `w1` since `dt d <= 1`) stops the cell instead. Written without branches
    /// (selects) so that the cell loops vectorise.
    fn change(w1: f64, wd: f64, lim: f64, slip: f64, k: &Consts) -> (f64, bool);
    /// Whether the law has a stick phase (a stuck cell's speed is exactly 0).
    const STICKS: bool;
}

/// `friction.model = "set_valued"`: Coulomb friction with a stick phase.
pub struct SetValued;

impl WallLaw for SetValued {
    const STICKS: bool = true;

    #[inline(always)]
    fn change(w1: f64, wd: f64, lim: f64, slip: f64, k: &Consts) -> (f64, bool) {
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
    }
}

/// `friction.model = "regularised"`: `tanh(w1 / v_r)` times the kinetic limit, no stick phase.
pub struct Regularised;

impl WallLaw for Regularised {
    const STICKS: bool = false;

    #[inline(always)]
    fn change(w1: f64, wd: f64, lim: f64, _slip: f64, k: &Consts) -> (f64, bool) {
        let df = -k.kr * lim * (w1 * k.inv_vr).tanh();
        (if df.abs() > wd.abs() { -wd } else { df }, false)
    }
}

/// The sources of a cell whose transported speed is `w1`, with the stop limit `lim`
/// (`dt limit / m`) and `slip = -kinetic_ratio lim`: the damping change `dd = -dt d w1`,
/// common to every law, the wall law's friction change `df` and whether the cell sticks
/// (see [`super`]).
#[inline(always)]
pub(super) fn source<L: WallLaw>(w1: f64, lim: f64, slip: f64, k: &Consts) -> (f64, f64, bool) {
    let dd = -k.damping * w1;
    let wd = w1 + dd;
    let (df, stuck) = L::change(w1, wd, lim, slip, k);
    (dd, df, stuck)
}

/// A source applied to both fields of a coupled run once per step, after both transports
/// (outside the cell loops): it changes the cells and books its own work in the ledger.
pub trait StepSource {
    fn apply(&mut self, torsion: &mut Field, axial: &mut Axial, ledger: &mut Ledger);
}

impl StepSource for CoupledFriction {
    /// The coupled wall friction ([`CoupledFriction::apply`]): its work on each field to
    /// `friction_loss` (the axial part also to `axial_friction_loss`), the weight's work it
    /// moves to `gravity_work`, the implicit step's dissipation to `inertia_loss`; the axial
    /// field's bit held below a stuck last cell within [`CoupledFriction::end_hold`].
    #[inline]
    fn apply(&mut self, torsion: &mut Field, axial: &mut Axial, ledger: &mut Ledger) {
        let work = CoupledFriction::apply(self, torsion, &mut axial.field);
        ledger.friction -= work.torsional + work.axial;
        ledger.axial_friction -= work.axial;
        ledger.gravity += work.gravity;
        ledger.inertia += work.numerical;
        axial.end_hold = self.end_hold();
    }
}

/// The sign bit of an `f64`.
const SIGN_BIT: u64 = 1 << 63;

#[cfg(test)]
mod tests {
    use super::*;

    /// The stick phase written out phase by phase (the static limit's clip of `wd` for a slow
    /// cell, the kinetic limit against the sign of `w1` for a sliding one, the stuck flag of
    /// each), against [`SetValued`]'s one threshold (through [`source`]): the same change and flag on slow, stuck
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
                    let src = Sources {
                        damping,
                        stick_speed,
                        kinetic_ratio,
                        model: FrictionModel::SetValued,
                        regularisation_speed: 0.0,
                    };
                    let k = Consts::new(0.9, &src);
                    for &w1 in &speeds {
                        for &lim in &limits {
                            let slip = -(kinetic_ratio * lim);
                            let (dd, df, stuck) = source::<SetValued>(w1, lim, slip, &k);
                            let (dd0, df0, stuck0) = written_out(w1, lim, slip, &k);
                            let case = format!(
                                "w1 {w1:e} lim {lim:e} damping {damping} stick {stick_speed} kr {kinetic_ratio}"
                            );
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

    /// [`Sources::sticks`] against the flags of the law [`Sources::with_law`] runs for each
    /// `friction.model`: a law with a stick phase stops some slow cells held within the static
    /// limit (and no sliding cell above the kinetic limit), a law without one never flags a
    /// cell.
    #[test]
    fn a_law_flags_stuck_cells_exactly_when_it_says_it_sticks() {
        /// The stuck flags of the law over slow, held and sliding cells: (any slow, any fast).
        struct Flags(Consts);
        impl WithWallLaw for Flags {
            type Output = (bool, bool);
            fn run<L: WallLaw>(self) -> (bool, bool) {
                let (mut slow, mut fast) = (false, false);
                for w1 in [-3.0, -1.0, -0.2, -1e-3, 0.0, 1e-3, 0.2, 1.0, 3.0] {
                    let (dd, df, stuck) = source::<L>(w1, 0.4, -0.26, &self.0);
                    assert!((w1 + dd + df).abs() <= (w1 + dd).abs(), "{w1}: reversed or sped up");
                    if w1.abs() < self.0.slow_below {
                        slow |= stuck;
                    } else {
                        fast |= stuck;
                    }
                }
                (slow, fast)
            }
        }
        for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
            let src =
                Sources { damping: 1e-3, stick_speed: 0.5, kinetic_ratio: 0.65, model, regularisation_speed: 0.1 };
            let (slow, fast) = src.with_law(Flags(Consts::new(0.93, &src)));
            assert_eq!((slow, fast), (src.sticks(), false), "{model:?}");
        }
    }
}
