//! Dense output of the Runge-Kutta-Nystrom pairs: Hermite-Birkhoff interpolation of the
//! step ends.
//!
//! At every step end `t_k` the solve knows `q_k`, `v_k` and `a_k = a(q_k)` (the next step's
//! first stage, no extra evaluation). On the output interval `[t_j, t_j+1]` the positions are
//! the polynomial `p` of degree `3m - 1 = 17` matching `q`, `q'` and `q''` at the `m = 6`
//! ends `t_j-2 .. t_j+3` (where the solve has fewer ends on one side, more on the other:
//! the window is balanced in steps, not in time, [`Birkhoff::window`]), and the velocities
//! are `p'`. Before `t0` and after `t_end` the solve takes two extra steps for these windows
//! (the lead-in and lead-out of [`super::rkn`]), so no interval of a solve that reaches
//! `t_end` has a one-sided window. For a
//! smooth solution the interpolation error is `O(h^18)` in `q` and `O(h^17)` in `v`, far
//! below the RKN12 pair's own error at the step sizes its control picks, provided
//! consecutive steps do not differ too much (`rkn.rs` lets a step at most double the
//! previous one when output times are requested). Measured against exact solutions
//! (`rkn_tests.rs`, a linear two-mass chain over 40 s): the dense error is within 1.3 times
//! the error at the step ends for `rtol = atol = 1e-8 .. 1e-12`; at `rtol = 1e-13` (`atol =
//! 1e-15`) 1.5e-13 against 2e-14 (on the ramp of doubling first steps), and near rounding
//! (`rtol = 1e-15`) 2.7e-14. On the 3-mode reference case (`benchmarks/compare_scipy.py`)
//! the lead-in made the dense error of the velocities 43 times smaller: the one-sided
//! window of the first interval had been 200 times less accurate than the others (the
//! product of the node distances, cubed, is 75 times larger for equal steps); the lead-out
//! did the same for the last interval, up to 40 times less accurate without it
//! (`tests/test_rkn12.py`). A solve that ends early (a failure) leaves its last intervals
//! one-sided and a few times less accurate.
//! (Four ends, degree 11, `O(h^12)`, were 100 times above the tolerance at `rtol = 1e-8`;
//! capping the steps by an estimate of that error, the last Newton term, kept them within it
//! at 1.7-1.9 times the steps. Near rounding such an estimate is noise that grows as the
//! step shrinks, and it drove the steps to underflow at `rtol = 1e-15`.)
//!
//! `p` is formed once per interval, in the variable `s = (t - t_j) / h_j` (`h_j = t_j+1 -
//! t_j`), as a Newton form: the confluent divided differences of the nodes (each end three
//! times, with `q`, `h q'` and `h^2 q'' / 2` in those units; the ends nearest the interval
//! first), four components side by side. The Newton form is then multiplied out into
//! monomials in `x = 2 s - 1`, for `p` and for `p'`. On a machine with AVX2 the full window
//! (six ends, every interval but the first few of a solve) is formed in explicit 4-lane
//! vectors with every index a constant ([`FullBuild`]): the table and the monomials stay in
//! registers, where the loops ([`BuildKernel`], the same operations in the same order, so the
//! same bits) were bound by their index arithmetic and by the table in memory (the 532
//! interpolants and 540 samples of `birkhoff_time`: 149 us, 270 us with the loops). The
//! samples of the interval are
//! evaluated in one block: per sample `x` once, then per component one multiply-add per
//! coefficient (17 for `q`, 16 for `v`), eight samples and three components side by side in
//! vector registers (six independent chains), into the solution's storage. (The Newton form
//! evaluated directly costs two multiply-adds per coefficient for `p` and `p'` together, plus
//! the factors `s - z_i`, and did not vectorise: 60-70 ns per 3-mode sample. Sixteen samples
//! of one component at a time left one chain of dependent steps per register.)
//!
//! An end closer than a quarter of the interval's length to one already taken is left out
//! (a spare end is kept for it): near-coincident nodes, e.g. a short last step, would cost
//! digits. Because the interval `[t_j, t_j+1]` needs the end `t_j+3`, its samples are recorded
//! when the step ending at `t_j+3` is accepted (or when the solve ends).

use super::sampling::{OutputSampler, RecordError};
use crate::simd::{dispatch, Kernel, MulAdd, Unfused, MIN_DISPATCH_LEN};
use crate::solution::Solution;

/// Step ends per interpolant: `NODES / 2` on each side of the output interval.
const NODES: usize = 6;
/// The ends on each side of an interval.
const HALF: usize = NODES / 2;
/// Ends kept: one more than an interpolant takes, a spare for an end left out as too close.
const RING: usize = NODES + 1;
/// Coefficients per component: degree `3 NODES - 1`.
const DEG: usize = 3 * NODES;
/// The end of each Newton node: node `i` is end `i / 3` (each end three times).
const END: [usize; DEG] = {
    let mut end = [0; DEG];
    let mut i = 0;
    while i < DEG {
        end[i] = i / 3;
        i += 1;
    }
    end
};
/// An end closer than this fraction of the interval's length to an end already taken is left
/// out (near-coincident triple nodes make the divided differences lose digits: a last step of
/// 2 % of the one before cost six digits on the intervals before it).
const MIN_SEPARATION: f64 = 0.25;

/// The last [`RING`] step ends of a solve and the output intervals not yet recorded.
pub(crate) struct Birkhoff {
    n: usize,
    /// `t` of the ends, ring-indexed by `end % RING`.
    t: [f64; RING],
    /// `[q, v]` of the ends, `RING x 2n`.
    y: Vec<f64>,
    /// `q`, `v` and `a(q)` of the ends in rows of `padded(n)` (the padding stays zero), `RING
    /// x 3 x padded(n)`: what [`BuildKernel`] loads, whole blocks of components at a time.
    rows: Vec<f64>,
    /// Ends pushed so far.
    ends: usize,
    /// Intervals recorded so far (interval `j` lies between ends `j` and `j + 1`).
    done: usize,
    /// The current interval's interpolant in the variable `x = 2 (t - t_j) / h_j - 1` (which
    /// runs over `[-1, 1]`): the monomial coefficients of `p` (`cq`) and of `p'` in `t`
    /// (`cv`), coefficient by coefficient, `DEG x padded(n)` each (the components of one
    /// coefficient side by side, as [`Dense::eval`] takes them; the padding stays zero), and
    /// the degree `deg` (`3 x ends - 1`: 17, lower only while a solve has fewer than six ends).
    cq: Vec<f64>,
    cv: Vec<f64>,
    deg: usize,
}

impl Birkhoff {
    pub fn new(n: usize) -> Self {
        Birkhoff {
            n,
            t: [0.0; RING],
            y: vec![0.0; RING * 2 * n],
            rows: vec![0.0; RING * 3 * padded(n)],
            ends: 0,
            done: 0,
            cq: vec![0.0; padded(n) * DEG],
            cv: vec![0.0; padded(n) * DEG],
            deg: 0,
        }
    }

    /// Adds the step end `(t, y = [q, v], a(q))`.
    pub fn push(&mut self, t: f64, y: &[f64], a: &[f64]) {
        let (n, slot) = (self.n, self.ends % RING);
        self.t[slot] = t;
        self.y[slot * 2 * n..(slot + 1) * 2 * n].copy_from_slice(y);
        let stride = padded(n);
        let rows = &mut self.rows[slot * 3 * stride..(slot + 1) * 3 * stride];
        for (row, values) in rows.chunks_exact_mut(stride).zip([&y[..n], &y[n..], a]) {
            row[..n].copy_from_slice(values);
        }
        self.ends += 1;
    }

    /// Marks the first `count` intervals as recorded: ends pushed before the start of the
    /// solve (only for the interpolants of the intervals after them).
    pub fn skip(&mut self, count: usize) {
        self.done += count;
    }

    /// Records the intervals whose interpolant is complete: `HALF` ends known on its right
    /// and `NODES` in all (every remaining interval when `last`: the solve has ended and no
    /// more ends will come).
    pub fn emit(&mut self, sampler: &mut OutputSampler, sol: &mut Solution, last: bool) -> Result<(), RecordError> {
        if self.ends == 0 {
            return Ok(());
        }
        let newest = self.ends - 1;
        while self.done < newest {
            let j = self.done;
            if !last && (newest < j + HALF || self.ends < NODES) {
                break;
            }
            let (slot0, slot1) = (j % RING, (j + 1) % RING);
            let (t0, t1) = (self.t[slot0], self.t[slot1]);
            if sampler.needs_interpolant(t1) {
                self.build(j, newest);
            }
            let y1 = &self.y[slot1 * 2 * self.n..(slot1 + 1) * 2 * self.n];
            let dense = Dense { cq: &self.cq, cv: &self.cv, deg: self.deg, n: self.n, t0, h: t1 - t0 };
            sampler.record_block(sol, t1, y1, |times, out| dense.eval(times, out))?;
            self.done += 1;
        }
        Ok(())
    }

    /// The ends of the interpolant of interval `j` among those kept (up to `newest`): `j` and
    /// `j + 1`, then by rings of index distance, `j - k` and `j + 1 + k` for `k = 1, 2, ..`
    /// (the nearer in time first), so that the window is balanced in steps, not in time,
    /// leaving out an end within [`MIN_SEPARATION`] interval lengths of one already taken; at
    /// most [`NODES`]. (Balanced in time, a window on a ramp of growing steps takes the short
    /// steps on one side and none on the other, and the gap amplifies the ends' errors.)
    fn window(&self, j: usize, newest: usize) -> ([usize; NODES], usize) {
        let oldest = (newest + 1).saturating_sub(RING);
        let (t_j, t_j1) = (self.t[j % RING], self.t[(j + 1) % RING]);
        let gap = MIN_SEPARATION * (t_j1 - t_j);
        let mut chosen = [j, j + 1, 0, 0, 0, 0];
        // The times of the chosen ends beside them (no ring index per comparison).
        let mut times = [t_j, t_j1, 0.0, 0.0, 0.0, 0.0];
        let mut count = 2;
        for k in 1..RING {
            if count == NODES {
                break;
            }
            let left = j.checked_sub(k).filter(|&e| e >= oldest);
            let right = Some(j + 1 + k).filter(|&e| e <= newest);
            let pair = match (left, right) {
                (Some(l), Some(r)) if self.t[r % RING] - t_j1 > t_j - self.t[l % RING] => [Some(l), Some(r)],
                (l, r) => [r, l],
            };
            for e in pair.into_iter().flatten() {
                let te = self.t[e % RING];
                if count < NODES && times[..count].iter().all(|&tc| (tc - te).abs() >= gap) {
                    chosen[count] = e;
                    times[count] = te;
                    count += 1;
                }
            }
        }
        (chosen, count)
    }

    /// The interpolant of interval `j` ([`Birkhoff::window`]) as monomials in `x = 2 s - 1`
    /// (`s = (t - t_j) / h`), into `cq` and `cv`.
    ///
    /// First its Newton form in `s`: the nodes (each end three times, the ends nearest the
    /// interval first) and the confluent divided differences `d_k`. Then, with
    /// `s - z_i = (x - w_i) / 2`, `w_i = 2 z_i - 1`, the nested form
    /// `p = e_0 + (x - w_0) (e_1 + (x - w_1) (...))`, `e_k = d_k / 2^k`, is multiplied out
    /// innermost first (one multiply-add per coefficient and node). The monomials of a smooth
    /// solution about the middle of the interval fall off like `(h |omega| / 2)^k / k!`, so
    /// the nested evaluation on `[-1, 1]` is well conditioned. (The highest ones carry the
    /// solver's error in the ends, about the tolerance, so none can be left out without
    /// moving the samples by more than rounding.) `cv` holds the derivative in `t`:
    /// `(2 / h) (k + 1) c_k+1`.
    fn build(&mut self, j: usize, newest: usize) {
        let (nodes, n) = (self.nodes(j, newest), self.n);
        let (rows, cq, cv) = (&self.rows[..], &mut self.cq[..], &mut self.cv[..]);
        self.deg = nodes.m - 1;
        #[cfg(target_arch = "x86_64")]
        if nodes.m == DEG {
            if let Some(simd) = crate::simd::avx2() {
                return simd.vectorize(FullBuild { simd, nodes: &nodes, n, rows, cq, cv });
            }
        }
        dispatch(BuildKernel { nodes: &nodes, n, rows, cq, cv });
    }

    /// The nodes of interval `j`'s interpolant ([`Birkhoff::window`]) in the variable `s`.
    fn nodes(&self, j: usize, newest: usize) -> Nodes {
        let (order, ends) = self.window(j, newest);
        let m = 3 * ends;
        let (t_j, h) = (self.t[j % RING], self.t[(j + 1) % RING] - self.t[j % RING]);
        let mut z = [0.0; DEG];
        for (e, &end) in order[..ends].iter().enumerate() {
            z[3 * e..3 * e + 3].fill((self.t[end % RING] - t_j) / h);
        }
        // 1 / (z_i - z_i-l) depends only on the two ends: one division per pair of ends.
        let mut recip = [[0.0; NODES]; NODES];
        for a in 0..ends {
            for b in 0..a {
                recip[a][b] = 1.0 / (z[3 * a] - z[3 * b]);
            }
        }
        let w: [f64; DEG] = std::array::from_fn(|i| 2.0 * z[i] - 1.0);
        let slots: [usize; NODES] = std::array::from_fn(|e| order[e.min(ends - 1)] % RING);
        Nodes { m, h, recip, w, slots }
    }
}

/// What [`Birkhoff::build`] found of an interval's nodes: `m` nodes, `1 / (z_a - z_b)` per
/// pair of ends, `w = 2 z - 1`, and the ring slots of the ends.
struct Nodes {
    m: usize,
    h: f64,
    recip: [[f64; NODES]; NODES],
    w: [f64; DEG],
    slots: [usize; NODES],
}

/// Components whose interpolants are formed side by side (the operations depend only on the
/// nodes, so one pass serves [`BLOCK`] components).
const BLOCK: usize = 4;

/// Components `first .. first + BLOCK` of a padded row (whole blocks: no partial loads).
#[inline(always)]
fn lanes(row: &[f64], first: usize) -> [f64; BLOCK] {
    row[first..first + BLOCK].try_into().expect("a block of a padded row")
}

/// The divided differences and monomials of [`Birkhoff::build`] for every component, in
/// blocks of [`BLOCK`] (a last short block has zeros in the lanes after its components),
/// under [`dispatch`]: the operations are the same on every path. Levels 0-2 end by end,
/// each entry from the inputs as the in-place levels would form it. Every window of a
/// machine without AVX2, and the short windows at the start of a solve; the full window of
/// a machine with AVX2 takes [`FullBuild`].
struct BuildKernel<'a> {
    nodes: &'a Nodes,
    n: usize,
    rows: &'a [f64],
    cq: &'a mut [f64],
    cv: &'a mut [f64],
}

impl Kernel for BuildKernel<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: MulAdd>(self) {
        let BuildKernel { nodes, n, rows, cq, cv } = self;
        let Nodes { m, h, ref recip, ref w, ref slots } = *nodes;
        let stride = padded(n);
        // Row `kind` (0: q, 1: v, 2: a) of the end in ring slot `slot`.
        let row = |slot: usize, kind: usize| &rows[(3 * slot + kind) * stride..(3 * slot + kind + 1) * stride];
        let half_h2 = 0.5 * h * h;
        let dt = 2.0 / h;
        let ends = m / 3;
        for first in (0..n).step_by(BLOCK) {
            // Levels 0, 1 and 2, end by end (each entry from the inputs, as the in-place
            // levels would form it): end `e` is nodes `3e, 3e + 1, 3e + 2`, its value `q`,
            // `h q'` at level 1 inside the triple and `h^2 q'' / 2` at level 2.
            let mut d = [[0.0; BLOCK]; DEG];
            for e in 0..ends {
                let q = lanes(row(slots[e], 0), first);
                let hv = lanes(row(slots[e], 1), first).map(|v| h * v);
                d[3 * e + 2] = lanes(row(slots[e], 2), first).map(|a| half_h2 * a);
                if e == 0 {
                    d[0] = q;
                    d[1] = hv;
                } else {
                    let (r, before) = (recip[e][e - 1], slots[e - 1]);
                    let q_before = lanes(row(before, 0), first);
                    let hv_before = lanes(row(before, 1), first).map(|v| h * v);
                    let across: [f64; BLOCK] = std::array::from_fn(|lane| (q[lane] - q_before[lane]) * r);
                    d[3 * e + 1] = std::array::from_fn(|lane| (hv[lane] - across[lane]) * r);
                    d[3 * e] = std::array::from_fn(|lane| (across[lane] - hv_before[lane]) * r);
                }
            }
            // Levels 3 and up: every pair of nodes is distinct.
            for l in 3..m {
                for i in (l..m).rev() {
                    let r = recip[END[i]][END[i - l]];
                    d[i] = std::array::from_fn(|lane| (d[i][lane] - d[i - 1][lane]) * r);
                }
            }
            // Monomials in x, innermost factor first.
            let mut scale = 1.0;
            for dk in d.iter_mut().take(m) {
                *dk = dk.map(|v| v * scale);
                scale *= 0.5;
            }
            let mut c = [[0.0; BLOCK]; DEG];
            c[0] = d[m - 1];
            for k in (0..m - 1).rev() {
                let (top, wk) = (m - 2 - k, w[k]);
                c[top + 1] = c[top];
                for i in (1..top + 1).rev() {
                    c[i] = std::array::from_fn(|lane| c[i - 1][lane] - wk * c[i][lane]);
                }
                c[0] = std::array::from_fn(|lane| d[k][lane] - wk * c[0][lane]);
            }
            // Whole blocks: the lanes after the last component hold zeros (from zero inputs).
            for k in 0..DEG {
                let at = k * stride + first;
                let factor = dt * (k + 1) as f64;
                let v = if k + 1 < DEG { c[k + 1].map(|c| factor * c) } else { [0.0; BLOCK] };
                cq[at..at + BLOCK].copy_from_slice(&c[k]);
                cv[at..at + BLOCK].copy_from_slice(&v);
            }
        }
    }
}

/// [`BuildKernel`] for a full window (`DEG` nodes) in AVX2's 4-lane vectors, written out:
/// the same operations in the same order, so the same bits (`full_window_matches_the_loops`),
/// with every index a constant so that the table stays in registers (the levels and the
/// factors one macro arm each: a loop whose bound depends on the outer loop's index stayed a
/// loop over the table in memory). The same code on AVX-512 machines: written with the
/// compiler's own vectorisation, the AVX-512 build paired the 4-lane operations into 8-lane
/// ones with shuffles (`birkhoff_time`'s 540 samples: 357 us against the loops' 261 us).
#[cfg(target_arch = "x86_64")]
struct FullBuild<'a> {
    simd: pulp::x86::V3,
    nodes: &'a Nodes,
    n: usize,
    rows: &'a [f64],
    cq: &'a mut [f64],
    cv: &'a mut [f64],
}

#[cfg(target_arch = "x86_64")]
impl pulp::NullaryFnOnce for FullBuild<'_> {
    type Output = ();

    #[inline(always)]
    fn call(self) {
        use pulp::f64x4;
        let FullBuild { simd, nodes, n, rows, cq, cv } = self;
        let Nodes { h, ref recip, ref w, ref slots, .. } = *nodes;
        let stride = padded(n);
        let half_h2 = 0.5 * h * h;
        let dt = 2.0 / h;
        let (sub, mul, splat) = (|a, b| simd.sub_f64x4(a, b), |a, b| simd.mul_f64x4(a, b), |v| simd.splat_f64x4(v));
        let (hh, half) = (splat(h), splat(half_h2));
        for first in (0..n).step_by(BLOCK) {
            let load = |slot: usize, kind: usize| {
                let at = (3 * slot + kind) * stride + first;
                let v = &rows[at..at + BLOCK];
                f64x4(v[0], v[1], v[2], v[3])
            };
            let mut d = [splat(0.0); DEG];
            for e in 0..NODES {
                let q = load(slots[e], 0);
                let hv = mul(hh, load(slots[e], 1));
                d[3 * e + 2] = mul(half, load(slots[e], 2));
                if e == 0 {
                    d[0] = q;
                    d[1] = hv;
                } else {
                    let r = splat(recip[e][e - 1]);
                    let q_before = load(slots[e - 1], 0);
                    let hv_before = mul(hh, load(slots[e - 1], 1));
                    let across = mul(sub(q, q_before), r);
                    d[3 * e + 1] = mul(sub(hv, across), r);
                    d[3 * e] = mul(sub(across, hv_before), r);
                }
            }
            macro_rules! levels {
                ($($l:literal)*) => {$(
                    for i in ($l..DEG).rev() {
                        d[i] = mul(sub(d[i], d[i - 1]), splat(recip[END[i]][END[i - $l]]));
                    }
                )*};
            }
            levels!(3 4 5 6 7 8 9 10 11 12 13 14 15 16 17);
            let mut scale = 1.0;
            for dk in d.iter_mut() {
                *dk = mul(*dk, splat(scale));
                scale *= 0.5;
            }
            let mut c = [splat(0.0); DEG];
            c[0] = d[DEG - 1];
            macro_rules! factors {
                ($($top:literal)*) => {$(
                    let (k, wk) = (DEG - 2 - $top, splat(w[DEG - 2 - $top]));
                    c[$top + 1] = c[$top];
                    for i in (1..$top + 1).rev() {
                        c[i] = sub(c[i - 1], mul(wk, c[i]));
                    }
                    c[0] = sub(d[k], mul(wk, c[0]));
                )*};
            }
            factors!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16);
            for k in 0..DEG {
                let at = k * stride + first;
                let v = if k + 1 < DEG { mul(splat(dt * (k + 1) as f64), c[k + 1]) } else { splat(0.0) };
                let (ck, v): ([f64; BLOCK], [f64; BLOCK]) = ([c[k].0, c[k].1, c[k].2, c[k].3], [v.0, v.1, v.2, v.3]);
                cq[at..at + BLOCK].copy_from_slice(&ck);
                cv[at..at + BLOCK].copy_from_slice(&v);
            }
        }
    }
}

/// Samples evaluated side by side by [`Dense::eval`]: one vector register of AVX-512 (two of
/// AVX2) per polynomial; a short last group repeats its last time and writes only its own
/// samples.
const LANES: usize = 8;

/// Components evaluated side by side by [`Dense::eval`]: their `2 CHUNK` polynomials are
/// independent chains of multiply-adds, enough to keep both arithmetic pipes busy through the
/// latency of each step (one chain of 17 dependent steps per register left the pipes idle
/// most of the time). The 3-mode reference case is one chunk.
const CHUNK: usize = 3;

/// `n` rounded up to whole chunks and whole blocks (`CHUNK x BLOCK` = 12): the row length of
/// the coefficients and of the ends' rows.
fn padded(n: usize) -> usize {
    n.div_ceil(CHUNK * BLOCK) * CHUNK * BLOCK
}

/// One interval's interpolant, ready to evaluate: the monomials of [`Birkhoff::build`].
struct Dense<'a> {
    cq: &'a [f64],
    cv: &'a [f64],
    deg: usize,
    n: usize,
    t0: f64,
    h: f64,
}

impl Dense<'_> {
    /// The states `[q, v]` at `times` (inside the interval) into `out`, `times.len() x 2n`:
    /// per sample `x` once, then per component the nested `p = c_k + x p` for `q` and one
    /// degree less for `v` (one multiply-add per coefficient and sample), [`LANES`] samples
    /// and [`CHUNK`] components side by side in vector registers ([`dispatch`]). The
    /// multiply-adds are fused on the vector paths only for systems of [`MIN_DISPATCH_LEN`] or
    /// more unknowns, the rule of every other kernel, so that small systems stay bit-identical
    /// on every machine.
    fn eval(&self, times: &[f64], out: &mut [f64]) {
        let fused = 2 * self.n >= MIN_DISPATCH_LEN;
        dispatch(DenseKernel { dense: self, times, out, fused });
    }
}

struct DenseKernel<'a, 'b> {
    dense: &'b Dense<'a>,
    times: &'b [f64],
    out: &'b mut [f64],
    fused: bool,
}

impl Kernel for DenseKernel<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn run<M: MulAdd>(self) {
        if self.fused {
            self.evaluate::<M>()
        } else {
            self.evaluate::<Unfused>()
        }
    }
}

/// `p = p x + c` for the polynomials of one chunk, lane by lane, each with its own
/// coefficient.
#[inline(always)]
fn horner<F: MulAdd>(p: &mut [[f64; LANES]; CHUNK], x: &[f64; LANES], c: &[f64; CHUNK]) {
    for (p, &c) in p.iter_mut().zip(c) {
        for (p, &x) in p.iter_mut().zip(x) {
            *p = F::mul_add(*p, x, c);
        }
    }
}

/// The coefficient `k` of the chunk starting at component `first` (`stride`: the padded row).
#[inline(always)]
fn chunk_row(c: &[f64], k: usize, stride: usize, first: usize) -> &[f64; CHUNK] {
    c[k * stride + first..k * stride + first + CHUNK].try_into().expect("a chunk of a padded row")
}

impl DenseKernel<'_, '_> {
    #[inline(always)]
    fn evaluate<F: MulAdd>(self) {
        let DenseKernel { dense, times, out, .. } = self;
        let Dense { cq, cv, deg, n, t0, h } = *dense;
        let inv_h = 1.0 / h;
        let (width, stride) = (2 * n, padded(n));
        for (ts, rows) in times.chunks(LANES).zip(out.chunks_mut(LANES * width)) {
            let mut x = [0.0; LANES];
            for (lane, x) in x.iter_mut().enumerate() {
                *x = 2.0 * ((ts[lane.min(ts.len() - 1)] - t0) * inv_h) - 1.0;
            }
            for first in (0..n).step_by(CHUNK) {
                let mut p = chunk_row(cq, deg, stride, first).map(|c| [c; LANES]);
                let mut dp = chunk_row(cv, deg - 1, stride, first).map(|c| [c; LANES]);
                for k in (1..deg).rev() {
                    horner::<F>(&mut p, &x, chunk_row(cq, k, stride, first));
                    horner::<F>(&mut dp, &x, chunk_row(cv, k - 1, stride, first));
                }
                horner::<F>(&mut p, &x, chunk_row(cq, 0, stride, first));
                // Through memory, behind a barrier: with the lanes taken out of the registers
                // one by one into the rows, the compiler vectorises the loop above across
                // the components instead of the samples (a third of the speed).
                let mut tile = [[0.0; LANES]; 2 * CHUNK];
                tile[..CHUNK].copy_from_slice(&p);
                tile[CHUNK..].copy_from_slice(&dp);
                let tile = std::hint::black_box(&mut tile);
                let own = CHUNK.min(n - first);
                for (lane, row) in rows.chunks_exact_mut(width).enumerate() {
                    if own == CHUNK {
                        let (q, v) = row.split_at_mut(n);
                        let (q, v) = (&mut q[first..first + CHUNK], &mut v[first..first + CHUNK]);
                        for c in 0..CHUNK {
                            q[c] = tile[c][lane];
                            v[c] = tile[CHUNK + c][lane];
                        }
                    } else {
                        for c in 0..own {
                            row[first + c] = tile[c][lane];
                            row[n + first + c] = tile[CHUNK + c][lane];
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Output;

    /// `q(t) = sum_k t^k / (k + 1)` (degree 17) is reproduced on uneven ends, in the middle
    /// and at both ends of the span (one-sided windows), to rounding.
    #[test]
    fn reproduces_polynomials_of_degree_17() {
        let q = |t: f64| (0..18).map(|k| t.powi(k) / f64::from(k + 1)).sum::<f64>();
        let dq = |t: f64| (1..18).map(|k| f64::from(k) * t.powi(k - 1) / f64::from(k + 1)).sum::<f64>();
        let ddq = |t: f64| (2..18).map(|k| f64::from(k * (k - 1)) * t.powi(k - 2) / f64::from(k + 1)).sum::<f64>();
        let ends = [0.0, 0.13, 0.31, 0.42, 0.6, 0.85, 0.97, 1.1, 1.25];
        let times: Vec<f64> = (0..=124).map(|k| f64::from(k) * 0.01).collect();
        let output = Output::Times(times.clone());
        let mut sampler = OutputSampler::new(&output);
        let mut sol = sampler.solution(2, 0);
        let mut b = Birkhoff::new(1);
        sampler.start(&mut sol, 0.0, &[q(0.0), dq(0.0)]).unwrap();
        for (e, &t) in ends.iter().enumerate() {
            b.push(t, &[q(t), dq(t)], &[ddq(t)]);
            b.emit(&mut sampler, &mut sol, e + 1 == ends.len()).unwrap();
        }
        assert_eq!(sol.t, times);
        for (k, &t) in times.iter().enumerate() {
            let got = sol.state(k);
            assert!((got[0] - q(t)).abs() < 1e-13 * q(t), "q({t}): {} vs {}", got[0], q(t));
            assert!((got[1] - dq(t)).abs() < 1e-12 * dq(t), "v({t}): {} vs {}", got[1], dq(t));
        }
    }

    /// Many components (in blocks of four, the last one short; `2n >= 32`, so the vector
    /// paths fuse the multiply-adds) give each component what it gets alone, to rounding,
    /// and the exact values to the interpolation error.
    #[test]
    fn many_components_match_one_at_a_time() {
        let n = 18;
        let omega = |i: usize| 1.0 + 0.15 * i as f64;
        let ends = [0.0, 0.21, 0.4, 0.66, 0.8, 1.05, 1.2, 1.43];
        let times: Vec<f64> = (0..=140).map(|k| f64::from(k) * 0.01).collect();
        let output = Output::Times(times.clone());
        let solve = |comps: &[usize]| {
            let m = comps.len();
            let mut sampler = OutputSampler::new(&output);
            let mut sol = sampler.solution(2 * m, 0);
            let mut b = Birkhoff::new(m);
            let state = |t: f64| {
                let q = comps.iter().map(|&i| (omega(i) * t + i as f64).sin());
                let v = comps.iter().map(|&i| omega(i) * (omega(i) * t + i as f64).cos());
                let a: Vec<f64> = comps.iter().map(|&i| -omega(i).powi(2) * (omega(i) * t + i as f64).sin()).collect();
                (q.chain(v).collect::<Vec<f64>>(), a)
            };
            sampler.start(&mut sol, 0.0, &state(0.0).0).unwrap();
            for (e, &t) in ends.iter().enumerate() {
                let (y, a) = state(t);
                b.push(t, &y, &a);
                b.emit(&mut sampler, &mut sol, e + 1 == ends.len()).unwrap();
            }
            sol
        };
        let all: Vec<usize> = (0..n).collect();
        let together = solve(&all);
        assert_eq!(together.t, times);
        for i in 0..n {
            let alone = solve(&[i]);
            for (k, &t) in times.iter().enumerate() {
                let (q, v) = (together.state(k)[i], together.state(k)[n + i]);
                let (qa, va) = (alone.state(k)[0], alone.state(k)[1]);
                assert!((q - qa).abs() < 1e-14 && (v - va).abs() < 1e-13, "component {i} at t = {t}");
                let phase = omega(i) * t + i as f64;
                assert!((q - phase.sin()).abs() < 1e-9, "component {i} at t = {t}: q {q}");
                assert!((v - omega(i) * phase.cos()).abs() < 1e-8, "component {i} at t = {t}: v {v}");
            }
        }
    }

    /// The full window's written-out vectors ([`FullBuild`], the path of every machine with
    /// AVX2) give the interpolant of the loops ([`BuildKernel`], baseline code) bit for bit:
    /// uneven ends, 1 to 9 components (short last blocks, a second block).
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn full_window_matches_the_loops() {
        let Some(simd) = crate::simd::avx2() else { return };
        for n in 1..10 {
            let mut b = Birkhoff::new(n);
            for k in 0..RING {
                let t = 0.1 * k as f64 + 0.013 * ((k * k) as f64).sin();
                let y: Vec<f64> = (0..2 * n).map(|i| (1.7 * t + i as f64).sin() * (1.0 + i as f64)).collect();
                let a: Vec<f64> = (0..n).map(|i| -(2.3 * t + i as f64).cos()).collect();
                b.push(t, &y, &a);
            }
            let nodes = b.nodes(3, RING - 1);
            assert_eq!(nodes.m, DEG);
            let (mut cq, mut cv) = (b.cq.clone(), b.cv.clone());
            crate::simd::baseline(BuildKernel { nodes: &nodes, n, rows: &b.rows, cq: &mut cq, cv: &mut cv });
            simd.vectorize(FullBuild { simd, nodes: &nodes, n, rows: &b.rows, cq: &mut b.cq, cv: &mut b.cv });
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
            assert_eq!(bits(&cq), bits(&b.cq), "cq, {n} components");
            assert_eq!(bits(&cv), bits(&b.cv), "cv, {n} components");
            assert!(cq[..n].iter().chain(&cv[..n]).all(|c| c.is_finite() && *c != 0.0));
        }
    }

    /// The error on `q = sin t` drops like `h^18` (`q`) and `h^17` (`v`) when the ends are
    /// twice as dense.
    #[test]
    fn interpolation_error_orders() {
        let err = |h: f64| {
            let mut b = Birkhoff::new(1);
            for k in -2..4 {
                let t = f64::from(k) * h;
                b.push(t, &[t.sin(), t.cos()], &[-t.sin()]);
            }
            // The interval [0, h] with the window [-2h, 3h] (j = 2 of the ends -2h .. 3h).
            b.build(2, 5);
            let (mut eq, mut ev): (f64, f64) = (0.0, 0.0);
            for i in 1..10 {
                let t = h * f64::from(i) / 10.0;
                let mut out = [0.0; 2];
                Dense { cq: &b.cq, cv: &b.cv, deg: b.deg, n: 1, t0: 0.0, h }.eval(&[t], &mut out);
                eq = eq.max((out[0] - t.sin()).abs());
                ev = ev.max((out[1] - t.cos()).abs());
            }
            (eq, ev)
        };
        let (a, b) = (err(3.0), err(1.5));
        let (oq, ov) = ((a.0 / b.0).log2(), (a.1 / b.1).log2());
        eprintln!("interpolation errors {a:?} {b:?}: orders {oq}, {ov}");
        assert!(oq > 17.5 && oq < 19.5, "q order {oq}");
        assert!(ov > 16.5 && ov < 18.5, "v order {ov}");
    }
}

#[cfg(test)]
mod timing {
    use super::*;
    use crate::options::Output;

    /// The interpolants' cost on the 3-mode reference case's pattern (532 steps over 1 s,
    /// 20,001 uniform samples): building them, and evaluating the samples.
    /// `cargo test --release -p drillstring-core --lib birkhoff_time -- --ignored --nocapture`
    #[test]
    #[ignore = "a timing, not a test"]
    fn birkhoff_time() {
        let n = 3;
        let steps = 532;
        let state = |t: f64| {
            let q: Vec<f64> = (0..n).map(|i| (f64::from(i as u32 + 1) * 40.0 * t).sin()).collect();
            let v: Vec<f64> = (0..n).map(|i| f64::from(i as u32 + 1) * 40.0 * (f64::from(i as u32 + 1) * 40.0 * t).cos()).collect();
            let a: Vec<f64> = (0..n).map(|i| -(f64::from(i as u32 + 1) * 40.0).powi(2) * (f64::from(i as u32 + 1) * 40.0 * t).sin()).collect();
            ([q, v].concat(), a)
        };
        // Uneven steps, in order.
        let ends: Vec<f64> = (0..=steps).map(|k| (f64::from(k as u32) + 0.3 * f64::from(k as u32).sin()) / steps as f64).collect();
        let data: Vec<(Vec<f64>, Vec<f64>)> = ends.iter().map(|&t| state(t)).collect();
        let run = |samples: usize| {
            let times: Vec<f64> = (0..samples).map(|k| k as f64 / (samples - 1) as f64 * ends[steps - 1]).collect();
            let output = Output::Times(times);
            let start = std::time::Instant::now();
            let mut sampler = OutputSampler::new(&output);
            let mut sol = sampler.solution(2 * n, 0);
            let mut b = Birkhoff::new(n);
            sampler.start(&mut sol, 0.0, &data[0].0).unwrap();
            for (e, &t) in ends.iter().enumerate() {
                b.push(t, &data[e].0, &data[e].1);
                b.emit(&mut sampler, &mut sol, e == steps).unwrap();
            }
            std::hint::black_box(&sol);
            start.elapsed().as_secs_f64()
        };
        for samples in [2, 540, 20001] {
            let best = (0..300).map(|_| run(samples)).fold(f64::INFINITY, f64::min);
            eprintln!("{samples} samples: {:.1} us", best * 1e6);
        }
    }
}
