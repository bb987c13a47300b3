//! The batch solve: many runs of one Galerkin basis in parallel, one [`RunRecord`] each.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::Duration;

use rayon::prelude::*;

use super::integrals::GalerkinIntegrals;
use crate::error::{Error, Num, Result};
use crate::integrators::{self, SolveOptions};
use crate::interrupt::{CancelFlag, Interrupt, Never};
use crate::metrics::{self, FftBuffers, FrequencyEstimator};
use crate::options::{default_fixed_dt, validate_span, Output};
use crate::solution::Status;

/// Largest number of threads of one batch solve.
pub const MAX_THREADS: usize = 1024;

/// How often the thread that started a batch asks its [`Interrupt`] hook while the runs go on.
const HOOK_INTERVAL: Duration = Duration::from_millis(5);

/// The threads a batch solve uses: `threads`, or every core the system offers for `None`.
///
/// Errors for `Some(0)` or more than [`MAX_THREADS`].
pub fn resolve_threads(threads: Option<usize>) -> Result<usize> {
    match threads {
        None => Ok(std::thread::available_parallelism().map_or(1, usize::from).min(MAX_THREADS)),
        Some(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        Some(n) => {
            Err(Error::invalid("threads", n, format!("an integer in 1..={MAX_THREADS} (or None for all cores)")))
        }
    }
}

/// `n` bytes as `"1.5 GiB"` (binary units, three significant digits).
fn human_bytes(n: u64) -> String {
    let mut value = n as f64;
    for unit in ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB"] {
        if value < 1024.0 || unit == "PiB" {
            return if unit == "bytes" { format!("{n} bytes") } else { format!("{value:.3} {unit}") };
        }
        value /= 1024.0;
    }
    unreachable!()
}

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
    /// Viscous damping rate `c`, 1/s (`>= 0`; 0 for the undamped model), see
    /// [`crate::modal::ModalSystem::with_damping`].
    pub damping_rate: f64,
}

/// Options shared by every run of a batch.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOptions {
    /// Method and tolerances. For a fixed-step method without `dt`, each run takes
    /// [`default_fixed_dt`], `min(1e-4, T_min / 100)` with `T_min` its shortest linear period
    /// (as `simulate`).
    pub solve: SolveOptions,
    /// End time, s (the runs start at 0).
    pub t_end: f64,
    /// Number of uniform samples `t_j = j t_end / (samples - 1)`, `>= 4`.
    pub samples: usize,
    /// Keep each run's samples in [`RunRecord::trajectory`].
    pub keep_trajectories: bool,
    /// Largest peak memory, in bytes, that a batch may need ([`SweepOptions::memory_bytes`]);
    /// `None` for no limit. A batch that would need more is refused before any work.
    pub memory_budget: Option<u64>,
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

    /// An estimate of the peak memory, in bytes, of a batch of `runs` runs of `modes` retained
    /// coordinates on `threads` threads (saturating; an upper estimate):
    ///
    /// * shared: the output times, the Hann window and the FFT plan, `8 S + 8 S + 16 F`;
    /// * per thread, one run at a time: its samples `8 S (2m + 1)`, `theta(z, t)` `8 S` and
    ///   the FFT buffers `32 F`;
    /// * per run: its record, `8 m + 256`; with kept trajectories also its samples twice (the
    ///   record's and the caller's arrays), `2 * 8 S (2m + 1)`;
    ///
    /// with `S` samples and `F = next_power_of_two(8 S)` the FFT length.
    pub fn memory_bytes(&self, modes: usize, runs: usize, threads: usize) -> u64 {
        let (s, m, runs) = (self.samples as u128, modes as u128, runs as u128);
        let fft = (self.samples.saturating_mul(metrics::PAD))
            .checked_next_power_of_two()
            .map_or(u128::from(u64::MAX), |f| f as u128);
        let shared = 16 * s + 16 * fft;
        let per_thread = 8 * s * (2 * m + 1) + 8 * s + 32 * fft;
        let kept = if self.keep_trajectories { 2 * 8 * s * (2 * m + 1) } else { 0 };
        let per_run = 8 * m + 256 + kept;
        let total = shared
            .saturating_add(per_thread.saturating_mul(threads.min(runs.max(1) as usize) as u128))
            .saturating_add(per_run.saturating_mul(runs));
        u64::try_from(total).unwrap_or(u64::MAX)
    }

    /// Refuses (naming `samples`) a batch whose [`SweepOptions::memory_bytes`] exceeds
    /// [`SweepOptions::memory_budget`].
    pub fn check_memory(&self, modes: usize, runs: usize, threads: usize) -> Result<()> {
        let Some(budget) = self.memory_budget else { return Ok(()) };
        let need = self.memory_bytes(modes, runs, threads);
        if need <= budget {
            return Ok(());
        }
        let what = if self.keep_trajectories {
            format!("{runs} runs with their trajectories of {} values per sample", 2 * modes + 1)
        } else {
            format!("{runs} runs on {} threads", threads.min(runs.max(1)))
        };
        Err(Error::invalid(
            "samples",
            self.samples,
            format!(
                "a number of samples whose batch fits the memory budget of {} (DRILLSTRING_MEMORY_BUDGET): \
                 {what} would need {} ({need} bytes); request fewer samples{}",
                human_bytes(budget),
                human_bytes(need),
                if self.keep_trajectories { ", runs or no trajectories" } else { ", runs per chunk or threads" },
            ),
        ))
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
pub struct RunSamples {
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
    /// The linearly unstable modes ([`crate::stability::unstable_modes`]: `K_ii / M_ii < 0`
    /// beyond round-off); `None` for an invalid spec.
    pub unstable_modes: Option<u32>,
    /// Right-hand-side evaluations.
    pub nfev: u64,
    /// Largest energy share of each retained mode (`m` values, NaN unless successful).
    pub max_share: Vec<f64>,
    pub trajectory: Option<RunSamples>,
}

/// The records of a batch as the columns of its table, one entry per run: the metrics (NaN for
/// a run without them), `unstable_modes` (-1 for an invalid spec), `nfev`, `max_share` (flat,
/// runs x modes) and, when trajectories are kept, `t`, `y` (flat, runs x samples x 2 modes) and
/// `theta` (runs x samples), NaN past where a run stopped.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BatchColumns {
    pub status: Vec<&'static str>,
    pub message: Vec<String>,
    pub max_theta: Vec<f64>,
    pub rms_theta: Vec<f64>,
    pub dominant_frequency_hz: Vec<f64>,
    pub energy_drift: Vec<f64>,
    pub unstable_modes: Vec<i64>,
    pub nfev: Vec<i64>,
    pub max_share: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub theta: Option<Vec<f64>>,
}

impl BatchColumns {
    /// The columns of `records` (`modes` retained modes); with `times` (the output times of
    /// kept trajectories), the trajectories too.
    pub fn new(records: &[RunRecord], modes: usize, times: Option<Vec<f64>>) -> BatchColumns {
        let column = |f: fn(&RunRecord) -> f64| records.iter().map(f).collect::<Vec<f64>>();
        let (y, theta) = match &times {
            Some(t) => {
                let (r, s) = (records.len(), t.len());
                let mut y = vec![f64::NAN; r * s * 2 * modes];
                let mut theta = vec![f64::NAN; r * s];
                for (i, rec) in records.iter().enumerate() {
                    if let Some(traj) = &rec.trajectory {
                        y[i * s * 2 * modes..i * s * 2 * modes + traj.y.len()].copy_from_slice(&traj.y);
                        theta[i * s..i * s + traj.theta.len()].copy_from_slice(&traj.theta);
                    }
                }
                (Some(y), Some(theta))
            }
            None => (None, None),
        };
        BatchColumns {
            status: records.iter().map(|r| r.status.name()).collect(),
            message: records.iter().map(|r| r.message.clone()).collect(),
            max_theta: column(|r| r.max_theta),
            rms_theta: column(|r| r.rms_theta),
            dominant_frequency_hz: column(|r| r.dominant_frequency_hz),
            energy_drift: column(|r| r.energy_drift),
            unstable_modes: records.iter().map(|r| r.unstable_modes.map_or(-1, i64::from)).collect(),
            nfev: records.iter().map(|r| i64::try_from(r.nfev).unwrap_or(i64::MAX)).collect(),
            max_share: records.iter().flat_map(|r| r.max_share.iter().copied()).collect(),
            t: times,
            y,
            theta,
        }
    }
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
    /// Raised when the batch is interrupted: every run polls it.
    cancel: &'a CancelFlag,
}

/// Solves every run of `runs` in parallel on `threads` threads (every core for `None`, see
/// [`resolve_threads`]) and returns one record per run, in input order.
///
/// Errors only for invalid shared input (`opts`, `threads`, a batch over
/// [`SweepOptions::memory_budget`]); a bad run becomes a record with status
/// [`RunStatus::Invalid`], a failed solve a record with its status, and neither affects the
/// other runs.
pub fn batch_solve(
    integrals: &GalerkinIntegrals,
    runs: &[RunSpec],
    opts: &SweepOptions,
    threads: Option<usize>,
) -> Result<Vec<RunRecord>> {
    batch_solve_with(integrals, runs, opts, threads, &Never)
}

/// [`batch_solve`] that asks `interrupt` every few milliseconds while the runs go on (from the
/// calling thread only, which waits for the pool: a hook that must run on a given thread,
/// such as Python's signal check, works). When it answers `true`, the runs under way stop
/// within a few milliseconds with [`Status::Interrupted`], the runs not yet started are
/// records with that status too, and the finished runs keep their results.
///
/// The runs go on a thread pool made for this call and dropped after it (never rayon's global
/// pool), so a process that forks after a batch can run batches in the child.
pub fn batch_solve_with(
    integrals: &GalerkinIntegrals,
    runs: &[RunSpec],
    opts: &SweepOptions,
    threads: Option<usize>,
    interrupt: &dyn Interrupt,
) -> Result<Vec<RunRecord>> {
    opts.validate()?;
    let threads = resolve_threads(threads)?;
    opts.check_memory(integrals.modes(), runs.len(), threads)?;
    let times = opts.times();
    let cancel = CancelFlag::new();
    let shared = Shared {
        integrals,
        opts,
        dt: opts.t_end / (opts.samples - 1) as f64,
        estimator: FrequencyEstimator::new(opts.samples),
        output: Output::Times(times),
        cancel: &cancel,
    };
    let work = || {
        runs.par_iter()
            .map_init(|| shared.estimator.buffers(), |buf, spec| run_guarded(&shared, spec, buf))
            .collect::<Vec<_>>()
    };
    run_on_pool(threads, runs.len(), &cancel, interrupt, || f64::NAN, work)
}

/// Runs `work` (parallel iterators inside it run on the pool) on a rayon pool of `threads`
/// made for this call and dropped after it (fork-safe: never the global pool), for a batch of
/// `runs` runs. Meanwhile the calling thread polls `interrupt` every [`HOOK_INTERVAL`] (a
/// Python signal check must run on the main thread) and cancels `cancel` when it asks to stop;
/// each poll first calls `tick`, whose value (the progress reached) is what the hook sees, and
/// `tick` is called once more when the work has ended. The batch solves and the drilling maps
/// both run this way.
pub(crate) fn run_on_pool<T: Send>(
    threads: usize,
    runs: usize,
    cancel: &CancelFlag,
    interrupt: &dyn Interrupt,
    mut tick: impl FnMut() -> f64,
    work: impl FnOnce() -> T + Send,
) -> Result<T> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.min(runs.max(1)))
        .build()
        .map_err(|e| Error::invalid("threads", threads, format!("a thread count the system allows ({e})")))?;
    let outcome = std::thread::scope(|scope| {
        let (done, finished) = mpsc::channel();
        let worker = scope.spawn(move || {
            let out = pool.install(work);
            let _ = done.send(());
            out
        });
        loop {
            let ended = !matches!(finished.recv_timeout(HOOK_INTERVAL), Err(mpsc::RecvTimeoutError::Timeout));
            let reached = tick();
            if ended {
                break;
            }
            if !cancel.is_cancelled() && interrupt.interrupted_at(reached) {
                cancel.cancel();
            }
        }
        worker.join()
    });
    outcome.map_err(|_| Error::invalid("runs", runs, "runs the batch solver can finish (internal error)"))
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

fn run_one(shared: &Shared<'_>, spec: &RunSpec, buf: &mut FftBuffers) -> RunRecord {
    let m = shared.integrals.modes();
    if shared.cancel.is_cancelled() {
        let message = "interrupted before this run started".to_string();
        return RunRecord::failed(RunStatus::Solved(Status::Interrupted), message, m);
    }
    let invalid = |e: Error| RunRecord::failed(RunStatus::Invalid, e.to_string(), m);
    let sys = match shared.integrals.scale(&spec.k, spec.length).and_then(|sys| sys.with_damping(spec.damping_rate)) {
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
        return invalid(Error::invalid("z", Num(spec.z), format!("0 <= z <= length = {}", Num(spec.length))));
    }
    let mut solve = shared.opts.solve;
    if !solve.method.is_adaptive() && solve.dt.is_none() {
        solve.dt = Some(default_fixed_dt(sys.mass(), sys.stiffness()));
    }
    let q0 = vec![0.0; m];
    let sol = match integrators::solve_second_order_with(
        &sys,
        0.0,
        &q0,
        &spec.initial_velocities,
        shared.opts.t_end,
        &shared.output,
        &solve,
        shared.cancel,
    ) {
        Ok(sol) => sol,
        Err(e) => return invalid(e),
    };
    let unstable = crate::stability::unstable_modes(sys.mass(), sys.stiffness()) as u32;
    let basis = shared.integrals.basis(spec.z, spec.length);
    let theta = metrics::section_twist(&sol.y, &basis);
    let status = RunStatus::Solved(sol.status);
    let mut record = RunRecord::failed(status, sol.message.clone(), m);
    record.unstable_modes = Some(unstable);
    record.nfev = sol.stats.nfev;
    if status.is_success() {
        let metrics = metrics::compute(&sys, &sol.y, &sol.dissipated, &theta, shared.dt, &shared.estimator, buf);
        record.max_theta = metrics.max_theta;
        record.rms_theta = metrics.rms_theta;
        record.dominant_frequency_hz = metrics.dominant_frequency_hz;
        record.energy_drift = metrics.energy_drift;
        record.max_share = metrics.max_share;
    }
    if shared.opts.keep_trajectories {
        record.trajectory = Some(RunSamples { y: sol.y, theta });
    }
    record
}
