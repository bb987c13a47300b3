//! The parts together: the bit boundary fed by the cut surface holds the analytic steady state
//! of the Detournay law, and the work into the rock per drilled volume is Teale's MSE.

use std::f64::consts::PI;

use super::bit_boundary::{solve_bit, BitPhase, Port};
use super::bitrock::{bit_area, mechanical_specific_energy, DetournayBit};
use super::cut_surface::{CutSurface, SurfaceRule};
use super::section::AxialSection;

#[test]
fn steady_drilling_through_the_parts_is_the_analytic_steady_state() {
    let law = DetournayBit::default();
    // Aarsnes & van de Wouw's pipe: Z_a = A sqrt(E rho); torsion J sqrt(G rho).
    let (ro, ri) = (0.0635f64, 0.054f64);
    let pipe = AxialSection { length: 2000.0, area: PI * (ro * ro - ri * ri), youngs_modulus: 200e9, density: 8e3 };
    let za = pipe.impedance();
    let zt = PI / 2.0 * (ro.powi(4) - ri.powi(4)) * (77e9f64 * 8e3).sqrt();
    // 30 m/h at 30 rpm: d = 2 pi V / Omega = 1/60 m per revolution,
    // W = a zeta eps d + a l sigma = 64800 + 71280 N, T = a^2 eps d / 2 + mu a W_f / 2.
    let (v, omega) = (30.0 / 3600.0, PI);
    let (d, w, t) = (1.0 / 60.0, 64800.0 + 71280.0, 5832.0 + 2309.472);
    // The strings' incoming invariants that carry this state: alpha = v + W / Z.
    let axial = Port::string(v + w / za, za);
    let torsion = Port::string(omega + t / zt, zt);
    let mut surface = CutSurface::steady(law.detournay.blades, SurfaceRule::Deepest, 0.0, 0.0, d);
    let (mut phi, mut x) = (0.0, 0.0);
    let dt = 1.0 / 3000.0;
    let mut work = 0.0;
    for _ in 0..6000 {
        let depth = f64::from(law.detournay.blades) * surface.depth_per_blade(phi, x);
        let s = solve_bit(&law, axial, torsion, depth);
        assert_eq!(s.phase, BitPhase::Cutting);
        assert!((depth - d).abs() < 1e-12 * d, "{depth}");
        assert!((s.weight_on_bit - w).abs() < 1e-9 * w);
        assert!((s.torque_on_bit - t).abs() < 1e-9 * t);
        assert!((s.axial_speed - v).abs() < 1e-9 * v && (s.angular_speed - omega).abs() < 1e-12 * omega);
        work += s.power() * dt;
        x += s.axial_speed * dt;
        phi += s.angular_speed * dt;
        surface.record(phi, x);
    }
    // Two seconds: one revolution, 1/60 m drilled; the work per drilled volume is the MSE.
    assert!((phi - 2.0 * PI).abs() < 1e-9 && (x - d).abs() < 1e-9 * d);
    let area = bit_area(law.radius);
    let mse = mechanical_specific_energy(w, t, omega, v, area);
    assert!((work / (area * x) - mse).abs() < 1e-9 * mse, "{} vs {mse}", work / (area * x));
}
