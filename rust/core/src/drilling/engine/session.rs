//! A run as a session: a [`Simulation`] stepped in chunks ([`Session::advance`]) with values
//! changed between them ([`Session::set`], the keys of [`SETTABLE`]), its state read at any
//! time ([`Session::state`]), its series so far ([`Session::run`]) and its result over what was
//! stepped ([`Session::result`]: energy balance, metrics, warnings). The batch run of a
//! configuration is a session stepped to `numerics.duration` and finished
//! ([`Simulation::run`]): one loop for both, so a session stepped through the duration in any
//! chunks gives the batch run's series bit for bit.
//!
//! A change takes effect from the next step; the configuration's `[[changes]]` entries are made
//! by the same [`Session::set`] before the step starting at the step boundary nearest their
//! time (the step a `top_drive.steps` entry at that time takes effect from,
//! [`super::controller::Setpoint`]).

use serde::Serialize;
use serde_json::Value;

use super::boundary::{BitEnd, TopDriveEnd};
use super::controller::{gains, Setpoint, Top, RPM_PER_RAD_S};
use super::coupled_friction::CoupledFriction;
use super::energy::{EnergyBalance, NOT_KEPT};
use super::field::StringField;
use super::run::{axial_transient, coupled_metrics, metrics, DrillRun, DrillStats, Simulation, RUNAWAY_FACTOR};
use super::sampler::Sampler;
use super::sources::{Sources, WallFriction};
use crate::drilling::axial::regime::Regime;
use crate::drilling::config::{settable_config, Change, DrillConfig};
use crate::drilling::grid::{breakoff_torque, min_cycle_torque, Grid};
use crate::drilling::plausibility::{
    axial_resolution_warning, lifting, non_finite_metrics_warning, off_bottom_warning, rotation_commanded,
    run_warnings, torque_limit_share, torque_limit_verdict, torque_limit_warning, transient_warning, NO_ROTATION,
};
use crate::error::{Num, Result};
use crate::interrupt::{Interrupt, Poller};
use crate::metrics::Verdict;
use crate::solution::Status;

/// The number of steps of a run of `duration` s on steps of `dt`: the first step end at or after
/// the duration (at least one step).
pub fn duration_steps(duration: f64, dt: f64) -> u64 {
    ((duration / dt) * (1.0 - 1e-12)).ceil().max(1.0) as u64
}

/// Whether a change at `time` is made before the step from `t` of length `dt`: the step
/// starting at the step boundary nearest `time`, or a later one.
fn due(time: f64, t: f64, dt: f64) -> bool {
    time <= t + 0.5 * dt
}

/// The state of a session at its time: the along-string fields and the ends (SI; speeds in rpm).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SessionState {
    /// The time reached, s.
    pub t_s: f64,
    /// Cell centres, m.
    pub z_m: Vec<f64>,
    /// Cell speeds, rpm.
    pub omega_rpm: Vec<f64>,
    /// Cell torques, N m.
    #[serde(rename = "torque_Nm")]
    pub torque_nm: Vec<f64>,
    /// The wall's normal force per metre at the cells, N/m ([`Grid::normal`]).
    #[serde(rename = "contact_N_per_m")]
    pub contact_n_per_m: Vec<f64>,
    /// Cells held by the set-valued wall friction (speed exactly 0 with a friction limit).
    pub stuck: Vec<bool>,
    /// A coupled run's axial cells (empty without a hoist): centres m, speed m/s (down
    /// positive), force N (compression positive).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axial_z_m: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axial_speed_m_per_s: Vec<f64>,
    #[serde(rename = "axial_force_N", skip_serializing_if = "Vec::is_empty")]
    pub axial_force_n: Vec<f64>,
    /// The top drive's and the bit's speed (as the series reports it), rpm.
    pub surface_rpm: f64,
    pub bit_rpm: f64,
    /// The motor torque and the torque on bit of the last step, N m (0 before the first).
    #[serde(rename = "motor_torque_Nm")]
    pub motor_torque_nm: f64,
    #[serde(rename = "bit_torque_Nm")]
    pub bit_torque_nm: f64,
}

/// A change made during a session: the time it took effect from (the session's time when it
/// was made), the dotted key and the value as given.
pub type Applied = Change;

/// A drilling run stepped in chunks (see the module docs). `Clone` is a snapshot: the copy
/// continues bit for bit as the original would.
#[derive(Clone)]
pub struct Session {
    sim: Simulation,
    /// The series and snapshots so far (metrics, energy and warnings are filled by
    /// [`Session::result`]).
    run: DrillRun,
    sampler: Sampler,
    /// The stored energy at the start, J.
    initial: f64,
    /// Steps taken.
    steps: u64,
    /// The batch run: storage reserved up front for the duration (the out-of-memory status
    /// before the first step), the series and snapshots to the duration only.
    batch: bool,
    /// The motor torque and torque on bit of the last step, N m.
    last: (f64, f64),
    /// The configuration's `[[changes]]` (sorted by time) and the next one to make.
    pending: Vec<Change>,
    next_change: usize,
    /// Every change made, in order.
    applied: Vec<Applied>,
}

impl Session {
    /// A session of `cfg` (validated first) at its initial state; `keep_fields`: record the
    /// field snapshots every `numerics.field_interval` (else none). Its storage grows as it is
    /// stepped, past `numerics.duration` if asked.
    pub fn new(cfg: &DrillConfig, keep_fields: bool) -> Result<Session> {
        Ok(Session::start(Simulation::new(cfg)?, false, keep_fields))
    }

    /// The session of `cfg` that `steps` steps with the changes `applied` (a session's
    /// [`Session::applied`]) reach: `cfg` (validated first) with its `[[changes]]` not yet due
    /// at that step kept and `applied` made at their times, stepped there; bit for bit the
    /// session those changes and steps made (a snapshot rebuilt from its description).
    pub fn resume(
        cfg: &DrillConfig,
        applied: &[Change],
        steps: u64,
        keep_fields: bool,
        interrupt: &dyn Interrupt,
    ) -> Result<Session> {
        let mut cfg = cfg.clone();
        let dt = Grid::new(&cfg)?.dt;
        let last = steps.saturating_sub(1) as f64 * dt;
        cfg.changes.retain(|c| steps == 0 || !due(c.time, last, dt));
        cfg.changes.splice(0..0, applied.iter().cloned());
        let t = steps as f64 * dt;
        if t > cfg.numerics.duration {
            cfg.numerics.duration = t;
        }
        let mut session = Session::new(&cfg, keep_fields)?;
        if steps > 0 {
            session.advance(steps, interrupt, &mut |_| {});
        }
        Ok(session)
    }

    /// The batch run's session of `sim` (see [`Simulation::run`]).
    pub(super) fn batch(sim: Simulation) -> Session {
        Session::start(sim, true, true)
    }

    fn start(sim: Simulation, batch: bool, keep_fields: bool) -> Session {
        let cfg = &sim.cfg;
        let nz = sim.grid.cells();
        let dt = sim.grid.dt;
        let courant = &sim.grid.courant;
        let (kp, ki) = gains(cfg, &sim.grid, sim.first_mode);
        let mut run = DrillRun {
            z: sim.grid.z.clone(),
            axial_z: sim.axial.as_ref().map_or_else(Vec::new, |a| a.z.clone()),
            metrics_finite: true,
            rotating: true,
            stats: DrillStats {
                cells: nz,
                steps: 0,
                dt,
                courant_min: courant.iter().copied().fold(f64::INFINITY, f64::min),
                courant_max: courant.iter().copied().fold(0.0, f64::max),
                courant_peak: courant.iter().copied().fold(0.0, f64::max),
                kp,
                ki,
                first_mode_hz: sim.first_mode / (2.0 * std::f64::consts::PI),
            },
            ..empty_like()
        };
        let mut sampler = if batch { Sampler::new(cfg) } else { Sampler::open(cfg, keep_fields) };
        let mut pending = cfg.changes.clone();
        pending.sort_by(|a, b| a.time.total_cmp(&b.time));
        let initial = sim.stored().total();
        let axial_cells = sim.axial.as_ref().map_or(0, |a| a.z.len());
        if batch {
            if let Err(oom) = sampler.reserve(&mut run, nz, axial_cells) {
                run.status = Status::OutOfMemory;
                run.message = oom.outputs_message();
            }
        } else if let Err(oom) = sampler.grow(&mut run, 1, 1, nz, axial_cells) {
            run.status = Status::OutOfMemory;
            run.message = oom.outputs_message();
        }
        if run.status == Status::Success
            && !sampler.start(&sim.torsion, sim.axial.as_ref(), &mut run, sim.sample(0.0, f64::NAN, f64::NAN))
        {
            run.status = Status::NonFinite;
            run.message = "the initial state is not finite".into();
        }
        Session {
            sim,
            run,
            sampler,
            initial,
            steps: 0,
            batch,
            last: (0.0, 0.0),
            pending,
            next_change: 0,
            applied: Vec::new(),
        }
    }

    /// The time step, s.
    pub fn dt(&self) -> f64 {
        self.sim.grid.dt
    }

    /// The time reached, s (steps taken times the step).
    pub fn t(&self) -> f64 {
        self.steps as f64 * self.sim.grid.dt
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// How the session stands: [`Status::Success`] while it can be stepped, else how it ended
    /// (`non_finite`, `out_of_memory`), with [`Session::message`].
    pub fn status(&self) -> Status {
        self.run.status
    }

    pub fn message(&self) -> &str {
        &self.run.message
    }

    /// The configuration as it stands (with the changes made so far).
    pub fn config(&self) -> &DrillConfig {
        &self.sim.cfg
    }

    /// The series and field snapshots so far (without metrics; [`Session::result`] has them).
    pub fn run(&self) -> &DrillRun {
        &self.run
    }

    /// Every change made so far (the configuration's `[[changes]]` reached and
    /// [`Session::set`]'s), in order, each with the time it took effect from.
    pub fn applied(&self) -> &[Applied] {
        &self.applied
    }

    /// The `numerics.duration` of the configuration whose batch run is what was stepped: the
    /// configuration's own when the session stands at the batch run's last step
    /// ([`duration_steps`]), else the time reached.
    pub fn replay_duration(&self) -> f64 {
        let duration = self.sim.cfg.numerics.duration;
        if self.steps == duration_steps(duration, self.sim.grid.dt) {
            duration
        } else {
            self.t()
        }
    }

    /// The steps that advance the session by `seconds`: to the step end nearest `t + seconds`,
    /// at least one; a time whose nearest step end is the duration's ends where the batch run
    /// does ([`duration_steps`]: the first step end at or after `numerics.duration`, which holds
    /// the last sample of the series).
    pub fn steps_for(&self, seconds: f64) -> u64 {
        let dt = self.sim.grid.dt;
        let duration = self.sim.cfg.numerics.duration;
        let target = (self.t() + seconds.max(0.0)) / dt;
        let mut end = if target.is_finite() { target.round().max(0.0) as u64 } else { u64::MAX / 2 };
        if end == (duration / dt).round() as u64 {
            end = duration_steps(duration, dt);
        }
        end.saturating_sub(self.steps).max(1)
    }

    /// Takes `count` steps (fewer when `interrupt` asks to stop or the run fails), calling
    /// `progress` with the fraction of them done (every ~0.1 %). Returns `true` when
    /// interrupted (the session stays usable at the step reached); a failure (a runaway or a
    /// non-finite state, no memory for the samples) ends the session with its status.
    pub fn advance(&mut self, count: u64, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> bool {
        if self.run.status != Status::Success {
            return false;
        }
        let dt = self.sim.grid.dt;
        if !self.batch {
            let rows = (count as f64 * dt / self.sim.cfg.numerics.output_interval).ceil() as usize + 1;
            let fi = self.sim.cfg.numerics.field_interval;
            let snaps = if fi > 0.0 { (count as f64 * dt / fi).ceil() as usize + 1 } else { 0 };
            let axial_cells = self.run.axial_z.len();
            if let Err(oom) = self.sampler.grow(&mut self.run, rows, snaps, self.sim.grid.cells(), axial_cells) {
                self.run.status = Status::OutOfMemory;
                self.run.message = oom.outputs_message();
                return false;
            }
        }
        let mut poller = Poller::new(interrupt);
        let mut runaway = self.runaway();
        let stride = (count / 1000).max(1);
        for k in 0..count {
            let n = self.steps;
            let t = n as f64 * dt;
            if poller.poll(t) {
                return true;
            }
            if self.changes_due(t) {
                runaway = self.runaway();
            }
            let (motor, bit) = self.sim.step(t);
            let t = (n + 1) as f64 * dt;
            let (top, end) = (self.sim.top.omega, self.sim.bit.omega);
            if top.abs().max(end.abs()) > runaway {
                self.run.status = Status::NonFinite;
                self.run.message = format!(
                    "the solution diverged: the {} speed reached {} rpm, more than {} times the largest setpoint, \
                     at t = {} s (a grid too coarse for the controller or the bit law: raise numerics.cells)",
                    if top.abs() > runaway { "top-drive" } else { "bit" },
                    Num(top.abs().max(end.abs()) * RPM_PER_RAD_S),
                    RUNAWAY_FACTOR,
                    Num(t)
                );
                return false;
            }
            self.steps = n + 1;
            self.run.stats.steps = n + 1;
            self.last = (motor, bit);
            let point = self.sampler.needs_point(n, t, (n + 2) as f64 * dt).then(|| self.sim.sample(t, motor, bit));
            if !self.sampler.record(n, t, point, &self.sim.torsion, self.sim.axial.as_ref(), &mut self.run, dt) {
                self.run.status = Status::NonFinite;
                self.run.message = format!("the state became non-finite before t = {} s", Num(t));
                return false;
            }
            if (k + 1) % stride == 0 {
                progress((k + 1) as f64 / count as f64);
            }
        }
        false
    }

    /// The speed beyond which the run has diverged, rad/s ([`RUNAWAY_FACTOR`]).
    fn runaway(&self) -> f64 {
        RUNAWAY_FACTOR * Setpoint::fastest(&self.sim.cfg.top_drive).max(1.0)
    }

    /// Makes the configuration's changes due before the step from `t` (their time at most half
    /// a step after it); whether any was made. A change the run refuses though the
    /// configuration's check accepted it (a gain the sampled top-drive loop cannot hold on this
    /// grid) is not made, and the run's message says so.
    fn changes_due(&mut self, t: f64) -> bool {
        let half = 0.5 * self.sim.grid.dt;
        let mut made = false;
        while let Some(c) = self.pending.get(self.next_change) {
            if !due(c.time, t, 2.0 * half) {
                break;
            }
            let c = c.clone();
            self.next_change += 1;
            if let Err(e) = self.set(&c.key, &c.value) {
                self.run.message = format!("changes: {e}");
            }
            made = true;
        }
        made
    }

    /// Sets the dotted `key` (one of [`SETTABLE`]) to `value` from the next step: the new
    /// configuration is checked as a whole ([`settable_config`]), then the parts that depend on
    /// the key are updated (the speed setpoint's target, the controller's gains and limit, its
    /// state kept, a new controller type taking over at the last motor torque, the wall
    /// friction's limits, the bit's load, the hoist's command). A changed target replaces the
    /// `steps` entries that have taken effect.
    pub fn set(&mut self, key: &str, value: &Value) -> Result<()> {
        let t = self.t();
        let mut cfg = settable_config(&self.sim.cfg, key, value)?;
        let sim = &mut self.sim;
        let dt = sim.grid.dt;
        let done = |s: &[f64; 2]| s[0] <= t + 0.5 * dt;
        if key == "top_drive.rpm" {
            cfg.top_drive.steps.retain(|s| !done(s));
        }
        if let Some(h) = &mut cfg.hoist {
            if matches!(key, "hoist.mode" | "hoist.speed" | "hoist.hook_load" | "hoist.weight_on_bit")
                || key == "hoist.autodriller.setpoint"
            {
                h.steps.retain(|s| !done(s));
            }
        }
        if key.starts_with("top_drive.") {
            let mut drive = Top::new(&cfg, &sim.grid, sim.first_mode)?;
            if cfg.top_drive.controller.kind == sim.cfg.top_drive.controller.kind {
                drive.carry(&sim.drive);
            } else {
                drive.hold(self.last.0);
            }
            sim.drive = drive;
            let omega = sim.top.omega;
            sim.top = TopDriveEnd::new(&cfg, dt);
            sim.top.omega = omega;
            (self.run.stats.kp, self.run.stats.ki) = gains(&cfg, &sim.grid, sim.first_mode);
        }
        if key.starts_with("bit.") {
            sim.bit = BitEnd { omega: sim.bit.omega, ..BitEnd::new(&cfg) };
        }
        if key.starts_with("friction.") {
            let grid = Grid::new(&cfg)?;
            let mut wall = WallFriction::torsional(&cfg, &grid, &sim.torsion.field);
            let coupled = match (&sim.axial, &sim.coupled_friction) {
                (Some(ax), Some(old)) => Some((
                    CoupledFriction::new(&cfg, &grid, &sim.torsion.field, &ax.field, &ax.half_kicks())?,
                    old.end_hold(),
                )),
                _ => None,
            };
            if let (Some((cf, hold)), Some(ax)) = (coupled, &mut sim.axial) {
                if cf.is_some() {
                    wall.off();
                    ax.end_hold = hold;
                }
                sim.coupled_friction = cf;
            }
            sim.torsion.sources = Sources::new(&cfg, dt);
            sim.grid = grid;
            sim.torsion.wall = wall;
        }
        if let (Some(ax), Some(h)) = (&mut sim.axial, &cfg.hoist) {
            if key.starts_with("hoist.") {
                ax.set_hoist(h.clone());
            }
        }
        sim.cfg = cfg;
        self.applied.push(Change { time: t, key: key.to_string(), value: value.clone() });
        Ok(())
    }

    /// [`Session::set`] of a value given as JSON text.
    pub fn set_json(&mut self, key: &str, value_json: &str) -> Result<()> {
        let value: Value = serde_json::from_str(value_json)
            .map_err(|e| crate::error::Error::invalid(key, format!("text that is not JSON ({e})"), "a JSON value"))?;
        self.set(key, &value)
    }

    /// The state at the time reached.
    pub fn state(&self) -> SessionState {
        let sim = &self.sim;
        let (omega, torque) = sim.fields();
        let sticks = sim.torsion.sources.sticks();
        let stuck = omega.iter().zip(&sim.grid.limit).map(|(&w, &lim)| sticks && lim > 0.0 && w == 0.0).collect();
        let (mut az, mut av, mut af) = (Vec::new(), Vec::new(), Vec::new());
        if let Some(ax) = &sim.axial {
            az.clone_from(&ax.z);
            ax.each_cell(|v, f| {
                av.push(v);
                af.push(f);
            });
        }
        SessionState {
            t_s: self.t(),
            z_m: sim.grid.z.clone(),
            omega_rpm: omega.iter().map(|w| w * RPM_PER_RAD_S).collect(),
            torque_nm: torque,
            contact_n_per_m: sim.grid.normal.clone(),
            stuck,
            axial_z_m: az,
            axial_speed_m_per_s: av,
            axial_force_n: af,
            surface_rpm: sim.top.omega * RPM_PER_RAD_S,
            bit_rpm: sim.bit_speed() * RPM_PER_RAD_S,
            motor_torque_nm: self.last.0,
            bit_torque_nm: self.last.1,
        }
    }

    /// The result of what was stepped: the series, the energy balance, the metrics over
    /// `window` (default `metrics.window`, else the last half of what was stepped, of the
    /// duration when stepped to it) and the warnings.
    pub fn result(&self, window: Option<[f64; 2]>) -> DrillRun {
        finished(&self.sim, self.run.clone(), self.initial, self.steps, window, self.batch)
    }

    /// Steps to `numerics.duration` and finishes: the batch run.
    pub(super) fn run_to_end(mut self, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> DrillRun {
        if self.run.status != Status::Success {
            return self.run;
        }
        let steps = duration_steps(self.sim.cfg.numerics.duration, self.sim.grid.dt);
        if self.advance(steps, interrupt, progress) {
            self.run.status = Status::Interrupted;
            self.run.message = format!("interrupted at t = {} s", Num(self.t()));
        }
        let run = std::mem::replace(&mut self.run, empty_like());
        let out = finished(&self.sim, run, self.initial, self.steps, None, true);
        progress(1.0);
        out
    }
}

/// Keeps the first `rows` samples of `run`'s series and its first `snapshots` field snapshots.
fn truncate(run: &mut DrillRun, rows: usize, snapshots: usize) {
    for v in [&mut run.t, &mut run.surface_rpm, &mut run.bit_rpm, &mut run.motor_torque, &mut run.bit_torque] {
        v.truncate(rows);
    }
    for v in [
        &mut run.bit_axial_speed,
        &mut run.rop,
        &mut run.weight_on_bit,
        &mut run.hook_load,
        &mut run.bit_depth,
        &mut run.depth_of_cut,
        &mut run.block_position,
    ] {
        v.truncate(rows);
    }
    let (cells, axial_cells) = (run.z.len(), run.axial_z.len());
    run.field_t.truncate(snapshots);
    run.omega_field.truncate(snapshots * cells);
    run.torque_field.truncate(snapshots * cells);
    run.axial_speed_field.truncate(snapshots * axial_cells);
    run.axial_force_field.truncate(snapshots * axial_cells);
}

/// An empty run: the base of a new one ([`Session::start`]), and what [`Session::run`] leaves
/// behind when it moves the run out.
fn empty_like() -> DrillRun {
    DrillRun {
        t: Vec::new(),
        surface_rpm: Vec::new(),
        bit_rpm: Vec::new(),
        motor_torque: Vec::new(),
        bit_torque: Vec::new(),
        field_t: Vec::new(),
        z: Vec::new(),
        omega_field: Vec::new(),
        torque_field: Vec::new(),
        bit_axial_speed: Vec::new(),
        rop: Vec::new(),
        weight_on_bit: Vec::new(),
        hook_load: Vec::new(),
        bit_depth: Vec::new(),
        depth_of_cut: Vec::new(),
        block_position: Vec::new(),
        axial_z: Vec::new(),
        axial_speed_field: Vec::new(),
        axial_force_field: Vec::new(),
        coupled: None,
        energy: EnergyBalance::default(),
        metrics: None,
        window: [f64::NAN; 2],
        breakoff_torque: f64::NAN,
        min_cycle_torque: f64::NAN,
        status: Status::Success,
        message: String::new(),
        warnings: Vec::new(),
        metrics_finite: false,
        rotating: false,
        stats: DrillStats::default(),
    }
}

/// `run` (the series of `steps` steps of `sim`, from the stored energy `initial`) finished:
/// the energy balance, the metrics over `window` and the warnings. The default window is
/// `metrics.window`, else the last half of the duration (`batch`, or a session stepped to
/// the duration), else of what was stepped.
fn finished(
    sim: &Simulation,
    mut run: DrillRun,
    initial: f64,
    steps: u64,
    window: Option<[f64; 2]>,
    batch: bool,
) -> DrillRun {
    let cfg = &sim.cfg;
    let dt = sim.grid.dt;
    let t = steps as f64 * dt;
    let duration = cfg.numerics.duration;
    let at_duration = steps == duration_steps(duration, dt);
    if at_duration && !batch {
        // the batch run's samples: its last step may end past a sample time after the duration
        truncate(&mut run, cfg.series_samples(), cfg.field_samples());
    }
    let end = if batch || at_duration { duration } else { t };
    run.window = window.or(cfg.metrics.window).unwrap_or([0.5 * end, end]);
    let breakoff = breakoff_torque(cfg).unwrap_or(f64::NAN);
    run.breakoff_torque = breakoff;
    run.min_cycle_torque = min_cycle_torque(cfg, breakoff);
    run.warnings = run_warnings(cfg, breakoff);
    sim.courant_peak(&mut run);
    let (energy, finite) = if cfg.numerics.energy_balance {
        sim.ledger.balance(initial, sim.stored())
    } else {
        run.warnings.push(NOT_KEPT.to_string());
        (EnergyBalance::not_kept(), sim.stored().total().is_finite())
    };
    run.energy = energy;
    if run.status == Status::Success && !finite {
        run.status = Status::NonFinite;
        run.message = format!("the energy became non-finite by t = {} s", Num(t));
    }
    metrics(cfg, &mut run);
    let share = torque_limit_share(&run.t, &run.motor_torque, run.window, cfg.top_drive.torque_limit);
    // (a limit below the static torque has its own warning: the motor may never break it free)
    let verdict = torque_limit_warning(cfg, breakoff).is_none().then(|| torque_limit_verdict(cfg, share)).flatten();
    if let Some((warning, reason)) = verdict {
        run.warnings.push(warning);
        if let Some(m) = &mut run.metrics {
            m.stick_slip_verdict = Verdict::Undetermined;
            m.stick_slip_reason = reason.into();
        }
    }
    if let Some(ax) = &sim.axial {
        let sections: Vec<(f64, usize, f64)> =
            ax.field.sections.iter().map(|s| (s.h * s.cells as f64, s.cells, s.courant)).collect();
        run.warnings.extend(axial_resolution_warning(&sections));
        run.coupled = coupled_metrics(&run, cfg.bit.radius);
        if let (Some(c), Some(why)) = (&run.coupled, axial_transient(&run)) {
            if c.regime == Regime::Undetermined
                && run.metrics.as_ref().is_some_and(|m| m.stick_slip_verdict == Verdict::No)
            {
                run.warnings.push(format!(
                    "regime undetermined, not smooth drilling: {why}; the string is still settling onto the bit \
                     (lengthen numerics.duration, move metrics.window later, or start from \
                     numerics.initial_state = \"steady\")"
                ));
            }
        }
    }
    run.rotating = rotation_commanded(cfg);
    if let (Some(c), Some(h)) = (&run.coupled, &cfg.hoist) {
        // (a string lifted without rotation is a pick-up, off bottom on purpose; lifted while
        // turning, the sign of hoist.speed may be the mistake)
        if run.rotating || !lifting(h) {
            run.warnings.extend(off_bottom_warning(c.bounce_fraction, run.window, h.mode));
        }
    }
    run.metrics_finite = run.metrics.as_ref().is_some_and(|m| non_finite_metrics_warning(m).is_none());
    if run.rotating || cfg.hoist.is_none() {
        run.warnings.extend(run.metrics.as_ref().and_then(non_finite_metrics_warning));
    } else if !run.metrics_finite {
        run.warnings.push(NO_ROTATION.to_string());
    }
    run.warnings.extend(transient_warning(&run.t, &run.surface_rpm, &run.motor_torque, run.window));
    run
}

#[cfg(test)]
#[path = "session_tests.rs"]
mod tests;
