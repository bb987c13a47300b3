//! The top boundary's seam: a command source implementing [`TopCommand`], registered in
//! [`Top`], run through the engine against the angular momentum balance of a free string.

use super::controller::{Command, Top, TopCommand, TopInput};
use super::run::Simulation;
use crate::drilling::config::{DrillConfig, TopDrive};

/// A motor torque held constant, N m.
#[derive(Debug, Clone, Copy)]
pub struct ConstantTorque(pub f64);

impl TopCommand for ConstantTorque {
    fn command(&mut self, _td: &TopDrive, _input: &TopInput) -> Command {
        Command::Torque(self.0)
    }
}

/// A 1000 m vertical 5-in string off bottom, without wall friction or damping.
fn free_string() -> DrillConfig {
    let json = r#"{"sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "bit": {"on_bottom": false}, "friction": {"static": 0.0}, "damping_rate": 0.0,
        "numerics": {"cells": 100, "duration": 20.0}}"#;
    DrillConfig::from_json(json).unwrap()
}

/// The angular momentum of the top drive, the string's cells and the BHA, N m s, and their
/// inertia, kg m^2.
fn momentum(sim: &Simulation) -> (f64, f64) {
    let f = &sim.torsion.field;
    let (mut l, mut inertia) = (sim.top.inertia * sim.top.omega, sim.top.inertia + sim.bit.inertia);
    for (s, sp) in f.sections.iter().enumerate() {
        // the cell's inertia rho J h is 4 e
        for j in 1..=sp.cells {
            l += 4.0 * sp.e * f.cell(s, j).0;
        }
        inertia += 4.0 * sp.e * sp.cells as f64;
    }
    (l + sim.bit.inertia * sim.bit.omega, inertia)
}

/// A constant torque at the top of a free string: the momentum is `tau t` every step (the
/// scheme conserves it exactly but for rounding) and the top speed, about which the string's
/// torsional waves ring, grows as the rigid body's `tau t / I`.
#[test]
fn a_top_command_plugged_in_drives_a_free_string_as_a_rigid_body() {
    let torque = 5000.0;
    let mut sim = Simulation::new(&free_string()).unwrap();
    sim.drive = Top::Test(ConstantTorque(torque));
    let dt = sim.grid.dt;
    let steps = (20.0 / dt).round() as usize;
    let mut top = Vec::with_capacity(steps);
    for k in 0..steps {
        sim.step(k as f64 * dt);
        top.push(sim.top.omega);
    }
    let t = steps as f64 * dt;
    let (l, inertia) = momentum(&sim);
    assert!((l - torque * t).abs() <= 1e-11 * torque * t, "momentum {l} vs tau t = {}", torque * t);
    // the top speed's mean over the last 5 s against the rigid body's at their middle
    let last = &top[steps - (5.0 / dt).round() as usize..];
    let mean = last.iter().sum::<f64>() / last.len() as f64;
    let rigid = torque * (t - 2.5) / inertia;
    assert!((mean - rigid).abs() < 0.02 * rigid, "mean top speed {mean} vs rigid {rigid} rad/s");
    assert!(sim.ledger.motor > 0.0);
}
