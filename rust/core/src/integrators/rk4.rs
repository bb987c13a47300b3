//! The classical fourth-order Runge-Kutta method with fixed steps (Hairer, Norsett,
//! Wanner, *Solving ODEs I*, sec. II.1):
//!
//! ```text
//! k1 = f(t, y),  k2 = f(t + h/2, y + h/2 k1),  k3 = f(t + h/2, y + h/2 k2),
//! k4 = f(t + h, y + h k3),  y_new = y + h/6 (k1 + 2 k2 + 2 k3 + k4)
//! ```
//!
//! on the uniform grid of [`super::grid::TimeGrid`] ([`super::fixed`]). Requested output times between grid points are
//! interpolated by cubic Hermite with the derivatives `f` at both ends; `f` at the end
//! of a step is `k1` of the next, so it costs nothing except on the last step.

use super::fixed::FixedScheme;
use super::hermite::hermite;
use super::sampling::{OutputSampler, Recorded};
use super::tableau::{Stages, RK4};
use crate::error::Result;
use crate::interrupt::Interrupt;
use crate::options::{FixedOptions, Output};
use crate::solution::{Solution, Stats};
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
    let check = || super::check_state("y0", y0, sys.dim());
    super::fixed::integrate((t0, t_end), output, opts, interrupt, check, |_| Run::new(sys, y0))
}

/// Buffers of one RK4 solve, allocated once.
struct Run<'a, S: ?Sized> {
    sys: &'a S,
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

impl<'a, S: OdeSystem + ?Sized> Run<'a, S> {
    fn new(sys: &'a S, y0: &[f64]) -> Self {
        let n = y0.len();
        Run {
            sys,
            y: y0.to_vec(),
            y_new: vec![0.0; n],
            f_new: vec![0.0; n],
            ytmp: vec![0.0; n],
            k: Stages::new(RK4.stages(), n),
            k1_valid: false,
            stats: Stats::default(),
        }
    }
}

impl<S: OdeSystem + ?Sized> FixedScheme for Run<'_, S> {
    fn start(&self) -> &[f64] {
        &self.y
    }

    /// One RK4 step from `(t, y)` into `y_new`.
    fn step(&mut self, t: f64, h: f64) {
        if !self.k1_valid {
            self.sys.rhs(t, &self.y, self.k.row_mut(0));
            self.stats.nfev += 1;
        }
        self.stats.nfev += RK4.eval_stages(self.sys, t, h, &self.y, &mut self.k, &mut self.ytmp);
        RK4.advance(h, &self.y, &self.k, &mut self.y_new);
        self.k1_valid = false;
    }

    fn new_state(&self) -> &[f64] {
        &self.y_new
    }

    fn record(&mut self, t: f64, t_new: f64, h: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        if sampler.needs_interpolant(t_new) {
            self.sys.rhs(t_new, &self.y_new, &mut self.f_new);
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

    fn stats(&mut self) -> &mut Stats {
        &mut self.stats
    }
}

/// One classical RK4 step of a small autonomous system `y' = f(y)` held in an array, in the
/// form `y + h/6 (k1 + 2 k2 + 2 k3 + k4)`: the step of the event-located loop
/// ([`super::events`]).
pub(crate) fn rk4_step<const N: usize>(f: impl Fn(&[f64; N]) -> [f64; N], y: &[f64; N], h: f64) -> [f64; N] {
    let add = |a: &[f64; N], k: &[f64; N], s: f64| -> [f64; N] { std::array::from_fn(|i| a[i] + s * k[i]) };
    let k1 = f(y);
    let k2 = f(&add(y, &k1, 0.5 * h));
    let k3 = f(&add(y, &k2, 0.5 * h));
    let k4 = f(&add(y, &k3, h));
    std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}
