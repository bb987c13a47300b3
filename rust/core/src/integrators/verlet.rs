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
//! on the uniform grid of [`super::grid::TimeGrid`] ([`super::fixed`]). `a(q_{n+1})` is reused as `a(q_n)` of the next step,
//! so a solve costs one evaluation of `a` per step plus one at the start
//! (`Stats::nfev = steps + 1`). Being symplectic and symmetric, the scheme keeps the
//! energy error of a Hamiltonian system bounded, `O(dt^2)`, with no secular drift over
//! exponentially long times. The sampled state is `[q, v]`; between grid points `q` is
//! interpolated by cubic Hermite with derivative `v`, and `v` by cubic Hermite with
//! derivative `a(q)`, exactly as for central differences.

use super::fixed::{FixedScheme, SecondOrderEnds, SecondOrderScheme};
use super::sampling::{OutputSampler, Recorded};
use super::Method;
use crate::solution::{Solution, Stats};
use crate::system::SecondOrderSystem;

/// Buffers of one Verlet solve, allocated once.
pub(crate) struct Verlet<'a, S: ?Sized> {
    sys: &'a S,
    /// `[q_n, v_n]`, `a(q_n)` and `[q_{n+1}, v_{n+1}]`, `a(q_{n+1})`.
    ends: SecondOrderEnds,
    stats: Stats,
}

impl<'a, S: SecondOrderSystem + ?Sized> SecondOrderScheme<'a, S> for Verlet<'a, S> {
    const METHOD: Method = Method::Verlet;

    /// Sets up `[q_0, v_0]` and `a(q_0)`.
    fn new(sys: &'a S, q0: &[f64], v0: &[f64], _dt: f64) -> Self {
        let mut run = Verlet { sys, ends: SecondOrderEnds::new(q0, v0), stats: Stats::default() };
        sys.acceleration(q0, &mut run.ends.acc);
        run.stats.nfev += 1;
        run
    }
}

impl<S: SecondOrderSystem + ?Sized> FixedScheme for Verlet<'_, S> {
    fn start(&self) -> &[f64] {
        &self.ends.state
    }

    /// One kick-drift-kick step.
    fn step(&mut self, _t: f64, dt: f64) {
        let half = 0.5 * dt;
        let e = &mut self.ends;
        let (q, v) = e.state.split_at(e.dof);
        let (q_new, v_new) = e.state_new.split_at_mut(e.dof);
        for i in 0..e.dof {
            let v_half = v[i] + half * e.acc[i];
            q_new[i] = q[i] + dt * v_half;
            v_new[i] = v_half;
        }
        self.sys.acceleration(q_new, &mut e.acc_new);
        self.stats.nfev += 1;
        for (v, &a) in v_new.iter_mut().zip(&e.acc_new) {
            *v += half * a;
        }
    }

    fn new_state(&self) -> &[f64] {
        &self.ends.state_new
    }

    fn record(&mut self, t: f64, t_new: f64, h: f64, sampler: &mut OutputSampler, sol: &mut Solution) -> Recorded {
        self.ends.record(t, t_new, h, sampler, sol)
    }

    fn stats(&mut self) -> &mut Stats {
        &mut self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{slope, Duffing, Harmonic};
    use super::super::{rk4, verlet, Method, SolveOptions};
    use super::*;
    use crate::error::Result;
    use crate::options::{FixedOptions, Output};
    use crate::solution::Status;
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
