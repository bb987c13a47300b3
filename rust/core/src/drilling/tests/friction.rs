//! The wall's friction and the energy ledger: the break-off torque, the balance of a loaded
//! run, the stick phase, a kinetic friction that never reverses a cell.

use super::*;

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
            m.severity, m.stuck_fraction, m.rpm_min, m.rpm_max, m.rpm_mean, m.torque_min, m.torque_max, m.cycle_period, run.energy.friction_loss
        );
        results.push(m);
    }
    // Both run to the end near the setpoint on average.
    for m in &results {
        assert!((m.rpm_mean - 40.0).abs() < 5.0, "{m:?}");
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
