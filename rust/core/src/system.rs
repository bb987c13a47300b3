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
//!
//! A system with an energy of its state implements [`Energy`]; [`energy_history`] and
//! [`potential_history`] evaluate it at every sample of a run.

use crate::error::{Error, Result};

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

/// `dq = v` in the first-order forms below: copies of constant length for up to four
/// coordinates, moved in registers (a copy of run-time length calls `memmove`, measured at
/// about a tenth of the 3-mode DOP853 steps, and its stores are not those the next loads of
/// the state expect).
#[inline(always)]
fn copy_velocity(dq: &mut [f64], v: &[f64]) {
    match v.len() {
        1 => dq[..1].copy_from_slice(&v[..1]),
        2 => dq[..2].copy_from_slice(&v[..2]),
        3 => dq[..3].copy_from_slice(&v[..3]),
        4 => dq[..4].copy_from_slice(&v[..4]),
        _ => dq.copy_from_slice(v),
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
        copy_velocity(dq, v);
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
        copy_velocity(dq, v);
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

/// A [`SecondOrderSystem`] with an energy `H(q, v)` of its state and its potential part `V(q)`.
pub trait Energy: SecondOrderSystem {
    /// The energy `H(q, v)` of one state (`q`, `v` of length [`SecondOrderSystem::dof`]).
    fn energy(&self, q: &[f64], v: &[f64]) -> f64;
    /// The potential `V(q)` of one configuration: the part of [`Energy::energy`] that is
    /// neither kinetic nor quadratic in `q` where the system says so (see its docs).
    fn potential(&self, q: &[f64]) -> f64;
}

/// The samples of row-major `(dof, samples)` arrays: `samples`, or an error naming `q` unless
/// every array holds `dof * samples` values.
fn sample_count(dof: usize, arrays: &[&[f64]]) -> Result<usize> {
    let len = arrays[0].len();
    let ok = arrays.iter().all(|a| a.len() == len) && if dof == 0 { len == 0 } else { len % dof == 0 };
    if !ok {
        let lens: Vec<String> = arrays.iter().map(|a| a.len().to_string()).collect();
        return Err(Error::invalid(
            "q",
            format!("{} values", lens.join(" and ")),
            format!("arrays of equal shape ({dof}, samples)"),
        ));
    }
    Ok(len.checked_div(dof).unwrap_or(0))
}

/// Calls `f` with each sample (column) of the row-major `(dof, samples)` arrays gathered into
/// contiguous states.
fn per_sample<const N: usize>(
    dof: usize,
    arrays: [&[f64]; N],
    mut f: impl FnMut([&[f64]; N]) -> f64,
) -> Result<Vec<f64>> {
    let samples = sample_count(dof, &arrays)?;
    let mut states = [(); N].map(|_| vec![0.0; dof]);
    let mut out = Vec::with_capacity(samples);
    for k in 0..samples {
        for (state, array) in states.iter_mut().zip(&arrays) {
            for (i, x) in state.iter_mut().enumerate() {
                *x = array[i * samples + k];
            }
        }
        let mut views: [&[f64]; N] = [&[]; N];
        for (view, state) in views.iter_mut().zip(&states) {
            *view = state;
        }
        out.push(f(views));
    }
    Ok(out)
}

/// [`Energy::energy`] of `sys` at every sample: `q` and `v` row-major `(dof, samples)` (one row
/// per coordinate). An error naming `q` unless both hold `dof * samples` values.
pub fn energy_history<S: Energy + ?Sized>(sys: &S, q: &[f64], v: &[f64]) -> Result<Vec<f64>> {
    per_sample(sys.dof(), [q, v], |[q, v]| sys.energy(q, v))
}

/// [`Energy::potential`] of `sys` at every sample of the row-major `(dof, samples)` `q`.
pub fn potential_history<S: Energy + ?Sized>(sys: &S, q: &[f64]) -> Result<Vec<f64>> {
    per_sample(sys.dof(), [q], |[q]| sys.potential(q))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `q'' = -q` with `H = (v^2 + q^2) / 2 + q^4` per coordinate.
    struct Toy(usize);

    impl SecondOrderSystem for Toy {
        fn dof(&self) -> usize {
            self.0
        }
        fn acceleration(&self, q: &[f64], acc: &mut [f64]) {
            for (a, &x) in acc.iter_mut().zip(q) {
                *a = -x;
            }
        }
    }

    impl Energy for Toy {
        fn energy(&self, q: &[f64], v: &[f64]) -> f64 {
            q.iter().zip(v).map(|(&q, &v)| 0.5 * (v * v + q * q)).sum::<f64>() + self.potential(q)
        }
        fn potential(&self, q: &[f64]) -> f64 {
            q.iter().map(|&q| q.powi(4)).sum()
        }
    }

    #[test]
    fn histories_gather_the_columns() {
        // two coordinates, three samples, row-major
        let q = [1.0, 0.0, 2.0, 0.0, 1.0, 1.0];
        let v = [0.0, 2.0, 0.0, 1.0, 0.0, 1.0];
        let sys = Toy(2);
        let e = energy_history(&sys, &q, &v).unwrap();
        for k in 0..3 {
            assert_eq!(e[k], sys.energy(&[q[k], q[3 + k]], &[v[k], v[3 + k]]));
        }
        assert_eq!(e, vec![2.0, 3.5, 20.0]);
        assert_eq!(potential_history(&sys, &q).unwrap(), vec![1.0, 1.0, 17.0]);
        assert!(energy_history(&sys, &[], &[]).unwrap().is_empty());
    }

    #[test]
    fn histories_reject_bad_shapes() {
        let sys = Toy(2);
        assert_eq!(energy_history(&sys, &[1.0; 3], &[1.0; 3]).unwrap_err().field(), "q");
        assert_eq!(energy_history(&sys, &[1.0; 4], &[1.0; 2]).unwrap_err().field(), "q");
        assert_eq!(potential_history(&sys, &[1.0]).unwrap_err().field(), "q");
        assert_eq!(potential_history(&Toy(0), &[1.0]).unwrap_err().field(), "q");
    }
}
