//! Tests of the PDE discretisation: gradient check, energy conservation, linear
//! frequencies, spatial convergence and input validation.

use std::f64::consts::PI;

use super::*;
use crate::integrators::{solve_second_order, Method, SolveOptions};
use crate::options::Output;
use crate::solution::{Solution, Status};
use crate::system::SecondOrderSystem;

/// The aluminium reference string (model notes, Table 1; printed `k5`), `Omega = pi`.
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

const LENGTH: f64 = 100.0;

/// A deterministic pseudo-random number in `[-1, 1)` (xorshift64*).
fn uniform(state: &mut u64) -> f64 {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    let bits = state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
    2.0 * (bits as f64 / (1u64 << 53) as f64) - 1.0
}

/// Least-squares slope of `log(err)` against `log(h)`.
fn slope(hs: &[f64], errs: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

// ---------------------------------------------------------------- the discretisation

#[test]
fn acceleration_is_the_gradient_of_the_discrete_energy() {
    // O(1) coefficients of both signs so that every term of the flux matters; sizes below,
    // at and past the node blocks of the sweep (16 interior nodes each).
    let k = PdeCoefficients { k1: 1.3, k2: 2.0, k3: 0.7, k4: -0.9, k5: 0.4, k6: 0.6 };
    let mut rng = 0x9e37_79b9_7f4a_7c15_u64;
    for n in [3, 7, 17, 18, 19, 35, 36, 40] {
        let sys = PdeSystem::new(k, 3.0, n).unwrap();
        // Keep the gradients O(1) on the finer grids.
        let amp = 6.0 / n as f64;
        for _ in 0..3 {
            let q: Vec<f64> = (0..n).map(|_| amp * uniform(&mut rng)).collect();
            let v: Vec<f64> = (0..n).map(|_| uniform(&mut rng)).collect();
            let mut acc = vec![0.0; n];
            let mut force = vec![0.0; n];
            sys.acceleration(&q, &mut acc);
            sys.force(&q, &mut force);
            for j in 0..n {
                let eps = 1e-5;
                let shifted = |d: f64| {
                    let mut qs = q.clone();
                    qs[j] += d;
                    sys.energy(&qs, &v)
                };
                // Fourth-order central difference of H_h in th_j.
                let fd =
                    (8.0 * (shifted(eps) - shifted(-eps)) - (shifted(2.0 * eps) - shifted(-2.0 * eps))) / (12.0 * eps);
                assert!((fd - force[j]).abs() < 1e-9 * (1.0 + fd.abs()), "N {n}, node {j}: fd {fd} vs {}", force[j]);
                let expected = -fd / (sys.weight(j) * k.k1);
                assert!((acc[j] - expected).abs() < 1e-8 * (1.0 + expected.abs()), "N {n}, node {j}: {}", acc[j]);
                // The kinetic term is sum_j w_j k1 v_j^2 / 2.
                let mut vs = v.clone();
                vs[j] += eps;
                let dk = (sys.energy(&q, &vs) - sys.energy(&q, &v)) / eps;
                let mass = sys.weight(j) * k.k1;
                assert!((dk - mass * (v[j] + 0.5 * eps)).abs() < 1e-8, "N {n}, node {j}: dH/dv {dk}");
            }
        }
    }
}

#[test]
fn acceleration_matches_the_closed_form() {
    // Spot check of the flux formula at one interior and both end nodes, N = 4.
    let k = PdeCoefficients { k1: 2.0, k2: 3.0, k3: 5.0, k4: 7.0, k5: 11.0, k6: 13.0 };
    let sys = PdeSystem::new(k, 1.5, 4).unwrap();
    let h = 0.5;
    let q = [0.1, -0.2, 0.3, 0.05];
    let g: Vec<f64> = (0..3).map(|c| (q[c + 1] - q[c]) / h).collect();
    let flux: Vec<f64> = (0..3)
        .map(|c| k.k2 * g[c] + 0.5 * k.k4 * (q[c] * q[c] + q[c + 1] * q[c + 1]) * g[c] + k.k5 * g[c].powi(3))
        .collect();
    let nodal = |j: usize, w: f64| w * (k.k3 * q[j].powi(3) - k.k6 * q[j]);
    let dv0 = nodal(0, h / 2.0) - flux[0] + h * 0.5 * k.k4 * q[0] * g[0] * g[0];
    let dv1 = nodal(1, h) + flux[0] - flux[1] + h * 0.5 * k.k4 * q[1] * (g[0] * g[0] + g[1] * g[1]);
    let dv3 = nodal(3, h / 2.0) + flux[2] + h * 0.5 * k.k4 * q[3] * g[2] * g[2];
    let mut acc = [0.0; 4];
    sys.acceleration(&q, &mut acc);
    for (j, dv, w) in [(0, dv0, h / 2.0), (1, dv1, h), (3, dv3, h / 2.0)] {
        let expected = -dv / (w * k.k1);
        assert!((acc[j] - expected).abs() < 1e-13 * expected.abs().max(1.0), "node {j}: {} vs {expected}", acc[j]);
    }
}

#[test]
fn uniform_twist_feels_only_the_nodal_terms() {
    // th = const has no gradient: every node, ends included, obeys k1 th'' = k6 th - k3 th^3.
    let k = reference_coefficients();
    let sys = PdeSystem::new(k, LENGTH, 11).unwrap();
    let th = 0.01;
    let mut acc = vec![0.0; 11];
    sys.acceleration(&[th; 11], &mut acc);
    let expected = (k.k6 * th - k.k3 * th.powi(3)) / k.k1;
    for (j, a) in acc.iter().enumerate() {
        assert!((a - expected).abs() < 1e-9 * expected.abs(), "node {j}: {a} vs {expected}");
    }
}

#[test]
fn grid_and_modal_initial_velocity() {
    let sys = PdeSystem::new(reference_coefficients(), LENGTH, 5).unwrap();
    assert_eq!(sys.nodes(), 5);
    assert_eq!(sys.dof(), 5);
    assert_eq!(sys.positions(), [0.0, 25.0, 50.0, 75.0, 100.0]);
    assert_eq!(sys.weights(), [12.5, 25.0, 25.0, 25.0, 12.5]);
    assert_eq!(sys.weights().iter().sum::<f64>(), LENGTH);
    let v = sys.initial_velocity_from_modes(&[0.1, 0.05]);
    for (j, &vj) in v.iter().enumerate() {
        let z = sys.z(j);
        let expected = 0.1 * (PI * z / LENGTH).cos() + 0.05 * (2.0 * PI * z / LENGTH).cos();
        assert!((vj - expected).abs() < 1e-15, "node {j}: {vj} vs {expected}");
    }
    assert!((v[0] - 0.15).abs() < 1e-16);
    assert_eq!(sys.initial_velocity_from_modes(&[]), vec![0.0; 5]);
    let q = [0.0, 1.0, 3.0, 2.0, -1.0];
    assert_eq!(sys.interpolate(&q, 25.0), 1.0);
    assert_eq!(sys.interpolate(&q, 37.5), 2.0);
    assert_eq!(sys.interpolate(&q, 100.0), -1.0);
    assert_eq!(sys.interpolate(&q, 1e9), -1.0);
    assert_eq!(sys.interpolate(&q, -1.0), 0.0);
}

// ---------------------------------------------------------------- energy conservation

/// Largest `|H - H0| / H0` over the samples.
fn relative_energy_drift(sys: &PdeSystem, sol: &Solution) -> f64 {
    let n = sys.nodes();
    let energy = |k: usize| {
        let (q, v) = sol.state(k).split_at(n);
        sys.energy(q, v)
    };
    let e0 = energy(0);
    (0..sol.len()).map(|k| ((energy(k) - e0) / e0).abs()).fold(0.0, f64::max)
}

#[test]
fn dop853_conserves_the_discrete_energy() {
    let sys = PdeSystem::new(reference_coefficients(), LENGTH, 60).unwrap();
    let q0 = vec![0.0; 60];
    let v0 = sys.initial_velocity_from_modes(&[0.1, 0.05, 0.02]);
    let opts = SolveOptions { rtol: 1e-12, atol: 1e-12, ..SolveOptions::new(Method::Dop853) };
    let sol = solve_second_order(&sys, 0.0, &q0, &v0, 1.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(sol.status, Status::Success, "{}", sol.message);
    let drift = relative_energy_drift(&sys, &sol);
    let amplitude =
        (0..sol.len()).map(|k| sol.state(k)[..60].iter().fold(0.0, |m: f64, x| m.max(x.abs()))).fold(0.0, f64::max);
    eprintln!(
        "DOP853 N = 60: max |H - H0| / H0 = {drift:e} over {} steps, max |th| = {amplitude:e}",
        sol.stats.naccept
    );
    assert!(amplitude > 1e-4, "the string moved: {amplitude}");
    assert!(drift < 1e-9, "energy drift {drift}");
}

#[test]
fn verlet_keeps_the_discrete_energy_bounded() {
    let k = reference_coefficients();
    let sys = PdeSystem::new(k, LENGTH, 60).unwrap();
    let q0 = vec![0.0; 60];
    let v0 = sys.initial_velocity_from_modes(&[0.1, 0.05, 0.02]);
    // Half the stability limit dt < 2 / w_max, w_max < 2 sqrt(k2 / k1) / h.
    let dt = 0.5 * sys.spacing() / (k.k2 / k.k1).sqrt();
    let opts = SolveOptions { dt: Some(dt), ..SolveOptions::new(Method::Verlet) };
    let sol = solve_second_order(&sys, 0.0, &q0, &v0, 2.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(sol.status, Status::Success, "{}", sol.message);
    let half = sol.len() / 2;
    let (first, second) = (first_half(&sys, &sol, half), second_half(&sys, &sol, half));
    eprintln!("Verlet N = 60, dt = {dt:e}: |H - H0| / H0 first half {first:e}, second half {second:e}");
    assert!(first < 1e-3 && second < 1.2 * first, "{first} {second}");
}

fn first_half(sys: &PdeSystem, sol: &Solution, half: usize) -> f64 {
    energy_error_range(sys, sol, 0..half)
}

fn second_half(sys: &PdeSystem, sol: &Solution, half: usize) -> f64 {
    energy_error_range(sys, sol, half..sol.len())
}

fn energy_error_range(sys: &PdeSystem, sol: &Solution, range: std::ops::Range<usize>) -> f64 {
    let n = sys.nodes();
    let e0 = sys.energy(&sol.state(0)[..n], &sol.state(0)[n..]);
    range
        .map(|k| {
            let (q, v) = sol.state(k).split_at(n);
            ((sys.energy(q, v) - e0) / e0).abs()
        })
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------- linear frequencies

/// The continuum `w_i^2 = (k2 (i pi / l)^2 - k6) / k1`.
fn continuum(k: &PdeCoefficients, i: usize) -> f64 {
    let kz = i as f64 * PI / LENGTH;
    (k.k2 * kz * kz - k.k6) / k.k1
}

#[test]
fn linear_frequencies_converge_at_second_order() {
    let k = reference_coefficients();
    let count = 6;
    let lowest =
        |cells: usize| PdeSystem::new(k, LENGTH, cells + 1).unwrap().linear_frequencies_squared(count).unwrap();
    let (coarse, fine) = (lowest(240), lowest(480));
    // The rigid-body mode is -k6/k1 (negative: rotation softening).
    for w2 in [coarse[0], fine[0]] {
        assert!(((w2 + k.k6 / k.k1) / (k.k6 / k.k1)).abs() < 1e-9, "w_0^2 = {w2}");
    }
    for i in 1..count {
        let exact = continuum(&k, i);
        let (e_coarse, e_fine) = ((coarse[i] - exact).abs(), (fine[i] - exact).abs());
        let ratio = e_coarse / e_fine;
        eprintln!(
            "mode {i}: w^2 = {:.9e}, rel. error N-1 = 240: {:e}, 480: {:e}, ratio {ratio:.4}",
            coarse[i],
            e_coarse / exact,
            e_fine / exact
        );
        assert!((ratio - 4.0).abs() < 0.05, "mode {i}: ratio {ratio}");
        assert!(e_coarse / exact < 1e-3 * (i * i) as f64, "mode {i}: {e_coarse}");
    }
    let w = PdeSystem::new(k, LENGTH, 241).unwrap().linear_frequencies(3).unwrap();
    assert_eq!(w[0], -(k.k6 / k.k1).sqrt());
    assert_eq!(w[1], coarse[1].sqrt());
}

#[test]
fn linear_frequencies_match_the_discrete_spectrum() {
    // The lumped-mass scheme's Neumann eigenvectors are cos(i pi j / (N - 1)) exactly, with
    // w_i^2 = 4 k2 / (k1 h^2) sin^2(i pi / (2 (N - 1))) - k6 / k1.
    let k = reference_coefficients();
    for nodes in [3, 4, 17, 241] {
        let sys = PdeSystem::new(k, LENGTH, nodes).unwrap();
        let w2 = sys.linear_frequencies_squared(nodes).unwrap();
        let c = k.k2 / (k.k1 * sys.spacing() * sys.spacing());
        for (i, &got) in w2.iter().enumerate() {
            let s = (i as f64 * PI / (2.0 * (nodes - 1) as f64)).sin();
            let expected = 4.0 * c * s * s - k.k6 / k.k1;
            assert!(
                (got - expected).abs() < 1e-12 * expected.abs().max(4.0 * c),
                "N = {nodes}, i = {i}: {got} vs {expected}"
            );
        }
    }
}

#[test]
fn linear_frequencies_agree_with_a_dense_solve_of_the_symmetrised_operator() {
    // Independent check of the factorisation: faer's dense self-adjoint eigenvalues of
    // A = M^{-1/2} K M^{-1/2}, built entry by entry.
    let k = reference_coefficients();
    let nodes = 241;
    let sys = PdeSystem::new(k, LENGTH, nodes).unwrap();
    let h = sys.spacing();
    let stiffness = |i: usize, j: usize| {
        let degree = if i == 0 || i + 1 == nodes { 1.0 } else { 2.0 };
        if i == j {
            k.k2 / h * degree - sys.weight(i) * k.k6
        } else if i.abs_diff(j) == 1 {
            -k.k2 / h
        } else {
            0.0
        }
    };
    let a = faer::Mat::<f64>::from_fn(nodes, nodes, |i, j| {
        stiffness(i, j) / (k.k1 * (sys.weight(i) * sys.weight(j)).sqrt())
    });
    let dense = a.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
    let ours = sys.linear_frequencies_squared(nodes).unwrap();
    let scale = 4.0 * k.k2 / (k.k1 * h * h);
    let worst = dense.iter().zip(&ours).map(|(d, o)| (d - o).abs() / scale).fold(0.0, f64::max);
    eprintln!(
        "dense vs tridiagonal: max |diff| / ||A|| = {worst:e}; dense w_0^2 rel. error {:e}",
        ((dense[0] + k.k6 / k.k1) / (k.k6 / k.k1)).abs()
    );
    assert!(worst < 1e-13, "{worst}");
}

// ---------------------------------------------------------------- spatial convergence

#[test]
fn small_amplitude_solution_converges_at_second_order_in_h() {
    let k = reference_coefficients();
    let (c1, t, z_k) = (1e-6, 0.05, 2.0 * LENGTH / 3.0);
    let w1 = continuum(&k, 1).sqrt();
    let exact = c1 / w1 * (w1 * t).sin() * (PI * z_k / LENGTH).cos();
    let cells = [40, 80, 160, 320];
    let opts = SolveOptions { rtol: 1e-11, atol: 1e-20, ..SolveOptions::new(Method::Dop853) };
    let errs: Vec<f64> = cells
        .iter()
        .map(|&m| {
            let sys = PdeSystem::new(k, LENGTH, m + 1).unwrap();
            let v0 = sys.initial_velocity_from_modes(&[c1]);
            let sol = solve_second_order(&sys, 0.0, &vec![0.0; m + 1], &v0, t, &Output::Times(vec![t]), &opts).unwrap();
            assert_eq!(sol.status, Status::Success, "{}", sol.message);
            eprintln!("N - 1 = {m}: {:?}", sol.stats);
            (sys.interpolate(&sol.state(0)[..m + 1], z_k) - exact).abs()
        })
        .collect();
    let hs: Vec<f64> = cells.iter().map(|&m| LENGTH / m as f64).collect();
    let p = slope(&hs, &errs);
    let ratios: Vec<f64> = errs.windows(2).map(|e| e[0] / e[1]).collect();
    eprintln!("th(2l/3, 0.05): exact {exact:e}, errors {errs:?}, ratios {ratios:?}, slope {p:.4}");
    assert!((p - 2.0).abs() < 0.2, "slope {p}");
    assert!(errs[3] < 1e-3 * exact.abs(), "{}", errs[3]);
}

// ---------------------------------------------------------------- validation

#[test]
fn bad_input_names_its_field() {
    let k = reference_coefficients();
    let field = |r: crate::Result<PdeSystem>| r.unwrap_err().field().to_string();
    assert_eq!(field(PdeSystem::new(k, LENGTH, 2)), "nodes");
    assert_eq!(field(PdeSystem::new(k, LENGTH, 0)), "nodes");
    assert_eq!(field(PdeSystem::new(k, LENGTH, MAX_NODES + 1)), "nodes");
    assert_eq!(field(PdeSystem::new(k, 0.0, 10)), "length");
    assert_eq!(field(PdeSystem::new(k, f64::INFINITY, 10)), "length");
    assert_eq!(field(PdeSystem::new(k, f64::NAN, 10)), "length");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k1: 0.0, ..k }, LENGTH, 10)), "k1");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k2: -1.0, ..k }, LENGTH, 10)), "k2");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k3: f64::NAN, ..k }, LENGTH, 10)), "k3");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k4: f64::INFINITY, ..k }, LENGTH, 10)), "k4");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k5: f64::NEG_INFINITY, ..k }, LENGTH, 10)), "k5");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k6: f64::NAN, ..k }, LENGTH, 10)), "k6");
    assert_eq!(field(PdeSystem::new(PdeCoefficients { k1: 1e-300, ..k }, 1e-300, 10)), "length");
    assert!(PdeSystem::new([1.0, 1.0, 0.0, 0.0, 0.0, 0.0], 1.0, 3).is_ok());
    assert!(PdeSystem::new(PdeCoefficients { k6: -1.0, k4: -2.0, ..k }, LENGTH, 3).is_ok());

    let sys = PdeSystem::new(k, LENGTH, 10).unwrap();
    assert_eq!(sys.linear_frequencies_squared(0).unwrap_err().field(), "count");
    assert_eq!(sys.linear_frequencies_squared(11).unwrap_err().field(), "count");
    assert_eq!(sys.linear_frequencies(11).unwrap_err().field(), "count");
    assert_eq!(sys.linear_frequencies_squared(10).unwrap().len(), 10);

    let (every, ok) = (Output::EveryStep, SolveOptions::new(Method::Dop853));
    let solve = |q0: &[f64], v0: &[f64], opts: &SolveOptions| solve_second_order(&sys, 0.0, q0, v0, 1e-3, &every, opts);
    assert_eq!(solve(&[0.0; 9], &[0.0; 10], &ok).unwrap_err().field(), "q0");
    assert_eq!(solve(&[0.0; 10], &[0.0; 11], &ok).unwrap_err().field(), "v0");
    let mut v0 = [0.0; 10];
    v0[3] = f64::NAN;
    assert_eq!(solve(&[0.0; 10], &v0, &ok).unwrap_err().field(), "v0");
    let verlet = SolveOptions::new(Method::Verlet);
    assert_eq!(solve(&[0.0; 10], &[0.0; 10], &verlet).unwrap_err().field(), "dt");
}

#[test]
fn divergence_ends_with_a_status_not_a_panic() {
    // Verlet far beyond its stability limit blows up: a status, never a panic.
    let sys = PdeSystem::new(reference_coefficients(), LENGTH, 30).unwrap();
    let v0 = sys.initial_velocity_from_modes(&[0.1]);
    let opts = SolveOptions { dt: Some(1e-2), ..SolveOptions::new(Method::Verlet) };
    let sol = solve_second_order(&sys, 0.0, &[0.0; 30], &v0, 10.0, &Output::EveryStep, &opts).unwrap();
    assert_eq!(sol.status, Status::NonFinite, "{}", sol.message);
    // Huge amplitudes with an adaptive method: some status, no panic.
    let opts = SolveOptions { max_steps: Some(1000), ..SolveOptions::new(Method::Dop853) };
    let sol = solve_second_order(&sys, 0.0, &[1e150; 30], &[1e150; 30], 1.0, &Output::EveryStep, &opts).unwrap();
    assert_ne!(sol.status, Status::Success);
    // Saved samples only: 11 requested times, whatever the number of steps.
    let opts = SolveOptions { rtol: 1e-8, atol: 1e-12, ..SolveOptions::new(Method::Dop853) };
    let times: Vec<f64> = (0..=10).map(|i| i as f64 * 0.01).collect();
    let sol = solve_second_order(&sys, 0.0, &[0.0; 30], &v0, 0.1, &Output::Times(times), &opts).unwrap();
    assert_eq!((sol.len(), sol.dim, sol.y.len()), (11, 60, 11 * 60));
    assert!(sol.stats.naccept > 11);
}

/// The potential as the sum over the model's terms of the one finite-difference rule, the cell
/// energy `h weight (a^p + b^p) / 2 g^r`, and its gradient from the terms' cell gradients.
fn potential_by_terms(model: &crate::terms::ModelTerms, q: &[f64], h: f64) -> (f64, Vec<f64>) {
    let mut energy = 0.0;
    let mut grad = vec![0.0; q.len()];
    for term in model.conservative() {
        for c in 0..q.len() - 1 {
            energy += term.cell_energy(q[c], q[c + 1], h);
            let (da, db) = term.cell_gradient(q[c], q[c + 1], h);
            grad[c] += da;
            grad[c + 1] += db;
        }
    }
    (energy, grad)
}

#[test]
fn the_fused_kernel_is_the_sum_of_the_terms_cell_energies() {
    let k = reference_coefficients();
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    for nodes in [3, 7, 40, 101] {
        let model = crate::terms::ModelTerms::from_coefficients(k).unwrap();
        let sys = PdeSystem::discretise(&model, LENGTH, nodes).unwrap();
        assert_eq!(sys, PdeSystem::new(k, LENGTH, nodes).unwrap());
        assert_eq!(sys.coefficients(), k, "the kernel collects each coefficient exactly");
        let q: Vec<f64> = (0..nodes).map(|_| 0.3 * uniform(&mut state)).collect();
        let (energy, grad) = potential_by_terms(&model, &q, sys.spacing());
        let potential = sys.potential(&q);
        assert!((energy - potential).abs() <= 1e-13 * potential.abs(), "{energy} vs {potential}");
        let mut force = vec![0.0; nodes];
        sys.force(&q, &mut force);
        let scale = force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        for j in 0..nodes {
            assert!((force[j] - grad[j]).abs() <= 1e-12 * scale, "node {j}: {} vs {}", force[j], grad[j]);
        }
    }
}

#[test]
fn the_consistent_model_has_two_terms_and_damping_comes_from_the_model() {
    let k = PdeCoefficients { k1: 0.4, k2: 2.0e9, k3: 0.0, k4: 0.0, k5: 3.0e3, k6: 0.0 };
    let model = crate::terms::ModelTerms::from_coefficients(k).unwrap().with_damping(0.25).unwrap();
    assert_eq!(model.conservative().len(), 2);
    let sys = PdeSystem::discretise(&model, LENGTH, 11).unwrap();
    assert_eq!(sys.coefficients(), k);
    assert_eq!(sys.damping_rate(), 0.25);
    assert_eq!(sys, PdeSystem::new(k, LENGTH, 11).unwrap().with_damping(0.25).unwrap());
}

static SLOPE_TWIST: crate::terms::TermSpec = crate::terms::TermSpec {
    name: "slope twist",
    equation: "none (a test shape)",
    coefficient: "k7",
    factor: (1, 2),
    p: 1,
    r: 1,
};

#[test]
fn a_shape_the_kernel_does_not_evaluate_is_refused_by_name() {
    let mut terms =
        crate::terms::ModelTerms::from_coefficients(reference_coefficients()).unwrap().conservative().to_vec();
    terms.push(SLOPE_TWIST.with(1.0).unwrap());
    let model = crate::terms::ModelTerms::new(1.0, terms).unwrap();
    let err = PdeSystem::discretise(&model, LENGTH, 11).unwrap_err();
    assert_eq!(err.field(), "k7");
    assert!(err.to_string().contains("slope twist"), "{err}");
    // without an elastic term there is no wave propagation
    let model = crate::terms::ModelTerms::new(1.0, vec![]).unwrap();
    assert_eq!(PdeSystem::discretise(&model, LENGTH, 11).unwrap_err().field(), "k2");
}
