//! The physical model: section properties of the annulus (paper eq. 8) and the coefficients
//! `k1 .. k6` of the torsion PDE for each model variant.
//!
//! Both models are the same PDE family (model notes, eq. 18)
//!
//! ```text
//! k1 th_tt = k2 th_zz - k3 th^3 + k4 (th^2 th_zz + th th_z^2) + k5 (th_z^3)_z + k6 th,
//! ```
//!
//! the Euler-Lagrange equation of
//! `H = int [k1/2 th_t^2 + k2/2 th_z^2 + k3/4 th^4 + k4/2 th^2 th_z^2 + k5/4 th_z^4 - k6/2 th^2] dz`.
//!
//! * [`Model::Paper`]: eq. 17 as printed, `k1 = rho I_p`, `k2 = 4 G I_p`,
//!   `k3 = 2 A G / (1 - 2 nu)`, `k4 = G I_p (5 - 6 nu) / (4 (1 - 2 nu))`,
//!   `k5 = G (I_r -+ I_x2y2 (5 - 6 nu)) / (8 (1 - 2 nu))` ([`K5Variant`]), `k6 = rho I_p Omega^2`.
//! * [`Model::Consistent`]: finite-strain torsion of rigidly rotating circular sections
//!   (`x = R(th(z)) X_perp + z e_z`), Green-Lagrange strain `E_xz = -th_z y / 2`,
//!   `E_yz = th_z x / 2`, `E_zz = th_z^2 r^2 / 2`, St Venant-Kirchhoff energy
//!   `W = lambda/2 (tr E)^2 + mu tr(E^2) = G r^2 th_z^2 / 2 + M r^4 th_z^4 / 8`
//!   (`M = lambda + 2 mu`), kinetic energy `rho I_p (Omega + th_t)^2 / 2` (the cross term is a
//!   time derivative for constant `Omega`). Per unit length `G I_p th_z^2 / 2 + M J4 th_z^4 / 8`,
//!   so `k1 = rho I_p`, `k2 = G I_p`, `k3 = k4 = k6 = 0`, `k5 = M J4 / 2`: wave speed
//!   `sqrt(G / rho)`, no force from a uniform twist, no dependence on a constant `Omega`.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::error::{Error, Num, Result};
use crate::pde::PdeCoefficients;
use crate::schema;
use crate::terms::ModelTerms;
use std::f64::consts::PI;

/// Which equations of motion: the paper's as printed, or the finite-strain re-derivation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Eq. 12 / 17 as printed (with the chosen [`K5Variant`]).
    Paper,
    /// Exact kinematics of rigidly rotating sections, Green-Lagrange strain, St Venant-Kirchhoff.
    Consistent,
}

impl Model {
    /// Every model, in the order of its names.
    pub const ALL: [Model; 2] = [Model::Paper, Model::Consistent];

    /// `"paper"` or `"consistent"`.
    pub fn name(self) -> &'static str {
        match self {
            Model::Paper => "paper",
            Model::Consistent => "consistent",
        }
    }

    /// The model of a name, or an error naming the field `model`.
    pub fn parse(name: &str) -> Result<Model> {
        Model::ALL
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or_else(|| Error::invalid("model", format!("{name:?}"), MODEL_TEXT))
    }
}

/// The sign inside `k5` of the paper model (model notes, erratum 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum K5Variant {
    /// `I_r - I_x2y2 (5 - 6 nu)`, as printed in eqs. 12 and 17.
    Paper,
    /// `I_r + I_x2y2 (5 - 6 nu)`, re-derived from eqs. 5-7.
    Energy,
}

impl K5Variant {
    /// Every variant, in the order of its names.
    pub const ALL: [K5Variant; 2] = [K5Variant::Paper, K5Variant::Energy];

    /// `"paper"` or `"energy"`.
    pub fn name(self) -> &'static str {
        match self {
            K5Variant::Paper => "paper",
            K5Variant::Energy => "energy",
        }
    }

    /// The variant of a name, or an error naming the field `k5_variant`.
    pub fn parse(name: &str) -> Result<K5Variant> {
        K5Variant::ALL
            .into_iter()
            .find(|v| v.name() == name)
            .ok_or_else(|| Error::invalid("k5_variant", format!("{name:?}"), K5_TEXT))
    }
}

/// Section properties of an annulus (eq. 8 and the fourth polar moment of the consistent model).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CrossSection {
    /// `A = pi (R^2 - r^2)`, m^2.
    pub area: f64,
    /// `I_p = int (x^2 + y^2) dA = pi (R^4 - r^4) / 2`, m^4.
    pub polar_moment: f64,
    /// `I_r = int (x^4 + y^4) dA = pi (R^6 - r^6) / 4`, m^6.
    pub i_r: f64,
    /// `I_x2y2 = int x^2 y^2 dA = pi (R^6 - r^6) / 24`, m^6.
    pub i_x2y2: f64,
    /// `J4 = int (x^2 + y^2)^2 dA = pi (R^6 - r^6) / 3 = I_r + 2 I_x2y2`, m^6.
    pub j4: f64,
}

impl CrossSection {
    /// The annulus of outer diameter `D > 0` and inner diameter `0 <= d < D` (m), `R = D/2`,
    /// `r = d/2`. Powers are evaluated as `powf` (the C library's `pow`), the way the
    /// Python reference evaluated them, so that values are reproduced bit for bit.
    pub fn annulus(outer_diameter: f64, inner_diameter: f64) -> Result<CrossSection> {
        check_diameters(outer_diameter, inner_diameter)?;
        let r_out = outer_diameter / 2.0;
        let r_in = inner_diameter / 2.0;
        let r6 = r_out.powf(6.0) - r_in.powf(6.0);
        let section = CrossSection {
            area: PI * (r_out.powf(2.0) - r_in.powf(2.0)),
            polar_moment: PI * (r_out.powf(4.0) - r_in.powf(4.0)) / 2.0,
            i_r: PI * r6 / 4.0,
            i_x2y2: PI * r6 / 24.0,
            j4: PI * r6 / 3.0,
        };
        for (name, value) in [
            ("area", section.area),
            ("polar_moment", section.polar_moment),
            ("i_r", section.i_r),
            ("i_x2y2", section.i_x2y2),
            ("j4", section.j4),
        ] {
            if !(value.is_finite() && value > 0.0) {
                // overflow or underflow of R^k: the outer diameter; R^k - r^k rounding to 0: the inner
                let field = if value.is_finite() && inner_diameter > 0.0 { "inner_diameter" } else { "outer_diameter" };
                let shown = if field == "inner_diameter" { inner_diameter } else { outer_diameter };
                return Err(Error::invalid(
                    field,
                    Num(shown),
                    format!("diameters whose section properties are finite and > 0 (here {name} = {})", Num(value)),
                ));
            }
        }
        Ok(section)
    }
}

/// The diameters of an annulus: `0 < D < inf`, `0 <= d < D` (m); an error naming the field.
fn check_diameters(outer_diameter: f64, inner_diameter: f64) -> Result<()> {
    positive("outer_diameter", outer_diameter)?;
    if !(inner_diameter.is_finite() && (0.0..outer_diameter).contains(&inner_diameter)) {
        let allowed = format!("0 <= inner_diameter < outer_diameter = {}", Num(outer_diameter));
        return Err(Error::invalid("inner_diameter", Num(inner_diameter), allowed));
    }
    Ok(())
}

/// `0 < value < inf`, else an error naming `name`.
fn positive(name: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(name, Num(value), format!("0 < {name} < inf")))
    }
}

/// The section the paper reports its twist at, `z_k = 2 l / 3` (m) of a string of length `l`:
/// the default section of every twist output.
pub fn default_section(length: f64) -> f64 {
    2.0 * length / 3.0
}

/// Shear modulus `G = E / (2 (1 + nu))` (isotropic Hooke's law), Pa.
pub fn shear_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    youngs_modulus / (2.0 * (1.0 + poisson_ratio))
}

/// P-wave modulus `M = lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu))`, Pa.
pub fn p_wave_modulus(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    youngs_modulus * (1.0 - poisson_ratio) / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio))
}

/// Young's modulus `E = 2 G (1 + nu)` from the shear modulus and Poisson's ratio (the inverse
/// of [`shear_modulus`]), Pa.
pub fn youngs_modulus(shear_modulus: f64, poisson_ratio: f64) -> f64 {
    2.0 * shear_modulus * (1.0 + poisson_ratio)
}

/// The quartic coefficient of the consistent model, `k5 = M J4 / 2` (`M` the P-wave modulus,
/// `J4 = int r^4 dA` the fourth polar moment): the torque-twist law is
/// `tau = k2 th_z + k5 th_z^3`, N m^4.
pub fn consistent_k5(p_wave_modulus: f64, j4: f64) -> f64 {
    p_wave_modulus * j4 / 2.0
}

/// Longitudinal bar speed `sqrt(E / rho)`, m/s: the speed of extensional waves in a thin bar,
/// the scale the torsional wave speeds are compared with.
pub fn bar_speed(youngs_modulus: f64, density: f64) -> f64 {
    (youngs_modulus / density).sqrt()
}

/// The rotation term `k6 = (k6 / Omega^2) Omega^2` of eq. 17 (N): `rho I_p Omega^2` in the paper
/// model (`k6_per_omega_squared = k1`), exactly 0 without rotation softening (the consistent
/// model, whatever `Omega`). `Omega^2` is evaluated as `powf`, as it always was.
pub fn k6(k6_per_omega_squared: f64, omega: f64) -> f64 {
    if k6_per_omega_squared == 0.0 {
        0.0
    } else {
        k6_per_omega_squared * omega.powf(2.0)
    }
}

/// The physical inputs of the coefficients (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Physical {
    /// `E`, Pa, `> 0`.
    pub youngs_modulus: f64,
    /// `rho`, kg/m^3, `> 0`.
    pub density: f64,
    /// `nu`, `-1 < nu < 0.5`.
    pub poisson_ratio: f64,
    /// `D`, m, `> 0`.
    pub outer_diameter: f64,
    /// `d`, m, `0 <= d < D`.
    pub inner_diameter: f64,
    /// `Omega`, rad/s, finite.
    pub omega: f64,
}

/// `k1 .. k6` of one model, and the factor `k6 / Omega^2` (`rho I_p` for the paper model, 0 for
/// the consistent one: the rotation speed does not enter it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Coefficients {
    #[serde(flatten)]
    pub k: PdeCoefficients,
    /// `k6 = k6_per_omega_squared * Omega^2`.
    pub k6_per_omega_squared: f64,
}

impl Coefficients {
    /// The model as terms ([`ModelTerms::from_coefficients`]): `k1` and the conservative terms
    /// of eq. 18 whose coefficient is not 0 (the consistent model: linear and nonlinear
    /// elasticity only), undamped, free ends.
    pub fn terms(&self) -> Result<ModelTerms> {
        ModelTerms::from_coefficients(self.k)
    }
}

/// Poisson's ratio of an isotropic elastic material: `-1 < nu < 0.5` (the bulk and shear moduli
/// positive); an error naming `field` otherwise. The one rule for the paper's model and the
/// drilling sections.
pub fn check_poisson_ratio(field: impl Into<String>, nu: f64) -> Result<()> {
    if nu.is_finite() && nu > -1.0 && nu < 0.5 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(nu), "-1 < poisson_ratio < 0.5"))
    }
}

fn check_physical(p: &Physical) -> Result<()> {
    positive("youngs_modulus", p.youngs_modulus)?;
    positive("density", p.density)?;
    check_poisson_ratio("poisson_ratio", p.poisson_ratio)?;
    if !p.omega.is_finite() {
        return Err(Error::invalid("omega", Num(p.omega), "a finite real number (rad/s, any sign)"));
    }
    Ok(())
}

/// The paper model's parameters (Python's `drillstring.Parameters`), SI units: the physical
/// inputs, the string length, the initial modal velocities `C_1, C_2, ...` (rad/s), the model
/// and `k5` variant by name and the viscous damping rate (1/s). Defaults: Table 1 of the paper
/// (aluminium reference) with `C = (0.1, 0.05, 0.02)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Parameters {
    pub length: f64,
    pub youngs_modulus: f64,
    pub density: f64,
    pub poisson_ratio: f64,
    pub outer_diameter: f64,
    pub inner_diameter: f64,
    pub omega: f64,
    pub initial_velocities: Vec<f64>,
    pub k5_variant: String,
    pub model: String,
    pub damping_rate: f64,
}

impl Default for Parameters {
    fn default() -> Self {
        Parameters {
            length: 100.0,
            youngs_modulus: 0.7e11,
            density: 2.7e3,
            poisson_ratio: 0.34,
            outer_diameter: 0.20,
            inner_diameter: 0.12,
            omega: 2.0 * PI * 0.5,
            initial_velocities: vec![0.1, 0.05, 0.02],
            k5_variant: "paper".into(),
            model: "paper".into(),
            damping_rate: 0.0,
        }
    }
}

/// What a field of [`Parameters`] takes, for an error of its type.
fn parameter_text(field: &str) -> Option<String> {
    Some(match field {
        "length" | "youngs_modulus" | "density" | "outer_diameter" => {
            format!("a finite real number, 0 < {field} < inf")
        }
        "inner_diameter" => "a finite real number, 0 <= inner_diameter < outer_diameter".into(),
        "poisson_ratio" => "a finite real number, -1 < poisson_ratio < 0.5".into(),
        "omega" => OMEGA_TEXT.into(),
        "damping_rate" => DAMPING_TEXT.into(),
        "initial_velocities" => "a sequence of finite real numbers (C_1, C_2, ...) in rad/s".into(),
        "k5_variant" => K5_TEXT.into(),
        "model" => MODEL_TEXT.into(),
        f if f.starts_with("initial_velocities[") => VELOCITY_TEXT.into(),
        _ => return None,
    })
}

const OMEGA_TEXT: &str = "a finite real number (rad/s, any sign)";
const DAMPING_TEXT: &str = "a finite real number >= 0 (1/s)";
const VELOCITY_TEXT: &str = "a finite real number (rad/s)";
const MODEL_TEXT: &str = "one of 'paper', 'consistent'";
const K5_TEXT: &str = "one of 'paper', 'energy'";

impl Parameters {
    /// Parses and validates parameters from a JSON object (every field optional: the
    /// defaults); an error names the field (`initial_velocities[2]`) and what it takes.
    pub fn from_json(json: &str) -> Result<Parameters> {
        let user: Value = serde_json::from_str(json)
            .map_err(|e| Error::invalid("parameters", format!("text that is not JSON ({e})"), "a JSON object"))?;
        if !user.is_object() {
            return Err(Error::invalid("parameters", schema::kind(&user), "a table/mapping of parameter fields"));
        }
        let p: Parameters = schema::parse(&user).map_err(|e| {
            let Error::InvalidInput { field, value, allowed } = e;
            let allowed = if value == "an unknown field" { allowed } else { parameter_text(&field).unwrap_or(allowed) };
            Error::InvalidInput { field, value, allowed }
        })?;
        p.validate()?;
        Ok(p)
    }

    /// The parameters as JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|_| "{}".into())
    }

    /// Checks every field's range, naming it.
    pub fn validate(&self) -> Result<()> {
        positive("length", self.length)?;
        positive("youngs_modulus", self.youngs_modulus)?;
        positive("density", self.density)?;
        check_diameters(self.outer_diameter, self.inner_diameter)?;
        check_poisson_ratio("poisson_ratio", self.poisson_ratio)?;
        if !self.omega.is_finite() {
            return Err(Error::invalid("omega", Num(self.omega), OMEGA_TEXT));
        }
        if !(self.damping_rate.is_finite() && self.damping_rate >= 0.0) {
            return Err(Error::invalid("damping_rate", Num(self.damping_rate), DAMPING_TEXT));
        }
        for (i, c) in self.initial_velocities.iter().enumerate() {
            if !c.is_finite() {
                return Err(Error::invalid(format!("initial_velocities[{i}]"), Num(*c), VELOCITY_TEXT));
            }
        }
        K5Variant::parse(&self.k5_variant)?;
        Model::parse(&self.model)?;
        Ok(())
    }
}

/// The coefficients `k1 .. k6` of `model` (module docs) for the physical inputs `p`; `k5`
/// selects the sign in `k5` of the paper model and is ignored by the consistent one.
///
/// Errors: an input out of range (naming its field), or (field `parameters`) inputs whose
/// coefficients are not finite or whose `k1`, `k2` are not `> 0` (overflow, underflow).
pub fn coefficients(p: &Physical, model: Model, k5: K5Variant) -> Result<Coefficients> {
    check_physical(p)?;
    let section = CrossSection::annulus(p.outer_diameter, p.inner_diameter)?;
    let nu = p.poisson_ratio;
    let g = shear_modulus(p.youngs_modulus, nu);
    let ip = section.polar_moment;
    let k1 = p.density * ip;
    let out = match model {
        Model::Paper => {
            let sign = match k5 {
                K5Variant::Paper => -1.0,
                K5Variant::Energy => 1.0,
            };
            Coefficients {
                k: PdeCoefficients {
                    k1,
                    k2: 4.0 * g * ip,
                    k3: 2.0 * section.area * g / (1.0 - 2.0 * nu),
                    k4: g * ip * (5.0 - 6.0 * nu) / (4.0 * (1.0 - 2.0 * nu)),
                    k5: g * (section.i_r + sign * section.i_x2y2 * (5.0 - 6.0 * nu)) / (8.0 * (1.0 - 2.0 * nu)),
                    k6: k6(k1, p.omega),
                },
                k6_per_omega_squared: k1,
            }
        }
        Model::Consistent => Coefficients {
            k: PdeCoefficients {
                k1,
                k2: g * ip,
                k3: 0.0,
                k4: 0.0,
                k5: consistent_k5(p_wave_modulus(p.youngs_modulus, nu), section.j4),
                k6: k6(0.0, p.omega),
            },
            k6_per_omega_squared: 0.0,
        },
    };
    if let Err(err) = out.k.validate() {
        return Err(Error::invalid(
            "parameters",
            format!(
                "E = {}, rho = {}, nu = {}, D = {}, d = {}, omega = {}",
                Num(p.youngs_modulus),
                Num(p.density),
                Num(nu),
                Num(p.outer_diameter),
                Num(p.inner_diameter),
                Num(p.omega)
            ),
            format!("magnitudes whose PDE coefficients k1..k6 are finite with k1, k2 > 0 ({err})"),
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_section_is_two_thirds_of_the_length() {
        assert_eq!(default_section(300.0), 200.0);
        assert_eq!(default_section(200.0), 400.0 / 3.0);
    }

    const ALUMINIUM: Physical = Physical {
        youngs_modulus: 0.7e11,
        density: 2.7e3,
        poisson_ratio: 0.34,
        outer_diameter: 0.20,
        inner_diameter: 0.12,
        omega: PI,
    };

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn model_annulus_table_1() {
        let s = CrossSection::annulus(0.20, 0.12).unwrap();
        assert!(close(s.area, PI * (0.01 - 0.0036), 1e-14));
        assert!(close(s.polar_moment, PI * 8.704e-5 / 2.0, 1e-13));
        assert!(close(s.i_r, PI * (1e-6 - 4.6656e-8) / 4.0, 1e-13));
        assert!(close(s.i_r, 6.0 * s.i_x2y2, 1e-15));
        // int r^4 dA = int (x^2 + y^2)^2 dA = I_r + 2 I_x2y2
        assert!(close(s.j4, s.i_r + 2.0 * s.i_x2y2, 1e-15));
        // solid shaft: I_p = pi R^4 / 2, J4 = pi R^6 / 3
        let solid = CrossSection::annulus(0.3, 0.0).unwrap();
        assert!(close(solid.polar_moment, PI * 0.15f64.powi(4) / 2.0, 1e-14));
        assert!(close(solid.j4, PI * 0.15f64.powi(6) / 3.0, 1e-14));
    }

    #[test]
    fn model_annulus_refuses_bad_diameters() {
        for (outer, inner, field) in [
            (0.0, 0.0, "outer_diameter"),
            (f64::NAN, 0.1, "outer_diameter"),
            (-1.0, 0.1, "outer_diameter"),
            (0.2, 0.2, "inner_diameter"),
            (0.2, -0.1, "inner_diameter"),
            (0.2, f64::INFINITY, "inner_diameter"),
            (1e-200, 0.0, "outer_diameter"),
            (1e100, 0.0, "outer_diameter"),
        ] {
            assert_eq!(CrossSection::annulus(outer, inner).unwrap_err().field(), field, "{outer} {inner}");
        }
    }

    #[test]
    fn model_moduli() {
        assert!(close(shear_modulus(0.7e11, 0.34), 0.7e11 / 2.68, 1e-15));
        // M = lambda + 2 mu with lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = G
        let (e, nu) = (2.1e11, 0.28);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        assert!(close(p_wave_modulus(e, nu), lambda + 2.0 * shear_modulus(e, nu), 1e-15));
        assert_eq!(p_wave_modulus(e, 0.0), e);
        assert!(close(shear_modulus(youngs_modulus(79.3e9, 0.3), 0.3), 79.3e9, 1e-15));
        assert_eq!(bar_speed(0.7e11, 2.7e3), (0.7e11f64 / 2.7e3).sqrt());
        assert!(close(bar_speed(2.1e11, 7.85e3), 5172.19, 1e-5));
    }

    #[test]
    fn model_terms_of_each_variant() {
        let coefficients = |m| coefficients(&ALUMINIUM, m, K5Variant::Paper).unwrap();
        let names = |m| -> Vec<&str> {
            coefficients(m).terms().unwrap().conservative().iter().map(|t| t.spec().coefficient).collect()
        };
        assert_eq!(names(Model::Paper), ["k2", "k3", "k4", "k5", "k6"]);
        assert_eq!(names(Model::Consistent), ["k2", "k5"]);
        let paper = coefficients(Model::Paper);
        let terms = paper.terms().unwrap();
        assert_eq!(terms.inertia(), paper.k.k1);
        let k: Vec<f64> = terms.conservative().iter().map(|t| t.coefficient()).collect();
        assert_eq!(k, paper.k.to_array()[1..].to_vec());
    }

    #[test]
    fn model_paper_coefficients_table_1() {
        let c = coefficients(&ALUMINIUM, Model::Paper, K5Variant::Paper).unwrap();
        let g = 0.7e11 / 2.68;
        let ip = PI * 8.704e-5 / 2.0;
        let ir = PI * (1e-6 - 4.6656e-8) / 4.0;
        let ixy = ir / 6.0;
        let k = c.k;
        assert!(close(k.k1, 0.36914970316741513, 1e-14));
        assert!(close(k.k2, 4.0 * g * ip, 1e-13));
        assert!(close(k.k3, 2.0 * PI * 0.0064 * g / 0.32, 1e-13));
        assert!(close(k.k4, g * ip * 2.96 / (4.0 * 0.32), 1e-13));
        assert!(close(k.k5, g * (ir - ixy * 2.96) / (8.0 * 0.32), 1e-13));
        assert!(close(k.k6, 2700.0 * ip * PI * PI, 1e-13));
        assert_eq!(c.k6_per_omega_squared, k.k1);
        assert_eq!(k.k6, k6(k.k1, PI));
        assert_eq!(k6(0.0, 1e200), 0.0);
        assert_eq!(k6(2.0, -3.0), 18.0);
        let energy = coefficients(&ALUMINIUM, Model::Paper, K5Variant::Energy).unwrap();
        assert!(close(energy.k.k5, g * (ir + ixy * 2.96) / (8.0 * 0.32), 1e-13));
        assert_eq!([k.k1, k.k2, k.k3, k.k4, k.k6], [energy.k.k1, energy.k.k2, energy.k.k3, energy.k.k4, energy.k.k6]);
    }

    #[test]
    fn model_consistent_coefficients() {
        let c = coefficients(&ALUMINIUM, Model::Consistent, K5Variant::Paper).unwrap();
        let g = 0.7e11 / 2.68;
        let m = 0.7e11 * 0.66 / (1.34 * 0.32);
        let ip = PI * 8.704e-5 / 2.0;
        let j4 = PI * (1e-6 - 4.6656e-8) / 3.0;
        assert!(close(c.k.k1, 2700.0 * ip, 1e-14));
        assert!(close(c.k.k2, g * ip, 1e-14));
        assert!(close(c.k.k5, m * j4 / 2.0, 1e-14));
        assert_eq!([c.k.k3, c.k.k4, c.k.k6, c.k6_per_omega_squared], [0.0; 4]);
        // wave speed sqrt(G / rho), a quarter of the paper model's k2
        let paper = coefficients(&ALUMINIUM, Model::Paper, K5Variant::Paper).unwrap();
        assert!(close((c.k.k2 / c.k.k1).sqrt(), (g / 2700.0).sqrt(), 1e-15));
        assert_eq!(paper.k.k2, 4.0 * c.k.k2);
        // the k5 variant and the rotation speed do not enter
        let other = Physical { omega: 1e200, ..ALUMINIUM };
        assert_eq!(coefficients(&other, Model::Consistent, K5Variant::Energy).unwrap(), c);
    }

    #[test]
    fn model_errors_name_the_field() {
        let bad = |p: Physical, model: Model| coefficients(&p, model, K5Variant::Paper).unwrap_err();
        assert_eq!(bad(Physical { poisson_ratio: 0.5, ..ALUMINIUM }, Model::Paper).field(), "poisson_ratio");
        assert_eq!(bad(Physical { density: 0.0, ..ALUMINIUM }, Model::Consistent).field(), "density");
        assert_eq!(bad(Physical { omega: f64::NAN, ..ALUMINIUM }, Model::Paper).field(), "omega");
        assert_eq!(bad(Physical { inner_diameter: 0.3, ..ALUMINIUM }, Model::Paper).field(), "inner_diameter");
        let overflow = bad(Physical { omega: 1e200, ..ALUMINIUM }, Model::Paper);
        assert_eq!(overflow.field(), "parameters");
        assert!(overflow.to_string().contains("k6"), "{overflow}");
        assert_eq!(bad(Physical { youngs_modulus: f64::MAX, ..ALUMINIUM }, Model::Paper).field(), "parameters");
        assert_eq!(bad(Physical { density: 1e-320, ..ALUMINIUM }, Model::Consistent).field(), "parameters");
        assert_eq!(Model::parse("paper").unwrap(), Model::Paper);
        assert_eq!(Model::parse("consistent").unwrap().name(), "consistent");
        assert_eq!(Model::parse("classic").unwrap_err().field(), "model");
        assert_eq!(K5Variant::parse("energy").unwrap(), K5Variant::Energy);
        assert_eq!(K5Variant::parse("x").unwrap_err().field(), "k5_variant");
    }
}
