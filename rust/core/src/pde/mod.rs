//! Method of lines for the torsion PDE (paper eq. 18), energy-conserving in space.
//!
//! ```text
//! k1 th_tt = k2 th_zz - k3 th^3 + k4 (th^2 th_zz + th th_z^2) + k5 (th_z^3)_z + k6 th,
//! th_z(0, t) = th_z(l, t) = 0,
//! ```
//!
//! is the Euler-Lagrange equation of
//!
//! ```text
//! H = int_0^l [k1/2 th_t^2 + k2/2 th_z^2 + k3/4 th^4 + k4/2 th^2 th_z^2 + k5/4 th_z^4 - k6/2 th^2] dz.
//! ```
//!
//! [`PdeSystem`] discretises `H` rather than the equation, on `N >= 3` nodes
//! `z_j = j h`, `h = l / (N - 1)` (both ends included), with trapezoid node weights
//! `w_0 = w_{N-1} = h/2`, `w_j = h` otherwise, and cell gradients
//! `g_c = (th_{c+1} - th_c) / h` on the `N - 1` cells:
//!
//! ```text
//! H_h = sum_j w_j [k1/2 v_j^2 + k3/4 th_j^4 - k6/2 th_j^2]
//!     + sum_c h [k2/2 g_c^2 + k4/4 (th_c^2 + th_{c+1}^2) g_c^2 + k5/4 g_c^4].
//! ```
//!
//! The semi-discrete equations of motion are the discrete Euler-Lagrange equations
//! `w_j k1 th_j'' = -dV_h/dth_j` (`V_h` = `H_h` without the kinetic term). With the cell
//! flux `F_c = k2 g_c + k4/2 (th_c^2 + th_{c+1}^2) g_c + k5 g_c^3`, and since
//! `dg_c/dth_c = -1/h`, `dg_c/dth_{c+1} = 1/h`,
//!
//! ```text
//! dV_h/dth_j = w_j (k3 th_j^3 - k6 th_j) + F_{j-1} - F_j + h k4/2 th_j (g_{j-1}^2 + g_j^2)
//! ```
//!
//! where the terms of a cell that does not exist (`j - 1 < 0`, `j > N - 2`) are dropped.
//! That drop *is* the Neumann condition `th_z = 0` (natural boundary condition: no ghost
//! nodes). This is the lumped-mass linear finite-element scheme, second order in `h`; the
//! semi-discrete system is Hamiltonian, so `H_h` ([`PdeSystem::energy`]) is conserved
//! exactly by the ODE and up to the time integrator's error by a solve (boundedly so by
//! the symplectic [`crate::integrators::verlet`]).
//!
//! Viscous damping ([`PdeSystem::with_damping`]) adds `-k1 c th_t` per unit length, lumped like
//! the inertia: `q_j'' = -(dV_h/dth_j) / (w_j k1) - c v_j`, dissipating `c sum_j w_j k1 v_j^2`,
//! so `H_h + dissipated` is conserved (see [`crate::system::Dissipating`]).
//!
//! The system is built from the model's terms ([`PdeSystem::discretise`] of a
//! [`crate::terms::ModelTerms`]): each conservative term `weight th^p th_z^r` contributes the
//! cell energy `h weight (a^p + b^p) / 2 g^r` (for `r = 0` the trapezoid nodal term above, for
//! `p = 0` the cell term, for `p = r = 2` the `k4` term), and its coefficient is collected into
//! the fused kernel once, at construction. The free ends ([`crate::terms::Boundary::Free`]) are
//! the natural ends of the sweep.
//!
//! A solve is just [`crate::integrators::solve_second_order`] on a [`PdeSystem`] with the
//! nodal values `q = th(z_j)` and `v = th_t(z_j)` as state: any method, and memory that
//! grows only with the saved samples. Explicit methods are stable for steps up to about
//! `h / c` (Verlet: `dt < 2 / w_max` with `w_max ~ 2 c / h`, `c = sqrt(k2 / k1)` the
//! torsional wave speed); their default step is half of it ([`PdeSystem::default_dt`]), and the
//! default output times resolve the highest cosine mode of the initial state
//! ([`PdeSystem::fastest_mode`]).

mod defaults;
mod discretisation;
mod eigen;

pub use defaults::{CFL_SHARE, MIN_RESOLVED_MODES, MODE_CONTENT_SHARE};
pub use discretisation::{PdeCoefficients, PdeSystem, MAX_NODES};

#[cfg(test)]
mod tests;
