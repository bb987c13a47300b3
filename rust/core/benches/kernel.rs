//! Benchmark of the drilling engine's torsional transport kernel alone
//! (`drilling::engine::kernel::transport`): 1000 cells, Courant number 0.998 (the upwind form,
//! as in Well B), damping and set-valued wall friction with a third of the cells slow, with the
//! energy sums (`transport`) and without (`transport_unbooked`). Prints ns per cell update,
//! the SIMD path (`DRILLSTRING_SIMD=avx2` or `baseline` pins one) and the core count.
//!
//! Run with `cargo bench -p drillstring-core --bench kernel`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use drillstring_core::drilling::config::FrictionModel;
use drillstring_core::drilling::engine::kernel::{transport, transport_unbooked, Wall};
use drillstring_core::drilling::engine::sources::Sources;

const CELLS: usize = 1000;

fn bench(c: &mut Criterion) {
    let len = CELLS + 2;
    let a: Vec<f64> = (0..len).map(|i| (i as f64 * 0.37).sin() * 3.0).collect();
    let b: Vec<f64> = (0..len).map(|i| (i as f64 * 0.11).cos() * 3.0).collect();
    let stop: Vec<f64> = (0..len).map(|i| if i == 0 || i == len - 1 { 0.0 } else { 0.02 }).collect();
    let slip: Vec<f64> = stop.iter().map(|&s| -(0.65 * s)).collect();
    let (mut an, mut bn) = (vec![0.0; len], vec![0.0; len]);
    let src = Sources {
        damping: 1e-4,
        stick_speed: 1.5,
        kinetic_ratio: 0.65,
        model: FrictionModel::SetValued,
        regularisation_speed: 0.0,
    };
    println!(
        "transport kernel, {CELLS} cells, path {}, {} cores",
        drillstring_core::simd::path(),
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    let mut group = c.benchmark_group("transport_kernel");
    group.throughput(Throughput::Elements(CELLS as u64));
    group.bench_function("ledger_on_1000_cells", |bench| {
        bench.iter(|| {
            transport(black_box(&a), &b, Wall::Cells { stop: &stop, slip: &slip }, &mut an, &mut bn, 0.998, &src)
        })
    });
    group.bench_function("ledger_off_1000_cells", |bench| {
        bench.iter(|| {
            transport_unbooked(
                black_box(&a),
                &b,
                Wall::Cells { stop: &stop, slip: &slip },
                &mut an,
                &mut bn,
                0.998,
                &src,
            )
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
