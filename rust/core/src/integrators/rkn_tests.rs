//! Tests of the RKN12(10) pair: convergence orders of the method and of its error estimate,
//! adaptive accuracy, dense output against exact solutions, statuses and refusals.

use super::rkn::testing::uniform_steps;
use super::rkn12::RKN12;
use super::tests::{slope, Duffing, Harmonic};
use super::*;
use crate::solution::Status;

fn opts(rtol: f64, atol: f64) -> AdaptiveOptions {
    AdaptiveOptions { rtol, atol, ..AdaptiveOptions::default() }
}

/// Error at `t_end` and largest step error estimate with `n` uniform steps on `q'' = -q`
/// from `(1, 0.5)`.
fn harmonic_uniform(n: usize, t_end: f64) -> (f64, f64) {
    let sys = Harmonic { w: 1.0 };
    let (y, est) = uniform_steps(&RKN12, &sys, (&[1.0], &[0.5]), (0.0, t_end), n);
    let exact = sys.exact(1.0, 0.5, t_end);
    ((y[0] - exact[0]).abs().max((y[1] - exact[1]).abs()), est)
}

/// Order 12 on the linear oscillator; the error estimate, the local error of the embedded
/// order-10 solution, shrinks like `h^11` per step.
#[test]
fn rkn12_has_order_12_and_an_order_10_estimate() {
    let t_end = 20.0;
    let ns = [10, 12, 14, 17];
    let hs: Vec<f64> = ns.iter().map(|&n| t_end / n as f64).collect();
    let (errs, ests): (Vec<f64>, Vec<f64>) = ns.iter().map(|&n| harmonic_uniform(n, t_end)).unzip();
    let (p, pe) = (slope(&hs, &errs), slope(&hs, &ests));
    eprintln!("RKN12 h = {hs:?}\nerr = {errs:?} (order {p})\nestimate = {ests:?} (order {pe})");
    assert!((p - 12.0).abs() < 0.6, "order {p}");
    assert!((pe - 11.0).abs() < 0.6, "estimate order {pe} (local error of an order-10 solution)");
}

/// Order 12 on a nonlinear problem: the local error of one step on Duffing
/// `q'' = -q - 4 q^3` from `(1, 0)`, against the same method with 64 substeps, is `O(h^13)`.
/// At step sizes whose error stays above rounding the measured slope is still approaching 13
/// (11.5 over `h = 0.4 .. 0.2`; in 60-digit arithmetic 11.7, 12.2, 12.8 over
/// `h = 0.4, 0.2, 0.1, 0.05`), so the check is for a slope above 11 (an order-10 method
/// would show at most 11).
#[test]
fn rkn12_has_order_12_on_duffing() {
    let sys = Duffing { a1: 1.0, a2: 1.0, a3: 4.0 };
    let run = |h: f64, n: usize| uniform_steps(&RKN12, &sys, (&[1.0], &[0.0]), (0.0, h), n).0;
    let hs = [0.4, 0.32, 0.25, 0.2];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let (y, reference) = (run(h, 1), run(h, 64));
            (y[0] - reference[0]).abs().max((y[1] - reference[1]).abs())
        })
        .collect();
    let p = slope(&hs, &errs);
    eprintln!("RKN12 Duffing one step h = {hs:?}\nlocal error = {errs:?} (order {p})");
    assert!(p > 11.0 && p < 14.0, "local order {p}");
}

/// `q'' = -K q` with `K = [[2, -1], [-1, 2]]` (frequencies 1 and sqrt 3): exact `[q, v]` at `t`
/// from `(q0, 0)` by the eigenvectors `(1, 1)/sqrt 2`, `(1, -1)/sqrt 2` of `K`, i.e.
/// `q(t) = cos(sqrt(K) t) q0`, `v(t) = -sqrt(K) sin(sqrt(K) t) q0`.
struct Chain2;

impl SecondOrderSystem for Chain2 {
    fn dof(&self) -> usize {
        2
    }
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        acc[0] = -2.0 * q[0] + q[1];
        acc[1] = q[0] - 2.0 * q[1];
    }
}

fn chain2_exact(q0: [f64; 2], t: f64) -> [f64; 4] {
    let (m1, m2) = (0.5 * (q0[0] + q0[1]), 0.5 * (q0[0] - q0[1]));
    let w2 = 3f64.sqrt();
    let (a, b) = (m1 * t.cos(), m2 * (w2 * t).cos());
    let (da, db) = (-m1 * t.sin(), -m2 * w2 * (w2 * t).sin());
    [a + b, a - b, da + db, da - db]
}

/// Every dense sample agrees with the exact solution of a linear system to the tolerance,
/// with the steps not tied to the output (far fewer steps than samples).
#[test]
fn rkn12_dense_output_matches_the_exact_linear_solution() {
    let q0 = [1.0, 0.25];
    for (rtol, atol, bound) in [(1e-8, 1e-8, 1e-7), (1e-10, 1e-10, 1e-9), (1e-12, 1e-12, 1e-11), (1e-13, 1e-15, 2e-13)]
    {
        let times: Vec<f64> = (0..=4000).map(|k| f64::from(k) * 0.01).collect();
        let sol =
            rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 40.0, &Output::Times(times.clone()), &opts(rtol, atol)).unwrap();
        assert_eq!(sol.status, Status::Success);
        assert_eq!(sol.t, times);
        let mut err: f64 = 0.0;
        let mut worst = 0.0;
        for (k, &t) in times.iter().enumerate() {
            let exact = chain2_exact(q0, t);
            for (a, b) in sol.state(k).iter().zip(exact) {
                if (a - b).abs() > err {
                    worst = t;
                }
                err = err.max((a - b).abs());
            }
        }
        // The error at the step ends alone (every-step output; without interpolation its steps
        // are not capped by the interpolation error).
        let steps = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 40.0, &Output::EveryStep, &opts(rtol, atol)).unwrap();
        let mut err_ends: f64 = 0.0;
        for k in 0..steps.len() {
            let exact = chain2_exact(q0, steps.t[k]);
            for (a, b) in steps.state(k).iter().zip(exact) {
                err_ends = err_ends.max((a - b).abs());
            }
        }
        eprintln!(
            "rtol {rtol:e}: dense error {err:e} (worst at t = {worst}), step-end error {err_ends:e}, \
             {} steps with output times, {} without",
            sol.stats.naccept, steps.stats.naccept
        );
        assert!(err < bound, "rtol {rtol}: dense error {err}");
        assert!(sol.stats.naccept < 400 && sol.stats.naccept >= steps.stats.naccept, "{:?}", sol.stats);
        // The steps do not depend on how many output times there are.
        let few =
            rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 40.0, &Output::Times(vec![3.0, 40.0]), &opts(rtol, atol)).unwrap();
        assert_eq!(few.stats, sol.stats);
        assert_eq!(few.state(1), sol.state(4000));
    }
}

/// The first intervals of a solve are as accurate as the others: their interpolants take
/// ends before `t0` (the backward lead-in steps) instead of a one-sided window, which was 75
/// times less accurate for equal steps (the product of the node distances, cubed).
#[test]
fn rkn12_dense_output_is_as_accurate_at_the_start() {
    let q0 = [1.0, 0.25];
    let (rtol, atol) = (1e-10, 1e-10);
    // Start with the step size the control settles on, so that the steps are about equal.
    let steps = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 20.0, &Output::EveryStep, &opts(rtol, atol)).unwrap();
    let h = steps.t[steps.len() / 2] - steps.t[steps.len() / 2 - 1];
    let o = AdaptiveOptions { first_step: Some(h), ..opts(rtol, atol) };
    let times: Vec<f64> = (0..=20_000).map(|k| f64::from(k) * 1e-3).collect();
    let sol = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 20.0, &Output::Times(times.clone()), &o).unwrap();
    assert_eq!(sol.status, Status::Success);
    let (mut first, mut rest) = (0.0f64, 0.0f64);
    for (k, &t) in times.iter().enumerate() {
        let e = sol.state(k).iter().zip(chain2_exact(q0, t)).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if t < 2.0 * h {
            first = first.max(e);
        } else if t < 10.0 * h {
            rest = rest.max(e);
        }
    }
    eprintln!("h = {h}: dense error {first:e} on the first two intervals, {rest:e} on the next eight; {:?}", sol.stats);
    assert!(first < 2.0 * rest, "first intervals {first:e}, later {rest:e}");
    // The lead-in and the lead-out cost two steps each: 17 evaluations per step (16 stages
    // and the end).
    let plain = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 20.0, &Output::EveryStep, &o).unwrap();
    assert_eq!(sol.stats.nfev, plain.stats.nfev + 4 * 17, "{:?} vs {:?}", sol.stats, plain.stats);
    assert_eq!((sol.stats.ndense, plain.stats.ndense), (4 * 17, 0));
}

/// At a tolerance near rounding the solve with output times takes the steps of the
/// every-step solve (an interpolation-error estimate once drove them to underflow here). The
/// dense error is then about ten rounding errors of `q` (2.7e-14 against 2e-14 at the step
/// ends; 5.5e-13 before the windows were balanced in steps: on the small first steps the
/// velocities, the derivative of the position interpolant, lose `eps |q| / (h |v|)`).
#[test]
fn rkn12_dense_output_near_rounding() {
    let q0 = [1.0, 0.25];
    let o = opts(1e-15, 1e-21);
    let times: Vec<f64> = (0..=2000).map(|k| f64::from(k) * 0.01).collect();
    let sol = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 20.0, &Output::Times(times.clone()), &o).unwrap();
    let steps = rkn12(&Chain2, 0.0, &q0, &[0.0, 0.0], 20.0, &Output::EveryStep, &o).unwrap();
    assert_eq!(sol.status, Status::Success, "{}", sol.message);
    let mut err: f64 = 0.0;
    for (k, &t) in times.iter().enumerate() {
        for (a, b) in sol.state(k).iter().zip(chain2_exact(q0, t)) {
            err = err.max((a - b).abs());
        }
    }
    eprintln!("rtol 1e-15: dense error {err:e}, {} steps ({} every-step)", sol.stats.naccept, steps.stats.naccept);
    assert!(err < 1e-13, "dense error {err}");
    assert!(sol.stats.naccept < steps.stats.naccept * 3 / 2, "{:?} vs {:?}", sol.stats, steps.stats);
}

/// `K(m) = pi / (2 agm(1, sqrt(1 - m)))`, the complete elliptic integral of the first kind.
fn ellip_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..40 {
        let (a1, b1) = (0.5 * (a + b), (a * b).sqrt());
        a = a1;
        b = b1;
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The one-mode Duffing `q'' + q + beta q^3 = 0` from `(0, c)`: at the quarter periods of the
/// exact period `T = 4 K(m) / sqrt(1 + beta A^2)` the dense output is `(±A, 0)` and `(0, ±c)`.
#[test]
fn rkn12_dense_output_hits_exact_duffing_quarter_periods() {
    let (beta, c) = (2.0, 1.5);
    let sys = Duffing { a1: 1.0, a2: 1.0, a3: beta };
    let amp = sys.amplitude(sys.energy(0.0, c));
    let m = beta * amp * amp / (2.0 * (1.0 + beta * amp * amp));
    let period = 4.0 * ellip_k(m) / (1.0 + beta * amp * amp).sqrt();
    let quarters = 40;
    let times: Vec<f64> = (1..=quarters).map(|k| f64::from(k) * 0.25 * period).collect();
    let t_end = times[quarters as usize - 1] + 0.1;
    let sol = rkn12(&sys, 0.0, &[0.0], &[c], t_end, &Output::Times(times.clone()), &opts(1e-12, 1e-12)).unwrap();
    assert_eq!(sol.status, Status::Success);
    let mut err: f64 = 0.0;
    for k in 0..times.len() {
        let want = match k % 4 {
            0 => [amp, 0.0],
            1 => [0.0, -c],
            2 => [-amp, 0.0],
            _ => [0.0, c],
        };
        let got = sol.state(k);
        err = err.max((got[0] - want[0]).abs()).max((got[1] - want[1]).abs());
    }
    eprintln!("Duffing quarter periods: error {err:e} over {quarters} quarters, {:?}", sol.stats);
    assert!(err < 2e-11, "error {err}");
}

/// Through [`solve_second_order`] by name; velocity-dependent forces are refused naming `method`.
#[test]
fn rkn12_by_name_and_refusal_of_damping() {
    assert_eq!(Method::parse("rkn12").unwrap(), Method::Rkn12);
    assert!(Method::Rkn12.is_adaptive());
    let sys = Harmonic { w: 2.0 };
    let so = SolveOptions { rtol: 1e-11, atol: 1e-11, ..SolveOptions::new(Method::Rkn12) };
    let a = solve_second_order(&sys, 0.0, &[1.0], &[0.5], 5.0, &Output::EveryStep, &so).unwrap();
    let b = rkn12(&sys, 0.0, &[1.0], &[0.5], 5.0, &Output::EveryStep, &so.adaptive()).unwrap();
    assert_eq!(a, b);
    // 17 evaluations per accepted step, 16 per rejected one, 1 at the start and 1 in hinit.
    let s = a.stats;
    assert_eq!(s.nfev, 2 + 17 * s.naccept + 16 * s.nreject);
    assert_eq!(*a.t.last().unwrap(), 5.0);

    struct Damped;
    impl SecondOrderSystem for Damped {
        fn dof(&self) -> usize {
            1
        }
        fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
            acc[0] = -q[0];
        }
        fn velocity_dependent(&self) -> bool {
            true
        }
        fn acceleration_full(&self, _t: f64, q: &[f64], v: &[f64], acc: &mut [f64]) {
            acc[0] = -q[0] - 0.1 * v[0];
        }
    }
    let err = solve_second_order(&Damped, 0.0, &[1.0], &[0.0], 1.0, &Output::EveryStep, &so).unwrap_err();
    assert!(err.to_string().contains("method") && err.to_string().contains("rkn12"), "{err}");
    let err = rkn12(&Damped, 0.0, &[1.0], &[0.0], 1.0, &Output::EveryStep, &so.adaptive()).unwrap_err();
    assert!(err.to_string().contains("method"), "{err}");
}

/// `"auto"` picks RKN12 for tight tolerances without damping, DOP853 otherwise.
#[test]
fn auto_resolution() {
    assert_eq!(Method::resolve("auto", false, AUTO_RKN12_MAX_RTOL).unwrap(), Method::Rkn12);
    assert_eq!(Method::resolve("auto", false, AUTO_RKN12_MAX_RTOL * 1.01).unwrap(), Method::Dop853);
    assert_eq!(Method::resolve("auto", true, 1e-14).unwrap(), Method::Dop853);
    assert_eq!(Method::resolve("rk4", false, 1e-14).unwrap(), Method::Rk4);
    let err = Method::resolve("rkn", false, 1e-12).unwrap_err().to_string();
    assert!(err.contains("method") && err.contains("auto"), "{err}");
}

/// The failure statuses: max_steps, non-finite state, interrupt; samples up to the failure.
#[test]
fn rkn12_statuses() {
    let sys = Harmonic { w: 1.0 };
    let times: Vec<f64> = (0..=100).map(|k| f64::from(k) * 0.1).collect();
    let o = AdaptiveOptions { max_steps: 5, ..opts(1e-12, 1e-12) };
    let sol = rkn12(&sys, 0.0, &[1.0], &[0.0], 10.0, &Output::Times(times.clone()), &o).unwrap();
    assert_eq!(sol.status, Status::MaxStepsReached);
    assert!(sol.message.contains("max_steps"), "{}", sol.message);
    // The samples reached (through the interpolant of the ends reached) are kept; the last
    // intervals lie in one-sided windows (no ends after them), so they are less accurate than
    // the tolerance (1e-9 here).
    assert!(!sol.is_empty() && sol.len() < times.len());
    for k in 0..sol.len() {
        let e = (sol.state(k)[0] - sol.t[k].cos()).abs();
        assert!(e < 1e-8, "t = {}: error {e:e}, {:?} {:?}", sol.t[k], sol.t, sol.stats);
    }

    /// `q'' = q^3` from `q = 1, v = 1/sqrt 2`: `q = 1 / (1 - t/sqrt 2)` blows up at `sqrt 2`.
    struct Blow;
    impl SecondOrderSystem for Blow {
        fn dof(&self) -> usize {
            1
        }
        fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
            acc[0] = q[0] * q[0] * q[0];
        }
    }
    let sol = rkn12(&Blow, 0.0, &[1.0], &[0.5f64.sqrt()], 2.0, &Output::EveryStep, &opts(1e-10, 1e-10)).unwrap();
    assert!(
        matches!(sol.status, Status::StepSizeUnderflow | Status::NonFinite | Status::MaxStepsReached),
        "{:?}: {}",
        sol.status,
        sol.message
    );
    eprintln!("blow-up: {:?} at t = {}: {}", sol.status, sol.t.last().unwrap(), sol.message);

    let flag = crate::CancelFlag::new();
    flag.cancel();
    let so = SolveOptions::new(Method::Rkn12);
    let sol = solve_second_order_with(&sys, 0.0, &[1.0], &[0.0], 1e6, &Output::EveryStep, &so, &flag).unwrap();
    assert_eq!(sol.status, Status::Interrupted);

    // Bad options are refused naming the field.
    let err = rkn12(&sys, 0.0, &[1.0], &[0.0], 1.0, &Output::EveryStep, &opts(-1.0, 1e-12)).unwrap_err();
    assert!(err.to_string().contains("rtol"), "{err}");
}
