//! The string's sections (`[[sections]]`) and its torque-twist law (`nonlinearity`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::{pos, DrillConfig, MAX_DIAMETER, MAX_SECTIONS, MAX_SECTION_LENGTH};

/// One section of the string, from the top.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Section {
    /// A label for tables and plots.
    #[schemars(extend("label" = "section name"))]
    pub name: String,
    /// Measured length of the section, > 0 and at most 100 km (required).
    #[schemars(extend("unit" = "m", "label" = "section length"))]
    pub length: f64,
    /// Outer diameter of the pipe body, > 0 and at most 10 m (required).
    #[schemars(extend("unit" = "m", "label" = "outer diameter"))]
    pub outer_diameter: f64,
    /// Inner diameter, from 0 to below the outer diameter (required).
    #[schemars(extend("unit" = "m", "label" = "inner diameter"))]
    pub inner_diameter: f64,
    /// Shear modulus `G` of the material, > 0.
    #[schemars(extend("unit" = "Pa", "label" = "shear modulus"))]
    pub shear_modulus: f64,
    /// Density of the material, > 0 (and above the mud density).
    #[schemars(extend("unit" = "kg/m^3", "label" = "density"))]
    pub density: f64,
    /// Diameter at which the wall's friction acts, > 0; the friction lever arm is half of it.
    /// Null: the tool joints' outer diameter when the section has tool joints (the string
    /// touches the wall at them), else the outer diameter.
    #[schemars(extend("unit" = "m", "label" = "contact diameter"))]
    pub contact_diameter: Option<f64>,
    /// Polar moment of area `J`, > 0. Null: `pi/32 (OD^4 - ID^4)` of the diameters.
    #[schemars(extend("unit" = "m^4", "label" = "polar moment"))]
    pub polar_moment: Option<f64>,
    /// Cross-section area `A`, > 0. Null: `pi/4 (OD^2 - ID^2)` of the diameters.
    #[schemars(extend("unit" = "m^2", "label" = "cross-section area"))]
    pub area: Option<f64>,
    /// `J4 = int r^4 dA`, > 0, of the `consistent` nonlinearity's `k5 = M J4 / 2` (unused by
    /// `linear`). Null: `pi/192 (OD^6 - ID^6)`, the annulus of the diameters. A section whose
    /// `polar_moment` is overridden (an equivalent section) needs it too for the consistent law.
    #[schemars(extend("unit" = "m^6", "label" = "quartic moment"))]
    pub quartic_moment: Option<f64>,
    /// Poisson's ratio, `0 < nu < 0.5`: with `shear_modulus` it gives the P-wave modulus
    /// `M = 2 G (1 - nu) / (1 - 2 nu)` of the `consistent` nonlinearity (unused by `linear`).
    #[schemars(extend("unit" = "", "label" = "Poisson's ratio"))]
    pub poisson_ratio: f64,
    /// API drill-pipe grade (`E-75`, `X-95`, `G-105`, `S-135`), for the torque and drag's
    /// utilisation; or `yield_strength`. Null: no utilisation.
    #[schemars(extend("label" = "grade"))]
    pub grade: Option<super::super::pipe::Grade>,
    /// Minimum yield strength, > 0, in place of `grade`.
    #[schemars(extend("unit" = "Pa", "label" = "yield strength"))]
    pub yield_strength: Option<f64>,
    /// Adjusted weight in air per length with the tool joints (as pipe tables give it), > 0,
    /// for the torque and drag. Null: from the tool joints, else the body.
    #[schemars(extend("unit" = "N/m", "label" = "nominal weight"))]
    pub nominal_weight: Option<f64>,
    /// Outer diameter of the tool joints, at least the body's; the wall's friction acts at it
    /// unless `contact_diameter` is given.
    #[schemars(extend("unit" = "m", "label" = "tool-joint outer diameter"))]
    pub tool_joint_outer_diameter: Option<f64>,
    /// Inner diameter of the tool joints, below their outer diameter.
    #[schemars(extend("unit" = "m", "label" = "tool-joint inner diameter"))]
    pub tool_joint_inner_diameter: Option<f64>,
    /// Length of one tool joint (pin and box), below the joint length.
    #[schemars(extend("unit" = "m", "label" = "tool-joint length"))]
    pub tool_joint_length: Option<f64>,
    /// Length of one joint, > 0 (null: 9.144 m, API range 2).
    #[schemars(extend("unit" = "m", "label" = "joint length"))]
    pub joint_length: Option<f64>,
    /// Make-up torque of the tool joints, > 0 (null: not checked).
    #[schemars(extend("unit" = "N*m", "label" = "make-up torque"))]
    pub makeup_torque: Option<f64>,
}

impl Default for Section {
    /// A template (the Aarsnes-Shor Well B drill pipe, 5 1/2", steel); `length` and the
    /// diameters are required in a configuration.
    fn default() -> Self {
        Section {
            name: "drill pipe".into(),
            length: 2500.0,
            outer_diameter: 0.146529,
            inner_diameter: 0.123024,
            shear_modulus: 79.3e9,
            density: 7850.0,
            contact_diameter: None,
            polar_moment: None,
            area: None,
            quartic_moment: None,
            poisson_ratio: 0.3,
            grade: None,
            yield_strength: None,
            nominal_weight: None,
            tool_joint_outer_diameter: None,
            tool_joint_inner_diameter: None,
            tool_joint_length: None,
            joint_length: None,
            makeup_torque: None,
        }
    }
}

/// The torque-twist law of the string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Nonlinearity {
    /// `tau = G J eps` (`eps` the twist per length): the linear wave equation.
    Linear,
    /// The finite-strain law of [`crate::model::Model::Consistent`],
    /// `tau = k2 eps + k5 eps^3` with `k2 = G J`, `k5 = M J4 / 2` (hardening).
    Consistent,
}

impl Nonlinearity {
    pub const NAMES: [&'static str; 2] = ["linear", "consistent"];
}

impl DrillConfig {
    /// `sections`: their count and each section's values.
    pub(super) fn validate_sections(&self) -> Result<()> {
        let n = self.sections.len();
        if !(1..=MAX_SECTIONS).contains(&n) {
            return Err(Error::invalid("sections", format!("{n} sections"), format!("1..={MAX_SECTIONS} sections")));
        }
        for (i, s) in self.sections.iter().enumerate() {
            let f = |k: &str| format!("sections[{i}].{k}");
            if !(s.length.is_finite() && s.length > 0.0 && s.length <= MAX_SECTION_LENGTH) {
                return Err(Error::invalid(
                    f("length"),
                    Num(s.length),
                    format!("a finite number > 0 m, at most {MAX_SECTION_LENGTH} m"),
                ));
            }
            if !(s.outer_diameter.is_finite() && s.outer_diameter > 0.0 && s.outer_diameter <= MAX_DIAMETER) {
                return Err(Error::invalid(
                    f("outer_diameter"),
                    Num(s.outer_diameter),
                    format!("a finite number > 0 m, at most {MAX_DIAMETER} m (in metres: 5 in = 0.127 m)"),
                ));
            }
            if let Some(d) = s.contact_diameter {
                if !(d.is_finite() && d > 0.0 && d <= MAX_DIAMETER) {
                    return Err(Error::invalid(
                        f("contact_diameter"),
                        Num(d),
                        format!("a finite number > 0 m, at most {MAX_DIAMETER} m, or null for the outer diameter"),
                    ));
                }
            }
            if !(s.inner_diameter.is_finite() && s.inner_diameter >= 0.0 && s.inner_diameter < s.outer_diameter) {
                return Err(Error::invalid(
                    f("inner_diameter"),
                    Num(s.inner_diameter),
                    format!("a finite number in [0, outer_diameter = {}) (m)", Num(s.outer_diameter)),
                ));
            }
            pos(f("shear_modulus"), s.shear_modulus, "Pa")?;
            pos(f("density"), s.density, "kg/m^3")?;
            crate::model::check_poisson_ratio(f("poisson_ratio"), s.poisson_ratio)?;
            for (k, v, unit) in [
                ("contact_diameter", s.contact_diameter, "m"),
                ("polar_moment", s.polar_moment, "m^4"),
                ("area", s.area, "m^2"),
                ("quartic_moment", s.quartic_moment, "m^6"),
            ] {
                if let Some(v) = v {
                    pos(f(k), v, &format!("{unit}, or null for the default"))?;
                }
            }
        }
        Ok(())
    }
}
