//! Explicit central differences for `q'' = a(q)` (the leapfrog / Stormer-Verlet scheme in
//! two-step form, Hairer, Norsett, Wanner, *Solving ODEs I*, sec. III.10):
//!
//! ```text
//! q_1     = q_0 + dt v_0                               (this start, as in the published table)
//! q_{n+1} = 2 q_n - q_{n-1} + dt^2 a(q_n)
//! v_n     = (q_{n+1} - q_{n-1}) / (2 dt)   (v_0 given)
//! ```
//!
//! on the uniform grid of [`Grid`]; second-order accurate. The sampled state is `[q, v]`.
//! Between grid points `q` is interpolated by cubic Hermite with derivative `v`, and `v` by
//! cubic Hermite with derivative `a(q)`. `Stats::nfev` counts evaluations of `a`
//! (one per grid point).

use super::grid::Grid;
use super::hermite::hermite;
use super::sampling::{record_failure, RecordError, Sampler};
use super::tableau::all_finite;
use crate::error::Result;
use crate::interrupt::{Interrupt, Poller};
use crate::options::{validate_span, FixedOptions, Output};
use crate::solution::{Solution, Stats, Status};
use crate::system::SecondOrderSystem;

/// Solves `q'' = a(q)` from `(q0, v0)` by central differences (see the module docs).
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    if sys.velocity_dependent() {
        return Err(super::refuse_velocity_dependent(super::Method::Central));
    }
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    super::check_state("q0", q0, sys.dof())?;
    super::check_state("v0", v0, sys.dof())?;
    let grid = Grid::new(t0, t_end, opts.dt);
    let mut sampler = Sampler::new(output);
    let hint = usize::try_from(grid.steps.min(opts.max_steps)).unwrap_or(usize::MAX).saturating_add(1);
    let mut sol = sampler.solution(2 * q0.len(), hint);
    let mut run = Run::new(sys, q0, v0, grid.dt);
    if let Err((status, message)) =
        run.steps(sys, &grid, opts.max_steps, &mut sampler, &mut sol, &mut Poller::new(interrupt))
    {
        sol.fail(status, message);
    }
    sol.stats = run.stats;
    Ok(sol)
}

/// Buffers of one central-difference solve, allocated once.
struct Run {
    dof: usize,
    dt: f64,
    /// `q_{n-1}`.
    q_prev: Vec<f64>,
    /// `q_n`.
    q: Vec<f64>,
    /// `q_{n+1}`.
    q_next: Vec<f64>,
    /// `[q_{n-1}, v_{n-1}]` and `a(q_{n-1})`.
    state_prev: Vec<f64>,
    acc_prev: Vec<f64>,
    /// `[q_n, v_n]` and `a(q_n)`.
    state: Vec<f64>,
    acc: Vec<f64>,
    buf: Vec<f64>,
    stats: Stats,
}

impl Run {
    /// Sets up `state_prev = [q_0, v_0]`, `a(q_0)` and the start `q_1 = q_0 + dt v_0`.
    fn new<S: SecondOrderSystem + ?Sized>(sys: &S, q0: &[f64], v0: &[f64], dt: f64) -> Self {
        let dof = q0.len();
        let mut run = Run {
            dof,
            dt,
            q_prev: q0.to_vec(),
            q: q0.iter().zip(v0).map(|(&q, &v)| q + dt * v).collect(),
            q_next: vec![0.0; dof],
            state_prev: [q0, v0].concat(),
            acc_prev: vec![0.0; dof],
            state: vec![0.0; 2 * dof],
            acc: vec![0.0; dof],
            buf: vec![0.0; 2 * dof],
            stats: Stats::default(),
        };
        sys.acceleration(q0, &mut run.acc_prev);
        run.stats.nfev += 1;
        run
    }

    /// Steps through the grid, recording output; `Err` carries a failure status.
    fn steps<S: SecondOrderSystem + ?Sized>(
        &mut self,
        sys: &S,
        grid: &Grid,
        max_steps: u64,
        sampler: &mut Sampler,
        sol: &mut Solution,
        poller: &mut Poller,
    ) -> std::result::Result<(), (Status, String)> {
        sampler.start(sol, grid.t0, &self.state_prev).map_err(|err| record_failure(err, grid.t0, grid.t0))?;
        for n in 1..=grid.steps {
            grid.before_step(n - 1, max_steps, poller)?;
            let t = grid.time(n);
            self.complete_state(sys);
            if !all_finite(&self.state) {
                return Err(grid.non_finite(n));
            }
            self.stats.naccept += 1;
            let t_prev = grid.time(n - 1);
            self.record(t_prev, t, sampler, sol).map_err(|err| record_failure(err, t_prev, t))?;
        }
        Ok(())
    }

    /// Evaluates `a(q_n)`, the next position `q_{n+1}` and the state `[q_n, v_n]`.
    fn complete_state<S: SecondOrderSystem + ?Sized>(&mut self, sys: &S) {
        let dt = self.dt;
        sys.acceleration(&self.q, &mut self.acc);
        self.stats.nfev += 1;
        let (pos, vel) = self.state.split_at_mut(self.dof);
        for i in 0..self.dof {
            self.q_next[i] = 2.0 * self.q[i] - self.q_prev[i] + dt * dt * self.acc[i];
            pos[i] = self.q[i];
            vel[i] = (self.q_next[i] - self.q_prev[i]) / (2.0 * dt);
        }
    }

    /// Records output of the interval `t -> t_new` and shifts the two-step history.
    fn record(
        &mut self,
        t: f64,
        t_new: f64,
        sampler: &mut Sampler,
        sol: &mut Solution,
    ) -> std::result::Result<(), RecordError> {
        let (dof, h) = (self.dof, self.dt);
        let (q0, v0) = self.state_prev.split_at(dof);
        let (q1, v1) = self.state.split_at(dof);
        let (a0, a1) = (&self.acc_prev, &self.acc);
        sampler.record(sol, t_new, &self.state, &mut self.buf, |t_out, out| {
            let theta = (t_out - t) / h;
            let (q_out, v_out) = out.split_at_mut(dof);
            hermite(theta, h, q0, v0, q1, v1, q_out);
            hermite(theta, h, v0, a0, v1, a1, v_out);
        })?;
        // (q_{n-1}, q_n, q_{n+1}) <- (q_n, q_{n+1}, unused)
        std::mem::swap(&mut self.q_prev, &mut self.q);
        std::mem::swap(&mut self.q, &mut self.q_next);
        std::mem::swap(&mut self.state_prev, &mut self.state);
        std::mem::swap(&mut self.acc_prev, &mut self.acc);
        Ok(())
    }
}
