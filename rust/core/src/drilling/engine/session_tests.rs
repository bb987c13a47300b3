//! A session against the batch run: stepped in uneven chunks, changed by `set`, by `steps` and by
//! `[[changes]]`, snapshot and continued; refused keys and values; a runaway's status.

use serde_json::json;

use super::*;
use crate::drilling::config::Change;
use crate::drilling::solve;
use crate::interrupt::{CancelFlag, Never};

/// A short torsion-only run on bottom (velocity-weakening bit) in a deviated well, on few cells.
fn torsional() -> DrillConfig {
    DrillConfig::from_value(json!({
        "damping_rate": 0.3,
        "sections": [
            {"length": 3000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086},
            {"length": 200.0, "outer_diameter": 0.1651, "inner_diameter": 0.0714}],
        "well": {"md": [0.0, 800.0, 1800.0, 4000.0], "inclination_deg": [0.0, 0.0, 30.0, 30.0],
                 "mud_density": 1200.0},
        "friction": {"static": 0.25, "kinetic_ratio": 0.8, "stick_speed": 0.1, "contact": "weight"},
        "top_drive": {"inertia": 2900.0, "rpm": 40.0, "ramp_time": 1.0,
                      "controller": {"type": "pi", "kp": 38e3, "ki": 100e3}},
        "bit": {"on_bottom": true, "weight_on_bit": 80e3, "radius": 0.108, "bha_inertia": 100.0},
        "numerics": {"cells": 60, "duration": 12.0, "output_interval": 0.01, "field_interval": 0.5}
    }))
    .unwrap()
}

/// The same string coupled: the depth-of-cut bit and a hoist holding the weight on bit.
fn coupled() -> DrillConfig {
    let mut value = serde_json::to_value(torsional()).unwrap();
    value["bit"] = json!({"law": "rgd", "radius": 0.108, "bha_inertia": 100.0, "bha_mass": 20e3});
    value["hoist"] = json!({"mode": "weight_on_bit", "weight_on_bit": 120e3, "ramp_time": 2.0});
    DrillConfig::from_value(value).unwrap()
}

/// Steps `s` by each of `chunks` (s), then to the duration.
fn step_through(s: &mut Session, chunks: &[f64]) {
    for &c in chunks {
        assert!(!s.advance(s.steps_for(c), &Never, &mut |_| {}));
    }
    let rest = s.config().numerics.duration - s.t();
    assert!(!s.advance(s.steps_for(rest), &Never, &mut |_| {}));
}

fn same_series(a: &DrillRun, b: &DrillRun) {
    assert_eq!(a.status, b.status, "{} / {}", a.message, b.message);
    for (x, y) in [
        (&a.t, &b.t),
        (&a.surface_rpm, &b.surface_rpm),
        (&a.bit_rpm, &b.bit_rpm),
        (&a.motor_torque, &b.motor_torque),
        (&a.bit_torque, &b.bit_torque),
        (&a.rop, &b.rop),
        (&a.weight_on_bit, &b.weight_on_bit),
        (&a.hook_load, &b.hook_load),
    ] {
        assert_eq!(x.len(), y.len());
        assert!(x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()), "series differ");
    }
}

/// `numerics.energy_balance = false`: every series and snapshot the run with the ledger's,
/// bit for bit (torsion alone at Courant numbers 1 and below, coupled), every energy output
/// NaN and a warning saying so.
#[test]
fn a_run_without_the_ledger_is_the_run_with_it_bit_for_bit() {
    let slower = |cfg: DrillConfig| {
        let mut value = serde_json::to_value(cfg).unwrap();
        value["numerics"]["courant"] = json!(0.93);
        DrillConfig::from_value(value).unwrap()
    };
    for cfg in [torsional(), coupled(), slower(torsional()), slower(coupled())] {
        let kept = solve(&cfg, &Never, &mut |_| {}).unwrap();
        assert_eq!(kept.status, Status::Success, "{}", kept.message);
        assert!(kept.energy.balance_error.abs() < 1e-11, "{:?}", kept.energy);
        let mut value = serde_json::to_value(&cfg).unwrap();
        value["numerics"]["energy_balance"] = json!(false);
        let off = solve(&DrillConfig::from_value(value).unwrap(), &Never, &mut |_| {}).unwrap();
        same_series(&off, &kept);
        for (x, y) in [
            (&off.omega_field, &kept.omega_field),
            (&off.torque_field, &kept.torque_field),
            (&off.bit_axial_speed, &kept.bit_axial_speed),
            (&off.bit_depth, &kept.bit_depth),
        ] {
            assert!(x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()));
        }
        assert_eq!(format!("{:?}", off.metrics), format!("{:?}", kept.metrics));
        assert_eq!(format!("{:?}", off.coupled), format!("{:?}", kept.coupled));
        let e = serde_json::to_value(off.energy).unwrap();
        assert!(e.as_object().unwrap().values().all(|v| v.as_f64().is_none_or(f64::is_nan)), "{e}");
        assert!(off.energy.balance_error.is_nan() && off.energy.motor_work.is_nan());
        assert_eq!(off.warnings.iter().filter(|w| w.as_str() == NOT_KEPT).count(), 1);
        assert!(!kept.warnings.iter().any(|w| w.contains("energy_balance")));
        let rest: Vec<_> = off.warnings.iter().filter(|w| w.as_str() != NOT_KEPT).collect();
        assert_eq!(rest, kept.warnings.iter().collect::<Vec<_>>());
    }
}

#[test]
fn a_session_stepped_in_uneven_chunks_is_the_batch_run_bit_for_bit() {
    for cfg in [torsional(), coupled()] {
        let batch = solve(&cfg, &Never, &mut |_| {}).unwrap();
        assert_eq!(batch.status, Status::Success, "{}", batch.message);
        let mut s = Session::new(&cfg, true).unwrap();
        step_through(&mut s, &[0.013, 2.5, 0.0, 3.77]);
        assert_eq!(s.steps(), batch.stats.steps);
        let r = s.result(None);
        same_series(&r, &batch);
        assert_eq!(r.omega_field, batch.omega_field);
        assert_eq!(r.field_t, batch.field_t);
        // (Debug: NaN metrics compare equal as text)
        assert_eq!(format!("{:?}", r.energy), format!("{:?}", batch.energy));
        assert_eq!(format!("{:?}", r.metrics), format!("{:?}", batch.metrics));
        assert_eq!(format!("{:?}", r.coupled), format!("{:?}", batch.coupled));
        assert_eq!(r.warnings, batch.warnings);
    }
}

#[test]
fn set_at_a_time_is_a_steps_entry_and_a_changes_entry_at_it() {
    for base in [torsional(), coupled()] {
        let t = 5.0;
        let mut stepped = base.clone();
        stepped.top_drive.steps = vec![[t, 80.0]];
        let by_steps = solve(&stepped, &Never, &mut |_| {}).unwrap();
        let mut changed = base.clone();
        changed.changes = vec![Change { time: t, key: "top_drive.rpm".into(), value: json!(80.0) }];
        let by_changes = solve(&changed, &Never, &mut |_| {}).unwrap();
        let mut s = Session::new(&base, false).unwrap();
        s.advance(s.steps_for(t), &Never, &mut |_| {});
        s.set("top_drive.rpm", &json!(80.0)).unwrap();
        assert_eq!(s.applied()[0].time, s.t());
        step_through(&mut s, &[]);
        let by_set = s.result(None);
        same_series(&by_steps, &by_set);
        same_series(&by_steps, &by_changes);
        // the change did something: the last half turns near 80 rpm, not 40
        let last = *by_set.surface_rpm.last().unwrap();
        assert!(last > 60.0, "{last}");
    }
}

#[test]
fn a_snapshot_continues_bit_for_bit() {
    for cfg in [torsional(), coupled()] {
        let mut s = Session::new(&cfg, true).unwrap();
        s.advance(s.steps_for(3.3), &Never, &mut |_| {});
        let mut copy = s.clone();
        for x in [&mut s, &mut copy] {
            x.set("friction.static", &json!(0.3)).unwrap();
            x.advance(x.steps_for(2.0), &Never, &mut |_| {});
        }
        same_series(&s.result(None), &copy.result(None));
        assert_eq!(s.state(), copy.state());
    }
}

#[test]
fn a_key_that_cannot_change_or_a_value_out_of_range_is_refused_naming_the_key() {
    let mut s = Session::new(&torsional(), false).unwrap();
    let e = s.set("numerics.cells", &json!(100)).unwrap_err();
    assert_eq!(e.field(), "numerics.cells");
    assert!(e.to_string().contains("cannot change during a run"), "{e}");
    let e = s.set("friction.static", &json!(-1.0)).unwrap_err();
    assert_eq!(e.field(), "friction.static");
    assert!(e.to_string().contains(">= 0") || e.to_string().contains("[0"), "{e}");
    let e = s.set("hoist.speed", &json!(0.01)).unwrap_err();
    assert_eq!(e.field(), "hoist.speed");
    assert!(s.applied().is_empty());
    // a refused changes entry names it
    let mut cfg = torsional();
    cfg.changes = vec![Change { time: 1.0, key: "top_drive.inertia".into(), value: json!(1.0) }];
    assert_eq!(cfg.validate().unwrap_err().field(), "changes[0].key");
    cfg.changes = vec![Change { time: 13.0, key: "top_drive.rpm".into(), value: json!(1.0) }];
    assert_eq!(cfg.validate().unwrap_err().field(), "changes[0].time");
    cfg.changes = vec![Change { time: 1.0, key: "friction.static".into(), value: json!(-2.0) }];
    assert_eq!(cfg.validate().unwrap_err().field(), "changes[0].value");
}

#[test]
fn a_session_grows_past_the_duration_and_an_interrupt_leaves_it_usable() {
    let cfg = torsional();
    let mut s = Session::new(&cfg, false).unwrap();
    let flag = CancelFlag::new();
    flag.cancel();
    assert!(s.advance(s.steps_for(1.0), &flag, &mut |_| {}));
    assert_eq!(s.status(), Status::Success);
    s.advance(s.steps_for(cfg.numerics.duration + 3.0), &Never, &mut |_| {});
    let r = s.result(None);
    assert!(r.field_t.is_empty());
    let last = *r.t.last().unwrap();
    assert!((last - (cfg.numerics.duration + 3.0)).abs() < 0.011, "{last}");
    assert_eq!(r.t.len(), r.bit_rpm.len());
    assert!((r.window[1] - s.t()).abs() < 1e-12);
}

#[test]
fn a_runaway_ends_the_session_with_a_status() {
    let cfg = torsional();
    let mut sim = Simulation::new(&cfg).unwrap();
    let n = sim.grid().cells();
    let fast = 2.0 * RUNAWAY_FACTOR * 40.0 / RPM_PER_RAD_S;
    sim.set_state(&vec![fast; n], &vec![0.0; n], 0.0, fast).unwrap();
    let mut s = Session::start(sim, false, false);
    assert!(!s.advance(10, &Never, &mut |_| {}));
    assert_eq!(s.status(), Status::NonFinite);
    assert!(s.message().contains("diverged"), "{}", s.message());
    let steps = s.steps();
    s.advance(10, &Never, &mut |_| {});
    assert_eq!(s.steps(), steps);
}

#[test]
fn a_session_resumed_from_its_changes_and_steps_is_the_same_session() {
    for mut cfg in [torsional(), coupled()] {
        // a configuration change still to come when resumed is kept, one made is not made twice
        cfg.changes = vec![
            Change { time: 1.0, key: "friction.static".into(), value: json!(0.3) },
            Change { time: 6.0, key: "top_drive.rpm".into(), value: json!(60.0) },
        ];
        let mut s = Session::new(&cfg, true).unwrap();
        s.advance(s.steps_for(2.0), &Never, &mut |_| {});
        s.set("top_drive.rpm", &json!(70.0)).unwrap();
        s.advance(s.steps_for(1.7), &Never, &mut |_| {});
        let mut again = Session::resume(&cfg, s.applied(), s.steps(), true, &Never).unwrap();
        assert_eq!(again.applied(), s.applied());
        for x in [&mut s, &mut again] {
            step_through(x, &[]);
        }
        assert_eq!(s.applied().len(), 3);
        same_series(&s.result(None), &again.result(None));
        assert_eq!(s.state(), again.state());
    }
}
