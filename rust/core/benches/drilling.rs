//! Benchmark of the drilling-system solver: Aarsnes-Shor Well B (MD 2500 m, 1000 cells,
//! 60 s simulated, 40 rpm, PI 38e3 / 100e3).
//!
//! Run with `cargo bench -p drillstring-core --bench drilling`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use drillstring_core::drilling::{solve, DrillConfig};
use drillstring_core::interrupt::Never;

fn bench(c: &mut Criterion) {
    let cfg = DrillConfig::default();
    let mut group = c.benchmark_group("drilling");
    group.sample_size(10);
    group.bench_function("well_b_60s_1000_cells", |b| b.iter(|| solve(black_box(&cfg), &Never, &mut |_| {}).unwrap()));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
