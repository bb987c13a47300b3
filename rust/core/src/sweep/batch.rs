//! The batch solve: many runs of one Galerkin basis in parallel, one [`RunRecord`] each.

use std::panic::{catch_unwind, AssertUnwindSafe};

use rayon::prelude::*;

use super::integrals::GalerkinIntegrals;
use super::metrics::{self, FftBuffers, FrequencyEstimator};
use crate::error::{Error, Result};
use crate::integrators::{self, SolveOptions};
use crate::options::{validate_span, Output};
use crate::solution::Status;

/// One run of a sweep: the PDE coefficients, the length, the initial modal velocities and the
/// section `z` where `theta(z, t)` is measured. The run starts at `q = 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpec {
    /// `k1..k6` of eq. 17.
    pub k: [f64; 6],
    /// `l`, m.
    pub length: f64,
    /// `qdot(0)` per retained coordinate, in the order of [`GalerkinIntegrals::indices`]
    /// (the rigid mode first when present).
    pub initial_velocities: Vec<f64>,
    /// Section of the metrics, `0 <= z <= l`.
    pub z: f64,
}

/// Options shared by every run of a batch.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOptions {
    /// Method and tolerances. For a fixed-step method without `dt`, each run takes
    /// `min(1e-4, T_min / 100)` with `T_min` its shortest linear period (as `simulate`).
    pub solve: SolveOptions,
    /// End time, s (the runs start at 0).
    pub t_end: f64,
    /// Number of uniform samples `t_j = j t_end / (samples - 1)`, `>= 4`.
    pub samples: usize,
    /// Keep each run's samples in [`RunRecord::trajectory`].
    pub keep_trajectories: bool,
}

impl SweepOptions {
    /// The uniform output times, exactly as `numpy.linspace(0, t_end, samples)`.
    pub fn times(&self) -> Vec<f64> {
        let n = self.samples;
        let step = self.t_end / (n - 1) as f64;
        let mut t: Vec<f64> = (0..n).map(|j| j as f64 * step).collect();
        t[n - 1] = self.t_end;
        t
    }

    pub fn validate(&self) -> Result<()> {
        if self.samples < 4 {
            return Err(Error::invalid("samples", self.samples, "an integer >= 4"));
        }
        validate_span(0.0, self.t_end, &Output::EveryStep)?;
        if self.solve.method.is_adaptive() {
            self.solve.adaptive().validate()
        } else {
            match self.solve.dt {
                Some(_) => self.solve.fixed()?.validate(),
                None => {
                    if self.solve.max_steps == Some(0) {
                        return Err(Error::invalid("max_steps", "0", "an integer >= 1"));
                    }
                    Ok(())
                }
            }
        }
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunStatus {
    /// Solved to `t_end`.
    Solved(Status),
    /// The spec was refused before solving (see the message); no metrics.
    Invalid,
    /// An internal error (a panic caught in this run only); no metrics.
    Error,
}

impl RunStatus {
    /// `"success"`, `"max_steps"`, `"step_size_underflow"`, `"non_finite"`, `"invalid"` or `"error"`.
    pub fn name(self) -> &'static str {
        match self {
            RunStatus::Solved(s) => s.name(),
            RunStatus::Invalid => "invalid",
            RunStatus::Error => "error",
        }
    }

    pub fn is_success(self) -> bool {
        self == RunStatus::Solved(Status::Success)
    }
}

/// The samples of one run (kept when [`SweepOptions::keep_trajectories`] is set).
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Row-major `[q, qdot]` per sample (`2 m` values each); fewer samples than requested
    /// when the solve stopped early.
    pub y: Vec<f64>,
    /// `theta(z, t_j)` per sample.
    pub theta: Vec<f64>,
}

/// The outcome of one run. Metrics are NaN unless the run succeeded.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    pub status: RunStatus,
    /// Why the run failed or was refused ("" on success).
    pub message: String,
    pub max_theta: f64,
    pub rms_theta: f64,
    pub dominant_frequency_hz: f64,
    pub energy_drift: f64,
    /// `#{K_i < 0}`; `None` for an invalid spec.
    pub unstable_modes: Option<u32>,
    /// Right-hand-side evaluations.
    pub nfev: u64,
    /// Largest energy share of each retained mode (`m` values, NaN unless successful).
    pub max_share: Vec<f64>,
    pub trajectory: Option<Trajectory>,
}

impl RunRecord {
    fn failed(status: RunStatus, message: String, modes: usize) -> Self {
        RunRecord {
            status,
            message,
            max_theta: f64::NAN,
            rms_theta: f64::NAN,
            dominant_frequency_hz: f64::NAN,
            energy_drift: f64::NAN,
            unstable_modes: None,
            nfev: 0,
            max_share: vec![f64::NAN; modes],
            trajectory: None,
        }
    }
}

/// What every run of a batch shares.
struct Shared<'a> {
    integrals: &'a GalerkinIntegrals,
    opts: &'a SweepOptions,
    output: Output,
    dt: f64,
    estimator: FrequencyEstimator,
}

/// Solves every run of `runs` (in parallel on `threads` threads, or rayon's global pool
/// when `None`) and returns one record per run, in input order.
///
/// Errors only for invalid shared input (`opts`, `threads = Some(0)`); a bad run becomes a
/// record with status [`RunStatus::Invalid`], a failed solve a record with its status, and
/// neither affects the other runs.
pub fn batch_solve(
    integrals: &GalerkinIntegrals,
    runs: &[RunSpec],
    opts: &SweepOptions,
    threads: Option<usize>,
) -> Result<Vec<RunRecord>> {
    opts.validate()?;
    let times = opts.times();
    let shared = Shared {
        integrals,
        opts,
        dt: opts.t_end / (opts.samples - 1) as f64,
        estimator: FrequencyEstimator::new(opts.samples),
        output: Output::Times(times),
    };
    let work = || {
        runs.par_iter()
            .map_init(|| shared.estimator.buffers(), |buf, spec| run_guarded(&shared, spec, buf))
            .collect::<Vec<_>>()
    };
    match threads {
        None => Ok(work()),
        Some(0) => Err(Error::invalid("threads", 0, "an integer >= 1 (or None for all cores)")),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| Error::invalid("threads", n, format!("a thread count the system allows ({e})")))?;
            Ok(pool.install(work))
        }
    }
}

/// [`run_one`], with a panic turned into a record of this run only.
fn run_guarded(shared: &Shared<'_>, spec: &RunSpec, buf: &mut FftBuffers) -> RunRecord {
    catch_unwind(AssertUnwindSafe(|| run_one(shared, spec, buf))).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        RunRecord::failed(RunStatus::Error, format!("internal error: {what}"), shared.integrals.modes())
    })
}

/// `min(1e-4, T_min / 100)`: the default step of the fixed-step methods (as `simulate`).
fn default_dt(mass: &[f64], stiffness: &[f64]) -> f64 {
    let w2 = mass.iter().zip(stiffness).map(|(m, k)| (k / m).abs()).fold(0.0f64, f64::max);
    if w2 == 0.0 {
        1e-4
    } else {
        (2.0 * std::f64::consts::PI / w2.sqrt() / 100.0).min(1e-4)
    }
}

fn run_one(shared: &Shared<'_>, spec: &RunSpec, buf: &mut FftBuffers) -> RunRecord {
    let m = shared.integrals.modes();
    let invalid = |e: Error| RunRecord::failed(RunStatus::Invalid, e.to_string(), m);
    let sys = match shared.integrals.scale(&spec.k, spec.length) {
        Ok(sys) => sys,
        Err(e) => return invalid(e),
    };
    if spec.initial_velocities.len() != m {
        return invalid(Error::invalid(
            "initial_velocities",
            format!("length {}", spec.initial_velocities.len()),
            format!("length {m} (one per retained mode)"),
        ));
    }
    if !(spec.z.is_finite() && (0.0..=spec.length).contains(&spec.z)) {
        return invalid(Error::invalid("z", spec.z, format!("0 <= z <= length = {}", spec.length)));
    }
    let mut solve = shared.opts.solve;
    if !solve.method.is_adaptive() && solve.dt.is_none() {
        solve.dt = Some(default_dt(sys.mass(), sys.stiffness()));
    }
    let q0 = vec![0.0; m];
    let sol = match integrators::solve_second_order(
        &sys,
        0.0,
        &q0,
        &spec.initial_velocities,
        shared.opts.t_end,
        &shared.output,
        &solve,
    ) {
        Ok(sol) => sol,
        Err(e) => return invalid(e),
    };
    let unstable = sys.stiffness().iter().filter(|&&k| k < 0.0).count() as u32;
    let basis = shared.integrals.basis(spec.z, spec.length);
    let theta = metrics::section_twist(&sol.y, &basis);
    let status = RunStatus::Solved(sol.status);
    let mut record = RunRecord::failed(status, sol.message.clone(), m);
    record.unstable_modes = Some(unstable);
    record.nfev = sol.stats.nfev;
    if status.is_success() {
        let metrics = metrics::compute(&sys, &sol.y, &theta, shared.dt, &shared.estimator, buf);
        record.max_theta = metrics.max_theta;
        record.rms_theta = metrics.rms_theta;
        record.dominant_frequency_hz = metrics.dominant_frequency_hz;
        record.energy_drift = metrics.energy_drift;
        record.max_share = metrics.max_share;
    }
    if shared.opts.keep_trajectories {
        record.trajectory = Some(Trajectory { y: sol.y, theta });
    }
    record
}
