//! Benchmarks of the integrators on a realistic 3-mode modal system (the aluminium
//! reference drill string, modes 1, 2, 3).
//!
//! Run with `cargo bench -p drillstring-core --bench integrators`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use drillstring_core::integrators::{central_difference, dop853, dopri5, rk4, rkn12};
use drillstring_core::modal::{ModalSystem, QuarticTerm};
use drillstring_core::{AdaptiveOptions, FirstOrder, FixedOptions, OdeSystem, Output};

/// `M q'' + K q + grad V(q) = 0` with `M_ii ~ k1 l / 2`, `K_ii ~ i^2 K_11` and quartic
/// couplings of magnitude `1e10`.
fn three_modes() -> ModalSystem {
    let term = |idx: [u32; 4], coef: f64| QuarticTerm { idx, coef };
    ModalSystem::new(
        vec![18.455, 18.455, 18.455],
        vec![704_600.0, 2_818_400.0, 6_341_400.0],
        vec![
            term([0, 0, 0, 0], 1.2e10),
            term([1, 1, 1, 1], 1.5e10),
            term([2, 2, 2, 2], 1.8e10),
            term([0, 0, 1, 1], 3.1e10),
            term([0, 0, 0, 2], 2.4e10),
            term([0, 1, 1, 2], 2.9e10),
        ],
    )
    .expect("valid modal system")
}

const Q0: [f64; 3] = [0.0; 3];
const V0: [f64; 3] = [0.1, 0.05, 0.02];

fn output() -> Output {
    Output::Times((0..=1000).map(|i| i as f64 / 1000.0).collect())
}

fn bench(c: &mut Criterion) {
    let sys = three_modes();
    let fo = FirstOrder(&sys);
    let y0: Vec<f64> = [Q0, V0].concat();
    let out = output();

    c.bench_function("rhs/3-mode", |b| {
        let y = [1e-4, -2e-4, 5e-5, 0.1, 0.05, 0.02];
        let mut dydt = [0.0; 6];
        b.iter(|| {
            fo.rhs(0.0, black_box(&y), &mut dydt);
            black_box(dydt)
        })
    });

    let opts = AdaptiveOptions { rtol: 1e-12, atol: 1e-12, ..AdaptiveOptions::default() };
    assert!(dop853(&fo, 0.0, &y0, 1.0, &out, &opts).expect("valid input").status.is_success());
    c.bench_function("dop853/3-mode t=1 rtol=1e-12", |b| {
        b.iter(|| dop853(&fo, 0.0, black_box(&y0), 1.0, &out, &opts).expect("valid input"))
    });

    // The same case by RKN12(10): the Runge-Kutta-Nystrom pair on q'' = a(q), same output.
    assert!(rkn12(&sys, 0.0, &Q0, &V0, 1.0, &out, &opts).expect("valid input").status.is_success());
    c.bench_function("rkn12/3-mode t=1 rtol=1e-12", |b| {
        b.iter(|| rkn12(&sys, 0.0, black_box(&Q0), &V0, 1.0, &out, &opts).expect("valid input"))
    });
    let fine: Output = Output::Times((0..=20_000).map(|i| i as f64 / 20_000.0).collect());
    let tight = AdaptiveOptions { rtol: 1e-12, atol: 1e-17, ..AdaptiveOptions::default() };
    c.bench_function("dop853/3-mode t=1 rtol=1e-12 atol=1e-17 20001 samples", |b| {
        b.iter(|| dop853(&fo, 0.0, black_box(&y0), 1.0, &fine, &tight).expect("valid input"))
    });
    c.bench_function("rkn12/3-mode t=1 rtol=1e-12 atol=1e-17 20001 samples", |b| {
        b.iter(|| rkn12(&sys, 0.0, black_box(&Q0), &V0, 1.0, &fine, &tight).expect("valid input"))
    });

    let opts = AdaptiveOptions { rtol: 1e-10, atol: 1e-12, ..AdaptiveOptions::default() };
    c.bench_function("dopri5/3-mode t=1 rtol=1e-10", |b| {
        b.iter(|| dopri5(&fo, 0.0, black_box(&y0), 1.0, &out, &opts).expect("valid input"))
    });

    let opts = FixedOptions::new(1e-4);
    c.bench_function("rk4/3-mode t=1 dt=1e-4", |b| {
        b.iter(|| rk4(&fo, 0.0, black_box(&y0), 1.0, &out, &opts).expect("valid input"))
    });

    c.bench_function("central/3-mode t=1 dt=1e-4", |b| {
        b.iter(|| central_difference(&sys, 0.0, black_box(&Q0), &V0, 1.0, &out, &opts).expect("valid input"))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
