//! The top drive's controllers and setpoint (see [`super`], "Controllers"): a controller reads
//! the top speed and the characteristic arriving at the top and asks the motor for a torque
//! ([`Command::Torque`]: `pi`, `soft_torque`) or a speed ([`Command::Speed`]: `speed`,
//! `z_torque`); the top drive ([`super::boundary::TopDriveEnd`]) carries it out. With
//! `top_drive.mode = "measured_speed"` the top speed is a given series instead ([`SpeedSeries`],
//! [`Command::Imposed`]).

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

/// The state of the controller.
#[derive(Debug, Clone, Copy)]
pub struct ControllerState {
    pub kind: ControllerKind,
    pub kp: f64,
    pub ki: f64,
    limit: f64,
    integral: f64,
    torque: f64,
    next: f64,
    z_factor: f64,
    /// `z_torque`: low-passed string torque at the top.
    slow_torque: f64,
    slow_factor: f64,
}

impl ControllerState {
    /// The controller of a configuration (gains tuned for `soft_torque` with the string's
    /// first natural frequency `first_mode`, rad/s), refused when the sampled loop is unstable
    /// on this grid ([`check_control_loop`]).
    pub fn new(cfg: &DrillConfig, grid: &Grid, first_mode: f64) -> Result<Self> {
        let td = &cfg.top_drive;
        let c = &td.controller;
        let (kp, ki) = match c.kind {
            ControllerKind::SoftTorque => {
                let w = c.tuning_frequency.map_or(first_mode, |f| 2.0 * PI * f);
                crate::drilling::tuning::soft_torque_gains(c.z_factor, grid.props[0].impedance, w, td.inertia)
            }
            _ => (c.kp, c.ki),
        };
        if td.mode == TopMode::Controller {
            check_control_loop(cfg, grid, kp)?;
        }
        Ok(ControllerState {
            kind: c.kind,
            kp,
            ki,
            limit: td.torque_limit,
            integral: 0.0,
            torque: 0.0,
            next: 0.0,
            z_factor: c.z_factor,
            slow_torque: 0.0,
            slow_factor: 1.0 - (-grid.dt / c.torque_highpass_time).exp(),
        })
    }

    /// The command for the step from `t` (length `dt`), with the top speed `omega` at its
    /// start and the characteristic arriving at the top.
    #[inline]
    pub fn command(
        &mut self,
        td: &TopDrive,
        t: f64,
        dt: f64,
        setpoint: f64,
        omega: f64,
        arriving: Arriving,
    ) -> Command {
        match self.kind {
            ControllerKind::Pi | ControllerKind::SoftTorque => {
                if t + 0.5 * dt >= self.next {
                    let mut holds = 0.0;
                    while self.next <= t + 0.5 * dt {
                        self.next += td.control_interval;
                        holds += 1.0;
                    }
                    let e = setpoint - omega;
                    let raw = self.kp * e + self.ki * self.integral;
                    self.torque = raw.clamp(-self.limit, self.limit);
                    // Anti-windup: no integration while saturated in the error's direction.
                    if !((raw > self.limit && e > 0.0) || (raw < -self.limit && e < 0.0)) {
                        self.integral += holds * td.control_interval * e;
                    }
                }
                Command::Torque(self.torque)
            }
            ControllerKind::Speed => Command::Speed(setpoint),
            ControllerKind::ZTorque => {
                // The top presents the damper z Z to torque waves: Omega = w_ref - (tau - tau_slow) / (z Z)
                // with tau = Z (Omega - beta_1).
                let z = self.z_factor;
                Command::Speed((z * setpoint + arriving.value + self.slow_torque / arriving.impedance) / (z + 1.0))
            }
        }
    }

    /// Sets the state that holds the top at its setpoint against the string torque `torque`
    /// (N m) at the top, for a run started in steady rotation
    /// ([`crate::drilling::start::InitialState::Steady`]): a PI's integral `torque / ki` (its
    /// command at zero speed error; without an integral gain the command stays 0), `z_torque`'s
    /// low-passed torque.
    pub fn hold(&mut self, torque: f64) {
        match self.kind {
            ControllerKind::Pi | ControllerKind::SoftTorque if self.ki > 0.0 => {
                self.integral = torque.clamp(-self.limit, self.limit) / self.ki;
            }
            ControllerKind::ZTorque => self.slow_torque = torque,
            _ => {}
        }
    }

    /// Takes over the running state of `old` (the integral, the torque held, the next sample
    /// time, `z_torque`'s low-passed torque): the same controller with new gains or limit
    /// continues where it was.
    pub fn carry(&mut self, old: &ControllerState) {
        self.integral = old.integral;
        self.torque = old.torque.clamp(-self.limit, self.limit);
        self.next = old.next;
        self.slow_torque = old.slow_torque;
    }

    /// Takes the string torque at the top after the step (`z_torque`'s low-pass).
    #[inline]
    pub fn observe(&mut self, tau_top: f64) {
        if self.kind == ControllerKind::ZTorque {
            self.slow_torque += (tau_top - self.slow_torque) * self.slow_factor;
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
