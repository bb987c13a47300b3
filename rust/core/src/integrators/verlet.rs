//! Velocity (Stormer-)Verlet for `q'' = a(q)`, the symplectic second-order
//! kick-drift-kick scheme (Hairer, Lubich, Wanner, *Geometric Numerical Integration*,
//! 2nd ed., sec. I.1.4 and VI.3):
//!
//! ```text
//! v_{n+1/2} = v_n + dt/2 a(q_n)            (kick)
//! q_{n+1}   = q_n + dt v_{n+1/2}           (drift)
//! v_{n+1}   = v_{n+1/2} + dt/2 a(q_{n+1})  (kick)
//! ```
//!
//! on the uniform grid of [`Grid`]. `a(q_{n+1})` is reused as `a(q_n)` of the next step,
//! so a solve costs one evaluation of `a` per step plus one at the start
//! (`Stats::nfev = steps + 1`). Being symplectic and symmetric, the scheme keeps the
//! energy error of a Hamiltonian system bounded, `O(dt^2)`, with no secular drift over
//! exponentially long times. The sampled state is `[q, v]`; between grid points `q` is
//! interpolated by cubic Hermite with derivative `v`, and `v` by cubic Hermite with
//! derivative `a(q)`, exactly as for central differences.

use super::grid::Grid;
use super::hermite::hermite;
use super::sampling::{record_failure, RecordError, Sampler};
use super::tableau::all_finite;
use crate::error::Result;
use crate::interrupt::{Interrupt, Poller};
use crate::options::{validate_span, FixedOptions, Output};
use crate::solution::{Solution, Stats, Status};
use crate::system::SecondOrderSystem;

/// Solves `q'' = a(q)` from `(q0, v0)` by velocity Verlet (see the module docs).
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
        return Err(super::refuse_velocity_dependent(super::Method::Verlet));
    }
    validate_span(t0, t_end, output)?;
    opts.validate()?;
    super::check_state("q0", q0, sys.dof())?;
    super::check_state("v0", v0, sys.dof())?;
    let grid = Grid::new(t0, t_end, opts.dt);
    let mut sampler = Sampler::new(output);
    let hint = usize::try_from(grid.steps.min(opts.max_steps)).unwrap_or(usize::MAX).saturating_add(1);
    let mut sol = sampler.solution(2 * q0.len(), hint);
    let mut run = Run::new(sys, q0, v0);
    if let Err((status, message)) =
        run.steps(sys, &grid, opts.max_steps, &mut sampler, &mut sol, &mut Poller::new(interrupt))
    {
        sol.fail(status, message);
    }
    sol.stats = run.stats;
    Ok(sol)
}

/// Buffers of one Verlet solve, allocated once.
struct Run {
    dof: usize,
    /// `[q_n, v_n]` and `a(q_n)`.
    state: Vec<f64>,
    acc: Vec<f64>,
    /// `[q_{n+1}, v_{n+1}]` and `a(q_{n+1})`.
    state_new: Vec<f64>,
    acc_new: Vec<f64>,
    buf: Vec<f64>,
    stats: Stats,
}

impl Run {
    /// Sets up `state = [q_0, v_0]` and `a(q_0)`.
    fn new<S: SecondOrderSystem + ?Sized>(sys: &S, q0: &[f64], v0: &[f64]) -> Self {
        let dof = q0.len();
        let mut run = Run {
            dof,
            state: [q0, v0].concat(),
            acc: vec![0.0; dof],
            state_new: vec![0.0; 2 * dof],
            acc_new: vec![0.0; dof],
            buf: vec![0.0; 2 * dof],
            stats: Stats::default(),
        };
        sys.acceleration(q0, &mut run.acc);
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
        sampler.start(sol, grid.t0, &self.state).map_err(|err| record_failure(err, grid.t0, grid.t0))?;
        for n in 0..grid.steps {
            grid.before_step(n, max_steps, poller)?;
            let (t, t_new) = (grid.time(n), grid.time(n + 1));
            self.step(sys, grid.dt);
            if !all_finite(&self.state_new) {
                return Err(grid.non_finite(n + 1));
            }
            self.stats.naccept += 1;
            self.record(t, t_new, grid.dt, sampler, sol).map_err(|err| record_failure(err, t, t_new))?;
        }
        Ok(())
    }

    /// One kick-drift-kick step from `(state, acc)` into `(state_new, acc_new)`.
    fn step<S: SecondOrderSystem + ?Sized>(&mut self, sys: &S, dt: f64) {
        let half = 0.5 * dt;
        let (q, v) = self.state.split_at(self.dof);
        let (q_new, v_new) = self.state_new.split_at_mut(self.dof);
        for i in 0..self.dof {
            let v_half = v[i] + half * self.acc[i];
            q_new[i] = q[i] + dt * v_half;
            v_new[i] = v_half;
        }
        sys.acceleration(q_new, &mut self.acc_new);
        self.stats.nfev += 1;
        for (v, &a) in v_new.iter_mut().zip(&self.acc_new) {
            *v += half * a;
        }
    }

    /// Records output of the step `t -> t_new` and moves to the new state.
    fn record(
        &mut self,
        t: f64,
        t_new: f64,
        h: f64,
        sampler: &mut Sampler,
        sol: &mut Solution,
    ) -> std::result::Result<(), RecordError> {
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

#[cfg(test)]
mod tests {
    use super::super::tests::{slope, Duffing, Harmonic};
    use super::super::{rk4, verlet, Method, SolveOptions};
    use super::*;
    use crate::system::FirstOrder;

    /// Largest error of the `[q, v]` samples against the exact harmonic solution.
    fn harmonic_error(sys: &Harmonic, q0: f64, v0: f64, sol: &Solution) -> f64 {
        let mut err: f64 = 0.0;
        for k in 0..sol.len() {
            let exact = sys.exact(q0, v0, sol.t[k]);
            for (y, e) in sol.state(k).iter().zip(exact) {
                err = err.max((y - e).abs());
            }
        }
        err
    }

    #[test]
    fn verlet_has_order_2() {
        let sys = Harmonic { w: 2.0 };
        let dts = [0.02, 0.01, 0.005, 0.0025];
        // From rest-free and from displaced starts: the kick-drift-kick start is second
        // order in both (unlike the published central-difference start).
        for (q0, v0) in [(0.0, 1.0), (1.0, 0.5)] {
            let errs: Vec<f64> = dts
                .iter()
                .map(|&dt| {
                    let sol = verlet(&sys, 0.0, &[q0], &[v0], 5.0, &Output::EveryStep, &FixedOptions::new(dt)).unwrap();
                    assert_eq!(sol.status, Status::Success);
                    harmonic_error(&sys, q0, v0, &sol)
                })
                .collect();
            let p = slope(&dts, &errs);
            eprintln!("verlet harmonic from ({q0}, {v0}): errors {errs:?} order {p}");
            assert!((p - 2.0).abs() < 0.1, "order {p}");
        }
    }

    #[test]
    fn verlet_is_kick_drift_kick_with_one_evaluation_per_step() {
        let sys = Harmonic { w: 2.0 };
        let dt = 0.125; // divides the span exactly: the grid keeps it
        let sol = verlet(&sys, 0.0, &[1.0], &[0.5], 0.375, &Output::EveryStep, &FixedOptions::new(dt)).unwrap();
        let v_half = 0.5 + 0.5 * dt * (-4.0 * 1.0);
        let q1 = 1.0 + dt * v_half;
        let v1 = v_half + 0.5 * dt * (-4.0 * q1);
        assert_eq!(sol.state(0), [1.0, 0.5]);
        assert_eq!(sol.state(1), [q1, v1]);
        assert_eq!(sol.len(), 4);
        assert_eq!(sol.stats.nfev, 4, "one evaluation per step plus the start");
        assert_eq!(sol.stats.naccept, 3);
    }

    #[test]
    fn verlet_output_hits_step_points_exactly_and_interpolates_to_order_2() {
        let sys = Harmonic { w: 3.0 };
        let opts = FixedOptions::new(0.01);
        let every = verlet(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::EveryStep, &opts).unwrap();
        let times: Vec<f64> = (0..=200).map(|i| if i == 200 { 1.0 } else { i as f64 * 0.005 }).collect();
        let sampled = verlet(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::Times(times), &opts).unwrap();
        for k in 0..=100 {
            assert_eq!(every.state(k), sampled.state(2 * k), "k = {k}");
        }
        assert_eq!(every.stats, sampled.stats);
        let (e_every, e_sampled) = (harmonic_error(&sys, 0.0, 1.0, &every), harmonic_error(&sys, 0.0, 1.0, &sampled));
        assert!(e_sampled < 1.5 * e_every && e_every < 1e-3, "{e_every} {e_sampled}");
    }

    /// Largest relative energy error over the first and second halves of a solve.
    fn energy_errors(sys: &Duffing, sol: &Solution) -> (f64, f64) {
        let e0 = sys.energy(sol.state(0)[0], sol.state(0)[1]);
        let half = sol.len() / 2;
        let err = |range: std::ops::Range<usize>| {
            range.map(|k| ((sys.energy(sol.state(k)[0], sol.state(k)[1]) - e0) / e0).abs()).fold(0.0, f64::max)
        };
        (err(0..half), err(half..sol.len()))
    }

    #[test]
    fn verlet_energy_error_is_bounded_without_drift() {
        // A hardening Duffing oscillator, amplitude ~1, period ~4.8: 10^5 steps span ~400 periods.
        let sys = Duffing { a1: 1.0, a2: 1.0, a3: 1.0 };
        let t_end = 2000.0;
        let mut max_errs = Vec::new();
        let dts = [0.02, 0.01];
        for dt in dts {
            let sol = verlet(&sys, 0.0, &[0.0], &[1.2], t_end, &Output::EveryStep, &FixedOptions::new(dt)).unwrap();
            assert_eq!(sol.status, Status::Success);
            assert!(sol.stats.naccept >= 100_000);
            let (first, second) = energy_errors(&sys, &sol);
            eprintln!("verlet Duffing dt = {dt}: max |H - H0| / H0 first half {first:e}, second half {second:e}");
            assert!(first < 0.5 * dt * dt, "O(dt^2) bound: {first}");
            // No secular drift: the second half is no worse than the first (1% slack
            // for where the oscillation's extremes fall).
            assert!(second <= 1.01 * first, "drift: {first} then {second}");
            max_errs.push(first.max(second));
        }
        let ratio = max_errs[0] / max_errs[1];
        assert!((ratio.log2() - 2.0).abs() < 0.2, "energy error ratio {ratio} per halving of dt");

        // The same measure detects the secular drift of a non-symplectic method.
        let sol = rk4(&FirstOrder(&sys), 0.0, &[0.0, 1.2], t_end, &Output::EveryStep, &FixedOptions::new(0.2)).unwrap();
        let (first, second) = energy_errors(&sys, &sol);
        eprintln!("rk4 Duffing dt = 0.2: first half {first:e}, second half {second:e}");
        assert!(second > 1.5 * first, "rk4 should drift: {first} then {second}");
    }

    #[test]
    fn verlet_status_paths_and_validation() {
        // q'' = +q^3 escapes to infinity in finite time.
        let sys = Duffing { a1: 1.0, a2: 0.0, a3: -1.0 };
        let sol = verlet(&sys, 0.0, &[1.0], &[1.0], 10.0, &Output::EveryStep, &FixedOptions::new(0.01)).unwrap();
        assert_eq!(sol.status, Status::NonFinite, "{}", sol.message);

        let sys = Harmonic { w: 1.0 };
        let fixed = FixedOptions { dt: 0.01, max_steps: 5 };
        let sol = verlet(&sys, 0.0, &[1.0], &[0.5], 10.0, &Output::EveryStep, &fixed).unwrap();
        assert_eq!(sol.status, Status::MaxStepsReached);
        assert_eq!(sol.len(), 6);
        assert!(sol.message.contains("max_steps = 5"), "{}", sol.message);

        let every = Output::EveryStep;
        let ok = FixedOptions::new(0.1);
        let field = |r: Result<Solution>| r.unwrap_err().field().to_string();
        assert_eq!(field(verlet(&sys, 0.0, &[1.0, 2.0], &[0.0], 1.0, &every, &ok)), "q0");
        assert_eq!(field(verlet(&sys, 0.0, &[1.0], &[f64::NAN], 1.0, &every, &ok)), "v0");
        assert_eq!(field(verlet(&sys, 0.0, &[1.0], &[0.0], 0.0, &every, &ok)), "t_end");
        assert_eq!(field(verlet(&sys, 0.0, &[1.0], &[0.0], 1.0, &every, &FixedOptions::new(-1.0))), "dt");
        let opts = SolveOptions::new(Method::Verlet);
        let err = super::super::solve_second_order(&sys, 0.0, &[1.0], &[0.0], 1.0, &every, &opts).unwrap_err();
        assert_eq!(err.field(), "dt");
        assert!(err.to_string().contains("required by method verlet"), "{err}");
    }

    #[test]
    fn verlet_is_registered() {
        assert_eq!(Method::parse("verlet").unwrap(), Method::Verlet);
        assert!(Method::ALL.contains(&Method::Verlet));
        assert!(!Method::Verlet.is_adaptive());
        let sys = Harmonic { w: 1.0 };
        let output = Output::Times(vec![0.0, 0.5, 2.0]);
        let direct = verlet(&sys, 0.0, &[1.0], &[0.5], 2.0, &output, &FixedOptions::new(1e-3)).unwrap();
        let opts = SolveOptions { dt: Some(1e-3), ..SolveOptions::new(Method::Verlet) };
        let solved = super::super::solve_second_order(&sys, 0.0, &[1.0], &[0.5], 2.0, &output, &opts).unwrap();
        assert_eq!(solved, direct);
    }
}
