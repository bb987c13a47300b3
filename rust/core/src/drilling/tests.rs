//! Tests of the drilling system against independently computed numbers (closed forms, the
//! frequency equations solved here by bisection, energies summed here from the outputs).

use std::f64::consts::PI;

use super::config::*;
use super::*;
use crate::interrupt::{CancelFlag, Never};
use crate::solution::Status;

const RPM: f64 = 60.0 / (2.0 * PI);
const G: f64 = 79.3e9;
const RHO: f64 = 7850.0;

fn section(length: f64, od: f64, id: f64) -> Section {
    Section { name: String::new(), length, outer_diameter: od, inner_diameter: id, ..Section::default() }
}

fn polar(od: f64, id: f64) -> f64 {
    PI / 32.0 * (od.powi(4) - id.powi(4))
}

/// A frictionless vertical string, ideal speed-controlled top at rest, bit off bottom.
/// A motor bandwidth, Hz, at which the top speed reaches the speed asked for within a step.
const IDEAL_MOTOR: f64 = 1e12;

fn frictionless(sections: Vec<Section>, cells: usize, duration: f64) -> DrillConfig {
    let mut cfg = DrillConfig { sections, ..DrillConfig::default() };
    cfg.well.md = None;
    cfg.well.inclination_deg = Inclination::Constant(0.0);
    cfg.friction.static_coefficient = 0.0;
    cfg.top_drive.controller.kind = ControllerKind::Speed;
    // an ideal speed source: no motor lag, no torque limit
    cfg.top_drive.motor_bandwidth = IDEAL_MOTOR;
    cfg.top_drive.torque_limit = f64::INFINITY;
    cfg.top_drive.rpm = 0.0;
    cfg.top_drive.ramp_time = 0.0;
    cfg.numerics.cells = cells;
    cfg.numerics.duration = duration;
    cfg.numerics.output_interval = 1e-4;
    cfg.numerics.field_interval = 0.0;
    cfg
}

/// Runs `cfg` from the cell speeds 0 and the torque `torque(z)`.
fn released(cfg: &DrillConfig, torque: impl Fn(f64) -> f64) -> DrillRun {
    let mut sim = Simulation::new(cfg).unwrap();
    let z = sim.grid().z.clone();
    let tau: Vec<f64> = z.iter().map(|&z| torque(z)).collect();
    sim.set_state(&vec![0.0; z.len()], &tau, 0.0, 0.0).unwrap();
    let run = sim.run(&Never, &mut |_| {});
    assert_eq!(run.status, Status::Success, "{}", run.message);
    run
}

/// Mean interval between upward zero crossings (linear interpolation).
fn crossing_period(t: &[f64], x: &[f64]) -> f64 {
    let mut times = Vec::new();
    for k in 1..t.len() {
        if x[k - 1] < 0.0 && x[k] >= 0.0 {
            times.push(t[k - 1] + (t[k] - t[k - 1]) * (-x[k - 1]) / (x[k] - x[k - 1]));
        }
    }
    if times.len() < 3 {
        let step = (t.len() / 40).max(1);
        for k in (0..t.len()).step_by(step) {
            eprintln!("{:8.4} {:12.6}", t[k], x[k]);
        }
    }
    assert!(times.len() >= 3, "{} crossings", times.len());
    (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64
}

/// First root of `f` on `(0, hi]` by a scan and bisection.
fn first_root(f: impl Fn(f64) -> f64, hi: f64) -> f64 {
    let n = 100_000;
    let mut lo = hi / n as f64;
    for k in 2..=n {
        let x = hi * k as f64 / n as f64;
        if f(lo).signum() != f(x).signum() {
            let (mut a, mut b) = (lo, x);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if f(m).signum() == f(a).signum() {
                    a = m
                } else {
                    b = m
                }
            }
            return 0.5 * (a + b);
        }
        lo = x;
    }
    panic!("no root")
}

#[test]
fn fixed_top_free_bit_frequencies_are_odd_quarter_waves() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let cfg = frictionless(vec![section(l, od, id)], 500, 8.0);
    for n in 1..=3 {
        let k = (2 * n - 1) as f64 * PI / (2.0 * l);
        let run = released(&cfg, |z| 1e3 * (k * z).cos());
        let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
        let exact = (2 * n - 1) as f64 * c / (4.0 * l);
        eprintln!("mode {n}: f = {f} Hz, exact {exact} Hz, rel {:.2e}", f / exact - 1.0);
        assert!((f / exact - 1.0).abs() < 1e-4, "mode {n}: {f} vs {exact}");
        assert!((run.stats.first_mode_hz / (c / (4.0 * l)) - 1.0).abs() < 1e-9);
        assert_eq!((run.stats.courant_min, run.stats.courant_max), (1.0, 1.0));
    }
}

#[test]
fn bha_inertia_frequency_solves_z_tan_z() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let i_string = RHO * polar(od, id) * l;
    for ratio in [1.0, 0.25] {
        let mut cfg = frictionless(vec![section(l, od, id)], 500, 40.0);
        cfg.bit.bha_inertia = i_string / ratio;
        // z tan z = I_string / I_BHA, z = w L / c
        let z = first_root(|z: f64| z * z.tan() - ratio, PI / 2.0 - 1e-12);
        let w = z * c / l;
        let run = released(&cfg, |x| 1e3 * (w / c * x).cos());
        let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
        let exact = w / (2.0 * PI);
        eprintln!("I_s/I_b = {ratio}: z = {z}, f = {f} Hz, exact {exact} Hz, rel {:.2e}", f / exact - 1.0);
        assert!((f / exact - 1.0).abs() < 2e-3, "{f} vs {exact}");
        assert!((run.stats.first_mode_hz / exact - 1.0).abs() < 1e-9, "{}", run.stats.first_mode_hz);
    }
}

#[test]
fn two_section_string_matches_its_frequency_equation() {
    // Travel times 3:1 so that 400 cells give Courant number 1 in both sections.
    let (od1, id1, od2, id2) = (0.14, 0.1, 0.2, 0.07);
    let c1 = (G / RHO).sqrt();
    let rho2 = 2.0 * RHO;
    let c2 = (G / rho2).sqrt();
    let (l1, t1) = (1500.0, 1500.0 / c1);
    let t2 = t1 / 3.0;
    let l2 = c2 * t2;
    let z1 = polar(od1, id1) * (G * RHO).sqrt();
    let z2 = polar(od2, id2) * (G * rho2).sqrt();
    let mut lower = section(l2, od2, id2);
    lower.density = rho2;
    let cfg = frictionless(vec![section(l1, od1, id1), lower], 400, 40.0);
    // Fixed top, free end: cos(w t1) cos(w t2) - (Z2 / Z1) sin(w t1) sin(w t2) = 0.
    let w = first_root(|w: f64| (w * t1).cos() * (w * t2).cos() - z2 / z1 * (w * t1).sin() * (w * t2).sin(), 20.0);
    // The mode: q = G J theta_z with theta(0) = 0, q(0) = 1, through the junction.
    let theta1 = (w * t1).sin() / (z1 * w);
    let q1 = (w * t1).cos();
    let mode = move |z: f64| {
        if z <= l1 {
            1e3 * (w * z / c1).cos()
        } else {
            let x = (z - l1) / c2;
            1e3 * (-z2 * w * theta1 * (w * x).sin() + q1 * (w * x).cos())
        }
    };
    let run = released(&cfg, mode);
    assert_eq!((run.stats.courant_min, run.stats.courant_max), (1.0, 1.0));
    let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
    let exact = w / (2.0 * PI);
    eprintln!("two sections (Z2/Z1 = {:.3}): f = {f} Hz, exact {exact} Hz, rel {:.2e}", z2 / z1, f / exact - 1.0);
    assert!((f / exact - 1.0).abs() < 1e-4, "{f} vs {exact}");
    assert!((run.stats.first_mode_hz / exact - 1.0).abs() < 1e-9);
    // No energy is made or lost at the junction (Courant 1, no friction, no damping).
    assert!(run.energy.numerical_loss.abs() < 1e-12 * run.energy.initial, "{:?}", run.energy);
    assert!(((run.energy.kinetic + run.energy.elastic) / run.energy.initial - 1.0).abs() < 1e-12);
}

#[test]
fn top_speed_step_gives_a_square_wave_at_the_bit() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let mut cfg = frictionless(vec![section(l, od, id)], 200, 3.0);
    cfg.top_drive.rpm = 60.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let (t_travel, dt) = (l / c, run.stats.dt);
    let mut checked = 0;
    for (t, rpm) in run.t.iter().zip(&run.bit_rpm) {
        let phase = t / t_travel; // 0 for phase in (0, 1), 120 rpm in (1, 3), 0 in (3, 5), ...
        let nearest_odd = 2.0 * ((phase - 1.0) / 2.0).round() + 1.0;
        if (phase - nearest_odd).abs() * t_travel < 3.0 * dt {
            continue;
        }
        let expected = if phase < 1.0 || ((phase - 1.0) / 2.0).floor() as i64 % 2 == 1 { 0.0 } else { 120.0 };
        assert!((rpm - expected).abs() < 1e-9, "t = {t}: {rpm} rpm, expected {expected}");
        checked += 1;
    }
    assert!(checked > run.t.len() * 9 / 10);
    // The period of the bit speed is 4 L / c.
    let centred: Vec<f64> = run.bit_rpm.iter().map(|r| r - 60.0).collect();
    let period = crossing_period(&run.t, &centred);
    assert!((period / (4.0 * t_travel) - 1.0).abs() < 1e-3, "{period} vs {}", 4.0 * t_travel);
}

/// String energy summed here from the snapshot `k` of a run: `sum h (rho J w^2 + tau^2 / (G J)) / 2`.
fn field_energy(run: &DrillRun, k: usize, h: f64, j: f64) -> f64 {
    let nz = run.z.len();
    (0..nz)
        .map(|i| {
            let w = run.omega_field[k * nz + i] / RPM;
            let tau = run.torque_field[k * nz + i];
            0.5 * h * (RHO * j * w * w + tau * tau / (G * j))
        })
        .sum()
}

#[test]
fn z_torque_absorbs_the_incident_wave() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let (j, cells) = (polar(od, id), 500);
    let z = j * (G * RHO).sqrt();
    // (z_factor, torque high-pass time, expected reflected energy fraction ((1 - z) / (1 + z))^2)
    for (z_factor, highpass, expected) in [(1.0, 20.0 / (2.0 * PI), 0.0), (1.0, 1e12, 0.0), (3.0, 1e12, 0.25)] {
        let mut cfg = frictionless(vec![section(l, od, id)], cells, 0.8 * l / c);
        cfg.top_drive.controller.kind = ControllerKind::ZTorque;
        cfg.top_drive.controller.z_factor = z_factor;
        cfg.top_drive.controller.torque_highpass_time = highpass;
        cfg.numerics.field_interval = cfg.numerics.duration;
        // An upward pulse: alpha = 0, beta = B exp(-((z - L/4) / (L/40))^2): omega = beta/2, tau = -Z beta/2.
        let pulse = |x: f64| 0.5 * (-((x - 0.25 * l) / (0.025 * l)).powi(2)).exp();
        let mut sim = Simulation::new(&cfg).unwrap();
        let zc = sim.grid().z.clone();
        let w: Vec<f64> = zc.iter().map(|&x| pulse(x)).collect();
        let tau: Vec<f64> = w.iter().map(|w| -z * w).collect();
        sim.set_state(&w, &tau, 0.0, 0.0).unwrap();
        let run = sim.run(&Never, &mut |_| {});
        assert_eq!(run.field_t.len(), 2);
        let h = l / cells as f64;
        let ratio = field_energy(&run, 1, h, j) / field_energy(&run, 0, h, j);
        eprintln!(
            "z_factor {z_factor}, high-pass {highpass} s: reflected energy fraction {ratio:.3e}, expected {expected}"
        );
        if expected == 0.0 {
            // The slow-torque feedback (the high-pass) reflects a little of the pulse's mean.
            let bound = if highpass < 1e3 { 1e-3 } else { 1e-12 };
            assert!(ratio < bound, "reflection {ratio}");
        } else {
            assert!((ratio / expected - 1.0).abs() < 0.02, "{ratio}");
        }
    }
}

#[test]
fn break_off_torque_is_the_integral_of_the_friction_limit() {
    let (od, id) = (0.146529, 0.123024);
    let area = PI / 4.0 * (od * od - id * id);
    let (mu, g) = (0.3, 9.81);
    let per_sin = mu * g * RHO * area * od / 2.0;
    // Constant 30 degrees.
    let mut cfg = DrillConfig { sections: vec![section(2500.0, od, id)], ..DrillConfig::default() };
    cfg.friction.contact = Contact::Weight;
    cfg.well.md = None;
    cfg.well.inclination_deg = Inclination::Constant(30.0);
    let exact = per_sin * 0.5 * 2500.0;
    let got = breakoff_torque(&cfg).unwrap();
    assert!((got / exact - 1.0).abs() < 1e-12, "{got} vs {exact}");
    // Well B survey: 0 to 500 m vertical, linear to 60 deg at 1600 m, 60 deg beyond.
    let mut cfg = DrillConfig { sections: vec![section(2500.0, od, id)], ..DrillConfig::default() };
    cfg.friction.contact = Contact::Weight;
    let b = (PI / 3.0) / 1100.0;
    let exact = per_sin * ((1.0 - (PI / 3.0).cos()) / b + (PI / 3.0).sin() * 900.0);
    let got = breakoff_torque(&cfg).unwrap();
    eprintln!("Well B survey: break-off {got} N m, exact {exact}, rel {:.2e}", got / exact - 1.0);
    assert!((got / exact - 1.0).abs() < 1e-9, "{got} vs {exact}");
    // Two sections with mud: each its own buoyed weight and lever arm.
    let mut cfg = DrillConfig { sections: vec![section(2000.0, od, id), section(500.0, 0.2, 0.08)], ..cfg };
    cfg.well.mud_density = 1200.0;
    let a2 = PI / 4.0 * (0.04 - 0.0064);
    let lower = mu * g * (RHO - 1200.0) * a2 * 0.1 * (PI / 3.0).sin() * 500.0;
    let upper = mu * g * (RHO - 1200.0) * area * od / 2.0 * ((1.0 - (PI / 3.0).cos()) / b + (PI / 3.0).sin() * 400.0);
    let got = breakoff_torque(&cfg).unwrap();
    assert!((got / (upper + lower) - 1.0).abs() < 1e-9, "{got} vs {}", upper + lower);
    // The profile's cumulative torque at the top cell is the break-off torque to cell accuracy.
    let profile = friction_profile(&cfg).unwrap();
    assert_eq!(profile.breakoff_torque, got);
    assert!((profile.cumulative[0] / got - 1.0).abs() < 1e-3, "{} vs {got}", profile.cumulative[0]);
    assert!(profile.limit_per_m[..100].iter().all(|&x| x == 0.0)); // vertical top
}

/// A loaded case: two sections with Courant numbers < 1, friction, damping, PI, bit on bottom
/// with a BHA inertia.
fn loaded(model: FrictionModel) -> DrillConfig {
    let mut collar = section(230.0, 0.2, 0.07);
    collar.shear_modulus = 67e9;
    let mut cfg = DrillConfig { sections: vec![section(2270.0, 0.146529, 0.123024), collar], ..DrillConfig::default() };
    cfg.friction.model = model;
    cfg.friction.contact = Contact::Weight;
    cfg.damping_rate = 0.05;
    cfg.bit = Bit { on_bottom: true, weight_on_bit: 5e4, bha_inertia: 50.0, ..Bit::default() };
    cfg.top_drive.torque_limit = 30e3;
    cfg.numerics.cells = 700;
    cfg.numerics.duration = 30.0;
    cfg
}

#[test]
fn energy_balance_closes() {
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let cfg = loaded(model);
        let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
        let e = run.energy;
        eprintln!("{model:?}: {e:?} courant {}..{}", run.stats.courant_min, run.stats.courant_max);
        assert!(run.stats.courant_min < 1.0);
        assert!(e.balance_error.abs() < 1e-11, "{e:?}");
        assert!(e.motor_work > 0.0 && e.friction_loss > 0.0 && e.damping_loss > 0.0 && e.bit_loss > 0.0);
        assert!(e.numerical_loss > 0.0 && e.numerical_loss < 0.05 * e.motor_work, "{e:?}");
        // The balance summed here: motor work = change + losses.
        let change = e.kinetic + e.elastic + e.top_drive + e.bha - e.initial;
        let losses = e.friction_loss + e.damping_loss + e.bit_loss + e.numerical_loss;
        assert!((e.motor_work - change - losses).abs() < 1e-10 * e.motor_work);
        assert!(run.motor_torque.iter().all(|m| m.abs() <= 30e3));
    }
    // Courant 1, no friction: no upwind dissipation; only the top drive's implicit Euler.
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 200, 5.0);
    cfg.top_drive.controller.kind = ControllerKind::Pi;
    cfg.top_drive.rpm = 60.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let e = run.energy;
    eprintln!("uniform, Courant 1, PI: {e:?}");
    assert!(e.balance_error.abs() < 1e-12);
    assert_eq!(e.upwind_loss, 0.0);
    assert!(e.inertia_loss < 0.02 * e.motor_work, "{e:?}");
}

#[test]
fn regularised_and_set_valued_friction_differ_measurably() {
    let mut results = Vec::new();
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let mut cfg = DrillConfig::default();
        cfg.friction.model = model;
        let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
        let m = run.metrics.unwrap();
        eprintln!(
            "{model:?}: SSI {:.3}, stuck {:.3}, bit rpm {:.1}..{:.1} mean {:.2}, motor torque {:.0}..{:.0}, period {:.3} s, friction loss {:.4e} J",
            m.ssi, m.stuck_fraction, m.bit_rpm_min, m.bit_rpm_max, m.bit_rpm_mean, m.motor_torque_min_nm, m.motor_torque_max_nm, m.period_s, run.energy.friction_loss
        );
        results.push(m);
    }
    // Both run to the end near the setpoint on average.
    for m in &results {
        assert!((m.bit_rpm_mean - 40.0).abs() < 5.0, "{m:?}");
    }
}

#[test]
fn a_torque_below_break_off_leaves_the_lower_string_exactly_at_rest() {
    let mut cfg = DrillConfig { sections: vec![section(2500.0, 0.146529, 0.123024)], ..DrillConfig::default() };
    let breakoff = breakoff_torque(&cfg).unwrap();
    let limit = 0.25 * breakoff;
    cfg.top_drive.torque_limit = limit;
    // saturated: 4.2 rad/s of error times kp is 80 times the limit (and kp within the stable
    // gains of the sampled loop, below 2 I / control_interval)
    cfg.top_drive.controller.kp = 5e5;
    cfg.bit = Bit { on_bottom: true, weight_on_bit: 1e5, ..Bit::default() };
    cfg.numerics.duration = 20.0;
    cfg.numerics.field_interval = 0.1;
    let profile = friction_profile(&cfg).unwrap();
    // Below the depth where the static friction above holds twice the motor torque, nothing moves.
    let h = 2500.0 / profile.z.len() as f64;
    let mut held = 0.0;
    let first = profile
        .limit_per_m
        .iter()
        .position(|l| {
            held += l * h;
            held > 2.0 * limit
        })
        .unwrap();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(run.bit_rpm.iter().all(|&w| w == 0.0), "bit moved");
    let nz = run.z.len();
    for k in 0..run.field_t.len() {
        let row = &run.omega_field[k * nz..(k + 1) * nz];
        assert!(row[first..].iter().all(|&w| w == 0.0), "moved below {} m at t = {}", profile.z[first], run.field_t[k]);
    }
    assert!(run.motor_torque.iter().all(|m| m.abs() <= limit));
    eprintln!(
        "held below {:.0} m of {} m; top moved up to {:.2} rpm",
        profile.z[first],
        2500,
        run.surface_rpm.iter().fold(0.0f64, |a, b| a.max(*b))
    );
}

#[test]
fn bad_configurations_name_the_field() {
    let base = r#""sections": [{"length": 1000, "outer_diameter": 0.14, "inner_diameter": 0.1}]"#;
    let field = |extra: &str| {
        let json = format!("{{{base}{extra}}}");
        match DrillConfig::from_json(&json).and_then(|c| c.validate()) {
            Err(e) => e.field().to_string(),
            Ok(()) => "ok".into(),
        }
    };
    assert_eq!(field(""), "ok");
    assert_eq!(field(r#", "numerics": {"cels": 10}"#), "numerics.cels");
    assert_eq!(field(r#", "numerics": {"cells": 0}"#), "numerics.cells");
    assert_eq!(field(r#", "numerics": {"cells": 1.5}"#), "numerics.cells");
    assert_eq!(field(r#", "numerics": {"cells": 2000, "max_cells": 1000}"#), "numerics.cells");
    assert_eq!(field(r#", "numerics": {"duration": -1}"#), "numerics.duration");
    assert_eq!(field(r#", "numerics": {"output_interval": 1e-9}"#), "numerics.output_interval");
    assert_eq!(field(r#", "numerics": {"field_interval": 1e-4, "cells": 100000}"#), "numerics.field_interval");
    assert_eq!(field(r#", "top_drive": {"inertia": 0}"#), "top_drive.inertia");
    assert_eq!(field(r#", "top_drive": {"controller": {"type": "fuzzy"}}"#), "top_drive.controller.type");
    assert_eq!(field(r#", "top_drive": {"controller": {"kp": "a"}}"#), "top_drive.controller.kp");
    assert_eq!(field(r#", "top_drive": {"steps": [[1, 2], [0.5, 3]]}"#), "top_drive.steps[1][0]");
    assert_eq!(field(r#", "top_drive": {"steps": [[1]]}"#), "top_drive.steps[0]");
    assert_eq!(field(r#", "well": {"inclination_deg": [0, 200, 3, 4]}"#), "well.inclination_deg[1]");
    assert_eq!(field(r#", "well": {"md": [0, 10, 5, 20]}"#), "well.md[2]");
    assert_eq!(field(r#", "well": {"md": [0, 10]}"#), "well.inclination_deg");
    assert_eq!(field(r#", "well": {"inclination_deg": 30}"#), "ok");
    assert_eq!(field(r#", "well": {"mud_density": 9000}"#), "well.mud_density");
    assert_eq!(field(r#", "friction": {"model": "smooth"}"#), "friction.model");
    assert_eq!(field(r#", "friction": {"kinetic_ratio": 1.5}"#), "friction.kinetic_ratio");
    assert_eq!(field(r#", "bit": {"mu_kinetic": 0.9}"#), "bit.mu_kinetic");
    assert_eq!(field(r#", "metrics": {"window": [5, 1]}"#), "metrics.window");
    let sections = |s: &str| {
        let json =
            format!(r#"{{"sections": [{{"length": 1000, "outer_diameter": 0.14, "inner_diameter": 0.1}}, {s}]}}"#);
        DrillConfig::from_json(&json).and_then(|c| c.validate()).map_err(|e| e.field().to_string()).err()
    };
    assert_eq!(sections(r#"{"length": 10, "outer_diameter": 0.1}"#).unwrap(), "sections[1].inner_diameter");
    assert_eq!(
        sections(r#"{"length": 10, "outer_diameter": 0.1, "inner_diameter": 0.2}"#).unwrap(),
        "sections[1].inner_diameter"
    );
    assert_eq!(
        sections(r#"{"length": 10, "outer_diameter": 0.1, "inner_diameter": 0, "polar_moment": -1}"#).unwrap(),
        "sections[1].polar_moment"
    );
    assert_eq!(
        sections(r#"{"length": 10, "outer_diameter": 0.1, "inner_diameter": 0, "colour": 1}"#).unwrap(),
        "sections[1].colour"
    );
    assert_eq!(DrillConfig::from_json("{}").unwrap_err().field(), "sections");
    assert_eq!(DrillConfig::from_json("[1]").unwrap_err().field(), "config");
    assert_eq!(DrillConfig::from_json("{").unwrap_err().field(), "config");
    assert_eq!(DrillConfig::from_json(r#"{"sections": []}"#).unwrap().validate().unwrap_err().field(), "sections");
    let cfg = DrillConfig { damping_rate: 1e9, ..DrillConfig::default() };
    assert_eq!(Simulation::new(&cfg).err().unwrap().field(), "damping_rate");
}

#[test]
fn the_bit_is_given_by_its_radius_or_its_diameter_not_both() {
    let pipe = r#"{"length": 1000, "outer_diameter": 0.127, "inner_diameter": 0.1}"#;
    let parse = |bit: &str| DrillConfig::from_json(&format!(r#"{{"sections": [{pipe}], "bit": {bit}}}"#));
    let cfg = parse(r#"{"diameter": 0.2159}"#).unwrap();
    assert_eq!((cfg.bit.radius, cfg.bit.diameter), (0.10795, None));
    cfg.validate().unwrap();
    let e = parse(r#"{"radius": 0.1, "diameter": 0.2}"#).unwrap_err();
    assert_eq!(e.field(), "bit.diameter");
    assert!(e.to_string().contains("both bit.radius and bit.diameter"), "{e}");
    assert_eq!(parse(r#"{"diameter": -0.2}"#).unwrap_err().field(), "bit.diameter");
    assert_eq!(parse(r#"{"radius": 0.1, "diameter": null}"#).unwrap().bit.radius, 0.1);
    // an override of one replaces the other; both at once are refused
    let base = cfg.to_json();
    let set = |pairs: &str| override_json(&base, pairs, "--set", true).map(|c| c.bit.radius);
    assert_eq!(set(r#"[["bit.diameter", 0.3]]"#).unwrap(), 0.15);
    assert_eq!(set(r#"[["bit", {"diameter": 0.25}]]"#).unwrap(), 0.125);
    assert_eq!(set(r#"[["bit.radius", 0.2]]"#).unwrap(), 0.2);
    assert_eq!(set(r#"[["bit.radius", 0.2], ["bit.diameter", 0.3]]"#).unwrap_err().field(), "bit.diameter");
    // a configuration built in Rust with both, disagreeing
    let mut both = DrillConfig::default();
    both.bit.diameter = Some(0.3);
    assert_eq!(both.validate().unwrap_err().field(), "bit.diameter");
}

#[test]
fn defaults_round_trip_and_well_b_example_parses() {
    let cfg = DrillConfig::default();
    let back = DrillConfig::from_json(&cfg.to_json()).unwrap();
    assert_eq!(back, cfg);
    cfg.validate().unwrap();
    let well_b = r#"{
      "sections": [
        {"name": "drill pipe", "length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
         "shear_modulus": 61e9, "density": 7850.0},
        {"name": "BHA (Aarsnes-Shor average)", "length": 230.0, "outer_diameter": 0.19425788212135248, "inner_diameter": 0.0,
         "shear_modulus": 61e9, "density": 7850.0,
         "polar_moment": 5.169666634679985e-4, "area": 0.02286618845760419}],
      "damping_rate": 0.08333333333333334,
      "friction": {"contact": "weight"},
      "top_drive": {"inertia": 2900.0, "rpm": 40.0, "ramp_time": 1.0, "controller": {"type": "pi", "kp": 38e3, "ki": 100e3},
                    "control_interval": 0.01},
      "friction": {"static": 0.3, "kinetic_ratio": 0.65, "stick_speed": 1.5},
      "numerics": {"cells": 1000, "duration": 60.0}
    }"#;
    let cfg = DrillConfig::from_json(well_b).unwrap();
    cfg.validate().unwrap();
    let grid = Grid::new(&cfg).unwrap();
    // Both sections at the pipe wave speed: 908 + 92 cells, Courant 1 (their 1000 cells, 908/92).
    assert_eq!(grid.counts, vec![908, 92]);
    // The collar impedance is theirs: Jc Gc / c_t with their Jc (extra pi) and Gc = 67e9.
    let c_t = (61e9f64 / 7850.0).sqrt();
    let jc = 4.7067114136638673e-4;
    assert!((grid.props[1].impedance / (jc * 67e9 / c_t) - 1.0).abs() < 1e-12);
}

#[test]
fn interrupt_and_progress() {
    let cfg = DrillConfig::default();
    let flag = CancelFlag::new();
    flag.cancel();
    let run = solve(&cfg, &flag, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Interrupted);
    assert!(run.t.len() < 10);
    let mut cfg = DrillConfig::default();
    cfg.numerics.duration = 2.0;
    let mut seen = Vec::new();
    let run = solve(&cfg, &Never, &mut |f| seen.push(f)).unwrap();
    assert_eq!(run.status, Status::Success);
    assert!(seen.windows(2).all(|w| w[1] >= w[0]) && *seen.last().unwrap() == 1.0 && seen.len() > 10);
    assert_eq!(run.t.len(), 201);
    assert!((run.t[200] - 2.0).abs() < 1e-12);
    assert_eq!(run.field_t.len(), 5);
    assert_eq!(run.omega_field.len(), 5 * run.z.len());
}

#[test]
fn soft_torque_gains_from_impedance_and_first_mode() {
    let mut cfg = DrillConfig::default();
    cfg.top_drive.controller.kind = ControllerKind::SoftTorque;
    cfg.numerics.duration = 1.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let p = &cfg.sections[0];
    let z = polar(p.outer_diameter, p.inner_diameter) * (p.shear_modulus * p.density).sqrt();
    let w = 2.0 * PI * run.stats.first_mode_hz;
    assert_eq!(cfg.top_drive.controller.z_factor, 4.0);
    assert!((run.stats.kp / (4.0 * z) - 1.0).abs() < 1e-12);
    assert!((run.stats.ki / (w * w * 2900.0) - 1.0).abs() < 1e-12);
    // Uniform string without BHA: the first mode is c / (4 L).
    let c = (p.shear_modulus / p.density).sqrt();
    assert!((run.stats.first_mode_hz / (c / (4.0 * p.length)) - 1.0).abs() < 1e-9);
}

#[test]
fn setpoint_ramps_and_steps() {
    // Ideal speed control: the top speed is the setpoint, a first-order approach of the target
    // (rpm until the first step, then each step's) with the ramp time constant.
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 100, 6.0);
    cfg.top_drive.rpm = 40.0;
    cfg.top_drive.ramp_time = 0.5;
    cfg.top_drive.steps = vec![[3.0, 60.0], [4.5, 0.0]];
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let dt = run.stats.dt;
    let exact = |t: f64| {
        let at3 = 40.0 * (1.0 - (-3.0f64 / 0.5).exp());
        let at45 = 60.0 + (at3 - 60.0) * (-1.5f64 / 0.5).exp();
        if t <= 3.0 {
            40.0 * (1.0 - (-t / 0.5).exp())
        } else if t <= 4.5 {
            60.0 + (at3 - 60.0) * (-(t - 3.0) / 0.5).exp()
        } else {
            at45 * (-(t - 4.5) / 0.5).exp()
        }
    };
    for (t, rpm) in run.t.iter().zip(&run.surface_rpm) {
        // The target changes at the first step end at or after the step time.
        if (t - 3.0).abs() < 2.0 * dt || (t - 4.5).abs() < 2.0 * dt {
            continue;
        }
        assert!((rpm - exact(*t)).abs() < 0.2, "t = {t}: {rpm} vs {}", exact(*t));
    }
}

#[test]
fn bit_on_bottom_sticks_and_slips_with_positive_bit_work() {
    for bha in [0.0, 100.0] {
        let mut cfg = loaded(FrictionModel::SetValued);
        cfg.bit = Bit { on_bottom: true, weight_on_bit: 1e5, bha_inertia: bha, ..Bit::default() };
        cfg.top_drive.torque_limit = f64::INFINITY;
        let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
        let (m, e) = (run.metrics.unwrap(), run.energy);
        eprintln!(
            "on bottom, BHA {bha}: SSI {:.3}, stuck {:.3}, bit rpm {:.1}..{:.1}, bit loss {:.4e} J, balance {:.1e}",
            m.ssi, m.stuck_fraction, m.bit_rpm_min, m.bit_rpm_max, e.bit_loss, e.balance_error
        );
        assert_eq!(run.status, Status::Success);
        assert!(e.bit_loss > 0.0 && e.balance_error.abs() < 1e-11, "{e:?}");
        // The bit never turns backwards (it sticks instead), its torque at most W r mu_s.
        assert!(m.bit_rpm_min >= -1e-9, "{}", m.bit_rpm_min);
        assert!(run.bit_torque.iter().all(|t| t.abs() <= 1e5 * 0.1 * 0.8 * (1.0 + 1e-12)));
    }
}

#[test]
fn overflow_ends_with_a_status_not_a_panic() {
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 50, 1.0);
    cfg.numerics.field_interval = 0.1;
    let mut sim = Simulation::new(&cfg).unwrap();
    let n = sim.grid().cells();
    sim.set_state(&vec![1e307; n], &vec![1e308; n], 0.0, 0.0).unwrap();
    let run = sim.run(&Never, &mut |_| {});
    assert_eq!(run.status, Status::NonFinite, "{}", run.message);
    assert!(!run.message.is_empty());
    assert!(run.bit_rpm.iter().chain(&run.omega_field).chain(&run.torque_field).all(|v| v.is_finite()));
    assert_eq!(run.omega_field.len(), run.field_t.len() * n);
}

#[test]
fn well_b_agrees_with_the_published_model() {
    // Aarsnes & Shor's Well B (MAIN.m, parameters_WellB.m, MD 2500 m, 40 rpm, 60 s) in the form
    // with the same continuum equations as their scheme (collar: their Jc with its extra pi,
    // Ac, Gc = 67 GPa, density rho Gc / Gp so that its wave speed is the pipe's; damping rate
    // 2 kt dt_sub). Reference: their code run in GNU Octave 7.3 (tests/data/aarsnes_shor/
    // reference.json), metrics over 30..60 s.
    let json = r#"{
      "sections": [
        {"length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
         "shear_modulus": 61e9, "density": 7850.0},
        {"length": 230.0, "outer_diameter": 0.19425788212135248, "inner_diameter": 0.09285466808235807,
         "shear_modulus": 67e9, "density": 8622.131147540984,
         "polar_moment": 4.7067114136638673e-4, "area": 0.02286618845760419}],
      "damping_rate": 0.08333333333333334,
      "friction": {"contact": "weight"},
      "numerics": {"cells": 1000, "duration": 60.0, "field_interval": 0}
    }"#;
    let cfg = DrillConfig::from_json(json).unwrap();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let m = run.metrics.unwrap();
    let (torque_min, torque_max, period, rpm_max, rpm_mean) = (6132.67, 24925.16, 10.0047, 120.325, 39.735);
    eprintln!(
        "Well B: motor torque {:.0}..{:.0} N m (Octave {torque_min:.0}..{torque_max:.0}), period {:.3} s ({period}), \
         bit rpm max {:.1} ({rpm_max}), mean {:.2} ({rpm_mean}), balance {:.1e}",
        m.motor_torque_min_nm,
        m.motor_torque_max_nm,
        m.period_s,
        m.bit_rpm_max,
        m.bit_rpm_mean,
        run.energy.balance_error
    );
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    assert!(rel(m.motor_torque_min_nm, torque_min) < 0.05 && rel(m.motor_torque_max_nm, torque_max) < 0.02);
    assert!(
        rel(m.period_s, period) < 0.02 && rel(m.bit_rpm_max, rpm_max) < 0.02 && rel(m.bit_rpm_mean, rpm_mean) < 0.01
    );
}

#[test]
fn a_short_section_gets_a_cell_and_a_stable_step() {
    // A 1 m sub between pipes: shorter than one cell of a 100-cell string.
    let sections = vec![section(500.0, 0.14, 0.1), section(1.0, 0.2, 0.07), section(500.0, 0.14, 0.1)];
    let mut cfg = frictionless(sections, 100, 2.0);
    cfg.top_drive.rpm = 30.0;
    let grid = Grid::new(&cfg).unwrap();
    assert_eq!(grid.counts[1], 1);
    assert!(grid.courant.iter().all(|&c| c > 0.0 && c <= 1.0), "{:?}", grid.courant);
    assert!(grid.cells() > 100);
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success);
    assert!(run.energy.balance_error.abs() < 1e-12);
    cfg.numerics.max_cells = 200;
    assert_eq!(cfg.validate().unwrap_err().field(), "numerics.cells");
}

#[test]
fn min_cycle_torque_is_the_published_tau_min_and_counts_the_bit() {
    // Aarsnes & Shor's MAIN.m, Well B: tauMin = tauMax(1) (1 - 2 (1 - fRat)).
    let (tau_max, f_rat) = (19531.0174047259, 0.65);
    let published = 5859.305221417771;
    let got = min_cycle_torque_from(tau_max, f_rat, 0.0, 0.0);
    assert!((got / published - 1.0).abs() < 1e-12, "{got} vs {published}");
    // Static and kinetic alike: no drop, the minimum is the torque itself.
    assert_eq!(min_cycle_torque_from(1000.0, 1.0, 50.0, 50.0), 1050.0);
    // A configuration: the wall's kinetic ratio, and the bit's W r mu_s, W r mu_k when on bottom.
    let mut cfg = DrillConfig { sections: vec![section(2500.0, 0.127, 0.1086)], ..DrillConfig::default() };
    let b = breakoff_torque(&cfg).unwrap();
    let r = cfg.friction.kinetic_ratio;
    assert!((min_cycle_torque(&cfg, b) - b * (1.0 - 2.0 * (1.0 - r))).abs() < 1e-9 * b);
    cfg.bit.on_bottom = true;
    cfg.bit.weight_on_bit = 1e5;
    let wr = 1e5 * cfg.bit.radius;
    let want = 2.0 * (r * b + wr * cfg.bit.mu_kinetic) - (b + wr * cfg.bit.mu_static);
    assert!((min_cycle_torque(&cfg, b) - want).abs() < 1e-9 * b);
    // The run reports it.
    cfg.numerics.duration = 0.05;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.min_cycle_torque, min_cycle_torque(&cfg, run.breakoff_torque));
}

// ---------------------------------------------------------------- the consistent nonlinearity

/// `k2 = G I_p`, `k5 = M J4 / 2` of a solid rod of diameter `d` (computed here:
/// `I_p = pi R^4 / 2`, `J4 = pi R^6 / 3`, `M = 2 G (1 - nu) / (1 - 2 nu)`).
fn rod_coefficients(d: f64, g: f64, nu: f64) -> (f64, f64) {
    let r = d / 2.0;
    let m = 2.0 * g * (1.0 - nu) / (1.0 - 2.0 * nu);
    (g * PI * r.powi(4) / 2.0, m * PI * r.powi(6) / 3.0 / 2.0)
}

/// A solid rod of an almost incompressible material (`M / G ~ 500`), so that the hardening
/// is resolvable at moderate twists.
fn soft_rod(length: f64) -> Section {
    Section { poisson_ratio: 0.499, ..section(length, 0.1, 0.0) }
}

#[test]
fn linear_runs_are_unchanged() {
    // Well B and the loaded case of `energy_balance_closes` with the default (linear) law:
    // numbers recorded before the consistent law was added, digit for digit.
    let json = r#"{
      "sections": [
        {"length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
         "shear_modulus": 61e9, "density": 7850.0},
        {"length": 230.0, "outer_diameter": 0.19425788212135248, "inner_diameter": 0.09285466808235807,
         "shear_modulus": 67e9, "density": 8622.131147540984,
         "polar_moment": 4.7067114136638673e-4, "area": 0.02286618845760419}],
      "damping_rate": 0.08333333333333334,
      "friction": {"contact": "weight"},
      "numerics": {"cells": 1000, "duration": 20.0, "field_interval": 0}
    }"#;
    let cfg = DrillConfig::from_json(json).unwrap();
    assert_eq!(cfg.nonlinearity, Nonlinearity::Linear);
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let sum = |x: &[f64]| x.iter().sum::<f64>();
    let got = [sum(&run.bit_rpm), sum(&run.motor_torque), run.energy.motor_work, run.energy.friction_loss];
    eprintln!("Well B 20 s: {got:?}");
    assert_eq!(got, WELL_B_FINGERPRINT);
    let mut cfg = loaded(FrictionModel::SetValued);
    cfg.numerics.duration = 10.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let got = [sum(&run.bit_rpm), sum(&run.motor_torque), run.energy.motor_work, run.energy.upwind_loss];
    eprintln!("loaded 10 s: {got:?}");
    assert_eq!(got, LOADED_FINGERPRINT);
}

// The bit speed's sum changed (52937.993822556935 before) when the end below a stuck last cell
// was reported at rest instead of creeping; the motor torque and the energies, the dynamics, did not.
const WELL_B_FINGERPRINT: [f64; 4] = [52918.07308358484, 27686614.84156269, 1122349.7601874035, 782097.2279241397];
const LOADED_FINGERPRINT: [f64; 4] = [22612.652434214873, 13708014.63578681, 536085.6656196791, 27.580043507515068];

#[test]
fn consistent_with_k5_zero_is_the_linear_scheme() {
    // The loaded case (two sections at Courant numbers < 1, friction with sticking, damping,
    // PI with a torque limit, bit on bottom with a BHA): the Godunov scheme with k5 = 0 is the
    // upwind scheme of the invariants, up to rounding.
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let mut cfg = loaded(model);
        cfg.numerics.duration = 4.0;
        let linear = solve(&cfg, &Never, &mut |_| {}).unwrap();
        cfg.nonlinearity = Nonlinearity::Consistent;
        cfg.numerics.max_shear_strain = 1e-12; // the step of the linear speed
        let mut sim = Simulation::new(&cfg).unwrap();
        assert_eq!(sim.grid().counts, Grid::new(&loaded(model)).unwrap().counts);
        sim.zero_quartic();
        let godunov = sim.run(&Never, &mut |_| {});
        assert_eq!(godunov.status, Status::Success, "{}", godunov.message);
        let diff = |a: &[f64], b: &[f64]| {
            let scale = a.iter().fold(f64::MIN_POSITIVE, |m: f64, x| m.max(x.abs()));
            a.iter().zip(b).fold(0.0, |m: f64, (x, y)| m.max((x - y).abs())) / scale
        };
        let d = [
            diff(&linear.bit_rpm, &godunov.bit_rpm),
            diff(&linear.surface_rpm, &godunov.surface_rpm),
            diff(&linear.motor_torque, &godunov.motor_torque),
            diff(&linear.omega_field, &godunov.omega_field),
            diff(&linear.torque_field, &godunov.torque_field),
        ];
        let (a, b) = (linear.energy, godunov.energy);
        eprintln!("{model:?}: relative differences {d:?}; upwind loss {} vs {}", a.upwind_loss, b.upwind_loss);
        assert!(d.iter().all(|&x| x < 1e-9), "{d:?}");
        assert!((a.upwind_loss / b.upwind_loss - 1.0).abs() < 1e-6, "{} {}", a.upwind_loss, b.upwind_loss);
        assert!((a.friction_loss / b.friction_loss - 1.0).abs() < 1e-9);
        assert!(b.balance_error.abs() < 1e-11, "{b:?}");
    }
}

#[test]
fn consistent_pulse_travels_at_the_tangent_speed() {
    // A rod twisted uniformly to eps0 (bit stuck, top held), then a small top-speed step: the
    // front travels at the tangent speed sqrt((k2 + 3 k5 eps0^2) / (rho I_p)), 9.5 % above
    // sqrt(G / rho) here, and carries the torque jump Z(eps0) d_omega.
    let (length, g, nu, d) = (1000.0, G, 0.499, 0.1);
    let (k2, k5) = rod_coefficients(d, g, nu);
    let k1 = RHO * k2 / g;
    let eps0 = 2.0 * 0.02 / d; // shear strain 0.02 at the surface
    let tau0 = k2 * eps0 + k5 * eps0.powi(3);
    let tangent = ((k2 + 3.0 * k5 * eps0 * eps0) / k1).sqrt();
    let linear = (g / RHO).sqrt();
    let mut cfg = frictionless(vec![soft_rod(length)], 2000, 0.5 * length / tangent);
    cfg.nonlinearity = Nonlinearity::Consistent;
    cfg.numerics.max_shear_strain = 0.025;
    cfg.numerics.field_interval = cfg.numerics.duration;
    // a bit held by the rock: a static torque of 1 MN m (500 kN, within the rod's 605 kN buoyed
    // weight, on a 1 m bit at mu_s = 2) above tau0
    cfg.bit =
        Bit { on_bottom: true, weight_on_bit: 5e5, radius: 1.0, mu_static: 2.0, mu_kinetic: 0.5, ..Bit::default() };
    let rpm = 1.0;
    cfg.top_drive.rpm = rpm;
    let dw = rpm / RPM;
    let mut sim = Simulation::new(&cfg).unwrap();
    let n = sim.grid().cells();
    sim.set_state(&vec![0.0; n], &vec![tau0; n], 0.0, 0.0).unwrap();
    let (w, tau) = sim.fields();
    assert!(w.iter().all(|&x| x == 0.0) && tau.iter().all(|t| (t / tau0 - 1.0).abs() < 1e-14));
    let run = sim.run(&Never, &mut |_| {});
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.stats.courant_peak <= 1.0 && run.stats.courant_max == 1.0, "{:?}", run.stats);
    assert!(run.bit_rpm.iter().all(|&w| w == 0.0), "the bit held");
    let t = run.field_t[1];
    let row = &run.torque_field[n..];
    let jump = row[0] - tau0;
    let expected_jump = (k1 * (k2 + 3.0 * k5 * eps0 * eps0)).sqrt() * dw;
    // The front: where the torque has risen by half the jump.
    let k = row.iter().position(|&x| x - tau0 < 0.5 * jump).unwrap();
    let (a, b) = (row[k - 1] - tau0 - 0.5 * jump, row[k] - tau0 - 0.5 * jump);
    let front = run.z[k - 1] + (run.z[k] - run.z[k - 1]) * a / (a - b);
    let speed = front / t;
    eprintln!(
        "front at {front:.2} m after {t:.5} s: {speed:.2} m/s, tangent {tangent:.2}, linear {linear:.2}; \
         jump {jump:.2} N m vs Z(eps0) dw = {expected_jump:.2}"
    );
    assert!((speed / tangent - 1.0).abs() < 2e-3, "{speed} vs {tangent}");
    assert!((jump / expected_jump - 1.0).abs() < 1e-3, "{jump} vs {expected_jump}");
    assert!(tangent / linear > 1.09);
}

/// Bit speed (rad/s) of a rod of length `l` with the top fixed and the bit free, released from
/// rest with the twist `eps(x) = s cos(pi x / (2 l))`, by the finite-difference PDE solver on
/// the rod of length `2 l` free at both ends whose twist is odd about its middle (which stays
/// at rest: the fixed top), at the times `times`.
fn pde_bit_speed(k: crate::pde::PdeCoefficients, l: f64, s: f64, times: &[f64], nodes: usize) -> Vec<f64> {
    use crate::integrators::{solve_second_order, Method, SolveOptions};
    use crate::options::Output;
    let sys = crate::pde::PdeSystem::new(k, 2.0 * l, nodes).unwrap();
    let q0: Vec<f64> = sys.positions().iter().map(|&z| -s * 2.0 * l / PI * (PI * (z - l) / (2.0 * l)).sin()).collect();
    let opts = SolveOptions { rtol: 1e-11, atol: 1e-14, ..SolveOptions::new(Method::Dop853) };
    let sol = solve_second_order(
        &sys,
        0.0,
        &q0,
        &vec![0.0; nodes],
        *times.last().unwrap(),
        &Output::Times(times.to_vec()),
        &opts,
    )
    .unwrap();
    assert_eq!(sol.status, Status::Success, "{}", sol.message);
    (0..sol.len()).map(|i| sol.state(i)[2 * nodes - 1]).collect()
}

#[test]
fn consistent_agrees_with_the_pde_solver_at_first_order() {
    // A fixed-free rod released from a large twist (shear strain 0.01 at the top, where the
    // tangent stiffness is 5 % above G I_p), no friction: the bit speed over two travel times
    // against the finite-difference solver of the consistent PDE (k1 th_tt = k2 th_zz +
    // k5 (th_z^3)_z, second order in h, DOP853), and the order of convergence in the cells.
    let (l, g, nu, d) = (1000.0, G, 0.499, 0.1);
    let (k2, k5) = rod_coefficients(d, g, nu);
    let k1 = RHO * k2 / g;
    let s = 2.0 * 0.01 / d;
    let duration = 2.0 * l / (g / RHO).sqrt();
    let out = 1e-3;
    let times: Vec<f64> = (0..=(duration / out * (1.0 + 1e-12)).floor() as usize).map(|i| i as f64 * out).collect();
    let k = crate::pde::PdeCoefficients { k1, k2, k3: 0.0, k4: 0.0, k5, k6: 0.0 };
    let reference = pde_bit_speed(k, l, s, &times, 2001);
    let linear = pde_bit_speed(crate::pde::PdeCoefficients { k5: 0.0, ..k }, l, s, &times, 2001);
    let scale = reference.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
    let gap = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0, |m: f64, (x, y)| m.max((x - y).abs())) / scale;
    let nonlinear_effect = gap(&reference, &linear);
    let cells = [50, 100, 200, 400, 800];
    let mut errors = Vec::new();
    for &m in &cells {
        let mut cfg = frictionless(vec![soft_rod(l)], m, duration);
        cfg.nonlinearity = Nonlinearity::Consistent;
        cfg.numerics.max_shear_strain = 0.01;
        cfg.numerics.output_interval = out;
        let mut sim = Simulation::new(&cfg).unwrap();
        let z = sim.grid().z.clone();
        let p = sim.grid().props[0];
        let tau: Vec<f64> = z.iter().map(|&x| p.torque(s * (PI * x / (2.0 * l)).cos())).collect();
        sim.set_state(&vec![0.0; z.len()], &tau, 0.0, 0.0).unwrap();
        let run = sim.run(&Never, &mut |_| {});
        assert_eq!(run.status, Status::Success, "{}", run.message);
        assert_eq!(run.t.len(), times.len());
        assert!(run.stats.courant_peak <= 1.0 + 1e-12, "{:?}", run.stats);
        let bit: Vec<f64> = run.bit_rpm.iter().map(|r| r / RPM).collect();
        let e = run.energy;
        assert!(e.balance_error.abs() < 1e-12 && e.upwind_loss > 0.0, "{e:?}");
        errors.push(gap(&bit, &reference));
        eprintln!(
            "{m} cells: error {:.3e}, transport loss {:.3e} of {:.3e} J",
            errors.last().unwrap(),
            e.upwind_loss,
            e.initial
        );
    }
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("nonlinear effect (PDE k5 vs k5 = 0) {nonlinear_effect:.3e}; errors {errors:?}; orders {orders:?}");
    assert!(orders[2..].iter().all(|&p| (p - 1.0).abs() < 0.25), "{orders:?}");
    assert!(errors[4] < 0.1 * nonlinear_effect, "{errors:?} vs {nonlinear_effect}");
}

#[test]
fn consistent_energy_balance_closes() {
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let mut cfg = loaded(model);
        cfg.nonlinearity = Nonlinearity::Consistent;
        let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
        let e = run.energy;
        eprintln!("consistent {model:?}: {e:?} courant {:?}", run.stats);
        assert_eq!(run.status, Status::Success);
        assert!(run.message.is_empty(), "{}", run.message);
        assert!(run.stats.courant_max <= 1.0 && run.stats.courant_peak <= run.stats.courant_max);
        assert!(e.balance_error.abs() < 1e-11, "{e:?}");
        assert!(e.motor_work > 0.0 && e.friction_loss > 0.0 && e.damping_loss > 0.0 && e.bit_loss > 0.0);
        assert!(e.upwind_loss > 0.0 && e.numerical_loss < 0.05 * e.motor_work, "{e:?}");
        let change = e.kinetic + e.elastic + e.top_drive + e.bha - e.initial;
        let losses = e.friction_loss + e.damping_loss + e.bit_loss + e.numerical_loss;
        assert!((e.motor_work - change - losses).abs() < 1e-10 * e.motor_work);
    }
    // Strains beyond numerics.max_shear_strain (a uniform string at Courant number 1 for
    // 1e-6): the run says so.
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 200, 1.0);
    cfg.top_drive.rpm = 60.0;
    cfg.nonlinearity = Nonlinearity::Consistent;
    cfg.numerics.max_shear_strain = 1e-6;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.stats.courant_max, 1.0);
    assert!(run.stats.courant_peak > 1.0, "{:?}", run.stats);
    assert!(run.message.contains("numerics.max_shear_strain"), "{}", run.message);
}

#[test]
fn well_b_with_the_consistent_law_changes_little() {
    // Shear strains of Well B stay near 1e-3, where the tangent stiffness differs from G J by
    // ~1e-5. Three runs separate the two changes the option makes: the law (consistent against
    // the same scheme and grid with k5 = 0) and the discretisation (the Godunov scheme on the grid
    // of the hardened speed, Courant numbers just below 1, against the linear scheme at 1).
    let json = r#"{
      "sections": [
        {"length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
         "shear_modulus": 61e9, "density": 7850.0},
        {"length": 230.0, "outer_diameter": 0.19425788212135248, "inner_diameter": 0.09285466808235807,
         "shear_modulus": 67e9, "density": 8622.131147540984,
         "polar_moment": 4.7067114136638673e-4, "area": 0.02286618845760419}],
      "damping_rate": 0.08333333333333334,
      "friction": {"contact": "weight"},
      "numerics": {"cells": 1000, "duration": 60.0, "field_interval": 0}
    }"#;
    let mut cfg = DrillConfig::from_json(json).unwrap();
    let base = solve(&cfg, &Never, &mut |_| {}).unwrap();
    cfg.nonlinearity = Nonlinearity::Consistent;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.message.is_empty(), "{}", run.message);
    let mut sim = Simulation::new(&cfg).unwrap();
    sim.zero_quartic();
    let quadratic = sim.run(&Never, &mut |_| {});
    let (a, b, q) = (base.metrics.unwrap(), run.metrics.unwrap(), quadratic.metrics.unwrap());
    let metrics = |m: &crate::metrics::StickSlip| {
        [m.motor_torque_min_nm, m.motor_torque_max_nm, m.period_s, m.bit_rpm_max, m.bit_rpm_mean]
    };
    let changes = |x: [f64; 5], y: [f64; 5]| -> [f64; 5] { std::array::from_fn(|i| y[i] / x[i] - 1.0) };
    let law = changes(metrics(&q), metrics(&b));
    let scheme = changes(metrics(&a), metrics(&q));
    let total = changes(metrics(&a), metrics(&b));
    let shown = |c: [f64; 5]| c.map(|c| format!("{c:.2e}"));
    eprintln!(
        "Well B, relative changes of torque min, max, period, rpm max, mean: law {:?}, scheme {:?}, total {:?}; \
         courant {}..{} peak {}; transport loss {:.4e} J (linear {:.4e}), balance {:.1e}",
        shown(law),
        shown(scheme),
        shown(total),
        run.stats.courant_min,
        run.stats.courant_max,
        run.stats.courant_peak,
        run.energy.upwind_loss,
        base.energy.upwind_loss,
        run.energy.balance_error
    );
    assert!(law.iter().all(|c| c.abs() < LAW_BOUND), "{law:?}");
    assert!(total.iter().all(|c| c.abs() < 0.1), "{total:?}");
    assert!(run.stats.courant_peak < 1.0 && run.energy.balance_error.abs() < 1e-11);
}

/// Measured: at most 2.5e-5 (the torque minimum and maximum).
const LAW_BOUND: f64 = 1e-4;

#[test]
fn consistent_fields_are_bad_input_when_out_of_range() {
    let field = |extra: &str| {
        let json =
            format!(r#"{{"sections": [{{"length": 100, "outer_diameter": 0.1, "inner_diameter": 0.05{extra}}}]}}"#);
        DrillConfig::from_json(&json).and_then(|c| c.validate()).err().map_or("ok".into(), |e| e.field().to_string())
    };
    assert_eq!(field(r#", "poisson_ratio": 0.5"#), "sections[0].poisson_ratio");
    assert_eq!(field(r#", "poisson_ratio": -1"#), "sections[0].poisson_ratio");
    assert_eq!(field(r#", "poisson_ratio": 0"#), "ok"); // the one rule of model::check_poisson_ratio: -1 < nu < 0.5
    assert_eq!(field(r#", "poisson_ratio": 0.25"#), "ok");
    assert_eq!(field(r#", "quartic_moment": 0"#), "sections[0].quartic_moment");
    assert_eq!(field(r#", "quartic_moment": -1e-7"#), "sections[0].quartic_moment");
    assert_eq!(field(r#", "quartic_moment": 1e-7"#), "ok");
    let top = |extra: &str| {
        let json =
            format!(r#"{{"sections": [{{"length": 100, "outer_diameter": 0.1, "inner_diameter": 0.05}}]{extra}}}"#);
        DrillConfig::from_json(&json).and_then(|c| c.validate()).err().map_or("ok".into(), |e| e.field().to_string())
    };
    assert_eq!(top(r#", "nonlinearity": "cubic""#), "nonlinearity");
    assert_eq!(top(r#", "nonlinearity": "consistent""#), "ok");
    assert_eq!(top(r#", "numerics": {"max_shear_strain": 0}"#), "numerics.max_shear_strain");
    assert_eq!(top(r#", "numerics": {"max_shear_strain": 2}"#), "numerics.max_shear_strain");
}

/// `quartic_moment` sets `J4` of `k5 = M J4 / 2`: unset, the annulus's `pi/192 (OD^6 - ID^6)`
/// (computed here); given, that value, whatever the diameters or a `polar_moment` override.
#[test]
fn quartic_moment_sets_k5() {
    let (od, id): (f64, f64) = (0.127, 0.1086);
    let mut s = section(100.0, od, id);
    let m = |s: &Section| {
        let nu = s.poisson_ratio;
        2.0 * s.shear_modulus * (1.0 - nu) / (1.0 - 2.0 * nu)
    };
    let annulus = PI / 192.0 * (od.powi(6) - id.powi(6));
    let k5 = grid::SectionProps::new(&s, 0.0).quartic;
    assert!((k5 - m(&s) * annulus / 2.0).abs() < 1e-12 * k5, "{k5}");
    s.polar_moment = Some(2.0 * polar(od, id));
    s.quartic_moment = Some(3.0 * annulus);
    let props = grid::SectionProps::new(&s, 0.0);
    assert!((props.quartic - 3.0 * k5).abs() < 1e-12 * k5, "{}", props.quartic);
    assert_eq!(props.stiffness, G * 2.0 * polar(od, id));
}

#[test]
fn with_stick_speed_zero_a_string_at_rest_stays_at_rest() {
    // Set-valued friction with stick_speed 0: a cell exactly at rest still counts as slow
    // (held by the static limit). Were it treated as sliding, the kinetic torque with the sign
    // of +0 would start it turning backwards.
    let mut cfg = loaded(FrictionModel::SetValued);
    cfg.friction.stick_speed = 0.0;
    cfg.top_drive.rpm = 0.0;
    cfg.numerics.duration = 2.0;
    cfg.numerics.field_interval = 0.5;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success);
    assert!(run.omega_field.iter().chain(&run.bit_rpm).chain(&run.surface_rpm).all(|&w| w == 0.0));
    assert_eq!(run.energy.friction_loss, 0.0);
    // Turning, the same setting sticks and slips with its energy balance closed.
    cfg.top_drive.rpm = 60.0;
    cfg.numerics.duration = 20.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(run.bit_rpm.iter().any(|&w| w > 30.0));
    assert!(run.energy.friction_loss > 0.0 && run.energy.balance_error.abs() < 1e-11, "{:?}", run.energy);
}

/// A kinetic friction far above the break-off torque (friction.static = 1000) never reverses a
/// cell: the friction loss is never negative and the balance closes without a numerical loss
/// that hides it (before: friction_loss -3.25e8 J against a numerical loss of +3.21e8 J).
#[test]
fn kinetic_friction_never_reverses_the_motion() {
    let json = r#"{
      "sections": [{"length": 3200.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
      "friction": {"static": 1000.0},
      "numerics": {"cells": 500, "duration": 5.0, "field_interval": 0}
    }"#;
    let cfg = DrillConfig::from_json(json).unwrap();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let e = run.energy;
    assert!(e.friction_loss >= 0.0, "{e:?}");
    // only the implicit top drive's first-order loss (no transport loss at Courant number 1)
    assert!(e.upwind_loss == 0.0 && e.inertia_loss < 1e-3 * e.motor_work, "{e:?}");
    assert!(e.balance_error.abs() < 1e-10, "{e:?}");
    // the motor cannot break the string free: the bit never turns
    assert!(
        run.bit_rpm.iter().all(|&w| w.abs() < 1e-9),
        "{:?}",
        run.bit_rpm.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
    );
}

/// A Courant number below 1 asked for shortens the step on the same cells.
#[test]
fn a_courant_number_below_one_shortens_the_step() {
    let mut cfg = DrillConfig::default();
    cfg.numerics.duration = 1.0;
    let base = Grid::new(&cfg).unwrap();
    cfg.numerics.courant = 0.5;
    let half = Grid::new(&cfg).unwrap();
    assert_eq!(base.counts, half.counts);
    assert!((half.dt - 0.5 * base.dt).abs() < 1e-15 * base.dt);
    assert!(half.courant.iter().zip(&base.courant).all(|(h, b)| (h - 0.5 * b).abs() < 1e-15));
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(run.energy.upwind_loss > 0.0 && run.energy.balance_error.abs() < 1e-10, "{:?}", run.energy);
    cfg.numerics.courant = 1.5;
    assert_eq!(cfg.validate().unwrap_err().field(), "numerics.courant");
}

/// A proportional gain the sampled top-drive loop cannot hold on the grid is refused, naming
/// the cells (with a count that holds) when the step is longer than the control interval
/// (before: 1 to 4 cells ran to bit speeds of 1e52 rpm and "success").
#[test]
fn an_unstable_controller_loop_is_refused() {
    let json = r#"{
      "sections": [{"length": 3200.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
      "numerics": {"cells": 4, "duration": 5.0, "field_interval": 0}
    }"#;
    let mut cfg = DrillConfig::from_json(json).unwrap();
    let err = Simulation::new(&cfg).err().expect("refused");
    assert_eq!(err.field(), "numerics.cells", "{err}");
    let needed: usize = err.to_string().split("at least ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    cfg.numerics.cells = needed;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.surface_rpm.iter().all(|w| w.abs() < 200.0));
    cfg.numerics.cells = needed - 1;
    assert_eq!(Simulation::new(&cfg).err().expect("refused").field(), "numerics.cells");
    // a gain above 2 I / control_interval on a fine grid names the gain
    cfg.numerics.cells = 2000;
    cfg.top_drive.controller.kp = 1e6;
    assert_eq!(Simulation::new(&cfg).err().expect("refused").field(), "top_drive.controller.kp");
}

/// A state beyond the runaway bound ends the run with `non_finite` and a message that says the
/// solution diverged, never "success".
#[test]
fn a_runaway_ends_with_a_status() {
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 100, 1.0);
    cfg.top_drive.rpm = 60.0;
    let mut sim = Simulation::new(&cfg).unwrap();
    let n = sim.grid().cells();
    let fast = 2.0 * RUNAWAY_FACTOR * 60.0 / RPM;
    sim.set_state(&vec![fast; n], &vec![0.0; n], 0.0, fast).unwrap();
    let run = sim.run(&Never, &mut |_| {});
    assert_eq!(run.status, Status::NonFinite);
    assert!(run.message.contains("diverged") && run.message.contains("speed reached"), "{}", run.message);
}

/// Unit mistakes and overflow are refused naming the field (before: an outer diameter of 1e50 m
/// succeeded with every energy 0 and 1e154 m said "invalid limit"); a run of more cell updates
/// than the limit is refused before it starts.
#[test]
fn absurd_sizes_are_refused_naming_the_field() {
    let mut cfg = DrillConfig::default();
    for od in [1e50, 1e154, 171.0] {
        cfg.sections[0].outer_diameter = od;
        assert_eq!(cfg.validate().unwrap_err().field(), "sections[0].outer_diameter", "{od}");
    }
    cfg.sections[0].outer_diameter = 0.146529;
    cfg.sections[0].length = 1e9;
    assert_eq!(cfg.validate().unwrap_err().field(), "sections[0].length");
    cfg.sections[0].length = 3000.0;
    cfg.numerics.cells = 1_000_000;
    cfg.numerics.duration = 86_400.0;
    cfg.numerics.output_interval = 10.0;
    cfg.numerics.field_interval = 0.0;
    let err = cfg.validate().unwrap_err();
    assert_eq!(err.field(), "numerics.cells", "{err}");
    assert!(err.to_string().contains("cell updates"), "{err}");
}

/// A torque limit below the string's static torque is warned about.
#[test]
fn a_torque_limit_below_the_static_torque_warns() {
    let mut cfg = DrillConfig::default();
    cfg.numerics.duration = 1.0;
    let limit_warnings = |run: &DrillRun| -> Vec<String> {
        run.warnings.iter().filter(|w| w.contains("top_drive.torque_limit")).cloned().collect()
    };
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(limit_warnings(&run).is_empty(), "{:?}", run.warnings);
    cfg.top_drive.torque_limit = 0.5 * run.breakoff_torque;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let w = limit_warnings(&run);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("never break") && w[0].contains("a motor too small"), "{w:?}");
    // a limit given in kN m: a thousand times it would do
    cfg.top_drive.torque_limit = 1e-3 * run.breakoff_torque;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert!(limit_warnings(&run)[0].contains("a limit in kN m?"), "{:?}", run.warnings);
}

/// A section boundary within rounding of a survey station is solved (before: `drill` refused
/// 800.0000000000001 m against the station at 800 m with an error naming no field), with the
/// break-off torque of the boundary at 800 m to rounding.
#[test]
fn a_section_boundary_at_a_station_within_rounding_is_solved() {
    let json = |l: f64| {
        format!(
            r#"{{"sections": [{{"length": {l:?}, "outer_diameter": 0.127, "inner_diameter": 0.1086}},
                {{"length": 2400.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}}],
              "well": {{"md": [0.0, 800.0, 1800.0, 4000.0], "inclination_deg": [0.0, 0.0, 30.0, 30.0]}},
              "friction": {{"contact": "weight"}},
              "numerics": {{"duration": 1.0}}}}"#
        )
    };
    let exact = breakoff_torque(&DrillConfig::from_json(&json(800.0)).unwrap()).unwrap();
    for l in [800.0000000000001, 799.9999999999999] {
        let cfg = DrillConfig::from_json(&json(l)).unwrap();
        cfg.validate().unwrap();
        assert!((breakoff_torque(&cfg).unwrap() / exact - 1.0).abs() < 1e-12);
    }
}

/// A metrics window that holds fewer than two samples of the run is refused naming it (before:
/// all-null metrics and "success").
#[test]
fn a_metrics_window_outside_the_run_is_refused() {
    let mut cfg = DrillConfig::default();
    cfg.numerics.duration = 2.0;
    for (w, ok) in
        [([5.0, 8.0], false), ([-3.0, -1.0], false), ([0.005, 0.015], false), ([0.0, 0.01], true), ([1.5, 9.0], true)]
    {
        cfg.metrics.window = Some(w);
        match cfg.validate() {
            Ok(()) => assert!(ok, "{w:?} accepted"),
            Err(e) => assert!(!ok && e.field() == "metrics.window", "{w:?}: {e}"),
        }
    }
}

#[test]
fn values_outside_drilling_practice_warn_naming_the_field() {
    let mut cfg = DrillConfig::default();
    assert!(super::plausibility::plausibility_warnings(&cfg).is_empty());
    cfg.sections[0].outer_diameter = 171.0;
    cfg.sections[0].inner_diameter = 100.0;
    cfg.bit.radius = 8.5;
    cfg.top_drive.rpm = -1e300;
    cfg.sections[0].length = 30_000.0;
    let w = super::plausibility::plausibility_warnings(&cfg);
    assert_eq!(w.len(), 4, "{w:?}");
    assert!(w[0].starts_with("sections[0].outer_diameter = 171 m"));
    assert!(w[1].starts_with("bit.radius = 8.5 m"));
    assert!(w[2].contains("30000 m long"));
    assert!(w[3].contains("1e+300 rpm"));
}
