//! The conservative terms: each one an energy monomial `weight th^p th_z^r` per unit length.
//!
//! Every conservative term of both model variants ([`crate::model`]) has an energy density of
//! this one shape, `weight = factor * k` with the term's PDE coefficient `k` and a fixed
//! `factor` (`1/2`, `1/4` or `-1/2`). Its force per unit length is the Euler-Lagrange
//! expression `-dE/dth + d/dz (dE/dth_z)` ([`EnergyTerm::euler_lagrange`]); summed over the
//! terms this is the right-hand side of eq. 18. The discretisations take the monomial, not
//! the force:
//!
//! * Galerkin ([`crate::sweep::GalerkinIntegrals::discretise`]): `p + r = 2` adds
//!   `2 weight int phi_i^p phi_i'^r` to the diagonal stiffness, `p + r = 4` adds
//!   `weight l (pi / l)^r I^(p,r)_t` to the quartic coefficients, `I^(p,r)` the exact
//!   dimensionless integrals of [`crate::galerkin`] (`r` even); or, for many modes, the term
//!   itself: the pseudo-spectral evaluation ([`crate::modal::spectral`]) sums its
//!   [`EnergyTerm::density`] and [`EnergyTerm::partials`] at quadrature points, so a new
//!   quartic term needs no new spectral code.
//! * Finite differences ([`crate::pde::PdeSystem::discretise`]): the cell energy
//!   [`EnergyTerm::cell_energy`] `h weight (a^p + b^p) / 2 g^r`, collected into the fused
//!   kernel by shape.
//!
//! One term is one [`TermSpec`] constant below (its name, paper equation, coefficient name,
//! factor, exponents).

use crate::error::{Error, Num, Result};

/// What a conservative term is: its name, where it comes from, and its energy monomial
/// `factor * k * th^p * th_z^r` (`k` the coefficient named `coefficient`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TermSpec {
    /// A short name, used in messages.
    pub name: &'static str,
    /// The paper's equation and the term's force in it.
    pub equation: &'static str,
    /// The name of the coefficient (`"k2"` .. `"k6"`).
    pub coefficient: &'static str,
    /// `factor` in the energy density, as `numerator / denominator` (exact powers of two).
    pub factor: (i8, u8),
    /// The power `p` of `th`.
    pub p: u32,
    /// The power `r` of `th_z`.
    pub r: u32,
}

/// Linear elasticity: energy `k2/2 th_z^2`, force `k2 th_zz` (eq. 18; `k2 = 4 G I_p` in the
/// paper, eq. 17, `G I_p` in the consistent model).
pub const LINEAR_ELASTIC: TermSpec =
    TermSpec { name: "linear elastic", equation: "eq. 18: k2 th_zz", coefficient: "k2", factor: (1, 2), p: 0, r: 2 };

/// Cubic restoring twist: energy `k3/4 th^4`, force `-k3 th^3` (eq. 18; `k3 = 2 A G / (1 - 2 nu)`,
/// eq. 17; absent from the consistent model).
pub const CUBIC_TWIST: TermSpec =
    TermSpec { name: "cubic twist", equation: "eq. 18: -k3 th^3", coefficient: "k3", factor: (1, 4), p: 4, r: 0 };

/// Twist-gradient coupling: energy `k4/2 th^2 th_z^2`, force `k4 (th^2 th_zz + th th_z^2)`
/// (eq. 18; `k4 = G I_p (5 - 6 nu) / (4 (1 - 2 nu))`, eq. 17; absent from the consistent model).
pub const TWIST_GRADIENT_COUPLING: TermSpec = TermSpec {
    name: "twist-gradient coupling",
    equation: "eq. 18: k4 (th^2 th_zz + th th_z^2)",
    coefficient: "k4",
    factor: (1, 2),
    p: 2,
    r: 2,
};

/// Nonlinear elasticity: energy `k5/4 th_z^4`, force `k5 (th_z^3)_z` (eq. 18; `k5` of eq. 17
/// with its [`crate::model::K5Variant`], `M J4 / 2` in the consistent model).
pub const NONLINEAR_ELASTIC: TermSpec = TermSpec {
    name: "nonlinear elastic",
    equation: "eq. 18: k5 (th_z^3)_z",
    coefficient: "k5",
    factor: (1, 4),
    p: 0,
    r: 4,
};

/// Rotation (centrifugal softening): energy `-k6/2 th^2`, force `k6 th` (eq. 18;
/// `k6 = rho I_p Omega^2`, eq. 17; absent from the consistent model).
pub const ROTATION: TermSpec =
    TermSpec { name: "rotation", equation: "eq. 18: k6 th", coefficient: "k6", factor: (-1, 2), p: 2, r: 0 };

/// The conservative terms of eq. 18 in the order of their coefficients `k2 .. k6`.
pub const EQ18_TERMS: [TermSpec; 5] =
    [LINEAR_ELASTIC, CUBIC_TWIST, TWIST_GRADIENT_COUPLING, NONLINEAR_ELASTIC, ROTATION];

/// `x^n` by repeated multiplication (`x * x` for `n = 2`, as written out by hand).
#[inline]
fn pow(x: f64, n: u32) -> f64 {
    match n {
        0 => 1.0,
        1 => x,
        _ => (1..n).fold(x, |acc, _| acc * x),
    }
}

impl TermSpec {
    /// `factor` as a number.
    pub fn factor(&self) -> f64 {
        f64::from(self.factor.0) / f64::from(self.factor.1)
    }

    /// `1 / factor` (`2`, `4`, `-2`): the energy density is `k th^p th_z^r / divisor`, the way
    /// the hand-written formulas divide (so that an overflow happens where theirs did).
    pub fn divisor(&self) -> f64 {
        f64::from(self.factor.1) / f64::from(self.factor.0)
    }

    /// The term with coefficient `k` (finite, else an error naming [`TermSpec::coefficient`]).
    pub fn with(&'static self, k: f64) -> Result<EnergyTerm> {
        if !k.is_finite() {
            return Err(Error::invalid(self.coefficient, Num(k), "a finite number"));
        }
        Ok(EnergyTerm { spec: self, coef: k })
    }
}

/// One conservative term: its [`TermSpec`] and its coefficient `k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyTerm {
    spec: &'static TermSpec,
    coef: f64,
}

impl EnergyTerm {
    pub fn spec(&self) -> &'static TermSpec {
        self.spec
    }

    pub fn name(&self) -> &'static str {
        self.spec.name
    }

    /// The coefficient `k` (`k2` .. `k6`).
    pub fn coefficient(&self) -> f64 {
        self.coef
    }

    /// `(p, r)`: the energy is `weight th^p th_z^r`.
    pub fn exponents(&self) -> (u32, u32) {
        (self.spec.p, self.spec.r)
    }

    /// `weight = factor * k`, exact (the factor is a power of two).
    pub fn weight(&self) -> f64 {
        self.spec.factor() * self.coef
    }

    /// The energy per unit length `weight th^p th_z^r`.
    pub fn density(&self, th: f64, th_z: f64) -> f64 {
        self.weight() * pow(th, self.spec.p) * pow(th_z, self.spec.r)
    }

    /// `(dE/dth, dE/dth_z)` of [`EnergyTerm::density`].
    pub fn partials(&self, th: f64, th_z: f64) -> (f64, f64) {
        let (p, r, w) = (self.spec.p, self.spec.r, self.weight());
        let d_th = if p == 0 { 0.0 } else { w * f64::from(p) * pow(th, p - 1) * pow(th_z, r) };
        let d_thz = if r == 0 { 0.0 } else { w * f64::from(r) * pow(th, p) * pow(th_z, r - 1) };
        (d_th, d_thz)
    }

    /// The force per unit length `-dE/dth + d/dz (dE/dth_z)` at a point with `th`, `th_z` and
    /// `th_zz`: the term of eq. 18's right-hand side (`k1 th_tt = sum of these`).
    pub fn euler_lagrange(&self, th: f64, th_z: f64, th_zz: f64) -> f64 {
        let (p, r, w) = (self.spec.p, self.spec.r, self.weight());
        let (d_th, _) = self.partials(th, th_z);
        // d/dz [w r th^p th_z^(r-1)] = w r [p th^(p-1) th_z^r + (r-1) th^p th_z^(r-2) th_zz]
        let flux_z = if r == 0 {
            0.0
        } else {
            let (fp, fr) = (f64::from(p), f64::from(r));
            let first = if p == 0 { 0.0 } else { fp * pow(th, p - 1) * pow(th_z, r) };
            let second = if r < 2 { 0.0 } else { (fr - 1.0) * pow(th, p) * pow(th_z, r - 2) * th_zz };
            w * fr * (first + second)
        };
        flux_z - d_th
    }

    /// The finite-difference energy of a cell of width `h` with end values `a`, `b`:
    /// `h weight (a^p + b^p) / 2 g^r`, `g = (b - a) / h` (the trapezoid rule for `r = 0`,
    /// the midpoint gradient for `p = 0`).
    pub fn cell_energy(&self, a: f64, b: f64, h: f64) -> f64 {
        let (p, r) = (self.spec.p, self.spec.r);
        let g = (b - a) / h;
        h * self.weight() * 0.5 * (pow(a, p) + pow(b, p)) * pow(g, r)
    }

    /// `(d/da, d/db)` of [`EnergyTerm::cell_energy`].
    pub fn cell_gradient(&self, a: f64, b: f64, h: f64) -> (f64, f64) {
        let (p, r, w) = (self.spec.p, self.spec.r, self.weight());
        let g = (b - a) / h;
        let mean = 0.5 * (pow(a, p) + pow(b, p));
        // d/dg of h w mean g^r is h w mean r g^(r-1); dg/da = -1/h, dg/db = 1/h
        let dg = if r == 0 { 0.0 } else { w * mean * f64::from(r) * pow(g, r - 1) };
        let (da, db) = if p == 0 {
            (0.0, 0.0)
        } else {
            let fp = 0.5 * f64::from(p) * h * w * pow(g, r);
            (fp * pow(a, p - 1), fp * pow(b, p - 1))
        };
        (da - dg, db + dg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terms() -> Vec<EnergyTerm> {
        EQ18_TERMS.iter().zip([3.0, 5.0, -7.0, 11.0, 13.0]).map(|(s, k)| s.with(k).unwrap()).collect()
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    #[test]
    fn the_terms_of_eq_18() {
        let names: Vec<_> = EQ18_TERMS.iter().map(|s| (s.coefficient, s.factor(), s.p, s.r)).collect();
        assert_eq!(
            names,
            vec![("k2", 0.5, 0, 2), ("k3", 0.25, 4, 0), ("k4", 0.5, 2, 2), ("k5", 0.25, 0, 4), ("k6", -0.5, 2, 0)]
        );
        assert_eq!(ROTATION.with(f64::NAN).unwrap_err().field(), "k6");
        let t = LINEAR_ELASTIC.with(3.0).unwrap();
        assert_eq!((t.name(), t.coefficient(), t.weight(), t.exponents()), ("linear elastic", 3.0, 1.5, (0, 2)));
    }

    #[test]
    fn partials_are_the_derivatives_of_the_density() {
        let eps = 1e-6;
        for t in terms() {
            for (th, thz) in [(0.3, -0.7), (-1.1, 0.4), (0.0, 0.9)] {
                let (d_th, d_thz) = t.partials(th, thz);
                let fd_th = (t.density(th + eps, thz) - t.density(th - eps, thz)) / (2.0 * eps);
                let fd_thz = (t.density(th, thz + eps) - t.density(th, thz - eps)) / (2.0 * eps);
                assert!(close(d_th, fd_th, 1e-8) && close(d_thz, fd_thz, 1e-8), "{}", t.name());
            }
        }
    }

    #[test]
    fn the_forces_add_up_to_eq_18() {
        let (k2, k3, k4, k5, k6) = (3.0, 5.0, -7.0, 11.0, 13.0);
        for (th, thz, thzz) in [(0.3, -0.7, 0.2), (-1.1, 0.4, -2.0)] {
            let sum: f64 = terms().iter().map(|t| t.euler_lagrange(th, thz, thzz)).sum();
            let rhs = k2 * thzz - k3 * th.powi(3)
                + k4 * (th * th * thzz + th * thz * thz)
                + k5 * 3.0 * thz * thz * thzz
                + k6 * th;
            assert!(close(sum, rhs, 1e-14), "{sum} vs {rhs}");
        }
    }

    #[test]
    fn the_euler_lagrange_force_is_the_variation_of_the_energy() {
        // th(z) = sum of a few smooth shapes; the force is -dH/dth as a functional: check
        // d/de int E(th + e eta) dz = -int force eta dz with eta vanishing with its derivative
        // at the ends (quadrature on a fine grid).
        let n = 4000;
        let (l, dz) = (1.0, 1.0 / 4000.0);
        let th = |z: f64| 0.4 * (2.0 * z).sin() + 0.3 * z * z;
        let th_z = |z: f64| 0.8 * (2.0 * z).cos() + 0.6 * z;
        let th_zz = |z: f64| -1.6 * (2.0 * z).sin() + 0.6;
        let eta = |z: f64| (std::f64::consts::PI * z / l).sin().powi(2);
        let eta_z = |z: f64| std::f64::consts::PI / l * (2.0 * std::f64::consts::PI * z / l).sin();
        for t in terms() {
            let (mut dh, mut work) = (0.0, 0.0);
            for j in 0..n {
                let z = (j as f64 + 0.5) * dz;
                let (d_th, d_thz) = t.partials(th(z), th_z(z));
                dh += (d_th * eta(z) + d_thz * eta_z(z)) * dz;
                work += t.euler_lagrange(th(z), th_z(z), th_zz(z)) * eta(z) * dz;
            }
            assert!(close(dh, -work, 1e-6), "{}: {dh} vs {}", t.name(), -work);
        }
    }

    #[test]
    fn cell_gradient_is_the_gradient_of_the_cell_energy() {
        let eps = 1e-6;
        for t in terms() {
            for (a, b, h) in [(0.3, -0.2, 0.5), (-1.0, 0.7, 0.1), (0.0, 0.4, 2.0)] {
                let (da, db) = t.cell_gradient(a, b, h);
                let fd_a = (t.cell_energy(a + eps, b, h) - t.cell_energy(a - eps, b, h)) / (2.0 * eps);
                let fd_b = (t.cell_energy(a, b + eps, h) - t.cell_energy(a, b - eps, h)) / (2.0 * eps);
                assert!(close(da, fd_a, 1e-7) && close(db, fd_b, 1e-7), "{}: {da} {fd_a} {db} {fd_b}", t.name());
            }
        }
    }

    #[test]
    fn cell_energy_is_trapezoid_midpoint_or_both() {
        let t = CUBIC_TWIST.with(4.0).unwrap();
        assert_eq!(t.cell_energy(1.0, 2.0, 0.5), 0.5 * (1.0 + 16.0) / 2.0);
        let t = LINEAR_ELASTIC.with(2.0).unwrap();
        assert_eq!(t.cell_energy(1.0, 2.0, 0.5), 0.5 * 4.0);
        let t = TWIST_GRADIENT_COUPLING.with(2.0).unwrap();
        assert_eq!(t.cell_energy(1.0, 2.0, 0.5), 0.5 * 2.5 * 4.0);
    }
}
