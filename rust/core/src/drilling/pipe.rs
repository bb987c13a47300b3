//! The pipe and the hole as a drilling engineer specifies them, for the torque and drag: a
//! section's grade (or yield strength), its nominal (adjusted) weight, its tool joints and
//! make-up torque; the hole's diameter and its casing and open-hole sections. Each key is
//! optional and changes nothing when absent.
//!
//! The weight per length of a section is, in this order: `nominal_weight` (the adjusted weight
//! in air with the tool joints, as pipe tables give it) times the buoyancy factor
//! `1 - rho_mud / rho`; else, with tool joints, the body's and the tool joints' steel averaged
//! over a joint, `(A (L_j - L_tj) + A_tj L_tj) / L_j` (upsets not counted); else the body's
//! `(rho - rho_mud) g A`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::error::{Error, Num, Result};
use crate::model::youngs_modulus;
use crate::well::buckling::{Body, Hole};
use crate::well::torque_drag::SlidingInterval;

use super::config::{DrillConfig, Section, MAX_DIAMETER};
use super::grid::SectionProps;

/// The length of a joint without `joint_length`, m: API range 2 (30 ft).
pub const DEFAULT_JOINT_LENGTH: f64 = 9.144;

/// One psi, Pa.
const PSI: f64 = 6_894.757_293_168_361;

/// An API 5DP drill-pipe grade (its minimum yield strength).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Grade {
    #[serde(rename = "E-75")]
    E75,
    #[serde(rename = "X-95")]
    X95,
    #[serde(rename = "G-105")]
    G105,
    #[serde(rename = "S-135")]
    S135,
}

impl Grade {
    pub const NAMES: [&'static str; 4] = ["E-75", "X-95", "G-105", "S-135"];

    /// The minimum yield strength (API Spec 5DP: 75, 95, 105, 135 ksi), Pa.
    pub fn yield_strength(self) -> f64 {
        let ksi = match self {
            Grade::E75 => 75.0,
            Grade::X95 => 95.0,
            Grade::G105 => 105.0,
            Grade::S135 => 135.0,
        };
        ksi * 1e3 * PSI
    }
}

/// A section of the hole from the one above (or the surface) to `bottom_md`: casing or open hole.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HoleSection {
    /// Measured depth of the section's bottom, below the section above's.
    #[schemars(extend("unit" = "m", "label" = "hole section bottom"))]
    pub bottom_md: f64,
    /// The hole's (or the casing's inner) diameter, larger than every pipe and tool joint in it.
    #[schemars(extend("unit" = "m", "label" = "hole diameter"))]
    pub diameter: f64,
    /// Static friction factor in the section, >= 0 (null: `friction.static`, or the intervals).
    #[serde(rename = "friction", default)]
    #[schemars(extend("unit" = "", "label" = "friction factor"))]
    pub friction: Option<f64>,
}

/// The yield strength of a section, Pa (None: no grade and no `yield_strength`).
pub fn yield_strength(s: &Section) -> Option<f64> {
    s.yield_strength.or(s.grade.map(Grade::yield_strength))
}

/// The friction lever arm of a section, m: half its `contact_diameter`, else half its
/// `tool_joint_outer_diameter` (a string with tool joints touches the wall at them), else half
/// its outer diameter. The grid's wall friction, the torque and drag and the break-off torque
/// all take it through [`SectionProps::contact_radius`].
pub fn contact_radius(s: &Section) -> f64 {
    s.contact_diameter.or(s.tool_joint_outer_diameter).unwrap_or(s.outer_diameter) / 2.0
}

/// The steel area averaged over a joint with its tool joints, m^2 (None without tool joints).
pub fn adjusted_area(s: &Section) -> Option<f64> {
    let (od, id, ltj) = (s.tool_joint_outer_diameter?, s.tool_joint_inner_diameter?, s.tool_joint_length?);
    let body = SectionProps::new(s, 0.0).area;
    let joint = s.joint_length.unwrap_or(DEFAULT_JOINT_LENGTH);
    let tj = PI / 4.0 * (od * od - id * id);
    Some((body * (joint - ltj) + tj * ltj) / joint)
}

/// The adjusted weight per length in air of a section, N/m: `nominal_weight`, else the steel
/// of [`adjusted_area`] (or of the body) times `rho g`.
pub fn adjusted_weight(s: &Section, gravity: f64) -> f64 {
    s.nominal_weight.unwrap_or_else(|| s.density * gravity * adjusted_area(s).unwrap_or(SectionProps::new(s, 0.0).area))
}

/// The buoyed weight per length of a section in mud of density `mud`, N/m.
pub fn buoyed_weight(s: &Section, mud: f64, gravity: f64) -> f64 {
    match (s.nominal_weight, adjusted_area(s)) {
        (Some(w), _) => w * (1.0 - mud / s.density),
        (None, Some(a)) => (s.density - mud) * gravity * a,
        (None, None) => SectionProps::new(s, mud).buoyed_mass_per_length * gravity,
    }
}

/// The pipe body of a section for buckling and the limits.
pub fn body(s: &Section) -> Body {
    let p = SectionProps::new(s, 0.0);
    Body {
        outer_diameter: s.outer_diameter,
        area: p.area,
        polar_moment: p.polar_moment,
        youngs_modulus: youngs_modulus(s.shear_modulus, s.poisson_ratio),
        yield_strength: yield_strength(s),
        makeup_torque: s.makeup_torque,
        joint_length: s.joint_length.unwrap_or(DEFAULT_JOINT_LENGTH),
    }
}

/// The hole of a configuration (None without `well.hole_diameter`).
pub fn hole(cfg: &DrillConfig) -> Option<Hole> {
    let d = cfg.well.hole_diameter?;
    Some(Hole { sections: cfg.well.hole_sections.iter().map(|h| (h.bottom_md, h.diameter)).collect(), diameter: d })
}

/// The friction factors of the hole sections that give one, times `ratio`.
pub fn hole_friction(cfg: &DrillConfig, ratio: f64) -> Vec<SlidingInterval> {
    let mut top = 0.0;
    let mut out = Vec::new();
    for h in &cfg.well.hole_sections {
        if let Some(mu) = h.friction {
            out.push(SlidingInterval { top_md: top, bottom_md: h.bottom_md, mu: ratio * mu });
        }
        top = h.bottom_md;
    }
    out
}

fn positive(field: String, x: Option<f64>, hi: f64, unit: &str) -> Result<()> {
    match x {
        Some(v) if !(v.is_finite() && v > 0.0 && v <= hi) => {
            Err(Error::invalid(field, Num(v), format!("a number > 0 and at most {} {unit}", Num(hi))))
        }
        _ => Ok(()),
    }
}

/// Checks the pipe keys of every section and the hole against them.
pub fn validate(cfg: &DrillConfig) -> Result<()> {
    let mut widest = (0.0, String::new());
    for (i, s) in cfg.sections.iter().enumerate() {
        let f = |k: &str| format!("sections[{i}].{k}");
        positive(f("yield_strength"), s.yield_strength, 5e9, "Pa")?;
        if s.yield_strength.is_some() && s.grade.is_some() {
            return Err(Error::invalid(f("yield_strength"), "both grade and yield_strength", "one of them"));
        }
        positive(f("nominal_weight"), s.nominal_weight, 1e5, "N/m")?;
        positive(f("makeup_torque"), s.makeup_torque, 1e7, "N m")?;
        positive(f("joint_length"), s.joint_length, 100.0, "m")?;
        positive(f("tool_joint_outer_diameter"), s.tool_joint_outer_diameter, MAX_DIAMETER, "m")?;
        positive(f("tool_joint_length"), s.tool_joint_length, 100.0, "m")?;
        let tj = [s.tool_joint_outer_diameter, s.tool_joint_inner_diameter, s.tool_joint_length];
        if tj.iter().any(Option::is_some) && !tj.iter().all(Option::is_some) {
            return Err(Error::invalid(
                f("tool_joint_outer_diameter"),
                "some of the tool joint's keys",
                "all of tool_joint_outer_diameter, tool_joint_inner_diameter and tool_joint_length, or none",
            ));
        }
        if let (Some(od), Some(id), Some(l)) = (tj[0], tj[1], tj[2]) {
            if od.is_nan() || od < s.outer_diameter {
                return Err(Error::invalid(
                    f("tool_joint_outer_diameter"),
                    Num(od),
                    format!("at least the body's outer diameter {} m", Num(s.outer_diameter)),
                ));
            }
            if !(id.is_finite() && id >= 0.0 && id < od) {
                return Err(Error::invalid(f("tool_joint_inner_diameter"), Num(id), format!("in [0, {}) m", Num(od))));
            }
            let joint = s.joint_length.unwrap_or(DEFAULT_JOINT_LENGTH);
            if l >= joint {
                return Err(Error::invalid(
                    f("tool_joint_length"),
                    Num(l),
                    format!("below the joint length {} m", Num(joint)),
                ));
            }
        }
        let od = s.tool_joint_outer_diameter.unwrap_or(0.0).max(s.outer_diameter);
        if od > widest.0 {
            widest = (
                od,
                if s.tool_joint_outer_diameter.is_some_and(|t| t >= s.outer_diameter) {
                    f("tool_joint_outer_diameter")
                } else {
                    f("outer_diameter")
                },
            );
        }
    }
    let w = &cfg.well;
    if w.hole_diameter.is_none() && !w.hole_sections.is_empty() {
        return Err(Error::invalid("well.hole_diameter", "null", "the open hole's diameter below the hole sections"));
    }
    let larger = |field: String, d: f64| -> Result<()> {
        if d.is_finite() && d > widest.0 && d <= MAX_DIAMETER {
            Ok(())
        } else {
            Err(Error::invalid(
                field,
                Num(d),
                format!(
                    "a diameter larger than every pipe and tool joint ({} m, {}) and at most {} m",
                    Num(widest.0),
                    widest.1,
                    Num(MAX_DIAMETER)
                ),
            ))
        }
    };
    if let Some(d) = w.hole_diameter {
        larger("well.hole_diameter".into(), d)?;
    }
    let mut top = 0.0;
    for (j, h) in w.hole_sections.iter().enumerate() {
        if !(h.bottom_md.is_finite() && h.bottom_md > top) {
            return Err(Error::invalid(
                format!("well.hole_sections[{j}].bottom_md"),
                Num(h.bottom_md),
                format!("a finite depth > {} m (the section above's bottom)", Num(top)),
            ));
        }
        larger(format!("well.hole_sections[{j}].diameter"), h.diameter)?;
        if let Some(mu) = h.friction {
            if !(mu.is_finite() && (0.0..=10.0).contains(&mu)) {
                return Err(Error::invalid(
                    format!("well.hole_sections[{j}].friction"),
                    Num(mu),
                    "a friction factor in [0, 10]",
                ));
            }
        }
        top = h.bottom_md;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const INCH: f64 = 0.0254;
    const LB_FT: f64 = 4.448_221_615_260_5 / 0.3048;

    /// API RP 7G (16th ed., Table 2; also the IADC Drilling Manual's drill-pipe tables): 5 in
    /// 19.50 lb/ft grade S-135 with NC50 tool joints, 6 5/8 in OD, 2 3/4 in ID, has an adjusted
    /// weight of 22.60 lb/ft. The tool joint's steel over a 30 ft joint, pin and box together
    /// 21 in of 6 5/8 in tool joint, and the body's plain-end steel (17.93 lb/ft) give it
    /// within 3 % (the upsets not counted).
    #[test]
    fn tool_joints_give_the_pipe_tables_adjusted_weight() {
        let s = Section {
            outer_diameter: 5.0 * INCH,
            inner_diameter: 4.276 * INCH,
            density: 7850.0,
            tool_joint_outer_diameter: Some(6.625 * INCH),
            tool_joint_inner_diameter: Some(2.75 * INCH),
            tool_joint_length: Some(1.75 * 0.3048),
            joint_length: Some(30.0 * 0.3048),
            ..Section::default()
        };
        let plain = adjusted_weight(&Section { tool_joint_outer_diameter: None, ..s.clone() }, 9.80665) / LB_FT;
        assert!((plain - 17.93).abs() < 0.05, "{plain}");
        let adjusted = adjusted_weight(&s, 9.80665) / LB_FT;
        assert!((adjusted / 22.60 - 1.0).abs() < 0.03, "{adjusted}");
        // the nominal weight overrides and is buoyed by the steel's density
        let n = Section { nominal_weight: Some(22.6 * LB_FT), ..s };
        assert!((buoyed_weight(&n, 1200.0, 9.81) - 22.6 * LB_FT * (1.0 - 1200.0 / 7850.0)).abs() < 1e-9);
    }

    /// The wall meets a section at its tool joints: their radius is the default lever arm, the
    /// body's without them, and `contact_diameter` overrides both.
    #[test]
    fn the_tool_joints_are_the_default_lever_arm() {
        let s =
            Section { outer_diameter: 5.0 * INCH, tool_joint_outer_diameter: Some(6.625 * INCH), ..Section::default() };
        assert_eq!(contact_radius(&s), 6.625 * INCH / 2.0);
        assert_eq!(SectionProps::new(&s, 1200.0).contact_radius, 6.625 * INCH / 2.0);
        assert_eq!(contact_radius(&Section { tool_joint_outer_diameter: None, ..s.clone() }), 5.0 * INCH / 2.0);
        assert_eq!(contact_radius(&Section { contact_diameter: Some(0.15), ..s }), 0.075);
    }

    #[test]
    fn grades_and_validation_name_the_key() {
        assert!((Grade::S135.yield_strength() - 930.79e6).abs() < 0.01e6);
        let mut cfg = DrillConfig::default();
        validate(&cfg).unwrap();
        cfg.well.hole_diameter = Some(0.1);
        assert_eq!(validate(&cfg).unwrap_err().field(), "well.hole_diameter");
        cfg.well.hole_diameter = Some(0.2159);
        cfg.sections[0].tool_joint_outer_diameter = Some(0.22);
        cfg.sections[0].tool_joint_inner_diameter = Some(0.07);
        cfg.sections[0].tool_joint_length = Some(0.5);
        let e = validate(&cfg).unwrap_err();
        assert_eq!(e.field(), "well.hole_diameter");
        assert!(e.to_string().contains("tool_joint_outer_diameter"), "{e}");
        cfg.sections[0].tool_joint_outer_diameter = Some(0.17);
        validate(&cfg).unwrap();
        cfg.well.hole_sections = vec![HoleSection { bottom_md: 0.0, diameter: 0.25, friction: None }];
        assert_eq!(validate(&cfg).unwrap_err().field(), "well.hole_sections[0].bottom_md");
    }
}
