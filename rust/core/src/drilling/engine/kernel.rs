//! The transport kernels: one step of a field's cells, the boundaries' and junctions' ghosts
//! set. [`transport`] is first-order upwind transport of the Riemann invariants (the exact
//! shift at Courant number 1) with the sources of [`super::sources`]; [`godunov`] the
//! first-order Godunov update of the `consistent` torsional law. Both run through
//! [`crate::simd::dispatch`] (AVX-512 or AVX2 when available; no fused multiply-adds, so every
//! path gives the same bits) and return the step's energy terms ([`Sums`]) for the ledger;
//! [`transport_unbooked`] is the same update without them (a run with
//! `numerics.energy_balance = false`), [`transport_kicked`] the update followed in the same
//! pass by a speed change per cell (the axial field's buoyed weight).

use super::field::{FieldSection, Nonlinear};
use super::sources::{source, Consts, SetValued, Sources, WallLaw, WithWallLaw};
use crate::drilling::config::FrictionModel;
use crate::drilling::grid::SectionProps;

/// Sums over a section's cells in one step.
#[derive(Default)]
pub struct Sums {
    /// `sum (d alpha^2 + d beta^2)` of the upwind differences (`consistent`: the transport's
    /// dissipation, J).
    pub jumps: f64,
    /// `sum delta_f (omega* + delta / 2)` and the same for the damping (`consistent`: their
    /// work, J, negative).
    pub friction: f64,
    pub damping: f64,
    /// Largest `|eps|` (`consistent`).
    pub peak: f64,
    /// `sum dv (v + dv / 2)` of a [`Kick`] with the ledger, summed as [`lane_sum`] sums.
    pub kick: f64,
}

/// The wall friction's limits of a section's cells as the kernels read them: per cell (the
/// `stop` and `slip` of [`super::sources::WallFriction`], padded like the invariants), or
/// none anywhere, the zeros stored without friction taken as constants. Without friction the
/// kernel computes with the same values, so it gives the same bits, but reads no limits and
/// leaves out what the constants fold away (the slow cell's threshold select: a sixth of the
/// torsional update at Courant number 1).
#[derive(Debug, Clone, Copy)]
pub enum Wall<'a> {
    Cells {
        stop: &'a [f64],
        slip: &'a [f64],
    },
    /// Every `stop` `+0` and every `slip` `-0` (the torsional wall friction's zeros,
    /// `-(kinetic_ratio 0)`; [`super::sources::WallFriction::off`]). Not with a [`Kick`].
    Off,
    /// Every `stop` and `slip` `+0` (the axial field's, which has no wall friction of its own).
    /// With a [`Kick`] only (each kernel is compiled for the walls it is given).
    OffZeros,
}

/// [`Wall`] as a kernel's constant parameter.
const CELLS: u8 = 0;
const OFF: u8 = 1;
const OFF_ZEROS: u8 = 2;

/// Upwind transport and sources of one section: `a`, `b` (and the `wall`'s limits) padded
/// (`[ghost, cells, ghost]`), the new invariants written to the cells of `an`, `bn`.
#[inline]
pub fn transport(a: &[f64], b: &[f64], wall: Wall, an: &mut [f64], bn: &mut [f64], c: f64, src: &Sources) -> Sums {
    crate::simd::dispatch(Transport::new(a, b, wall, an, bn, c, src, true))
}

/// [`transport`] without the energy terms (the same new invariants, bit for bit; no sums).
#[inline]
pub fn transport_unbooked(a: &[f64], b: &[f64], wall: Wall, an: &mut [f64], bn: &mut [f64], c: f64, src: &Sources) {
    crate::simd::dispatch(Transport::new(a, b, wall, an, bn, c, src, false));
}

/// A speed change added to every cell after the transport and the other sources (the
/// coupled run's buoyed weight, `dt g_eff` per padded index) and, with the ledger (`booked`),
/// the sum of its work per cell, `dv (v + dv / 2)` with `v` the speed before it
/// ([`Sums::kick`]).
pub struct Kick<'a> {
    pub dv: &'a [f64],
    pub booked: bool,
}

/// [`transport`] (with the energy terms when `kick.booked`, else none) followed by the speed
/// change `kick` in the same pass over the cells: the bits of [`transport`] then `alpha +=
/// dv`, `beta += dv` cell by cell, and the kick's work summed in four lanes in the order of
/// [`lane_sum`] over the cells (the same bits).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn transport_kicked(
    a: &[f64],
    b: &[f64],
    wall: Wall,
    an: &mut [f64],
    bn: &mut [f64],
    c: f64,
    src: &Sources,
    kick: Kick,
) -> Sums {
    let mut transport = Transport::new(a, b, wall, an, bn, c, src, kick.booked);
    let n = transport.a.len();
    transport.dv = &kick.dv[1..=n];
    crate::simd::dispatch(transport)
}

struct Transport<'a> {
    a_prev: &'a [f64],
    a: &'a [f64],
    b: &'a [f64],
    b_next: &'a [f64],
    /// The wall's limits (of the cells, without the ghosts).
    wall: Wall<'a>,
    an: &'a mut [f64],
    bn: &'a mut [f64],
    c: f64,
    src: &'a Sources,
    /// Whether the energy terms are summed ([`Sums`]; zero without).
    ledger: bool,
    /// The cells' [`Kick`] (empty: none).
    dv: &'a [f64],
}

impl<'a> Transport<'a> {
    /// The kernel over the cells of padded `a`, `b` and `wall` (`[ghost, cells, ghost]`),
    /// writing the cells of `an`, `bn`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn new(
        a: &'a [f64],
        b: &'a [f64],
        wall: Wall<'a>,
        an: &'a mut [f64],
        bn: &'a mut [f64],
        c: f64,
        src: &'a Sources,
        ledger: bool,
    ) -> Self {
        let n = a.len() - 2;
        Transport {
            a_prev: &a[..n],
            a: &a[1..=n],
            b: &b[1..=n],
            b_next: &b[2..n + 2],
            wall: match wall {
                Wall::Cells { stop, slip } => Wall::Cells { stop: &stop[1..=n], slip: &slip[1..=n] },
                off => off,
            },
            an: &mut an[1..=n],
            bn: &mut bn[1..=n],
            c,
            src,
            ledger,
            dv: &[],
        }
    }
}

impl crate::simd::Kernel for Transport<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> Sums {
        let src = self.src;
        match (self.ledger, self.dv.is_empty()) {
            (true, true) => src.with_law(Specialised::<true>(self)),
            (false, true) => src.with_law(Specialised::<false>(self)),
            (true, false) => self.kicked::<true>(),
            (false, false) => self.kicked::<false>(),
        }
    }
}

/// [`Transport`] without a [`Kick`], with the ledger or without, run with the wall law.
struct Specialised<'a, const LEDGER: bool>(Transport<'a>);

impl<const LEDGER: bool> WithWallLaw for Specialised<'_, LEDGER> {
    type Output = Sums;

    #[inline(always)]
    fn run<L: WallLaw>(self) -> Sums {
        self.0.specialised::<L, LEDGER>()
    }
}

impl Transport<'_> {
    /// [`Transport::cells`] with the wall law `L`, specialised on which energy terms are
    /// non-zero (fewer stores) and on a wall without friction ([`Wall::Off`]; the axial
    /// field's [`Wall::OffZeros`] is a kick's).
    #[inline(always)]
    fn specialised<L: WallLaw, const LEDGER: bool>(self) -> Sums {
        match self.wall {
            Wall::Cells { .. } => self.damped::<L, LEDGER, false, CELLS>(),
            Wall::Off => self.damped::<L, LEDGER, false, OFF>(),
            Wall::OffZeros => panic!("the axial field's wall without a kick"),
        }
    }

    /// [`Transport::cells`] with a [`Kick`] (the axial field: set-valued friction only), its
    /// wall without friction ([`Wall::OffZeros`]) or any.
    #[inline(always)]
    fn kicked<const LEDGER: bool>(self) -> Sums {
        assert!(self.src.model == FrictionModel::SetValued, "a kick with the set-valued friction only");
        match self.wall {
            Wall::Cells { .. } => self.damped::<SetValued, LEDGER, true, CELLS>(),
            Wall::OffZeros => self.damped::<SetValued, LEDGER, true, OFF_ZEROS>(),
            Wall::Off => panic!("a kick with the torsional wall's zeros"),
        }
    }

    /// [`Transport::cells`] at Courant number 1 or below, with damping or without.
    #[inline(always)]
    fn damped<L: WallLaw, const LEDGER: bool, const KICK: bool, const WALL: u8>(self) -> Sums {
        match (self.c < 1.0, self.src.damping > 0.0) {
            (false, false) => self.wide::<L, false, false, LEDGER, KICK, WALL>(),
            (false, true) => self.wide::<L, false, true, LEDGER, KICK, WALL>(),
            (true, false) => self.wide::<L, true, false, LEDGER, KICK, WALL>(),
            (true, true) => self.wide::<L, true, true, LEDGER, KICK, WALL>(),
        }
    }

    /// [`Transport::cells`] in chunks of [`WIDTH`] cells with the ledger, else of
    /// [`UNBOOKED_WALL`] or [`UNBOOKED_OFF`] cells.
    #[inline(always)]
    fn wide<L: WallLaw, const UPWIND: bool, const DAMPED: bool, const LEDGER: bool, const KICK: bool, const WALL: u8>(
        self,
    ) -> Sums {
        if LEDGER {
            self.cells::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, WIDTH>()
        } else if KICK || WALL != CELLS {
            self.cells::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, UNBOOKED_OFF>()
        } else {
            self.cells::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, UNBOOKED_WALL>()
        }
    }
}

/// The energy terms are added lane by lane into [`WIDTH`] accumulators (cell `i` into lane
/// `i % WIDTH`), the lanes summed at the end: eight, two AVX2 registers or one AVX-512
/// register per sum, so that the three sums and the update of a chunk fit AVX2's sixteen
/// registers. (Sixteen lanes, until 2026-12-08, spilled them on AVX2.)
const WIDTH: usize = 8;

/// Cells per chunk without the ledger (no lanes to keep), as measured fastest on AVX2 and
/// AVX-512 alike: eight with a wall of cells (the update then fits AVX2's registers: 0.80
/// against 1.03 ns per cell update), sixteen with a wall without friction or a kick (the
/// coupled fields; eight were compiled into loads lane by lane there: the coupled example
/// 0.62 against 0.46 s on AVX2).
const UNBOOKED_WALL: usize = 8;
const UNBOOKED_OFF: usize = 16;

/// The energy terms of a step, lane by lane (`W` lanes: [`WIDTH`] with the ledger).
struct Lanes<const W: usize> {
    jump: [f64; W],
    fric: [f64; W],
    damp: [f64; W],
}

impl<const W: usize> Lanes<W> {
    fn new() -> Self {
        Lanes { jump: [0.0; W], fric: [0.0; W], damp: [0.0; W] }
    }
}

/// A chunk of `W` cells.
type Chunk<const W: usize> = [f64; W];

impl Transport<'_> {
    /// The update loop over chunks of `W` cells read and written in place, the energy
    /// terms added lane by lane in a fixed order (so every instruction set gives the same
    /// bits), the accumulators in registers. The last `n % W` cells go through the same
    /// chunk code: the last whole chunk of the section again, or in a section shorter than a
    /// chunk padded with cells at rest without friction, whose terms are zeros (adding a zero
    /// leaves a lane's sum unchanged, bit for bit: a lane's sum is never `-0`).
    /// Without `LEDGER` no energy term is computed and the sums are zero. With `WALL` not
    /// `CELLS` the limits are the constants of [`Wall::Off`] or [`Wall::OffZeros`].
    #[inline(always)]
    fn cells<
        L: WallLaw,
        const UPWIND: bool,
        const DAMPED: bool,
        const LEDGER: bool,
        const KICK: bool,
        const WALL: u8,
        const W: usize,
    >(
        self,
    ) -> Sums {
        let Transport { a_prev, a, b, b_next, wall, an, bn, c, src, dv, .. } = self;
        let n = a.len();
        let (stop, slip) = match wall {
            Wall::Cells { stop, slip } if WALL == CELLS => (stop, slip),
            _ if WALL == CELLS => unreachable!("a wall of cells"),
            // (not read)
            _ => (a, a),
        };
        let k = Consts::new(c, src);
        let mut lanes = Lanes::<W>::new();
        // Every slice exactly `n` long, so that `i + W <= n` proves the chunks in bounds
        // (the kick's only where it is used).
        let (a_prev, a, b, b_next, stop, slip) = (&a_prev[..n], &a[..n], &b[..n], &b_next[..n], &stop[..n], &slip[..n]);
        let (an, bn) = (&mut an[..n], &mut bn[..n]);
        let dv = if KICK { &dv[..n] } else { dv };
        macro_rules! at {
            ($x:expr, $i:expr) => {
                <&Chunk<W>>::try_from(&$x[$i..$i + W]).expect("a whole chunk")
            };
        }
        macro_rules! at_mut {
            ($x:expr, $i:expr) => {
                <&mut Chunk<W>>::try_from(&mut $x[$i..$i + W]).expect("a whole chunk")
            };
        }
        // The kick's work in the lanes of [`lane_sum`] (cell `i` into lane `i % LANES`; a chunk
        // starts at a multiple of LANES).
        let mut kick_lanes = [0.0; LANES];
        let (none, mut w) = ([0.0; W], [0.0; W]);
        let mut i = 0;
        while i + W <= n {
            let inputs = [at!(a_prev, i), at!(a, i), at!(b, i), at!(b_next, i), at!(stop, i), at!(slip, i)];
            let kick = if KICK { at!(dv, i) } else { &none };
            let (na, nb) = (at_mut!(an, i), at_mut!(bn, i));
            chunk::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, W>(inputs, kick, na, nb, &mut w, &k, &mut lanes);
            if KICK && LEDGER {
                for block in w.chunks_exact(LANES) {
                    for l in 0..LANES {
                        kick_lanes[l] += block[l];
                    }
                }
            }
            i += W;
        }
        // (the sum of the last `n % LANES` cells', empty unless a tail has them)
        let mut kick_rest = [0.0_f64; 0].iter().sum::<f64>();
        if i < n && n >= W {
            // The last chunk ends at the last cell: it overlaps the one before, whose cells it
            // writes again with the values they have (the inputs are not written), and the
            // terms of its cells from `i` on go to their lanes (cell `j` into lane `j - i`,
            // `j % W`). The terms come to the lanes as `0 + term`, which adds to a lane as
            // `term` does (a lane's sum is never -0). No copies to a padded chunk, which the
            // compiler makes calls of.
            let s = n - W;
            let inputs = [at!(a_prev, s), at!(a, s), at!(b, s), at!(b_next, s), at!(stop, s), at!(slip, s)];
            let kick = if KICK { at!(dv, s) } else { &none };
            let (na, nb) = (at_mut!(an, s), at_mut!(bn, s));
            let mut last = Lanes::<W>::new();
            chunk::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, W>(inputs, kick, na, nb, &mut w, &k, &mut last);
            if LEDGER {
                for j in i..n {
                    lanes.jump[j - i] += last.jump[j - s];
                    lanes.fric[j - i] += last.fric[j - s];
                    lanes.damp[j - i] += last.damp[j - s];
                }
            }
            if KICK && LEDGER {
                let blocks = w[i - s..].chunks_exact(LANES);
                kick_rest = blocks.remainder().iter().sum::<f64>();
                for block in blocks {
                    for l in 0..LANES {
                        kick_lanes[l] += block[l];
                    }
                }
            }
        } else if i < n {
            // Fewer cells than a chunk: copied element by element into a padded one.
            let mut pad = [[0.0; W]; 7];
            let dv = if KICK { &dv[i..] } else { dv };
            for (p, x) in pad.iter_mut().zip([&a_prev[i..], &a[i..], &b[i..], &b_next[i..], &stop[i..], &slip[i..], dv])
            {
                for (y, &v) in p.iter_mut().zip(x) {
                    *y = v;
                }
            }
            let [ap, aa, bb, bx, st, sl, kick] = &pad;
            let (mut na, mut nb, mut w) = ([0.0; W], [0.0; W], [0.0; W]);
            let inputs = [ap, aa, bb, bx, st, sl];
            chunk::<L, UPWIND, DAMPED, LEDGER, KICK, WALL, W>(inputs, kick, &mut na, &mut nb, &mut w, &k, &mut lanes);
            for (j, (x, y)) in an[i..].iter_mut().zip(&mut bn[i..]).enumerate() {
                *x = na[j];
                *y = nb[j];
            }
            if KICK && LEDGER {
                let blocks = w[..n - i].chunks_exact(LANES);
                kick_rest = blocks.remainder().iter().sum::<f64>();
                for block in blocks {
                    for l in 0..LANES {
                        kick_lanes[l] += block[l];
                    }
                }
            }
        }
        // The lanes in order, the three sums side by side (a lane's sum is never -0, so
        // starting from 0 gives the bits of `Iterator::sum`).
        let mut sums = Sums::default();
        for l in 0..W {
            sums.jumps += lanes.jump[l];
            sums.friction += lanes.fric[l];
            sums.damping += lanes.damp[l];
        }
        if KICK && LEDGER {
            sums.kick = kick_lanes.iter().sum::<f64>() + kick_rest;
        }
        sums
    }
}

/// One chunk: `[a_prev, a, b, b_next, stop, slip]` and the kick in, `alpha`, `beta` and the
/// kick's work out (separate references, so that the compiler knows they alias nothing; in
/// an array of references it does not, and the loop measured a fifth slower), the energy
/// terms added to `lanes` (cell `l` of the chunk into lane `l`) with `LEDGER`. With `KICK`
/// the speed change `dv` follows the update, as a source after it: its work
/// `dv (v + dv / 2)` at the speed `v` the update left. With `WALL` not `CELLS`, `st` and `sl`
/// are not read: the limits are [`Wall::Off`]'s or [`Wall::OffZeros`]'s constants.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn chunk<
    L: WallLaw,
    const UPWIND: bool,
    const DAMPED: bool,
    const LEDGER: bool,
    const KICK: bool,
    const WALL: u8,
    const W: usize,
>(
    [ap, aa, bb, bx, st, sl]: [&Chunk<W>; 6],
    kick: &Chunk<W>,
    na: &mut Chunk<W>,
    nb: &mut Chunk<W>,
    work: &mut Chunk<W>,
    k: &Consts,
    lanes: &mut Lanes<W>,
) {
    for l in 0..W {
        let (lim, slip) = match WALL {
            CELLS => (st[l], sl[l]),
            OFF => (0.0, -0.0),
            _ => (0.0, 0.0),
        };
        let cell = update::<L, UPWIND>(ap[l], aa[l], bb[l], bx[l], lim, slip, k);
        if KICK {
            let dv = kick[l];
            if LEDGER {
                let v = 0.5 * (cell.an + cell.bn);
                work[l] = dv * (v + 0.5 * dv);
            }
            na[l] = cell.an + dv;
            nb[l] = cell.bn + dv;
        } else {
            na[l] = cell.an;
            nb[l] = cell.bn;
        }
        if LEDGER {
            if UPWIND {
                lanes.jump[l] += cell.jump;
            }
            lanes.fric[l] += cell.friction;
            if DAMPED {
                lanes.damp[l] += cell.damping;
            }
        }
    }
}

/// What one cell's update adds and writes.
struct Cell {
    an: f64,
    bn: f64,
    jump: f64,
    friction: f64,
    damping: f64,
}

/// One cell: upwind transport of the invariants from `(a_prev, a)` and `(b, b_next)` (at
/// Courant number 1, `!UPWIND`, the exact shift `a_prev`, `b_next`), then the damping and
/// friction sources; branch-free (selects) so that blocks vectorise.
#[inline(always)]
fn update<L: WallLaw, const UPWIND: bool>(
    a_prev: f64,
    a: f64,
    b: f64,
    b_next: f64,
    lim: f64,
    slip: f64,
    k: &Consts,
) -> Cell {
    let (da, db) = (a - a_prev, b - b_next);
    let (a1, b1) = if UPWIND { (a - k.c * da, b - k.c * db) } else { (a_prev, b_next) };
    let w1 = 0.5 * (a1 + b1);
    let (dd, df, stuck) = source::<L>(w1, lim, slip, k);
    let d = dd + df;
    let wbar = w1 + 0.5 * d;
    // Stuck: stopped exactly (omega = 0), the torque kept.
    let s1 = 0.5 * (a1 - b1);
    Cell {
        an: if stuck { s1 } else { a1 + d },
        bn: if stuck { -s1 } else { b1 + d },
        jump: da * da + db * db,
        friction: df * wbar,
        damping: dd * wbar,
    }
}

/// One step of the `consistent` scheme on section `sp` (law `law`; faces at the boundaries
/// and junctions set): the faces inside it by the acoustic (two-wave) Riemann solver with the
/// larger tangent impedance of the two cells, `omega* = (w_l + w_r) / 2 + (tau_l - tau_r) / (2 Z)`,
/// `tau* = (tau_l + tau_r) / 2 + Z (w_l - w_r) / 2`, then the finite-volume update
/// `omega += dt (tau*_top - tau*_bottom) / (rho J h)`, `eps += dt (omega*_top - omega*_bottom) / h`
/// and the sources. Returns the sums, with `jumps` the transport's dissipation
/// `dt (tau*_top omega*_top - tau*_bottom omega*_bottom) - dE` (J) and `friction`, `damping`
/// the work of the sources (J, negative).
pub fn godunov(
    nl: &mut Nonlinear,
    sp: &FieldSection,
    law: SectionProps,
    (stop, slip): (&[f64], &[f64]),
    dt: f64,
    src: &Sources,
) -> Sums {
    crate::simd::dispatch(Godunov { nl, sp, law, stop, slip, dt, src })
}

/// [`godunov`] as a [`crate::simd::Kernel`] (AVX2 code when available; no fused multiply-adds).
struct Godunov<'a> {
    nl: &'a mut Nonlinear,
    sp: &'a FieldSection,
    law: SectionProps,
    stop: &'a [f64],
    slip: &'a [f64],
    dt: f64,
    src: &'a Sources,
}

impl crate::simd::Kernel for Godunov<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> Sums {
        let src = self.src;
        src.with_law(self)
    }
}

impl WithWallLaw for Godunov<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<L: WallLaw>(self) -> Sums {
        self.cells::<L>()
    }
}

/// Cells per block of [`godunov`].
const BLOCK: usize = 128;

/// Lanes of the summation (independent accumulators, vectorisable).
const LANES: usize = 4;

/// `sum x` with [`LANES`] accumulators.
#[inline(always)]
pub(super) fn lane_sum(x: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let blocks = x.chunks_exact(LANES);
    let rest = blocks.remainder();
    for blk in blocks {
        for l in 0..LANES {
            acc[l] += blk[l];
        }
    }
    acc.iter().sum::<f64>() + rest.iter().sum::<f64>()
}

impl Godunov<'_> {
    #[inline(always)]
    fn cells<L: WallLaw>(self) -> Sums {
        let Godunov { nl, sp, law, stop, slip, dt, src } = self;
        let p = &law;
        let r = sp.offset + 1..=sp.offset + sp.cells;
        let Nonlinear {
            omega,
            strain,
            omega_next,
            strain_next,
            face_omega,
            face_torque,
            cell_impedance,
            cell_torque,
            ..
        } = nl;
        // Tangent impedance and torque of every cell, then the faces inside the section.
        for ((z, t), &eps) in
            cell_impedance[r.clone()].iter_mut().zip(&mut cell_torque[r.clone()]).zip(&strain[r.clone()])
        {
            *z = p.tangent_impedance(eps);
            *t = p.torque(eps);
        }
        let inner = sp.offset + 1..sp.offset + sp.cells;
        let (zc, tc, wc) = (&cell_impedance[r.clone()], &cell_torque[r.clone()], &omega[r.clone()]);
        for (k, (fw, ft)) in face_omega[inner.clone()].iter_mut().zip(&mut face_torque[inner]).enumerate() {
            let (wl, wr) = (wc[k], wc[k + 1]);
            let z = zc[k].max(zc[k + 1]);
            let (tl, tr) = (tc[k], tc[k + 1]);
            *fw = 0.5 * (wl + wr) + 0.5 * (tl - tr) / z;
            *ft = 0.5 * (tl + tr) + 0.5 * z * (wl - wr);
        }
        let k = Consts::new(0.0, src);
        let (k1, k2, k5, h) = (p.inertia_per_length, p.stiffness, p.quartic, sp.h);
        let (rw, rs) = (dt / (k1 * h), dt / h);
        let mut sums = Sums::default();
        let faces = sp.offset..=sp.offset + sp.cells;
        let (fw, ft) = (&face_omega[faces.clone()], &face_torque[faces]);
        let (w0, s0, lim, slip) = (&omega[r.clone()], &strain[r.clone()], &stop[r.clone()], &slip[r.clone()]);
        let (wn, sn) = (&mut omega_next[r.clone()], &mut strain_next[r]);
        // Blocks of BLOCK cells whose per-cell terms stay on the stack, each then summed in
        // lanes, so that the update loop vectorises.
        let (mut jump, mut fric, mut damp, mut peak) = ([0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
        let mut start = 0;
        while start < sp.cells {
            let m = BLOCK.min(sp.cells - start);
            for j in 0..m {
                let c = start + j;
                let (wt, tt, wb, tb) = (fw[c], ft[c], fw[c + 1], ft[c + 1]);
                let (w, s) = (w0[c], s0[c]);
                let w1 = w + rw * (tt - tb);
                let s1 = s + rs * (wt - wb);
                let de = h
                    * (0.5 * k1 * (w1 - w) * (w1 + w)
                        + (s1 - s) * (s1 + s) * (0.5 * k2 + 0.25 * k5 * (s1 * s1 + s * s)));
                jump[j] = dt * (tt * wt - tb * wb) - de;
                let (dd, df, stuck) = source::<L>(w1, lim[c], slip[c], &k);
                let d = dd + df;
                let wbar = w1 + 0.5 * d;
                wn[c] = if stuck { 0.0 } else { w1 + d };
                sn[c] = s1;
                fric[j] = df * wbar;
                damp[j] = dd * wbar;
                peak[j] = s1.abs();
            }
            sums.jumps += lane_sum(&jump[..m]);
            sums.friction += k1 * h * lane_sum(&fric[..m]);
            sums.damping += k1 * h * lane_sum(&damp[..m]);
            sums.peak = peak[..m].iter().fold(sums.peak, |a, &b| if b > a { b } else { a });
            start += m;
        }
        sums
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drilling::engine::sources::Regularised;
    use FrictionModel as Model;

    /// The chunked kernel, with the last cells through the last whole chunk again (or padded
    /// to a chunk below one), against the update cell by cell with the energy terms in lane
    /// `j % WIDTH`: the same bits, on every path and for counts below, at and above a chunk,
    /// stuck, slow and sliding cells, both friction laws.
    #[test]
    fn chunks_and_padding_give_the_bits_of_the_cell_by_cell_update() {
        for n in [1, 5, 8, 9, 16, 17, 31, 40, 91] {
            let len = n + 2;
            let a: Vec<f64> = (0..len).map(|i| (i as f64 * 0.77).sin() * 2.0).collect();
            let b: Vec<f64> = (0..len).map(|i| (i as f64 * 0.31).cos() * 2.0 - 0.5).collect();
            let stop: Vec<f64> =
                (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { 0.3 + 0.1 * (i % 3) as f64 }).collect();
            let slip: Vec<f64> = stop.iter().map(|&s| -(0.65 * s)).collect();
            for (c, model) in [
                (0.93, Model::SetValued),
                (1.0, Model::SetValued),
                (0.93, Model::Regularised),
                (1.0, Model::Regularised),
            ] {
                let src =
                    Sources { damping: 1e-3, stick_speed: 1.5, kinetic_ratio: 0.65, model, regularisation_speed: 0.1 };
                let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
                let fast = transport(&a, &b, Wall::Cells { stop: &stop, slip: &slip }, &mut an, &mut bn, c, &src);
                let (mut an0, mut bn0) = (vec![0.0; len], vec![0.0; len]);
                let slow = crate::simd::baseline(Transport::new(
                    &a,
                    &b,
                    Wall::Cells { stop: &stop, slip: &slip },
                    &mut an0,
                    &mut bn0,
                    c,
                    &src,
                    true,
                ));
                let (mut an1, mut bn1) = (vec![0.0; len], vec![0.0; len]);
                transport_unbooked(&a, &b, Wall::Cells { stop: &stop, slip: &slip }, &mut an1, &mut bn1, c, &src);
                assert_eq!(
                    an1.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    an.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
                );
                assert_eq!(
                    bn1.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    bn.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
                );
                // The reference: cell by cell.
                let k = Consts::new(c, &src);
                let mut lanes = Lanes::<WIDTH>::new();
                let mut stuck = 0;
                for j in 0..n {
                    let i = j + 1;
                    let cell = if model == Model::Regularised {
                        if c < 1.0 {
                            update::<Regularised, true>(a[i - 1], a[i], b[i], b[i + 1], stop[i], slip[i], &k)
                        } else {
                            update::<Regularised, false>(a[i - 1], a[i], b[i], b[i + 1], stop[i], slip[i], &k)
                        }
                    } else if c < 1.0 {
                        update::<SetValued, true>(a[i - 1], a[i], b[i], b[i + 1], stop[i], slip[i], &k)
                    } else {
                        update::<SetValued, false>(a[i - 1], a[i], b[i], b[i + 1], stop[i], slip[i], &k)
                    };
                    assert_eq!(
                        (an[i].to_bits(), bn[i].to_bits()),
                        (cell.an.to_bits(), cell.bn.to_bits()),
                        "n {n} c {c} cell {j}"
                    );
                    assert_eq!((an0[i].to_bits(), bn0[i].to_bits()), (cell.an.to_bits(), cell.bn.to_bits()));
                    stuck += usize::from(cell.an + cell.bn == 0.0);
                    if c < 1.0 {
                        lanes.jump[j % WIDTH] += cell.jump;
                    }
                    lanes.fric[j % WIDTH] += cell.friction;
                    lanes.damp[j % WIDTH] += cell.damping;
                }
                let total = |x: &[f64; WIDTH]| x.iter().sum::<f64>();
                for sums in [&fast, &slow] {
                    assert_eq!(sums.jumps.to_bits(), total(&lanes.jump).to_bits(), "n {n} c {c}");
                    assert_eq!(sums.friction.to_bits(), total(&lanes.fric).to_bits(), "n {n} c {c}");
                    assert_eq!(sums.damping.to_bits(), total(&lanes.damp).to_bits(), "n {n} c {c}");
                }
                if n >= 16 && model == Model::SetValued {
                    assert!(stuck > 0 && stuck < n, "n {n}: {stuck} stuck cells (the case must hold both)");
                }
            }
        }
    }

    /// [`transport_kicked`] against [`transport`] followed by the kick cell by cell (the speed
    /// `v = (alpha + beta) / 2`, work `dv (v + dv / 2)`, `alpha += dv`, `beta += dv`): the same
    /// bits, with and without the ledger, below, at and above a chunk, upwind and at Courant
    /// number 1.
    #[test]
    fn the_kick_in_the_pass_gives_the_bits_of_the_kick_after_it() {
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for n in [1, 5, 8, 9, 16, 17, 40, 91] {
            let len = n + 2;
            let a: Vec<f64> = (0..len).map(|i| (i as f64 * 0.77).sin() * 2.0).collect();
            let b: Vec<f64> = (0..len).map(|i| (i as f64 * 0.31).cos() * 2.0 - 0.5).collect();
            let zeros = vec![0.0; len];
            let dv: Vec<f64> =
                (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { 1e-3 * (1.0 + (i % 5) as f64) }).collect();
            for c in [0.93, 1.0] {
                let src = Sources {
                    damping: 1e-3,
                    stick_speed: 0.0,
                    kinetic_ratio: 0.0,
                    model: Model::SetValued,
                    regularisation_speed: 0.0,
                };
                let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
                let sums = transport(&a, &b, Wall::Cells { stop: &zeros, slip: &zeros }, &mut an, &mut bn, c, &src);
                let mut work = vec![0.0; len];
                for i in 1..=n {
                    let v = 0.5 * (an[i] + bn[i]);
                    work[i] = dv[i] * (v + 0.5 * dv[i]);
                    an[i] += dv[i];
                    bn[i] += dv[i];
                }
                let (mut ak, mut bk) = (vec![0.0; len], vec![0.0; len]);
                let kicked = transport_kicked(
                    &a,
                    &b,
                    Wall::Cells { stop: &zeros, slip: &zeros },
                    &mut ak,
                    &mut bk,
                    c,
                    &src,
                    Kick { dv: &dv, booked: true },
                );
                assert_eq!((bits(&ak), bits(&bk)), (bits(&an), bits(&bn)), "n {n} c {c}");
                assert_eq!(kicked.kick.to_bits(), lane_sum(&work[1..=n]).to_bits(), "n {n} c {c}");
                let pairs =
                    [(kicked.jumps, sums.jumps), (kicked.friction, sums.friction), (kicked.damping, sums.damping)];
                assert!(pairs.iter().all(|(x, y)| x.to_bits() == y.to_bits()), "n {n} c {c}");
                let (mut au, mut bu) = (vec![0.0; len], vec![0.0; len]);
                transport_kicked(
                    &a,
                    &b,
                    Wall::Cells { stop: &zeros, slip: &zeros },
                    &mut au,
                    &mut bu,
                    c,
                    &src,
                    Kick { dv: &dv, booked: false },
                );
                assert_eq!((bits(&au), bits(&bu)), (bits(&an), bits(&bn)), "n {n} c {c} without the ledger");
            }
        }
    }

    /// A wall without friction taken as constants ([`Wall::Off`], [`Wall::OffZeros`]) against
    /// the same zeros read per cell: the same bits of the invariants and the energy terms, with
    /// and without the ledger, a kick, damping, below, at and above a chunk, upwind and at
    /// Courant number 1, on cells at rest, at signed zeros and tiny speeds.
    #[test]
    fn a_wall_without_friction_gives_the_bits_of_its_zeros_per_cell() {
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for n in [1, 5, 8, 9, 16, 17, 40, 91] {
            let len = n + 2;
            let special = [0.0, -0.0, 1e-320, -1e-320, 5e-324];
            let a: Vec<f64> =
                (0..len).map(|i| if i % 7 == 3 { special[i % 5] } else { (i as f64 * 0.77).sin() }).collect();
            let b: Vec<f64> =
                (0..len).map(|i| if i % 7 == 3 { -a[i] } else { (i as f64 * 0.31).cos() - 0.5 }).collect();
            let dv: Vec<f64> =
                (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { 1e-3 * (i % 3) as f64 }).collect();
            let (zeros, negative) = (vec![0.0; len], vec![-0.0; len]);
            for (c, damping, stick_speed) in [(0.93, 1e-3, 0.0), (1.0, 1e-3, 0.5), (1.0, 0.0, 0.0), (0.93, 0.0, 0.5)] {
                let src = Sources {
                    damping,
                    stick_speed,
                    kinetic_ratio: 0.0,
                    model: FrictionModel::SetValued,
                    regularisation_speed: 0.0,
                };
                for (off, slip) in [(Wall::Off, &negative), (Wall::OffZeros, &zeros)] {
                    let cells = Wall::Cells { stop: &zeros, slip };
                    for booked in [true, false] {
                        for kicked in [true, false] {
                            let run = |wall: Wall| {
                                let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
                                let sums = if kicked {
                                    transport_kicked(&a, &b, wall, &mut an, &mut bn, c, &src, Kick { dv: &dv, booked })
                                } else if booked {
                                    transport(&a, &b, wall, &mut an, &mut bn, c, &src)
                                } else {
                                    transport_unbooked(&a, &b, wall, &mut an, &mut bn, c, &src);
                                    Sums::default()
                                };
                                (bits(&an), bits(&bn), bits(&[sums.jumps, sums.friction, sums.damping, sums.kick]))
                            };
                            // (each wall without friction is compiled for its field's kernel)
                            if kicked != matches!(off, Wall::OffZeros) {
                                continue;
                            }
                            assert_eq!(run(off), run(cells), "n {n} c {c} {off:?} booked {booked} kicked {kicked}");
                        }
                    }
                }
            }
        }
    }

    /// The time per cell update of [`transport`] on 1000 cells (Courant number 0.998,
    /// damping, set-valued friction, a third of the cells slow): the best of many short
    /// windows. `cargo test --release kernel_time -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn kernel_time() {
        let n = 1000;
        let len = n + 2;
        let a: Vec<f64> = (0..len).map(|i| (i as f64 * 0.37).sin() * 3.0).collect();
        let b: Vec<f64> = (0..len).map(|i| (i as f64 * 0.11).cos() * 3.0).collect();
        let stop: Vec<f64> = (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { 0.02 }).collect();
        let slip: Vec<f64> = stop.iter().map(|&s| -(0.65 * s)).collect();
        let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
        for (name, c, damping, ledger) in [
            ("upwind, damped", 0.998, 1e-4, true),
            ("upwind, damped, no ledger", 0.998, 1e-4, false),
            ("Courant 1, damped", 1.0, 1e-4, true),
            ("Courant 1", 1.0, 0.0, true),
        ] {
            let src = Sources {
                damping,
                stick_speed: 1.5,
                kinetic_ratio: 0.65,
                model: Model::SetValued,
                regularisation_speed: 0.0,
            };
            let mut best = f64::INFINITY;
            let mut sink = 0.0;
            for _ in 0..400 {
                let start = std::time::Instant::now();
                for _ in 0..50 {
                    if ledger {
                        sink += transport(&a, &b, Wall::Cells { stop: &stop, slip: &slip }, &mut an, &mut bn, c, &src)
                            .friction;
                    } else {
                        transport_unbooked(&a, &b, Wall::Cells { stop: &stop, slip: &slip }, &mut an, &mut bn, c, &src);
                    }
                    sink += an[n / 2];
                }
                best = best.min(start.elapsed().as_secs_f64() / (50 * n) as f64);
            }
            println!("transport, {name}: {:.3} ns per cell update ({})", best * 1e9, crate::simd::path());
            assert!(sink.is_finite());
        }
    }
}
