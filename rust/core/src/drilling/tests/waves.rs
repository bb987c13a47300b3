//! The string's natural frequencies and waves: the frequency equations solved here by bisection,
//! a square wave at the bit, an absorbed wave at a matched top.

use super::*;

#[test]
fn fixed_top_free_bit_frequencies_are_odd_quarter_waves() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let cfg = frictionless(vec![section(l, od, id)], 500, 8.0);
    for n in 1..=3 {
        let k = (2 * n - 1) as f64 * PI / (2.0 * l);
        let run = released(&cfg, |z| 1e3 * (k * z).cos());
        let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
        let exact = (2 * n - 1) as f64 * c / (4.0 * l);
        eprintln!("mode {n}: f = {f} Hz, exact {exact} Hz, rel {:.2e}", f / exact - 1.0);
        assert!((f / exact - 1.0).abs() < 1e-4, "mode {n}: {f} vs {exact}");
        assert!((run.stats.first_mode_hz / (c / (4.0 * l)) - 1.0).abs() < 1e-9);
        assert_eq!((run.stats.courant_min, run.stats.courant_max), (1.0, 1.0));
    }
}

#[test]
fn bha_inertia_frequency_solves_z_tan_z() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let i_string = RHO * polar(od, id) * l;
    for ratio in [1.0, 0.25] {
        let mut cfg = frictionless(vec![section(l, od, id)], 500, 40.0);
        cfg.bit.bha_inertia = i_string / ratio;
        // z tan z = I_string / I_BHA, z = w L / c
        let z = first_root(|z: f64| z * z.tan() - ratio, PI / 2.0 - 1e-12);
        let w = z * c / l;
        let run = released(&cfg, |x| 1e3 * (w / c * x).cos());
        let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
        let exact = w / (2.0 * PI);
        eprintln!("I_s/I_b = {ratio}: z = {z}, f = {f} Hz, exact {exact} Hz, rel {:.2e}", f / exact - 1.0);
        assert!((f / exact - 1.0).abs() < 2e-3, "{f} vs {exact}");
        assert!((run.stats.first_mode_hz / exact - 1.0).abs() < 1e-9, "{}", run.stats.first_mode_hz);
    }
}

#[test]
fn two_section_string_matches_its_frequency_equation() {
    // Travel times 3:1 so that 400 cells give Courant number 1 in both sections.
    let (od1, id1, od2, id2) = (0.14, 0.1, 0.2, 0.07);
    let c1 = (G / RHO).sqrt();
    let rho2 = 2.0 * RHO;
    let c2 = (G / rho2).sqrt();
    let (l1, t1) = (1500.0, 1500.0 / c1);
    let t2 = t1 / 3.0;
    let l2 = c2 * t2;
    let z1 = polar(od1, id1) * (G * RHO).sqrt();
    let z2 = polar(od2, id2) * (G * rho2).sqrt();
    let mut lower = section(l2, od2, id2);
    lower.density = rho2;
    let cfg = frictionless(vec![section(l1, od1, id1), lower], 400, 40.0);
    // Fixed top, free end: cos(w t1) cos(w t2) - (Z2 / Z1) sin(w t1) sin(w t2) = 0.
    let w = first_root(|w: f64| (w * t1).cos() * (w * t2).cos() - z2 / z1 * (w * t1).sin() * (w * t2).sin(), 20.0);
    // The mode: q = G J theta_z with theta(0) = 0, q(0) = 1, through the junction.
    let theta1 = (w * t1).sin() / (z1 * w);
    let q1 = (w * t1).cos();
    let mode = move |z: f64| {
        if z <= l1 {
            1e3 * (w * z / c1).cos()
        } else {
            let x = (z - l1) / c2;
            1e3 * (-z2 * w * theta1 * (w * x).sin() + q1 * (w * x).cos())
        }
    };
    let run = released(&cfg, mode);
    assert_eq!((run.stats.courant_min, run.stats.courant_max), (1.0, 1.0));
    let f = 1.0 / crossing_period(&run.t, &run.bit_rpm);
    let exact = w / (2.0 * PI);
    eprintln!("two sections (Z2/Z1 = {:.3}): f = {f} Hz, exact {exact} Hz, rel {:.2e}", z2 / z1, f / exact - 1.0);
    assert!((f / exact - 1.0).abs() < 1e-4, "{f} vs {exact}");
    assert!((run.stats.first_mode_hz / exact - 1.0).abs() < 1e-9);
    // No energy is made or lost at the junction (Courant 1, no friction, no damping).
    assert!(run.energy.numerical_loss.abs() < 1e-12 * run.energy.initial, "{:?}", run.energy);
    assert!(((run.energy.kinetic + run.energy.elastic) / run.energy.initial - 1.0).abs() < 1e-12);
}

#[test]
fn top_speed_step_gives_a_square_wave_at_the_bit() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let mut cfg = frictionless(vec![section(l, od, id)], 200, 3.0);
    cfg.top_drive.rpm = 60.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let (t_travel, dt) = (l / c, run.stats.dt);
    let mut checked = 0;
    for (t, rpm) in run.t.iter().zip(&run.bit_rpm) {
        let phase = t / t_travel; // 0 for phase in (0, 1), 120 rpm in (1, 3), 0 in (3, 5), ...
        let nearest_odd = 2.0 * ((phase - 1.0) / 2.0).round() + 1.0;
        if (phase - nearest_odd).abs() * t_travel < 3.0 * dt {
            continue;
        }
        let expected = if phase < 1.0 || ((phase - 1.0) / 2.0).floor() as i64 % 2 == 1 { 0.0 } else { 120.0 };
        assert!((rpm - expected).abs() < 1e-9, "t = {t}: {rpm} rpm, expected {expected}");
        checked += 1;
    }
    assert!(checked > run.t.len() * 9 / 10);
    // The period of the bit speed is 4 L / c.
    let centred: Vec<f64> = run.bit_rpm.iter().map(|r| r - 60.0).collect();
    let period = crossing_period(&run.t, &centred);
    assert!((period / (4.0 * t_travel) - 1.0).abs() < 1e-3, "{period} vs {}", 4.0 * t_travel);
}

/// String energy summed here from the snapshot `k` of a run: `sum h (rho J w^2 + tau^2 / (G J)) / 2`.
fn field_energy(run: &DrillRun, k: usize, h: f64, j: f64) -> f64 {
    let nz = run.z.len();
    (0..nz)
        .map(|i| {
            let w = run.omega_field[k * nz + i] / RPM;
            let tau = run.torque_field[k * nz + i];
            0.5 * h * (RHO * j * w * w + tau * tau / (G * j))
        })
        .sum()
}

#[test]
fn z_torque_absorbs_the_incident_wave() {
    let (l, od, id) = (1000.0, 0.14, 0.1);
    let c = (G / RHO).sqrt();
    let (j, cells) = (polar(od, id), 500);
    let z = j * (G * RHO).sqrt();
    // (z_factor, torque high-pass time, expected reflected energy fraction ((1 - z) / (1 + z))^2)
    for (z_factor, highpass, expected) in [(1.0, 20.0 / (2.0 * PI), 0.0), (1.0, 1e12, 0.0), (3.0, 1e12, 0.25)] {
        let mut cfg = frictionless(vec![section(l, od, id)], cells, 0.8 * l / c);
        cfg.top_drive.controller.kind = ControllerKind::ZTorque;
        cfg.top_drive.controller.z_factor = z_factor;
        cfg.top_drive.controller.torque_highpass_time = highpass;
        cfg.numerics.field_interval = cfg.numerics.duration;
        // An upward pulse: alpha = 0, beta = B exp(-((z - L/4) / (L/40))^2): omega = beta/2, tau = -Z beta/2.
        let pulse = |x: f64| 0.5 * (-((x - 0.25 * l) / (0.025 * l)).powi(2)).exp();
        let mut sim = Simulation::new(&cfg).unwrap();
        let zc = sim.grid().z.clone();
        let w: Vec<f64> = zc.iter().map(|&x| pulse(x)).collect();
        let tau: Vec<f64> = w.iter().map(|w| -z * w).collect();
        sim.set_state(&w, &tau, 0.0, 0.0).unwrap();
        let run = sim.run(&Never, &mut |_| {});
        assert_eq!(run.field_t.len(), 2);
        let h = l / cells as f64;
        let ratio = field_energy(&run, 1, h, j) / field_energy(&run, 0, h, j);
        eprintln!(
            "z_factor {z_factor}, high-pass {highpass} s: reflected energy fraction {ratio:.3e}, expected {expected}"
        );
        if expected == 0.0 {
            // The slow-torque feedback (the high-pass) reflects a little of the pulse's mean.
            let bound = if highpass < 1e3 { 1e-3 } else { 1e-12 };
            assert!(ratio < bound, "reflection {ratio}");
        } else {
            assert!((ratio / expected - 1.0).abs() < 0.02, "{ratio}");
        }
    }
}
