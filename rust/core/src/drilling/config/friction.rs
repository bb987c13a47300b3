//! The wall's friction (`[friction]`): factors, law, contact force, intervals, coupling.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::{nonneg, pos, within, DrillConfig};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionModel {
    /// Set-valued Coulomb friction with a true stick phase (Aarsnes & Shor).
    SetValued,
    /// `tanh(omega / regularisation_speed)` times the kinetic limit.
    Regularised,
}

/// Along-string Coulomb friction (soft-string contact).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Friction {
    /// Static friction factor between string and wall, >= 0 (where no interval applies).
    ///
    /// One friction vocabulary for both models: a contact that sticks holds up to `static`
    /// (the break-off torque, the stick phases of the dynamic model); a contact that slides
    /// carries the kinetic factor `static x kinetic_ratio`, in the dynamic model and in every
    /// load of `torque-drag` (pick-up, slack-off and rotating are steady slides). A
    /// torque-and-drag "friction factor" is the kinetic factor: with `kinetic_ratio = 1` (one
    /// factor) `static` is it.
    #[serde(rename = "static")]
    #[schemars(extend("unit" = "", "label" = "static friction factor"))]
    pub static_coefficient: f64,
    /// Kinetic over static friction factor, in [0, 1]: the sliding factor of the dynamic model
    /// and of `torque-drag` is `static x kinetic_ratio`.
    #[schemars(extend("unit" = "", "label" = "kinetic/static friction ratio"))]
    pub kinetic_ratio: f64,
    /// A cell slower than this sticks if the torque needed to stop it is within the static
    /// limit, >= 0 (Aarsnes-Shor `o_thres`): the torsional wall friction's rule. The coupled
    /// wall friction of a run with a hoist (`coupling = "axial_torsional"`) has no threshold: a
    /// contact sticks exactly when the force that stops it in a step is within the static
    /// limit, and slides on the kinetic factor otherwise.
    #[schemars(extend("unit" = "rad/s", "label" = "stick speed"))]
    pub stick_speed: f64,
    /// The wall friction law: `set_valued` (a true stick phase) or `regularised` (smooth).
    #[schemars(extend("label" = "friction model"))]
    pub model: FrictionModel,
    /// The speed scale of `regularised` friction, > 0.
    #[schemars(extend("unit" = "rad/s", "label" = "regularisation speed"))]
    pub regularisation_speed: f64,
    /// The normal force the wall's friction limit is made of: `soft_string` (default), the
    /// normal force of the static soft-string torque-and-drag solution (buoyed weight and
    /// tension times curvature, rotating off bottom, or on bottom with the bit's weight), or
    /// `weight`, the buoyed weight times the sine of the inclination alone (Aarsnes & Shor 2018,
    /// eq. 6, to reproduce their model).
    #[schemars(extend("label" = "contact force"))]
    pub contact: Contact,
    /// Static friction factors over depth intervals (cased and open hole differ); `static`
    /// applies where no interval does. The kinetic factor is `kinetic_ratio` times the static
    /// one everywhere.
    #[schemars(extend("label" = "friction intervals"))]
    pub intervals: Vec<FrictionInterval>,
    /// What the wall friction of a coupled run (`[hoist]`) acts on: `axial_torsional` (default),
    /// the Coulomb friction against the contact's sliding velocity (axial speed, contact radius
    /// times angular speed) on both fields with one stick phase, so that a rotating string
    /// slides axially with little drag; or `torsion_only`, the torsional field alone (the axial
    /// field without wall friction, the coupled runs before this key). No effect without a hoist.
    #[schemars(extend("label" = "wall friction coupling"))]
    pub coupling: FrictionCoupling,
}

/// What the wall friction of a coupled run acts on ([`Friction::coupling`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionCoupling {
    /// Against the sliding velocity `(v, r omega)` on both fields
    /// ([`super::engine::coupled_friction`]).
    #[default]
    AxialTorsional,
    /// On the torsional field alone.
    TorsionOnly,
}

impl FrictionCoupling {
    pub const NAMES: [&'static str; 2] = ["axial_torsional", "torsion_only"];
}

/// The normal force of the wall's friction limit ([`Friction::contact`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Contact {
    /// `g sin(inc) (rho - rho_mud) A` per metre (Aarsnes & Shor 2018).
    Weight,
    /// The soft-string normal force per metre of [`crate::well::torque_drag`].
    SoftString,
}

impl Contact {
    pub const NAMES: [&'static str; 2] = ["weight", "soft_string"];
}

/// A static friction factor over `[top_md, bottom_md)`, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionInterval {
    /// Measured depth of the interval's top, >= 0.
    #[schemars(extend("unit" = "m", "label" = "interval top"))]
    pub top_md: f64,
    /// Measured depth of the interval's bottom, below its top.
    #[schemars(extend("unit" = "m", "label" = "interval bottom"))]
    pub bottom_md: f64,
    /// Static friction factor in the interval, >= 0.
    #[serde(rename = "static")]
    #[schemars(extend("unit" = "", "label" = "static friction factor"))]
    pub static_coefficient: f64,
}

impl Default for Friction {
    /// Aarsnes & Shor (2018), MAIN.m: `mu = 0.3`, `fRat = 0.65`, `oThres = 1.5`.
    fn default() -> Self {
        Friction {
            static_coefficient: 0.3,
            kinetic_ratio: 0.65,
            stick_speed: 1.5,
            model: FrictionModel::SetValued,
            regularisation_speed: 0.1,
            contact: Contact::SoftString,
            intervals: Vec::new(),
            coupling: FrictionCoupling::AxialTorsional,
        }
    }
}

impl DrillConfig {
    /// `friction.intervals`: each interval's depths and factor.
    pub(super) fn validate_friction_intervals(&self) -> Result<()> {
        for (j, iv) in self.friction.intervals.iter().enumerate() {
            let f = |k: &str| format!("friction.intervals[{j}].{k}");
            nonneg(f("top_md"), iv.top_md, "m")?;
            if !(iv.bottom_md.is_finite() && iv.bottom_md > iv.top_md) {
                return Err(Error::invalid(
                    f("bottom_md"),
                    Num(iv.bottom_md),
                    format!("a finite depth > top_md = {} m", Num(iv.top_md)),
                ));
            }
            nonneg(f("static"), iv.static_coefficient, "-")?;
        }
        Ok(())
    }

    /// `friction`: the factors and speeds.
    pub(super) fn validate_friction(&self) -> Result<()> {
        let fr = &self.friction;
        nonneg("friction.static", fr.static_coefficient, "-")?;
        within("friction.kinetic_ratio", fr.kinetic_ratio, 0.0, 1.0, "-")?;
        nonneg("friction.stick_speed", fr.stick_speed, "rad/s")?;
        pos("friction.regularisation_speed", fr.regularisation_speed, "rad/s")?;
        Ok(())
    }
}
