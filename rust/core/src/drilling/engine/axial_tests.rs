//! The coupled run against closed forms: the bit law's steady state, the axial natural
//! frequency, the energy balance.

use std::f64::consts::PI;

use crate::drilling::config::DrillConfig;
use crate::drilling::solver::solve;
use crate::interrupt::Never;

/// Aarsnes & van de Wouw's pipe (OD 127 mm, ID 108 mm, E 200 GPa, rho 8000 kg/m^3, nu 0.3 so
/// that G = E / 2.6), 1000 m, vertical, friction off, with a hoist and the Detournay law.
pub(super) fn coupled(law: &str, extra: &str) -> DrillConfig {
    let json = format!(
        r#"{{"sections": [{{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
            "shear_modulus": {g}, "density": 8000.0, "poisson_ratio": 0.3}}],
           "well": {{"inclination_deg": 0.0, "mud_density": 0.0}},
           "friction": {{"static": 0.0}},
           "damping_rate": 0.5,
           "top_drive": {{"rpm": 60.0, "ramp_time": 2.0, "controller": {{"type": "speed"}}}},
           "bit": {{"radius": 0.108, "law": "{law}"}},
           "hoist": {{"speed": {v}, "ramp_time": 2.0}},
           "numerics": {{"cells": 200, "duration": 40.0, "output_interval": 0.01}},
           "metrics": {{"window": [30.0, 40.0]}} {extra}}}"#,
        g = 200e9 / 2.6,
        v = 30.0 / 3600.0,
    );
    DrillConfig::from_json(&json).unwrap()
}

/// The window's samples of a series.
fn window(run: &crate::drilling::engine::DrillRun, x: &[f64]) -> Vec<f64> {
    (0..run.t.len()).filter(|&k| run.t[k] >= run.window[0] && run.t[k] <= run.window[1]).map(|k| x[k]).collect()
}

/// A short stiff string at 120 rpm and 30 m/h with strong damping: the run settles.
fn settling(law: &str) -> DrillConfig {
    let mut cfg = coupled(law, "");
    cfg.sections[0].length = 200.0;
    cfg.numerics.cells = 100;
    cfg.damping_rate = 10.0;
    cfg.top_drive.rpm = 120.0;
    cfg.numerics.duration = 60.0;
    cfg.metrics.window = Some([50.0, 60.0]);
    cfg
}

#[test]
fn the_rate_law_settles_to_the_analytic_steady_state() {
    let run = solve(&settling("detournay"), &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    // By hand (Richard et al. 2007 with a = 0.108 m, eps = sigma = 60 MPa, zeta = 0.6,
    // l = 11 mm, mu = 0.6, gamma = 1): d = 2 pi V / Omega = 2 pi (30 / 3600) / (4 pi) m,
    // W = a zeta eps d + a l sigma = 16200 + 71280 N, T = a^2 eps d / 2 + mu a (a l sigma) / 2
    // = 1458 + 2309.472 N m.
    let d = 2.0 * PI * (30.0 / 3600.0) / (4.0 * PI);
    let (w, t) = (87_480.0, 3767.472);
    for (name, x, want, tol) in [
        ("depth of cut", &run.depth_of_cut, d, 1e-9),
        ("weight on bit", &run.weight_on_bit, w, 1e-9),
        ("torque on bit", &run.bit_torque, t, 1e-9),
        ("rop", &run.rop, 30.0, 1e-6),
        ("bit rpm", &run.bit_rpm, 120.0, 1e-6),
    ] {
        for v in window(&run, x) {
            assert!((v - want).abs() <= tol * want, "{name}: {v} vs {want}");
        }
    }
    let m = run.coupled.unwrap();
    assert!((m.wob_mean_n - w).abs() < 1e-9 * w && (m.tob_mean_nm - t).abs() < 1e-9 * t);
    assert!((m.rop_mean_m_per_h - 30.0).abs() < 1e-6 * 30.0 && m.bounce_fraction == 0.0);
    // Teale: W / A + Omega T / (A V), A = pi a^2.
    let area = PI * 0.108 * 0.108;
    let mse = w / area + 4.0 * PI * t / (area * 30.0 / 3600.0);
    assert!((m.mse_mean_pa - mse).abs() < 1e-6 * mse, "{} vs {mse}", m.mse_mean_pa);
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
}

#[test]
fn the_regenerative_law_drills_at_the_hoist_speed_around_the_steady_state() {
    // The exact delay is unstable here (a small axial-torsional limit cycle, W within ~5 % of
    // the steady value): the mean rate of penetration is the hoist's, the means of weight and
    // torque within 2 % of the steady state's.
    let run = solve(&settling("rgd"), &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let m = run.coupled.unwrap();
    assert!((m.rop_mean_m_per_h - 30.0).abs() < 1e-3 * 30.0, "{m:?}");
    assert!((m.wob_mean_n - 87_480.0).abs() < 0.02 * 87_480.0, "{m:?}");
    assert!((m.tob_mean_nm - 3767.472).abs() < 0.02 * 3767.472, "{m:?}");
    assert_eq!(m.bounce_fraction, 0.0);
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
}

#[test]
fn a_velocity_step_into_a_string_on_a_stuck_bit_is_the_wave_staircase() {
    // No gravity, damping or rotation: the block starts at V, a compression wave Z V runs down
    // at c = sqrt(E / rho) and doubles at the stuck bit (a fixed end), so the weight on bit is
    // 0 until L / c, then 2 Z V, 4 Z V, 6 Z V, ... each held for 2 L / c (the fixed-fixed
    // string's first natural frequency c / (2 L)); Z = A sqrt(E rho).
    let mut cfg = coupled("detournay", "");
    cfg.well.gravity = 0.0;
    cfg.damping_rate = 0.0;
    cfg.top_drive.rpm = 0.0;
    cfg.hoist.as_mut().unwrap().ramp_time = 0.0;
    cfg.numerics.duration = 1.5;
    cfg.metrics.window = None;
    cfg.numerics.output_interval = 0.001;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let area = PI / 4.0 * (0.127f64.powi(2) - 0.108f64.powi(2));
    let (c, z, v) = ((200e9f64 / 8000.0).sqrt(), area * (200e9f64 * 8000.0).sqrt(), 30.0 / 3600.0);
    let travel = 1000.0 / c;
    let at = |t: f64| run.weight_on_bit[(t / 0.001).round() as usize];
    assert!(at(0.8 * travel) < 1e-9 * z * v);
    for (k, t) in [(1.0, 2.0 * travel), (2.0, 4.0 * travel), (3.0, 6.0 * travel)] {
        let want = 2.0 * k * z * v;
        assert!((at(t) - want).abs() < 0.01 * want, "t = {t}: {} vs {want}", at(t));
    }
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
}

#[test]
fn a_coupled_law_and_a_hoist_come_together() {
    let mut cfg = coupled("rgd", "");
    cfg.hoist = None;
    assert!(cfg.validate().unwrap_err().to_string().contains("bit.law"));
    let mut cfg = coupled("rgd", "");
    cfg.bit.law = crate::drilling::config::BitRockLaw::VelocityWeakening;
    assert!(cfg.validate().unwrap_err().to_string().contains("hoist"));
    let mut cfg = coupled("rgd", "");
    cfg.bit.detournay.blades = 0;
    assert!(cfg.validate().unwrap_err().to_string().contains("bit.detournay.blades"));
}
