//! The systems the integrators advance.
//!
//! Every integrator is generic over [`OdeSystem`], a first-order system
//! `y' = f(t, y)`. Mechanical models (the modal Galerkin system, the finite-difference
//! PDE) are naturally second order, `q'' = a(t, q, q')`; they implement
//! [`SecondOrderSystem`] and are turned into a first-order system with state
//! `y = [q, q']` by [`FirstOrder`].
//!
//! A second-order system says whether its forces depend on the velocity
//! ([`SecondOrderSystem::velocity_dependent`]). Those that do not (the undamped models)
//! are advanced through `a(q)` alone, which the Runge-Kutta-Nystrom form, velocity Verlet
//! and central differences need; those that do (viscous damping) go through the
//! first-order form of `a(t, q, v)`, with the energy they dissipate integrated alongside
//! ([`Dissipating`]).

/// A first-order system of ordinary differential equations `y' = f(t, y)`.
///
/// `rhs` must not allocate: it is called in the integrators' inner loop.
pub trait OdeSystem {
    /// Length of the state vector `y`.
    fn dim(&self) -> usize;
    /// Writes `f(t, y)` into `dydt` (both of length [`OdeSystem::dim`]).
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]);
}

/// A second-order system `q'' = a(t, q, v)` (`v = q'`) with `dof` coordinates, split into
/// the conservative part `a(q)` ([`SecondOrderSystem::acceleration`]) and, when
/// [`SecondOrderSystem::velocity_dependent`] is true, the rest.
pub trait SecondOrderSystem {
    /// Number of generalised coordinates `q`.
    fn dof(&self) -> usize;
    /// Writes the accelerations of the forces that depend on `q` only, `a(q)`, into `acc`
    /// (both of length [`SecondOrderSystem::dof`]). For a system that is not
    /// [`SecondOrderSystem::velocity_dependent`] this is the whole acceleration.
    fn acceleration(&self, q: &[f64], acc: &mut [f64]);
    /// Whether the accelerations depend on `v` (or `t`): then only the integrators that
    /// evaluate [`SecondOrderSystem::acceleration_full`] apply. `false` by default.
    fn velocity_dependent(&self) -> bool {
        false
    }
    /// Writes the whole acceleration `a(t, q, v)` into `acc`. By default
    /// [`SecondOrderSystem::acceleration`] (bit-identical: a system that is not
    /// velocity-dependent must not override it).
    #[inline]
    fn acceleration_full(&self, _t: f64, q: &[f64], _v: &[f64], acc: &mut [f64]) {
        self.acceleration(q, acc);
    }
    /// The power the velocity-dependent forces take out of the system at `(q, v)`, in the
    /// units of the system's energy per unit time (`>= 0` for dissipation); 0 by default.
    fn dissipated_power(&self, _q: &[f64], _v: &[f64]) -> f64 {
        0.0
    }
}

/// The first-order form `y = [q, q']`, `y' = [q', a(t, q, q')]` of a [`SecondOrderSystem`].
#[derive(Debug, Clone, Copy)]
pub struct FirstOrder<'a, S: ?Sized>(pub &'a S);

impl<S: SecondOrderSystem + ?Sized> OdeSystem for FirstOrder<'_, S> {
    fn dim(&self) -> usize {
        2 * self.0.dof()
    }

    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.0.dof();
        let (q, v) = y.split_at(n);
        let (dq, dv) = dydt.split_at_mut(n);
        dq.copy_from_slice(v);
        self.0.acceleration_full(t, q, v, dv);
    }
}

/// The first-order form of a [`SecondOrderSystem`] with the dissipated energy appended:
/// `y = [q, q', D]`, `y' = [q', a(t, q, q'), P(q, q')]` with `P` the
/// [`SecondOrderSystem::dissipated_power`], so that `D(t)` is the energy the
/// velocity-dependent forces took out since the start, integrated with the state by the
/// same method and error control (the balance `H(t) + D(t) = H(0)` then closes to the
/// solve's tolerance).
#[derive(Debug, Clone, Copy)]
pub struct Dissipating<'a, S: ?Sized>(pub &'a S);

impl<S: SecondOrderSystem + ?Sized> OdeSystem for Dissipating<'_, S> {
    fn dim(&self) -> usize {
        2 * self.0.dof() + 1
    }

    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.0.dof();
        let (q, rest) = y.split_at(n);
        let v = &rest[..n];
        let (dq, rest) = dydt.split_at_mut(n);
        let (dv, dd) = rest.split_at_mut(n);
        dq.copy_from_slice(v);
        self.0.acceleration_full(t, q, v, dv);
        dd[0] = self.0.dissipated_power(q, v);
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
