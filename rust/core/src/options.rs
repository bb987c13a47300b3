//! Solver options and the output request, validated before any work is done.

use crate::error::Num;
use crate::error::{Error, Result};

/// Default step limit of the adaptive methods (accepted + rejected steps).
pub const ADAPTIVE_MAX_STEPS: u64 = 10_000_000;

/// Default step limit of the fixed-step methods. Their step count ([`fixed_steps`]) is known up
/// front: a request needing more is refused before any work unless a limit is given.
pub const FIXED_MAX_STEPS: u64 = 100_000_000;

/// The default step of the fixed-step methods on a modal system, s, unless the fastest linear
/// mode asks for a shorter one ([`default_fixed_dt`]).
pub const DEFAULT_FIXED_DT: f64 = 1e-4;

/// Steps per period of the fastest linear mode that the default fixed step gives at least.
pub const STEPS_PER_PERIOD: f64 = 100.0;

/// The largest step count [`fixed_steps`] reports (it saturates there).
pub const MAX_STEP_COUNT: u64 = 1 << 62;

/// The number of steps of a fixed-step method over `span` with the step `dt`:
/// `ceil(span / dt - 1e-9)`, at least 1 (the `1e-9` keeps a span that is a multiple of `dt` up
/// to rounding from getting an extra step), saturating at [`MAX_STEP_COUNT`].
pub fn fixed_steps(span: f64, dt: f64) -> u64 {
    let ratio = span / dt;
    if ratio.is_nan() || ratio >= MAX_STEP_COUNT as f64 {
        return MAX_STEP_COUNT;
    }
    let n = (ratio - 1e-9).ceil();
    if n >= 1.0 {
        n as u64
    } else {
        1
    }
}

/// The fastest linear mode of a system of uncoupled masses `mass` and stiffnesses `stiffness`:
/// its index (the first of equals) and rate `sqrt(|K_i / M_i|)`, rad/s (the growth rate of a
/// mode with `K_i < 0` counts as its rate; NaN ratios are skipped); `None` without modes.
pub fn fastest_mode(mass: &[f64], stiffness: &[f64]) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for (i, (m, k)) in mass.iter().zip(stiffness).enumerate() {
        let w2 = (k / m).abs();
        if !w2.is_nan() && best.is_none_or(|(_, top)| w2 > top) {
            best = Some((i, w2));
        }
    }
    best.map(|(i, w2)| (i, w2.sqrt()))
}

/// The default step of the fixed-step methods on a modal system: [`DEFAULT_FIXED_DT`], or
/// `1 /` [`STEPS_PER_PERIOD`] of the shortest linear period `2 pi / max sqrt(|K_i / M_i|)` if
/// that is shorter.
pub fn default_fixed_dt(mass: &[f64], stiffness: &[f64]) -> f64 {
    match fastest_mode(mass, stiffness) {
        Some((_, omega)) if omega != 0.0 => {
            (2.0 * std::f64::consts::PI / omega / STEPS_PER_PERIOD).min(DEFAULT_FIXED_DT)
        }
        _ => DEFAULT_FIXED_DT,
    }
}

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
        AdaptiveOptions {
            rtol: 1e-9,
            atol: 1e-12,
            max_steps: ADAPTIVE_MAX_STEPS,
            first_step: None,
            max_step: f64::INFINITY,
        }
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
        FixedOptions { dt, max_steps: FIXED_MAX_STEPS }
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn fixed_steps_counts_whole_steps() {
        assert_eq!(fixed_steps(1.0, 0.1), 10); // 1 / 0.1 = 10.000000000000002 in floats
        assert_eq!(fixed_steps(1.0, 0.3), 4);
        assert_eq!(fixed_steps(1.0, 2.0), 1);
        assert_eq!(fixed_steps(1.0, 1e-300), MAX_STEP_COUNT);
        assert_eq!(fixed_steps(1.0, 0.0), MAX_STEP_COUNT);
    }

    #[test]
    fn default_fixed_dt_resolves_the_fastest_mode() {
        // w = 2 pi 1000 rad/s: period 1e-3 s, one hundredth of it is 1e-5 s
        let w = 2.0 * PI * 1000.0;
        assert_eq!(fastest_mode(&[1.0, 2.0, 1.0], &[1.0, -2.0 * w * w, w * w]), Some((1, w)));
        assert!((default_fixed_dt(&[1.0, 2.0], &[1.0, -2.0 * w * w]) - 1e-5).abs() < 1e-18);
        // slow modes keep 1e-4 s; no stiffness at all too
        assert_eq!(default_fixed_dt(&[1.0], &[4.0]), DEFAULT_FIXED_DT);
        assert_eq!(default_fixed_dt(&[1.0], &[0.0]), DEFAULT_FIXED_DT);
        assert_eq!(fastest_mode(&[], &[]), None);
    }
}
