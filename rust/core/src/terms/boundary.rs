//! Boundary conditions at the ends `z = 0` and `z = l`, one piece each discretisation asks for.
//!
//! Today the string has free ends (eq. 14). A new boundary (a fixed top, a bit with inertia or
//! friction) is a variant here; each discretisation then handles it where it matches on the
//! boundary: the basis of the Galerkin integrals ([`crate::galerkin::integrals`], which refuses
//! what it cannot build) and the end nodes of the finite differences
//! ([`crate::pde::PdeSystem::discretise`] and its sweep).

/// The boundary conditions of the torsion PDE.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Boundary {
    /// Free ends, `th_z(0, t) = th_z(l, t) = 0` (eq. 14): no torque at either end. The
    /// Galerkin basis is `cos(i pi z / l)`; the finite differences have natural ends (the
    /// cells beyond the ends are missing, no ghost nodes).
    #[default]
    Free,
}

impl Boundary {
    /// `"free"`.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::Free => "free",
        }
    }
}
