//! Benchmark of the batch solve: 200 three-mode runs of the aluminium reference string
//! (Table 1, C = (0.1, 0.05, 0.02)) over a length x speed grid, 0 <= t <= 1, rtol 1e-8,
//! 1024 samples per run, on one thread and on rayon's global pool.
//!
//! Run with `cargo bench -p drillstring-core --bench sweep`.

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use drillstring_core::integrators::solve_second_order;
use drillstring_core::integrators::{Method, SolveOptions};
use drillstring_core::metrics::{self, FrequencyEstimator};
use drillstring_core::sweep::{batch_solve, GalerkinIntegrals, RunSpec, SweepOptions};
use drillstring_core::Output;

/// `drillstring.galerkin.dimensionless_integrals(3)`.
fn three_modes() -> GalerkinIntegrals {
    GalerkinIntegrals::new(
        vec![1, 2, 3],
        vec![
            [0, 0, 0, 0],
            [0, 0, 0, 2],
            [0, 0, 1, 1],
            [0, 0, 2, 2],
            [0, 1, 1, 2],
            [1, 1, 1, 1],
            [1, 1, 2, 2],
            [2, 2, 2, 2],
        ],
        vec![0.375, 0.5, 1.5, 1.5, 1.5, 0.375, 1.5, 0.375],
        vec![0.125, 0.5, 1.25, 2.5, 2.25, 0.5, 3.25, 1.125],
        vec![0.375, -1.5, 6.0, 13.5, 18.0, 6.0, 54.0, 30.375],
    )
    .expect("valid integrals")
}

/// k1..k6 of the aluminium reference at Omega = 0 (k6 is set per run).
const K: [f64; 6] = [
    0.369_149_703_167_415_13,
    14_284_399.790_889_474,
    3_282_260_981.362_472,
    8_258_168.629_107_977,
    3_870.660_966_621_384_4,
    0.0,
];

fn runs(count: usize) -> Vec<RunSpec> {
    let side = (count as f64).sqrt().ceil() as usize;
    (0..count)
        .map(|r| {
            let length = 100.0 + 200.0 * (r / side) as f64 / side as f64;
            let omega = 2.0 * PI * 2.0 * (r % side) as f64 / side as f64;
            let mut k = K;
            k[5] = K[0] * omega * omega;
            RunSpec { k, length, initial_velocities: vec![0.1, 0.05, 0.02], z: 2.0 * length / 3.0, damping_rate: 0.0 }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let integrals = three_modes();
    let specs = runs(200);
    let opts = SweepOptions {
        solve: SolveOptions { rtol: 1e-8, atol: 1e-12, ..SolveOptions::new(Method::Dop853) },
        t_end: 1.0,
        samples: 1024,
        keep_trajectories: false,
        memory_budget: None,
    };
    let check = batch_solve(&integrals, &specs, &opts, None).expect("valid options");
    assert!(check.iter().all(|r| r.status.is_success()));
    // the parts of one run (l = 100 m, Omega = 0): set-up, integration, metrics
    let spec = &specs[0];
    c.bench_function("sweep/per-run set-up (scale integrals)", |b| {
        b.iter(|| integrals.scale(black_box(&spec.k), spec.length).expect("valid run"))
    });
    let sys = integrals.scale(&spec.k, spec.length).expect("valid run");
    let output = Output::Times(opts.times());
    let q0 = [0.0; 3];
    c.bench_function("sweep/integration, 1024 samples", |b| {
        b.iter(|| {
            solve_second_order(&sys, 0.0, &q0, black_box(&spec.initial_velocities), 1.0, &output, &opts.solve)
                .expect("valid run")
        })
    });
    let sol = solve_second_order(&sys, 0.0, &q0, &spec.initial_velocities, 1.0, &output, &opts.solve).expect("valid");
    let basis = integrals.basis(spec.z, spec.length);
    let theta = metrics::section_twist(&sol.y, &basis);
    let estimator = FrequencyEstimator::new(opts.samples);
    let mut buf = estimator.buffers();
    let dt = 1.0 / (opts.samples - 1) as f64;
    c.bench_function("sweep/dominant frequency (FFT), 1024 samples", |b| {
        b.iter(|| estimator.dominant_frequency(black_box(&theta), dt, &mut buf))
    });
    c.bench_function("sweep/all metrics, 1024 samples", |b| {
        b.iter(|| {
            let theta = metrics::section_twist(black_box(&sol.y), &basis);
            metrics::compute(&sys, &sol.y, &sol.dissipated, &theta, dt, &estimator, &mut buf)
        })
    });

    let mut group = c.benchmark_group("sweep");
    group.sample_size(10);
    group.bench_function("batch 200 x 3-mode t=1 rtol=1e-8, 1 thread", |b| {
        b.iter(|| batch_solve(&integrals, black_box(&specs), &opts, Some(1)).expect("valid options"))
    });
    group.bench_function("batch 200 x 3-mode t=1 rtol=1e-8, all cores", |b| {
        b.iter(|| batch_solve(&integrals, black_box(&specs), &opts, None).expect("valid options"))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
