//! Tests of the drilling system against independently computed numbers.

use super::config::*;
use super::*;
use crate::interrupt::Never;

fn well_b() -> DrillConfig {
    DrillConfig::default()
}

#[test]
fn smoke_well_b() {
    let cfg = well_b();
    let t0 = std::time::Instant::now();
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    eprintln!("{:?} {:?}", t0.elapsed(), run.stats);
    eprintln!("{:?}", run.energy);
    eprintln!("{:?} breakoff {}", run.metrics, run.breakoff_torque);
    let n = run.t.len();
    for k in (0..n).step_by(n / 30) {
        eprintln!("{:7.2} {:8.2} {:8.2} {:10.1}", run.t[k], run.surface_rpm[k], run.bit_rpm[k], run.motor_torque[k]);
    }
}
