//! Benchmarks of the finite-difference (lumped-mass finite-element) PDE system on the
//! aluminium reference drill string (model notes, Table 1, `Omega = pi`).
//!
//! Run with `cargo bench -p drillstring-core --bench pde`.

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use drillstring_core::integrators::{solve_second_order, Method, SolveOptions};
use drillstring_core::pde::{PdeCoefficients, PdeSystem};
use drillstring_core::{Output, SecondOrderSystem};

const LENGTH: f64 = 100.0;

/// `k1 .. k6` from E, rho, nu, D, d, Omega (paper eqs. 12, 17; printed `k5`).
fn reference_coefficients() -> PdeCoefficients {
    let (e, rho, nu, d_out, d_in, omega) = (0.7e11, 2.7e3, 0.34, 0.2, 0.12, PI);
    let g = e / (2.0 * (1.0 + nu));
    let (r_out, r_in) = (d_out / 2.0, d_in / 2.0);
    let area = PI * (r_out * r_out - r_in * r_in);
    let ip = PI * (r_out.powi(4) - r_in.powi(4)) / 2.0;
    let ir = PI * (r_out.powi(6) - r_in.powi(6)) / 4.0;
    let ix2y2 = PI * (r_out.powi(6) - r_in.powi(6)) / 24.0;
    PdeCoefficients {
        k1: rho * ip,
        k2: 4.0 * g * ip,
        k3: 2.0 * area * g / (1.0 - 2.0 * nu),
        k4: g * ip * (5.0 - 6.0 * nu) / (4.0 * (1.0 - 2.0 * nu)),
        k5: g * (ir - ix2y2 * (5.0 - 6.0 * nu)) / (8.0 * (1.0 - 2.0 * nu)),
        k6: rho * ip * omega * omega,
    }
}

fn bench(c: &mut Criterion) {
    let k = reference_coefficients();
    // rho I_p = 2.7e3 * pi (0.1^4 - 0.06^4) / 2 (tests/test_section_coefficients.py).
    assert!((k.k1 - 0.36914970316741513).abs() < 1e-12, "k1 = {}", k.k1);

    for nodes in [240, 2400] {
        let sys = PdeSystem::new(k, LENGTH, nodes).expect("valid system");
        // A smooth state of realistic size: the three-mode shape at amplitude ~5e-4 rad.
        let q: Vec<f64> = sys.initial_velocity_from_modes(&[5e-4, 2.5e-4, 1e-4]);
        let mut acc = vec![0.0; nodes];
        c.bench_function(&format!("pde/acceleration N={nodes}"), |b| {
            b.iter(|| {
                sys.acceleration(black_box(&q), &mut acc);
                black_box(acc[nodes / 2])
            })
        });
    }

    let nodes = 240;
    let sys = PdeSystem::new(k, LENGTH, nodes).expect("valid system");
    let q0 = vec![0.0; nodes];
    let v0 = sys.initial_velocity_from_modes(&[0.1, 0.05, 0.02]);
    let output = Output::Times((0..=100).map(|i| i as f64 / 100.0).collect());
    let opts = SolveOptions { rtol: 1e-10, atol: 1e-12, ..SolveOptions::new(Method::Dop853) };
    let sol = solve_second_order(&sys, 0.0, &q0, &v0, 1.0, &output, &opts).expect("valid input");
    assert!(sol.status.is_success(), "{}", sol.message);
    eprintln!("dop853 N={nodes} t=1: {:?}", sol.stats);
    c.bench_function("pde/dop853 N=240 t=1 rtol=1e-10", |b| {
        b.iter(|| solve_second_order(&sys, 0.0, black_box(&q0), &v0, 1.0, &output, &opts).expect("valid input"))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
