//! The `consistent` nonlinearity: the tangent wave speed, the PDE solver at first order, the
//! energy balance, the linear limit.

use super::*;

/// `k2 = G I_p`, `k5 = M J4 / 2` of a solid rod of diameter `d` (computed here:
/// `I_p = pi R^4 / 2`, `J4 = pi R^6 / 3`, `M = 2 G (1 - nu) / (1 - 2 nu)`).
fn rod_coefficients(d: f64, g: f64, nu: f64) -> (f64, f64) {
    let r = d / 2.0;
    let m = 2.0 * g * (1.0 - nu) / (1.0 - 2.0 * nu);
    (g * PI * r.powi(4) / 2.0, m * PI * r.powi(6) / 3.0 / 2.0)
}

/// A solid rod of an almost incompressible material (`M / G ~ 500`), so that the hardening
/// is resolvable at moderate twists.
fn soft_rod(length: f64) -> Section {
    Section { poisson_ratio: 0.499, ..section(length, 0.1, 0.0) }
}

#[test]
fn linear_runs_are_unchanged() {
    // Well B and the loaded case of `energy_balance_closes` with the default (linear) law:
    // numbers recorded before the consistent law was added, digit for digit.
    let cfg = well_b(20.0);
    assert_eq!(cfg.nonlinearity, Nonlinearity::Linear);
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let sum = |x: &[f64]| x.iter().sum::<f64>();
    let got = [sum(&run.bit_rpm), sum(&run.motor_torque), run.energy.motor_work, run.energy.friction_loss];
    eprintln!("Well B 20 s: {got:?}");
    assert_eq!(got, WELL_B_FINGERPRINT);
    let mut cfg = loaded(FrictionModel::SetValued);
    cfg.numerics.duration = 10.0;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    let got = [sum(&run.bit_rpm), sum(&run.motor_torque), run.energy.motor_work, run.energy.upwind_loss];
    eprintln!("loaded 10 s: {got:?}");
    assert_eq!(got, LOADED_FINGERPRINT);
}

// The bit speed's sum changed (52937.993822556935 before) when the end below a stuck last cell
// was reported at rest instead of creeping; the motor torque and the energies, the dynamics, did not.
const WELL_B_FINGERPRINT: [f64; 4] = [52918.07308358484, 27686614.84156269, 1122349.7601874035, 782097.2279241397];
const LOADED_FINGERPRINT: [f64; 4] = [22612.652434214873, 13708014.63578681, 536085.6656196791, 27.580043507515068];

#[test]
fn consistent_with_k5_zero_is_the_linear_scheme() {
    // The loaded case (two sections at Courant numbers < 1, friction with sticking, damping,
    // PI with a torque limit, bit on bottom with a BHA): the Godunov scheme with k5 = 0 is the
    // upwind scheme of the invariants, up to rounding.
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let mut cfg = loaded(model);
        cfg.numerics.duration = 4.0;
        let linear = solve(&cfg, &Never, &mut |_| {}).unwrap();
        cfg.nonlinearity = Nonlinearity::Consistent;
        cfg.numerics.max_shear_strain = 1e-12; // the step of the linear speed
        let mut sim = Simulation::new(&cfg).unwrap();
        assert_eq!(sim.grid().counts, Grid::new(&loaded(model)).unwrap().counts);
        sim.zero_quartic();
        let godunov = sim.run(&Never, &mut |_| {});
        assert_eq!(godunov.status, Status::Success, "{}", godunov.message);
        let diff = |a: &[f64], b: &[f64]| {
            let scale = a.iter().fold(f64::MIN_POSITIVE, |m: f64, x| m.max(x.abs()));
            a.iter().zip(b).fold(0.0, |m: f64, (x, y)| m.max((x - y).abs())) / scale
        };
        let d = [
            diff(&linear.bit_rpm, &godunov.bit_rpm),
            diff(&linear.surface_rpm, &godunov.surface_rpm),
            diff(&linear.motor_torque, &godunov.motor_torque),
            diff(&linear.omega_field, &godunov.omega_field),
            diff(&linear.torque_field, &godunov.torque_field),
        ];
        let (a, b) = (linear.energy, godunov.energy);
        eprintln!("{model:?}: relative differences {d:?}; upwind loss {} vs {}", a.upwind_loss, b.upwind_loss);
        assert!(d.iter().all(|&x| x < 1e-9), "{d:?}");
        assert!((a.upwind_loss / b.upwind_loss - 1.0).abs() < 1e-6, "{} {}", a.upwind_loss, b.upwind_loss);
        assert!((a.friction_loss / b.friction_loss - 1.0).abs() < 1e-9);
        assert!(b.balance_error.abs() < 1e-11, "{b:?}");
    }
}

#[test]
fn consistent_pulse_travels_at_the_tangent_speed() {
    // A rod twisted uniformly to eps0 (bit stuck, top held), then a small top-speed step: the
    // front travels at the tangent speed sqrt((k2 + 3 k5 eps0^2) / (rho I_p)), 9.5 % above
    // sqrt(G / rho) here, and carries the torque jump Z(eps0) d_omega.
    let (length, g, nu, d) = (1000.0, G, 0.499, 0.1);
    let (k2, k5) = rod_coefficients(d, g, nu);
    let k1 = RHO * k2 / g;
    let eps0 = 2.0 * 0.02 / d; // shear strain 0.02 at the surface
    let tau0 = k2 * eps0 + k5 * eps0.powi(3);
    let tangent = ((k2 + 3.0 * k5 * eps0 * eps0) / k1).sqrt();
    let linear = (g / RHO).sqrt();
    let mut cfg = frictionless(vec![soft_rod(length)], 2000, 0.5 * length / tangent);
    cfg.nonlinearity = Nonlinearity::Consistent;
    cfg.numerics.max_shear_strain = 0.025;
    cfg.numerics.field_interval = cfg.numerics.duration;
    // a bit held by the rock: a static torque of 1 MN m (500 kN, within the rod's 605 kN buoyed
    // weight, on a 1 m bit at mu_s = 2) above tau0
    cfg.bit =
        Bit { on_bottom: true, weight_on_bit: 5e5, radius: 1.0, mu_static: 2.0, mu_kinetic: 0.5, ..Bit::default() };
    let rpm = 1.0;
    cfg.top_drive.rpm = rpm;
    let dw = rpm / RPM;
    let mut sim = Simulation::new(&cfg).unwrap();
    let n = sim.grid().cells();
    sim.set_state(&vec![0.0; n], &vec![tau0; n], 0.0, 0.0).unwrap();
    let (w, tau) = sim.fields();
    assert!(w.iter().all(|&x| x == 0.0) && tau.iter().all(|t| (t / tau0 - 1.0).abs() < 1e-14));
    let run = sim.run(&Never, &mut |_| {});
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.stats.courant_peak <= 1.0 && run.stats.courant_max == 1.0, "{:?}", run.stats);
    assert!(run.bit_rpm.iter().all(|&w| w == 0.0), "the bit held");
    let t = run.field_t[1];
    let row = &run.torque_field[n..];
    let jump = row[0] - tau0;
    let expected_jump = (k1 * (k2 + 3.0 * k5 * eps0 * eps0)).sqrt() * dw;
    // The front: where the torque has risen by half the jump.
    let k = row.iter().position(|&x| x - tau0 < 0.5 * jump).unwrap();
    let (a, b) = (row[k - 1] - tau0 - 0.5 * jump, row[k] - tau0 - 0.5 * jump);
    let front = run.z[k - 1] + (run.z[k] - run.z[k - 1]) * a / (a - b);
    let speed = front / t;
    eprintln!(
        "front at {front:.2} m after {t:.5} s: {speed:.2} m/s, tangent {tangent:.2}, linear {linear:.2}; \
         jump {jump:.2} N m vs Z(eps0) dw = {expected_jump:.2}"
    );
    assert!((speed / tangent - 1.0).abs() < 2e-3, "{speed} vs {tangent}");
    assert!((jump / expected_jump - 1.0).abs() < 1e-3, "{jump} vs {expected_jump}");
    assert!(tangent / linear > 1.09);
}

/// Bit speed (rad/s) of a rod of length `l` with the top fixed and the bit free, released from
/// rest with the twist `eps(x) = s cos(pi x / (2 l))`, by the finite-difference PDE solver on
/// the rod of length `2 l` free at both ends whose twist is odd about its middle (which stays
/// at rest: the fixed top), at the times `times`.
fn pde_bit_speed(k: crate::pde::PdeCoefficients, l: f64, s: f64, times: &[f64], nodes: usize) -> Vec<f64> {
    use crate::integrators::{solve_second_order, Method, SolveOptions};
    use crate::options::Output;
    let sys = crate::pde::PdeSystem::new(k, 2.0 * l, nodes).unwrap();
    let q0: Vec<f64> = sys.positions().iter().map(|&z| -s * 2.0 * l / PI * (PI * (z - l) / (2.0 * l)).sin()).collect();
    let opts = SolveOptions { rtol: 1e-11, atol: 1e-14, ..SolveOptions::new(Method::Dop853) };
    let sol = solve_second_order(
        &sys,
        0.0,
        &q0,
        &vec![0.0; nodes],
        *times.last().unwrap(),
        &Output::Times(times.to_vec()),
        &opts,
    )
    .unwrap();
    assert_eq!(sol.status, Status::Success, "{}", sol.message);
    (0..sol.len()).map(|i| sol.state(i)[2 * nodes - 1]).collect()
}

#[test]
fn consistent_agrees_with_the_pde_solver_at_first_order() {
    // A fixed-free rod released from a large twist (shear strain 0.01 at the top, where the
    // tangent stiffness is 5 % above G I_p), no friction: the bit speed over two travel times
    // against the finite-difference solver of the consistent PDE (k1 th_tt = k2 th_zz +
    // k5 (th_z^3)_z, second order in h, DOP853), and the order of convergence in the cells.
    let (l, g, nu, d) = (1000.0, G, 0.499, 0.1);
    let (k2, k5) = rod_coefficients(d, g, nu);
    let k1 = RHO * k2 / g;
    let s = 2.0 * 0.01 / d;
    let duration = 2.0 * l / (g / RHO).sqrt();
    let out = 1e-3;
    let times: Vec<f64> = (0..=(duration / out * (1.0 + 1e-12)).floor() as usize).map(|i| i as f64 * out).collect();
    let k = crate::pde::PdeCoefficients { k1, k2, k3: 0.0, k4: 0.0, k5, k6: 0.0 };
    let reference = pde_bit_speed(k, l, s, &times, 2001);
    let linear = pde_bit_speed(crate::pde::PdeCoefficients { k5: 0.0, ..k }, l, s, &times, 2001);
    let scale = reference.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
    let gap = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0, |m: f64, (x, y)| m.max((x - y).abs())) / scale;
    let nonlinear_effect = gap(&reference, &linear);
    let cells = [50, 100, 200, 400, 800];
    let mut errors = Vec::new();
    for &m in &cells {
        let mut cfg = frictionless(vec![soft_rod(l)], m, duration);
        cfg.nonlinearity = Nonlinearity::Consistent;
        cfg.numerics.max_shear_strain = 0.01;
        cfg.numerics.output_interval = out;
        let mut sim = Simulation::new(&cfg).unwrap();
        let z = sim.grid().z.clone();
        let p = sim.grid().props[0];
        let tau: Vec<f64> = z.iter().map(|&x| p.torque(s * (PI * x / (2.0 * l)).cos())).collect();
        sim.set_state(&vec![0.0; z.len()], &tau, 0.0, 0.0).unwrap();
        let run = sim.run(&Never, &mut |_| {});
        assert_eq!(run.status, Status::Success, "{}", run.message);
        assert_eq!(run.t.len(), times.len());
        assert!(run.stats.courant_peak <= 1.0 + 1e-12, "{:?}", run.stats);
        let bit: Vec<f64> = run.bit_rpm.iter().map(|r| r / RPM).collect();
        let e = run.energy;
        assert!(e.balance_error.abs() < 1e-12 && e.upwind_loss > 0.0, "{e:?}");
        errors.push(gap(&bit, &reference));
        eprintln!(
            "{m} cells: error {:.3e}, transport loss {:.3e} of {:.3e} J",
            errors.last().unwrap(),
            e.upwind_loss,
            e.initial
        );
    }
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("nonlinear effect (PDE k5 vs k5 = 0) {nonlinear_effect:.3e}; errors {errors:?}; orders {orders:?}");
    assert!(orders[2..].iter().all(|&p| (p - 1.0).abs() < 0.25), "{orders:?}");
    assert!(errors[4] < 0.1 * nonlinear_effect, "{errors:?} vs {nonlinear_effect}");
}

#[test]
fn consistent_energy_balance_closes() {
    for model in [FrictionModel::SetValued, FrictionModel::Regularised] {
        let mut cfg = loaded(model);
        cfg.nonlinearity = Nonlinearity::Consistent;
        let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
        let e = run.energy;
        eprintln!("consistent {model:?}: {e:?} courant {:?}", run.stats);
        assert_eq!(run.status, Status::Success);
        assert!(run.message.is_empty(), "{}", run.message);
        assert!(run.stats.courant_max <= 1.0 && run.stats.courant_peak <= run.stats.courant_max);
        assert!(e.balance_error.abs() < 1e-11, "{e:?}");
        assert!(e.motor_work > 0.0 && e.friction_loss > 0.0 && e.damping_loss > 0.0 && e.bit_loss > 0.0);
        assert!(e.upwind_loss > 0.0 && e.numerical_loss < 0.05 * e.motor_work, "{e:?}");
        let change = e.kinetic + e.elastic + e.top_drive + e.bha - e.initial;
        let losses = e.friction_loss + e.damping_loss + e.bit_loss + e.numerical_loss;
        assert!((e.motor_work - change - losses).abs() < 1e-10 * e.motor_work);
    }
    // Strains beyond numerics.max_shear_strain (a uniform string at Courant number 1 for
    // 1e-6): the run says so.
    let mut cfg = frictionless(vec![section(1000.0, 0.14, 0.1)], 200, 1.0);
    cfg.top_drive.rpm = 60.0;
    cfg.nonlinearity = Nonlinearity::Consistent;
    cfg.numerics.max_shear_strain = 1e-6;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.stats.courant_max, 1.0);
    assert!(run.stats.courant_peak > 1.0, "{:?}", run.stats);
    assert!(run.message.contains("numerics.max_shear_strain"), "{}", run.message);
}

#[test]
fn well_b_with_the_consistent_law_changes_little() {
    // Shear strains of Well B stay near 1e-3, where the tangent stiffness differs from G J by
    // ~1e-5. Three runs separate the two changes the option makes: the law (consistent against
    // the same scheme and grid with k5 = 0) and the discretisation (the Godunov scheme on the grid
    // of the hardened speed, Courant numbers just below 1, against the linear scheme at 1).
    let mut cfg = well_b(60.0);
    let base = solve(&cfg, &Never, &mut |_| {}).unwrap();
    cfg.nonlinearity = Nonlinearity::Consistent;
    let run = solve(&cfg, &Never, &mut |_| {}).unwrap();
    assert_eq!(run.status, Status::Success, "{}", run.message);
    assert!(run.message.is_empty(), "{}", run.message);
    let mut sim = Simulation::new(&cfg).unwrap();
    sim.zero_quartic();
    let quadratic = sim.run(&Never, &mut |_| {});
    let (a, b, q) = (base.metrics.unwrap(), run.metrics.unwrap(), quadratic.metrics.unwrap());
    let metrics = |m: &crate::metrics::StickSlip| {
        [m.motor_torque_min_nm, m.motor_torque_max_nm, m.period_s, m.bit_rpm_max, m.bit_rpm_mean]
    };
    let changes = |x: [f64; 5], y: [f64; 5]| -> [f64; 5] { std::array::from_fn(|i| y[i] / x[i] - 1.0) };
    let law = changes(metrics(&q), metrics(&b));
    let scheme = changes(metrics(&a), metrics(&q));
    let total = changes(metrics(&a), metrics(&b));
    let shown = |c: [f64; 5]| c.map(|c| format!("{c:.2e}"));
    eprintln!(
        "Well B, relative changes of torque min, max, period, rpm max, mean: law {:?}, scheme {:?}, total {:?}; \
         courant {}..{} peak {}; transport loss {:.4e} J (linear {:.4e}), balance {:.1e}",
        shown(law),
        shown(scheme),
        shown(total),
        run.stats.courant_min,
        run.stats.courant_max,
        run.stats.courant_peak,
        run.energy.upwind_loss,
        base.energy.upwind_loss,
        run.energy.balance_error
    );
    assert!(law.iter().all(|c| c.abs() < LAW_BOUND), "{law:?}");
    assert!(total.iter().all(|c| c.abs() < 0.1), "{total:?}");
    assert!(run.stats.courant_peak < 1.0 && run.energy.balance_error.abs() < 1e-11);
}

/// Measured: at most 2.5e-5 (the torque minimum and maximum).
const LAW_BOUND: f64 = 1e-4;

#[test]
fn consistent_fields_are_bad_input_when_out_of_range() {
    let field = |extra: &str| {
        let json =
            format!(r#"{{"sections": [{{"length": 100, "outer_diameter": 0.1, "inner_diameter": 0.05{extra}}}]}}"#);
        DrillConfig::from_json(&json).and_then(|c| c.validate()).err().map_or("ok".into(), |e| e.field().to_string())
    };
    assert_eq!(field(r#", "poisson_ratio": 0.5"#), "sections[0].poisson_ratio");
    assert_eq!(field(r#", "poisson_ratio": -1"#), "sections[0].poisson_ratio");
    assert_eq!(field(r#", "poisson_ratio": 0"#), "ok"); // the one rule of model::check_poisson_ratio: -1 < nu < 0.5
    assert_eq!(field(r#", "poisson_ratio": 0.25"#), "ok");
    assert_eq!(field(r#", "quartic_moment": 0"#), "sections[0].quartic_moment");
    assert_eq!(field(r#", "quartic_moment": -1e-7"#), "sections[0].quartic_moment");
    assert_eq!(field(r#", "quartic_moment": 1e-7"#), "ok");
    let top = |extra: &str| {
        let json =
            format!(r#"{{"sections": [{{"length": 100, "outer_diameter": 0.1, "inner_diameter": 0.05}}]{extra}}}"#);
        DrillConfig::from_json(&json).and_then(|c| c.validate()).err().map_or("ok".into(), |e| e.field().to_string())
    };
    assert_eq!(top(r#", "nonlinearity": "cubic""#), "nonlinearity");
    assert_eq!(top(r#", "nonlinearity": "consistent""#), "ok");
    assert_eq!(top(r#", "numerics": {"max_shear_strain": 0}"#), "numerics.max_shear_strain");
    assert_eq!(top(r#", "numerics": {"max_shear_strain": 2}"#), "numerics.max_shear_strain");
}

/// `quartic_moment` sets `J4` of `k5 = M J4 / 2`: unset, the annulus's `pi/192 (OD^6 - ID^6)`
/// (computed here); given, that value, whatever the diameters or a `polar_moment` override.
#[test]
fn quartic_moment_sets_k5() {
    let (od, id): (f64, f64) = (0.127, 0.1086);
    let mut s = section(100.0, od, id);
    let m = |s: &Section| {
        let nu = s.poisson_ratio;
        2.0 * s.shear_modulus * (1.0 - nu) / (1.0 - 2.0 * nu)
    };
    let annulus = PI / 192.0 * (od.powi(6) - id.powi(6));
    let k5 = grid::SectionProps::new(&s, 0.0).quartic;
    assert!((k5 - m(&s) * annulus / 2.0).abs() < 1e-12 * k5, "{k5}");
    s.polar_moment = Some(2.0 * polar(od, id));
    s.quartic_moment = Some(3.0 * annulus);
    let props = grid::SectionProps::new(&s, 0.0);
    assert!((props.quartic - 3.0 * k5).abs() < 1e-12 * k5, "{}", props.quartic);
    assert_eq!(props.stiffness, G * 2.0 * polar(od, id));
}
