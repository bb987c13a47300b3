//! The bit on bottom: the parts of coupled axial-torsional drilling dynamics with a depth-of-cut
//! bit-rock law, self-contained and tested, for the drilling engine to assemble (issue #30).
//!
//! * [`section`]: axial section properties (bar wave speed `sqrt(E / rho)`, impedance
//!   `A sqrt(E rho)`), the static effective tension from the buoyed weight and the weight on bit,
//!   the axial natural frequencies of a multi-section string (closed forms, transfer matrix);
//! * [`bitrock`]: the Detournay cutting + frictional-contact law (Richard, Germay & Detournay
//!   2007) with its parameters, its steady state, and the mechanical specific energy (Teale 1965);
//! * [`cut_surface`]: the regenerative depth of cut, the rock surface one blade pass back as an
//!   exactly interpolated state-dependent delay on the bit's angle (stick, reverse rotation and
//!   lift-off handled);
//! * [`bit_boundary`]: the bit as the set-valued bottom boundary of both fields (cutting, stick,
//!   lift-off) from their incoming Riemann invariants;
//! * [`hoist`]: the hoist at the top (block velocity, hook load, autodriller PI on weight on bit
//!   or rate of penetration with limits and anti-windup, weight on bit as a weight indicator's),
//!   its modes one implementation each of [`hoist_mode::HoistRule`];
//! * [`regime`]: the regime of a coupled run's window (smooth drilling, stick-slip, bit bounce,
//!   both, off bottom) from its torsional verdict and its bounce fraction.
//!
//! Units are SI throughout (m, s, N, N m, rad, rad/s, Pa); axial speeds and positions are down
//! positive.

pub mod bit_boundary;
pub mod bitrock;
pub mod cut_surface;
pub mod hoist;
pub mod hoist_mode;
pub mod regime;
pub mod section;

#[cfg(test)]
mod tests;
