//! The well's table (`[well]`): survey stations, a survey file or a plan, mud and gravity.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};
use crate::well::plan::SegmentSpec;

use super::{finite, nonneg, within, DrillConfig};

/// The inclination: one constant angle, or a table at the measured depths `well.md`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Inclination {
    Constant(f64),
    Table(Vec<f64>),
}

/// The well: survey (linear interpolation in measured depth, constant beyond the ends), mud.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Well {
    /// Measured depths of the survey stations, strictly increasing. Null with a constant
    /// inclination (one number in `inclination_deg`).
    #[schemars(extend("unit" = "m", "label" = "measured depth"))]
    pub md: Option<Vec<f64>>,
    /// Inclination at each `md` station, from 0 to below 180 degrees (0: vertical); one number without `md` is
    /// a constant inclination.
    #[schemars(extend("unit" = "deg", "label" = "inclination"))]
    pub inclination_deg: Inclination,
    /// Density of the mud, for the buoyancy of the string (weight `(rho - mud_density) g A` per
    /// metre): from 0 (no buoyancy) to below every section's density.
    #[schemars(extend("unit" = "kg/m^3", "label" = "mud density"))]
    pub mud_density: f64,
    /// Acceleration of gravity, >= 0.
    #[schemars(extend("unit" = "m/s^2", "label" = "gravity"))]
    pub gravity: f64,
    /// Azimuth in degrees clockwise from north, 0 to 360: one constant angle, or one per `md`
    /// station (with a plan: the constant azimuth it starts from).
    #[schemars(extend("unit" = "deg", "label" = "azimuth"))]
    pub azimuth_deg: Inclination,
    /// A survey file (CSV: columns md, inc, azi; units in the header as `md_m` / `md_ft`,
    /// `inc_deg` / `inc_rad`, ...; default m and degrees), in place of `md`,
    /// `inclination_deg` and `azimuth_deg`. A relative path is relative to the working
    /// directory here; the TOML loader makes it relative to the configuration file.
    #[schemars(extend("label" = "survey file"))]
    pub survey: Option<String>,
    /// A plan in place of the stations: segments `{hold = m}`, `{build = deg/30 m,
    /// inclination = deg}`, `{drop = ..., inclination = ...}`, `{turn = deg/30 m, azimuth =
    /// deg}` from the surface, vertical at azimuth `azimuth_deg` (a constant).
    #[schemars(extend("label" = "well plan"))]
    pub plan: Option<Vec<SegmentSpec>>,
    /// A survey (stations, file or plan) shorter than the string is refused, unless `extend`
    /// is true: then the hole goes straight on in the last station's direction.
    #[schemars(extend("label" = "extend the survey"))]
    pub extend: bool,
    /// The stations read from `survey` when the configuration was parsed (md m, inclination
    /// and azimuth degrees).
    #[serde(skip)]
    pub survey_stations: Option<std::sync::Arc<[Vec<f64>; 3]>>,
}

impl Default for Well {
    /// The Aarsnes-Shor Well B survey: vertical to 500 m, build to 60 deg at 1600 m.
    fn default() -> Self {
        Well {
            md: Some(vec![0.0, 500.0, 1600.0, 4000.0]),
            inclination_deg: Inclination::Table(vec![0.0, 0.0, 60.0, 60.0]),
            mud_density: 0.0,
            gravity: 9.81,
            azimuth_deg: Inclination::Constant(0.0),
            survey: None,
            plan: None,
            extend: false,
            survey_stations: None,
        }
    }
}

impl DrillConfig {
    /// `well`: the stations (or a survey file or plan in their place), the mud below every section's
    /// density, gravity, the azimuths and the trajectory they make.
    pub(super) fn validate_well(&self) -> Result<()> {
        let min_density = self.sections.iter().fold(f64::INFINITY, |m, s| m.min(s.density));
        let w = &self.well;
        let replaced = w.survey.is_some() || w.plan.is_some();
        match (&w.md, &w.inclination_deg) {
            _ if replaced => {}
            (None, Inclination::Constant(x)) => crate::drilling::limits::check_inclination("well.inclination_deg", *x)?,
            (Some(_), Inclination::Constant(_)) => {
                return Err(Error::invalid(
                    "well.inclination_deg",
                    "a single number with well.md given",
                    "a list of one inclination per well.md station (or null well.md)",
                ))
            }
            (None, Inclination::Table(_)) => {
                return Err(Error::invalid("well.md", "null", "the measured depths of the inclination table"))
            }
            (Some(md), Inclination::Table(inc)) => {
                if md.is_empty() {
                    return Err(Error::invalid("well.md", "an empty list", "at least one station"));
                }
                for (j, d) in md.iter().enumerate() {
                    finite(format!("well.md[{j}]"), *d, "m")?;
                    if j > 0 && *d <= md[j - 1] {
                        return Err(Error::invalid(
                            format!("well.md[{j}]"),
                            Num(*d),
                            format!("strictly increasing depths (> well.md[{}] = {})", j - 1, Num(md[j - 1])),
                        ));
                    }
                }
                if inc.len() != md.len() {
                    return Err(Error::invalid(
                        "well.inclination_deg",
                        format!("{} values", inc.len()),
                        format!("{} values (one per well.md station)", md.len()),
                    ));
                }
                for (j, x) in inc.iter().enumerate() {
                    crate::drilling::limits::check_inclination(format!("well.inclination_deg[{j}]"), *x)?;
                }
            }
        }
        if !(w.mud_density.is_finite() && w.mud_density >= 0.0 && w.mud_density < min_density) {
            return Err(Error::invalid(
                "well.mud_density",
                Num(w.mud_density),
                format!("a finite number in [0, {}) kg/m^3 (below every section's density)", Num(min_density)),
            ));
        }
        nonneg("well.gravity", w.gravity, "m/s^2")?;
        match &w.azimuth_deg {
            Inclination::Constant(a) => within("well.azimuth_deg", *a, 0.0, 360.0, "degrees")?,
            Inclination::Table(v) => {
                for (j, a) in v.iter().enumerate() {
                    within(format!("well.azimuth_deg[{j}]"), *a, 0.0, 360.0, "degrees")?;
                }
            }
        }
        crate::drilling::well::trajectory(self)?;
        Ok(())
    }
}
