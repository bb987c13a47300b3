//! The lumped BHA mass at the bit (`bit.bha_mass`) against closed forms: the hanging hook load
//! carries its buoyed weight, a string lifted off bottom by a constant extra hook load
//! accelerates as one body of the string's and the BHA's mass, the energy balance closes.

use std::f64::consts::PI;

use crate::drilling::config::{DrillConfig, HoistMode};
use crate::drilling::solver::solve;
use crate::interrupt::Never;
use crate::solution::Status;

/// The coupled test string (1000 m of the pipe, OD 127 mm, ID 108 mm, rho 8000 kg/m^3,
/// vertical, `super::tests::coupled`) in mud of 1200 kg/m^3 with a BHA of `mass` kg, held at the
/// hook load `hook` N (ramp 0), no damping.
fn hanging(mass: f64, hook: f64) -> DrillConfig {
    let mut cfg = super::tests::coupled("detournay", "");
    cfg.well.mud_density = 1200.0;
    cfg.damping_rate = 0.0;
    cfg.bit.bha_mass = mass;
    let h = cfg.hoist.as_mut().expect("a hoist");
    (h.mode, h.hook_load, h.ramp_time) = (HoistMode::HookLoad, hook, 0.0);
    cfg.numerics.duration = 20.0;
    cfg.metrics.window = Some([10.0, 20.0]);
    cfg
}

/// `(string mass, buoyancy factor g (1 - rho_mud / rho))`.
fn string() -> (f64, f64) {
    (8000.0 * PI / 4.0 * (0.127 * 0.127 - 0.108 * 0.108) * 1000.0, 9.81 * (1.0 - 1200.0 / 8000.0))
}

/// The hanging hook load is the buoyed weight of the string and the BHA; pulled with 10 kN more,
/// the bit lifts off and the string and BHA accelerate together at `10 kN / (m_string + M)`
/// (the least-squares parabola of the bit's depth), the energy balance closed.
#[test]
fn the_bha_mass_hangs_from_the_string_and_moves_with_it() {
    let (ms, bg) = string();
    for mass in [0.0, 20_000.0] {
        let weight = bg * (ms + mass);
        let run = solve(&hanging(mass, weight + 10e3), &Never, &mut |_| {}).unwrap();
        assert_eq!(run.status, Status::Success, "{}", run.message);
        assert!((run.hook_load[0] - weight).abs() < 1e-9 * weight, "{mass}: {} vs {weight}", run.hook_load[0]);
        // Fit depth = c0 + c1 t + c2 t^2 over the run (normal equations).
        let mut a = [[0.0; 3]; 3];
        let mut b = [0.0; 3];
        for (&t, &d) in run.t.iter().zip(&run.bit_depth) {
            let p = [1.0, t, t * t];
            for i in 0..3 {
                b[i] += p[i] * d;
                for j in 0..3 {
                    a[i][j] += p[i] * p[j];
                }
            }
        }
        let c2 = solve3(a, b)[2];
        let want = -10e3 / (ms + mass);
        println!("bha {mass} kg: acceleration {} m/s^2, closed form {want}", 2.0 * c2);
        assert!((2.0 * c2 - want).abs() < 1e-4 * want.abs(), "{mass}: {} vs {want}", 2.0 * c2);
        assert!(run.weight_on_bit.iter().skip(100).all(|&w| w == 0.0));
        assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
    }
}

/// Gaussian elimination of a 3x3 system.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> [f64; 3] {
    for k in 0..3 {
        let (pivot, bk) = (a[k], b[k]);
        for i in k + 1..3 {
            let f = a[i][k] / pivot[k];
            for (x, p) in a[i][k..].iter_mut().zip(&pivot[k..]) {
                *x -= f * p;
            }
            b[i] -= f * bk;
        }
    }
    let mut x = [0.0; 3];
    for k in (0..3).rev() {
        x[k] = (b[k] - (k + 1..3).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// Drilling in a 60-degree well with wall friction on both fields and a 15 t BHA: the energy
/// balance closes with the BHA's kinetic energy, its weight's work and its implicit-Euler term.
#[test]
fn the_energy_balance_closes_with_a_bha_mass() {
    let mut cfg = crate::drilling::engine::coupled_friction::tests::inclined("");
    cfg.bit.bha_mass = 15_000.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
    assert!(run.weight_on_bit.iter().any(|&w| w > 0.0));
}
