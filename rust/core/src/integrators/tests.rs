//! Tests shared by the integrators: problems with known solutions, convergence orders,
//! dense output, tolerance proportionality, status paths and input validation.

use super::adaptive::testing::uniform_steps;
use super::adaptive::Scheme;
use super::dop853::Dop853;
use super::dopri5::Dopri5;
use super::form::{Nystrom, Plain};
use super::*;
use crate::solution::Status;

// ---------------------------------------------------------------- test problems

/// `q'' = -w^2 q`.
pub(crate) struct Harmonic {
    pub w: f64,
}

impl SecondOrderSystem for Harmonic {
    fn dof(&self) -> usize {
        1
    }
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        acc[0] = -self.w * self.w * q[0];
    }
}

impl Harmonic {
    /// The exact `[q, v]` at `t` from `(q0, v0)` at 0.
    pub fn exact(&self, q0: f64, v0: f64, t: f64) -> [f64; 2] {
        let (s, c) = (self.w * t).sin_cos();
        [q0 * c + v0 / self.w * s, -q0 * self.w * s + v0 * c]
    }
}

/// `y' = -y^2`, exact `y = y0 / (1 + y0 t)`.
pub(crate) struct Decay;

impl OdeSystem for Decay {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = -y[0] * y[0];
    }
}

/// `y' = y^2`: from `y(0) = 1` it blows up at `t = 1`.
pub(crate) struct BlowUp;

impl OdeSystem for BlowUp {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[0] * y[0];
    }
}

/// `y' = (1 + |y|^2) J y`: rotation at the amplitude-dependent rate `1 + |y0|^2`.
pub(crate) struct NonlinearRotation;

impl OdeSystem for NonlinearRotation {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let w = 1.0 + y[0] * y[0] + y[1] * y[1];
        dydt[0] = -w * y[1];
        dydt[1] = w * y[0];
    }
}

/// One-mode Duffing `a1 q'' + a2 q + a3 q^3 = 0`.
pub(crate) struct Duffing {
    pub a1: f64,
    pub a2: f64,
    pub a3: f64,
}

impl SecondOrderSystem for Duffing {
    fn dof(&self) -> usize {
        1
    }
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        acc[0] = -(self.a2 * q[0] + self.a3 * q[0] * q[0] * q[0]) / self.a1;
    }
}

impl Duffing {
    pub fn energy(&self, q: f64, v: f64) -> f64 {
        0.5 * self.a1 * v * v + 0.5 * self.a2 * q * q + 0.25 * self.a3 * q.powi(4)
    }

    /// The amplitude of the motion with energy `e`: the root of `a3/4 A^4 + a2/2 A^2 = e`.
    pub fn amplitude(&self, e: f64) -> f64 {
        let a_sq = (-0.5 * self.a2 + (0.25 * self.a2 * self.a2 + self.a3 * e).sqrt()) / (0.5 * self.a3);
        a_sq.sqrt()
    }
}

/// Least-squares slope of `log(err)` against `log(h)`.
pub(crate) fn slope(hs: &[f64], errs: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

type AdaptiveFn<S> = fn(&S, f64, &[f64], f64, &Output, &AdaptiveOptions) -> Result<Solution>;

/// DOP853 and DOPRI5 as function pointers, with their names.
fn adaptive_solvers<S: OdeSystem>() -> [(&'static str, AdaptiveFn<S>); 2] {
    [("dop853", dop853::<S>), ("dopri5", dopri5::<S>)]
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| if i + 1 == n { b } else { a + (b - a) * i as f64 / (n - 1) as f64 }).collect()
}

fn adaptive_opts(rtol: f64, atol: f64) -> AdaptiveOptions {
    AdaptiveOptions { rtol, atol, ..AdaptiveOptions::default() }
}

/// Largest error of `[q, v]` samples against the exact harmonic solution.
fn harmonic_error(sys: &Harmonic, q0: f64, v0: f64, sol: &Solution) -> f64 {
    let mut err: f64 = 0.0;
    for k in 0..sol.len() {
        let exact = sys.exact(q0, v0, sol.t[k]);
        for (a, b) in sol.state(k).iter().zip(exact) {
            err = err.max((a - b).abs());
        }
    }
    err
}

// ---------------------------------------------------------------- convergence orders

/// Error at `t_end` of the pair `P` with `n` uniform steps on the harmonic oscillator.
fn uniform_error_harmonic<P: Scheme>(n: usize, t_end: f64) -> f64 {
    let sys = Harmonic { w: 1.0 };
    let y = uniform_steps::<P, _>(&Plain(&FirstOrder(&sys)), 0.0, &[1.0, 0.5], t_end, n);
    let exact = sys.exact(1.0, 0.5, t_end);
    (y[0] - exact[0]).abs().max((y[1] - exact[1]).abs())
}

/// Error at `t_end` of the pair `P` with `n` uniform steps on [`NonlinearRotation`] from
/// `y0 = (0.6, 0.3)` (exact: rotation by the angle `(1 + 0.45) t`).
fn uniform_error_rotation<P: Scheme>(n: usize, t_end: f64) -> f64 {
    let y0 = [0.6, 0.3];
    let y = uniform_steps::<P, _>(&Plain(&NonlinearRotation), 0.0, &y0, t_end, n);
    let (s, c) = (1.45 * t_end).sin_cos();
    let exact = [c * y0[0] - s * y0[1], s * y0[0] + c * y0[1]];
    (y[0] - exact[0]).abs().max((y[1] - exact[1]).abs())
}

/// [`uniform_error_harmonic`] in the Runge-Kutta-Nystrom form.
fn uniform_error_harmonic_nystrom<P: Scheme>(n: usize, t_end: f64) -> f64 {
    let sys = Harmonic { w: 1.0 };
    let y = uniform_steps::<P, _>(&Nystrom::new(&sys, &P::row_inputs()), 0.0, &[1.0, 0.5], t_end, n);
    let exact = sys.exact(1.0, 0.5, t_end);
    (y[0] - exact[0]).abs().max((y[1] - exact[1]).abs())
}

/// A nonlinear chain of `n` unit masses: `q_i'' = (q_{i-1} - 2 q_i + q_{i+1}) - q_i^3`
/// (free ends), enough coordinates for the Nystrom form of [`solve_second_order`].
struct DuffingChain(usize);

impl SecondOrderSystem for DuffingChain {
    fn dof(&self) -> usize {
        self.0
    }
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        let n = self.0;
        for i in 0..n {
            let left = if i > 0 { q[i - 1] - q[i] } else { 0.0 };
            let right = if i + 1 < n { q[i + 1] - q[i] } else { 0.0 };
            acc[i] = left + right - q[i] * q[i] * q[i];
        }
    }
}

/// The Nystrom form is the same method as the first-order form, up to rounding: uniform
/// steps agree to rounding, and full adaptive solves (error estimate, step control, dense
/// output with DOP853's extra stages) take the same steps and agree to far below the tolerance.
#[test]
fn nystrom_form_is_the_same_method() {
    let n = NYSTROM_MIN_DOF;
    let sys = DuffingChain(n);
    assert!(n >= NYSTROM_MIN_DOF);
    let q0: Vec<f64> = (0..n).map(|i| 0.8 * (i as f64 * 0.9).sin()).collect();
    let v0: Vec<f64> = (0..n).map(|i| 0.5 * (i as f64 * 0.4).cos()).collect();
    let y0 = [q0.clone(), v0.clone()].concat();
    let plain = Plain(&FirstOrder(&sys));
    fn compare<P: Scheme>(sys: &DuffingChain, plain: &Plain<'_, FirstOrder<'_, DuffingChain>>, y0: &[f64]) {
        let nystrom = Nystrom::new(sys, &P::row_inputs());
        let a = uniform_steps::<P, _>(plain, 0.0, y0, 3.0, 60);
        let b = uniform_steps::<P, _>(&nystrom, 0.0, y0, 3.0, 60);
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-13, "uniform steps: {x} vs {y}");
        }
    }
    compare::<Dop853>(&sys, &plain, &y0);
    compare::<Dopri5>(&sys, &plain, &y0);
    let output = Output::Times((0..=40).map(|i| i as f64 * 0.25).collect());
    for method in [Method::Dop853, Method::Dopri5] {
        let opts = SolveOptions { rtol: 1e-10, atol: 1e-12, ..SolveOptions::new(method) };
        let first = match method {
            Method::Dop853 => dop853(&FirstOrder(&sys), 0.0, &y0, 10.0, &output, &opts.adaptive()),
            _ => dopri5(&FirstOrder(&sys), 0.0, &y0, 10.0, &output, &opts.adaptive()),
        }
        .unwrap();
        let second = solve_second_order(&sys, 0.0, &q0, &v0, 10.0, &output, &opts).unwrap();
        assert!(first.status.is_success() && second.status.is_success());
        let (s1, s2) = (first.stats, second.stats);
        assert!(s1.naccept.abs_diff(s2.naccept) <= 1 && s1.nreject.abs_diff(s2.nreject) <= 1, "{s1:?} vs {s2:?}");
        assert!(s1.naccept > 50, "{s1:?}");
        let scale = first.y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let diff = first.y.iter().zip(&second.y).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(diff < 1e-10 * scale, "{method:?}: max difference {diff} (scale {scale})");
    }
}

fn measured_order(ns: &[usize], t_end: f64, err: impl Fn(usize) -> f64) -> f64 {
    let hs: Vec<f64> = ns.iter().map(|&n| t_end / n as f64).collect();
    let errs: Vec<f64> = ns.iter().map(|&n| err(n)).collect();
    eprintln!("h = {hs:?}\nerr = {errs:?}");
    slope(&hs, &errs)
}

#[test]
fn dop853_has_order_8() {
    let ns = [10, 14, 20, 28];
    let p = measured_order(&ns, 10.0, |n| uniform_error_harmonic::<Dop853>(n, 10.0));
    eprintln!("DOP853 harmonic order {p}");
    assert!((p - 8.0).abs() < 0.5, "order {p}");
    let p = measured_order(&ns, 5.0, |n| uniform_error_rotation::<Dop853>(n, 5.0));
    eprintln!("DOP853 nonlinear rotation order {p}");
    assert!((p - 8.0).abs() < 0.5, "order {p}");
    let p = measured_order(&ns, 10.0, |n| uniform_error_harmonic_nystrom::<Dop853>(n, 10.0));
    eprintln!("DOP853 harmonic order, Nystrom form {p}");
    assert!((p - 8.0).abs() < 0.5, "order {p}");
}

#[test]
fn dopri5_has_order_5() {
    let ns = [20, 40, 80, 160];
    let p = measured_order(&ns, 10.0, |n| uniform_error_harmonic::<Dopri5>(n, 10.0));
    eprintln!("DOPRI5 harmonic order {p}");
    assert!((p - 5.0).abs() < 0.5, "order {p}");
    let p = measured_order(&ns, 10.0, |n| uniform_error_harmonic_nystrom::<Dopri5>(n, 10.0));
    eprintln!("DOPRI5 harmonic order, Nystrom form {p}");
    assert!((p - 5.0).abs() < 0.5, "order {p}");
    let ns = [80, 112, 160, 224];
    let p = measured_order(&ns, 5.0, |n| uniform_error_rotation::<Dopri5>(n, 5.0));
    eprintln!("DOPRI5 nonlinear rotation order {p}");
    assert!((p - 5.0).abs() < 0.5, "order {p}");
}

#[test]
fn rk4_has_order_4() {
    let sys = Harmonic { w: 2.0 };
    let t_end = 5.0;
    let dts = [0.05, 0.025, 0.0125, 0.00625];
    let errs: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let sol =
                rk4(&FirstOrder(&sys), 0.0, &[1.0, 0.5], t_end, &Output::Times(vec![t_end]), &FixedOptions::new(dt))
                    .unwrap();
            harmonic_error(&sys, 1.0, 0.5, &sol)
        })
        .collect();
    let p = slope(&dts, &errs);
    eprintln!("RK4 harmonic errors {errs:?} order {p}");
    assert!((p - 4.0).abs() < 0.5, "order {p}");
    let errs: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let y0 = [0.6, 0.3];
            let sol =
                rk4(&NonlinearRotation, 0.0, &y0, t_end, &Output::Times(vec![t_end]), &FixedOptions::new(dt)).unwrap();
            let (s, c) = (1.45 * t_end).sin_cos();
            (sol.y[0] - (c * y0[0] - s * y0[1])).abs().max((sol.y[1] - (s * y0[0] + c * y0[1])).abs())
        })
        .collect();
    let p = slope(&dts, &errs);
    eprintln!("RK4 nonlinear rotation errors {errs:?} order {p}");
    assert!((p - 4.0).abs() < 0.5, "order {p}");
}

/// Central-difference error at `t_end = 5` on `q'' = -4 q` from `(q0, v0)`, per `dt`.
fn central_errors(q0: f64, v0: f64, dts: &[f64]) -> Vec<f64> {
    let sys = Harmonic { w: 2.0 };
    let output = Output::Times(vec![5.0]);
    dts.iter()
        .map(|&dt| {
            let sol = central_difference(&sys, 0.0, &[q0], &[v0], 5.0, &output, &FixedOptions::new(dt)).unwrap();
            harmonic_error(&sys, q0, v0, &sol)
        })
        .collect()
}

#[test]
fn central_difference_has_order_2() {
    // From q0 = 0 (a(q0) = 0, the drill-string start) the start q1 = q0 + dt v0 is exact
    // to O(dt^3) and the scheme is second order.
    let dts = [0.02, 0.01, 0.005, 0.0025];
    let errs = central_errors(0.0, 1.0, &dts);
    let p = slope(&dts, &errs);
    eprintln!("central harmonic errors {errs:?} order {p}");
    assert!((p - 2.0).abs() < 0.5, "order {p}");
}

/// The published start `q1 = q0 + dt v0` drops the `dt^2/2 a(q0)` term: when
/// `a(q0) != 0` it is an `O(dt)` velocity error and the scheme is only first order.
#[test]
fn central_difference_start_is_first_order_when_a_q0_is_nonzero() {
    let dts = [0.02, 0.01, 0.005, 0.0025];
    let errs = central_errors(1.0, 0.5, &dts);
    let p = slope(&dts, &errs);
    eprintln!("central harmonic errors from q0 = 1: {errs:?} order {p}");
    assert!((p - 1.0).abs() < 0.3, "order {p}");
}

/// The central-difference amplitude of the one-mode Duffing oscillator (the published
/// table's setting) converges at second order: the error drops ~4x when dt halves.
#[test]
fn central_difference_amplitude_error_drops_fourfold() {
    let sys = Duffing { a1: 0.36910, a2: 2.5, a3: 40.0 };
    let v0 = 1.0;
    let exact = sys.amplitude(sys.energy(0.0, v0));
    let amplitude_error = |dt: f64| {
        let sol =
            central_difference(&sys, 0.0, &[0.0], &[v0], 2.0, &Output::EveryStep, &FixedOptions::new(dt)).unwrap();
        let q: Vec<f64> = (0..sol.len()).map(|k| sol.state(k)[0]).collect();
        // First local maximum, refined by the vertex of the parabola through its neighbours.
        let n = (1..q.len() - 1).find(|&n| q[n] >= q[n - 1] && q[n] >= q[n + 1]).unwrap();
        let (qm, q0, qp) = (q[n - 1], q[n], q[n + 1]);
        let peak = q0 + (qp - qm) * (qp - qm) / (8.0 * (2.0 * q0 - qp - qm));
        (peak - exact).abs()
    };
    let errs: Vec<f64> = [0.02, 0.01, 0.005].iter().map(|&dt| amplitude_error(dt)).collect();
    eprintln!("amplitude {exact}, errors {errs:?}");
    for w in errs.windows(2) {
        let ratio = w[0] / w[1];
        assert!((3.3..4.7).contains(&ratio), "ratio {ratio}, errors {errs:?}");
    }
}

// ---------------------------------------------------------------- adaptive behaviour

#[test]
fn dop853_dense_output_is_accurate() {
    let sys = Harmonic { w: 1.0 };
    let times = linspace(0.0, 20.0, 2001);
    let opts = adaptive_opts(1e-10, 1e-12);
    let sol = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 20.0, &Output::Times(times.clone()), &opts).unwrap();
    assert_eq!(sol.status, Status::Success);
    assert_eq!(sol.t, times);
    let amplitude = (1.0f64 + 0.25).sqrt();
    let err = harmonic_error(&sys, 1.0, 0.5, &sol) / amplitude;
    eprintln!("DOP853 dense relative error {err:e}, {:?}", sol.stats);
    assert!(err < 1e-8, "relative error {err}");
    // Far fewer steps than output times: the steps are not tied to the output.
    assert!(sol.stats.naccept < 200, "{:?}", sol.stats);
}

#[test]
fn dopri5_dense_output_is_accurate() {
    let sys = Harmonic { w: 1.0 };
    let times = linspace(0.0, 20.0, 2001);
    let opts = adaptive_opts(1e-9, 1e-12);
    let sol = dopri5(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 20.0, &Output::Times(times), &opts).unwrap();
    assert_eq!(sol.status, Status::Success);
    let err = harmonic_error(&sys, 1.0, 0.5, &sol);
    eprintln!("DOPRI5 dense error {err:e}, {:?}", sol.stats);
    assert!(err < 1e-7, "error {err}");
}

/// The global error shrinks roughly in proportion to rtol.
#[test]
fn error_is_proportional_to_tolerance() {
    let sys = Harmonic { w: 1.0 };
    let rtols = [1e-5, 1e-7, 1e-9, 1e-11];
    for (name, solver) in adaptive_solvers::<FirstOrder<Harmonic>>() {
        let errs: Vec<f64> = rtols
            .iter()
            .map(|&rtol| {
                let sol = solver(
                    &FirstOrder(&sys),
                    0.0,
                    &[1.0, 0.5],
                    10.0,
                    &Output::Times(vec![10.0]),
                    &adaptive_opts(rtol, rtol),
                )
                .unwrap();
                harmonic_error(&sys, 1.0, 0.5, &sol)
            })
            .collect();
        let p = slope(&rtols, &errs);
        eprintln!("{name}: errors {errs:?}, d log err / d log rtol = {p}");
        assert!(errs.windows(2).all(|w| w[1] < w[0]), "{name}: {errs:?}");
        assert!((0.6..1.4).contains(&p), "{name}: slope {p}");
    }
}

/// 10 or 10000 output times: identical steps and final state, same accuracy.
#[test]
fn steps_are_not_tied_to_output_times() {
    let sys = Harmonic { w: 1.0 };
    let opts = adaptive_opts(1e-8, 1e-10);
    for (_, solver) in adaptive_solvers::<FirstOrder<Harmonic>>() {
        let run = |n: usize| {
            let output = Output::Times(linspace(0.0, 10.0, n));
            solver(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &output, &opts).unwrap()
        };
        let (coarse, fine) = (run(10), run(10000));
        assert_eq!(coarse.stats.naccept, fine.stats.naccept);
        assert_eq!(coarse.stats.nreject, fine.stats.nreject);
        assert_eq!(coarse.state(9), fine.state(9999));
        let (e_coarse, e_fine) = (harmonic_error(&sys, 1.0, 0.5, &coarse), harmonic_error(&sys, 1.0, 0.5, &fine));
        eprintln!("errors {e_coarse:e} {e_fine:e}, {:?} {:?}", coarse.stats, fine.stats);
        assert!(e_fine < 3.0 * e_coarse.max(1e-9) && e_coarse < 3.0 * e_fine, "{e_coarse} vs {e_fine}");
    }
}

#[test]
fn dop853_conserves_duffing_energy() {
    let sys = Duffing { a1: 1.0, a2: 1.0, a3: 1.0 };
    let opts = adaptive_opts(1e-12, 1e-12);
    let sol = solve_second_order(
        &sys,
        0.0,
        &[1.0],
        &[0.0],
        10.0,
        &Output::EveryStep,
        &SolveOptions { rtol: 1e-12, atol: 1e-12, ..SolveOptions::new(Method::Dop853) },
    )
    .unwrap();
    let direct = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.0], 10.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(sol, direct);
    let e0 = sys.energy(1.0, 0.0);
    let drift =
        (0..sol.len()).map(|k| (sys.energy(sol.state(k)[0], sol.state(k)[1]) - e0).abs() / e0).fold(0.0, f64::max);
    eprintln!("DOP853 Duffing relative energy drift {drift:e} over {} steps", sol.stats.naccept);
    assert!(drift < 1e-10, "drift {drift}");
    assert_eq!(*sol.t.last().unwrap(), 10.0);
}

#[test]
fn adaptive_evaluation_counts() {
    let sys = Harmonic { w: 1.0 };
    let opts = adaptive_opts(1e-8, 1e-10);
    let sol = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &Output::EveryStep, &opts).unwrap();
    let s = sol.stats;
    assert_eq!(sol.len() as u64, s.naccept + 1);
    assert_eq!(s.nfev, 2 + 12 * s.naccept + 11 * s.nreject);
    let sol = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &Output::Times(linspace(0.0, 10.0, 7)), &opts).unwrap();
    let extra = sol.stats.nfev - (2 + 12 * sol.stats.naccept + 11 * sol.stats.nreject);
    assert!(extra > 0 && extra % 3 == 0 && extra <= 3 * 5, "extra {extra}");
    let sol = dopri5(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &Output::EveryStep, &opts).unwrap();
    let s = sol.stats;
    assert_eq!(s.nfev, 2 + 6 * (s.naccept + s.nreject));
    // first_step replaces hinit's evaluation.
    let opts = AdaptiveOptions { first_step: Some(1e-3), ..opts };
    let sol = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &Output::EveryStep, &opts).unwrap();
    let s = sol.stats;
    assert_eq!(s.nfev, 1 + 12 * s.naccept + 11 * s.nreject);
    assert_eq!(sol.t[1], 1e-3);
}

#[test]
fn max_step_bounds_the_steps() {
    let sys = Harmonic { w: 1.0 };
    let opts = AdaptiveOptions { max_step: 0.1, ..adaptive_opts(1e-6, 1e-6) };
    let sol = dop853(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &Output::EveryStep, &opts).unwrap();
    assert!(sol.t.windows(2).all(|w| w[1] - w[0] <= 0.1 + 1e-15));
    assert!(sol.stats.naccept >= 100);
}

// ---------------------------------------------------------------- fixed-step output

#[test]
fn fixed_step_output_hits_step_points_exactly() {
    let sys = Harmonic { w: 3.0 };
    let opts = FixedOptions::new(0.01);
    let every = rk4(&FirstOrder(&sys), 0.0, &[1.0, 0.0], 1.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(every.len(), 101);
    assert_eq!(every.stats.nfev, 400);
    let times: Vec<f64> = (0..=200).map(|i| if i == 200 { 1.0 } else { i as f64 * 0.005 }).collect();
    let sampled = rk4(&FirstOrder(&sys), 0.0, &[1.0, 0.0], 1.0, &Output::Times(times), &opts).unwrap();
    for k in 0..=100 {
        // t = 0.01 k is the grid point t0 + k dt_eff.
        assert_eq!(every.t[k], sampled.t[2 * k]);
        assert_eq!(every.state(k), sampled.state(2 * k), "k = {k}");
    }
    assert_eq!(sampled.stats.naccept, 100);
    assert_eq!(sampled.stats.nfev, 400 + 1, "k1 reused, one extra f at t_end");
    let err = harmonic_error(&sys, 1.0, 0.0, &sampled);
    assert!(err < 1e-6, "{err}");

    let every = central_difference(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(every.len(), 101);
    assert_eq!(every.stats.nfev, 101);
    assert_eq!(every.state(0), [0.0, 1.0]);
    let times: Vec<f64> = (0..=200).map(|i| if i == 200 { 1.0 } else { i as f64 * 0.005 }).collect();
    let sampled = central_difference(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::Times(times), &opts).unwrap();
    for k in 0..=100 {
        assert_eq!(every.state(k), sampled.state(2 * k), "k = {k}");
    }
    // Interpolated midpoints are as accurate as the second-order grid values.
    let (e_every, e_sampled) = (harmonic_error(&sys, 0.0, 1.0, &every), harmonic_error(&sys, 0.0, 1.0, &sampled));
    assert!(e_sampled < 1.5 * e_every && e_every < 1e-3, "{e_every} {e_sampled}");
}

#[test]
fn central_difference_uses_the_published_start() {
    let sys = Harmonic { w: 2.0 };
    let dt = 0.1;
    let sol = central_difference(&sys, 0.0, &[1.0], &[0.5], 0.3, &Output::EveryStep, &FixedOptions::new(dt)).unwrap();
    let q1 = 1.0 + dt * 0.5;
    let q2 = 2.0 * q1 - 1.0 + dt * dt * (-4.0 * q1);
    assert_eq!(sol.state(1)[0], q1);
    assert_eq!(sol.state(2)[0], q2);
    assert_eq!(sol.state(1)[1], (q2 - 1.0) / (2.0 * dt));
    assert_eq!(sol.state(0), [1.0, 0.5]);
}

#[test]
fn fixed_step_shrinks_dt_to_divide_the_span() {
    let sys = Harmonic { w: 1.0 };
    let sol = rk4(&FirstOrder(&sys), 0.0, &[1.0, 0.0], 1.0, &Output::EveryStep, &FixedOptions::new(0.3)).unwrap();
    assert_eq!(sol.t, [0.0, 0.25, 0.5, 0.75, 1.0]);
}

// ---------------------------------------------------------------- status paths

#[test]
fn blow_up_ends_in_underflow_or_non_finite() {
    let output = Output::Times(linspace(0.0, 2.0, 21));
    for (_, solver) in adaptive_solvers::<BlowUp>() {
        let sol = solver(&BlowUp, 0.0, &[1.0], 2.0, &output, &AdaptiveOptions::default()).unwrap();
        eprintln!("{}: {} {:?}", sol.status, sol.message, sol.stats);
        assert!(matches!(sol.status, Status::StepSizeUnderflow | Status::NonFinite), "{}", sol.status);
        assert!(sol.message.contains("t = "), "{}", sol.message);
        // The solution cannot pass the singularity at t = 1.
        assert!((10..=11).contains(&sol.len()) && *sol.t.last().unwrap() <= 1.0, "{:?}", sol.t);
    }
    let sol = rk4(&BlowUp, 0.0, &[1.0], 2.0, &output, &FixedOptions::new(0.01)).unwrap();
    assert_eq!(sol.status, Status::NonFinite);
    assert!(sol.message.contains("t = "), "{}", sol.message);
    assert!(sol.len() < 21);
}

#[test]
fn max_steps_reached_keeps_partial_samples() {
    let sys = Harmonic { w: 1.0 };
    let output = Output::Times(linspace(0.0, 10.0, 101));
    let opts = AdaptiveOptions { max_steps: 5, ..adaptive_opts(1e-10, 1e-10) };
    for (_, solver) in adaptive_solvers::<FirstOrder<Harmonic>>() {
        let sol = solver(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &output, &opts).unwrap();
        assert_eq!(sol.status, Status::MaxStepsReached);
        assert_eq!(sol.stats.naccept + sol.stats.nreject, 5);
        assert!(sol.message.contains("max_steps = 5"), "{}", sol.message);
        assert!(sol.message.contains("t = "), "{}", sol.message);
        assert!(!sol.is_empty() && sol.len() < 101);
        assert!(harmonic_error(&sys, 1.0, 0.5, &sol) < 1e-8);
    }
    let fixed = FixedOptions { dt: 0.01, max_steps: 5 };
    let sol = rk4(&FirstOrder(&sys), 0.0, &[1.0, 0.5], 10.0, &output, &fixed).unwrap();
    assert_eq!(sol.status, Status::MaxStepsReached);
    assert_eq!(sol.stats.naccept, 5);
    assert_eq!(sol.len(), 1);
    let sol = central_difference(&sys, 0.0, &[1.0], &[0.5], 10.0, &Output::EveryStep, &fixed).unwrap();
    assert_eq!(sol.status, Status::MaxStepsReached);
    assert_eq!(sol.len(), 6);
    assert!(sol.message.contains("max_steps = 5"), "{}", sol.message);
}

#[test]
fn central_difference_divergence_is_non_finite() {
    // q'' = +q^3 (a3 < 0) escapes to infinity in finite time.
    let sys = Duffing { a1: 1.0, a2: 0.0, a3: -1.0 };
    let sol =
        central_difference(&sys, 0.0, &[1.0], &[1.0], 10.0, &Output::EveryStep, &FixedOptions::new(0.01)).unwrap();
    assert_eq!(sol.status, Status::NonFinite, "{}", sol.message);
}

/// Extreme but valid numbers end with a status, never a panic or a hang.
#[test]
fn extreme_inputs_do_not_panic() {
    let duffing = Duffing { a1: 1.0, a2: 1.0, a3: 1.0 };
    let huge = AdaptiveOptions { max_steps: 2000, ..AdaptiveOptions::default() };
    let cases: [(f64, f64, f64, AdaptiveOptions); 5] = [
        (0.0, 1e200, 1.0, huge),
        (0.0, 1e-300, 1.0, huge),
        (-1e308, 1e308, 1e300, huge),
        (0.0, 1.0, 1e300, AdaptiveOptions { rtol: 1e-300, atol: 1e-300, ..huge }),
        (
            0.0,
            1.0,
            1.0,
            AdaptiveOptions { rtol: 1e300, atol: 1e300, first_step: Some(1e-300), max_step: 1e-300, ..huge },
        ),
    ];
    for (t0, t_end, q0, opts) in cases {
        for method in Method::ALL {
            let solve =
                SolveOptions { dt: Some(opts.max_step.min(0.1)), max_steps: Some(2000), ..SolveOptions::new(method) };
            let solve = SolveOptions { rtol: opts.rtol, atol: opts.atol, first_step: opts.first_step, ..solve };
            let sol =
                solve_second_order(&duffing, t0, &[q0], &[0.0], t_end, &Output::Times(vec![t_end]), &solve).unwrap();
            assert!(sol.len() <= 1);
            assert_eq!(sol.status == Status::Success, sol.len() == 1, "{method:?}: {}", sol.message);
        }
    }
    let sol = dop853(&BlowUp, 0.0, &[1e300], 1.0, &Output::EveryStep, &AdaptiveOptions::default()).unwrap();
    assert_ne!(sol.status, Status::Success);
}

// ---------------------------------------------------------------- validation and API

#[test]
fn invalid_inputs_name_their_field() {
    let sys = Harmonic { w: 1.0 };
    let fo = FirstOrder(&sys);
    let ok = AdaptiveOptions::default();
    let every = Output::EveryStep;
    let field = |r: Result<Solution>| r.unwrap_err().field().to_string();
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &adaptive_opts(0.0, 1e-9))), "rtol");
    assert_eq!(field(dopri5(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &adaptive_opts(-1.0, 1e-9))), "rtol");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &adaptive_opts(1e-9, f64::NAN))), "atol");
    assert_eq!(field(dop853(&fo, 0.0, &[f64::NAN, 0.0], 1.0, &every, &ok)), "y0");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, f64::INFINITY], 1.0, &every, &ok)), "y0");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0], 1.0, &every, &ok)), "y0");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 1.0, &Output::Times(vec![0.5, 0.2]), &ok)), "t_eval");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 1.0, &Output::Times(vec![1.5]), &ok)), "t_eval");
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 0.0, &every, &ok)), "t_end");
    assert_eq!(field(dop853(&fo, 1.0, &[1.0, 0.0], 0.5, &every, &ok)), "t_end");
    assert_eq!(field(dop853(&fo, f64::NAN, &[1.0, 0.0], 0.5, &every, &ok)), "t0");
    let bad_first = AdaptiveOptions { first_step: Some(-1.0), ..ok };
    assert_eq!(field(dop853(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &bad_first)), "first_step");
    let bad_max = AdaptiveOptions { max_steps: 0, ..ok };
    assert_eq!(field(dopri5(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &bad_max)), "max_steps");
    assert_eq!(field(rk4(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &FixedOptions::new(0.0))), "dt");
    assert_eq!(field(rk4(&fo, 0.0, &[1.0, 0.0], 1.0, &every, &FixedOptions::new(f64::NAN))), "dt");
    assert_eq!(field(rk4(&fo, 0.0, &[1.0, 0.0, 3.0], 1.0, &every, &FixedOptions::new(0.1))), "y0");
    let fixed = FixedOptions::new(0.1);
    assert_eq!(field(central_difference(&sys, 0.0, &[1.0, 2.0], &[0.0], 1.0, &every, &fixed)), "q0");
    assert_eq!(field(central_difference(&sys, 0.0, &[1.0], &[f64::NAN], 1.0, &every, &fixed)), "v0");
    assert_eq!(field(central_difference(&sys, 0.0, &[1.0], &[0.0], -1.0, &every, &fixed)), "t_end");

    let err = solve_second_order(&sys, 0.0, &[1.0], &[0.0], 1.0, &every, &SolveOptions::new(Method::Rk4)).unwrap_err();
    assert_eq!(err.field(), "dt");
    assert!(err.to_string().contains("required by method rk4"), "{err}");
    let err =
        solve_second_order(&sys, 0.0, &[1.0], &[0.0], 1.0, &every, &SolveOptions::new(Method::Central)).unwrap_err();
    assert!(err.to_string().contains("required by method central"), "{err}");
    let opts = SolveOptions::new(Method::Dop853);
    assert_eq!(field(solve_second_order(&sys, 0.0, &[1.0, 1.0], &[0.0], 1.0, &every, &opts)), "q0");
    assert_eq!(field(solve_second_order(&sys, 0.0, &[1.0], &[], 1.0, &every, &opts)), "v0");
}

#[test]
fn method_names_round_trip() {
    for m in Method::ALL {
        assert_eq!(Method::parse(m.name()).unwrap(), m);
    }
    assert!(Method::Dop853.is_adaptive() && Method::Dopri5.is_adaptive());
    assert!(!Method::Rk4.is_adaptive() && !Method::Central.is_adaptive());
    let err = Method::parse("euler").unwrap_err();
    assert_eq!(err.field(), "method");
    assert!(err.to_string().contains("\"dop853\", \"dopri5\", \"rkn12\", \"rk4\", \"central\""), "{err}");
    assert_eq!(SolveOptions::default().method, Method::Dop853);
}

#[test]
fn solve_second_order_dispatches_every_method() {
    let sys = Harmonic { w: 1.0 };
    let output = Output::Times(linspace(0.0, 2.0, 11));
    for method in Method::ALL {
        let opts = SolveOptions { dt: Some(1e-3), rtol: 1e-10, atol: 1e-12, ..SolveOptions::new(method) };
        let sol = solve_second_order(&sys, 0.0, &[0.0], &[0.5], 2.0, &output, &opts).unwrap();
        assert_eq!(sol.status, Status::Success);
        assert_eq!(sol.dim, 2);
        let err = harmonic_error(&sys, 0.0, 0.5, &sol);
        assert!(err < 1e-6, "{method:?}: {err}");
    }
    let direct = central_difference(&sys, 0.0, &[1.0], &[0.5], 2.0, &output, &FixedOptions::new(1e-3)).unwrap();
    let opts = SolveOptions { dt: Some(1e-3), ..SolveOptions::new(Method::Central) };
    assert_eq!(solve_second_order(&sys, 0.0, &[1.0], &[0.5], 2.0, &output, &opts).unwrap(), direct);
}

#[test]
fn adaptive_methods_solve_a_nonlinear_problem() {
    let times = linspace(0.0, 5.0, 51);
    for (name, solver) in adaptive_solvers::<Decay>() {
        let sol =
            solver(&Decay, 0.0, &[2.0], 5.0, &Output::Times(times.clone()), &adaptive_opts(1e-10, 1e-12)).unwrap();
        let err = sol.t.iter().zip(&sol.y).map(|(&t, &y)| (y - 2.0 / (1.0 + 2.0 * t)).abs()).fold(0.0, f64::max);
        eprintln!("{name} y' = -y^2: max error {err:e}, {:?}", sol.stats);
        assert!(err < 1e-9, "{name}: {err}");
    }
}
