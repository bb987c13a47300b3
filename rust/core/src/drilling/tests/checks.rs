//! Bad input named by its field, the round trip of the defaults, the warnings of a run.

use super::*;

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
