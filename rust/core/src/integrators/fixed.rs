//! The one fixed-step loop of RK4, central differences and velocity Verlet: the uniform grid
//! ([`TimeGrid`]), the step limit and interrupt polling, the check of every new state, the samples
//! and the statuses. The schemes differ only in their step and its interpolant
//! ([`FixedScheme`]).

use super::grid::TimeGrid;
use super::hermite::hermite;
use super::sampling::{record_failure, OutputSampler, Recorded};
use super::tableau::all_finite;
use crate::error::Result;
use crate::interrupt::{Interrupt, Poller};
use crate::options::{validate_span, FixedOptions, Output};
use crate::solution::{Solution, Stats, Status};
use crate::system::SecondOrderSystem;

use super::Method;

/// A fixed-step scheme as the loop of [`integrate`] drives it.
pub(crate) trait FixedScheme {
    /// The state at `t0`.
    fn start(&self) -> &[f64];
    /// Takes the step `t -> t + h` into the new state (not moved to yet).
    fn step(&mut self, t: f64, h: f64);
    /// The new state of the last step.
    fn new_state(&self) -> &[f64];
    /// Records the samples of the step `t -> t_new` of size `h` (interpolated inside it) and
    /// moves to the new state.
    fn record(&mut self, t: f64, t_new: f64, h: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded;
    fn stats(&mut self) -> &mut Stats;
}

/// Validates the span, the options and (by `check`) the initial state, then steps the scheme
/// made by `new` for the grid's step through the grid, polling `interrupt` before every step.
pub(crate) fn integrate<R: FixedScheme>(
    (t0, t_end): (f64, f64),
    output: &Output,
    opts: &FixedOptions,
    interrupt: &dyn Interrupt,
    check: impl FnOnce() -> Result<()>,
    new: impl FnOnce(f64) -> R,
) -> Result<Solution> {
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    check()?;
    let grid = TimeGrid::new(t0, t_end, opts.dt);
    let mut sampler = OutputSampler::new(output);
    let mut run = new(grid.dt);
    let hint = usize::try_from(grid.steps.min(opts.max_steps)).unwrap_or(usize::MAX).saturating_add(1);
    let mut sol = sampler.solution(run.start().len(), hint);
    if let Err((status, message)) = steps(&mut run, &grid, opts.max_steps, &mut sampler, &mut sol, interrupt) {
        sol.fail(status, message);
    }
    sol.stats = *run.stats();
    Ok(sol)
}

/// Steps through the grid, recording output; `Err` carries a failure status.
fn steps<R: FixedScheme>(
    run: &mut R,
    grid: &TimeGrid,
    max_steps: u64,
    sampler: &mut OutputSampler,
    sol: &mut Solution,
    interrupt: &dyn Interrupt,
) -> std::result::Result<(), (Status, String)> {
    let mut poller = Poller::new(interrupt);
    sampler.start(sol, grid.t0, run.start()).map_err(|err| record_failure(err, grid.t0, grid.t0))?;
    for n in 0..grid.steps {
        grid.before_step(n, max_steps, &mut poller)?;
        let (t, t_new) = (grid.time(n), grid.time(n + 1));
        run.step(t, grid.dt);
        if !all_finite(run.new_state()) {
            return Err(grid.non_finite(n + 1));
        }
        run.stats().naccept += 1;
        run.record(t, t_new, grid.dt, sampler, sol).map_err(|err| record_failure(err, t, t_new))?;
    }
    Ok(())
}

/// A scheme for `q'' = a(q)` on the state `[q, v]`, solved by [`second_order`].
pub(crate) trait SecondOrderScheme<'a, S: ?Sized>: FixedScheme {
    /// The method, named when forces that depend on the velocity are refused.
    const METHOD: Method;
    /// The scheme at `(q0, v0)` with the grid's step `dt` (`a(q0)` evaluated).
    fn new(sys: &'a S, q0: &[f64], v0: &[f64], dt: f64) -> Self;
}

/// Solves `q'' = a(q)` from `(q0, v0)` by the scheme `R`: a system whose forces depend on the
/// velocity is refused (an error naming `method`), then [`integrate`] with `q0`, `v0` checked.
#[allow(clippy::too_many_arguments)]
pub(crate) fn second_order<'a, R: SecondOrderScheme<'a, S>, S: SecondOrderSystem + ?Sized>(
    sys: &'a S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    if sys.velocity_dependent() {
        return Err(super::refuse_velocity_dependent(R::METHOD));
    }
    let check = || super::check_state("q0", q0, sys.dof()).and_then(|()| super::check_state("v0", v0, sys.dof()));
    integrate((t0, t_end), output, opts, interrupt, check, |dt| R::new(sys, q0, v0, dt))
}

/// The ends of a step of a second-order scheme, `[q, v]` and `a(q)` at both, and its samples:
/// `q` by cubic Hermite with derivative `v`, `v` by cubic Hermite with derivative `a(q)`.
pub(crate) struct SecondOrderEnds {
    pub dof: usize,
    /// `[q, v]` and `a(q)` at the start of the step.
    pub state: Vec<f64>,
    pub acc: Vec<f64>,
    /// `[q, v]` and `a(q)` at its end.
    pub state_new: Vec<f64>,
    pub acc_new: Vec<f64>,
    buf: Vec<f64>,
}

impl SecondOrderEnds {
    /// The start `[q0, v0]` (`a(q0)` to be written into `acc`).
    pub fn new(q0: &[f64], v0: &[f64]) -> Self {
        let dof = q0.len();
        SecondOrderEnds {
            dof,
            state: [q0, v0].concat(),
            acc: vec![0.0; dof],
            state_new: vec![0.0; 2 * dof],
            acc_new: vec![0.0; dof],
            buf: vec![0.0; 2 * dof],
        }
    }

    /// Records the samples of the step `t -> t_new` of size `h` and moves to its end.
    pub fn record(&mut self, t: f64, t_new: f64, h: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        let dof = self.dof;
        let (q0, v0) = self.state.split_at(dof);
        let (q1, v1) = self.state_new.split_at(dof);
        let (a0, a1) = (&self.acc, &self.acc_new);
        sampler.record(sol, t_new, &self.state_new, &mut self.buf, |t_out, out| {
            let theta = (t_out - t) / h;
            let (q_out, v_out) = out.split_at_mut(dof);
            hermite(theta, h, q0, v0, q1, v1, q_out);
            hermite(theta, h, v0, a0, v1, a1, v_out);
        })?;
        std::mem::swap(&mut self.state, &mut self.state_new);
        std::mem::swap(&mut self.acc, &mut self.acc_new);
        Ok(())
    }
}
