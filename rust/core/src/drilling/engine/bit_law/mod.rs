//! The bit law: one interface, [`BitRock`], for every law at the bit, and the laws registered
//! ([`Law`], selected by `bit.law`).
//!
//! Every end of the string is a (set-valued) law between the end's speed `w'` and the load it
//! takes, meeting the end's momentum balance with the arriving characteristic folded in,
//! [`EndLine`]: `(I / dt + Z) w' = I w / dt + Z alpha - load`. A bit law takes the torsional
//! field's line (the BHA inertia `bit.bha_inertia` folded in) and the bit's speed at the step
//! start ([`BitEnds`]) and returns the bit's speeds, loads and phase for the step
//! ([`BitContact`]). What a law needs from the axial field it declares itself,
//! [`BitRock::AXIAL`]:
//!
//! * [`AxialNeed::None`]: a law of the torsional field alone, with the weight on bit of the
//!   configuration (`bit.weight_on_bit`; a run without `[hoist]`);
//! * [`AxialNeed::DepthOfCut`]: a law meeting the axial field's end too, at the depth of cut per
//!   revolution of the step ([`AxialEnd`]; a coupled run, `[hoist]`). The run finds the depth
//!   ([`crate::drilling::engine::axial_field`]: the rate form `2 pi v' / omega`, implicit in the axial
//!   speed, or the regenerative cut surface) by calling the law at trial depths, sets both
//!   fields' bottom ghosts from the contact and books `dt (W v' + T w')` as the bit's work.
//!
//! The phases are set-valued: contact (cutting and frictional contact), torsional stick
//! (`w' = 0`, the torque that holds the bit within the static limit) and lift-off (`W = 0`,
//! `T = 0`, the bit free on both lines).
//!
//! The configuration's check asks [`axial_need`] whether `bit.law` needs a `[hoist]`; the run
//! builds the law with [`Law::new`]. A new law is one file implementing [`BitRock`] and its
//! registration here: a variant of [`Law`], its line in [`Law::new`], [`axial_need`] and
//! [`validate`], and its `bit.law` name in `config.rs` ([`BitRockLaw`]) with its keys.
//! The dispatch is a `match` once per step, outside every cell loop.

use crate::drilling::axial::bit_boundary::{BitContact, Port};
use crate::drilling::axial::bitrock::{DetournayBit, SteadyDrilling};
use crate::drilling::bit::VelocityWeakening;
use crate::drilling::config::{BitRockLaw, DrillConfig};
use crate::drilling::engine::boundary::EndLine;
use crate::error::Result;

pub mod weakening;

use weakening::DetournayWeakening;

/// What a bit law needs from the axial field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxialNeed {
    /// Nothing: the torsional field alone (a run without `[hoist]`).
    None,
    /// The axial field's end and the depth of cut per revolution (a coupled run, `[hoist]`).
    DepthOfCut,
}

/// The axial field's end at the bit and the depth of cut per revolution of the step, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialEnd {
    pub port: Port,
    pub depth: f64,
}

/// What a law meets at the bit in a step.
#[derive(Debug, Clone, Copy)]
pub struct BitEnds {
    /// The torsional field's end: the line of the BHA's momentum balance.
    pub torsion: EndLine,
    /// The bit's angular speed at the step start, rad/s.
    pub omega: f64,
    /// The axial end, given to a law of [`AxialNeed::DepthOfCut`] (None in a torsion-only run).
    pub axial: Option<AxialEnd>,
}

/// A bit-rock law: the bit's speeds, weight, torque and phase for a step.
pub trait BitRock {
    /// What the law needs from the axial field.
    const AXIAL: AxialNeed;

    /// The bit's new speeds and loads on the ends `ends` (set-valued phases, see the module).
    fn resolve(&self, ends: &BitEnds) -> BitContact;

    /// A depth-of-cut law's steady drilling at the rate of penetration `rop` (m/s) and the
    /// rotary speed `omega` (rad/s), and the contact of the bit in it (a run started in steady
    /// drilling, `numerics.initial_state = "steady"`); None for a law without one.
    fn steady(&self, _rop: f64, _omega: f64) -> Option<(SteadyDrilling, BitContact)> {
        None
    }
}

/// The laws registered (`bit.law`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// No torque: off bottom, or the velocity-weakening law without weight on bit.
    Free,
    /// `velocity_weakening` ([`crate::drilling::bit`]).
    VelocityWeakening(VelocityWeakening),
    /// `detournay` and `rgd` ([`crate::drilling::axial::bitrock`]).
    Detournay(DetournayBit),
    /// `detournay_weakening` ([`weakening`]).
    DetournayWeakening(DetournayWeakening),
}

/// Whether the law `law` needs the axial field of a coupled run (`[hoist]`), as the law
/// declares ([`BitRock::AXIAL`]).
pub fn axial_need(law: BitRockLaw) -> AxialNeed {
    match law {
        BitRockLaw::VelocityWeakening => VelocityWeakening::AXIAL,
        BitRockLaw::Detournay | BitRockLaw::Rgd => DetournayBit::AXIAL,
        BitRockLaw::DetournayWeakening => DetournayWeakening::AXIAL,
    }
}

/// Checks the keys of the configuration's law (`bit.law`), naming the field.
pub fn validate(cfg: &DrillConfig) -> Result<()> {
    match cfg.bit.law {
        BitRockLaw::VelocityWeakening => Ok(()),
        BitRockLaw::Detournay | BitRockLaw::Rgd => cfg.bit.detournay.law(cfg.bit.radius).validate("bit.detournay"),
        BitRockLaw::DetournayWeakening => {
            cfg.bit.detournay.law(cfg.bit.radius).validate("bit.detournay")?;
            cfg.bit.weakening.validate(cfg.bit.detournay.friction)
        }
    }
}

impl Law {
    /// The law of a configuration's bit.
    pub fn new(cfg: &DrillConfig) -> Law {
        let b = &cfg.bit;
        match b.law {
            BitRockLaw::VelocityWeakening if b.on_bottom && b.weight_on_bit > 0.0 => {
                Law::VelocityWeakening(VelocityWeakening {
                    weight_radius: b.weight_on_bit * b.radius,
                    mu_static: b.mu_static,
                    mu_kinetic: b.mu_kinetic,
                    decay: b.decay,
                    stick_speed: b.stick_speed,
                })
            }
            BitRockLaw::VelocityWeakening => Law::Free,
            BitRockLaw::Detournay | BitRockLaw::Rgd => Law::Detournay(b.detournay.law(b.radius)),
            BitRockLaw::DetournayWeakening => {
                Law::DetournayWeakening(DetournayWeakening { cut: b.detournay.law(b.radius), weakening: b.weakening })
            }
        }
    }

    /// What the law needs from the axial field.
    pub fn axial(&self) -> AxialNeed {
        match self {
            Law::Free => AxialNeed::None,
            Law::VelocityWeakening(_) => VelocityWeakening::AXIAL,
            Law::Detournay(_) => DetournayBit::AXIAL,
            Law::DetournayWeakening(_) => DetournayWeakening::AXIAL,
        }
    }

    /// [`BitRock::resolve`] of the law.
    #[inline]
    pub fn resolve(&self, ends: &BitEnds) -> BitContact {
        match self {
            Law::Free => BitContact::torsional(
                ends.torsion.drive / ends.torsion.denom,
                0.0,
                crate::drilling::axial::bit_boundary::BitPhase::LiftOff,
            ),
            Law::VelocityWeakening(l) => l.resolve(ends),
            Law::Detournay(l) => l.resolve(ends),
            Law::DetournayWeakening(l) => l.resolve(ends),
        }
    }

    /// [`BitRock::steady`] of the law.
    pub fn steady(&self, rop: f64, omega: f64) -> Option<(SteadyDrilling, BitContact)> {
        match self {
            Law::Free => None,
            Law::VelocityWeakening(l) => l.steady(rop, omega),
            Law::Detournay(l) => l.steady(rop, omega),
            Law::DetournayWeakening(l) => l.steady(rop, omega),
        }
    }

    /// A depth-of-cut law's cutting and contact geometry (blades, radius, the wear flats'
    /// weight; the weight of steady drilling at a depth of cut), None for a torsion-only law.
    pub fn cutting(&self) -> Option<&DetournayBit> {
        match self {
            Law::Free | Law::VelocityWeakening(_) => None,
            Law::Detournay(l) => Some(l),
            Law::DetournayWeakening(l) => Some(&l.cut),
        }
    }
}
