//! The bit (`[bit]`): size, the velocity-weakening law, the Detournay law, the BHA.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::metrics::STICK_SPEED;

use super::super::axial::bitrock::DetournayBit;
pub use super::super::engine::bit_law::weakening::Weakening;
use super::{bit_size_conflict, nonneg, pos, within, DrillConfig};

/// The bit: off bottom (free end or a lumped BHA inertia) or on bottom (Navarro-Lopez torque).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Bit {
    /// Whether the bit cuts (on bottom, the bit-rock torque) or hangs free.
    #[schemars(extend("label" = "bit on bottom"))]
    pub on_bottom: bool,
    /// Weight on bit `W`, >= 0.
    #[schemars(extend("unit" = "N", "label" = "weight on bit"))]
    pub weight_on_bit: f64,
    /// Bit radius `r`, > 0 (or give `diameter`, not both).
    #[schemars(extend("unit" = "m", "label" = "bit radius"))]
    pub radius: f64,
    /// Bit diameter, > 0, in place of `radius` (not both). Null: `radius` gives the bit.
    #[schemars(extend("unit" = "m", "label" = "bit diameter"))]
    pub diameter: Option<f64>,
    /// Static bit-rock friction coefficient `mu_s`, >= 0.
    #[schemars(extend("unit" = "", "label" = "static bit friction"))]
    pub mu_static: f64,
    /// Kinetic bit-rock friction coefficient `mu_k`, from 0 to `mu_static`.
    #[schemars(extend("unit" = "", "label" = "kinetic bit friction"))]
    pub mu_kinetic: f64,
    /// Velocity-weakening rate of `T = W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)`, >= 0.
    #[schemars(extend("unit" = "s/rad", "label" = "velocity-weakening rate"))]
    pub decay: f64,
    /// Below this speed the bit sticks while the holding torque is within `W r mu_s`; >= 0.
    #[schemars(extend("unit" = "rad/s", "label" = "bit stick speed"))]
    pub stick_speed: f64,
    /// Lumped inertia at the bit, >= 0 (0: none).
    #[schemars(extend("unit" = "kg*m^2", "label" = "BHA inertia"))]
    pub bha_inertia: f64,
    /// The bit-rock law: `velocity_weakening` (default: the torque `W r mu(|w|)` with the weight
    /// on bit `weight_on_bit`, torsion only), `detournay` (the Detournay cutting + contact law of
    /// `bit.detournay` with the depth of cut per revolution `2 pi v / omega` of the bit's speeds)
    /// or `rgd` (the same law with the regenerative depth of cut, the bit's position one blade
    /// pass back), or `detournay_weakening` (the `detournay` law with the wear flats' friction
    /// falling with the bit's speed, `bit.weakening`). The laws but `velocity_weakening` need a
    /// `[hoist]` table and the reverse.
    #[schemars(extend("label" = "bit-rock law"))]
    pub law: BitRockLaw,
    #[schemars(extend("label" = "Detournay bit law"))]
    pub detournay: Detournay,
    #[schemars(extend("label" = "wear-flat friction weakening"))]
    pub weakening: Weakening,
    /// Lumped mass at the bit on the axial field of a coupled run (`[hoist]`), >= 0 (0: none,
    /// the string's end alone): its inertia and its buoyed weight along the hole (the density of
    /// the last section), which the string carries in the initial static tension.
    #[schemars(extend("unit" = "kg", "label" = "BHA mass"))]
    pub bha_mass: f64,
}

/// The bit-rock law of the bit (`bit.law`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BitRockLaw {
    /// The Navarro-Lopez velocity-weakening torque at the weight on bit `bit.weight_on_bit`.
    VelocityWeakening,
    /// The Detournay law with the depth of cut from the bit's axial and angular speed.
    Detournay,
    /// The Detournay law with the regenerative depth of cut (Richard, Germay & Detournay 2007).
    Rgd,
    /// The Detournay law (rate form) with the wear flats' friction falling with the bit's speed.
    DetournayWeakening,
}

impl BitRockLaw {
    /// The law's name in the configuration (`bit.law`).
    pub fn name(self) -> String {
        serde_json::to_value(self).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default()
    }
}

/// The Detournay cutting + frictional-contact law (`bit.law` `detournay` or `rgd`; Richard,
/// Germay & Detournay 2007) with the bit radius `bit.radius`: cutting `W_c = a zeta eps d`,
/// `T_c = a^2 eps d / 2`, contact `W_f <= a l sigma`, `T_f = gamma mu a W_f / 2` (`d` the depth
/// of cut per revolution). Defaults: Aarsnes & van de Wouw (2019).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Detournay {
    /// Number of blades `n`, >= 1.
    #[schemars(extend("unit" = "", "label" = "blades"))]
    pub blades: u32,
    /// Intrinsic specific energy of the rock `eps`, > 0: the cutting energy per volume.
    #[schemars(extend("unit" = "Pa", "label" = "intrinsic specific energy"))]
    pub intrinsic_specific_energy: f64,
    /// Ratio `zeta` of the vertical to the horizontal cutting force, >= 0.
    #[schemars(extend("unit" = "", "label" = "cutting force ratio"))]
    pub cutting_ratio: f64,
    /// Contact strength `sigma` under the wear flats, >= 0.
    #[schemars(extend("unit" = "Pa", "label" = "contact strength"))]
    pub contact_strength: f64,
    /// Total wear-flat length `l` (sum over the blades), >= 0.
    #[schemars(extend("unit" = "m", "label" = "wear-flat length"))]
    pub wear_flat_length: f64,
    /// Friction coefficient `mu` at the wear-flat/rock contact, >= 0.
    #[schemars(extend("unit" = "", "label" = "wear-flat friction"))]
    pub friction: f64,
    /// Bit geometry factor `gamma` (1 for a flat bit profile), >= 0.
    #[schemars(extend("unit" = "", "label" = "bit geometry factor"))]
    pub geometry: f64,
    /// The regenerative depth of cut of `bit.law = "rgd"`: `exact_delay` (default: the bit's
    /// position one blade angle back, interpolated exactly) or `upwind` (Aarsnes & van de Wouw's
    /// cut surface, first-order upwind on `cut_surface_cells` cells; diffusive).
    ///
    /// The upwind surface converges to the exact delay at first order in the cells; on their 169
    /// cells at 30 rpm its diffusion damps the regenerative instability (see the drilling guide).
    #[schemars(extend("label" = "cut surface"))]
    pub cut_surface: CutSurfaceScheme,
    /// Cells of the `upwind` cut surface over one blade angle, 1 to 1000000 (their code: 169, 84,
    /// 42 at 30, 60, 120 rpm); unused with `exact_delay`.
    #[schemars(extend("unit" = "", "label" = "cut-surface cells"))]
    pub cut_surface_cells: u32,
}

/// The regenerative depth of cut's numerics (`bit.detournay.cut_surface`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CutSurfaceScheme {
    /// The exact delay: the recorded bit position one blade angle back, interpolated.
    ExactDelay,
    /// First-order upwind transport of the depth of cut on `cut_surface_cells` cells.
    Upwind,
}

/// The most cells of an upwind cut surface (`bit.detournay.cut_surface_cells`).
pub const MAX_CUT_SURFACE_CELLS: u32 = 1_000_000;

impl Default for Detournay {
    fn default() -> Self {
        Detournay::PUBLISHED
    }
}

impl Detournay {
    /// The dimensional case of Aarsnes & van de Wouw (2019), `Coupled/parameters.m` (their
    /// `gamma = 1`; their code's contact torque is that of `geometry = 2` here, see
    /// [`crate::drilling::axial::bitrock`]), with the exact-delay cut surface.
    pub const PUBLISHED: Detournay = Detournay {
        blades: 4,
        intrinsic_specific_energy: 60e6,
        cutting_ratio: 0.6,
        contact_strength: 60e6,
        wear_flat_length: 11e-3,
        friction: 0.6,
        geometry: 1.0,
        cut_surface: CutSurfaceScheme::ExactDelay,
        cut_surface_cells: 169,
    };

    /// The law with the bit radius `radius`.
    pub fn law(&self, radius: f64) -> DetournayBit {
        DetournayBit { radius, detournay: *self }
    }
}

impl Default for Bit {
    fn default() -> Self {
        Bit {
            on_bottom: false,
            weight_on_bit: 0.0,
            radius: 0.1,
            diameter: None,
            mu_static: 0.8,
            mu_kinetic: 0.5,
            decay: 1.0,
            stick_speed: STICK_SPEED,
            bha_inertia: 0.0,
            law: BitRockLaw::VelocityWeakening,
            detournay: Detournay::default(),
            weakening: Weakening::default(),
            bha_mass: 0.0,
        }
    }
}

impl DrillConfig {
    /// `bit`: weight, size, friction, BHA.
    pub(super) fn validate_bit(&self) -> Result<()> {
        let b = &self.bit;
        nonneg("bit.weight_on_bit", b.weight_on_bit, "N")?;
        pos("bit.radius", b.radius, "m")?;
        if let Some(d) = b.diameter {
            pos("bit.diameter", d, "m, or null to give bit.radius")?;
            if b.radius != d / 2.0 {
                return Err(bit_size_conflict());
            }
        }
        nonneg("bit.mu_static", b.mu_static, "-")?;
        within("bit.mu_kinetic", b.mu_kinetic, 0.0, b.mu_static, "-, at most bit.mu_static")?;
        nonneg("bit.decay", b.decay, "s/rad")?;
        nonneg("bit.stick_speed", b.stick_speed, "rad/s")?;
        nonneg("bit.bha_inertia", b.bha_inertia, "kg m^2")?;
        nonneg("bit.bha_mass", b.bha_mass, "kg")?;
        Ok(())
    }
}
