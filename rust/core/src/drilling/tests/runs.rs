//! Runs: interrupt and progress, controllers, setpoints, the bit on bottom, Well B, grids and
//! their step, the status of a run that overflows or diverges.

use super::*;

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
    let cfg = well_b(60.0);
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
