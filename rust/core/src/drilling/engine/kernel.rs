//! The transport kernels: one step of a field's cells, the boundaries' and junctions' ghosts
//! set. [`transport`] is first-order upwind transport of the Riemann invariants (the exact
//! shift at Courant number 1) with the sources of [`super::sources`]; [`godunov`] the
//! first-order Godunov update of the `consistent` torsional law. Both run through
//! [`crate::simd::dispatch`] (AVX-512 or AVX2 when available; no fused multiply-adds, so every
//! path gives the same bits) and return the step's energy terms ([`Sums`]) for the ledger.

use super::field::{Nonlinear, Section};
use super::sources::{source, Consts, Sources};
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
}

/// Upwind transport and sources of one section: `a`, `b`, `stop`, `slip` padded (`[ghost,
/// cells, ghost]`), the new invariants written to the cells of `an`, `bn`.
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn transport(
    a: &[f64],
    b: &[f64],
    stop: &[f64],
    slip: &[f64],
    an: &mut [f64],
    bn: &mut [f64],
    c: f64,
    src: &Sources,
) -> Sums {
    let n = a.len() - 2;
    let kernel = Transport {
        a_prev: &a[..n],
        a: &a[1..=n],
        b: &b[1..=n],
        b_next: &b[2..n + 2],
        stop: &stop[1..=n],
        slip: &slip[1..=n],
        an: &mut an[1..=n],
        bn: &mut bn[1..=n],
        c,
        src,
    };
    crate::simd::dispatch(kernel)
}

struct Transport<'a> {
    a_prev: &'a [f64],
    a: &'a [f64],
    b: &'a [f64],
    b_next: &'a [f64],
    stop: &'a [f64],
    slip: &'a [f64],
    an: &'a mut [f64],
    bn: &'a mut [f64],
    c: f64,
    src: &'a Sources,
}

impl crate::simd::Kernel for Transport<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> Sums {
        // Specialised on the model and on which energy terms are non-zero (fewer stores).
        match (self.src.regularised.is_some(), self.c < 1.0, self.src.damping > 0.0) {
            (false, false, false) => self.cells::<false, false, false>(),
            (false, false, true) => self.cells::<false, false, true>(),
            (false, true, false) => self.cells::<false, true, false>(),
            (false, true, true) => self.cells::<false, true, true>(),
            (true, false, false) => self.cells::<true, false, false>(),
            (true, false, true) => self.cells::<true, false, true>(),
            (true, true, false) => self.cells::<true, true, false>(),
            (true, true, true) => self.cells::<true, true, true>(),
        }
    }
}

/// Cells side by side in [`Transport::cells`]: the energy terms are added lane by lane into
/// [`WIDTH`] accumulators (cell `i` into lane `i % WIDTH`), the lanes summed at the end.
const WIDTH: usize = 16;

/// `&x[i..i + WIDTH]` as an array (one bounds check per chunk).
#[inline(always)]
fn chunk(x: &[f64], i: usize) -> &[f64; WIDTH] {
    x[i..i + WIDTH].try_into().expect("a whole chunk")
}

#[inline(always)]
fn chunk_mut(x: &mut [f64], i: usize) -> &mut [f64; WIDTH] {
    (&mut x[i..i + WIDTH]).try_into().expect("a whole chunk")
}

impl Transport<'_> {
    /// The update loop over chunks of [`WIDTH`] cells read and written in place, the energy
    /// terms in a fixed order (so every instruction set gives the same bits).
    #[inline(always)]
    fn cells<const REGULARISED: bool, const UPWIND: bool, const DAMPED: bool>(self) -> Sums {
        let Transport { a_prev, a, b, b_next, stop, slip, an, bn, c, src } = self;
        let n = a.len();
        let k = Consts::new(c, src);
        let mut jump = [0.0; WIDTH];
        let mut fric = [0.0; WIDTH];
        let mut damp = [0.0; WIDTH];
        let whole = n - n % WIDTH;
        let mut i = 0;
        while i < whole {
            let (ap, aa, bb, bx, st, sl) =
                (chunk(a_prev, i), chunk(a, i), chunk(b, i), chunk(b_next, i), chunk(stop, i), chunk(slip, i));
            let (na, nb) = (chunk_mut(an, i), chunk_mut(bn, i));
            for l in 0..WIDTH {
                let cell = update::<REGULARISED, UPWIND>(ap[l], aa[l], bb[l], bx[l], st[l], sl[l], &k);
                na[l] = cell.an;
                nb[l] = cell.bn;
                if UPWIND {
                    jump[l] += cell.jump;
                }
                fric[l] += cell.friction;
                if DAMPED {
                    damp[l] += cell.damping;
                }
            }
            i += WIDTH;
        }
        for i in whole..n {
            let l = i - whole;
            let cell = update::<REGULARISED, UPWIND>(a_prev[i], a[i], b[i], b_next[i], stop[i], slip[i], &k);
            an[i] = cell.an;
            bn[i] = cell.bn;
            if UPWIND {
                jump[l] += cell.jump;
            }
            fric[l] += cell.friction;
            if DAMPED {
                damp[l] += cell.damping;
            }
        }
        let total = |x: &[f64; WIDTH]| x.iter().sum::<f64>();
        Sums { jumps: total(&jump), friction: total(&fric), damping: total(&damp), peak: 0.0 }
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
fn update<const REGULARISED: bool, const UPWIND: bool>(
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
    let (dd, df, stuck) = source::<REGULARISED>(w1, lim, slip, k);
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
    sp: &Section,
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
    sp: &'a Section,
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
        if self.src.regularised.is_some() {
            self.cells::<true>()
        } else {
            self.cells::<false>()
        }
    }
}

/// Cells per block of [`godunov`].
const BLOCK: usize = 128;

/// Lanes of the summation (independent accumulators, vectorisable).
const LANES: usize = 4;

/// `sum x` with [`LANES`] accumulators.
#[inline(always)]
fn lane_sum(x: &[f64]) -> f64 {
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
    fn cells<const REGULARISED: bool>(self) -> Sums {
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
                let (dd, df, stuck) = source::<REGULARISED>(w1, lim[c], slip[c], &k);
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
