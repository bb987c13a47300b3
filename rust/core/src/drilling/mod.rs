//! The drilling system (issue #13): torsional stick-slip of a multi-section drill string
//! driven by a top drive, with along-string Coulomb friction and a bit on or off bottom.
//!
//! The string is the linear torsional wave equation in Riemann invariants (characteristics),
//! after Aarsnes & Shor, "Torsional vibrations with bit off bottom: Modeling, characterization
//! and field data validation", J. Pet. Sci. Eng. 163 (2018) 712-721, and their open model
//! (Open-Source-Drilling-Community/Aarsnes-and-Shor-Torsional-Model, `torsionalWaveStep.m`):
//! per section the wave speed `c = sqrt(G / rho)` and impedance `Z = J sqrt(G rho)`, one time
//! step for all sections (Courant number `<= 1`, `= 1` for a uniform string, where the upwind
//! update is exact transport), exact continuity of speed and torque at section changes, the
//! top drive an inertia driven by a controller, the bit a free end, a lumped BHA inertia or the
//! Navarro-Lopez velocity-weakening bit torque with a stick phase; soft-string Coulomb friction
//! with the set-valued stick resolution of that code (or a regularised form); viscous damping.
//! Optionally (`nonlinearity = "consistent"`) the torque-twist law is the finite-strain one of
//! [`crate::model::Model::Consistent`], advanced by a first-order Godunov scheme whose linear
//! limit is the scheme above (see [`solver`]).
//!
//! * [`config`]: [`DrillConfig`] (JSON, defaults, validation with dotted field names, limits);
//! * [`grid`]: section properties, the time step and cells, the friction limit, the string's
//!   first natural frequency, the break-off torque and the minimum cycle torque it implies;
//! * [`bit`]: the velocity-weakening bit-rock torque law (Navarro-Lopez & Cortes 2007), shared
//!   by the string's bit and the lumped model (the bit laws' interface and registry:
//!   [`engine::bit_law`]);
//! * [`engine`]: the time stepping as composable parts: the field, the transport kernel, the
//!   boundaries (top drive, bit), the sources, the controllers, the output sampler, the energy
//!   ledger and the run loop;
//! * [`solver`]: the entry points [`solve`] and [`friction_profile`], the run's warnings;
//! * [`map`]: stick-slip maps, many runs of one base configuration with per-run overrides
//!   solved in parallel, one row of metrics each ([`map::solve_map`]);
//! * [`tuning`]: the controller presets' rules (gains from the string's impedance, first mode
//!   and the top-drive inertia) and the recommendation of `drillstring tune`;
//! * [`plausibility`]: warnings (not errors) for values that are likely mistakes, a torque
//!   limit below the break-off torque, a motor at its torque limit, a transient still decaying
//!   in the metrics window and metrics that are not finite;
//! * [`start`]: where a run starts, at rest or in a coupled run's steady drilling;
//! * [`compare`]: two runs' metrics compared with the tolerances of the grid and start checks;
//! * [`limits`]: what a configuration may ask for beyond each value's range (loads within the
//!   string's buoyed weight, a hole without a reversing dogleg nor above the rig floor, the
//!   torque and drag's and the cut surface's work), checked before anything sized by it is
//!   allocated; [`effect`]: whether a key changes a run under the configuration's modes;
//! * [`lumped`]: the lumped two-inertia model of Navarro-Lopez & Cortes (2007), its solver
//!   with a true stick phase, its steady rotations and their stability.
//! * [`axial`]: the bit on bottom as parts (axial section properties and statics, the Detournay
//!   bit-rock law and MSE, the regenerative cut surface, the set-valued bit boundary, the hoist
//!   and autodriller), assembled by [`engine::axial_field`] into a coupled run (`[hoist]`).

pub mod axial;
pub mod bit;
pub mod compare;
pub mod config;
pub mod effect;
pub mod engine;
pub mod grid;
pub mod limits;
pub mod lumped;
pub mod map;
pub mod pipe;
pub mod plausibility;
pub mod schema_doc;
pub mod solver;
pub mod start;
pub mod tuning;
pub mod well;

#[cfg(test)]
mod tests;

pub use config::{
    DrillConfig, DEFAULT_TORQUE_LIMIT, MAX_CELLS, MAX_CELL_STEPS, MAX_DURATION, MAX_OUTPUT_BYTES, MAX_SECTIONS,
};
pub use grid::{breakoff_torque, min_cycle_torque, min_cycle_torque_from, Grid};
pub use solver::{
    friction_profile, solve, DrillRun, DrillStats, EnergyBalance, FrictionProfile, Simulation, RUNAWAY_FACTOR,
};
