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
fn the_upwind_cut_surface_settles_at_the_steady_state_where_the_exact_delay_cycles() {
    // Their upwind cut surface on 20 cells (Courant number 0.13 at 120 rpm on this string's step):
    // its diffusion damps the limit cycle of the exact delay; its discrete steady state is the
    // delay's, `d = 2 pi V / Omega` (the chain's cells at `(j + 1) V t_n / cells`), so the run
    // settles at the law's steady state of the rate form's test. 2000 cells give the exact
    // delay's cycle (its WOB range within 2 %; measured 0.4 %).
    let mut cfg = settling("rgd");
    cfg.bit.detournay.cut_surface = crate::drilling::config::CutSurfaceScheme::Upwind;
    cfg.bit.detournay.cut_surface_cells = 20;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let d = 2.0 * PI * (30.0 / 3600.0) / (4.0 * PI);
    let (w, t) = (87_480.0, 3767.472);
    for (name, x, want) in [("depth of cut", &run.depth_of_cut, d), ("weight on bit", &run.weight_on_bit, w)] {
        for v in window(&run, x) {
            assert!((v - want).abs() <= 1e-6 * want, "{name}: {v} vs {want}");
        }
    }
    for v in window(&run, &run.bit_torque) {
        assert!((v - t).abs() <= 1e-6 * t, "torque on bit: {v} vs {t}");
    }
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
    let range = |r: &crate::drilling::engine::DrillRun| {
        let x = window(r, &r.weight_on_bit);
        x.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - x.iter().cloned().fold(f64::INFINITY, f64::min)
    };
    assert!(range(&run) < 1e-6 * w);
    let exact = solve(&settling("rgd"), &Never, &mut |_| {}).unwrap();
    let fine = {
        cfg.bit.detournay.cut_surface_cells = 2000;
        solve(&cfg, &Never, &mut |_| {}).unwrap()
    };
    assert!(range(&exact) > 1e-3 * w, "the exact delay cycles: {}", range(&exact));
    assert!((range(&fine) / range(&exact) - 1.0).abs() < 0.02, "{} vs {}", range(&fine), range(&exact));
}

#[test]
fn the_upwind_cut_surface_cells_are_checked() {
    for cells in [0, 1_000_001] {
        let mut cfg = coupled("rgd", "");
        cfg.bit.detournay.cut_surface_cells = cells;
        assert!(cfg.validate().unwrap_err().to_string().contains("bit.detournay.cut_surface_cells"));
    }
}

#[test]
fn the_weight_on_bit_mode_drills_at_the_imposed_weight() {
    // The hook held at the hanging string's static load (its weight in air here: no mud, a
    // vertical frictionless hole) less 80 kN: the rate law settles at W = 80 kN, at the depth of
    // cut d = (W - a l sigma) / (a zeta eps) and ROP = d Omega / (2 pi), apart from the
    // string's velocity damping, which takes rho A L k_d ROP (~0.1 % here) off the weight.
    let mut cfg = settling("detournay");
    let h = cfg.hoist.as_mut().unwrap();
    h.mode = crate::drilling::config::HoistMode::WeightOnBit;
    h.weight_on_bit = 80e3;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let m = run.coupled.unwrap();
    let w = 80e3;
    let d = (w - 0.108 * 0.011 * 60e6) / (0.108 * 0.6 * 60e6);
    // 120 rpm: 2 rev/s.
    let rop = d * 2.0 * 3600.0;
    // Measured: W 0.09 % below, ROP 0.8 % below (the damping's 72 N less weight, 1.85e-5 m less
    // depth of cut); the ROP of the law at the mean weight within 0.05 %.
    assert!((m.wob_mean_n - w).abs() < 0.002 * w, "{m:?}");
    assert!((m.rop_mean_m_per_h - rop).abs() < 0.01 * rop, "{} vs {rop} m/h", m.rop_mean_m_per_h);
    let at_mean = (m.wob_mean_n - 0.108 * 0.011 * 60e6) / (0.108 * 0.6 * 60e6) * 2.0 * 3600.0;
    assert!((m.rop_mean_m_per_h - at_mean).abs() < 5e-4 * at_mean, "{} vs {at_mean} m/h", m.rop_mean_m_per_h);
    // The hook load: the weight in air of the 200 m pipe less the weight on bit.
    let area = PI / 4.0 * (0.127f64.powi(2) - 0.108f64.powi(2));
    let hanging = 8000.0 * area * 200.0 * cfg.well.gravity;
    let hook = window(&run, &run.hook_load);
    let mean = hook.iter().sum::<f64>() / hook.len() as f64;
    assert!((mean - (hanging - w)).abs() < 1e-6 * hanging, "{mean} vs {}", hanging - w);
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
    // the velocity-weakening law's bit on bottom has no meaning with a coupled law
    let mut cfg = coupled("rgd", "");
    cfg.bit.on_bottom = true;
    let message = cfg.validate().unwrap_err().to_string();
    assert!(message.starts_with("invalid bit.on_bottom: got true with bit.law = rgd, expected false"), "{message}");
}

/// The short string of [`settling`] drilled by the autodriller on `target` at `setpoint` with
/// the gains `kp`, `ki`, the block velocity within `[0, max_speed]` m/s, and the steps `steps`.
fn autodrilled(target: &str, setpoint: f64, kp: f64, ki: f64, max_speed: f64, steps: &str) -> DrillConfig {
    let mut cfg = settling("detournay");
    let json = format!(
        r#"{{"mode": "autodriller", "ramp_time": 2.0, "steps": {steps},
            "autodriller": {{"target": "{target}", "setpoint": {setpoint}, "kp": {kp}, "ki": {ki},
                            "min_speed": 0.0, "max_speed": {max_speed}}}}}"#
    );
    cfg.hoist = Some(serde_json::from_str(&json).unwrap());
    cfg.validate().unwrap();
    cfg
}

/// The rate law's steady state at 120 rpm (see [`the_rate_law_settles_to_the_analytic_steady_state`]):
/// `W = a zeta eps d + a l sigma`, `d = 2 pi V / Omega`, so the ROP of a weight `w` (m/h) and
/// the weight of a ROP `rop` (m/h).
fn steady_rop(w: f64) -> f64 {
    (w - 71_280.0) / (0.108 * 0.6 * 60e6) * 2.0 * 3600.0
}
fn steady_wob(rop: f64) -> f64 {
    71_280.0 + 0.108 * 0.6 * 60e6 * rop / 3600.0 / 2.0
}

/// The string's spring `k = E A / L` = 3.5e6 N/m and the rock's `dW/dV = 1.944e6` N s/m at
/// 120 rpm make the loop on the weight `W' = k (kp e + ki int e) - (k / r) W`: with
/// `kp = 5e-7` (m/s)/N and `ki = 1e-6` (m/s)/(N s) its poles are `-1.78 +- 0.37 i` 1/s; the
/// high-frequency loop gain `2 Z kp = 0.14 < 1` (a wave doubling on the rock).
const KP: f64 = 5e-7;
const KI: f64 = 1e-6;

#[test]
fn the_autodriller_holds_its_weight_on_bit_and_follows_a_step() {
    // 90 kN, then 80 kN at 30 s: the bit drills at the rock's ROP of that weight.
    let cfg = autodrilled("weight_on_bit", 90e3, KP, KI, 100.0 / 3600.0, "[[30.0, 80e3]]");
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let at = |t: f64| (t / 0.01).round() as usize;
    let (w, rop) = (run.weight_on_bit[at(29.0)], run.rop[at(29.0)]);
    assert!((w - 90e3).abs() < 1e-4 * 90e3, "{w}");
    assert!((rop - steady_rop(90e3)).abs() < 1e-3 * rop, "{rop} vs {}", steady_rop(90e3));
    for w in window(&run, &run.weight_on_bit) {
        assert!((w - 80e3).abs() < 1e-4 * 80e3, "{w}");
    }
    let m = run.coupled.unwrap();
    assert!((m.rop_mean_m_per_h - steady_rop(80e3)).abs() < 1e-3 * steady_rop(80e3), "{m:?}");
    assert!(run.energy.balance_error.abs() < 1e-12, "{:?}", run.energy);
}

#[test]
fn the_autodriller_holds_its_rop_and_its_speed_limit() {
    // On ROP: 20 m/h, the weight the rock needs for it.
    let cfg = autodrilled("rop", 20.0 / 3600.0, 0.5, 2.0, 100.0 / 3600.0, "[]");
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, crate::solution::Status::Success, "{}", run.message);
    let m = run.coupled.unwrap();
    assert!((m.rop_mean_m_per_h - 20.0).abs() < 1e-3 * 20.0, "{m:?}");
    assert!((m.wob_mean_n - steady_wob(20.0)).abs() < 1e-3 * steady_wob(20.0), "{m:?}");
    // 90 kN needs 34.7 m/h: with the block held to 20 m/h the bit drills at 20 m/h under the
    // weight of that rate, below the setpoint.
    let cfg = autodrilled("weight_on_bit", 90e3, KP, KI, 20.0 / 3600.0, "[]");
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let m = run.coupled.unwrap();
    assert!((m.rop_mean_m_per_h - 20.0).abs() < 1e-3 * 20.0, "{m:?}");
    assert!((m.wob_mean_n - steady_wob(20.0)).abs() < 1e-3 * steady_wob(20.0), "{m:?}");
    // The bit never outruns the block for long: its depth at the end is at most the block's
    // travel at the limit plus the string's shortening under the weight, W / k.
    let end = *run.bit_depth.last().unwrap();
    assert!(end <= 20.0 / 3600.0 * 60.0 + 90e3 / 3.5e6, "{end}");
}

#[test]
fn an_autodriller_without_gains_is_refused() {
    let mut cfg = autodrilled("weight_on_bit", 90e3, KP, KI, 0.01, "[]");
    let a = &mut cfg.hoist.as_mut().unwrap().autodriller;
    (a.kp, a.ki) = (0.0, 0.0);
    let err = cfg.validate().unwrap_err();
    assert_eq!(err.field(), "hoist.autodriller.kp");
    assert!(err.to_string().contains("kp > 0 or ki > 0"), "{err}");
    cfg.hoist.as_mut().unwrap().autodriller.max_speed = -1.0;
    cfg.hoist.as_mut().unwrap().autodriller.ki = 1.0;
    assert_eq!(cfg.validate().unwrap_err().field(), "hoist.autodriller.max_speed");
}

#[test]
fn a_bit_that_never_touches_bottom_is_warned_about() {
    // The block pulled up at 36 m/h: the bit lifts off at once and has no weight in the window.
    let mut cfg = settling("detournay");
    cfg.hoist.as_mut().unwrap().speed = -0.01;
    cfg.numerics.duration = 10.0;
    cfg.metrics.window = Some([5.0, 10.0]);
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let m = run.coupled.unwrap();
    assert_eq!((m.bounce_fraction, m.rop_mean_m_per_h, m.wob_mean_n), (1.0, 0.0, 0.0), "{m:?}");
    let warned: Vec<&String> = run.warnings.iter().filter(|w| w.contains("never touched bottom")).collect();
    assert_eq!(warned.len(), 1, "{:?}", run.warnings);
    assert!(warned[0].contains("[5, 10] s") && warned[0].contains("hoist.speed"), "{}", warned[0]);
    // Drilling: no such warning.
    let run = solve(&settling("detournay"), &Never, &mut |_| {}).unwrap();
    assert!(run.warnings.iter().all(|w| !w.contains("never touched")), "{:?}", run.warnings);
}

#[test]
fn the_axial_snapshots_hold_the_steady_drilling_string() {
    // Steady drilling at 30 m/h: every cell moves down at the rate of penetration, the force at
    // the bottom cell is the weight on bit (half a cell above it: within 1 %), and the
    // compression falls from the bit up by the weight per metre rho A g (the viscous drag
    // damping_rate rho A v, 2.3 N/m, lowers it by less than 1 %).
    let mut cfg = settling("detournay");
    cfg.numerics.field_interval = 1.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let (nt, nz) = (run.field_t.len(), run.axial_z.len());
    assert_eq!((nt, run.axial_speed_field.len(), run.axial_force_field.len()), (61, nt * nz, nt * nz));
    assert!(nz > 1 && run.axial_z[0] > 0.0 && run.axial_z[nz - 1] < 200.0);
    let last = (nt - 1) * nz;
    let v = 30.0 / 3600.0;
    for k in 0..nz {
        // within the splitting's O(damping_rate dt) = 0.6 % (dt = 6.45e-4 s; the state after the
        // gravity kick alone would be g dt / 2 = 3.2 mm/s, 38 %, too fast)
        assert!((run.axial_speed_field[last + k] - v).abs() < 0.005 * v, "{k}: {}", run.axial_speed_field[last + k]);
    }
    let area = PI / 4.0 * (0.127f64.powi(2) - 0.108f64.powi(2));
    let per_metre = 8000.0 * area * 9.81;
    let (top, bottom) = (run.axial_force_field[last], run.axial_force_field[last + nz - 1]);
    assert!((bottom - 87_480.0).abs() < 0.01 * 87_480.0, "{bottom}");
    let slope = (bottom - top) / (run.axial_z[nz - 1] - run.axial_z[0]);
    assert!(slope < per_metre && slope > 0.99 * per_metre, "{slope} vs {per_metre}");
}
