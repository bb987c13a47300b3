//! The adaptive stepping loop of the embedded Runge-Kutta-Nystrom pairs for `q'' = a(q)`
//! (RKN12(10), `rkn12.rs`).
//!
//! The step control is that of the first-order pairs ([`super::adaptive`]): a step is
//! accepted when the scaled RMS norm over the `2 n` components of `y = [q, v]`,
//!
//! ```text
//! err = sqrt(1/(2n) sum_i (e_i / sc_i)^2),   sc_i = atol + rtol max(|y_i|, |y_new,i|),
//! ```
//!
//! of the embedded difference `e = (h^2 sum (b - b^) K, h sum (b' - b'^) K)` is `<= 1`; the
//! next step is `h / clamp(err^expo1 / safe, 1/fac2, 1/fac1)` (after a rejection as in
//! Hairer's codes), a non-finite `err` is a rejection with `h_new = 0.2 h`, the first step is
//! Hairer's `hinit` ([`super::adaptive::initial_step`]) and the last one is stretched or split
//! to land on `t_end` ([`super::adaptive::clip_to_end`]). The statuses on failure and their
//! messages are those of the first-order pairs.
//!
//! Output times are sampled through the Hermite-Birkhoff interpolant of the step ends
//! ([`super::birkhoff`]), which needs the ends after the output interval: samples are
//! recorded up to three steps late (and the rest at the end of the solve, or when it fails).
//! For the first and last intervals the solve takes two steps backwards from `t0` and two
//! beyond `t_end` ([`Run::lead_in_ends`], [`Run::lead_out`]: 68 evaluations, counted in `nfev`
//! and `ndense`; the steps from `t0` to `t_end` are unchanged).
//! With output times a step may at most double the previous one (the interpolant spans five
//! steps and its error grows with their ratios), and a step that would leave less than half
//! a step to `t_end` is replaced by two equal ones (no short last step: a near-coincident
//! node); otherwise the steps are those of every-step output, and they do not depend on how
//! many output times there are.

use super::adaptive::{initial_step, min_step, solve, Control, Core, Stepper};
use super::birkhoff::Birkhoff;
use super::sampling::{OutputSampler, Recorded};
use super::tableau::{all_finite, Stages};
use crate::error::Result;
use crate::interrupt::Interrupt;
use crate::options::{validate_span, AdaptiveOptions, Output};
use crate::solution::Solution;
use crate::system::SecondOrderSystem;

/// An embedded explicit Runge-Kutta-Nystrom pair for `q'' = a(q)` as data.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RknPair {
    /// Nodes `c_i` (`c_0 = 0`).
    pub c: &'static [f64],
    /// Row `i`: `a_i0 .. a_i,i-1` of the stage positions (possibly shorter: zeros dropped).
    pub a: &'static [&'static [f64]],
    /// Position weights `b_i`.
    pub b: &'static [f64],
    /// Velocity weights `b'_i`.
    pub bp: &'static [f64],
    /// Position error weights `b_i - b^_i`.
    pub eq: &'static [f64],
    /// Velocity error weights `b'_i - b'^_i`.
    pub ev: &'static [f64],
    /// Step-size control (`expo1 = 1/(q+1)` for an estimate of order `q`).
    pub control: Control,
}

impl RknPair {
    /// Number of stages.
    pub fn stages(&self) -> usize {
        self.c.len()
    }
}

/// Most stages of a pair (RKN12's 17).
const MAX_STAGES: usize = 17;

/// Solves `q'' = a(q)` from `(q0, v0)` on `[t0, t_end]` with `pair`; the state in the
/// [`Solution`] is `[q, v]`. The caller has checked `q0`, `v0` and that the system's forces do
/// not depend on the velocity.
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate<S: SecondOrderSystem + ?Sized>(
    pair: &'static RknPair,
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    let dense = matches!(output, Output::Times(_));
    Ok(solve(&mut Run::new(pair, sys, t0, q0, v0, t_end, opts, dense), output, interrupt))
}

/// The state of one solve; all buffers are allocated here, once.
struct Run<'a, S: ?Sized> {
    pair: &'static RknPair,
    sys: &'a S,
    n: usize,
    /// The state `[q, v]`.
    core: Core,
    /// A stage position, `n`.
    qs: Vec<f64>,
    /// The error estimate `[e_q, e_v]`, `2 n`.
    err: Vec<f64>,
    /// `K_0 .. K_16`; row 0 holds `a(q)` at the step's start.
    k: Stages,
    /// The interpolant of the step ends, for output times (`None`: every-step output).
    dense: Option<Birkhoff>,
}

impl<'a, S: SecondOrderSystem + ?Sized> Run<'a, S> {
    #[allow(clippy::too_many_arguments)]
    fn new(
        pair: &'static RknPair,
        sys: &'a S,
        t0: f64,
        q0: &[f64],
        v0: &[f64],
        t_end: f64,
        opts: &AdaptiveOptions,
        dense: bool,
    ) -> Self {
        assert!(pair.stages() <= MAX_STAGES, "{} stages exceed {MAX_STAGES}", pair.stages());
        let n = q0.len();
        let mut run = Run {
            pair,
            sys,
            n,
            core: Core::new(opts, t0, [q0, v0].concat(), t_end),
            qs: vec![0.0; n],
            err: vec![0.0; 2 * n],
            k: Stages::new(pair.stages(), n),
            dense: dense.then(|| Birkhoff::new(n)),
        };
        sys.acceleration(q0, run.k.row_mut(0));
        run.core.stats.nfev += 1;
        run
    }

    /// The ends before `t0` for the interpolants of the first intervals, then `t0` itself.
    ///
    /// The interpolant of an interval takes the three ends on each side of it; the first
    /// intervals of a solve have none before them, and a one-sided window multiplies the
    /// interpolation error by about `(prod |s - z_i|)^3` over its nodes, 75 times for the
    /// first interval of equal steps (measured: 200 times the error of the other intervals in
    /// the velocities of the 3-mode reference case). `q'' = a(q)` is autonomous and solved
    /// as well backwards as forwards, so [`LEAD_IN`] steps of size `-h` (the first step's
    /// size, reduced as the control asks) give the missing ends ([`Run::extra_ends`]); the
    /// forward solve starts from `(q0, v0)` as before. Returns the size of the first forward
    /// step: `h`, or the backward one if the control reduced it.
    fn lead_in_ends(&mut self, h: f64) -> f64 {
        let (ends, hb) = self.extra_ends(-h);
        let d = self.dense.as_mut().expect("the lead-in is for output times");
        for (t, y, a) in ends.iter().rev() {
            d.push(*t, y, a);
        }
        d.skip(ends.len());
        // `extra_ends` left the state at `t0` as it found it.
        d.push(self.core.t, &self.core.y, self.k.row(0));
        if ends.is_empty() {
            h
        } else {
            -hb
        }
    }

    /// The ends after `t_end` for the interpolants of the last intervals (as [`Run::lead_in_ends`]
    /// at the start): [`LEAD_IN`] steps of size `h`, the last step of the solve, beyond
    /// `t_end`. No output time lies there, so only the windows use them. Without them the
    /// last interval was up to 40 times less accurate than the others (`tests/test_rkn12.py`).
    fn lead_out(&mut self, h: f64) {
        let (ends, _) = self.extra_ends(h);
        let d = self.dense.as_mut().expect("the lead-out is for output times");
        for (t, y, a) in &ends {
            d.push(*t, y, a);
        }
    }

    /// Up to [`LEAD_IN`] steps of size `h` (either sign) from the current state, which is
    /// restored afterwards: the ends `(t, [q, v], a(q))` reached, nearest first, and the step
    /// size taken (reduced as the control asks after a rejection). They cost 17 evaluations
    /// each (counted in `nfev` and, as evaluations for the output only, in `ndense`; not in
    /// the steps). If they fail (a non-finite state, or more than [`LEAD_IN_TRIES`]
    /// attempts), the ends reached are returned.
    #[allow(clippy::type_complexity)]
    fn extra_ends(&mut self, h: f64) -> (Vec<(f64, Vec<f64>, Vec<f64>)>, f64) {
        let n = self.n;
        let (t0, y0, a0) = (self.core.t, self.core.y.clone(), self.k.row(0).to_vec());
        let mut ends: Vec<(f64, Vec<f64>, Vec<f64>)> = Vec::with_capacity(LEAD_IN);
        let (sign, mut size) = (h.signum(), h.abs());
        let mut t = t0;
        for _ in 0..LEAD_IN_TRIES {
            if ends.len() == LEAD_IN || size.is_nan() || size < min_step(t) {
                break;
            }
            let err = self.attempt(sign * size);
            self.core.stats.ndense += (self.pair.stages() - 1) as u64;
            if err.is_nan() || err > 1.0 || !all_finite(&self.core.y_new) {
                size = if err.is_finite() { self.pair.control.rejected_step(size, err) } else { 0.2 * size };
                continue;
            }
            std::mem::swap(&mut self.core.y, &mut self.core.y_new);
            t += sign * size;
            self.sys.acceleration(&self.core.y[..n], self.k.row_mut(0));
            self.core.stats.nfev += 1;
            self.core.stats.ndense += 1;
            ends.push((t, self.core.y.clone(), self.k.row(0).to_vec()));
        }
        self.core.y.copy_from_slice(&y0);
        self.k.row_mut(0).copy_from_slice(&a0);
        (ends, sign * size)
    }
}

impl<S: SecondOrderSystem + ?Sized> Stepper for Run<'_, S> {
    fn control(&self) -> Control {
        self.pair.control
    }

    fn core(&self) -> &Core {
        &self.core
    }

    fn core_mut(&mut self) -> &mut Core {
        &mut self.core
    }

    /// The stages, `y_new` and the error norm.
    fn attempt(&mut self, h: f64) -> f64 {
        let (pair, n) = (self.pair, self.n);
        let (q, v) = self.core.y.split_at(n);
        for s in 1..pair.stages() {
            self.k.axpy_combine_plus(q, h * h, pair.a[s], v, h * pair.c[s], &mut self.qs);
            self.sys.acceleration(&self.qs, self.k.row_mut(s));
        }
        self.core.stats.nfev += (pair.stages() - 1) as u64;
        let (q_new, v_new) = self.core.y_new.split_at_mut(n);
        self.k.axpy_combine_plus(q, h * h, pair.b, v, h, q_new);
        self.k.axpy_combine(v, h, pair.bp, v_new);
        let mut weights = [0.0; MAX_STAGES];
        let (e_q, e_v) = self.err.split_at_mut(n);
        for (w, &e) in weights.iter_mut().zip(pair.eq) {
            *w = h * h * e;
        }
        self.k.combine(&weights[..pair.stages()], e_q);
        for (w, &e) in weights.iter_mut().zip(pair.ev) {
            *w = h * e;
        }
        self.k.combine(&weights[..pair.stages()], e_v);
        let (sum, _) = super::adaptive::scaled_sums(
            &self.err,
            &self.err,
            &self.core.y,
            &self.core.y_new,
            self.core.opts.rtol,
            self.core.opts.atol,
        );
        (sum / (2 * n) as f64).sqrt()
    }

    /// The acceleration at `t_new` (`K_0` of the next step), the output samples, and the move
    /// to the new state.
    fn accept(&mut self, _h: f64, t_new: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        self.core.stats.naccept += 1;
        std::mem::swap(&mut self.core.y, &mut self.core.y_new);
        self.core.t = t_new;
        self.sys.acceleration(&self.core.y[..self.n], self.k.row_mut(0));
        self.core.stats.nfev += 1;
        match self.dense.as_mut() {
            Some(d) => {
                d.push(t_new, &self.core.y, self.k.row(0));
                d.emit(sampler, sol, false)
            }
            None => sampler.record(sol, t_new, &self.core.y, &mut [], |_, _| {}),
        }
    }

    /// On `y' = [v, a(q)]` with the pair's order.
    fn hinit(&mut self) -> f64 {
        let n = self.n;
        let mut f0 = vec![0.0; 2 * n];
        let mut f1 = vec![0.0; 2 * n];
        let mut ytmp = vec![0.0; 2 * n];
        f0[..n].copy_from_slice(&self.core.y[n..]);
        f0[n..].copy_from_slice(self.k.row(0));
        let sys = self.sys;
        let tol = (self.core.opts.rtol, self.core.opts.atol);
        let order = self.pair.control.hinit_order;
        let guess = initial_step(&self.core.y, &f0, &mut f1, &mut ytmp, tol, order, self.core.hmax, |_, y, f| {
            let (fq, fv) = f.split_at_mut(n);
            fq.copy_from_slice(&y[n..]);
            sys.acceleration(&y[..n], fv);
        });
        self.core.stats.nfev += 1;
        guess
    }

    /// With output times a step may at most double the previous one.
    fn max_growth(&self) -> Option<f64> {
        self.dense.as_ref().map(|_| DENSE_MAX_GROWTH)
    }

    /// With output times, the ends before `t0` ([`Run::lead_in_ends`]).
    fn lead_in(&mut self, h: f64) -> f64 {
        if self.dense.is_some() {
            self.lead_in_ends(h)
        } else {
            h
        }
    }

    /// With output times, the ends after `t_end` when it was reached ([`Run::lead_out`]), then
    /// the output intervals still waiting for later step ends, from the ends reached.
    fn finish(&mut self, done: Option<f64>, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        if let (Some(h_last), true) = (done, self.dense.is_some()) {
            self.lead_out(h_last);
        }
        match self.dense.as_mut() {
            Some(d) => d.emit(sampler, sol, true),
            None => Ok(()),
        }
    }
}

/// Steps taken backwards from `t0` and forwards from `t_end` for the interpolants of the
/// first and last intervals ([`Run::lead_in_ends`], [`Run::lead_out`]): the interpolant takes three
/// ends on each side of its interval, these are two (with `t0` or `t_end`, three).
const LEAD_IN: usize = 2;
/// Attempts of the backward steps before the interpolants make do with the ends reached.
const LEAD_IN_TRIES: usize = 8;

/// The largest ratio of consecutive steps when output times are interpolated: the
/// interpolant of an interval spans five steps, and its error grows with their ratios.
const DENSE_MAX_GROWTH: f64 = 2.0;

#[cfg(test)]
pub(crate) mod testing {
    //! Test hook: the pair stepped with `n` uniform steps, every step accepted.

    use super::*;

    /// Takes `n` uniform steps of `pair` from `(q0, v0)` over `[t0, t_end]`; returns the final
    /// `[q, v]` and the largest error estimate `[e_q, e_v]` (max norm) of the steps.
    pub(crate) fn uniform_steps<S: SecondOrderSystem + ?Sized>(
        pair: &'static RknPair,
        sys: &S,
        (q0, v0): (&[f64], &[f64]),
        (t0, t_end): (f64, f64),
        n: usize,
    ) -> (Vec<f64>, f64) {
        let opts = AdaptiveOptions::default();
        let output = Output::EveryStep;
        let mut sampler = OutputSampler::new(&output);
        let mut sol = sampler.solution(2 * q0.len(), n + 1);
        let mut run = Run::new(pair, sys, t0, q0, v0, t_end, &opts, false);
        let h = (t_end - t0) / n as f64;
        let mut est: f64 = 0.0;
        for i in 1..=n {
            run.attempt(h);
            est = run.err.iter().fold(est, |m, e| m.max(e.abs()));
            run.accept(h, t0 + i as f64 * h, &mut sampler, &mut sol).expect("finite every-step output");
        }
        (run.core.y, est)
    }
}
