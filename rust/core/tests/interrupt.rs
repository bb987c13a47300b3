//! Cancellation of long solves: every method stops promptly when a flag is raised from another
//! thread, keeps the samples recorded so far, and a hook that never fires changes nothing.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use drillstring_core::integrators::{solve_second_order, solve_second_order_with, Method, SolveOptions};
use drillstring_core::interrupt::Never;
use drillstring_core::modal::{ModalSystem, QuarticTerm};
use drillstring_core::pde::PdeSystem;
use drillstring_core::{CancelFlag, Output, SecondOrderSystem, Solution, Status};

/// Three coupled hardening modes (bounded motion for any time span).
fn modal() -> ModalSystem {
    ModalSystem::new(
        vec![1.0, 2.0, 1.5],
        vec![4.0, 30.0, 90.0],
        vec![
            QuarticTerm { idx: [0, 0, 0, 0], coef: 0.5 },
            QuarticTerm { idx: [0, 0, 1, 1], coef: 0.3 },
            QuarticTerm { idx: [1, 1, 2, 2], coef: 0.2 },
            QuarticTerm { idx: [2, 2, 2, 2], coef: 1.0 },
        ],
    )
    .unwrap()
}

/// Longest accepted time from raising the flag to the solve's return. The solves poll the flag
/// every few milliseconds (printed by each test); the bound is loose so that the tests also pass
/// on a loaded machine, and still fails for a solve that never polls (it would run to `t = 1e9`).
const PROMPT: Duration = Duration::from_secs(2);

fn options(method: Method) -> SolveOptions {
    let dt = if method.is_adaptive() { None } else { Some(1e-3) };
    SolveOptions { dt, ..SolveOptions::new(method) }
}

/// Solves `sys` to an end time it cannot reach soon and raises `flag` from another thread after
/// `delay`; returns the solution and the time from the raise to the solve's return.
fn cancel_after<S: SecondOrderSystem + Sync>(
    sys: &S,
    q0: &[f64],
    v0: &[f64],
    opts: &SolveOptions,
    delay: Duration,
) -> (Solution, Duration) {
    let flag = CancelFlag::new();
    let output = Output::Times((0..=10).map(f64::from).chain([1e9]).collect());
    std::thread::scope(|s| {
        let raiser = s.spawn(|| {
            std::thread::sleep(delay);
            flag.cancel();
            Instant::now()
        });
        let sol = solve_second_order_with(sys, 0.0, q0, v0, 1e9, &output, opts, &flag).unwrap();
        let returned = Instant::now();
        let raised = raiser.join().unwrap();
        (sol, returned.saturating_duration_since(raised))
    })
}

#[test]
fn a_flag_raised_from_another_thread_stops_every_method_promptly() {
    let sys = modal();
    for method in Method::ALL {
        let opts = SolveOptions { max_steps: Some(u64::MAX), ..options(method) };
        let (sol, latency) = cancel_after(&sys, &[0.0; 3], &[0.3, 0.2, 0.1], &opts, Duration::from_millis(150));
        eprintln!("{}: stopped {latency:?} after the flag, at {} samples: {}", method.name(), sol.len(), sol.message);
        assert_eq!(sol.status, Status::Interrupted, "{}: {}", method.name(), sol.message);
        assert_eq!(sol.status.code(), 4);
        assert_eq!(sol.status.name(), "interrupted");
        assert!(sol.message.starts_with("interrupted at t = "), "{}", sol.message);
        assert!(latency < PROMPT, "{}: {latency:?}", method.name());
        // The samples reached before the interrupt are kept, and they are finite.
        assert!(!sol.is_empty() && sol.len() < 12, "{}", sol.len());
        assert!(sol.y.iter().all(|v| v.is_finite()));
        assert_eq!(sol.y.len(), sol.len() * sol.dim);
    }
}

#[test]
fn a_large_pde_solve_stops_promptly_too() {
    // 2001 nodes: one step costs a thousand times a modal one (a few ms unoptimised).
    let sys = PdeSystem::new([1.0, 1.0, 0.1, 0.1, 0.1, 0.0], 1.0, 2001).unwrap();
    let v0 = sys.initial_velocity_from_modes(&[0.1, 0.05]);
    let q0 = vec![0.0; sys.nodes()];
    for method in [Method::Dop853, Method::Verlet] {
        let opts = SolveOptions { dt: Some(2e-4), ..SolveOptions::new(method) };
        let (sol, latency) = cancel_after(&sys, &q0, &v0, &opts, Duration::from_millis(200));
        eprintln!("pde {}: stopped {latency:?} after the flag: {}", method.name(), sol.message);
        assert_eq!(sol.status, Status::Interrupted, "{}", sol.message);
        assert!(latency < PROMPT, "{latency:?}");
    }
}

#[test]
fn one_flag_stops_solves_on_several_threads() {
    let sys = modal();
    let flag = CancelFlag::new();
    let output = Output::Times(vec![0.0, 1e9]);
    let opts = SolveOptions { max_steps: Some(u64::MAX), ..SolveOptions::new(Method::Dop853) };
    let statuses: Vec<Status> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..3)
            .map(|_| {
                s.spawn(|| {
                    solve_second_order_with(&sys, 0.0, &[0.0; 3], &[0.3, 0.2, 0.1], 1e9, &output, &opts, &flag)
                        .unwrap()
                        .status
                })
            })
            .collect();
        std::thread::sleep(Duration::from_millis(100));
        flag.cancel();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(statuses, vec![Status::Interrupted; 3]);
}

#[test]
fn an_already_raised_flag_stops_after_the_first_step() {
    let sys = modal();
    let flag = CancelFlag::new();
    flag.cancel();
    for method in Method::ALL {
        let sol = solve_second_order_with(
            &sys,
            0.0,
            &[0.0; 3],
            &[0.3, 0.2, 0.1],
            10.0,
            &Output::EveryStep,
            &options(method),
            &flag,
        )
        .unwrap();
        assert_eq!(sol.status, Status::Interrupted, "{}", method.name());
        assert_eq!(sol.len(), 1, "{}: only the initial sample", method.name());
        assert!(sol.stats.naccept <= 1);
    }
}

#[test]
fn hooks_that_never_fire_leave_results_bit_identical() {
    let sys = modal();
    let polls = AtomicU64::new(0);
    let counting = || {
        polls.fetch_add(1, Ordering::Relaxed);
        false
    };
    let flag = CancelFlag::new();
    for method in Method::ALL {
        for output in [Output::EveryStep, Output::Times((0..=50).map(|i| f64::from(i) * 0.2).collect())] {
            let opts = options(method);
            let plain = solve_second_order(&sys, 0.0, &[0.0; 3], &[0.3, 0.2, 0.1], 10.0, &output, &opts).unwrap();
            assert_eq!(plain.status, Status::Success);
            let never =
                solve_second_order_with(&sys, 0.0, &[0.0; 3], &[0.3, 0.2, 0.1], 10.0, &output, &opts, &Never).unwrap();
            let counted =
                solve_second_order_with(&sys, 0.0, &[0.0; 3], &[0.3, 0.2, 0.1], 10.0, &output, &opts, &counting)
                    .unwrap();
            let flagged =
                solve_second_order_with(&sys, 0.0, &[0.0; 3], &[0.3, 0.2, 0.1], 10.0, &output, &opts, &flag).unwrap();
            assert_eq!(plain, never, "{}", method.name());
            assert_eq!(plain, counted, "{}", method.name());
            assert_eq!(plain, flagged, "{}", method.name());
        }
    }
    assert!(polls.load(Ordering::Relaxed) > 0, "the hook was polled");
}

/// A hook that records the times it is asked at (the progress of the solve).
struct Recorder(std::sync::Mutex<Vec<f64>>);

impl drillstring_core::Interrupt for Recorder {
    fn interrupted(&self) -> bool {
        false
    }
    fn interrupted_at(&self, t: f64) -> bool {
        self.0.lock().unwrap().push(t);
        false
    }
}

#[test]
fn the_hook_sees_the_time_reached_by_every_method() {
    // Each method is asked with non-decreasing times inside the span, often enough to follow
    // a long solve, and the numbers are those of a solve without the hook.
    let sys = modal();
    let t_end = 200.0;
    let output = Output::Times(vec![0.0, t_end]);
    for method in Method::ALL {
        let opts = options(method);
        let hook = Recorder(std::sync::Mutex::new(Vec::new()));
        let sol =
            solve_second_order_with(&sys, 0.0, &[0.0; 3], &[0.1, 0.0, 0.0], t_end, &output, &opts, &hook).unwrap();
        let plain = solve_second_order(&sys, 0.0, &[0.0; 3], &[0.1, 0.0, 0.0], t_end, &output, &opts).unwrap();
        assert_eq!(sol, plain, "{method:?}");
        let times = hook.0.into_inner().unwrap();
        assert!(times.len() >= 2, "{method:?}: asked {} times", times.len());
        assert!(times.windows(2).all(|w| w[0] <= w[1]), "{method:?}");
        assert!(times.iter().all(|&t| (0.0..=t_end).contains(&t)), "{method:?}");
    }
}
