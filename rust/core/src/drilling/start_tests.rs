//! The steady start against the rest start and the bit law's steady state.

use super::*;
use crate::drilling::solve;
use crate::interrupt::Never;

/// A short uniform coupled string (the van de Wouw pipe, 500 m, no gravity), the rate law.
fn coupled(extra: &str) -> DrillConfig {
    DrillConfig::from_json(&format!(
        r#"{{"sections": [{{"length": 500.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
              "shear_modulus": 77e9, "density": 8000.0, "poisson_ratio": 0.2987012987012987}}],
            "well": {{"inclination_deg": 0.0, "gravity": 0.0}}, "friction": {{"static": 0.0}},
            "damping_rate": 2.0,
            "top_drive": {{"rpm": 120.0, "torque_limit": 1e12, "controller": {{"type": "speed"}},
                          "motor_bandwidth": 1000.0}},
            "bit": {{"radius": 0.108, "law": "detournay"}},
            "hoist": {{"mode": "velocity", "speed": 0.002777777777777778}},
            "numerics": {{"cells": 200, "duration": 4.0}}{extra}}}"#
    ))
    .unwrap()
}

#[test]
fn rest_is_the_default_and_changes_nothing() {
    let cfg = coupled("");
    assert_eq!(cfg.numerics.initial_state, InitialState::Rest);
    let again = coupled(r#", "numerics": {"cells": 200, "duration": 4.0, "initial_state": "rest"}"#);
    let (a, b) = (solve(&cfg, &Never, &mut |_| {}).unwrap(), solve(&again, &Never, &mut |_| {}).unwrap());
    assert_eq!(a.rop, b.rop);
    assert_eq!(a.motor_torque, b.motor_torque);
}

/// From the steady state the run is at the law's steady point from the first sample: ROP at the
/// hoist's rate, weight and torque on bit at the law's, the motor torque at the string's.
#[test]
fn a_steady_start_drills_at_the_steady_state_from_the_start() {
    let cfg = coupled(r#", "numerics": {"cells": 200, "duration": 4.0, "initial_state": "steady"}"#);
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let law = cfg.bit.detournay.law(cfg.bit.radius);
    let omega = 120.0 * std::f64::consts::TAU / 60.0;
    let rop = 10.0 / 3600.0;
    let s = law.steady_state(rop, omega);
    let k = run.t.iter().position(|&t| t >= 0.5).unwrap();
    for j in [k, run.t.len() - 1] {
        assert!((run.rop[j] - 10.0).abs() < 0.02, "ROP {} at {}", run.rop[j], run.t[j]);
        assert!(
            (run.weight_on_bit[j] / s.weight_on_bit - 1.0).abs() < 2e-3,
            "{} {}",
            run.weight_on_bit[j],
            s.weight_on_bit
        );
        assert!((run.bit_torque[j] / s.torque_on_bit - 1.0).abs() < 2e-3, "{} {}", run.bit_torque[j], s.torque_on_bit);
        assert!((run.bit_rpm[j] - 120.0).abs() < 0.1, "{}", run.bit_rpm[j]);
    }
    // the rest start is still far from it at 4 s: the string has not yet compressed
    let rest = solve(&coupled(""), &Never, &mut |_| {}).unwrap();
    assert!(rest.weight_on_bit[k] < 0.5 * s.weight_on_bit, "{}", rest.weight_on_bit[k]);
}

/// The torque profile of steady rotation: the torque on bit plus the damping torque below.
#[test]
fn the_steady_torque_is_the_torque_on_bit_plus_what_the_string_loses_below() {
    let cfg = coupled("");
    let grid = Grid::new(&cfg).unwrap();
    let wall = Wall::new(&cfg, &grid, true);
    let omega = 2.0;
    let (cells, top) = wall.torques(0.01, omega, 1000.0);
    let rho_j = grid.props[0].inertia_per_length;
    // damping 2 1/s: 2 rho J omega per metre over 500 m
    assert!((top - (1000.0 + 2.0 * rho_j * omega * 500.0)).abs() < 1e-6 * top, "{top}");
    let last = cells[cells.len() - 1];
    assert!((last - (1000.0 + 2.0 * rho_j * omega * 0.5 * grid.spacing[0])).abs() < 1e-9 * last);
    // with wall friction, coupled: the kinetic force mu_k N splits by (v, r omega)
    let cfg = coupled(r#", "friction": {"static": 0.3, "kinetic_ratio": 0.5}, "well": {"inclination_deg": 90.0}"#);
    let grid = Grid::new(&cfg).unwrap();
    let wall = Wall::new(&cfg, &grid, true);
    let r = grid.props[0].contact_radius;
    let f = 0.5 * grid.limit[0] / r;
    let (v, w) = (0.01f64, 2.0);
    let s = v.hypot(r * w);
    let drag = wall.axial_resistance_below(0.0, v, w)
        - 2.0 * 500.0 * v * AxialSection::from_section(&cfg.sections[0]).mass_per_length();
    assert!((drag - f * v / s * 500.0).abs() < 1e-6 * drag, "{drag}");
}

#[test]
fn a_steady_start_is_refused_where_there_is_no_steady_drilling() {
    let mut cfg = coupled("");
    cfg.numerics.initial_state = InitialState::Steady;
    cfg.hoist = None;
    cfg.bit.law = crate::drilling::config::BitRockLaw::VelocityWeakening;
    let err = crate::drilling::Simulation::new(&cfg).err().expect("refused");
    assert_eq!(err.field(), "numerics.initial_state");
    let mut cfg = coupled("");
    cfg.numerics.initial_state = InitialState::Steady;
    cfg.hoist.as_mut().unwrap().speed = -0.01;
    let err = crate::drilling::Simulation::new(&cfg).err().expect("refused");
    assert!(err.to_string().contains("does not drill down"), "{err}");
    cfg.hoist.as_mut().unwrap().speed = 0.01;
    cfg.top_drive.rpm = 0.0;
    assert_eq!(crate::drilling::Simulation::new(&cfg).err().expect("refused").field(), "numerics.initial_state");
}
