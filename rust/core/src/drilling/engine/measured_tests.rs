//! `top_drive.mode = "measured_speed"`: the top speed imposed from a series, against a
//! controller run on the same grid and step, a rigid-body closed form and the energy balance.

use crate::drilling::config::{DrillConfig, TopMode};
use crate::drilling::engine::controller::SpeedSeries;
use crate::drilling::grid::Grid;
use crate::drilling::solver::solve;
use crate::interrupt::Never;
use crate::solution::Status;

/// A 1500 m vertical 5-in string on bottom with wall friction, PI control to 60 rpm: a
/// break-off and stick-slip in the first 15 s.
fn on_bottom() -> DrillConfig {
    let json = r#"{"sections": [{"length": 1500.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "top_drive": {"rpm": 60.0, "ramp_time": 1.0},
        "numerics": {"cells": 150, "duration": 15.0}}"#;
    let mut cfg = DrillConfig::from_json(json).unwrap();
    // a sample at every step end
    cfg.numerics.output_interval = Grid::new(&cfg).unwrap().dt;
    cfg
}

fn measured(cfg: &DrillConfig, series: Vec<[f64; 2]>) -> DrillConfig {
    let mut m = cfg.clone();
    m.top_drive.mode = TopMode::MeasuredSpeed;
    m.top_drive.speed_series = series;
    m
}

#[test]
fn imposing_a_controller_runs_speed_reproduces_its_motor_torque() {
    let cfg = on_bottom();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    let mut series: Vec<[f64; 2]> = run.t.iter().zip(&run.surface_rpm).map(|(&t, &w)| [t, w]).collect();
    // the last sample is a step before the duration: held to it (the step after it is not sampled)
    series.push([cfg.numerics.duration, *run.surface_rpm.last().unwrap()]);
    // the torque limit is not used with an imposed speed (nor warned about)
    let mut imposed_cfg = measured(&cfg, series);
    imposed_cfg.top_drive.torque_limit = 1.0;
    let imposed = solve(&imposed_cfg, &Never, &mut |_| {}).unwrap();
    assert!(imposed.warnings.iter().all(|w| !w.contains("torque_limit")), "{:?}", imposed.warnings);
    assert_eq!(imposed.status, Status::Success, "{}", imposed.message);
    assert_eq!(imposed.t.len(), run.t.len());
    let peak = run.motor_torque.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(peak > 1e4, "a break-off torque, {peak} N m");
    // The same grid and step, the top speed the same up to the rpm round trip and the
    // interpolation at a step end (a few ulps): the torque agrees to 1e-6 of its peak (the
    // inertia's I / dt multiplies those ulps; measured: 2.4e-9 N m of a 17 kN m peak).
    let diff = run.motor_torque.iter().zip(&imposed.motor_torque).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff <= 1e-6 * peak, "motor torque differs by {diff} N m of {peak}");
    let bit = run.bit_rpm.iter().zip(&imposed.bit_rpm).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(bit <= 1e-6 * 60.0, "bit speed differs by {bit} rpm");
    let (e0, e1) = (&run.energy, &imposed.energy);
    // the motor's work agrees but for the run's last step, after the last sample (its speed held)
    assert!(((e1.motor_work - e0.motor_work) / e0.motor_work).abs() < 1e-4, "{} vs {}", e1.motor_work, e0.motor_work);
    assert!(e1.balance_error.abs() < 1e-9, "balance error {}", e1.balance_error);
}

#[test]
fn a_rigid_string_takes_its_inertia_times_the_acceleration() {
    // 300 m with no wall friction or damping, a light top drive and a BHA: after a smooth
    // onset (a quadratic over tau = 2 s) the top accelerates at a = 2 rad/s^2 and, averaged over
    // many of the string's periods (about 0.1 s), the motor torque is (I_td + rho J L + I_bha) a.
    let json = r#"{"sections": [{"length": 300.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
            "density": 7850.0}],
        "friction": {"static": 0.0}, "damping_rate": 0.0,
        "top_drive": {"inertia": 5.0},
        "bit": {"on_bottom": false, "bha_inertia": 20.0},
        "numerics": {"cells": 300, "duration": 12.0, "output_interval": 0.001}}"#;
    let cfg = DrillConfig::from_json(json).unwrap();
    let (a, tau) = (2.0, 2.0);
    let speed = |t: f64| if t < tau { a * t * t / (2.0 * tau) } else { a * (t - tau / 2.0) };
    let rpm = 60.0 / (2.0 * std::f64::consts::PI);
    let series: Vec<[f64; 2]> = (0..=12_000).map(|k| k as f64 * 1e-3).map(|t| [t, speed(t) * rpm]).collect();
    let run = solve(&measured(&cfg, series), &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    let j = std::f64::consts::PI / 32.0 * (0.127f64.powi(4) - 0.108f64.powi(4));
    let want = (5.0 + 7850.0 * j * 300.0 + 20.0) * a;
    let window: Vec<f64> = (0..run.t.len()).filter(|&k| run.t[k] >= 4.0).map(|k| run.motor_torque[k]).collect();
    let mean = window.iter().sum::<f64>() / window.len() as f64;
    assert!((mean / want - 1.0).abs() < 2e-3, "mean motor torque {mean} N m, rigid body {want} N m");
    // the top follows the series exactly
    let k = run.t.iter().position(|&t| t >= 6.0).unwrap();
    assert!((run.surface_rpm[k] - speed(run.t[k]) * rpm).abs() < 1e-9 * 300.0);
    // the motor's work is the kinetic energy given (no losses but the top's implicit step)
    assert!(run.energy.balance_error.abs() < 1e-9, "balance error {}", run.energy.balance_error);
}

#[test]
fn the_series_is_interpolated_linearly_and_held_at_its_ends() {
    let mut td = DrillConfig::default().top_drive;
    td.mode = TopMode::MeasuredSpeed;
    let rpm = 60.0 / (2.0 * std::f64::consts::PI);
    td.speed_series = vec![[-1.0, 0.0], [1.0, 20.0 * rpm], [3.0, 10.0 * rpm]];
    let mut s = SpeedSeries::new(&td).unwrap();
    for (t, want) in [(-2.0, 0.0), (0.0, 10.0), (0.5, 15.0), (2.0, 15.0), (2.5, 12.5), (4.0, 10.0), (0.25, 12.5)] {
        assert!((s.at(t) - want).abs() < 1e-12, "at {t}: {} not {want}", s.at(t));
    }
    td.mode = TopMode::Controller;
    assert!(SpeedSeries::new(&td).is_none());
}

#[test]
fn a_bad_series_is_refused_naming_the_field() {
    let base = on_bottom();
    let cases: [(Vec<[f64; 2]>, &str); 5] = [
        (vec![[0.0, 0.0]], "top_drive.speed_series"),
        (vec![[0.0, 0.0], [1.0, f64::NAN], [20.0, 1.0]], "top_drive.speed_series[1][1]"),
        (vec![[0.0, 0.0], [1.0, 1.0], [1.0, 2.0], [20.0, 1.0]], "top_drive.speed_series[2][0]"),
        (vec![[0.5, 0.0], [20.0, 1.0]], "top_drive.speed_series[0][0]"),
        (vec![[0.0, 0.0], [10.0, 1.0]], "top_drive.speed_series[1][0]"),
    ];
    for (series, field) in cases {
        let err = measured(&base, series).validate().unwrap_err().to_string();
        assert!(err.contains(field), "{err}");
    }
    let mut ignored = base.clone();
    ignored.top_drive.speed_series = vec![[0.0, 0.0], [20.0, 1.0]];
    let err = ignored.validate().unwrap_err().to_string();
    assert!(err.contains("top_drive.speed_series") && err.contains("measured_speed"), "{err}");
    // from JSON, by name
    let json = r#"{"sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "top_drive": {"mode": "measured_speed", "speed_series": [[0, 0], [1, 60], [100, 60]]}}"#;
    assert_eq!(DrillConfig::from_json(json).unwrap().top_drive.mode, TopMode::MeasuredSpeed);
}
