//! Parameter sweeps: many runs of one Galerkin basis solved in parallel.
//!
//! * [`GalerkinIntegrals`]: the dimensionless quartic integrals of the basis, generated
//!   once per sweep and scaled to each run's [`crate::modal::ModalSystem`] (a few
//!   multiplications per term);
//! * [`batch_solve`]: solves a slice of [`RunSpec`]s on a rayon pool, one [`RunRecord`]
//!   per run in input order (status, message, metrics of [`crate::metrics`], work counters);
//!   an invalid spec or a failed solve is a record, never an error of the batch.

pub mod batch;
pub mod integrals;

pub use batch::{
    batch_solve, batch_solve_with, resolve_threads, RunRecord, RunSamples, RunSpec, RunStatus, SweepOptions,
    MAX_THREADS,
};
pub use integrals::{discretise_spectral, mode_shape, mode_slope, GalerkinIntegrals};

#[cfg(test)]
mod tests;
