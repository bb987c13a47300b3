//! Dense output of the Runge-Kutta-Nystrom pairs: Hermite-Birkhoff interpolation of the
//! step ends.
//!
//! At every step end `t_k` the solve knows `q_k`, `v_k` and `a_k = a(q_k)` (the next step's
//! first stage, no extra evaluation). On the output interval `[t_j, t_j+1]` the positions are
//! the polynomial `p` of degree `3m - 1 = 17` matching `q`, `q'` and `q''` at the `m = 6`
//! ends `t_j-2 .. t_j+3` (one-sided at the ends of the span: the six ends nearest; fewer
//! when the solve has fewer), and the velocities are `p'`. For a smooth solution the
//! interpolation error is `O(h^18)` in `q` and `O(h^17)` in `v`, far below the RKN12 pair's
//! own error at the step sizes its control picks, provided consecutive steps do not differ
//! too much (`rkn.rs` lets a step at most double the previous one when output times are
//! requested). Measured against exact solutions (`rkn_tests.rs`, a linear two-mass chain
//! over 40 s): the dense error is within 1.3 times the error at the step ends for
//! `rtol = atol = 1e-8 .. 1e-12`; at `rtol = 1e-13` (`atol = 1e-15`) 1.5e-13 against 2e-14,
//! and near rounding (`rtol = 1e-15`) 5.5e-13: the velocities are the derivative of the
//! position interpolant, which loses about `eps |q| / (h |v|)` on small steps. The first and
//! last two intervals of a solve have one-sided windows and are a few times less accurate.
//! (Four ends, degree 11, `O(h^12)`, were 100 times above the tolerance at `rtol = 1e-8`;
//! capping the steps by an estimate of that error, the last Newton term, kept them within it
//! at 1.7-1.9 times the steps. Near rounding such an estimate is noise that grows as the
//! step shrinks, and it drove the steps to underflow at `rtol = 1e-15`.)
//!
//! `p` is formed once per interval, in the variable `s = (t - t_j) / h_j` (`h_j = t_j+1 -
//! t_j`), as a Newton form: the confluent divided differences of the nodes (each end three
//! times, with `q`, `h q'` and `h^2 q'' / 2` in those units; the ends nearest the interval
//! first). The samples of the interval are then evaluated in one block: per sample the
//! factors `s - z_i` once, then the nested form of `p` and `p'` per component (two
//! multiply-adds per coefficient, four samples side by side), straight into the solution's
//! storage.
//!
//! An end closer than a quarter of the interval's length to one already taken is left out
//! (a spare end is kept for it): near-coincident nodes, e.g. a short last step, would cost
//! digits. Because the interval `[t_j, t_j+1]` needs the end `t_j+3`, its samples are recorded
//! when the step ending at `t_j+3` is accepted (or when the solve ends).

use super::sampling::{RecordError, Sampler};
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
    /// `a(q)` of the ends, `RING x n`.
    a: Vec<f64>,
    /// Ends pushed so far.
    ends: usize,
    /// Intervals recorded so far (interval `j` lies between ends `j` and `j + 1`).
    done: usize,
    /// The Newton form of the current interval: its nodes in `s` and, per component, its
    /// divided differences (`n x DEG`).
    z: [f64; DEG],
    coef: Vec<f64>,
}

impl Birkhoff {
    pub fn new(n: usize) -> Self {
        Birkhoff {
            n,
            t: [0.0; RING],
            y: vec![0.0; RING * 2 * n],
            a: vec![0.0; RING * n],
            ends: 0,
            done: 0,
            z: [0.0; DEG],
            coef: vec![0.0; n * DEG],
        }
    }

    /// Adds the step end `(t, y = [q, v], a(q))`.
    pub fn push(&mut self, t: f64, y: &[f64], a: &[f64]) {
        let (n, slot) = (self.n, self.ends % RING);
        self.t[slot] = t;
        self.y[slot * 2 * n..(slot + 1) * 2 * n].copy_from_slice(y);
        self.a[slot * n..(slot + 1) * n].copy_from_slice(a);
        self.ends += 1;
    }

    /// Records the intervals whose interpolant is complete: `HALF` ends known on its right
    /// and `NODES` in all (every remaining interval when `last`: the solve has ended and no
    /// more ends will come).
    pub fn emit(&mut self, sampler: &mut Sampler, sol: &mut Solution, last: bool) -> Result<(), RecordError> {
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
            let (coef, z, n, h) = (&self.coef, &self.z, self.n, t1 - t0);
            sampler.record_block(sol, t1, y1, |times, out| eval_block(coef, z, n, t0, h, times, out))?;
            self.done += 1;
        }
        Ok(())
    }

    /// The ends of the interpolant of interval `j` among those kept (up to `newest`), nearest
    /// the interval first (`j`, `j + 1`, then by distance in time), leaving out an end within
    /// [`MIN_SEPARATION`] interval lengths of one already taken; at most [`NODES`].
    fn window(&self, j: usize, newest: usize) -> ([usize; NODES], usize) {
        let oldest = (newest + 1).saturating_sub(RING);
        let (t_j, t_j1) = (self.t[j % RING], self.t[(j + 1) % RING]);
        let gap = MIN_SEPARATION * (t_j1 - t_j);
        let mut chosen = [j, j + 1, 0, 0, 0, 0];
        let mut count = 2;
        let (mut left, mut right) = (j.checked_sub(1).filter(|&e| e >= oldest), Some(j + 2).filter(|&e| e <= newest));
        while count < NODES {
            // The nearer of the next end on each side.
            let take_right = match (left, right) {
                (Some(l), Some(r)) => self.t[r % RING] - t_j1 <= t_j - self.t[l % RING],
                (None, Some(_)) => true,
                (Some(_), None) => false,
                (None, None) => break,
            };
            let e = if take_right {
                let r = right.expect("a right end");
                right = Some(r + 1).filter(|&e| e <= newest);
                r
            } else {
                let l = left.expect("a left end");
                left = l.checked_sub(1).filter(|&e| e >= oldest);
                l
            };
            let te = self.t[e % RING];
            if chosen[..count].iter().all(|&c| (self.t[c % RING] - te).abs() >= gap) {
                chosen[count] = e;
                count += 1;
            }
        }
        (chosen, count)
    }

    /// The Newton form (in `s`) of the interpolant of interval `j` ([`Birkhoff::window`]):
    /// the nodes into `z` (each end three times, the ends nearest the interval first, which
    /// keeps the nested evaluation on `[0, 1]` well conditioned), the divided differences
    /// into `coef` (unused ones zero).
    fn build(&mut self, j: usize, newest: usize) {
        let n = self.n;
        let (order, ends) = self.window(j, newest);
        let m = 3 * ends;
        let (t_j, h) = (self.t[j % RING], self.t[(j + 1) % RING] - self.t[j % RING]);
        let z = &mut self.z;
        z.fill(0.0);
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
        let slots: [usize; NODES] = std::array::from_fn(|e| order[e.min(ends - 1)] % RING);
        let half_h2 = 0.5 * h * h;
        for comp in 0..n {
            // Level 0: the values.
            let mut d = [0.0; DEG];
            for (e, &slot) in slots[..ends].iter().enumerate() {
                d[3 * e..3 * e + 3].fill(self.y[slot * 2 * n + comp]);
            }
            // Level 1: h q' inside a triple (i mod 3 = 1, 2), a difference across ends.
            for i in (1..m).rev() {
                d[i] = if i % 3 != 0 {
                    h * self.y[slots[i / 3] * 2 * n + n + comp]
                } else {
                    (d[i] - d[i - 1]) * recip[END[i]][END[i - 1]]
                };
            }
            // Level 2: h^2 q'' / 2 inside a triple (i mod 3 = 2).
            for i in (2..m).rev() {
                d[i] = if i % 3 == 2 {
                    half_h2 * self.a[slots[i / 3] * n + comp]
                } else {
                    (d[i] - d[i - 1]) * recip[END[i]][END[i - 2]]
                };
            }
            // Levels 3 and up: every pair of nodes is distinct.
            for l in 3..m {
                for i in (l..m).rev() {
                    d[i] = (d[i] - d[i - 1]) * recip[END[i]][END[i - l]];
                }
            }
            self.coef[comp * DEG..(comp + 1) * DEG].copy_from_slice(&d);
        }
    }
}

/// Samples evaluated together by [`eval_block`]: groups of [`WIDE`] while that many remain,
/// then groups of [`NARROW`].
const WIDE: usize = 16;
const NARROW: usize = 4;

/// The states `[q, v]` at `times` (inside the interval from `t0` of length `h`) into `out`,
/// `times.len() x 2n`, from the Newton form (`z`, per component the divided differences
/// `coef`, `n x DEG`): per sample the factors `s - z_k` once, then per component the nested
/// `p = d_k + (s - z_k) p`, `p' = p + (s - z_k) p'` (two multiply-adds per coefficient).
/// Several samples go through the nested form together: one chain of 17 dependent
/// multiply-adds per sample would leave the arithmetic units idle (measured 50 ns per 3-mode
/// sample one at a time; groups of 16 instead of 4 took 66-70 instead of 80-84 ns per sample
/// on a loaded machine, 20,001 samples of the 3-mode case); a short last group repeats its
/// last time and writes only its own. Every sample's arithmetic is the same whatever its group.
fn eval_block(coef: &[f64], z: &[f64; DEG], n: usize, t0: f64, h: f64, times: &[f64], out: &mut [f64]) {
    let wide = times.len() / WIDE * WIDE;
    let (t_wide, t_rest) = times.split_at(wide);
    let (o_wide, o_rest) = out.split_at_mut(wide * 2 * n);
    eval_groups::<WIDE>(coef, z, n, t0, h, t_wide, o_wide);
    eval_groups::<NARROW>(coef, z, n, t0, h, t_rest, o_rest);
}

/// [`eval_block`] in groups of `L` samples.
fn eval_groups<const L: usize>(
    coef: &[f64],
    z: &[f64; DEG],
    n: usize,
    t0: f64,
    h: f64,
    times: &[f64],
    out: &mut [f64],
) {
    let inv_h = 1.0 / h;
    let coef = &coef[..n * DEG];
    let width = 2 * n;
    for (ts, rows) in times.chunks(L).zip(out.chunks_mut(L * width)) {
        let mut u = [[0.0; L]; DEG];
        for lane in 0..L {
            let s = (ts[lane.min(ts.len() - 1)] - t0) * inv_h;
            for (uk, &zk) in u.iter_mut().zip(z) {
                uk[lane] = s - zk;
            }
        }
        for (comp, d) in coef.chunks_exact(DEG).enumerate() {
            let d: &[f64; DEG] = d.try_into().expect("DEG coefficients");
            let mut p = [d[DEG - 1]; L];
            let mut dp = [0.0; L];
            for k in (0..DEG - 1).rev() {
                for lane in 0..L {
                    dp[lane] = dp[lane] * u[k][lane] + p[lane];
                    p[lane] = p[lane] * u[k][lane] + d[k];
                }
            }
            for (lane, row) in rows.chunks_exact_mut(width).enumerate() {
                row[comp] = p[lane];
                row[n + comp] = dp[lane] * inv_h;
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
        let mut sampler = Sampler::new(&output);
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
                eval_block(&b.coef, &b.z, 1, 0.0, h, &[t], &mut out);
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
