//! The linear part of the model: the frequencies, wave speed and critical speeds of eq. 18, the
//! one-mode Duffing coefficients (eqs. 19, 20) and the linear stability of the equilibrium
//! `q = qdot = 0` of a modal system (paper sec. 3.6, eqs. 28, 29).
//!
//! Linearising eq. 18 about `th = 0` (the quartic energy adds nothing there), the mode
//! `cos(i pi z / l)` has `w_i^2 = (k2 (i pi / l)^2 - k6) / k1` ([`frequency_squared`]); with
//! `k6 = (k6 / Omega^2) Omega^2` ([`crate::model::k6`]) it loses linear stability above the
//! critical speed `Omega_i = (i pi / l) sqrt(k2 / (k6 / Omega^2))` ([`critical_speed`]).
//!
//! The modal system `M q'' + c M q' + K q + grad V(q) = 0` written in first order,
//! `x = (q, qdot)`, has at the equilibrium the Jacobian `J = [[0, I], [-M^-1 K, -c I]]`
//! ([`jacobian`]). `M` and `K` are diagonal, so every mode `i` is a block of its own with
//! `mu_i = K_ii / M_ii` ([`rates`]) and the eigenvalues `-c/2 +- sqrt(c^2/4 - mu_i)`
//! ([`mode_eigenvalue`]). A mode is ([`classify_mode`]):
//!
//! * `Saddle` for `mu_i < -tol` (a real positive eigenvalue: linearly unstable),
//! * `Degenerate` for `|mu_i| <= tol` (a zero eigenvalue: the linearisation does not decide),
//! * `Centre` without damping, else `StableFocus` (`mu_i > c^2/4`, decaying oscillation) or
//!   `StableNode` (overdamped),
//!
//! with `tol = ROUNDOFF max_j |mu_j|`, the round-off of the rates. The equilibrium is a saddle if
//! any mode is, else degenerate if any mode is, else a centre (no damping), a stable focus (some
//! mode oscillates) or a stable node ([`classify`]). Sweeps count the modes that are saddles
//! ([`unstable_modes`]).

use std::f64::consts::PI;

use crate::error::{Error, Num, Result};

/// Relative round-off of the rates `K_ii / M_ii`: a rate within `ROUNDOFF max |mu|` of 0 is zero.
pub const ROUNDOFF: f64 = 1e-12;

/// `w_i^2 = (k2 (i pi / l)^2 - k6) / k1` (rad^2/s^2) of the mode `cos(i pi z / l)` of eq. 18,
/// linearised about `th = 0`; negative for `i = 0` with rotation and above a critical speed.
pub fn frequency_squared(k1: f64, k2: f64, k6: f64, length: f64, i: f64) -> f64 {
    let wave = i * PI / length;
    (k2 * (wave * wave) - k6) / k1
}

/// `w = sqrt(w^2)` (rad/s) where `w^2 >= 0`, NaN where it is negative (an unstable mode has
/// no frequency).
pub fn linear_frequency(frequency_squared: f64) -> f64 {
    if frequency_squared >= 0.0 {
        frequency_squared.sqrt()
    } else {
        f64::NAN
    }
}

/// The linear torsional wave speed `c = sqrt(k2 / k1)` (m/s); NaN for `k2 < 0`.
pub fn wave_speed(k1: f64, k2: f64) -> f64 {
    if k2 >= 0.0 {
        (k2 / k1).sqrt()
    } else {
        f64::NAN
    }
}

/// The rotation speed `Omega_i = (i pi / l) sqrt(k2 / (k6 / Omega^2))` (rad/s) at which
/// `w_i^2` of mode `i` changes sign; `inf` for a model without rotation softening
/// (`k6_per_omega_squared == 0`), NaN for `k2 < 0`. In the paper model (`k6 = k1 Omega^2`)
/// `(i pi / l) sqrt(4 G / rho)`, independent of the section.
pub fn critical_speed(k2: f64, k6_per_omega_squared: f64, length: f64, i: f64) -> f64 {
    if k6_per_omega_squared == 0.0 {
        return f64::INFINITY;
    }
    let speed = if k2 >= 0.0 { (k2 / k6_per_omega_squared).sqrt() } else { f64::NAN };
    i * PI / length * speed
}

/// The squared wave speed `k2 / k1` a modal model of the paper's family (`k6 = k1 Omega^2`)
/// implies: the mean over the elastic modes (`i >= 1`) of `(mu_i + Omega^2) / (i pi / l)^2`,
/// for a model known only by its masses and stiffnesses. NaN without an elastic mode.
pub fn wave_speed_squared_of_rates(rates: &[f64], indices: &[u32], length: f64, omega: f64) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for (&mu, &i) in rates.iter().zip(indices) {
        if i > 0 {
            let wave = f64::from(i) * (PI / length);
            sum += (mu + omega * omega) / (wave * wave);
            count += 1;
        }
    }
    if count == 0 {
        f64::NAN
    } else {
        sum / count as f64
    }
}

fn check_diagonals(mass: &[f64], stiffness: &[f64]) -> Result<()> {
    if mass.is_empty() || mass.len() != stiffness.len() {
        return Err(Error::invalid(
            "stiffness",
            format!("{} masses and {} stiffnesses", mass.len(), stiffness.len()),
            "as many stiffnesses as masses, at least one",
        ));
    }
    if let Some(k) = mass.iter().position(|m| !(m.is_finite() && *m > 0.0)) {
        return Err(Error::invalid(format!("mass[{k}]"), Num(mass[k]), "a finite number > 0"));
    }
    if let Some(k) = stiffness.iter().position(|s| !s.is_finite()) {
        return Err(Error::invalid(format!("stiffness[{k}]"), Num(stiffness[k]), "a finite number"));
    }
    Ok(())
}

/// `mu_i = K_ii / M_ii` (1/s^2), the eigenvalues of `M^-1 K`: `w_i^2` of the modal model.
///
/// Errors: no mode, unequal lengths (`"stiffness"`), a mass not finite and `> 0`
/// (`"mass[k]"`), a stiffness not finite (`"stiffness[k]"`).
pub fn rates(mass: &[f64], stiffness: &[f64]) -> Result<Vec<f64>> {
    check_diagonals(mass, stiffness)?;
    Ok(stiffness.iter().zip(mass).map(|(k, m)| k / m).collect())
}

/// The one-mode Duffing equation `a1 q'' + a2 q + a3 q^3 = 0` (eq. 19, the corrected eq. 20) of
/// the modal model of the single mode `i = 1` on `[0, length]`: its mass, stiffness and the sum
/// of its quartic coefficients (`V = C q^4`), divided by `int phi_1^2 = l / 2`:
/// `a1 = M / (l/2) = k1`, `a2 = K / (l/2) = k2 pi^2 / l^2 - k6`,
/// `a3 = 4 C / (l/2) = 3 k3 / 4 + k4 pi^2 / (2 l^2) + 3 k5 pi^4 / (4 l^4)`.
///
/// Errors: a basis other than the single mode `i = 1` (`"modes"`), bad diagonals as [`rates`].
pub fn duffing(indices: &[u32], mass: &[f64], stiffness: &[f64], quartic: &[f64], length: f64) -> Result<[f64; 3]> {
    if indices != [1] {
        let shown: Vec<String> = indices.iter().map(u32::to_string).collect();
        return Err(Error::invalid(
            "modes",
            format!("{} retained modes (i = [{}])", indices.len(), shown.join(", ")),
            "exactly one mode i = 1 (modes=1, rigid_mode=False)",
        ));
    }
    check_diagonals(mass, stiffness)?;
    let norm = length / 2.0;
    let sum = quartic.iter().skip(1).fold(quartic.first().copied().unwrap_or(0.0), |acc, c| acc + c);
    Ok([mass[0] / norm, stiffness[0] / norm, 4.0 * sum / norm])
}

/// The Jacobian `J = [[0, I], [-M^-1 K, -c I]]` (`2m x 2m`, row-major) of the first-order modal
/// system at `q = qdot = 0`, with the damping rate `c` (the force `-c M qdot`).
///
/// Errors as [`rates`], and `"damping_rate"` unless `c` is finite and `>= 0`.
pub fn jacobian(mass: &[f64], stiffness: &[f64], damping_rate: f64) -> Result<Vec<f64>> {
    let c = crate::terms::ViscousDamping::new(damping_rate)?.rate();
    let mu = rates(mass, stiffness)?;
    let m = mu.len();
    let mut jac = vec![0.0; 4 * m * m];
    for (k, &mu_k) in mu.iter().enumerate() {
        jac[k * 2 * m + m + k] = 1.0;
        jac[(m + k) * 2 * m + k] = -mu_k;
        jac[(m + k) * 2 * m + m + k] = -c;
    }
    Ok(jac)
}

/// The eigenvalue `-c/2 + sqrt(c^2/4 - mu)` (principal root, `Im >= 0`) of a mode with the rate
/// `mu = K_ii / M_ii` and the damping rate `c`, as `(re, im)`; the mode's other eigenvalue is
/// `-c/2 - sqrt(c^2/4 - mu)`: `+-i w` for a stable undamped mode, `+-s` real for an unstable one.
pub fn mode_eigenvalue(mu: f64, damping_rate: f64) -> (f64, f64) {
    let c = damping_rate;
    let radicand = 0.25 * c * c - mu;
    let (re, im) = if radicand >= 0.0 { (radicand.sqrt(), 0.0) } else { (0.0, (-radicand).sqrt()) };
    (-0.5 * c + re, im)
}

/// The type of the equilibrium, of one mode or of the whole modal system (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Classification {
    Centre,
    StableFocus,
    StableNode,
    Degenerate,
    Saddle,
}

impl Classification {
    /// `"centre"`, `"stable focus"`, `"stable node"`, `"degenerate"` or `"saddle"`.
    pub fn name(self) -> &'static str {
        match self {
            Classification::Centre => "centre",
            Classification::StableFocus => "stable focus",
            Classification::StableNode => "stable node",
            Classification::Degenerate => "degenerate",
            Classification::Saddle => "saddle",
        }
    }

    /// A centre, stable focus or stable node.
    pub fn is_stable(self) -> bool {
        matches!(self, Classification::Centre | Classification::StableFocus | Classification::StableNode)
    }
}

/// The classification of a mode of rate `mu` among modes whose largest `|mu|` is `scale`, with
/// the damping rate `c` (module docs; `|mu| <= ROUNDOFF scale` counts as 0).
pub fn classify_mode(mu: f64, scale: f64, damping_rate: f64) -> Classification {
    let tol = ROUNDOFF * scale;
    if mu < -tol {
        Classification::Saddle
    } else if mu.abs() <= tol {
        Classification::Degenerate
    } else if damping_rate == 0.0 {
        Classification::Centre
    } else if mu > 0.25 * damping_rate * damping_rate {
        Classification::StableFocus
    } else {
        Classification::StableNode
    }
}

/// The largest `|mu|` of the rates: the scale of their round-off.
pub fn scale(rates: &[f64]) -> f64 {
    rates.iter().fold(0.0, |acc: f64, mu| acc.max(mu.abs()))
}

/// The classification of the whole equilibrium from those of its modes: a saddle if any mode
/// is, else degenerate if any mode is, else a centre without damping, a stable focus if some
/// mode oscillates, a stable node if none does.
pub fn classify(modes: &[Classification]) -> Classification {
    let any = |c: Classification| modes.contains(&c);
    [Classification::Saddle, Classification::Degenerate, Classification::StableFocus, Classification::StableNode]
        .into_iter()
        .find(|&c| any(c))
        .unwrap_or(Classification::Centre)
}

/// The number of linearly unstable modes (saddles, [`classify_mode`]) of a modal system with the
/// diagonal `mass` and `stiffness` (damping changes no mode's stability).
pub fn unstable_modes(mass: &[f64], stiffness: &[f64]) -> usize {
    let mu: Vec<f64> = stiffness.iter().zip(mass).map(|(k, m)| k / m).collect();
    let scale = scale(&mu);
    mu.iter().filter(|&&mu| classify_mode(mu, scale, 0.0) == Classification::Saddle).count()
}

/// The linear stability of the equilibrium of one modal system ([`analyse`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Stability {
    /// `mu_i = K_ii / M_ii` per mode.
    pub rates: Vec<f64>,
    /// Per mode `-c/2 + sqrt(c^2/4 - mu_i)` as `(re, im)` ([`mode_eigenvalue`]).
    pub mode_eigenvalues: Vec<(f64, f64)>,
    /// All `2m` eigenvalues of the Jacobian (both roots of every mode), sorted by imaginary,
    /// then real part.
    pub eigenvalues: Vec<(f64, f64)>,
    /// Per mode.
    pub mode_classification: Vec<Classification>,
    /// Of the equilibrium ([`classify`]).
    pub classification: Classification,
}

/// Serialised as `rates`, the real and imaginary parts of the eigenvalues as separate columns
/// (`mode_eigenvalues_real`, `mode_eigenvalues_imag`, `eigenvalues_real`, `eigenvalues_imag`),
/// `mode_classification` (names) and `classification` (a name).
impl serde::Serialize for Stability {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let part = |v: &[(f64, f64)], k: usize| v.iter().map(|c| if k == 0 { c.0 } else { c.1 }).collect::<Vec<f64>>();
        let mut map = s.serialize_map(Some(7))?;
        map.serialize_entry("rates", &self.rates)?;
        map.serialize_entry("mode_eigenvalues_real", &part(&self.mode_eigenvalues, 0))?;
        map.serialize_entry("mode_eigenvalues_imag", &part(&self.mode_eigenvalues, 1))?;
        map.serialize_entry("eigenvalues_real", &part(&self.eigenvalues, 0))?;
        map.serialize_entry("eigenvalues_imag", &part(&self.eigenvalues, 1))?;
        let names: Vec<&str> = self.mode_classification.iter().map(|c| c.name()).collect();
        map.serialize_entry("mode_classification", &names)?;
        map.serialize_entry("classification", self.classification.name())?;
        map.end()
    }
}

/// Rates, eigenvalues and classification of the equilibrium of the modal system with the
/// diagonal `mass` and `stiffness` and the damping rate `c`. Errors as [`jacobian`].
pub fn analyse(mass: &[f64], stiffness: &[f64], damping_rate: f64) -> Result<Stability> {
    let c = crate::terms::ViscousDamping::new(damping_rate)?.rate();
    let rates = rates(mass, stiffness)?;
    let scale = scale(&rates);
    let mode_eigenvalues: Vec<(f64, f64)> = rates.iter().map(|&mu| mode_eigenvalue(mu, c)).collect();
    let mode_classification: Vec<Classification> = rates.iter().map(|&mu| classify_mode(mu, scale, c)).collect();
    let mut eigenvalues: Vec<(f64, f64)> = rates
        .iter()
        .zip(&mode_eigenvalues)
        .flat_map(|(&mu, &(re, im))| {
            let c2 = 0.25 * c * c - mu;
            // the other root -c/2 - sqrt(c^2/4 - mu): -c/2 - re' for a real root, the conjugate else
            let other = if c2 >= 0.0 { (-0.5 * c - c2.sqrt(), 0.0) } else { (re, -im) };
            [(re, im), other]
        })
        .collect();
    eigenvalues.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
    let classification = classify(&mode_classification);
    Ok(Stability { rates, mode_eigenvalues, eigenvalues, mode_classification, classification })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn stability_frequencies_of_the_free_free_string() {
        // k6 = 0: w_i = i pi c / l with c = sqrt(k2 / k1)
        let (k1, k2, l) = (2.0, 8.0, 50.0);
        let c = wave_speed(k1, k2);
        assert_eq!(c, 2.0);
        for i in 0..5 {
            let w = linear_frequency(frequency_squared(k1, k2, 0.0, l, f64::from(i)));
            assert!(close(w, f64::from(i) * PI * c / l, 1e-15), "{i}: {w}");
        }
        // k6 = k1 Omega^2: the rigid mode has -Omega^2, an unstable mode no frequency
        let omega = 3.0;
        assert!(close(frequency_squared(k1, k2, k1 * omega * omega, l, 0.0), -omega * omega, 1e-15));
        assert!(linear_frequency(-1e-300).is_nan() && linear_frequency(0.0) == 0.0);
        assert!(wave_speed(1.0, -1.0).is_nan());
    }

    #[test]
    fn stability_critical_speed_is_where_the_frequency_vanishes() {
        let (k1, k2, l) = (0.37, 5.4e9, 100.0);
        for i in 1..4 {
            let crit = critical_speed(k2, k1, l, f64::from(i));
            assert!(close(crit, f64::from(i) * PI / l * (k2 / k1).sqrt(), 1e-15));
            let w2 = |omega: f64| frequency_squared(k1, k2, k1 * omega * omega, l, f64::from(i));
            assert!(w2(crit).abs() <= 1e-12 * w2(0.0));
            assert!(w2(crit * (1.0 - 1e-6)) > 0.0 && w2(crit * (1.0 + 1e-6)) < 0.0);
        }
        assert_eq!(critical_speed(k2, k1, l, 0.0), 0.0);
        assert_eq!(critical_speed(k2, 0.0, l, 2.0), f64::INFINITY);
        assert!(critical_speed(-1.0, k1, l, 2.0).is_nan());
        // the speed implied by rates of the paper family: k2 / k1 back
        let omega = 2.5;
        let indices = [0, 1, 2, 3];
        let mu: Vec<f64> =
            indices.iter().map(|&i| frequency_squared(k1, k2, k1 * omega * omega, l, f64::from(i))).collect();
        assert!(close(wave_speed_squared_of_rates(&mu, &indices, l, omega), k2 / k1, 1e-12));
        assert!(wave_speed_squared_of_rates(&mu[..1], &indices[..1], l, omega).is_nan());
    }

    #[test]
    fn stability_duffing_is_eq_20() {
        let (k, l) = ([2.0, 3.0, 5.0, 7.0, 11.0, 13.0], 1.7);
        let g = crate::galerkin::integrals(crate::terms::Boundary::Free, 1, false).unwrap();
        let sys = g.scale(&k, l).unwrap();
        let quartic: Vec<f64> = sys.terms().iter().map(|t| t.coef).collect();
        let [a1, a2, a3] = duffing(&[1], sys.mass(), sys.stiffness(), &quartic, l).unwrap();
        let w = PI / l;
        assert!(close(a1, k[0], 1e-15));
        assert!(close(a2, k[1] * w * w - k[5], 1e-14));
        assert!(close(a3, 0.75 * k[2] + k[3] * w * w / 2.0 + 0.75 * k[4] * w.powi(4), 1e-14));
        let err = duffing(&[0, 1], &[1.0, 1.0], &[1.0, 1.0], &[], l).unwrap_err();
        assert!(err.field() == "modes" && err.to_string().contains("i = [0, 1]"), "{err}");
    }

    #[test]
    fn stability_eigenvalues_are_the_roots_of_each_mode() {
        // lambda^2 + c lambda + mu = 0 for each root
        for c in [0.0, 0.5, 10.0] {
            for mu in [4.0, 1.0 / 16.0, 0.0, -9.0] {
                let (re, im) = mode_eigenvalue(mu, c);
                assert!(im >= 0.0);
                let (r2, i2) = (re * re - im * im, 2.0 * re * im);
                assert!((r2 + c * re + mu).abs() <= 1e-14 * (1.0 + mu.abs()), "{c} {mu}");
                assert!((i2 + c * im).abs() <= 1e-14 * (1.0 + mu.abs()), "{c} {mu}");
            }
        }
        assert_eq!(mode_eigenvalue(4.0, 0.0), (0.0, 2.0));
        assert_eq!(mode_eigenvalue(-9.0, 0.0), (3.0, 0.0));
        let s = analyse(&[1.0, 2.0], &[4.0, -18.0], 0.0).unwrap();
        assert_eq!(s.rates, [4.0, -9.0]);
        assert_eq!(s.eigenvalues, [(0.0, -2.0), (-3.0, 0.0), (3.0, 0.0), (0.0, 2.0)]);
        let damped = analyse(&[1.0], &[4.0], 2.0).unwrap();
        assert_eq!(damped.eigenvalues, [(-1.0, -(3f64.sqrt())), (-1.0, 3f64.sqrt())]);
    }

    #[test]
    fn stability_classification() {
        use Classification::*;
        let names = |mass: &[f64], stiffness: &[f64], c: f64| {
            let s = analyse(mass, stiffness, c).unwrap();
            (s.mode_classification.iter().map(|c| c.name()).collect::<Vec<_>>(), s.classification.name())
        };
        assert_eq!(names(&[1.0, 1.0], &[1.0, 4.0], 0.0), (vec!["centre", "centre"], "centre"));
        assert_eq!(names(&[1.0, 1.0], &[-1.0, 4.0], 0.0), (vec!["saddle", "centre"], "saddle"));
        assert_eq!(names(&[1.0, 1.0], &[0.0, 4.0], 0.0), (vec!["degenerate", "centre"], "degenerate"));
        // round-off of a rate counts as 0
        assert_eq!(names(&[1.0, 1.0], &[-1e-13, 4.0], 0.0).1, "degenerate");
        // c = 2: mu > 1 oscillates, mu <= 1 is overdamped
        assert_eq!(names(&[1.0, 1.0], &[4.0, 1.0], 2.0), (vec!["stable focus", "stable node"], "stable focus"));
        assert_eq!(names(&[1.0], &[1.0], 2.0), (vec!["stable node"], "stable node"));
        assert!(Centre.is_stable() && StableNode.is_stable() && !Degenerate.is_stable() && !Saddle.is_stable());
        assert_eq!(unstable_modes(&[2.0, 2.0, 2.0], &[-4.0, 1.0, -1e-14]), 1);
        assert_eq!(unstable_modes(&[1.0], &[-1e-300]), 1);
    }

    #[test]
    fn stability_jacobian_blocks() {
        let jac = jacobian(&[2.0, 4.0], &[8.0, -4.0], 0.5).unwrap();
        #[rustfmt::skip]
        let expected = [
            0.0, 0.0, 1.0, 0.0,
            0.0, 0.0, 0.0, 1.0,
            -4.0, 0.0, -0.5, 0.0,
            0.0, 1.0, 0.0, -0.5,
        ];
        assert_eq!(jac, expected);
        assert_eq!(jacobian(&[1.0], &[1.0], -1.0).unwrap_err().field(), "damping_rate");
        assert_eq!(rates(&[0.0], &[1.0]).unwrap_err().field(), "mass[0]");
        assert_eq!(rates(&[1.0], &[f64::NAN]).unwrap_err().field(), "stiffness[0]");
        assert_eq!(rates(&[], &[]).unwrap_err().field(), "stiffness");
    }
}
