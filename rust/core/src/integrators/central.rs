//! Explicit central differences for `q'' = a(q)` (the leapfrog / Stormer-Verlet scheme in
//! two-step form, Hairer, Norsett, Wanner, *Solving ODEs I*, sec. III.10):
//!
//! ```text
//! q_1     = q_0 + dt v_0                               (this start, as in the published table)
//! q_{n+1} = 2 q_n - q_{n-1} + dt^2 a(q_n)
//! v_n     = (q_{n+1} - q_{n-1}) / (2 dt)   (v_0 given)
//! ```
//!
//! on the uniform grid of [`super::grid::TimeGrid`] ([`super::fixed`]); second-order accurate. The sampled state is `[q, v]`.
//! Between grid points `q` is interpolated by cubic Hermite with derivative `v`, and `v` by
//! cubic Hermite with derivative `a(q)`. `Stats::nfev` counts evaluations of `a`
//! (one per grid point).

use super::fixed::{FixedScheme, SecondOrderEnds, SecondOrderScheme};
use super::sampling::{OutputSampler, Recorded};
use super::Method;
use crate::solution::{Solution, Stats};
use crate::system::SecondOrderSystem;

/// Buffers of one central-difference solve, allocated once.
pub(crate) struct Central<'a, S: ?Sized> {
    sys: &'a S,
    dt: f64,
    /// `q_{n-1}`.
    q_prev: Vec<f64>,
    /// `q_n`.
    q: Vec<f64>,
    /// `q_{n+1}`.
    q_next: Vec<f64>,
    /// `[q_{n-1}, v_{n-1}]`, `a(q_{n-1})` and `[q_n, v_n]`, `a(q_n)`.
    ends: SecondOrderEnds,
    stats: Stats,
}

impl<'a, S: SecondOrderSystem + ?Sized> SecondOrderScheme<'a, S> for Central<'a, S> {
    const METHOD: Method = Method::Central;

    /// Sets up `[q_0, v_0]`, `a(q_0)` and the start `q_1 = q_0 + dt v_0`.
    fn new(sys: &'a S, q0: &[f64], v0: &[f64], dt: f64) -> Self {
        let dof = q0.len();
        let mut run = Central {
            sys,
            dt,
            q_prev: q0.to_vec(),
            q: q0.iter().zip(v0).map(|(&q, &v)| q + dt * v).collect(),
            q_next: vec![0.0; dof],
            ends: SecondOrderEnds::new(q0, v0),
            stats: Stats::default(),
        };
        sys.acceleration(q0, &mut run.ends.acc);
        run.stats.nfev += 1;
        run
    }
}

impl<S: SecondOrderSystem + ?Sized> FixedScheme for Central<'_, S> {
    fn start(&self) -> &[f64] {
        &self.ends.state
    }

    /// Evaluates `a(q_n)`, the next position `q_{n+1}` and the state `[q_n, v_n]`.
    fn step(&mut self, _t: f64, _h: f64) {
        let (dt, dof) = (self.dt, self.ends.dof);
        self.sys.acceleration(&self.q, &mut self.ends.acc_new);
        self.stats.nfev += 1;
        let acc = &self.ends.acc_new;
        let (pos, vel) = self.ends.state_new.split_at_mut(dof);
        for i in 0..dof {
            self.q_next[i] = 2.0 * self.q[i] - self.q_prev[i] + dt * dt * acc[i];
            pos[i] = self.q[i];
            vel[i] = (self.q_next[i] - self.q_prev[i]) / (2.0 * dt);
        }
    }

    fn new_state(&self) -> &[f64] {
        &self.ends.state_new
    }

    /// Records the interval `t -> t_new` and shifts the two-step history.
    fn record(&mut self, t: f64, t_new: f64, _h: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        self.ends.record(t, t_new, self.dt, sampler, sol)?;
        // (q_{n-1}, q_n, q_{n+1}) <- (q_n, q_{n+1}, unused)
        std::mem::swap(&mut self.q_prev, &mut self.q);
        std::mem::swap(&mut self.q, &mut self.q_next);
        Ok(())
    }

    fn stats(&mut self) -> &mut Stats {
        &mut self.stats
    }
}
