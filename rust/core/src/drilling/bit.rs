//! The bit-rock torque law, shared by the distributed string ([`super::solver`]) and the lumped
//! two-inertia model ([`super::lumped`]).
//!
//! Navarro-Lopez & Cortes, "Avoiding harmful oscillations in a drillstring through dynamical
//! analysis", J. Sound Vib. 307 (2007) 152-171: while the bit slips at speed `w`,
//! `T = W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)` with `W` the weight on bit, `r`
//! the bit radius and `decay = gamma_b / v_f` (the paper's `gamma_b` over its velocity scale
//! `v_f`); at rest the torque is whatever holds the bit, up to the static limit `W r mu_s`.

/// The slipping bit's friction coefficient at the speed `speed` (rad/s):
/// `mu_kinetic + (mu_static - mu_kinetic) exp(-decay |speed|)`, from `mu_static` at rest down to
/// `mu_kinetic` fast (`decay` in 1/(rad/s)).
#[inline]
pub fn friction_coefficient(mu_static: f64, mu_kinetic: f64, decay: f64, speed: f64) -> f64 {
    mu_kinetic + (mu_static - mu_kinetic) * (-decay * speed.abs()).exp()
}

/// The torque of the slipping bit, N m: `W r mu(|speed|) sign(speed)` with `W r` given as
/// `weight_radius` (N m) and `mu` the [`friction_coefficient`].
#[inline]
pub fn slip_torque(weight_radius: f64, mu_static: f64, mu_kinetic: f64, decay: f64, speed: f64) -> f64 {
    (weight_radius * friction_coefficient(mu_static, mu_kinetic, decay, speed)).copysign(speed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_static_at_rest_to_kinetic_fast_and_odd() {
        assert_eq!(friction_coefficient(0.8, 0.5, 0.9, 0.0), 0.8);
        assert!((friction_coefficient(0.8, 0.5, 0.9, 1e3) - 0.5).abs() < 1e-15);
        let x = 1.7;
        let expected = 0.5 + 0.3 * (-0.9f64 * x).exp();
        assert!((friction_coefficient(0.8, 0.5, 0.9, -x) - expected).abs() < 1e-15);
        assert_eq!(slip_torque(100.0, 0.8, 0.5, 0.9, -x), -slip_torque(100.0, 0.8, 0.5, 0.9, x));
        assert!((slip_torque(100.0, 0.8, 0.5, 0.9, x) - 100.0 * expected).abs() < 1e-12);
    }
}
