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

/// Aarsnes & Shor's Well B (MD 2500 m, their collar's Jc with its extra pi, Ac and a density
/// giving the pipe's wave speed, damping rate `2 kt dt_sub`) on 1000 cells for `duration` s.
fn well_b(duration: f64) -> DrillConfig {
    let json = format!(
        r#"{{
      "sections": [
        {{"length": 2270.0, "outer_diameter": 0.146529, "inner_diameter": 0.123024,
         "shear_modulus": 61e9, "density": 7850.0}},
        {{"length": 230.0, "outer_diameter": 0.19425788212135248, "inner_diameter": 0.09285466808235807,
         "shear_modulus": 67e9, "density": 8622.131147540984,
         "polar_moment": 4.7067114136638673e-4, "area": 0.02286618845760419}}],
      "damping_rate": 0.08333333333333334,
      "friction": {{"contact": "weight"}},
      "numerics": {{"cells": 1000, "duration": {duration:?}, "field_interval": 0}}
    }}"#
    );
    DrillConfig::from_json(&json).unwrap()
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

mod checks;
mod consistent;
mod friction;
mod runs;
mod waves;
