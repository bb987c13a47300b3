//! Property-based tests (proptest):
//!
//! * every integrator on random stable linear systems `y' = A y` (and `q'' = -K q` for the
//!   second-order schemes) matches the matrix exponential `exp(A t) y0`, at the step points and
//!   through its dense output;
//! * no input of finite numbers (however huge, negative or inconsistent) makes
//!   `ModalSystem::new`, `PdeSystem::new` or a solve panic: the result is an `Err` naming a field
//!   or a `Solution` with some status whose samples are all finite.

use drillstring_core::integrators::{
    central_difference, dop853, dopri5, rk4, solve_second_order, verlet, Method, SolveOptions,
};
use drillstring_core::modal::{ModalSystem, QuarticTerm};
use drillstring_core::pde::PdeSystem;
use drillstring_core::{AdaptiveOptions, FixedOptions, OdeSystem, Output, SecondOrderSystem, Solution};
use proptest::prelude::*;

// ------------------------------------------------------------------ linear systems and exp(A t)

/// `y' = A y` with a dense `n x n` matrix (row-major).
#[derive(Debug, Clone)]
struct Linear {
    n: usize,
    a: Vec<f64>,
}

impl OdeSystem for Linear {
    fn dim(&self) -> usize {
        self.n
    }
    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        for (i, d) in dydt.iter_mut().enumerate() {
            *d = (0..self.n).map(|j| self.a[i * self.n + j] * y[j]).sum();
        }
    }
}

/// `q'' = -K q` with a dense symmetric positive definite `K`.
#[derive(Debug, Clone)]
struct Springs {
    n: usize,
    k: Vec<f64>,
}

impl SecondOrderSystem for Springs {
    fn dof(&self) -> usize {
        self.n
    }
    fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
        for (i, a) in acc.iter_mut().enumerate() {
            *a = -(0..self.n).map(|j| self.k[i * self.n + j] * q[j]).sum::<f64>();
        }
    }
}

impl Springs {
    /// The first-order matrix `[[0, I], [-K, 0]]`.
    fn first_order(&self) -> Linear {
        let (n, m) = (self.n, 2 * self.n);
        let mut a = vec![0.0; m * m];
        for i in 0..n {
            a[i * m + n + i] = 1.0;
            for j in 0..n {
                a[(n + i) * m + j] = -self.k[i * n + j];
            }
        }
        Linear { n: m, a }
    }
}

fn matmul(n: usize, x: &[f64], y: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            let xik = x[i * n + k];
            for j in 0..n {
                out[i * n + j] += xik * y[k * n + j];
            }
        }
    }
    out
}

/// `exp(A t)` by scaling and squaring with a 30-term Taylor series (exact to rounding for the
/// small, well-scaled matrices used here).
fn expm(sys: &Linear, t: f64) -> Vec<f64> {
    let n = sys.n;
    let norm = (0..n).map(|i| (0..n).map(|j| (sys.a[i * n + j] * t).abs()).sum::<f64>()).fold(0.0, f64::max);
    let squarings = if norm > 0.5 { (norm / 0.5).log2().ceil() as i32 } else { 0 };
    let scale = t / 2f64.powi(squarings);
    let b: Vec<f64> = sys.a.iter().map(|v| v * scale).collect();
    let mut result: Vec<f64> = (0..n * n).map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 }).collect();
    let mut term = result.clone();
    for k in 1..30 {
        term = matmul(n, &term, &b).into_iter().map(|v| v / f64::from(k)).collect();
        for (r, t) in result.iter_mut().zip(&term) {
            *r += t;
        }
    }
    for _ in 0..squarings {
        result = matmul(n, &result, &result);
    }
    result
}

fn exact(sys: &Linear, y0: &[f64], t: f64) -> Vec<f64> {
    let e = expm(sys, t);
    (0..sys.n).map(|i| (0..sys.n).map(|j| e[i * sys.n + j] * y0[j]).sum()).collect()
}

/// Largest error of the samples (at most ~40 of them, always the last) against `exp(A t) y0`,
/// relative to `max(|y0|, 1e-3)`.
fn max_error(sys: &Linear, y0: &[f64], sol: &Solution) -> f64 {
    let scale = y0.iter().fold(1e-3_f64, |m, v| m.max(v.abs()));
    let stride = sol.len().div_ceil(40).max(1);
    (0..sol.len())
        .filter(|k| k % stride == 0 || k + 1 == sol.len())
        .map(|k| {
            let want = exact(sys, y0, sol.t[k]);
            sol.state(k).iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale
        })
        .fold(0.0, f64::max)
}

/// A random stable `A = S - B B^T` (S skew-symmetric, B B^T positive semi-definite: every
/// eigenvalue has a non-positive real part), entries of order 1.
fn stable_matrix() -> impl Strategy<Value = Linear> {
    (2usize..=3)
        .prop_flat_map(|n| {
            (Just(n), prop::collection::vec(-1.5..1.5f64, n * n), prop::collection::vec(-1.0..1.0f64, n * n))
        })
        .prop_map(|(n, s, b)| {
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let skew = s[i * n + j] - s[j * n + i];
                    let damping: f64 = (0..n).map(|k| b[i * n + k] * b[j * n + k]).sum();
                    a[i * n + j] = skew - 0.5 * damping;
                }
            }
            Linear { n, a }
        })
}

/// A random symmetric positive definite `K = B B^T + c I`, frequencies between ~0.3 and ~3.
fn spd_matrix() -> impl Strategy<Value = Springs> {
    (1usize..=3).prop_flat_map(|n| (Just(n), prop::collection::vec(-1.0..1.0f64, n * n), 0.1..2.0f64)).prop_map(
        |(n, b, c)| {
            let mut k = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    k[i * n + j] =
                        (0..n).map(|m| b[i * n + m] * b[j * n + m]).sum::<f64>() + if i == j { c } else { 0.0 };
                }
            }
            Springs { n, k }
        },
    )
}

/// `n + 1` uniform times on `[0, t_end]`, the last exactly `t_end`.
fn uniform(t_end: f64, n: u32) -> Vec<f64> {
    (0..=n).map(|k| if k == n { t_end } else { t_end * f64::from(k) / f64::from(n) }).collect()
}

fn state(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-2.0..2.0f64, n)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn adaptive_methods_match_the_matrix_exponential(
        (sys, y0) in stable_matrix().prop_flat_map(|s| { let n = s.n; (Just(s), state(n)) }),
        t_end in 0.1..5.0f64,
    ) {
        let opts = AdaptiveOptions { rtol: 1e-10, atol: 1e-12, ..AdaptiveOptions::default() };
        let times = uniform(t_end, 7);
        for output in [Output::EveryStep, Output::Times(times)] {
            let sol = dop853(&sys, 0.0, &y0, t_end, &output, &opts).unwrap();
            prop_assert!(sol.status.is_success(), "{}", sol.message);
            let err = max_error(&sys, &y0, &sol);
            prop_assert!(err < 1e-8, "dop853 error {err:e}");
            let sol = dopri5(&sys, 0.0, &y0, t_end, &output, &opts).unwrap();
            prop_assert!(sol.status.is_success(), "{}", sol.message);
            let err = max_error(&sys, &y0, &sol);
            prop_assert!(err < 1e-7, "dopri5 error {err:e}");
        }
    }

    #[test]
    fn rk4_matches_the_matrix_exponential(
        (sys, y0) in stable_matrix().prop_flat_map(|s| { let n = s.n; (Just(s), state(n)) }),
        t_end in 0.1..3.0f64,
    ) {
        let times = uniform(t_end, 9);
        for output in [Output::EveryStep, Output::Times(times)] {
            let sol = rk4(&sys, 0.0, &y0, t_end, &output, &FixedOptions::new(2e-3)).unwrap();
            prop_assert!(sol.status.is_success(), "{}", sol.message);
            let err = max_error(&sys, &y0, &sol);
            prop_assert!(err < 1e-8, "rk4 error {err:e}");
        }
    }

    #[test]
    fn second_order_schemes_match_the_matrix_exponential(
        (sys, q0, v0) in spd_matrix().prop_flat_map(|s| { let n = s.n; (Just(s), state(n), state(n)) }),
        t_end in 0.1..3.0f64,
    ) {
        let first = sys.first_order();
        let y0 = [q0.as_slice(), v0.as_slice()].concat();
        let dt = 1e-3;
        let times = uniform(t_end, 9);
        for output in [Output::EveryStep, Output::Times(times)] {
            let sol = verlet(&sys, 0.0, &q0, &v0, t_end, &output, &FixedOptions::new(dt)).unwrap();
            prop_assert!(sol.status.is_success(), "{}", sol.message);
            let err = max_error(&first, &y0, &sol);
            prop_assert!(err < 2e-5, "verlet error {err:e}");
            // The published central-difference start q1 = q0 + dt v0 is first order.
            let sol = central_difference(&sys, 0.0, &q0, &v0, t_end, &output, &FixedOptions::new(dt)).unwrap();
            prop_assert!(sol.status.is_success(), "{}", sol.message);
            let err = max_error(&first, &y0, &sol);
            prop_assert!(err < 1e-2, "central error {err:e}");
            // Every method through the common entry point.
            for method in Method::ALL {
                let opts = SolveOptions { dt: Some(dt), rtol: 1e-10, atol: 1e-12, ..SolveOptions::new(method) };
                let sol = solve_second_order(&sys, 0.0, &q0, &v0, t_end, &output, &opts).unwrap();
                prop_assert!(sol.status.is_success(), "{}: {}", method.name(), sol.message);
                prop_assert!(max_error(&first, &y0, &sol) < 1e-2, "{}", method.name());
            }
        }
    }
}

// ------------------------------------------------------------------ no panic on finite input

/// Any finite number, weighted towards the troublesome: 0, +-1, huge, tiny, subnormal.
fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => prop::sample::select(vec![1.0, -1.0, 1e300, -1e300, 1e-300, -1e-300, f64::MAX, f64::MIN, 5e-324, 1e154]),
        1 => prop::num::f64::NORMAL,
    ]
}

fn positive_or_not() -> impl Strategy<Value = f64> {
    prop_oneof![3 => 1e-6..10.0f64, 1 => finite()]
}

fn method() -> impl Strategy<Value = Method> {
    prop::sample::select(Method::ALL.to_vec())
}

/// Random (possibly invalid) solver options with a small step budget so that every case ends fast.
fn options() -> impl Strategy<Value = SolveOptions> {
    (
        method(),
        positive_or_not(),
        positive_or_not(),
        prop::option::of(positive_or_not()),
        1u64..2000,
        prop::option::of(positive_or_not()),
        prop_oneof![Just(f64::INFINITY), positive_or_not()],
    )
        .prop_map(|(method, rtol, atol, dt, max_steps, first_step, max_step)| SolveOptions {
            method,
            rtol,
            atol,
            dt,
            max_steps: Some(max_steps),
            first_step,
            max_step,
        })
}

/// Mostly a valid span; sometimes anything finite.
fn t_end() -> impl Strategy<Value = f64> {
    prop_oneof![4 => 1e-3..10.0f64, 1 => finite()]
}

/// How the output is requested: every step, sorted fractions of the span (valid output times),
/// or any finite values.
#[derive(Debug, Clone)]
enum Request {
    EveryStep,
    Fractions(Vec<f64>),
    Raw(Vec<f64>),
}

impl Request {
    fn output(&self, t_end: f64) -> Output {
        match self {
            Request::EveryStep => Output::EveryStep,
            Request::Fractions(f) => {
                let mut f = f.clone();
                f.sort_by(f64::total_cmp);
                Output::Times(f.iter().map(|x| if *x == 1.0 { t_end } else { x * t_end }).collect())
            }
            Request::Raw(t) => Output::Times(t.clone()),
        }
    }
}

fn request() -> impl Strategy<Value = Request> {
    prop_oneof![
        2 => Just(Request::EveryStep),
        3 => prop::collection::vec(prop_oneof![0.0..=1.0f64, Just(0.0), Just(1.0)], 0..6).prop_map(Request::Fractions),
        1 => prop::collection::vec(finite(), 0..4).prop_map(Request::Raw),
    ]
}

/// Solves that ran (rather than being refused), for a look at the coverage with `--nocapture`.
static SOLVED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// The invariants of any `Solution`: consistent lengths and finite samples.
fn check_solution(sol: &Solution) -> Result<(), TestCaseError> {
    prop_assert_eq!(sol.y.len(), sol.t.len() * sol.dim);
    prop_assert!(sol.t.iter().all(|t| t.is_finite()), "non-finite time");
    prop_assert!(sol.y.iter().all(|v| v.is_finite()), "non-finite sample, status {}: {}", sol.status, sol.message);
    prop_assert_eq!(sol.status.is_success(), sol.message.is_empty());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn modal_systems_never_panic_on_finite_input(
        modes in 1usize..=4,
        mass in prop::collection::vec(prop_oneof![6 => 1e-6..10.0f64, 1 => finite()], 4),
        stiffness in prop::collection::vec(finite(), 4),
        terms in prop::collection::vec((prop::array::uniform4(0u32..4), finite()), 0..6),
        q0 in prop::collection::vec(finite(), 4),
        v0 in prop::collection::vec(finite(), 4),
        inconsistent in prop::bool::weighted(0.05),
        t_end in t_end(),
        request in request(),
        opts in options(),
    ) {
        let output = request.output(t_end);
        // Consistent lengths and indices (so that solves run), now and then not.
        let (n, m) = (modes, if inconsistent { modes - 1 } else { modes });
        let terms: Vec<QuarticTerm> = terms
            .into_iter()
            .map(|(idx, coef)| QuarticTerm { idx: if inconsistent { idx } else { idx.map(|i| i % n as u32) }, coef })
            .collect();
        let Ok(sys) = ModalSystem::new(mass[..n].to_vec(), stiffness[..m].to_vec(), terms) else { return Ok(()) };
        if let Ok(sol) = solve_second_order(&sys, 0.0, &q0[..m], &v0[..n], t_end, &output, &opts) {
            check_solution(&sol)?;
            let solved = SOLVED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            if solved % 1000 == 0 {
                eprintln!("solved {solved}: {}", sol.status);
            }
        }
    }

    #[test]
    fn pde_systems_never_panic_on_finite_input(
        k in prop::array::uniform6(finite()),
        length in positive_or_not(),
        nodes in 0usize..12,
        fill in finite(),
        t_end in t_end(),
        request in request(),
        opts in options(),
    ) {
        let output = request.output(t_end);
        let Ok(sys) = PdeSystem::new(k, length, nodes) else { return Ok(()) };
        let q0 = vec![fill; sys.nodes()];
        let v0 = sys.initial_velocity_from_modes(&[fill, 1.0]);
        let _ = sys.energy(&q0, &v0);
        let _ = sys.linear_frequencies_squared(sys.nodes().min(3));
        if let Ok(sol) = solve_second_order(&sys, 0.0, &q0, &v0, t_end, &output, &opts) {
            check_solution(&sol)?;
        }
    }
}
