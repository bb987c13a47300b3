//! Batch-level tests: order, fault isolation, thread-count independence, known frequencies.

use super::*;
use crate::integrators::{Method, SolveOptions};
use crate::solution::Status;
use crate::sweep::batch::{batch_solve_with, resolve_threads, MAX_THREADS};
use std::time::Duration;

/// One mode `i = 1`: `cos4 = 3/8`, `mixed = 1/8`, `sin4 = 3/8` (galerkin.dimensionless_integrals(1)).
fn one_mode() -> GalerkinIntegrals {
    GalerkinIntegrals::new(vec![1], vec![[0; 4]], vec![0.375], vec![0.125], vec![0.375]).unwrap()
}

/// k of the aluminium reference (Table 1, "paper" k5) at Omega = pi rad/s.
const K_REF: [f64; 6] = [
    0.369_149_703_167_415_13,
    14_284_399.790_889_474,
    3_282_260_981.362_472,
    8_258_168.629_107_977,
    3_870.660_966_621_384_4,
    3.643_361_535_041_950_4,
];

fn options(rtol: f64) -> SweepOptions {
    SweepOptions {
        solve: SolveOptions { rtol, atol: 1e-12, ..SolveOptions::new(Method::Dop853) },
        t_end: 1.0,
        samples: 1024,
        keep_trajectories: false,
        memory_budget: None,
    }
}

fn spec(length: f64, c: f64) -> RunSpec {
    RunSpec { k: K_REF, length, initial_velocities: vec![c], z: 2.0 * length / 3.0, damping_rate: 0.0 }
}

#[test]
fn duffing_frequency_one_mode() {
    // a1 x'' + a2 x + a3 x^3 = 0, x(0) = 0, x'(0) = C: exact period 4 K(m) / sqrt(w2 + beta A^2)
    let g = one_mode();
    let l = 100.0;
    let [k1, k2, k3, k4, k5, k6] = K_REF;
    let pi = std::f64::consts::PI;
    let w2 = (k2 * pi * pi / (l * l) - k6) / k1;
    let beta = (0.75 * k3 + k4 * pi * pi / (2.0 * l * l) + 0.75 * k5 * pi.powi(4) / l.powi(4)) / k1;
    let c = 0.1;
    let amp = (2.0 * c * c / (w2 + (w2 * w2 + 2.0 * beta * c * c).sqrt())).sqrt();
    let stiff = w2 + beta * amp * amp;
    let m = beta * amp * amp / (2.0 * stiff);
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    let kk = pi / (2.0 * a);
    let exact = stiff.sqrt() / (4.0 * kk);
    let rec = &batch_solve(&g, &[spec(l, c)], &options(1e-10), Some(1)).unwrap()[0];
    assert!(rec.status.is_success(), "{}", rec.message);
    assert!((rec.dominant_frequency_hz - exact).abs() < 5e-3 * exact, "{} vs {exact}", rec.dominant_frequency_hz);
    assert!((rec.max_theta - amp * (2.0 * pi / 3.0).cos().abs()).abs() < 1e-6 * amp);
    assert_eq!(rec.unstable_modes, Some(0));
    assert!(rec.energy_drift < 1e-7);
    assert!((rec.max_share[0] - 1.0).abs() < 1e-12);
}

#[test]
fn unstable_count_flips_at_the_critical_speed() {
    let g = one_mode();
    let l = 100.0;
    let [k1, k2, ..] = K_REF;
    let crit = std::f64::consts::PI / l * (k2 / k1).sqrt();
    let runs: Vec<RunSpec> = [0.99, 1.01]
        .iter()
        .map(|f| {
            let mut s = spec(l, 0.1);
            s.k[5] = k1 * (f * crit) * (f * crit);
            s
        })
        .collect();
    let mut opts = options(1e-8);
    opts.t_end = 0.05;
    let recs = batch_solve(&g, &runs, &opts, None).unwrap();
    assert_eq!(recs[0].unstable_modes, Some(0));
    assert_eq!(recs[1].unstable_modes, Some(1));
}

#[test]
fn faults_are_isolated_and_order_is_kept() {
    let g = one_mode();
    let mut bad_k = spec(100.0, 0.1);
    bad_k.k[0] = -1.0;
    let mut bad_z = spec(100.0, 0.1);
    bad_z.z = 150.0;
    let mut bad_len = spec(100.0, 0.1);
    bad_len.initial_velocities = vec![0.1, 0.2];
    let good: Vec<RunSpec> = [100.0, 150.0, 200.0].iter().map(|&l| spec(l, 0.1)).collect();
    let runs = vec![good[0].clone(), bad_k, good[1].clone(), bad_z, bad_len, good[2].clone()];
    let opts = options(1e-8);
    let recs = batch_solve(&g, &runs, &opts, Some(2)).unwrap();
    let alone = batch_solve(&g, &good, &opts, Some(1)).unwrap();
    let names: Vec<&str> = recs.iter().map(|r| r.status.name()).collect();
    assert_eq!(names, ["success", "invalid", "success", "invalid", "invalid", "success"]);
    assert!(recs[1].message.contains("k1"), "{}", recs[1].message);
    assert!(recs[3].message.contains("invalid z"), "{}", recs[3].message);
    assert!(recs[4].message.contains("initial_velocities"), "{}", recs[4].message);
    assert_eq!(recs[1].unstable_modes, None);
    assert_eq!([&recs[0], &recs[2], &recs[5]], [&alone[0], &alone[1], &alone[2]]);
}

#[test]
fn step_limit_is_a_record() {
    let g = one_mode();
    let mut opts = options(1e-8);
    opts.solve.max_steps = Some(10);
    let recs = batch_solve(&g, &[spec(100.0, 0.1)], &opts, None).unwrap();
    assert_eq!(recs[0].status, RunStatus::Solved(Status::MaxStepsReached));
    assert!(!recs[0].message.is_empty());
    assert!(recs[0].max_theta.is_nan() && recs[0].nfev > 0);
}

#[test]
fn trajectories_only_when_asked() {
    let g = one_mode();
    let mut opts = options(1e-8);
    let recs = batch_solve(&g, &[spec(100.0, 0.1)], &opts, None).unwrap();
    assert!(recs[0].trajectory.is_none());
    opts.keep_trajectories = true;
    let recs = batch_solve(&g, &[spec(100.0, 0.1)], &opts, None).unwrap();
    let traj = recs[0].trajectory.as_ref().unwrap();
    assert_eq!(traj.theta.len(), 1024);
    assert_eq!(traj.y.len(), 2048);
    let max = traj.theta.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert_eq!(max, recs[0].max_theta);
}

#[test]
fn fixed_step_methods_get_a_default_dt() {
    let g = one_mode();
    let mut opts = options(1e-8);
    opts.solve.method = Method::Rk4;
    opts.t_end = 0.1;
    let rec = &batch_solve(&g, &[spec(100.0, 0.1)], &opts, None).unwrap()[0];
    assert!(rec.status.is_success(), "{}", rec.message);
    // w_1 ~ 195 rad/s: the default step is 1e-4 s, as a direct solve with that step
    let sys = g.scale(&K_REF, 100.0).unwrap();
    let solve = SolveOptions { dt: Some(1e-4), ..opts.solve };
    let direct = crate::integrators::solve_second_order(
        &sys,
        0.0,
        &[0.0],
        &[0.1],
        0.1,
        &crate::Output::Times(opts.times()),
        &solve,
    )
    .unwrap();
    assert_eq!(rec.nfev, direct.stats.nfev);
}

#[test]
fn shared_input_errors() {
    let g = one_mode();
    let mut opts = options(1e-8);
    assert_eq!(batch_solve(&g, &[], &opts, Some(0)).unwrap_err().field(), "threads");
    opts.samples = 3;
    assert_eq!(batch_solve(&g, &[], &opts, None).unwrap_err().field(), "samples");
    let mut opts = options(-1.0);
    assert_eq!(batch_solve(&g, &[], &opts, None).unwrap_err().field(), "rtol");
    opts = options(1e-8);
    opts.t_end = f64::NAN;
    assert_eq!(batch_solve(&g, &[], &opts, None).unwrap_err().field(), "t_end");
    assert!(batch_solve(&g, &[], &options(1e-8), None).unwrap().is_empty());
}

#[test]
fn thread_counts_are_bounded() {
    let g = one_mode();
    let opts = options(1e-8);
    for bad in [0, MAX_THREADS + 1, 1_000_000] {
        let err = batch_solve(&g, &[spec(100.0, 0.1)], &opts, Some(bad)).unwrap_err();
        assert_eq!(err.field(), "threads");
        assert!(err.to_string().contains(&format!("1..={MAX_THREADS}")), "{err}");
    }
    assert_eq!(resolve_threads(Some(3)).unwrap(), 3);
    assert!((1..=MAX_THREADS).contains(&resolve_threads(None).unwrap()));
}

#[test]
fn a_batch_over_the_memory_budget_is_refused_before_any_allocation() {
    // 1e9 samples: the FFT buffers alone would need tens of GiB (this aborted the process
    // before the check): an error naming samples, computed without allocating them.
    let g = one_mode();
    let mut opts = options(1e-8);
    opts.samples = 1_000_000_000;
    opts.memory_budget = Some(2 << 30);
    let err = batch_solve(&g, &[spec(100.0, 0.1)], &opts, None).unwrap_err();
    assert_eq!(err.field(), "samples");
    assert!(err.to_string().contains("memory budget of 2.000 GiB"), "{err}");
    // The estimate: 1024 samples, one mode, one run, one thread.
    opts.samples = 1024;
    let fft = 8192u64;
    let want = 16 * 1024 + 16 * fft + (8 * 1024 * 3 + 8 * 1024 + 32 * fft) + (8 + 256);
    assert_eq!(opts.memory_bytes(1, 1, 4), want);
    // Kept trajectories scale with the runs; a budget just below the need refuses.
    opts.keep_trajectories = true;
    let need = opts.memory_bytes(1, 1000, 2);
    assert_eq!(need - opts.memory_bytes(1, 999, 2), 8 + 256 + 2 * 8 * 1024 * 3);
    opts.memory_budget = Some(need - 1);
    let runs = vec![spec(100.0, 0.1); 1000];
    let err = batch_solve(&g, &runs, &opts, Some(2)).unwrap_err();
    assert!(err.to_string().contains("1000 runs with their trajectories"), "{err}");
    opts.memory_budget = Some(need);
    assert_eq!(batch_solve(&g, &runs[..10], &opts, Some(2)).unwrap().len(), 10);
    // Absurd sizes saturate instead of overflowing.
    opts.samples = usize::MAX;
    assert_eq!(opts.memory_bytes(256, usize::MAX, MAX_THREADS), u64::MAX);
}

#[test]
fn an_interrupt_stops_the_runs_under_way_and_keeps_the_finished_ones() {
    // Short runs (l = 1e5 m: 0.03 Hz, ~1e3 steps over 200 s) and long ones (l = 10 m: 311 Hz,
    // ~1e6 steps, a few hundred ms at least); the hook fires after 30 ms.
    let g = one_mode();
    let mut opts = options(1e-10);
    opts.t_end = 200.0;
    let runs: Vec<RunSpec> = [1e5, 1e5, 1e5, 10.0, 1e5, 1e5, 10.0, 1e5].iter().map(|&l| spec(l, 0.1)).collect();
    let start = std::time::Instant::now();
    let hook = || start.elapsed() > Duration::from_millis(30);
    let recs = batch_solve_with(&g, &runs, &opts, Some(2), &hook).unwrap();
    for (rec, run) in recs.iter().zip(&runs) {
        match rec.status {
            // A finished run is exactly the run solved alone.
            RunStatus::Solved(Status::Success) => {
                assert_eq!(rec, &batch_solve(&g, std::slice::from_ref(run), &opts, Some(1)).unwrap()[0])
            }
            RunStatus::Solved(Status::Interrupted) => {
                assert!(rec.message.contains("interrupted"), "{}", rec.message);
                assert!(rec.max_theta.is_nan());
            }
            other => panic!("{other:?}: {}", rec.message),
        }
    }
    for long in [3, 6] {
        assert_eq!(recs[long].status, RunStatus::Solved(Status::Interrupted), "{}", recs[long].message);
    }
    // A hook that never fires changes nothing.
    let short = &runs[..3];
    assert_eq!(
        batch_solve_with(&g, short, &opts, Some(2), &|| false).unwrap(),
        batch_solve(&g, short, &opts, Some(1)).unwrap()
    );
}
