//! The classical fourth-order Runge-Kutta method with fixed steps (Hairer, Norsett,
//! Wanner, *Solving ODEs I*, sec. II.1):
//!
//! ```text
//! k1 = f(t, y),  k2 = f(t + h/2, y + h/2 k1),  k3 = f(t + h/2, y + h/2 k2),
//! k4 = f(t + h, y + h k3),  y_new = y + h/6 (k1 + 2 k2 + 2 k3 + k4)
//! ```
//!
//! on the uniform grid of [`Grid`]. Requested output times between grid points are
//! interpolated by cubic Hermite with the derivatives `f` at both ends; `f` at the end
//! of a step is `k1` of the next, so it costs nothing except on the last step.

use super::grid::Grid;
use super::hermite::hermite;
use super::sampling::{record_failure, RecordError, Sampler};
use super::tableau::{all_finite, Stages, RK4};
use crate::error::Result;
use crate::interrupt::{Interrupt, Poller};
use crate::options::{validate_span, FixedOptions, Output};
use crate::solution::{Solution, Stats, Status};
use crate::system::OdeSystem;

/// Solves `y' = f(t, y)` on `[t0, t_end]` with classical RK4 (see the module docs).
pub(crate) fn integrate<S: OdeSystem + ?Sized>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    super::check_state("y0", y0, sys.dim())?;
    let grid = Grid::new(t0, t_end, opts.dt);
    let mut sampler = Sampler::new(output);
    let hint = usize::try_from(grid.steps.min(opts.max_steps)).unwrap_or(usize::MAX).saturating_add(1);
    let mut sol = sampler.solution(y0.len(), hint);
    let mut run = Run::new(y0);
    if let Err((status, message)) =
        run.steps(sys, &grid, opts.max_steps, &mut sampler, &mut sol, &mut Poller::new(interrupt))
    {
        sol.fail(status, message);
    }
    sol.stats = run.stats;
    Ok(sol)
}

/// Buffers of one RK4 solve, allocated once.
struct Run {
    y: Vec<f64>,
    y_new: Vec<f64>,
    /// `f(t_{n+1}, y_{n+1})` when output inside the step needed it.
    f_new: Vec<f64>,
    ytmp: Vec<f64>,
    k: Stages,
    /// Whether `k` row 0 already holds `f(t_n, y_n)`.
    k1_valid: bool,
    stats: Stats,
}

impl Run {
    fn new(y0: &[f64]) -> Self {
        let n = y0.len();
        Run {
            y: y0.to_vec(),
            y_new: vec![0.0; n],
            f_new: vec![0.0; n],
            ytmp: vec![0.0; n],
            k: Stages::new(RK4.stages(), n),
            k1_valid: false,
            stats: Stats::default(),
        }
    }

    /// Steps through the grid, recording output; `Err` carries a failure status.
    fn steps<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        grid: &Grid,
        max_steps: u64,
        sampler: &mut Sampler,
        sol: &mut Solution,
        poller: &mut Poller,
    ) -> std::result::Result<(), (Status, String)> {
        sampler.start(sol, grid.t0, &self.y).map_err(|err| record_failure(err, grid.t0, grid.t0))?;
        for n in 0..grid.steps {
            grid.before_step(n, max_steps, poller)?;
            let (t, t_new) = (grid.time(n), grid.time(n + 1));
            self.step(sys, t, grid.dt);
            if !all_finite(&self.y_new) {
                return Err(grid.non_finite(n + 1));
            }
            self.stats.naccept += 1;
            self.record(sys, t, t_new, grid.dt, sampler, sol).map_err(|err| record_failure(err, t, t_new))?;
        }
        Ok(())
    }

    /// One RK4 step from `(t, y)` into `y_new`.
    fn step<S: OdeSystem + ?Sized>(&mut self, sys: &S, t: f64, h: f64) {
        if !self.k1_valid {
            sys.rhs(t, &self.y, self.k.row_mut(0));
            self.stats.nfev += 1;
        }
        self.stats.nfev += RK4.eval_stages(sys, t, h, &self.y, &mut self.k, &mut self.ytmp);
        RK4.advance(h, &self.y, &self.k, &mut self.y_new);
        self.k1_valid = false;
    }

    /// Records output of the step `t -> t_new` and moves to the new state.
    fn record<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        t_new: f64,
        h: f64,
        sampler: &mut Sampler,
        sol: &mut Solution,
    ) -> std::result::Result<(), RecordError> {
        if sampler.needs_interpolant(t_new) {
            sys.rhs(t_new, &self.y_new, &mut self.f_new);
            self.stats.nfev += 1;
            self.k1_valid = true;
        }
        let (y, f0, y1, f1) = (&self.y, self.k.row(0), &self.y_new, &self.f_new);
        sampler.record(sol, t_new, y1, &mut self.ytmp, |t_out, out| {
            hermite((t_out - t) / h, h, y, f0, y1, f1, out);
        })?;
        std::mem::swap(&mut self.y, &mut self.y_new);
        if self.k1_valid {
            self.k.row_mut(0).copy_from_slice(&self.f_new);
        }
        Ok(())
    }
}
