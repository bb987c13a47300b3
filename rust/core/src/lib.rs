//! drillstring-core: the numerics of drillstring.
//!
//! The model is the nonlinear torsion PDE of a rotating drill string (paper eq. 18)
//!
//! ```text
//! k1 th_tt = k2 th_zz - k3 th^3 + k4 (th^2 th_zz + th th_z^2) + k5 (th_z^3)_z + k6 th,
//! th_z(0, t) = th_z(l, t) = 0,
//! ```
//!
//! written once as composable physics terms ([`terms`]: the inertia `k1`, one energy monomial
//! per conservative term, the viscous damping, the boundary), each discretised by the
//! Bubnov-Galerkin projection on `cos(i pi z / l)` ([`galerkin`], [`sweep::GalerkinIntegrals`])
//! to the modal system `M q'' + c M q' + K q + N(q) = 0` ([`modal::ModalSystem`], `c` an
//! optional viscous damping rate, 0 for the paper's model) or by finite differences ([`pde`]),
//! and integrated by the explicit Runge-Kutta methods and the central-difference scheme in
//! [`integrators`].
//!
//! Invalid input is an [`Error`]; numerical failure (step limit, step-size underflow,
//! non-finite state) ends a solve with a [`Status`] and a message. Nothing here panics on
//! finite or non-finite numeric input. A long solve can be stopped from another thread (or a
//! signal handler's hook) through [`interrupt`]: it ends with [`Status::Interrupted`].
//!
//! The crate has no `unsafe` code (enforced below), so Miri and AddressSanitizer have nothing
//! beyond the standard library and the dependencies to check.

#![forbid(unsafe_code)]

pub mod drilling;
pub mod error;
pub mod galerkin;
pub mod integrators;
pub mod interrupt;
pub mod metrics;
pub mod modal;
pub mod model;
pub mod options;
pub mod outputs;
pub mod pde;
mod schema;
pub mod simd;
pub mod solution;
pub mod stability;
pub mod sweep;
pub mod system;
pub mod terms;
pub mod well;

pub use error::{Error, Num, Result};
pub use interrupt::{CancelFlag, Interrupt};
pub use options::{AdaptiveOptions, FixedOptions, Output};
pub use solution::{Solution, Stats, Status};
pub use system::{Dissipating, FirstOrder, OdeSystem, SecondOrderSystem};

/// Helpers of the crate's tests.
#[cfg(test)]
pub(crate) mod test_support {
    /// Deterministic pseudo-random numbers in [0, 1) (xorshift64 from `seed`, non-zero).
    pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }
}
