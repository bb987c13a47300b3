//! The limits of [`super`]: each refusal names its field and the allowed range, before anything
//! sized by the input is allocated.

use super::*;
use crate::drilling::config::{Inclination, Override};
use crate::drilling::plausibility::run_warnings;
use crate::drilling::well::trajectory;
use crate::well::plan::SegmentSpec;

/// A coupled run: 1000 m of 5-in pipe (28.06 kg/m), vertical, with a hoist and the Detournay
/// law `law`.
fn coupled(law: &str, extra: &str) -> DrillConfig {
    let json = format!(
        r#"{{"sections": [{{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
            "shear_modulus": {g}, "density": 8000.0, "poisson_ratio": 0.3}}],
           "well": {{"inclination_deg": 0.0, "mud_density": 0.0}},
           "friction": {{"static": 0.0}},
           "top_drive": {{"rpm": 60.0, "ramp_time": 2.0, "controller": {{"type": "speed"}}}},
           "bit": {{"radius": 0.108, "law": "{law}"}},
           "hoist": {{"speed": 0.01, "ramp_time": 2.0}},
           "numerics": {{"cells": 200, "duration": 40.0, "output_interval": 0.01}} {extra}}}"#,
        g = 200e9 / 2.6,
    );
    DrillConfig::from_json(&json).unwrap()
}

fn refused(cfg: &DrillConfig) -> Error {
    cfg.validate().expect_err("refused")
}

#[test]
fn hoist_steps_and_setpoints_take_their_modes_range() {
    for mode in [HoistMode::HookLoad, HoistMode::WeightOnBit] {
        let mut cfg = coupled("rgd", "");
        let h = cfg.hoist.as_mut().unwrap();
        h.mode = mode;
        h.hook_load = 200e3;
        h.weight_on_bit = 10e3;
        h.steps = vec![[5.0, 20e3], [10.0, -50e3]];
        let e = refused(&cfg);
        assert_eq!(e.field(), "hoist.steps[1][1]", "{e}");
        assert!(e.to_string().contains(">= 0"), "{e}");
    }
    let mut cfg = coupled("rgd", "");
    let h = cfg.hoist.as_mut().unwrap();
    h.mode = HoistMode::Autodriller;
    h.autodriller.kp = 1e-7;
    h.autodriller.setpoint = -10e3;
    assert_eq!(refused(&cfg).field(), "hoist.autodriller.setpoint");
    // a velocity step may be negative (a pick-up)
    let mut cfg = coupled("rgd", "");
    cfg.hoist.as_mut().unwrap().steps = vec![[5.0, -0.05]];
    cfg.validate().unwrap();
}

#[test]
fn a_weight_on_bit_above_the_buoyed_weight_is_refused_or_warned_with_the_number() {
    let mut cfg = coupled("rgd", "");
    let hanging = hanging_hook_load(&cfg);
    // 1000 m of 28.06 kg/m pipe, vertical, no mud
    let area = std::f64::consts::PI / 4.0 * (0.127f64.powi(2) - 0.108f64.powi(2));
    assert!((hanging - 8000.0 * area * 1000.0 * 9.81).abs() < 1e-6 * hanging, "{hanging}");
    cfg.bit.weight_on_bit = 10e6;
    let e = refused(&cfg);
    assert_eq!(e.field(), "bit.weight_on_bit");
    assert!(e.to_string().contains(&format!("at most {} N", Short(hanging))), "{e}");
    cfg.bit.weight_on_bit = 0.0;
    // the hoist's weight above it: warned (the coupled model's hoist then pushes)
    let h = cfg.hoist.as_mut().unwrap();
    h.mode = HoistMode::WeightOnBit;
    h.weight_on_bit = 50e3;
    h.steps = vec![[10.0, 100e6]];
    cfg.validate().unwrap();
    let w = run_warnings(&cfg, 0.0);
    let above = format!(
        "hoist.steps[0][1] = 100000000 N is above the string's buoyed weight along the hole, {} N",
        Short(hanging)
    );
    assert!(w.iter().any(|m| m.starts_with(&above)), "{w:?}");
    cfg.hoist.as_mut().unwrap().steps = vec![[10.0, 0.9 * hanging]];
    assert!(!run_warnings(&cfg, 0.0).iter().any(|m| m.contains("buoyed weight")));
    // the torque and drag's rotating on bottom: refused
    let mut td = DrillConfig::default();
    td.bit.weight_on_bit = 10e6;
    assert_eq!(refused(&td).field(), "bit.weight_on_bit");
}

#[test]
fn a_weight_the_bit_cannot_turn_at_is_warned() {
    let mut cfg = coupled("rgd", "");
    cfg.top_drive.controller.kind = crate::drilling::config::ControllerKind::Pi;
    cfg.top_drive.torque_limit = 10e3;
    let h = cfg.hoist.as_mut().unwrap();
    h.mode = HoistMode::WeightOnBit;
    h.weight_on_bit = 20e3;
    h.steps = vec![[10.0, 250e3]];
    cfg.validate().unwrap();
    let law = cfg.bit.detournay.law(cfg.bit.radius);
    let needed = law.torque_at_weight(250e3);
    assert!(needed > cfg.top_drive.torque_limit, "{needed}");
    let w = run_warnings(&cfg, 0.0);
    let msg = w.iter().find(|m| m.contains("cannot drill")).expect("warned");
    assert!(msg.starts_with("hoist.steps[0][1] = 250000 N") && msg.contains(&Short(needed).to_string()), "{msg}");
    // within the motor: no warning
    cfg.hoist.as_mut().unwrap().steps = vec![[10.0, 30e3]];
    assert!(!run_warnings(&cfg, 0.0).iter().any(|m| m.contains("cannot drill")));
    // the torque at weight inverts the steady state's weight
    let s = law.steady_state(0.01, 6.0);
    assert!((law.torque_at_weight(s.weight_on_bit) - s.torque_on_bit).abs() < 1e-9 * s.torque_on_bit);
}

#[test]
fn block_and_series_speeds_far_outside_practice_are_warned() {
    let mut cfg = coupled("rgd", "");
    cfg.hoist.as_mut().unwrap().speed = 1e6;
    let w = crate::drilling::plausibility::plausibility_warnings(&cfg);
    assert!(w.iter().any(|m| m.starts_with("hoist.speed = 1000000 m/s is over the 3 m/s")), "{w:?}");
    cfg.hoist.as_mut().unwrap().speed = 0.01;
    cfg.hoist.as_mut().unwrap().steps = vec![[5.0, 30.0]];
    let w = crate::drilling::plausibility::plausibility_warnings(&cfg);
    assert!(w.iter().any(|m| m.starts_with("hoist.steps[0][1] = 30 m/s")), "{w:?}");
    let mut cfg = DrillConfig::default();
    cfg.top_drive.mode = TopMode::MeasuredSpeed;
    cfg.top_drive.speed_series = vec![[0.0, 0.0], [60.0, 1000.0]];
    let w = crate::drilling::plausibility::plausibility_warnings(&cfg);
    assert!(w.iter().any(|m| m.contains("1000 rpm") && m.contains("top_drive.speed_series[1][1]")), "{w:?}");
}

fn stations(md: &[f64], inc: &[f64], azi: &[f64]) -> DrillConfig {
    let mut cfg = DrillConfig::default();
    cfg.sections[0].length = 1000.0;
    cfg.well.md = Some(md.to_vec());
    cfg.well.inclination_deg = Inclination::Table(inc.to_vec());
    cfg.well.azimuth_deg = Inclination::Table(azi.to_vec());
    cfg
}

#[test]
fn a_hole_turning_back_within_an_interval_is_refused_naming_the_station() {
    // a 180 degree dogleg in one interval: inclination 0 to 180 is refused as a direction, the
    // reversal of a horizontal hole as a dogleg
    let cfg =
        stations(&[0.0, 100.0, 400.0, 500.0, 1200.0], &[0.0, 0.0, 90.0, 90.0, 90.0], &[0.0, 0.0, 0.0, 0.0, 180.0]);
    let e = refused(&cfg);
    assert_eq!(e.field(), "well.md[4]", "{e}");
    assert!(e.to_string().contains("a dogleg of 180 deg"), "{e}");
    // all horizontal, reversing azimuth
    let cfg = stations(&[0.0, 600.0, 1200.0], &[90.0, 90.0, 90.0], &[0.0, 0.0, 180.0]);
    assert_eq!(refused(&cfg).field(), "well.md[2]");
    // a survey file names the row (1 = the header)
    let dir = std::env::temp_dir().join(format!("drillstring-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("reversing.csv");
    std::fs::write(&path, "md_m,inc_deg,azi_deg\n0,90,0\n600,90,0\n1200,90,180\n").unwrap();
    let mut file = DrillConfig::default();
    file.sections[0].length = 1000.0;
    file.well.md = None;
    file.well.inclination_deg = Inclination::Constant(0.0);
    file.well.survey = Some(path.to_string_lossy().into_owned());
    assert_eq!(refused(&file).field(), "well.survey, row 4");
    // 178 degrees is an arc
    let cfg = stations(&[0.0, 600.0, 1200.0], &[90.0, 90.0, 90.0], &[0.0, 0.0, 178.0]);
    cfg.validate().unwrap();
}

#[test]
fn a_hole_above_the_rig_floor_is_refused_naming_the_station() {
    // down 30 m, then up at 150 degrees for 1000 m: 836 m above the floor
    let cfg = stations(&[0.0, 30.0, 60.0, 1100.0], &[0.0, 0.0, 150.0, 150.0], &[0.0, 0.0, 0.0, 0.0]);
    let e = refused(&cfg);
    assert_eq!(e.field(), "well.md[3]", "{e}");
    assert!(e.to_string().contains("above the rig floor"), "{e}");
    // a straight hole pointing up from the surface, and 180 degrees
    let mut cfg = DrillConfig::default();
    cfg.well.md = None;
    cfg.well.inclination_deg = Inclination::Constant(120.0);
    assert_eq!(refused(&cfg).field(), "well.inclination_deg");
    cfg.well.inclination_deg = Inclination::Constant(180.0);
    let e = refused(&cfg);
    assert!(e.field() == "well.inclination_deg" && e.to_string().contains("[0, 180)"), "{e}");
    // horizontal from the surface stays at TVD 0: accepted
    cfg.well.inclination_deg = Inclination::Constant(90.0);
    cfg.validate().unwrap();
    // a survey going up after going down far enough stays below the floor
    let cfg = stations(&[0.0, 800.0, 900.0, 1100.0], &[0.0, 0.0, 120.0, 120.0], &[0.0, 0.0, 0.0, 0.0]);
    trajectory(&cfg).unwrap();
}

#[test]
fn plans_empty_reversing_or_too_finely_turned_are_refused() {
    let mut cfg = DrillConfig::default();
    cfg.well.md = None;
    cfg.well.inclination_deg = Inclination::Constant(0.0);
    cfg.well.plan = Some(vec![]);
    assert_eq!(refused(&cfg).field(), "well.plan");
    // a turn at 1e-9 deg/30 m would need 1e10 stations: refused before they are allocated
    cfg.well.plan = Some(vec![
        SegmentSpec { hold: Some(100.0), ..Default::default() },
        SegmentSpec { build: Some(3.0), inclination: Some(60.0), ..Default::default() },
        SegmentSpec { turn: Some(1e-9), azimuth: Some(90.0), ..Default::default() },
    ]);
    cfg.well.extend = true;
    let e = refused(&cfg);
    assert_eq!(e.field(), "well.plan[2].turn", "{e}");
    assert!(e.to_string().contains("deg/30 m"), "{e}");
    // a build to 170 degrees is written on stations 90 degrees apart at most: no reversal
    cfg.well.plan = Some(vec![
        SegmentSpec { hold: Some(2000.0), ..Default::default() },
        SegmentSpec { build: Some(10.0), inclination: Some(170.0), ..Default::default() },
    ]);
    let t = trajectory(&cfg).unwrap();
    assert!(t.dogleg.iter().all(|b| b.to_degrees() <= 90.0 + 1e-9), "{:?}", t.dogleg);
    let radius = 30.0 / 10f64.to_radians();
    let tvd = 2000.0 + radius * 170f64.to_radians().sin();
    assert!((t.position.last().unwrap()[2] - tvd).abs() < 1e-9 * tvd, "{:?}", t.position);
}

#[test]
fn torque_drag_inputs_that_would_exhaust_memory_or_time_are_refused() {
    let mut cfg = DrillConfig::default();
    cfg.torque_drag.step = 1e-9;
    let e = refused(&cfg);
    assert_eq!(e.field(), "torque_drag.step");
    assert!(e.to_string().contains("at least 0.0025 m"), "{e}");
    // the analysis itself, without validation
    assert_eq!(crate::drilling::well::torque_drag(&cfg).unwrap_err().field(), "torque_drag.step");
    cfg.torque_drag.step = 1.0;
    cfg.torque_drag.friction_factors = vec![];
    let e = refused(&cfg);
    assert!(e.field() == "torque_drag.friction_factors" && e.to_string().contains("0 factors"), "{e}");
    cfg.torque_drag.friction_factors = vec![0.2; 50];
    cfg.torque_drag.broomstick_points = 100_000;
    let e = refused(&cfg);
    assert_eq!(e.field(), "torque_drag.broomstick_points");
    assert_eq!(crate::drilling::well::broomstick(&cfg).unwrap_err().field(), "torque_drag.broomstick_points");
}

#[test]
fn an_upwind_cut_surface_is_counted_by_the_work_guard() {
    let mut cfg = coupled("rgd", "");
    cfg.bit.detournay.cut_surface = CutSurfaceScheme::Upwind;
    cfg.bit.detournay.cut_surface_cells = 169;
    cfg.validate().unwrap();
    cfg.bit.detournay.cut_surface_cells = 1_000_000;
    let e = refused(&cfg);
    assert_eq!(e.field(), "bit.detournay.cut_surface_cells");
    assert!(e.to_string().contains("an integer in 1..="), "{e}");
    // the largest count it names passes
    let most: u32 = e.to_string().split("1..=").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    cfg.bit.detournay.cut_surface_cells = most;
    cfg.validate().unwrap();
    cfg.bit.detournay.cut_surface_cells = most + 1;
    assert!(cfg.validate().is_err());
}

#[test]
fn an_axis_without_effect_refuses_the_map() {
    let mut cfg = DrillConfig::default();
    cfg.top_drive.mode = TopMode::MeasuredSpeed;
    cfg.top_drive.speed_series = vec![[0.0, 40.0], [60.0, 40.0]];
    let base: serde_json::Value = serde_json::from_str(&cfg.to_json()).unwrap();
    let runs: Vec<Vec<Override>> =
        [40.0, 80.0].iter().map(|r| vec![("top_drive.rpm".to_string(), serde_json::json!(r))]).collect();
    let e = crate::drilling::map::check_axes(&base, &runs).unwrap_err();
    assert!(e.field() == "axis top_drive.rpm" && e.to_string().contains("measured_speed"), "{e}");
    // with the mode an axis too, the rpm changes the controller's runs
    let runs: Vec<Vec<Override>> = ["controller", "measured_speed"]
        .iter()
        .flat_map(|m| {
            [40.0, 80.0].map(|r| {
                vec![
                    ("top_drive.mode".to_string(), serde_json::json!(m)),
                    (
                        "top_drive.speed_series".to_string(),
                        serde_json::json!(if *m == "controller" {
                            serde_json::json!([])
                        } else {
                            serde_json::json!([[0.0, 40.0], [60.0, 40.0]])
                        }),
                    ),
                    ("top_drive.rpm".to_string(), serde_json::json!(r)),
                ]
            })
        })
        .collect();
    crate::drilling::map::check_axes(&base, &runs).unwrap();
}
