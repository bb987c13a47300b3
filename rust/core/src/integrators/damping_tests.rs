//! Velocity-dependent systems: viscous damping on the modal and PDE systems, the dissipated
//! energy, the automatic choice of form and the methods that refuse such systems.

use super::*;
use crate::modal::{ModalSystem, QuarticTerm};
use crate::pde::PdeSystem;
use crate::solution::Status;

/// `x(t) = v0 / wd e^{-c t / 2} sin(wd t)`, `wd = sqrt(w^2 - c^2 / 4)`: the damped oscillator
/// `x'' + c x' + w^2 x = 0` from `x(0) = 0`, `x'(0) = v0`.
fn damped(w: f64, c: f64, v0: f64, t: f64) -> f64 {
    let wd = (w * w - 0.25 * c * c).sqrt();
    v0 / wd * (-0.5 * c * t).exp() * (wd * t).sin()
}

fn methods() -> [(Method, Option<f64>, f64); 3] {
    // (method, dt, tolerance of the comparison relative to the amplitude)
    [(Method::Dop853, None, 1e-8), (Method::Dopri5, None, 1e-7), (Method::Rk4, Some(1e-3), 1e-6)]
}

fn options(method: Method, dt: Option<f64>) -> SolveOptions {
    SolveOptions { dt, rtol: 1e-11, atol: 1e-14, ..SolveOptions::new(method) }
}

/// One linear mode with mass 2 and `w = 7`.
fn linear_mode(c: f64) -> ModalSystem {
    ModalSystem::new(vec![2.0], vec![2.0 * 49.0], vec![]).unwrap().with_damping(c).unwrap()
}

/// Two coupled nonlinear modes.
fn nonlinear_modes(c: f64) -> ModalSystem {
    ModalSystem::new(
        vec![2.0, 3.0],
        vec![50.0, 120.0],
        vec![
            QuarticTerm { idx: [0, 0, 0, 0], coef: 40.0 },
            QuarticTerm { idx: [0, 0, 1, 1], coef: 25.0 },
            QuarticTerm { idx: [1, 1, 1, 1], coef: 10.0 },
        ],
    )
    .unwrap()
    .with_damping(c)
    .unwrap()
}

#[test]
fn damped_linear_mode_decays_at_half_the_damping_rate() {
    let (w, c, v0) = (7.0, 1.5, 0.3);
    let sys = linear_mode(c);
    assert!(sys.velocity_dependent());
    let times: Vec<f64> = (0..=50).map(|i| 0.1 * i as f64).collect();
    let amplitude = v0 / w;
    for (method, dt, tol) in methods() {
        let sol =
            solve_second_order(&sys, 0.0, &[0.0], &[v0], 5.0, &Output::Times(times.clone()), &options(method, dt))
                .unwrap();
        assert_eq!(sol.status, Status::Success);
        assert_eq!(sol.dim, 2);
        assert_eq!(sol.dissipated.len(), times.len());
        for (k, &t) in times.iter().enumerate() {
            let err = (sol.state(k)[0] - damped(w, c, v0, t)).abs() / amplitude;
            assert!(err < tol, "{method:?} at t = {t}: relative error {err:e}");
        }
    }
}

#[test]
fn energy_balance_closes_to_the_tolerance() {
    let sys = nonlinear_modes(0.8);
    let (q0, v0) = ([0.0, 0.0], [1.5, -1.0]);
    let times: Vec<f64> = (0..=100).map(|i| 0.05 * i as f64).collect();
    for (rtol, bound) in [(1e-8, 1e-6), (1e-11, 1e-9)] {
        let opts = SolveOptions { rtol, atol: rtol * 1e-3, ..SolveOptions::new(Method::Dop853) };
        let sol = solve_second_order(&sys, 0.0, &q0, &v0, 5.0, &Output::Times(times.clone()), &opts).unwrap();
        let h0 = sys.energy(&q0, &v0);
        let mut worst = 0.0f64;
        for k in 0..sol.len() {
            let (q, v) = sol.state(k).split_at(2);
            worst = worst.max((sys.energy(q, v) + sol.dissipated[k] - h0).abs() / h0);
        }
        // the damping took out most of the energy: the balance is not trivially H = H(0)
        assert!(sol.dissipated[sol.len() - 1] > 0.5 * h0);
        assert!(worst < bound, "rtol {rtol:e}: balance error {worst:e}");
    }
}

#[test]
fn zero_damping_is_the_undamped_system_bit_for_bit() {
    let undamped = nonlinear_modes(0.0);
    let plain =
        ModalSystem::new(undamped.mass().to_vec(), undamped.stiffness().to_vec(), undamped.terms().to_vec()).unwrap();
    assert!(!undamped.velocity_dependent());
    let times: Vec<f64> = (0..=20).map(|i| 0.1 * i as f64).collect();
    for method in Method::ALL {
        let dt = if method.is_adaptive() { None } else { Some(1e-3) };
        let opts = options(method, dt);
        let run = |sys: &ModalSystem| {
            solve_second_order(sys, 0.0, &[0.0, 0.0], &[1.0, 0.5], 2.0, &Output::Times(times.clone()), &opts).unwrap()
        };
        let (a, b) = (run(&undamped), run(&plain));
        assert!(a.dissipated.is_empty());
        assert_eq!(a.stats, b.stats);
        assert!(a.y.iter().zip(&b.y).all(|(x, y)| x.to_bits() == y.to_bits()), "{method:?}");
    }
}

#[test]
fn central_and_verlet_refuse_velocity_dependent_forces() {
    let sys = linear_mode(0.5);
    let fixed = FixedOptions::new(1e-3);
    for method in [Method::Central, Method::Verlet] {
        let opts = options(method, Some(1e-3));
        let err = solve_second_order(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::EveryStep, &opts).unwrap_err();
        assert_eq!(err.field(), "method");
        assert!(err.to_string().contains(method.name()), "{err}");
    }
    let err = central_difference(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::EveryStep, &fixed).unwrap_err();
    assert_eq!(err.field(), "method");
    let err = verlet(&sys, 0.0, &[0.0], &[1.0], 1.0, &Output::EveryStep, &fixed).unwrap_err();
    assert_eq!(err.field(), "method");
}

#[test]
fn damping_rate_is_validated() {
    for bad in [-1.0, -1e-300, f64::NAN, f64::INFINITY] {
        assert_eq!(linear_mode(0.0).with_damping(bad).unwrap_err().field(), "damping_rate");
        let pde = PdeSystem::new([1.0, 1.0, 0.0, 0.0, 0.0, 0.0], 1.0, 5).unwrap();
        assert_eq!(pde.with_damping(bad).unwrap_err().field(), "damping_rate");
    }
}

#[test]
fn damped_pde_mode_decays_at_half_the_damping_rate() {
    // Linear PDE k1 th_tt = k2 th_zz: cos(pi z_j / l) is an exact eigenvector of the lumped
    // scheme with w^2 = 2 k2 (1 - cos(pi h / l)) / (k1 h^2).
    let (k1, k2, length, nodes, c, amp) = (2.0, 3.0, 1.0, 41, 0.9, 0.2);
    let sys = PdeSystem::new([k1, k2, 0.0, 0.0, 0.0, 0.0], length, nodes).unwrap().with_damping(c).unwrap();
    let h = sys.spacing();
    let w = (2.0 * k2 * (1.0 - (std::f64::consts::PI * h / length).cos()) / (k1 * h * h)).sqrt();
    let v0 = sys.initial_velocity_from_modes(&[amp]);
    let q0 = vec![0.0; nodes];
    let times: Vec<f64> = (0..=40).map(|i| 0.25 * i as f64).collect();
    for (method, dt, tol) in methods() {
        let dt = dt.map(|_| 1e-2);
        let sol =
            solve_second_order(&sys, 0.0, &q0, &v0, 10.0, &Output::Times(times.clone()), &options(method, dt)).unwrap();
        assert_eq!(sol.status, Status::Success);
        for (k, &t) in times.iter().enumerate() {
            let want = damped(w, c, amp, t);
            let got = sol.state(k)[0];
            assert!((got - want).abs() < tol * amp / w, "{method:?} at t = {t}: {got} vs {want}");
        }
        // the energy balance on the nodal energy H_h
        let h0 = sys.energy(&q0, &v0);
        let k = sol.len() - 1;
        let (q, v) = sol.state(k).split_at(nodes);
        let balance = (sys.energy(q, v) + sol.dissipated[k] - h0).abs() / h0;
        assert!(balance < 10.0 * tol, "{method:?}: balance {balance:e}");
    }
}
