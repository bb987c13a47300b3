//! The adaptive stepping loop shared by Dormand-Prince 5(4) and DOP853.
//!
//! One loop, the method as data ([`Scheme`]: tableau, error estimate, dense output,
//! step-size constants), following Hairer's `dopri5.f` / `dop853.f` (Hairer, Norsett,
//! Wanner, *Solving ODEs I*, sec. II.4-II.6).
//!
//! A step `(t, y) -> (t + h, y_new)` is accepted when the scaled RMS error
//!
//! ```text
//! err = sqrt(1/n sum_i (e_i / sc_i)^2),   sc_i = atol + rtol max(|y_i|, |y_new,i|)
//! ```
//!
//! is `<= 1` (DOP853 combines two estimates, see `dop853.rs`). The next step is
//! `h_new = h / fac` with (Lund-stabilised, sec. IV.2)
//!
//! ```text
//! fac11 = err^expo1,  fac = fac11 / facold^beta,  fac = clamp(fac / safe, 1/fac2, 1/fac1)
//! ```
//!
//! and `facold = max(err, 1e-4)` of the last accepted step. After a rejection
//! `h_new = h / min(1/fac1, fac11 / safe)` and the step following the next accepted one
//! may not grow beyond it. A non-finite `err` is a rejection with `h_new = 0.2 h`.
//! The stages are evaluated FSAL: `f(t + h, y_new)` of an accepted step is `k_0` of
//! the next one. A step that would end within 1% of `t_end` is stretched to land on it.
//!
//! Checked against Hairer's codes as shipped in scipy (`scipy.integrate.ode`): identical
//! accepted/rejected step and evaluation counts for DOPRI5; for DOP853 too once scipy's
//! C port's rejection typo (`h / min(facc1, facc1 / safe)` instead of
//! `h / min(facc1, fac11 / safe)`) is mimicked. `Stats::nreject` counts every rejection
//! (Hairer's `NREJCT` skips those before the first accepted step).

use std::marker::PhantomData;

use super::form::Form;
use super::sampling::{record_failure, OutputSampler, Recorded};
use super::tableau::{all_finite, Stages, Tableau};
use crate::error::Num;
use crate::error::Result;
use crate::interrupt::{Interrupt, Poller};
use crate::options::{validate_span, AdaptiveOptions, Output};
use crate::simd::{dispatch_len, Kernel, MulAdd};
use crate::solution::{Solution, Stats, Status};

/// Hairer's step-size control constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Control {
    /// Safety factor `safe`.
    pub safe: f64,
    /// Smallest allowed ratio `h_new / h` (`fac1`).
    pub fac1: f64,
    /// Largest allowed ratio `h_new / h` (`fac2`).
    pub fac2: f64,
    /// Lund stabilisation exponent `beta`.
    pub beta: f64,
    /// `expo1`, the exponent of `err` (`1/(q+1) - c beta` for error order `q`).
    pub expo1: f64,
    /// Order used by the initial step guess `hinit`.
    pub hinit_order: i32,
}

impl Control {
    /// The next step after an accepted attempt of size `h` with scaled error `err`, `facold`
    /// the error of the previous accepted step: `h / clamp(err^expo1 / facold^beta / safe,
    /// 1/fac2, 1/fac1)`.
    #[inline]
    pub fn accepted_step(&self, h: f64, err: f64, facold: f64) -> f64 {
        let fac = (err.powf(self.expo1) / facold.powf(self.beta) / self.safe).min(1.0 / self.fac1).max(1.0 / self.fac2);
        h / fac
    }

    /// The step to retry after a rejected attempt of size `h` with scaled error `err`:
    /// `h / min(1/fac1, err^expo1 / safe)`.
    #[inline]
    pub fn rejected_step(&self, h: f64, err: f64) -> f64 {
        h / (1.0 / self.fac1).min(err.powf(self.expo1) / self.safe)
    }
}

/// An embedded Runge-Kutta pair with dense output, run by [`integrate`].
///
/// Row layout of the stage storage: `0 .. TABLEAU.stages()` the step's stages,
/// `FSAL` the derivative `f(t + h, y_new)`, then any extra dense-output stages.
pub(crate) trait Scheme {
    const TABLEAU: Tableau;
    const CONTROL: Control;
    /// Rows of the stage storage.
    const ROWS: usize;
    /// Row of `f(t + h, y_new)`.
    const FSAL: usize;
    /// Whether the error estimate uses `f(t + h, y_new)` (then it is evaluated on every
    /// attempt; otherwise only on accepted steps).
    const FSAL_IN_ERROR: bool;
    /// Rows of the dense-output coefficients.
    const DENSE_ROWS: usize;
    /// The input coefficients of the stored rows after `FSAL` (extra dense-output stages).
    const EXTRA_INPUTS: &'static [&'static [f64]];

    /// The input coefficients of every stored row: the tableau's rows, `b` for `FSAL`,
    /// then [`Scheme::EXTRA_INPUTS`] (see [`super::form::Nystrom::new`]).
    fn row_inputs() -> Vec<&'static [f64]> {
        let mut rows = Self::TABLEAU.a.to_vec();
        debug_assert_eq!(rows.len(), Self::FSAL);
        rows.push(Self::TABLEAU.b);
        rows.extend_from_slice(Self::EXTRA_INPUTS);
        debug_assert_eq!(rows.len(), Self::ROWS);
        rows
    }

    /// The scaled error norm of the attempted step with stages `k`; `work` is scratch of
    /// length `2 n`.
    fn error_norm<F: Form>(form: &F, k: &Stages, step: &Attempt<'_>, work: &mut [f64]) -> f64;

    /// Builds the continuous extension of the accepted step `t -> t + h` into `dense`,
    /// evaluating any extra stages. Returns the number of right-hand-side evaluations.
    #[allow(clippy::too_many_arguments)]
    fn dense_prepare<F: Form>(
        form: &F,
        t: f64,
        h: f64,
        y: &[f64],
        y_new: &[f64],
        k: &mut Stages,
        ytmp: &mut [f64],
        dense: &mut Stages,
    ) -> u64;

    /// Evaluates the continuous extension at `theta = (t_out - t) / h` into `out`.
    fn dense_eval(dense: &Stages, y: &[f64], theta: f64, out: &mut [f64]);

    /// The continuous extension of the step `t -> t + h` at each of `times` into the rows
    /// of `out` (`times.len() x y.len()`): [`Scheme::dense_eval`] sample by sample, unless
    /// a scheme evaluates a block faster (the same values bit for bit).
    fn dense_eval_block(dense: &Stages, y: &[f64], t: f64, h: f64, times: &[f64], out: &mut [f64]) {
        for (&t_out, row) in times.iter().zip(out.chunks_exact_mut(y.len())) {
            Self::dense_eval(dense, y, (t_out - t) / h, row);
        }
    }
}

/// An attempted step `(t, y) -> (t + h, y_new)` and the tolerances its error is measured by.
pub(crate) struct Attempt<'a> {
    pub h: f64,
    pub y: &'a [f64],
    pub y_new: &'a [f64],
    pub rtol: f64,
    pub atol: f64,
}

/// The scaling `sc_i = atol + rtol max(|y_i|, |y_new,i|)` of Hairer's error norm.
#[inline(always)]
pub(crate) fn scale(atol: f64, rtol: f64, y: f64, y_new: f64) -> f64 {
    atol + rtol * y.abs().max(y_new.abs())
}

/// Lanes of the error-norm sums: independent partial sums the compiler can vectorise.
const LANES: usize = 4;

/// `(sum_i (a_i / sc_i)^2, sum_i (b_i / sc_i)^2)` with `sc_i` of [`scale`], summed in
/// [`LANES`] interleaved partial sums.
pub(crate) fn scaled_sums(a: &[f64], b: &[f64], y: &[f64], y_new: &[f64], rtol: f64, atol: f64) -> (f64, f64) {
    dispatch_len(y.len(), ScaledSums { a, b, y, y_new, rtol, atol })
}

/// The kernel of [`scaled_sums`].
struct ScaledSums<'a> {
    a: &'a [f64],
    b: &'a [f64],
    y: &'a [f64],
    y_new: &'a [f64],
    rtol: f64,
    atol: f64,
}

impl Kernel for ScaledSums<'_> {
    type Output = (f64, f64);

    #[inline(always)]
    fn run<M: MulAdd>(self) -> (f64, f64) {
        let ScaledSums { a, b, y, y_new, rtol, atol } = self;
        let n = y.len();
        let (a, b, y_new) = (&a[..n], &b[..n], &y_new[..n]);
        let (mut sa, mut sb) = ([0.0; LANES], [0.0; LANES]);
        let body = n - n % LANES;
        for i0 in (0..body).step_by(LANES) {
            let a: &[f64; LANES] = a[i0..i0 + LANES].try_into().expect("LANES components");
            let b: &[f64; LANES] = b[i0..i0 + LANES].try_into().expect("LANES components");
            let y0: &[f64; LANES] = y[i0..i0 + LANES].try_into().expect("LANES components");
            let y1: &[f64; LANES] = y_new[i0..i0 + LANES].try_into().expect("LANES components");
            for l in 0..LANES {
                let inv = 1.0 / scale(atol, rtol, y0[l], y1[l]);
                let (ea, eb) = (a[l] * inv, b[l] * inv);
                sa[l] = M::mul_add(ea, ea, sa[l]);
                sb[l] = M::mul_add(eb, eb, sb[l]);
            }
        }
        for i in body..n {
            let inv = 1.0 / scale(atol, rtol, y[i], y_new[i]);
            let (ea, eb) = (a[i] * inv, b[i] * inv);
            sa[0] = M::mul_add(ea, ea, sa[0]);
            sb[0] = M::mul_add(eb, eb, sb[0]);
        }
        (sa.iter().sum(), sb.iter().sum())
    }
}

/// Validates the inputs of an adaptive solve.
pub(crate) fn validate<F: Form>(
    form: &F,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
) -> Result<()> {
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    super::check_state("y0", y0, form.dim())
}

/// Solves `y' = f(t, y)` on `[t0, t_end]` with the pair `P`, polling `interrupt` once per
/// step attempt (rate-limited by [`Poller`]).
pub(crate) fn integrate<P: Scheme, F: Form>(
    form: &F,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    validate(form, t0, y0, t_end, output, opts)?;
    Ok(solve(&mut Run::<P, F>::new(form, t0, y0, t_end, opts), output, interrupt))
}

/// What the state of every adaptive solve holds: its options and span, the time and state
/// reached, the state of the last attempt, the statistics.
pub(crate) struct Core {
    pub opts: AdaptiveOptions,
    pub t_end: f64,
    /// Largest step: `min(max_step, t_end - t0)`.
    pub hmax: f64,
    pub t: f64,
    pub y: Vec<f64>,
    pub y_new: Vec<f64>,
    pub stats: Stats,
}

impl Core {
    /// At `(t0, y0)`, nothing evaluated yet.
    pub fn new(opts: &AdaptiveOptions, t0: f64, y0: Vec<f64>, t_end: f64) -> Self {
        let n = y0.len();
        Core {
            opts: *opts,
            t_end,
            hmax: opts.max_step.min(t_end - t0),
            t: t0,
            y: y0,
            y_new: vec![0.0; n],
            stats: Stats::default(),
        }
    }
}

/// What the one adaptive loop ([`solve`]) drives: an embedded pair's state with its step
/// attempt (the new state and its scaled error norm), the move to an accepted step with its
/// output samples, and its step-size control. Implemented by the explicit Runge-Kutta pairs
/// ([`Run`], any [`Scheme`]) and the Runge-Kutta-Nystrom pairs (`rkn.rs`).
pub(crate) trait Stepper {
    /// The step-size control constants.
    fn control(&self) -> Control;
    /// The span, the time, the state and the statistics.
    fn core(&self) -> &Core;
    fn core_mut(&mut self) -> &mut Core;
    /// Attempts the step `t -> t + h`: the new state and the scaled error norm.
    fn attempt(&mut self, h: f64) -> f64;
    /// Accepts the attempted step of size `h` ending at `t_new`: output samples and the move
    /// to the new state. `Err`: a sample could not be recorded (see [`OutputSampler::record`]).
    fn accept(&mut self, h: f64, t_new: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded;
    /// Hairer's initial step guess ([`initial_step`]).
    fn hinit(&mut self) -> f64;
    /// The largest ratio of consecutive steps (`None`: no bound but `hmax`); with a bound a
    /// step that would leave less than half a step to `t_end` is also replaced by two equal
    /// ones (no short last step).
    fn max_growth(&self) -> Option<f64> {
        None
    }
    /// Before the loop, with the first step `h`: the size of the first step to take.
    fn lead_in(&mut self, h: f64) -> f64 {
        h
    }
    /// After the loop (`done`: the size of the last step when `t_end` was reached): samples
    /// still to be recorded.
    fn finish(&mut self, _done: Option<f64>, _sampler: &mut OutputSampler, _sol: &mut Solution) -> Recorded {
        Ok(())
    }
}

/// The one adaptive solve of a validated [`Stepper`] for `output`, polling `interrupt` once
/// per step attempt: the samples, the status and the statistics.
pub(crate) fn solve<R: Stepper>(run: &mut R, output: &Output, interrupt: &dyn Interrupt) -> Solution {
    let mut sampler = OutputSampler::new(output);
    let mut sol = sampler.solution(run.core().y.len(), 1024);
    let sampler = &mut sampler;
    let c = run.core();
    if let Err(err) = sampler.start(&mut sol, c.t, &c.y) {
        let (status, message) = record_failure(err, c.t, c.t);
        sol.fail(status, message);
    } else {
        let mut h = match c.opts.first_step {
            Some(h) => h.min(c.hmax),
            None => run.hinit(),
        };
        h = run.lead_in(h);
        let outcome = step_loop(run, h, sampler, &mut sol, &mut Poller::new(interrupt));
        let done = match outcome {
            Outcome::Done(h_last) => Some(h_last),
            Outcome::Failed(..) => None,
        };
        let flushed = run.finish(done, sampler, &mut sol);
        if let Outcome::Failed(status, message) = outcome {
            sol.fail(status, message);
        } else if let Err(err) = flushed {
            let t = run.core().t;
            let (status, message) = record_failure(err, t, t);
            sol.fail(status, message);
        }
    }
    sol.stats = run.core().stats;
    sol
}

/// How the loop of [`step_loop`] ended.
enum Outcome {
    /// Reached `t_end`; the size of the last step.
    Done(f64),
    Failed(Status, String),
}

/// The accept/reject loop from step size `h` until `t_end`, a failure or an interrupt.
fn step_loop<R: Stepper>(
    run: &mut R,
    mut h: f64,
    sampler: &mut OutputSampler,
    sol: &mut Solution,
    poller: &mut Poller,
) -> Outcome {
    let c = run.control();
    let (t_end, hmax, max_steps) = (run.core().t_end, run.core().hmax, run.core().opts.max_steps);
    let growth = run.max_growth();
    let mut facold: f64 = 1e-4;
    let mut reject = false;
    let mut attempts: u64 = 0;
    loop {
        let t = run.core().t;
        if attempts >= max_steps {
            return Outcome::Failed(Status::MaxStepsReached, max_steps_message(t, t_end, max_steps));
        }
        if poller.poll(t) {
            return Outcome::Failed(Status::Interrupted, interrupted_message(t, t_end, attempts));
        }
        if h.is_nan() || h < min_step(t) {
            return Outcome::Failed(Status::StepSizeUnderflow, underflow_message(h, t));
        }
        let (h_step, last) = clip_to_end(t, t_end, hmax, h);
        h = h_step;
        if growth.is_some() && !last && t + 1.5 * h > t_end {
            // No short last step: it would be a near-coincident node of the interpolant.
            h = 0.5 * (t_end - t);
        }
        attempts += 1;
        let err = run.attempt(h);
        if !err.is_finite() {
            run.core_mut().stats.nreject += 1;
            reject = true;
            h *= 0.2;
            continue;
        }
        let mut h_new = c.accepted_step(h, err, facold);
        if err <= 1.0 {
            facold = err.max(1e-4);
            let t_new = if last { t_end } else { t + h };
            if !all_finite(&run.core().y_new) {
                return Outcome::Failed(Status::NonFinite, non_finite_message(t, t_new));
            }
            if let Err(err) = run.accept(h, t_new, sampler, sol) {
                let (status, message) = record_failure(err, t, t_new);
                return Outcome::Failed(status, message);
            }
            if last {
                return Outcome::Done(h);
            }
            h_new = h_new.min(hmax);
            if let Some(growth) = growth {
                h_new = h_new.min(growth * h);
            }
            if reject {
                h_new = h_new.min(h);
            }
            reject = false;
        } else {
            h_new = c.rejected_step(h, err);
            reject = true;
            run.core_mut().stats.nreject += 1;
        }
        h = h_new;
    }
}

/// The state of one adaptive solve; all buffers are allocated here, once.
pub(crate) struct Run<'a, P, F> {
    form: &'a F,
    core: Core,
    ytmp: Vec<f64>,
    /// Scratch of the error estimate, `2 n`.
    work: Vec<f64>,
    /// Scratch of the initial step guess: two derivatives over the whole state, `2 n`.
    init: Vec<f64>,
    k: Stages,
    dense: Stages,
    scheme: PhantomData<P>,
}

impl<'a, P: Scheme, F: Form> Run<'a, P, F> {
    /// Sets up the buffers and evaluates `k_0 = f(t0, y0)`.
    pub fn new(form: &'a F, t0: f64, y0: &[f64], t_end: f64, opts: &'a AdaptiveOptions) -> Self {
        let n = y0.len();
        let mut run = Run {
            form,
            core: Core::new(opts, t0, y0.to_vec(), t_end),
            ytmp: vec![0.0; n],
            work: vec![0.0; 2 * n],
            init: Vec::new(),
            k: Stages::new(P::ROWS, form.row_len()),
            dense: Stages::new(P::DENSE_ROWS, n),
            scheme: PhantomData,
        };
        form.eval_at(&mut run.k, 0, t0, &run.core.y);
        run.core.stats.nfev += 1;
        run
    }

    /// `k[FSAL] = f(t_new, y_new)`.
    fn eval_fsal(&mut self, t_new: f64) {
        self.form.eval_at(&mut self.k, P::FSAL, t_new, &self.core.y_new);
        self.core.stats.nfev += 1;
    }
}

impl<P: Scheme, F: Form> Stepper for Run<'_, P, F> {
    fn control(&self) -> Control {
        P::CONTROL
    }

    fn core(&self) -> &Core {
        &self.core
    }

    fn core_mut(&mut self) -> &mut Core {
        &mut self.core
    }

    /// The stages, `y_new` and the error norm.
    fn attempt(&mut self, h: f64) -> f64 {
        let tab = P::TABLEAU;
        for s in 1..tab.stages() {
            self.form.eval_stage(&mut self.k, s, self.core.t + tab.c[s] * h, h, &self.core.y, tab.a[s], &mut self.ytmp);
        }
        self.core.stats.nfev += (tab.stages() - 1) as u64;
        self.form.advance(&self.k, tab.b, h, &self.core.y, &mut self.core.y_new, &mut self.ytmp);
        if P::FSAL_IN_ERROR {
            self.eval_fsal(self.core.t + h);
        }
        let step = Attempt {
            h,
            y: &self.core.y,
            y_new: &self.core.y_new,
            rtol: self.core.opts.rtol,
            atol: self.core.opts.atol,
        };
        P::error_norm(self.form, &self.k, &step, &mut self.work)
    }

    /// FSAL derivative, output samples, and the move to the new state.
    fn accept(&mut self, h: f64, t_new: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        self.core.stats.naccept += 1;
        if !P::FSAL_IN_ERROR {
            self.eval_fsal(t_new);
        }
        if sampler.needs_interpolant(t_new) {
            let extra = P::dense_prepare(
                self.form,
                self.core.t,
                h,
                &self.core.y,
                &self.core.y_new,
                &mut self.k,
                &mut self.ytmp,
                &mut self.dense,
            );
            self.core.stats.nfev += extra;
            self.core.stats.ndense += extra;
        }
        // The samples of the step in one block, written in place: the continuous extension's
        // coefficients were formed once above; per sample only the nested evaluation.
        let (t, y, dense) = (self.core.t, &self.core.y, &self.dense);
        sampler.record_block(sol, t_new, &self.core.y_new, |times, out| P::dense_eval_block(dense, y, t, h, times, out))?;
        std::mem::swap(&mut self.core.y, &mut self.core.y_new);
        self.k.copy_row(P::FSAL, 0);
        self.core.t = t_new;
        Ok(())
    }

    /// From `f(t0, y0)` in row 0.
    fn hinit(&mut self) -> f64 {
        let n = self.core.y.len();
        self.init.resize(2 * n, 0.0);
        let (f0, f1) = self.init.split_at_mut(n);
        // f(t0, y0) over the whole state, from row 0 (no new evaluation).
        self.form.combine(&self.k, &[1.0], 0.0, &self.core.y, f0);
        let (form, t) = (self.form, self.core.t);
        let tol = (self.core.opts.rtol, self.core.opts.atol);
        let guess = initial_step(
            &self.core.y,
            f0,
            f1,
            &mut self.ytmp,
            tol,
            P::CONTROL.hinit_order,
            self.core.hmax,
            |h, y, f| form.rhs(t + h, y, f),
        );
        self.core.stats.nfev += 1;
        guess
    }
}

/// The step floor `10 eps max(|t|, tiny)`: a step below it ends the solve with
/// [`Status::StepSizeUnderflow`].
pub(crate) fn min_step(t: f64) -> f64 {
    10.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE)
}

/// Hairer's end-point rule for the step `h` from `t`: a step that would come within `1%` of
/// `t_end` is stretched to end exactly there (the last step); if that would exceed `hmax`, the
/// rest is split into two equal steps instead. The step to take and whether it is the last.
pub(crate) fn clip_to_end(t: f64, t_end: f64, hmax: f64, h: f64) -> (f64, bool) {
    let rest = t_end - t;
    if t + 1.01 * h <= t_end {
        (h, false)
    } else if rest <= hmax {
        (rest, true)
    } else {
        (0.5 * rest, false)
    }
}

/// The message of a solve that used its `max_steps` step attempts.
pub(crate) fn max_steps_message(t: f64, t_end: f64, max_steps: u64) -> String {
    format!(
        "reached t = {} before t_end = {}: max_steps = {max_steps} step attempts (accepted + rejected) used",
        Num(t),
        Num(t_end)
    )
}

/// The message of an interrupted adaptive solve.
pub(crate) fn interrupted_message(t: f64, t_end: f64, attempts: u64) -> String {
    format!("interrupted at t = {} before t_end = {} after {attempts} step attempts", Num(t), Num(t_end))
}

/// The message of a step from `t` to `t_new` whose new state is not finite.
pub(crate) fn non_finite_message(t: f64, t_new: f64) -> String {
    format!("state became non-finite in the step from t = {} to t = {}", Num(t), Num(t_new))
}

/// The message of a step that fell below [`min_step`].
pub(crate) fn underflow_message(h: f64, t: f64) -> String {
    format!("step size h = {} fell below 10*eps*|t| = {} at t = {}", Num(h), Num(min_step(t)), Num(t))
}

/// Hairer's initial step guess `hinit`: with `d0 = ||y0||`, `d1 = ||f0||` (scaled with
/// `sc_i = atol + rtol |y0_i|`), an explicit Euler step of `h0 = 0.01 d0 / d1` and
/// `d2 = ||f(t0 + h0, y0 + h0 f0) - f0|| / h0`, the step
/// `min(100 h0, (0.01 / max(d2, d1))^(1/order), hmax)`. `rhs(h0, y, f)` evaluates
/// `f(t0 + h0, y)` (one evaluation); `f1` and `ytmp` (length of `y`) are scratch.
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step(
    y: &[f64],
    f0: &[f64],
    f1: &mut [f64],
    ytmp: &mut [f64],
    (rtol, atol): (f64, f64),
    order: i32,
    hmax: f64,
    rhs: impl FnOnce(f64, &[f64], &mut [f64]),
) -> f64 {
    let (mut dnf, mut dny) = (0.0, 0.0);
    for (&y, &f) in y.iter().zip(f0.iter()) {
        let sk = atol + rtol * y.abs();
        dnf += (f / sk) * (f / sk);
        dny += (y / sk) * (y / sk);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 { 1e-6 } else { (dny / dnf).sqrt() * 0.01 };
    h = h.min(hmax);
    if h.is_nan() || h <= 0.0 {
        h = 1e-6_f64.min(hmax);
    }
    for ((yt, &y), &f) in ytmp.iter_mut().zip(y).zip(f0.iter()) {
        *yt = y + h * f;
    }
    rhs(h, ytmp, f1);
    let mut der2 = 0.0;
    for ((&y, &f0i), &f1i) in y.iter().zip(f0.iter()).zip(f1.iter()) {
        let sk = atol + rtol * y.abs();
        der2 += ((f1i - f0i) / sk) * ((f1i - f0i) / sk);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 { 1e-6_f64.max(h * 1e-3) } else { (0.01 / der12).powf(1.0 / f64::from(order)) };
    let guess = (100.0 * h).min(h1).min(hmax);
    if guess > 0.0 {
        guess
    } else {
        h
    }
}

#[cfg(test)]
pub(crate) mod testing {
    //! Test hook: the adaptive pairs stepped with `n` uniform steps, every step accepted.

    use super::*;

    /// Takes `n` uniform steps of the pair `P` (its propagated solution) from `(t0, y0)`
    /// to `t_end` and returns the final state.
    pub(crate) fn uniform_steps<P: Scheme, F: Form>(form: &F, t0: f64, y0: &[f64], t_end: f64, n: usize) -> Vec<f64> {
        let opts = AdaptiveOptions::default();
        let output = Output::EveryStep;
        let mut sampler = OutputSampler::new(&output);
        let mut sol = sampler.solution(y0.len(), n + 1);
        let mut run = Run::<P, F>::new(form, t0, y0, t_end, &opts);
        let h = (t_end - t0) / n as f64;
        for i in 1..=n {
            run.attempt(h);
            run.accept(h, t0 + i as f64 * h, &mut sampler, &mut sol).expect("finite every-step output");
        }
        run.core.y
    }
}
