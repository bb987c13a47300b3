//! Benchmark of the drilling-system solver: Aarsnes-Shor Well B (MD 2500 m, 1000 cells,
//! 60 s simulated, 40 rpm, PI 38e3 / 100e3, off bottom), in the form that has the same
//! continuum equations as their scheme (the collar with their `Jc` (extra factor pi), `Ac`,
//! contact radius, `Gc = 67 GPa` and density `rho Gc / Gp`, so that its wave speed is the pipe's;
//! damping rate `2 kt dt_sub`). The time per run is the time per simulated minute, with the
//! linear law and with `nonlinearity = "consistent"` (the Godunov scheme on `(omega, eps)`; its
//! grid has a few cells more, for the tangent speed at `numerics.max_shear_strain`); the ratio
//! of the two (best of 5 runs each, interleaved) is printed with the core count.
//!
//! Run with `cargo bench -p drillstring-core --bench drilling`.

use std::hint::black_box;
use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion};
use drillstring_core::drilling::config::Nonlinearity;
use drillstring_core::drilling::{solve, DrillConfig};
use drillstring_core::interrupt::Never;

/// Aarsnes & Shor (2018), MAIN.m + parameters_WellB.m, MD 2500 m.
const WELL_B: &str = r#"{
  "sections": [
    {"name": "drill pipe", "length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
     "shear_modulus": 61e9, "density": 7850.0},
    {"name": "collar (Aarsnes-Shor equivalent)", "length": 230.0,
     "outer_diameter": 0.19425788212135248, "inner_diameter": 0.09285466808235807,
     "shear_modulus": 67e9, "density": 8622.131147540984,
     "polar_moment": 4.7067114136638673e-4, "area": 0.02286618845760419}
  ],
  "well": {"md": [0, 500, 1600, 4000], "inclination_deg": [0, 0, 60, 60]},
  "friction": {"static": 0.3, "kinetic_ratio": 0.65, "stick_speed": 1.5},
  "damping_rate": 0.08333333333333334,
  "top_drive": {"inertia": 2900.0, "rpm": 40.0, "ramp_time": 1.0,
                "controller": {"type": "pi", "kp": 38e3, "ki": 100e3}, "control_interval": 0.01},
  "numerics": {"cells": 1000, "duration": 60.0, "output_interval": 0.01, "field_interval": 0.5}
}"#;

fn bench(c: &mut Criterion) {
    let cfg = DrillConfig::from_json(WELL_B).unwrap();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(run.status.is_success(), "{}", run.message);
    let m = run.metrics.unwrap();
    println!(
        "Well B, 60 s: {} cells, {} steps, motor torque {:.0}..{:.0} N m, period {:.2} s, bit rpm max {:.1}, balance error {:.1e}",
        run.stats.cells, run.stats.steps, m.motor_torque_min_nm, m.motor_torque_max_nm, m.period_s, m.bit_rpm_max, run.energy.balance_error
    );
    let consistent = DrillConfig { nonlinearity: Nonlinearity::Consistent, ..cfg.clone() };
    let mut best = [f64::INFINITY; 2];
    for _ in 0..5 {
        for (k, c) in [&cfg, &consistent].into_iter().enumerate() {
            let start = Instant::now();
            black_box(solve(c, &Never, &mut |_| {}).unwrap());
            best[k] = best[k].min(start.elapsed().as_secs_f64());
        }
    }
    println!(
        "Well B, 60 s: linear {:.3} s, consistent {:.3} s per run (best of 5): consistent / linear = {:.2} ({} cores)",
        best[0],
        best[1],
        best[1] / best[0],
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    let mut group = c.benchmark_group("drilling");
    group.sample_size(20);
    group.bench_function("well_b_1000_cells_per_simulated_minute", |b| {
        b.iter(|| solve(black_box(&cfg), &Never, &mut |_| {}).unwrap())
    });
    group.bench_function("well_b_consistent_1000_cells_per_simulated_minute", |b| {
        b.iter(|| solve(black_box(&consistent), &Never, &mut |_| {}).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
