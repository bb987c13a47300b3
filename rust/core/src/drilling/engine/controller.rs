//! What drives the top of the torsional field (see [`super`], "Controllers"): the trait
//! [`TopCommand`], implemented by the controllers, which read the top speed and the
//! characteristic arriving at the top and ask the motor for a torque ([`Command::Torque`]:
//! [`Pi`] for `pi` and `soft_torque`) or a speed ([`Command::Speed`]: [`SpeedControl`] for
//! `speed`, [`ZTorque`]), and by the measured surface speed of `top_drive.mode =
//! "measured_speed"` ([`SpeedSeries`], [`Command::Imposed`]); registered in [`Top`], which the
//! run holds and matches once per step. The top drive ([`super::boundary::TopDriveEnd`]) carries
//! the command out. Also the setpoint and the stability check of the sampled loop.

use std::f64::consts::PI;

use super::boundary::Arriving;
use crate::drilling::config::{ControllerKind, DrillConfig, TopDrive, TopMode};
use crate::drilling::grid::Grid;
use crate::error::{Error, Num, Result};

/// rpm per rad/s.
pub const RPM_PER_RAD_S: f64 = 60.0 / (2.0 * PI);

/// What a controller asks of the motor for a step.
#[derive(Debug, Clone, Copy)]
pub enum Command {
    /// A motor torque, N m (within the torque limit).
    Torque(f64),
    /// A top speed, rad/s, which the motor's speed loop follows.
    Speed(f64),
    /// The top speed at the step's end, rad/s, imposed exactly (no lag, no torque limit): a
    /// measured surface speed ([`SpeedSeries`]).
    Imposed(f64),
}

/// What a step's top command is computed from.
#[derive(Debug, Clone, Copy)]
pub struct TopInput {
    /// The step's start, s, and its length, s.
    pub t: f64,
    pub dt: f64,
    /// The speed setpoint at the step's end, rad/s.
    pub setpoint: f64,
    /// The top speed at the step's start, rad/s.
    pub omega: f64,
    /// The characteristic arriving at the top.
    pub arriving: Arriving,
}

/// What drives the top of the torsional field: it reads the top speed, the setpoint and the
/// characteristic arriving at the top, and gives the top drive ([`super::boundary::TopDriveEnd`])
/// its [`Command`] for the step. The controllers and the measured surface speed implement it;
/// the run holds one [`Top`], matched once per step.
pub trait TopCommand {
    /// The command for the step `input`.
    fn command(&mut self, td: &TopDrive, input: &TopInput) -> Command;

    /// Takes the string torque at the top after the step, N m.
    fn observe(&mut self, _tau_top: f64) {}

    /// Sets the state that holds the top at its setpoint against the string torque `torque`
    /// (N m) at the top: a run started in steady rotation
    /// ([`crate::drilling::start::InitialState::Steady`]), or a controller taking over during a
    /// run at the last motor torque.
    fn hold(&mut self, _torque: f64) {}

    /// Takes over the running state of `old`, the same kind with new gains or limit.
    fn carry(&mut self, _old: &Self)
    where
        Self: Sized,
    {
    }
}

/// `pi` and `soft_torque`: a PI on the speed error sampled in a zero-order hold at
/// `control_interval`, with anti-windup at the torque limit.
#[derive(Debug, Clone, Copy)]
pub struct Pi {
    pub kp: f64,
    pub ki: f64,
    limit: f64,
    integral: f64,
    torque: f64,
    next: f64,
}

impl TopCommand for Pi {
    #[inline]
    fn command(&mut self, td: &TopDrive, input: &TopInput) -> Command {
        let (t, dt) = (input.t, input.dt);
        if t + 0.5 * dt >= self.next {
            let mut holds = 0.0;
            while self.next <= t + 0.5 * dt {
                self.next += td.control_interval;
                holds += 1.0;
            }
            let e = input.setpoint - input.omega;
            let raw = self.kp * e + self.ki * self.integral;
            self.torque = raw.clamp(-self.limit, self.limit);
            // Anti-windup: no integration while saturated in the error's direction.
            if !((raw > self.limit && e > 0.0) || (raw < -self.limit && e < 0.0)) {
                self.integral += holds * td.control_interval * e;
            }
        }
        Command::Torque(self.torque)
    }

    /// The integral `torque / ki` (the command at zero speed error; without an integral gain
    /// the command stays 0).
    fn hold(&mut self, torque: f64) {
        if self.ki > 0.0 {
            self.integral = torque.clamp(-self.limit, self.limit) / self.ki;
        }
    }

    /// The integral, the torque held and the next sample time.
    fn carry(&mut self, old: &Self) {
        self.integral = old.integral;
        self.torque = old.torque.clamp(-self.limit, self.limit);
        self.next = old.next;
    }
}

/// `z_torque`: the top presents the damper `z Z` to torque waves,
/// `Omega = w_ref - (tau - tau_slow) / (z Z)` with `tau = Z (Omega - beta_1)`.
#[derive(Debug, Clone, Copy)]
pub struct ZTorque {
    z_factor: f64,
    /// The low-passed string torque at the top, N m.
    slow_torque: f64,
    slow_factor: f64,
}

impl TopCommand for ZTorque {
    #[inline]
    fn command(&mut self, _td: &TopDrive, input: &TopInput) -> Command {
        let (z, a) = (self.z_factor, input.arriving);
        Command::Speed((z * input.setpoint + a.value + self.slow_torque / a.impedance) / (z + 1.0))
    }

    #[inline]
    fn observe(&mut self, tau_top: f64) {
        self.slow_torque += (tau_top - self.slow_torque) * self.slow_factor;
    }

    fn hold(&mut self, torque: f64) {
        self.slow_torque = torque;
    }

    fn carry(&mut self, old: &Self) {
        self.slow_torque = old.slow_torque;
    }
}

/// `speed`: the top speed asked for is the setpoint.
#[derive(Debug, Clone, Copy)]
pub struct SpeedControl;

impl TopCommand for SpeedControl {
    #[inline]
    fn command(&mut self, _td: &TopDrive, input: &TopInput) -> Command {
        Command::Speed(input.setpoint)
    }
}

impl TopCommand for SpeedSeries {
    /// The series' speed at the step's end, imposed.
    #[inline]
    fn command(&mut self, _td: &TopDrive, input: &TopInput) -> Command {
        Command::Imposed(self.at(input.t + input.dt))
    }

    /// The cursor (the series is the configuration's, which does not change during a run).
    fn carry(&mut self, old: &Self) {
        self.cursor = old.cursor;
    }
}

/// What drives the top, registered (`top_drive.mode`, `top_drive.controller.type`).
#[derive(Debug, Clone)]
pub enum Top {
    /// `pi`, `soft_torque`.
    Pi(Pi),
    ZTorque(ZTorque),
    Speed(SpeedControl),
    /// `top_drive.mode = "measured_speed"`.
    Measured(SpeedSeries),
    #[cfg(test)]
    Test(super::top_tests::ConstantTorque),
}

/// Dispatches a call to the variant's [`TopCommand`] implementation.
macro_rules! each_top {
    ($top:expr, $c:ident => $call:expr) => {
        match $top {
            Top::Pi($c) => $call,
            Top::ZTorque($c) => $call,
            Top::Speed($c) => $call,
            Top::Measured($c) => $call,
            #[cfg(test)]
            Top::Test($c) => $call,
        }
    };
}

/// The controller gains `(kp, ki)` of a configuration: `soft_torque`'s tuned with the string's
/// first natural frequency `first_mode` (rad/s) unless `tuning_frequency` is given, else the
/// configuration's `kp` and `ki`.
pub fn gains(cfg: &DrillConfig, grid: &Grid, first_mode: f64) -> (f64, f64) {
    let td = &cfg.top_drive;
    let c = &td.controller;
    match c.kind {
        ControllerKind::SoftTorque => {
            let w = c.tuning_frequency.map_or(first_mode, |f| 2.0 * PI * f);
            crate::drilling::tuning::soft_torque_gains(c.z_factor, grid.props[0].impedance, w, td.inertia)
        }
        _ => (c.kp, c.ki),
    }
}

impl Top {
    /// What drives the top in a configuration (gains by [`gains`]), a controller refused when
    /// the sampled loop is unstable on this grid ([`check_control_loop`]).
    pub fn new(cfg: &DrillConfig, grid: &Grid, first_mode: f64) -> Result<Self> {
        let td = &cfg.top_drive;
        let c = &td.controller;
        if let Some(series) = SpeedSeries::new(td) {
            return Ok(Top::Measured(series));
        }
        let (kp, ki) = gains(cfg, grid, first_mode);
        check_control_loop(cfg, grid, kp)?;
        Ok(match c.kind {
            ControllerKind::Pi | ControllerKind::SoftTorque => {
                Top::Pi(Pi { kp, ki, limit: td.torque_limit, integral: 0.0, torque: 0.0, next: 0.0 })
            }
            ControllerKind::ZTorque => Top::ZTorque(ZTorque {
                z_factor: c.z_factor,
                slow_torque: 0.0,
                slow_factor: 1.0 - (-grid.dt / c.torque_highpass_time).exp(),
            }),
            ControllerKind::Speed => Top::Speed(SpeedControl),
        })
    }

    /// [`TopCommand::command`] of the variant.
    #[inline]
    pub fn command(&mut self, td: &TopDrive, input: &TopInput) -> Command {
        each_top!(self, c => c.command(td, input))
    }

    /// [`TopCommand::observe`] of the variant.
    #[inline]
    pub fn observe(&mut self, tau_top: f64) {
        each_top!(self, c => c.observe(tau_top))
    }

    /// [`TopCommand::hold`] of the variant.
    pub fn hold(&mut self, torque: f64) {
        each_top!(self, c => c.hold(torque))
    }

    /// [`TopCommand::carry`] from `old` of the same variant (nothing from another).
    pub fn carry(&mut self, old: &Top) {
        match (self, old) {
            (Top::Pi(c), Top::Pi(o)) => c.carry(o),
            (Top::ZTorque(c), Top::ZTorque(o)) => c.carry(o),
            (Top::Speed(c), Top::Speed(o)) => c.carry(o),
            (Top::Measured(c), Top::Measured(o)) => c.carry(o),
            _ => {}
        }
    }
}

/// The speed setpoint: a first-order approach (time constant `ramp_time`, exact over each
/// step) of the target, `rpm` then `steps`. A step's target is the target at the step's
/// middle ([`Setpoint::advance`]): a `steps` entry at `T` takes effect from the step starting
/// at the step boundary nearest `T`, the step a change made at that time during a run
/// ([`super::session::Session::set`], a `[[changes]]` entry) takes effect from.
#[derive(Debug, Clone, Copy, Default)]
pub struct Setpoint {
    /// rad/s.
    pub value: f64,
    /// `1 - exp(-dt / ramp_time)`, the fraction of the way to the target made in a step
    /// (`None` without a ramp).
    approach: Option<f64>,
}

impl Setpoint {
    /// The target at time `t`, rad/s.
    pub fn target(td: &TopDrive, t: f64) -> f64 {
        let rpm = td.steps.iter().rev().find(|s| s[0] <= t).map_or(td.rpm, |s| s[1]);
        rpm / RPM_PER_RAD_S
    }

    /// At rest, for steps of `dt`.
    pub fn new(td: &TopDrive, dt: f64) -> Self {
        let ramp = td.ramp_time;
        Setpoint { value: 0.0, approach: (ramp > 0.0).then(|| 1.0 - (-dt / ramp).exp()) }
    }

    /// Advances over the step from `t` of length `dt` towards the target at its middle
    /// `t + dt / 2`; returns the value at its end.
    #[inline]
    pub fn advance(&mut self, td: &TopDrive, t: f64, dt: f64) -> f64 {
        let target = Self::target(td, t + 0.5 * dt);
        self.value = match self.approach {
            Some(f) => self.value + (target - self.value) * f,
            None => target,
        };
        self.value
    }

    /// The largest speed the setpoint takes (`measured_speed`: the series), rad/s.
    pub fn fastest(td: &TopDrive) -> f64 {
        let rpm = match td.mode {
            TopMode::Controller => td.steps.iter().map(|s| s[1].abs()).fold(td.rpm.abs(), f64::max),
            TopMode::MeasuredSpeed => td.speed_series.iter().map(|s| s[1].abs()).fold(0.0, f64::max),
        };
        rpm / RPM_PER_RAD_S
    }
}

/// `top_drive.mode = "measured_speed"`: the top speed, the series `top_drive.speed_series`
/// interpolated linearly (held at its ends), rad/s.
#[derive(Debug, Clone, Default)]
pub struct SpeedSeries {
    t: Vec<f64>,
    /// rad/s.
    omega: Vec<f64>,
    /// The interval of the last time asked for (times are asked in increasing order).
    cursor: usize,
}

impl SpeedSeries {
    /// The series of a configuration (None with `mode = "controller"`).
    pub fn new(td: &TopDrive) -> Option<Self> {
        (td.mode == TopMode::MeasuredSpeed).then(|| SpeedSeries {
            t: td.speed_series.iter().map(|p| p[0]).collect(),
            omega: td.speed_series.iter().map(|p| p[1] / RPM_PER_RAD_S).collect(),
            cursor: 0,
        })
    }

    /// The speed at `t`, rad/s.
    #[inline]
    pub fn at(&mut self, t: f64) -> f64 {
        let (ts, ws) = (&self.t, &self.omega);
        let last = ts.len() - 1;
        if t <= ts[0] {
            return ws[0];
        }
        if t >= ts[last] {
            return ws[last];
        }
        if ts[self.cursor] > t {
            self.cursor = 0;
        }
        while ts[self.cursor + 1] < t {
            self.cursor += 1;
        }
        let k = self.cursor;
        let f = (t - ts[k]) / (ts[k + 1] - ts[k]);
        ws[k] + f * (ws[k + 1] - ws[k])
    }
}

/// Refuses a proportional gain that the sampled controller loop cannot hold on this grid.
///
/// The `pi` and `soft_torque` torque is computed from the top speed at a sample and held for
/// `h = max(dt, control_interval)`; the top drive then answers implicitly,
/// `(I / h + Z) Omega' = I / h Omega + kp (setpoint - Omega) + ...`, so the speed error is
/// multiplied by `(I / h - kp) / (I / h + Z)` per sample: the loop oscillates with a growing
/// amplitude (speeds of 1e52 rpm on 1 to 4 cells) unless `kp < 2 I / h + Z`. The error names
/// `numerics.cells` (with the count that holds) when the step is the longer, else the gain.
pub fn check_control_loop(cfg: &DrillConfig, grid: &Grid, kp: f64) -> Result<()> {
    let td = &cfg.top_drive;
    let c = &td.controller;
    if !matches!(c.kind, ControllerKind::Pi | ControllerKind::SoftTorque) {
        return Ok(());
    }
    let z = grid.props[0].impedance;
    let h = grid.dt.max(td.control_interval);
    let bound = 2.0 * td.inertia / h + z;
    if kp < bound {
        return Ok(());
    }
    let gain = if c.kind == ControllerKind::Pi { "top_drive.controller.kp" } else { "top_drive.controller.z_factor" };
    if grid.dt > td.control_interval && kp > z {
        // the step that holds: dt < 2 I / (kp - Z), on the same travel time
        let needed = (grid.cells() as f64 * grid.dt * (kp - z) / (2.0 * td.inertia)).floor() + 1.0;
        return Err(Error::invalid(
            "numerics.cells",
            cfg.numerics.cells,
            format!(
                "at least {} cells: with a step of {} s the controller's gain {gain} = {} N m s/rad is at \
                 least 2 I / dt + Z = {} N m s/rad, and the sampled top-drive loop is unstable",
                Num(needed),
                Num(grid.dt),
                Num(kp),
                Num(bound)
            ),
        ));
    }
    Err(Error::invalid(
        gain,
        Num(if c.kind == ControllerKind::Pi { kp } else { c.z_factor }),
        format!(
            "a gain below 2 I / control_interval + Z = {} N m s/rad (kp here {} N m s/rad): above it the sampled \
             top-drive loop is unstable; lower the gain or top_drive.control_interval",
            Num(bound),
            Num(kp)
        ),
    ))
}

#[cfg(test)]
#[path = "measured_tests.rs"]
mod measured_tests;
