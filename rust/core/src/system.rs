//! The systems the integrators advance.
//!
//! Every integrator is generic over [`OdeSystem`], a first-order system
//! `y' = f(t, y)`. Mechanical models (the modal Galerkin system, later the
//! finite-difference PDE) are naturally second order, `q'' = a(q)`; they implement
//! [`SecondOrderSystem`] and are turned into a first-order system with state
//! `y = [q, q']` by [`FirstOrder`].

/// A first-order system of ordinary differential equations `y' = f(t, y)`.
///
/// `rhs` must not allocate: it is called in the integrators' inner loop.
pub trait OdeSystem {
    /// Length of the state vector `y`.
    fn dim(&self) -> usize;
    /// Writes `f(t, y)` into `dydt` (both of length [`OdeSystem::dim`]).
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]);
}

/// An autonomous second-order system `q'' = a(q)` with `dof` coordinates.
pub trait SecondOrderSystem {
    /// Number of generalised coordinates `q`.
    fn dof(&self) -> usize;
    /// Writes the accelerations `a(q)` into `acc` (both of length [`SecondOrderSystem::dof`]).
    fn acceleration(&self, q: &[f64], acc: &mut [f64]);
}

/// The first-order form `y = [q, q']`, `y' = [q', a(q)]` of a [`SecondOrderSystem`].
#[derive(Debug, Clone, Copy)]
pub struct FirstOrder<'a, S: ?Sized>(pub &'a S);

impl<S: SecondOrderSystem + ?Sized> OdeSystem for FirstOrder<'_, S> {
    fn dim(&self) -> usize {
        2 * self.0.dof()
    }

    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.0.dof();
        let (q, v) = y.split_at(n);
        let (dq, dv) = dydt.split_at_mut(n);
        dq.copy_from_slice(v);
        self.0.acceleration(q, dv);
    }
}

impl<S: OdeSystem + ?Sized> OdeSystem for &S {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        (**self).rhs(t, y, dydt)
    }
}
