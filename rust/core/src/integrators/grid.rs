//! The uniform time grid of the fixed-step methods.
//!
//! The requested step `dt` is shrunk to the largest value `<= dt` that divides the span:
//! `N = ceil((t_end - t0) / dt - 1e-9)` steps ([`crate::options::fixed_steps`]) of
//! `dt_eff = (t_end - t0) / N`.
//! Grid times are computed as `t_n = t0 + n dt_eff`, never accumulated, and `t_N = t_end`
//! exactly.

use crate::error::Num;
use crate::interrupt::Poller;
use crate::solution::Status;

/// `N` uniform steps from `t0` to `t_end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TimeGrid {
    pub t0: f64,
    pub t_end: f64,
    /// Number of steps `N >= 1`.
    pub steps: u64,
    /// The effective step `dt_eff = (t_end - t0) / N`.
    pub dt: f64,
}

impl TimeGrid {
    /// The grid for a requested step `dt > 0` on `t0 < t_end` (validated by the caller).
    pub fn new(t0: f64, t_end: f64, dt: f64) -> Self {
        let span = t_end - t0;
        // saturating: an absurd step count is caught by `max_steps`
        let steps = crate::options::fixed_steps(span, dt);
        TimeGrid { t0, t_end, steps, dt: span / steps as f64 }
    }

    /// The checks before the step after `done` completed steps: the step limit, then an
    /// interrupt request. `Err` carries the status and message that end the solve.
    pub fn before_step(&self, done: u64, max_steps: u64, poller: &mut Poller) -> Result<(), (Status, String)> {
        let t = self.time(done);
        if done >= max_steps {
            let msg = format!(
                "reached t = {} before t_end = {}: max_steps = {max_steps} steps used of the {} needed with dt = {}",
                Num(t),
                Num(self.t_end),
                self.steps,
                Num(self.dt)
            );
            return Err((Status::MaxStepsReached, msg));
        }
        if poller.poll(t) {
            let msg = format!("interrupted at t = {} before t_end = {} after {done} steps", Num(t), Num(self.t_end));
            return Err((Status::Interrupted, msg));
        }
        Ok(())
    }

    /// The failure of step `step` (1-based) whose new state is not finite.
    pub fn non_finite(&self, step: u64) -> (Status, String) {
        let msg = format!(
            "state became non-finite in the step from t = {} to t = {} (step {step})",
            Num(self.time(step - 1)),
            Num(self.time(step))
        );
        (Status::NonFinite, msg)
    }

    /// The grid time `t_n` (`t_end` exactly for `n >= N`).
    pub fn time(&self, n: u64) -> f64 {
        if n >= self.steps {
            self.t_end
        } else {
            self.t0 + n as f64 * self.dt
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shrinks_dt_to_divide_the_span() {
        let g = TimeGrid::new(0.0, 1.0, 0.3);
        assert_eq!(g.steps, 4);
        assert_eq!(g.dt, 0.25);
        assert_eq!(g.time(4), 1.0);
        // A multiple of dt up to rounding gets no extra step.
        let g = TimeGrid::new(0.0, 0.3, 0.1);
        assert_eq!(g.steps, 3);
        assert_eq!(g.time(3), 0.3);
        // dt larger than the span: one step.
        let g = TimeGrid::new(1.0, 2.0, 1e300);
        assert_eq!(g.steps, 1);
        assert_eq!(g.dt, 1.0);
        // Absurdly small dt saturates instead of panicking.
        let g = TimeGrid::new(0.0, 1e300, 1e-300);
        assert_eq!(g.steps, crate::options::MAX_STEP_COUNT);
    }
}
