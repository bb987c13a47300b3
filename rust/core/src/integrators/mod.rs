//! Time integrators: the adaptive explicit Runge-Kutta pairs DOP853 and Dormand-Prince
//! 5(4) with dense output, the adaptive Runge-Kutta-Nystrom pair RKN12(10) for
//! `q'' = a(q)`, classical RK4, central differences and velocity Verlet with fixed steps.
//!
//! Every solve validates its input first (an [`Error`] names the offending field) and
//! then never panics: numerical failure ends it with a [`crate::Status`] and the samples
//! reached so far. Adaptive steps are not tied to the output grid: [`Output::Times`] is
//! sampled through the methods' continuous extensions. Fixed-step methods use
//! `N = ceil((t_end - t0) / dt - 1e-9)` uniform steps of `(t_end - t0) / N` (the largest
//! step `<= dt` that divides the span) and cubic Hermite interpolation between them.
//!
//! Reference: E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential
//! Equations I: Nonstiff Problems*, 2nd ed., Springer 1993, sec. II.1-II.6.

mod adaptive;
mod birkhoff;
mod central;
mod dop853;
mod dopri5;
pub(crate) mod events;
mod fixed;
mod form;
mod grid;
mod hermite;
mod rk4;
mod rkn;
mod rkn12;
mod sampling;
mod tableau;
mod verlet;

use crate::error::{Error, Num, Result};
use crate::interrupt::{Interrupt, Never};
use crate::options::{AdaptiveOptions, FixedOptions, Output};
use crate::solution::Solution;
use crate::system::{Dissipating, FirstOrder, OdeSystem, SecondOrderSystem};
use form::{Nystrom, Plain};

/// DOP853 (Dormand-Prince order 8 with 5th/3rd-order error estimate and 7th-order dense
/// output), with Hairer's step-size control (`safe = 0.9`, `fac1 = 0.333`, `fac2 = 6`,
/// `beta = 0`).
pub fn dop853<S: OdeSystem + ?Sized>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
) -> Result<Solution> {
    adaptive::integrate::<dop853::Dop853, _>(&Plain(sys), t0, y0, t_end, output, opts, &Never)
}

/// Dormand-Prince 5(4) (`DOPRI5`, 4th-order dense output), with Hairer's step-size control
/// (`safe = 0.9`, `fac1 = 0.2`, `fac2 = 10`, Lund stabilisation `beta = 0.04`).
pub fn dopri5<S: OdeSystem + ?Sized>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
) -> Result<Solution> {
    adaptive::integrate::<dopri5::Dopri5, _>(&Plain(sys), t0, y0, t_end, output, opts, &Never)
}

/// RKN12(10), the 17-stage Runge-Kutta-Nystrom pair of order 12 with an order-10 error
/// estimate of Dormand, El-Mikkawy and Prince (*IMA J. Numer. Anal.* 7 (1987) 423-430), for
/// `q'' = a(q)`, with Hairer's step-size control; output times through the degree-11
/// Hermite-Birkhoff interpolant of four step ends (`q`, `v`, `a(q)` at each). The state in the
/// [`Solution`] is `[q, v]`; `Stats::nfev` counts evaluations of `a` (17 per accepted step).
/// A [`SecondOrderSystem::velocity_dependent`] system is refused (an [`Error`] naming `method`).
///
/// ```
/// use drillstring_core::integrators::rkn12;
/// use drillstring_core::modal::ModalSystem;
/// use drillstring_core::{AdaptiveOptions, Output};
///
/// // q'' = -q from (1, 0): q = cos t.
/// let sys = ModalSystem::new(vec![1.0], vec![1.0], vec![]).unwrap();
/// let opts = AdaptiveOptions { rtol: 1e-12, atol: 1e-12, ..AdaptiveOptions::default() };
/// let sol = rkn12(&sys, 0.0, &[1.0], &[0.0], 10.0, &Output::Times(vec![2.5, 10.0]), &opts).unwrap();
/// assert!((sol.state(0)[0] - 2.5_f64.cos()).abs() < 1e-11);
/// assert!((sol.state(1)[1] + 10.0_f64.sin()).abs() < 1e-11);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn rkn12<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &AdaptiveOptions,
) -> Result<Solution> {
    check_state("q0", q0, sys.dof())?;
    check_state("v0", v0, sys.dof())?;
    if sys.velocity_dependent() {
        return Err(refuse_velocity_dependent(Method::Rkn12));
    }
    rkn::integrate(&rkn12::RKN12, sys, t0, q0, v0, t_end, output, opts, &Never)
}

/// Classical fourth-order Runge-Kutta with fixed steps (see the module docs for the grid).
pub fn rk4<S: OdeSystem + ?Sized>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
) -> Result<Solution> {
    rk4::integrate(sys, t0, y0, t_end, output, opts, &Never)
}

/// Explicit central differences `q[n+1] = 2 q[n] - q[n-1] + dt^2 a(q[n])`, started with
/// `q[1] = q[0] + dt v0` (exactly this start: it is what the published table used).
/// The state in the [`Solution`] is `[q, v]` with `v` the central-difference velocity
/// `(q[n+1] - q[n-1]) / (2 dt)` (`v0` at `n = 0`). `Stats::nfev` counts evaluations of `a`.
/// A [`SecondOrderSystem::velocity_dependent`] system is refused (an [`Error`] naming `method`).
pub fn central_difference<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
) -> Result<Solution> {
    fixed::second_order::<central::Central<S>, S>(sys, t0, q0, v0, t_end, output, opts, &Never)
}

/// Velocity (Stormer-)Verlet, the symplectic kick-drift-kick scheme
/// `v+ = v + dt/2 a(q)`, `q1 = q + dt v+`, `v1 = v+ + dt/2 a(q1)`: second order, bounded
/// energy error without drift. The state in the [`Solution`] is `[q, v]`; `Stats::nfev`
/// counts evaluations of `a` (one per step plus one at the start). A
/// [`SecondOrderSystem::velocity_dependent`] system is refused (an [`Error`] naming `method`).
pub fn verlet<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &FixedOptions,
) -> Result<Solution> {
    fixed::second_order::<verlet::Verlet<S>, S>(sys, t0, q0, v0, t_end, output, opts, &Never)
}

/// An integration method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    Dop853,
    Dopri5,
    Rkn12,
    Rk4,
    Central,
    Verlet,
}

impl Method {
    /// Every method, in the order of their names in [`Method::parse`]'s error.
    pub const ALL: [Method; 6] =
        [Method::Dop853, Method::Dopri5, Method::Rkn12, Method::Rk4, Method::Central, Method::Verlet];

    /// Parses `"dop853"`, `"dopri5"`, `"rkn12"`, `"rk4"`, `"central"` or `"verlet"`.
    pub fn parse(name: &str) -> Result<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name).ok_or_else(|| {
            Error::invalid(
                "method",
                format!("{name:?}"),
                "one of \"dop853\", \"dopri5\", \"rkn12\", \"rk4\", \"central\", \"verlet\" (or \"auto\")",
            )
        })
    }

    /// The method a name selects for a system: a name of [`Method::parse`], or `"auto"`:
    /// [`Method::Rkn12`] for forces that do not depend on the velocity when
    /// `rtol <= AUTO_RKN12_MAX_RTOL`, [`Method::Dop853`] otherwise.
    ///
    /// ```
    /// use drillstring_core::integrators::Method;
    /// assert_eq!(Method::resolve("auto", false, 1e-12).unwrap(), Method::Rkn12);
    /// assert_eq!(Method::resolve("auto", true, 1e-12).unwrap(), Method::Dop853);
    /// assert_eq!(Method::resolve("auto", false, 1e-6).unwrap(), Method::Dop853);
    /// assert_eq!(Method::resolve("dopri5", false, 1e-12).unwrap(), Method::Dopri5);
    /// ```
    pub fn resolve(name: &str, velocity_dependent: bool, rtol: f64) -> Result<Method> {
        if name != "auto" {
            return Method::parse(name);
        }
        Ok(if !velocity_dependent && rtol <= AUTO_RKN12_MAX_RTOL { Method::Rkn12 } else { Method::Dop853 })
    }

    /// The name accepted by [`Method::parse`].
    pub fn name(self) -> &'static str {
        match self {
            Method::Dop853 => "dop853",
            Method::Dopri5 => "dopri5",
            Method::Rkn12 => "rkn12",
            Method::Rk4 => "rk4",
            Method::Central => "central",
            Method::Verlet => "verlet",
        }
    }

    /// Whether the method chooses its steps (`rtol`, `atol`, `first_step`, `max_step`
    /// apply) rather than taking fixed steps of `dt`.
    pub fn is_adaptive(self) -> bool {
        matches!(self, Method::Dop853 | Method::Dopri5 | Method::Rkn12)
    }
}

/// The loosest `rtol` at which `"auto"` ([`Method::resolve`]) picks RKN12 over DOP853 for
/// forces that do not depend on the velocity. Measured (`python benchmarks/compare_scipy.py
/// --crossover`: 3-mode aluminium case, 0 <= t <= 1, 20,001 output samples, atol = 1e-5 rtol,
/// core solves, two runs on an AVX2 machine): RKN12 needs about half the evaluations of DOP853
/// at every rtol from 1e-4 to 1e-13 and, with its dense output evaluated as monomials in
/// blocks, is faster at every one (1.1-2.2x at 1e-4 to 1e-6, 1.4-1.7x at 1e-7, 2.1-2.3x at
/// 1e-12). The bound is set by accuracy instead: at rtol 1e-4 and 1e-6 RKN12's samples are
/// further from the converged reference than DOP853's (2.6e-3 against 8.0e-4 of max |q|;
/// 1.1e-5 against 7.4e-6), from 1e-7 on they are closer (2.1e-7 against 7.3e-7; 2.6e-13
/// against 6.6e-12 at 1e-12).
pub const AUTO_RKN12_MAX_RTOL: f64 = 1e-7;

/// Options for any method: `rtol`, `atol`, `first_step`, `max_step` are used by the
/// adaptive methods, `dt` is required (`Some`) by the fixed-step ones. `max_steps: None`
/// takes the method's default ([`AdaptiveOptions::default`], [`FixedOptions::new`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    pub dt: Option<f64>,
    pub max_steps: Option<u64>,
    pub first_step: Option<f64>,
    pub max_step: f64,
}

impl SolveOptions {
    /// The defaults of [`AdaptiveOptions`] for `method`, without `dt`.
    pub fn new(method: Method) -> Self {
        let a = AdaptiveOptions::default();
        SolveOptions {
            method,
            rtol: a.rtol,
            atol: a.atol,
            dt: None,
            max_steps: None,
            first_step: a.first_step,
            max_step: a.max_step,
        }
    }

    /// The options of an adaptive method.
    pub fn adaptive(&self) -> AdaptiveOptions {
        let default = AdaptiveOptions::default();
        AdaptiveOptions {
            rtol: self.rtol,
            atol: self.atol,
            max_steps: self.max_steps.unwrap_or(default.max_steps),
            first_step: self.first_step,
            max_step: self.max_step,
        }
    }

    /// The options of a fixed-step method; `dt` must be given.
    pub fn fixed(&self) -> Result<FixedOptions> {
        let dt = self.dt.ok_or_else(|| {
            Error::invalid("dt", "None", format!("a finite number > 0 (required by method {})", self.method.name()))
        })?;
        let mut opts = FixedOptions::new(dt);
        if let Some(max_steps) = self.max_steps {
            opts.max_steps = max_steps;
        }
        Ok(opts)
    }
}

impl Default for SolveOptions {
    /// DOP853 with the default tolerances.
    fn default() -> Self {
        SolveOptions::new(Method::Dop853)
    }
}

/// Solves a second-order system `q'' = a(t, q, v)` from `(q0, v0)`; the state in the
/// [`Solution`] is `y = [q, v]`. Never interrupted: see [`solve_second_order_with`].
///
/// The form is chosen from [`SecondOrderSystem::velocity_dependent`]: a system whose forces
/// do not depend on the velocity is advanced through `a(q)` by any method (the
/// Runge-Kutta-Nystrom form for [`NYSTROM_MIN_DOF`] coordinates or more); one whose forces
/// do goes through the first-order form with the dissipated energy appended
/// ([`Dissipating`], reported in [`Solution::dissipated`]) by DOP853, DOPRI5 or RK4, and
/// central differences and Verlet refuse it (an [`Error`] naming `method`).
pub fn solve_second_order<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &SolveOptions,
) -> Result<Solution> {
    solve_second_order_with(sys, t0, q0, v0, t_end, output, opts, &Never)
}

/// [`solve_second_order`] that polls `interrupt` while it steps (every few milliseconds, see
/// [`crate::interrupt`]): once the hook answers `true` the solve ends with
/// [`crate::Status::Interrupted`], a message and the samples recorded so far. A hook that never
/// fires leaves the result bit-identical to [`solve_second_order`].
///
/// ```
/// use drillstring_core::integrators::{solve_second_order_with, Method, SolveOptions};
/// use drillstring_core::modal::ModalSystem;
/// use drillstring_core::{CancelFlag, Output, Status};
///
/// let sys = ModalSystem::new(vec![1.0], vec![1.0], vec![]).unwrap();
/// let flag = CancelFlag::new();
/// flag.cancel(); // e.g. from another thread
/// let opts = SolveOptions::new(Method::Dop853);
/// let sol = solve_second_order_with(&sys, 0.0, &[0.0], &[1.0], 1e6, &Output::EveryStep, &opts, &flag).unwrap();
/// assert_eq!(sol.status, Status::Interrupted);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn solve_second_order_with<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &SolveOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    check_state("q0", q0, sys.dof())?;
    check_state("v0", v0, sys.dof())?;
    if sys.velocity_dependent() {
        return solve_dissipating(sys, t0, q0, v0, t_end, output, opts, interrupt);
    }
    let first_order = FirstOrder(sys);
    let y0 = || [q0, v0].concat();
    match opts.method {
        Method::Dop853 => {
            adaptive_second_order::<dop853::Dop853, S>(sys, &y0(), (t0, t_end), output, &opts.adaptive(), interrupt)
        }
        Method::Dopri5 => {
            adaptive_second_order::<dopri5::Dopri5, S>(sys, &y0(), (t0, t_end), output, &opts.adaptive(), interrupt)
        }
        Method::Rkn12 => rkn::integrate(&rkn12::RKN12, sys, t0, q0, v0, t_end, output, &opts.adaptive(), interrupt),
        Method::Rk4 => rk4::integrate(&first_order, t0, &y0(), t_end, output, &opts.fixed()?, interrupt),
        Method::Central => {
            fixed::second_order::<central::Central<S>, S>(sys, t0, q0, v0, t_end, output, &opts.fixed()?, interrupt)
        }
        Method::Verlet => {
            fixed::second_order::<verlet::Verlet<S>, S>(sys, t0, q0, v0, t_end, output, &opts.fixed()?, interrupt)
        }
    }
}

/// A velocity-dependent system by DOP853, DOPRI5 or RK4 on `y = [q, v, D]` ([`Dissipating`]):
/// the dissipated energy `D` is one more component of the state, so it is integrated to the
/// same order and, by the adaptive methods, under the same error control as the motion. It is
/// moved out of the samples into [`Solution::dissipated`].
#[allow(clippy::too_many_arguments)]
fn solve_dissipating<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    output: &Output,
    opts: &SolveOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    if matches!(opts.method, Method::Central | Method::Verlet | Method::Rkn12) {
        return Err(refuse_velocity_dependent(opts.method));
    }
    let form = Dissipating(sys);
    let y0 = [q0, v0, &[0.0]].concat();
    let mut sol = match opts.method {
        Method::Dop853 => {
            adaptive::integrate::<dop853::Dop853, _>(&Plain(&form), t0, &y0, t_end, output, &opts.adaptive(), interrupt)
        }
        Method::Dopri5 => {
            adaptive::integrate::<dopri5::Dopri5, _>(&Plain(&form), t0, &y0, t_end, output, &opts.adaptive(), interrupt)
        }
        _ => rk4::integrate(&form, t0, &y0, t_end, output, &opts.fixed()?, interrupt),
    }?;
    split_dissipated(&mut sol);
    Ok(sol)
}

/// Moves the last state component of every sample into [`Solution::dissipated`].
fn split_dissipated(sol: &mut Solution) {
    let (dim, samples) = (sol.dim, sol.len());
    let kept = dim - 1;
    sol.dissipated = (0..samples).map(|k| sol.y[k * dim + kept]).collect();
    for k in 0..samples {
        sol.y.copy_within(k * dim..k * dim + kept, k * kept);
    }
    sol.y.truncate(samples * kept);
    sol.dim = kept;
}

/// The error of a method that advances `q'' = a(q)` only (central differences, Verlet, RKN12)
/// asked to solve a system with velocity-dependent forces.
pub(crate) fn refuse_velocity_dependent(method: Method) -> Error {
    Error::invalid(
        "method",
        method.name(),
        "\"dop853\", \"dopri5\" or \"rk4\" for forces that depend on the velocity (damping_rate > 0): \
         central differences, Verlet and rkn12 advance q'' = a(q) only",
    )
}

/// Second-order systems with at least this many coordinates go through the adaptive pairs in
/// the Runge-Kutta-Nystrom form (stage rows of `a(q)` only, half the stage arithmetic; same
/// method to rounding, see `integrators/form.rs`). Below it the first-order form is as fast
/// or faster: the Nystrom form's per-step coefficient algebra (a few hundred flops) outweighs
/// the saving. Measured with DOP853 on a nonlinear chain: break-even near 64 coordinates;
/// on the PDE system 15-20 % less time per evaluation at N = 240 and N = 2400.
pub const NYSTROM_MIN_DOF: usize = 64;

/// `P` on `y = [q, v]` over `span = (t0, t_end)`, in the form [`NYSTROM_MIN_DOF`] picks.
fn adaptive_second_order<P: adaptive::Scheme, S: SecondOrderSystem + ?Sized>(
    sys: &S,
    y0: &[f64],
    (t0, t_end): (f64, f64),
    output: &Output,
    opts: &AdaptiveOptions,
    interrupt: &dyn Interrupt,
) -> Result<Solution> {
    if sys.dof() >= NYSTROM_MIN_DOF {
        adaptive::integrate::<P, _>(&Nystrom::new(sys, &P::row_inputs()), t0, y0, t_end, output, opts, interrupt)
    } else {
        adaptive::integrate::<P, _>(&Plain(&FirstOrder(sys)), t0, y0, t_end, output, opts, interrupt)
    }
}

/// Checks that an initial state has length `dim >= 1` and finite entries.
fn check_state(field: &'static str, values: &[f64], dim: usize) -> Result<()> {
    if dim == 0 {
        return Err(Error::invalid(field, "a system of dimension 0", "a system with at least one unknown"));
    }
    if values.len() != dim {
        return Err(Error::invalid(field, format!("length {}", values.len()), format!("length {dim}")));
    }
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::invalid(field, format!("{field}[{i}] = {}", Num(*v)), "finite values"));
    }
    Ok(())
}

#[cfg(test)]
mod damping_tests;
#[cfg(test)]
mod rkn_tests;
#[cfg(test)]
mod tests;
