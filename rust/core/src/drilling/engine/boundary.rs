//! The ends of the string. A boundary meets the characteristic arriving at its end
//! ([`Arriving`]: the invariant and the impedance it travels with) and sets the end's speed
//! for the step; the string then carries the load `Z (Omega' - beta_1)` at the top and
//! `Z (alpha_n - w')` at the bottom. With a lumped inertia `I` at the end (implicit Euler),
//! the end's momentum balance with the characteristic folded in is the line [`EndLine`],
//! `(I / dt + Z) w' = I w / dt + Z value - load`, and a law at the end is a (set-valued)
//! relation between `w'` and `load` that meets it.
//!
//! * top: [`TopDriveEnd`], an inertia driven by the motor, which carries out a controller's
//!   [`Command`] within its torque limit and speed-loop lag, or is given its speed
//!   ([`Command::Imposed`], a measured surface speed) with the torque that imposes it
//!   ([`imposing_torque`]);
//! * bottom: [`BitEnd`], the BHA inertia with a bit law of the torsional field alone
//!   ([`super::bit_law`]: a free end, or the velocity-weakening bit torque of
//!   [`crate::drilling::bit`] with its stick phase); a law that needs the axial field meets
//!   both fields' lines at once in [`super::axial`].

use super::bit_law::{BitEnds, Law};
use super::controller::Command;
use super::energy::Ledger;
use crate::drilling::config::DrillConfig;

/// The characteristic arriving at an end and the impedance it travels with.
#[derive(Debug, Clone, Copy)]
pub struct Arriving {
    pub value: f64,
    pub impedance: f64,
}

/// An end's momentum balance over a step: `denom w' = drive - load`, with `drive = I w / dt +
/// Z value` and `denom = I / dt + Z` (the end's inertia `I`, speed `w` at the step start).
#[derive(Debug, Clone, Copy)]
pub struct EndLine {
    pub drive: f64,
    pub denom: f64,
}

impl EndLine {
    /// The line of an end of inertia `inertia` at speed `speed` meeting `arriving`.
    #[inline]
    pub fn new(inertia: f64, speed: f64, dt: f64, arriving: Arriving) -> Self {
        EndLine {
            drive: inertia * speed / dt + arriving.impedance * arriving.value,
            denom: inertia / dt + arriving.impedance,
        }
    }

    /// The end's speed under `load`.
    #[inline]
    pub fn speed(&self, load: f64) -> f64 {
        (self.drive - load) / self.denom
    }
}

/// The motor torque that takes the top drive (inertia `inertia`) from `omega` to `omega1` over a
/// step of `dt` against the characteristic `arriving` (implicit Euler, as [`EndLine`]):
/// `I (omega1 - omega) / dt + Z (omega1 - beta_1)`, the inertia's acceleration torque plus the
/// string torque at the top. It is the torque a drive measures (its motor's), so that a model
/// driven by a measured speed gives a torque comparable with the measured one.
#[inline]
pub fn imposing_torque(inertia: f64, omega: f64, omega1: f64, dt: f64, arriving: Arriving) -> f64 {
    inertia * (omega1 - omega) / dt + arriving.impedance * (omega1 - arriving.value)
}

/// The top drive: its inertia and speed, the motor's torque limit and speed-loop lag.
#[derive(Debug, Clone, Copy)]
pub struct TopDriveEnd {
    /// rad/s.
    pub omega: f64,
    pub inertia: f64,
    limit: f64,
    /// `1 - exp(-2 pi motor_bandwidth dt)`, the fraction of the speed asked for the top
    /// reaches in a step.
    motor_lag: f64,
}

impl TopDriveEnd {
    pub fn new(cfg: &DrillConfig, dt: f64) -> Self {
        let td = &cfg.top_drive;
        TopDriveEnd {
            omega: 0.0,
            inertia: td.inertia,
            limit: td.torque_limit,
            motor_lag: 1.0 - (-2.0 * std::f64::consts::PI * td.motor_bandwidth * dt).exp(),
        }
    }

    /// Carries out `command` over a step: returns the new top speed, the motor torque and the
    /// string torque at the top, and books the motor's work and the inertia's dissipation.
    #[inline]
    pub fn step(&mut self, command: Command, arriving: Arriving, dt: f64, ledger: &mut Ledger) -> (f64, f64, f64) {
        let (beta1, z0) = (arriving.value, arriving.impedance);
        let inertia = self.inertia;
        let omega = self.omega;
        let implicit = |tm: f64| (inertia * omega / dt + tm + z0 * beta1) / (inertia / dt + z0);
        let (omega1, motor) = match command {
            Command::Torque(tm) => (implicit(tm), tm),
            Command::Imposed(wanted) => (wanted, imposing_torque(inertia, omega, wanted, dt, arriving)),
            Command::Speed(wanted) => {
                // The motor's speed loop: a first-order lag towards the speed asked for.
                let wanted = omega + (wanted - omega) * self.motor_lag;
                let tm = imposing_torque(inertia, omega, wanted, dt, arriving);
                if tm.abs() <= self.limit {
                    (wanted, tm)
                } else {
                    let tm = tm.clamp(-self.limit, self.limit);
                    (implicit(tm), tm)
                }
            }
        };
        ledger.motor += dt * motor * omega1;
        ledger.inertia += 0.5 * inertia * (omega1 - omega) * (omega1 - omega);
        self.omega = omega1;
        (omega1, motor, z0 * (omega1 - beta1))
    }
}

/// The bit: the BHA inertia and its law.
#[derive(Debug, Clone, Copy)]
pub struct BitEnd {
    /// rad/s.
    pub omega: f64,
    pub inertia: f64,
    pub law: Law,
}

impl BitEnd {
    pub fn new(cfg: &DrillConfig) -> Self {
        BitEnd { omega: 0.0, inertia: cfg.bit.bha_inertia, law: Law::new(cfg) }
    }

    /// One step against `arriving`: returns the new bit speed and the bit torque, and books
    /// the bit's work and the BHA inertia's dissipation (in a step where the bit sticks the
    /// BHA's kinetic energy is taken by the bit torque).
    #[inline]
    pub fn step(&mut self, arriving: Arriving, dt: f64, ledger: &mut Ledger) -> (f64, f64) {
        let (ib, wb) = (self.inertia, self.omega);
        let ends = BitEnds { torsion: EndLine::new(ib, wb, dt, arriving), omega: wb, axial: None };
        let c = self.law.resolve(&ends);
        let (wb1, tbit) = (c.angular_speed, c.torque_on_bit);
        ledger.bit += dt * tbit * wb1;
        let stop = 0.5 * ib * (wb1 - wb) * (wb1 - wb);
        if wb1 == 0.0 && tbit != 0.0 {
            ledger.bit += stop;
        } else {
            ledger.inertia += stop;
        }
        self.omega = wb1;
        (wb1, tbit)
    }
}
