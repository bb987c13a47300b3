//! Solver options and the output request, validated before any work is done.

use crate::error::Num;
use crate::error::{Error, Result};

/// Where the solution is sampled.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// At these times: finite, non-decreasing, inside `[t0, t_end]`. Adaptive methods
    /// interpolate with their dense output, so steps are not tied to this grid.
    Times(Vec<f64>),
    /// At `t0` and after every accepted step.
    EveryStep,
}

/// Options of the adaptive methods (Dormand-Prince 5(4), DOP853).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveOptions {
    /// Relative tolerance, > 0.
    pub rtol: f64,
    /// Absolute tolerance, > 0.
    pub atol: f64,
    /// Largest number of steps (accepted + rejected) before the solve ends with
    /// [`crate::Status::MaxStepsReached`].
    pub max_steps: u64,
    /// Initial step; `None` chooses it with Hairer's `hinit`.
    pub first_step: Option<f64>,
    /// Upper bound on the step size (`f64::INFINITY` for none).
    pub max_step: f64,
}

impl Default for AdaptiveOptions {
    fn default() -> Self {
        AdaptiveOptions { rtol: 1e-9, atol: 1e-12, max_steps: 10_000_000, first_step: None, max_step: f64::INFINITY }
    }
}

impl AdaptiveOptions {
    pub fn validate(&self) -> Result<()> {
        positive("rtol", self.rtol)?;
        positive("atol", self.atol)?;
        if self.max_steps == 0 {
            return Err(Error::invalid("max_steps", "0", "an integer >= 1"));
        }
        if let Some(h) = self.first_step {
            positive("first_step", h)?;
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(Error::invalid("max_step", Num(self.max_step), "> 0 (or infinity)"));
        }
        Ok(())
    }
}

/// Options of the fixed-step methods (classical RK4, central differences).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedOptions {
    /// Step size, finite and > 0.
    pub dt: f64,
    /// Largest number of steps before the solve ends with [`crate::Status::MaxStepsReached`].
    pub max_steps: u64,
}

impl FixedOptions {
    pub fn new(dt: f64) -> Self {
        FixedOptions { dt, max_steps: 100_000_000 }
    }

    pub fn validate(&self) -> Result<()> {
        positive("dt", self.dt)?;
        if self.max_steps == 0 {
            return Err(Error::invalid("max_steps", "0", "an integer >= 1"));
        }
        Ok(())
    }
}

/// Checks the time span and output request shared by every method.
pub fn validate_span(t0: f64, t_end: f64, output: &Output) -> Result<()> {
    if !t0.is_finite() {
        return Err(Error::invalid("t0", Num(t0), "a finite number"));
    }
    if !(t_end.is_finite() && t_end > t0) {
        return Err(Error::invalid("t_end", Num(t_end), format!("a finite number > t0 = {}", Num(t0))));
    }
    if let Output::Times(times) = output {
        // The common case in one branch-free pass: sorted, the first at or after t0, the
        // last at or before t_end (every comparison with a NaN is false). Otherwise the
        // loop below names the first bad value.
        let sorted = times.windows(2).fold(true, |ok, w| ok & (w[0] <= w[1]));
        if sorted && times.first().is_none_or(|&t| t0 <= t) && times.last().is_none_or(|&t| t <= t_end) {
            return Ok(());
        }
        let mut prev = t0;
        for (k, &t) in times.iter().enumerate() {
            if !t.is_finite() || t < t0 || t > t_end {
                return Err(Error::invalid(
                    "t_eval",
                    format!("t_eval[{k}] = {}", Num(t)),
                    format!("finite values in [{}, {}]", Num(t0), Num(t_end)),
                ));
            }
            if t < prev {
                return Err(Error::invalid(
                    "t_eval",
                    format!("t_eval[{k}] = {} < t_eval[{}] = {}", Num(t), k.saturating_sub(1), Num(prev)),
                    "non-decreasing values",
                ));
            }
            prev = t;
        }
    }
    Ok(())
}

fn positive(field: &'static str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(value), "a finite number > 0"))
    }
}
