//! The time stepping of the drilling system: Riemann invariants on the cells, the impedance
//! junctions, the top drive and the bit, the controllers, the outputs and the energy balance.
//!
//! # The scheme
//!
//! With `tau` the torque carried down the string (`tau = -G J theta_z`) and `Z = J sqrt(G rho)`
//! the impedance, the invariants `alpha = omega + tau / Z` (travelling down at `c`) and
//! `beta = omega - tau / Z` (travelling up) obey
//! `alpha_t + c alpha_z = beta_t - c beta_z = -(f / (rho J) + d omega)` with `f` the friction
//! torque per metre and `d` the damping rate (Aarsnes & Shor 2018, eqs. 5-8 and
//! torsionalWaveStep.m). Each step (`dt`, common to all sections):
//!
//! 1. boundaries from the state at `t_n`: the top speed `Omega'` (top-drive inertia, implicit
//!    in the string torque `Z (Omega' - beta_1)`, or imposed by an ideal controller), the
//!    bit speed (BHA inertia, implicit likewise; on bottom the Navarro-Lopez torque
//!    `W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)` at the speed of the step start, with a
//!    stick phase: below `bit.stick_speed`, or when the slip torque would reverse the bit, the
//!    torque that stops it in this step if within `W r mu_s`, else `W r mu_s`), the junctions
//!    (continuity of speed and torque: `omega = (Z_a alpha_a + Z_b beta_b) / (Z_a + Z_b)`);
//!    each gives the ghost invariant entering its neighbouring cell (`alpha = 2 omega - beta`);
//! 2. first-order upwind transport, `alpha_j <- alpha_j - C (alpha_j - alpha_{j-1})` (exact
//!    shift at Courant number `C = 1`);
//! 3. the sources, added to both invariants, evaluated at the transported speed
//!    `omega*_j = (alpha*_j + beta*_j) / 2` (the material now in the cell): damping
//!    `-dt d omega*_j`, and friction: when `|omega*_j| < stick_speed` the torque that stops the
//!    cell in this step, clipped to the static limit (a stopped cell gets `omega = 0` exactly,
//!    its torque kept), else the kinetic limit against `omega*_j` (the set-valued resolution
//!    of torsionalWaveStep.m, which evaluates the threshold and direction at the speed before
//!    transport; with the speed after it, friction cannot pump energy into the grid-scale
//!    mode that the exact shift at Courant 1 leaves undamped), or `tanh(omega*_j / v_r)` times
//!    the kinetic limit (regularised).
//!
//! A stopped cell's new torque comes from its neighbours' invariants: at `C = 1` it is
//! `(tau_{j-1} + tau_{j+1}) / 2 + Z (omega_{j-1} - omega_{j+1}) / 2`, so inside a stuck region
//! the torque relaxes towards a linear profile (over `n` stuck cells in ~`n^2` steps) instead of
//! staying frozen as in the continuum; the scheme of torsionalWaveStep.m does the same.
//!
//! # The `consistent` nonlinearity
//!
//! With `nonlinearity = "consistent"` the torque is the finite-strain law of
//! [`crate::model::Model::Consistent`], `tau(eps) = k2 eps + k5 eps^3` (`eps = -theta_z` the
//! twist per length, `k2 = G J`, `k5 = M J4 / 2`), and the string is the p-system
//! `rho J omega_t = -tau(eps)_z - f - rho J d omega`, `eps_t = -omega_z`, whose local wave speed is
//! the tangent speed `sqrt((k2 + 3 k5 eps^2) / (rho J))` (hardening). The cells hold
//! `(omega, eps)` and the scheme is the first-order Godunov finite-volume scheme with the
//! acoustic (two-wave, Suliciu relaxation) Riemann solver: at a face between states `l` and
//! `r` the outgoing characteristics `omega_l + tau_l / Z_l` and `omega_r - tau_r / Z_r` meet,
//! `omega* = (Z_l (omega_l + tau_l / Z_l) + Z_r (omega_r - tau_r / Z_r)) / (Z_l + Z_r)`,
//! `tau* = Z_l (omega_l + tau_l / Z_l - omega*)`, with `Z_l = Z_r` the larger tangent impedance
//! `sqrt(rho J (k2 + 3 k5 eps^2))` of the two cells inside a section, each side's own at a
//! junction (continuity of speed and torque), and the cell's at the top drive and the bit,
//! which are solved exactly as above with `beta_1 = omega_1 - tau_1 / Z_1` and
//! `alpha_n = omega_n + tau_n / Z_n`. Then
//! `omega_j += dt (tau*_{j-1/2} - tau*_{j+1/2}) / (rho J h)`,
//! `eps_j += dt (omega*_{j-1/2} - omega*_{j+1/2}) / h`, and the same sources (damping, friction
//! with its stick phase: a stuck cell keeps its twist) at the transported speed. With `k5 = 0`
//! the face values are those of the invariants and the update is the upwind scheme above
//! (to rounding). The time step is made for the tangent speed at `numerics.max_shear_strain`
//! (Courant number `<= 1` at that strain; every section's wave speed is raised by the largest
//! hardening factor of the sections, so that sections of equal wave speeds keep whole numbers
//! of steps per travel time, [`Grid::speed`]); the run reports the largest tangent Courant number
//! met ([`DrillStats::courant_peak`]). The elastic energy is `sum h (k2 eps^2 / 2 + k5 eps^4 / 4)`
//! and the transport's dissipation (`upwind_loss`) is measured per cell as the energy the face
//! fluxes bring in (`dt tau* omega*`) less the cell's energy change, so the balance closes to
//! rounding and the scheme's first-order dissipation is reported (positive; it vanishes at
//! first order with `h` on smooth solutions).
//!
//! # Controllers
//!
//! * `pi`: `tau_m = kp e + ki int e`, `e = setpoint - Omega`, sampled in a zero-order hold at
//!   `control_interval`, as MAIN.m of Aarsnes & Shor (their `38e3`, `100e3`);
//! * `soft_torque`: the same PI with `kp = z_factor Z_top` and `ki = (2 pi f)^2 I_TD`, so that
//!   at the tuning frequency `f` the top drive's inertia and the integral cancel and it presents
//!   the damping `kp` to the string (Kyllingstad & Nessjøen, SPE/IADC 119660, 2009); the gains
//!   as in Open-Source-Drilling-Community/Simulator4nDOF, `Simulator/TopdriveController.cs`
//!   (commit b14d6c2, controller type 2, without its inertia compensation), `f` by default the
//!   string's first natural frequency;
//! * `z_torque`: impedance matching (ZTorque, Dwars, SPE/IADC 173037, 2015; Simulator4nDOF
//!   controller type 3, whose speed setpoint is lowered by the high-passed string torque over
//!   `Z`): here the ideal form, the top speed `Omega = w_ref - (tau_top - tau_slow) / (z Z_top)`
//!   every step (`tau_slow` the string torque low-passed with `torque_highpass_time`), which
//!   absorbs an incident torque wave completely at `z_factor = 1`;
//! * `speed`: the top speed is the setpoint.
//!
//! `speed` and `z_torque` ask for a top speed, which the motor's speed loop follows as a
//! first-order lag of time constant `1 / (2 pi top_drive.motor_bandwidth)` (exact over the
//! step), and infer the motor torque (`I_TD dOmega/dt + tau_top`, bounded as the grid is
//! refined); with `top_drive.torque_limit` exceeded they fall back to the clipped torque. The
//! `pi` and `soft_torque` gains are checked against the sampled loop's stability bound
//! `kp < 2 I_TD / max(dt, control_interval) + Z` before a run. The setpoint approaches its target (`rpm`, then `steps`) as a first-order lag of time
//! constant `ramp_time`, exactly over each step.
//!
//! # Energy
//!
//! With `e = rho J h / 4` per cell the discrete energy is `sum e (alpha^2 + beta^2)` (kinetic
//! `e (alpha + beta)^2 / 2`, elastic `e (alpha - beta)^2 / 2`) plus the top-drive and BHA
//! kinetic energies. Every step satisfies exactly (up to rounding)
//! `dt tau_m Omega' = dE + dt T_bit omega_bit' + friction + damping + numerical`, where the
//! friction and damping terms are the work of their sources (`4 e delta (omega* + delta / 2)`
//! per cell), and `numerical` the upwind dissipation `e C (1 - C) (d alpha^2 + d beta^2)` (0 at
//! `C = 1`) plus the implicit-Euler dissipation `I (Omega' - Omega)^2 / 2` of the top drive and
//! BHA (in a step where the bit sticks, the BHA's term counts as bit loss: the bit torque stops
//! it). The motor work is `sum dt tau_m Omega'`.

use std::f64::consts::PI;

use serde::Serialize;

use crate::error::{Error, Num, Result};
use crate::interrupt::{Interrupt, Poller};
use crate::metrics::{stick_slip, StickSlip};
use crate::solution::{serialize_list, Status};

use super::bit::slip_torque;
use super::config::{ControllerKind, DrillConfig, FrictionModel, Nonlinearity};
use super::grid::{breakoff_torque, first_natural_frequency, min_cycle_torque, static_torque, Grid, SectionProps};
use super::plausibility::{non_finite_metrics_warning, run_warnings, transient_warning};

const RPM_PER_RAD_S: f64 = 60.0 / (2.0 * PI);

/// A run whose top-drive or bit speed exceeds this many times the largest setpoint (or 1 rad/s)
/// has diverged: it ends with the status `non_finite` and a message saying so.
pub const RUNAWAY_FACTOR: f64 = 1000.0;

/// The energy balance of a run, J (from the start to the end reached).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// `sum dt tau_m Omega'`.
    pub motor_work: f64,
    /// Total energy at the start (string, top drive, BHA).
    pub initial: f64,
    /// At the end: string kinetic and elastic, top-drive and BHA kinetic.
    pub kinetic: f64,
    pub elastic: f64,
    pub top_drive: f64,
    pub bha: f64,
    pub friction_loss: f64,
    pub damping_loss: f64,
    pub bit_loss: f64,
    /// `upwind_loss + inertia_loss`.
    pub numerical_loss: f64,
    /// Dissipation of the first-order upwind transport: `linear`, `e C (1 - C) (d alpha^2 +
    /// d beta^2)` per cell and step (0 at Courant number 1); `consistent`, the energy the
    /// Godunov fluxes bring into a cell less its energy change in the transport.
    pub upwind_loss: f64,
    /// Dissipation of the implicit Euler steps of the top-drive and BHA inertias,
    /// `I (Omega' - Omega)^2 / 2` per step (first order in `dt`).
    pub inertia_loss: f64,
    /// `(motor_work - (final - initial) - losses) / scale`, `scale` the largest of
    /// `|motor_work|`, the energies and the losses.
    pub balance_error: f64,
}

/// Counters and discretisation of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct DrillStats {
    pub cells: usize,
    /// Time steps taken.
    pub steps: u64,
    pub dt: f64,
    /// Smallest and largest Courant number of the sections at the speed the step is made for
    /// (`linear`: `sqrt(G / rho)`; `consistent`: the tangent speed at `numerics.max_shear_strain`).
    pub courant_min: f64,
    pub courant_max: f64,
    /// The largest Courant number of the local wave speed met in the run: `courant_max` for
    /// `linear`; for `consistent` the tangent speed at the largest twist each section reached
    /// (above 1 when the strains exceeded `numerics.max_shear_strain`; the message says so).
    pub courant_peak: f64,
    /// The controller gains used (for `soft_torque`, the tuned ones), N m s/rad and N m/rad.
    pub kp: f64,
    pub ki: f64,
    /// First natural frequency of the string (fixed top, bit free or with the BHA), Hz.
    pub first_mode_hz: f64,
}

/// The result of a run (serialised without the metrics and what goes with them: `metrics`,
/// `window`, `breakoff_torque`, `min_cycle_torque`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DrillRun {
    /// Series at `k output_interval`: time s, top-drive and bit speed rpm, motor and bit torque N m.
    pub t: Vec<f64>,
    pub surface_rpm: Vec<f64>,
    pub bit_rpm: Vec<f64>,
    pub motor_torque: Vec<f64>,
    pub bit_torque: Vec<f64>,
    /// Snapshot times (the step nearest to `k field_interval`), s.
    pub field_t: Vec<f64>,
    /// Cell centres, m.
    pub z: Vec<f64>,
    /// `field_t.len() x z.len()`, row-major: speed rpm, torque N m.
    pub omega_field: Vec<f64>,
    pub torque_field: Vec<f64>,
    pub energy: EnergyBalance,
    /// Stick-slip metrics over the window (None when the window holds fewer than 2 samples).
    #[serde(skip)]
    pub metrics: Option<StickSlip>,
    /// The window `[t_start, t_end]` asked for.
    #[serde(skip)]
    pub window: [f64; 2],
    #[serde(skip)]
    pub breakoff_torque: f64,
    /// The minimum motor torque of a stick-slip cycle implied by break-off
    /// ([`super::grid::min_cycle_torque`]), N m.
    #[serde(skip)]
    pub min_cycle_torque: f64,
    pub status: Status,
    pub message: String,
    /// What the configuration makes doubtful (a torque limit the string's static torque
    /// exceeds); the metrics' own are [`StickSlip::warnings`].
    #[serde(serialize_with = "serialize_list")]
    pub warnings: Vec<String>,
    /// False when a headline metric is not finite or the window has none
    /// ([`super::plausibility::non_finite_metrics`]): not a result, whatever `status` says.
    pub metrics_finite: bool,
    pub stats: DrillStats,
}

/// The friction profile of a configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Profile {
    /// Cell centres, m.
    pub z: Vec<f64>,
    /// Static friction limit per metre, N m/m.
    pub limit_per_m: Vec<f64>,
    /// Static friction torque of the string below each cell centre (from the bit up), N m.
    pub cumulative: Vec<f64>,
    /// The integral of the limit over the string, N m.
    pub breakoff_torque: f64,
    /// The bit's static torque (on bottom; 0 off bottom), N m ([`super::grid::bit_static_torque`]).
    pub bit_static_torque: f64,
    /// The static torque the motor must exceed to break the string free: `breakoff_torque` plus
    /// `bit_static_torque`, N m ([`static_torque`]).
    pub static_torque: f64,
    /// The static torque the string holds at each cell centre at break-off: `cumulative` plus
    /// `bit_static_torque` (the bit's torque is carried along the whole string), N m.
    pub holding: Vec<f64>,
    /// The well at the cell centres (minimum curvature): inclination and azimuth, degrees,
    /// true vertical depth, m, and the curvature as a dogleg severity, degrees per 30 m.
    pub inclination_deg: Vec<f64>,
    pub azimuth_deg: Vec<f64>,
    pub tvd: Vec<f64>,
    pub dls_deg_per_30m: Vec<f64>,
    /// The static friction factor at the cell centres (`friction.static` or an interval's).
    pub friction_factor: Vec<f64>,
}

/// The friction profile at the cell centres and the break-off torque of a valid configuration.
pub fn friction_profile(cfg: &DrillConfig) -> Result<Profile> {
    cfg.validate()?;
    let grid = Grid::new(cfg)?;
    let n = grid.cells();
    let mut cumulative = vec![0.0; n];
    let mut below = 0.0;
    for j in (0..n).rev() {
        let piece = grid.limit[j] * grid.spacing[grid.section_of[j]];
        cumulative[j] = below + 0.5 * piece;
        below += piece;
    }
    let traj = super::well::trajectory(cfg)?;
    let points: Vec<_> = grid.z.iter().map(|&z| traj.at(z)).collect();
    let breakoff = breakoff_torque(cfg)?;
    let bit = super::grid::bit_static_torque(cfg);
    Ok(Profile {
        inclination_deg: points.iter().map(|p| p.inc.to_degrees()).collect(),
        azimuth_deg: points.iter().map(|p| p.azi.to_degrees()).collect(),
        tvd: points.iter().map(|p| p.position[2]).collect(),
        dls_deg_per_30m: points.iter().map(|p| p.curvature.to_degrees() * 30.0).collect(),
        friction_factor: grid.z.iter().map(|&z| super::well::friction_factor(cfg, z)).collect(),
        z: grid.z,
        limit_per_m: grid.limit,
        holding: cumulative.iter().map(|c| c + bit).collect(),
        cumulative,
        breakoff_torque: breakoff,
        bit_static_torque: bit,
        static_torque: static_torque(cfg, breakoff),
    })
}

/// Runs a configuration (validated first) from rest; see [`Simulation`].
pub fn solve(cfg: &DrillConfig, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> Result<DrillRun> {
    Ok(Simulation::new(cfg)?.run(interrupt, progress))
}

/// One section's slice of the padded state: `[ghost alpha, cells..., ghost beta]`.
#[derive(Debug, Clone, Copy)]
struct Span {
    /// Index of the top ghost.
    offset: usize,
    cells: usize,
    courant: f64,
    /// `rho J h / 4`.
    e: f64,
    impedance: f64,
    /// Cell length, m.
    h: f64,
    props: SectionProps,
}

/// The state of the `consistent` scheme: cell speed and twist per length, padded like the
/// invariants (`[ghost, cells, ghost]` per section, ghosts unused), and the face values
/// `(omega*, tau*)` at padded index `offset + j` for the face below cell `j` (`offset`: the
/// section's top face).
struct Nonlinear {
    omega: Vec<f64>,
    strain: Vec<f64>,
    omega_next: Vec<f64>,
    strain_next: Vec<f64>,
    face_omega: Vec<f64>,
    face_torque: Vec<f64>,
    /// Per cell in a step: tangent impedance and torque.
    cell_impedance: Vec<f64>,
    cell_torque: Vec<f64>,
    /// Largest `|eps|` of each section's cells so far.
    peak_strain: Vec<f64>,
}

/// The state of the controller.
#[derive(Debug, Clone, Copy)]
struct Control {
    kind: ControllerKind,
    kp: f64,
    ki: f64,
    limit: f64,
    integral: f64,
    torque: f64,
    next: f64,
    z_factor: f64,
    /// `z_torque`: low-passed string torque at the top.
    slow_torque: f64,
    /// `speed`, `z_torque`: `1 - exp(-2 pi motor_bandwidth dt)`, the fraction of the speed
    /// asked for the top reaches in a step.
    motor_lag: f64,
    slow_factor: f64,
}

/// A drilling-system run being set up (initial state) and run.
pub struct Simulation<'c> {
    cfg: &'c DrillConfig,
    grid: Grid,
    spans: Vec<Span>,
    alpha: Vec<f64>,
    beta: Vec<f64>,
    alpha_next: Vec<f64>,
    beta_next: Vec<f64>,
    /// `dt limit / (rho J)` per padded index (0 at the ghosts).
    stop: Vec<f64>,
    /// `-kinetic_ratio stop`: the kinetic friction change of a cell turning forwards.
    slip: Vec<f64>,
    omega_top: f64,
    omega_bit: f64,
    setpoint: f64,
    control: Control,
    losses: Losses,
    first_mode: f64,
    /// `Some` for the `consistent` nonlinearity (then `alpha`, `beta` are unused).
    nl: Option<Nonlinear>,
}

#[derive(Debug, Clone, Copy, Default)]
struct Losses {
    motor: f64,
    friction: f64,
    damping: f64,
    bit: f64,
    upwind: f64,
    inertia: f64,
}

impl<'c> Simulation<'c> {
    /// Validates `cfg` and sets the system at rest.
    pub fn new(cfg: &'c DrillConfig) -> Result<Self> {
        cfg.validate()?;
        let grid = Grid::new(cfg)?;
        let dt = grid.dt;
        if cfg.damping_rate * dt > 1.0 {
            return Err(Error::invalid(
                "damping_rate",
                Num(cfg.damping_rate),
                format!("at most 1 / dt = {} 1/s for this time step (more cells allow more)", Num(1.0 / dt)),
            ));
        }
        let mut spans = Vec::with_capacity(grid.props.len());
        let mut offset = 0;
        let mut stop = Vec::with_capacity(grid.cells() + 2 * grid.props.len());
        let mut cell = 0;
        for (s, p) in grid.props.iter().enumerate() {
            let n = grid.counts[s];
            spans.push(Span {
                offset,
                cells: n,
                courant: grid.courant[s],
                e: 0.25 * p.inertia_per_length * grid.spacing[s],
                impedance: p.impedance,
                h: grid.spacing[s],
                props: *p,
            });
            stop.push(0.0);
            for _ in 0..n {
                stop.push(dt * grid.limit[cell] / p.inertia_per_length);
                cell += 1;
            }
            stop.push(0.0);
            offset += n + 2;
        }
        let len = offset;
        let slip = stop.iter().map(|&lim| -(cfg.friction.kinetic_ratio * lim)).collect();
        let td = &cfg.top_drive;
        let first_mode = first_natural_frequency(&grid.props, cfg.bit.bha_inertia);
        let c = &td.controller;
        let (kp, ki) = match c.kind {
            ControllerKind::SoftTorque => {
                let w = c.tuning_frequency.map_or(first_mode, |f| 2.0 * PI * f);
                super::tuning::soft_torque_gains(c.z_factor, grid.props[0].impedance, w, td.inertia)
            }
            _ => (c.kp, c.ki),
        };
        check_control_loop(cfg, &grid, kp)?;
        let control = Control {
            kind: c.kind,
            kp,
            ki,
            limit: td.torque_limit,
            integral: 0.0,
            torque: 0.0,
            next: 0.0,
            z_factor: c.z_factor,
            slow_torque: 0.0,
            motor_lag: 1.0 - (-2.0 * PI * td.motor_bandwidth * dt).exp(),
            slow_factor: 1.0 - (-dt / c.torque_highpass_time).exp(),
        };
        let nl = (cfg.nonlinearity == Nonlinearity::Consistent).then(|| Nonlinear {
            omega: vec![0.0; len],
            strain: vec![0.0; len],
            omega_next: vec![0.0; len],
            strain_next: vec![0.0; len],
            face_omega: vec![0.0; len],
            face_torque: vec![0.0; len],
            cell_impedance: vec![0.0; len],
            cell_torque: vec![0.0; len],
            peak_strain: vec![0.0; grid.props.len()],
        });
        Ok(Simulation {
            cfg,
            grid,
            spans,
            alpha: vec![0.0; len],
            beta: vec![0.0; len],
            alpha_next: vec![0.0; len],
            beta_next: vec![0.0; len],
            stop,
            slip,
            omega_top: 0.0,
            omega_bit: 0.0,
            setpoint: 0.0,
            control,
            losses: Losses::default(),
            first_mode,
            nl,
        })
    }

    /// Sets `k5 = 0` in every section (the `consistent` scheme with the linear law), for tests
    /// of its linear limit.
    #[cfg(test)]
    pub(crate) fn zero_quartic(&mut self) {
        for sp in &mut self.spans {
            sp.props.quartic = 0.0;
        }
    }

    /// The discretisation.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Sets the initial state: the speed (rad/s) and torque (N m) of every cell (top to
    /// bottom, `grid().cells()` each), the top-drive and the bit speed (rad/s). With the
    /// `consistent` law a cell's twist is the one carrying its torque
    /// ([`SectionProps::strain`]).
    pub fn set_state(&mut self, omega: &[f64], torque: &[f64], omega_top: f64, omega_bit: f64) -> Result<()> {
        let n = self.grid.cells();
        for (name, x) in [("omega", omega), ("torque", torque)] {
            if x.len() != n {
                return Err(Error::invalid(name, format!("length {}", x.len()), format!("length {n} (the cells)")));
            }
            if let Some(v) = x.iter().find(|v| !v.is_finite()) {
                return Err(Error::invalid(name, Num(*v), "finite values"));
            }
        }
        if !(omega_top.is_finite() && omega_bit.is_finite()) {
            return Err(Error::invalid("omega_top", Num(omega_top + omega_bit), "finite speeds"));
        }
        let mut k = 0;
        for sp in &self.spans {
            for j in 1..=sp.cells {
                if let Some(nl) = &mut self.nl {
                    nl.omega[sp.offset + j] = omega[k];
                    nl.strain[sp.offset + j] = sp.props.strain(torque[k]);
                } else {
                    let s = torque[k] / sp.impedance;
                    self.alpha[sp.offset + j] = omega[k] + s;
                    self.beta[sp.offset + j] = omega[k] - s;
                }
                k += 1;
            }
        }
        self.omega_top = omega_top;
        self.omega_bit = omega_bit;
        Ok(())
    }

    /// Speeds (rad/s) and torques (N m) of the cells.
    pub fn fields(&self) -> (Vec<f64>, Vec<f64>) {
        let mut w = Vec::with_capacity(self.grid.cells());
        let mut t = Vec::with_capacity(self.grid.cells());
        for sp in &self.spans {
            for j in 1..=sp.cells {
                let (wj, tj) = self.cell(sp, j);
                w.push(wj);
                t.push(tj);
            }
        }
        (w, t)
    }

    /// Speed (rad/s) and torque (N m) of cell `j` (1-based) of a section.
    #[inline]
    fn cell(&self, sp: &Span, j: usize) -> (f64, f64) {
        match &self.nl {
            Some(nl) => (nl.omega[sp.offset + j], sp.props.torque(nl.strain[sp.offset + j])),
            None => {
                let (a, b) = (self.alpha[sp.offset + j], self.beta[sp.offset + j]);
                (0.5 * (a + b), 0.5 * sp.impedance * (a - b))
            }
        }
    }

    /// The bit speed reported, rad/s: the speed of the string's end, except that an end slower
    /// than `friction.stick_speed` below a stuck last cell (speed exactly 0) is at rest.
    ///
    /// Below a stuck cell the end's speed is `omega_n + tau_n / Z` of the cell's invariant (the
    /// boundary's Riemann solution), which creeps at the stuck cell's torque over the
    /// impedance: a speed proportional to the cell size (the torque of a stuck string falls
    /// linearly to 0 at a free end, so the last cell's is about `h / 2` times its gradient).
    /// In the continuum the string is at rest down to its end. The creep moves no state (the
    /// scheme keeps no angle), so reporting 0 changes nothing else; the published code of
    /// Aarsnes & Shor reports the last cell's speed for the same reason.
    fn bit_speed(&self) -> f64 {
        let last = self.spans.last().expect("at least one section");
        let (w, _) = self.cell(last, last.cells);
        let fr = &self.cfg.friction;
        let stuck = fr.model == FrictionModel::SetValued && w == 0.0;
        if stuck && self.omega_bit.abs() < fr.stick_speed.max(self.cfg.metrics.stick_speed) {
            0.0
        } else {
            self.omega_bit
        }
    }

    /// The characteristic variable leaving cell `j` of a section towards a face and the
    /// impedance it travels with: downwards (`down`) `omega + tau / Z`, else `omega - tau / Z`
    /// (`consistent`: `Z` the tangent impedance of the cell's twist).
    #[inline]
    fn outgoing(&self, sp: &Span, j: usize, down: bool) -> (f64, f64) {
        match &self.nl {
            Some(nl) => {
                let eps = nl.strain[sp.offset + j];
                let z = sp.props.tangent_impedance(eps);
                let s = sp.props.torque(eps) / z;
                let w = nl.omega[sp.offset + j];
                (if down { w + s } else { w - s }, z)
            }
            None => (if down { self.alpha[sp.offset + j] } else { self.beta[sp.offset + j] }, sp.impedance),
        }
    }

    /// `(string kinetic, string elastic, top drive, BHA)` energies, J.
    fn energies(&self) -> (f64, f64, f64, f64) {
        let (mut kin, mut ela) = (0.0, 0.0);
        if let Some(nl) = &self.nl {
            for sp in &self.spans {
                let (mut k, mut e) = (0.0, 0.0);
                for j in 1..=sp.cells {
                    let w = nl.omega[sp.offset + j];
                    k += w * w;
                    e += sp.props.elastic_energy(nl.strain[sp.offset + j]);
                }
                kin += 0.5 * sp.props.inertia_per_length * sp.h * k;
                ela += sp.h * e;
            }
        } else {
            for sp in &self.spans {
                let (mut k, mut e) = (0.0, 0.0);
                for j in 1..=sp.cells {
                    let (a, b) = (self.alpha[sp.offset + j], self.beta[sp.offset + j]);
                    k += (a + b) * (a + b);
                    e += (a - b) * (a - b);
                }
                kin += 0.5 * sp.e * k;
                ela += 0.5 * sp.e * e;
            }
        }
        let td = 0.5 * self.cfg.top_drive.inertia * self.omega_top * self.omega_top;
        let bha = 0.5 * self.cfg.bit.bha_inertia * self.omega_bit * self.omega_bit;
        (kin, ela, td, bha)
    }

    /// The setpoint target at time `t`, rad/s.
    fn target(&self, t: f64) -> f64 {
        let td = &self.cfg.top_drive;
        let rpm = td.steps.iter().rev().find(|s| s[0] <= t).map_or(td.rpm, |s| s[1]);
        rpm / RPM_PER_RAD_S
    }

    /// One step from `t` (start of the step); returns `(motor torque, bit torque)` applied.
    fn step(&mut self, t: f64) -> (f64, f64) {
        let dt = self.grid.dt;
        let cfg = self.cfg;
        let t1 = t + dt;
        // Setpoint: first-order approach of the target (exact over the step).
        let ramp = cfg.top_drive.ramp_time;
        let target = self.target(t1);
        self.setpoint =
            if ramp > 0.0 { self.setpoint + (target - self.setpoint) * (1.0 - (-dt / ramp).exp()) } else { target };

        // Top drive.
        let first = self.spans[0];
        let (beta1, z0) = self.outgoing(&first, 1, false);
        let inertia = cfg.top_drive.inertia;
        let omega = self.omega_top;
        let implicit = |tm: f64| (inertia * omega / dt + tm + z0 * beta1) / (inertia / dt + z0);
        let ctl = &mut self.control;
        let (omega1, motor) = match ctl.kind {
            ControllerKind::Pi | ControllerKind::SoftTorque => {
                if t + 0.5 * dt >= ctl.next {
                    let mut holds = 0.0;
                    while ctl.next <= t + 0.5 * dt {
                        ctl.next += cfg.top_drive.control_interval;
                        holds += 1.0;
                    }
                    let e = self.setpoint - omega;
                    let raw = ctl.kp * e + ctl.ki * ctl.integral;
                    ctl.torque = raw.clamp(-ctl.limit, ctl.limit);
                    // Anti-windup: no integration while saturated in the error's direction.
                    if !((raw > ctl.limit && e > 0.0) || (raw < -ctl.limit && e < 0.0)) {
                        ctl.integral += holds * cfg.top_drive.control_interval * e;
                    }
                }
                (implicit(ctl.torque), ctl.torque)
            }
            ControllerKind::Speed | ControllerKind::ZTorque => {
                let wanted = if ctl.kind == ControllerKind::Speed {
                    self.setpoint
                } else {
                    // The top presents the damper z Z to torque waves: Omega = w_ref - (tau - tau_slow) / (z Z)
                    // with tau = Z (Omega - beta_1).
                    let z = ctl.z_factor;
                    (z * self.setpoint + beta1 + ctl.slow_torque / z0) / (z + 1.0)
                };
                // The motor's speed loop: a first-order lag towards the speed asked for.
                let wanted = omega + (wanted - omega) * ctl.motor_lag;
                let tm = inertia * (wanted - omega) / dt + z0 * (wanted - beta1);
                if tm.abs() <= ctl.limit {
                    (wanted, tm)
                } else {
                    let tm = tm.clamp(-ctl.limit, ctl.limit);
                    (implicit(tm), tm)
                }
            }
        };
        let tau_top = z0 * (omega1 - beta1);
        if ctl.kind == ControllerKind::ZTorque {
            ctl.slow_torque += (tau_top - ctl.slow_torque) * ctl.slow_factor;
        }
        match &mut self.nl {
            Some(nl) => {
                nl.face_omega[first.offset] = omega1;
                nl.face_torque[first.offset] = tau_top;
            }
            None => self.alpha[first.offset] = 2.0 * omega1 - beta1,
        }
        self.losses.motor += dt * motor * omega1;
        self.losses.inertia += 0.5 * inertia * (omega1 - omega) * (omega1 - omega);
        self.omega_top = omega1;

        // Bit.
        let last = *self.spans.last().expect("at least one section");
        let (alpha_n, zl) = self.outgoing(&last, last.cells, true);
        let b = &cfg.bit;
        let ib = b.bha_inertia;
        let wb = self.omega_bit;
        let drive = ib * wb / dt + zl * alpha_n;
        let denom = ib / dt + zl;
        let (wb1, tbit) = if b.on_bottom && b.weight_on_bit > 0.0 {
            let wr = b.weight_on_bit * b.radius;
            // Stick: the torque that stops the bit in this step, if within the static limit.
            let stick = |drive: f64| {
                let hold = wr * b.mu_static;
                if drive.abs() <= hold {
                    (0.0, drive)
                } else {
                    let tb = hold.copysign(drive);
                    ((drive - tb) / denom, tb)
                }
            };
            if wb.abs() < b.stick_speed {
                stick(drive)
            } else {
                let tb = slip_torque(wr, b.mu_static, b.mu_kinetic, b.decay, wb);
                let w = (drive - tb) / denom;
                // A slip torque that would reverse the bit stops it instead (set-valued at 0).
                if w * wb < 0.0 {
                    stick(drive)
                } else {
                    (w, tb)
                }
            }
        } else {
            (drive / denom, 0.0)
        };
        match &mut self.nl {
            Some(nl) => {
                nl.face_omega[last.offset + last.cells] = wb1;
                nl.face_torque[last.offset + last.cells] = zl * (alpha_n - wb1);
            }
            None => self.beta[last.offset + last.cells + 1] = 2.0 * wb1 - alpha_n,
        }
        self.losses.bit += dt * tbit * wb1;
        // A bit stopped in this step: the BHA's kinetic energy is taken by the bit torque.
        let stop = 0.5 * ib * (wb1 - wb) * (wb1 - wb);
        if wb1 == 0.0 && tbit != 0.0 {
            self.losses.bit += stop;
        } else {
            self.losses.inertia += stop;
        }
        self.omega_bit = wb1;

        // Junctions.
        for k in 1..self.spans.len() {
            let (a, bl) = (self.spans[k - 1], self.spans[k]);
            let (alpha_a, za) = self.outgoing(&a, a.cells, true);
            let (beta_b, zb) = self.outgoing(&bl, 1, false);
            let w = (za * alpha_a + zb * beta_b) / (za + zb);
            match &mut self.nl {
                Some(nl) => {
                    let tau = za * (alpha_a - w);
                    for face in [a.offset + a.cells, bl.offset] {
                        nl.face_omega[face] = w;
                        nl.face_torque[face] = tau;
                    }
                }
                None => {
                    self.beta[a.offset + a.cells + 1] = 2.0 * w - alpha_a;
                    self.alpha[bl.offset] = 2.0 * w - beta_b;
                }
            }
        }

        // Cells.
        let fr = &cfg.friction;
        let sources = Sources {
            damping: dt * cfg.damping_rate,
            stick_speed: fr.stick_speed,
            kinetic_ratio: fr.kinetic_ratio,
            regularised: (fr.model == FrictionModel::Regularised).then_some(fr.regularisation_speed),
        };
        if let Some(nl) = &mut self.nl {
            for (s, sp) in self.spans.iter().enumerate() {
                let sums = godunov(nl, sp, (&self.stop, &self.slip), dt, &sources);
                self.losses.upwind += sums.jumps;
                self.losses.friction -= sums.friction;
                self.losses.damping -= sums.damping;
                nl.peak_strain[s] = nl.peak_strain[s].max(sums.peak);
            }
            std::mem::swap(&mut nl.omega, &mut nl.omega_next);
            std::mem::swap(&mut nl.strain, &mut nl.strain_next);
            return (motor, tbit);
        }
        for sp in &self.spans {
            let r = sp.offset..sp.offset + sp.cells + 2;
            let sums = transport(
                &self.alpha[r.clone()],
                &self.beta[r.clone()],
                &self.stop[r.clone()],
                &self.slip[r.clone()],
                &mut self.alpha_next[r.clone()],
                &mut self.beta_next[r],
                sp.courant,
                &sources,
            );
            self.losses.upwind += sp.e * sp.courant * (1.0 - sp.courant) * sums.jumps;
            self.losses.friction -= 4.0 * sp.e * sums.friction;
            self.losses.damping -= 4.0 * sp.e * sums.damping;
        }
        std::mem::swap(&mut self.alpha, &mut self.alpha_next);
        std::mem::swap(&mut self.beta, &mut self.beta_next);
        (motor, tbit)
    }

    /// Runs to `numerics.duration` (or until `interrupt` asks to stop, or a non-finite value),
    /// calling `progress` with the fraction done (every ~0.1 %).
    pub fn run(mut self, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> DrillRun {
        let cfg = self.cfg;
        let dt = self.grid.dt;
        let duration = cfg.numerics.duration;
        let steps = ((duration / dt) * (1.0 - 1e-12)).ceil().max(1.0) as u64;
        let n_series = cfg.series_samples();
        let n_fields = cfg.field_samples();
        let nz = self.grid.cells();
        let (k0, e0, t0, b0) = self.energies();
        let initial = k0 + e0 + t0 + b0;

        let breakoff = breakoff_torque(cfg).unwrap_or(f64::NAN);
        let mut run = DrillRun {
            t: Vec::new(),
            surface_rpm: Vec::new(),
            bit_rpm: Vec::new(),
            motor_torque: Vec::new(),
            bit_torque: Vec::new(),
            field_t: Vec::new(),
            z: self.grid.z.clone(),
            omega_field: Vec::new(),
            torque_field: Vec::new(),
            energy: EnergyBalance::default(),
            metrics: None,
            window: cfg.metrics.window.unwrap_or([0.5 * duration, duration]),
            breakoff_torque: breakoff,
            min_cycle_torque: min_cycle_torque(cfg, breakoff),
            status: Status::Success,
            message: String::new(),
            warnings: run_warnings(cfg, breakoff),
            metrics_finite: true,
            stats: DrillStats {
                cells: nz,
                steps: 0,
                dt,
                courant_min: self.grid.courant.iter().copied().fold(f64::INFINITY, f64::min),
                courant_max: self.grid.courant.iter().copied().fold(0.0, f64::max),
                courant_peak: self.grid.courant.iter().copied().fold(0.0, f64::max),
                kp: self.control.kp,
                ki: self.control.ki,
                first_mode_hz: self.first_mode / (2.0 * PI),
            },
        };
        let reserved = crate::solution::reserve_outputs(&mut [
            (&mut run.t, n_series),
            (&mut run.surface_rpm, n_series),
            (&mut run.bit_rpm, n_series),
            (&mut run.motor_torque, n_series),
            (&mut run.bit_torque, n_series),
            (&mut run.field_t, n_fields),
            (&mut run.omega_field, n_fields * nz),
            (&mut run.torque_field, n_fields * nz),
        ]);
        if let Err(oom) = reserved {
            run.status = Status::OutOfMemory;
            run.message = oom.outputs_message();
            return run;
        }

        let out_dt = cfg.numerics.output_interval;
        let field_dt = cfg.numerics.field_interval;
        if n_fields > 0 && !self.snapshot(&mut run, 0.0) {
            run.status = Status::NonFinite;
            run.message = "the initial state is not finite".into();
            return run;
        }
        let mut poller = Poller::new(interrupt);
        let td = &cfg.top_drive;
        let fastest = td.steps.iter().map(|s| s[1].abs()).fold(td.rpm.abs(), f64::max) / RPM_PER_RAD_S;
        let runaway = RUNAWAY_FACTOR * fastest.max(1.0);
        let stride = (steps / 1000).max(1);
        // (t, omega_top, omega_bit, motor, bit) at the previous step end.
        let mut prev = [0.0, self.omega_top, self.bit_speed(), f64::NAN, f64::NAN];
        let mut next_series = 0usize;
        let mut next_field = 1usize;
        let mut t = 0.0;
        for n in 0..steps {
            if poller.poll(t) {
                run.status = Status::Interrupted;
                run.message = format!("interrupted at t = {} s", Num(t));
                break;
            }
            let (motor, bit) = self.step(t);
            t = (n + 1) as f64 * dt;
            if self.omega_top.abs().max(self.omega_bit.abs()) > runaway {
                run.status = Status::NonFinite;
                run.message = format!(
                    "the solution diverged: the {} speed reached {} rpm, more than {} times the largest setpoint, \
                     at t = {} s (a grid too coarse for the controller or the bit law: raise numerics.cells)",
                    if self.omega_top.abs() > runaway { "top-drive" } else { "bit" },
                    Num(self.omega_top.abs().max(self.omega_bit.abs()) * RPM_PER_RAD_S),
                    RUNAWAY_FACTOR,
                    Num(t)
                );
                break;
            }
            run.stats.steps = n + 1;
            let cur = [t, self.omega_top, self.bit_speed(), motor, bit];
            if n == 0 {
                prev[3] = motor;
                prev[4] = bit;
            }
            while next_series < n_series {
                let ts = next_series as f64 * out_dt;
                if ts > t * (1.0 + 1e-12) {
                    break;
                }
                let w = if cur[0] > prev[0] { ((ts - prev[0]) / (cur[0] - prev[0])).clamp(0.0, 1.0) } else { 1.0 };
                let at = |k: usize| prev[k] + w * (cur[k] - prev[k]);
                let sample = [ts, at(1) * RPM_PER_RAD_S, at(2) * RPM_PER_RAD_S, at(3), at(4)];
                if sample.iter().any(|v| !v.is_finite()) {
                    run.status = Status::NonFinite;
                    run.message = format!("the state became non-finite before t = {} s", Num(t));
                    break;
                }
                run.t.push(sample[0]);
                run.surface_rpm.push(sample[1]);
                run.bit_rpm.push(sample[2]);
                run.motor_torque.push(sample[3]);
                run.bit_torque.push(sample[4]);
                next_series += 1;
            }
            if run.status != Status::Success {
                break;
            }
            if next_field < n_fields && t >= next_field as f64 * field_dt - 0.5 * dt {
                if !self.snapshot(&mut run, t) {
                    run.status = Status::NonFinite;
                    run.message = format!("the state became non-finite before t = {} s", Num(t));
                    break;
                }
                next_field += 1;
            }
            prev = cur;
            if (n + 1) % stride == 0 {
                progress((n + 1) as f64 / steps as f64);
            }
        }
        if let Some(nl) = &self.nl {
            let peak = self
                .spans
                .iter()
                .zip(&nl.peak_strain)
                .map(|(sp, &eps)| sp.props.tangent_speed(eps) * dt / sp.h)
                .fold(0.0, f64::max);
            run.stats.courant_peak = peak;
            if peak > 1.0 + 1e-12 {
                let bound = cfg.numerics.max_shear_strain;
                let strain = (nl.peak_strain.iter().zip(&self.grid.strain_bound))
                    .map(|(&eps, &b)| bound * eps / b)
                    .fold(0.0, f64::max);
                let note = format!(
                    "the shear strain reached {} > numerics.max_shear_strain = {}: the tangent Courant number \
                     reached {} > 1 (raise numerics.max_shear_strain)",
                    Num(strain),
                    Num(cfg.numerics.max_shear_strain),
                    Num(peak)
                );
                run.message = if run.message.is_empty() { note } else { format!("{}; {note}", run.message) };
            }
        }
        let (kin, ela, td, bha) = self.energies();
        let l = self.losses;
        let change = kin + ela + td + bha - initial;
        let numerical = l.upwind + l.inertia;
        let residual = l.motor - change - l.friction - l.damping - l.bit - numerical;
        let scale = [l.motor, initial, kin + ela + td + bha, l.friction, l.damping, l.bit, numerical]
            .iter()
            .fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
        run.energy = EnergyBalance {
            motor_work: l.motor,
            initial,
            kinetic: kin,
            elastic: ela,
            top_drive: td,
            bha,
            friction_loss: l.friction,
            damping_loss: l.damping,
            bit_loss: l.bit,
            numerical_loss: numerical,
            upwind_loss: l.upwind,
            inertia_loss: l.inertia,
            balance_error: residual / scale,
        };
        if run.status == Status::Success && !(residual.is_finite() && scale.is_finite()) {
            run.status = Status::NonFinite;
            run.message = format!("the energy became non-finite by t = {} s", Num(t));
        }
        let [a, b] = run.window;
        let stuck = cfg.metrics.stick_speed;
        let mut omega_bit = Vec::new();
        let note = if omega_bit.try_reserve_exact(run.bit_rpm.len()).is_err() {
            Some("no metrics: their memory could not be allocated".to_string())
        } else {
            omega_bit.extend(run.bit_rpm.iter().map(|r| r / RPM_PER_RAD_S));
            run.metrics = stick_slip(&run.t, &omega_bit, Some(&run.motor_torque), Some((a, b)), stuck).ok();
            run.metrics.is_none().then(|| {
                format!(
                    "no metrics: the window metrics.window = [{}, {}] s holds fewer than 2 samples of the series \
                     (0 to {} s)",
                    Num(a),
                    Num(b),
                    Num(run.t.last().copied().unwrap_or(0.0))
                )
            })
        };
        if let Some(note) = note {
            run.message = if run.message.is_empty() { note } else { format!("{}; {note}", run.message) };
        }
        run.metrics_finite = run.metrics.as_ref().is_some_and(|m| non_finite_metrics_warning(m).is_none());
        run.warnings.extend(run.metrics.as_ref().and_then(non_finite_metrics_warning));
        run.warnings.extend(transient_warning(&run.t, &run.surface_rpm, &run.motor_torque, run.window));
        progress(1.0);
        run
    }

    /// Appends the fields at `t`; `false` (nothing appended) when a value is not finite.
    fn snapshot(&self, run: &mut DrillRun, t: f64) -> bool {
        let start = run.omega_field.len();
        for sp in &self.spans {
            for j in 1..=sp.cells {
                let (w, tau) = self.cell(sp, j);
                run.omega_field.push(w * RPM_PER_RAD_S);
                run.torque_field.push(tau);
            }
        }
        let finite = run.omega_field[start..].iter().chain(&run.torque_field[start..]).all(|v| v.is_finite());
        if finite {
            run.field_t.push(t);
        } else {
            run.omega_field.truncate(start);
            run.torque_field.truncate(start);
        }
        finite
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
fn check_control_loop(cfg: &DrillConfig, grid: &Grid, kp: f64) -> Result<()> {
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

/// The per-step constants of the sources.
struct Sources {
    /// `dt d`.
    damping: f64,
    stick_speed: f64,
    kinetic_ratio: f64,
    /// `Some(v_r)` for the regularised friction.
    regularised: Option<f64>,
}

/// Sums over a section's cells in one step.
#[derive(Default)]
struct Sums {
    /// `sum (d alpha^2 + d beta^2)` of the upwind differences.
    jumps: f64,
    /// `sum delta_f (omega* + delta / 2)` and the same for the damping.
    friction: f64,
    damping: f64,
    /// Largest `|eps|` (`consistent`).
    peak: f64,
}

/// One step of the `consistent` scheme on a section (faces at the boundaries and junctions
/// set): the faces inside it by the acoustic (two-wave) Riemann solver with the larger tangent
/// impedance of the two cells, `omega* = (w_l + w_r) / 2 + (tau_l - tau_r) / (2 Z)`,
/// `tau* = (tau_l + tau_r) / 2 + Z (w_l - w_r) / 2`, then the finite-volume update
/// `omega += dt (tau*_top - tau*_bottom) / (rho J h)`, `eps += dt (omega*_top - omega*_bottom) / h`
/// and the sources as in [`update`]. Returns the sums, with `jumps` the transport's
/// dissipation `dt (tau*_top omega*_top - tau*_bottom omega*_bottom) - dE` (J) and
/// `friction`, `damping` the work of the sources (J, negative).
fn godunov(nl: &mut Nonlinear, sp: &Span, (stop, slip): (&[f64], &[f64]), dt: f64, src: &Sources) -> Sums {
    crate::simd::dispatch(Godunov { nl, sp, stop, slip, dt, src })
}

/// [`godunov`] as a [`crate::simd::Kernel`] (AVX2 code when available; no fused multiply-adds).
struct Godunov<'a> {
    nl: &'a mut Nonlinear,
    sp: &'a Span,
    stop: &'a [f64],
    slip: &'a [f64],
    dt: f64,
    src: &'a Sources,
}

impl crate::simd::Kernel for Godunov<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> Sums {
        if self.src.regularised.is_some() {
            self.cells::<true>()
        } else {
            self.cells::<false>()
        }
    }
}

impl Godunov<'_> {
    #[inline(always)]
    fn cells<const REGULARISED: bool>(self) -> Sums {
        let Godunov { nl, sp, stop, slip, dt, src } = self;
        let p = &sp.props;
        let r = sp.offset + 1..=sp.offset + sp.cells;
        let Nonlinear {
            omega,
            strain,
            omega_next,
            strain_next,
            face_omega,
            face_torque,
            cell_impedance,
            cell_torque,
            ..
        } = nl;
        // Tangent impedance and torque of every cell, then the faces inside the section.
        for ((z, t), &eps) in
            cell_impedance[r.clone()].iter_mut().zip(&mut cell_torque[r.clone()]).zip(&strain[r.clone()])
        {
            *z = p.tangent_impedance(eps);
            *t = p.torque(eps);
        }
        let inner = sp.offset + 1..sp.offset + sp.cells;
        let (zc, tc, wc) = (&cell_impedance[r.clone()], &cell_torque[r.clone()], &omega[r.clone()]);
        for (k, (fw, ft)) in face_omega[inner.clone()].iter_mut().zip(&mut face_torque[inner]).enumerate() {
            let (wl, wr) = (wc[k], wc[k + 1]);
            let z = zc[k].max(zc[k + 1]);
            let (tl, tr) = (tc[k], tc[k + 1]);
            *fw = 0.5 * (wl + wr) + 0.5 * (tl - tr) / z;
            *ft = 0.5 * (tl + tr) + 0.5 * z * (wl - wr);
        }
        let k = Consts::new(0.0, src);
        let (k1, k2, k5, h) = (p.inertia_per_length, p.stiffness, p.quartic, sp.h);
        let (rw, rs) = (dt / (k1 * h), dt / h);
        let mut sums = Sums::default();
        let faces = sp.offset..=sp.offset + sp.cells;
        let (fw, ft) = (&face_omega[faces.clone()], &face_torque[faces]);
        let (w0, s0, lim, slip) = (&omega[r.clone()], &strain[r.clone()], &stop[r.clone()], &slip[r.clone()]);
        let (wn, sn) = (&mut omega_next[r.clone()], &mut strain_next[r]);
        // Blocks of BLOCK cells whose per-cell terms stay on the stack, each then summed in
        // lanes, so that the update loop vectorises.
        let (mut jump, mut fric, mut damp, mut peak) = ([0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
        let mut start = 0;
        while start < sp.cells {
            let m = BLOCK.min(sp.cells - start);
            for j in 0..m {
                let c = start + j;
                let (wt, tt, wb, tb) = (fw[c], ft[c], fw[c + 1], ft[c + 1]);
                let (w, s) = (w0[c], s0[c]);
                let w1 = w + rw * (tt - tb);
                let s1 = s + rs * (wt - wb);
                let de = h
                    * (0.5 * k1 * (w1 - w) * (w1 + w)
                        + (s1 - s) * (s1 + s) * (0.5 * k2 + 0.25 * k5 * (s1 * s1 + s * s)));
                jump[j] = dt * (tt * wt - tb * wb) - de;
                let (dd, df, stuck) = source::<REGULARISED>(w1, lim[c], slip[c], &k);
                let d = dd + df;
                let wbar = w1 + 0.5 * d;
                wn[c] = if stuck { 0.0 } else { w1 + d };
                sn[c] = s1;
                fric[j] = df * wbar;
                damp[j] = dd * wbar;
                peak[j] = s1.abs();
            }
            sums.jumps += lane_sum(&jump[..m]);
            sums.friction += k1 * h * lane_sum(&fric[..m]);
            sums.damping += k1 * h * lane_sum(&damp[..m]);
            sums.peak = peak[..m].iter().fold(sums.peak, |a, &b| if b > a { b } else { a });
            start += m;
        }
        sums
    }
}

/// Upwind transport and sources of one section: `a`, `b`, `stop`, `slip` padded (`[ghost, cells, ghost]`),
/// the new invariants written to the cells of `an`, `bn`. Runs through
/// [`crate::simd::dispatch`] (AVX2 when available; no fused multiply-adds, so both paths give
/// the same bits).
#[allow(clippy::too_many_arguments)]
fn transport(
    a: &[f64],
    b: &[f64],
    stop: &[f64],
    slip: &[f64],
    an: &mut [f64],
    bn: &mut [f64],
    c: f64,
    src: &Sources,
) -> Sums {
    let n = a.len() - 2;
    let kernel = Transport {
        a_prev: &a[..n],
        a: &a[1..=n],
        b: &b[1..=n],
        b_next: &b[2..],
        stop: &stop[1..=n],
        slip: &slip[1..=n],
        an: &mut an[1..=n],
        bn: &mut bn[1..=n],
        c,
        src,
    };
    crate::simd::dispatch(kernel)
}

struct Transport<'a> {
    a_prev: &'a [f64],
    a: &'a [f64],
    b: &'a [f64],
    b_next: &'a [f64],
    stop: &'a [f64],
    slip: &'a [f64],
    an: &'a mut [f64],
    bn: &'a mut [f64],
    c: f64,
    src: &'a Sources,
}

/// Cells per block of [`godunov`].
const BLOCK: usize = 128;

/// Lanes of the summation (independent accumulators, vectorisable).
const LANES: usize = 4;

/// `sum x` with [`LANES`] accumulators.
#[inline(always)]
fn lane_sum(x: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let blocks = x.chunks_exact(LANES);
    let rest = blocks.remainder();
    for blk in blocks {
        for l in 0..LANES {
            acc[l] += blk[l];
        }
    }
    acc.iter().sum::<f64>() + rest.iter().sum::<f64>()
}

impl crate::simd::Kernel for Transport<'_> {
    type Output = Sums;

    #[inline(always)]
    fn run<M: crate::simd::MulAdd>(self) -> Sums {
        // Specialised on the model and on which energy terms are non-zero (fewer stores).
        match (self.src.regularised.is_some(), self.c < 1.0, self.src.damping > 0.0) {
            (false, false, false) => self.cells::<false, false, false>(),
            (false, false, true) => self.cells::<false, false, true>(),
            (false, true, false) => self.cells::<false, true, false>(),
            (false, true, true) => self.cells::<false, true, true>(),
            (true, false, false) => self.cells::<true, false, false>(),
            (true, false, true) => self.cells::<true, false, true>(),
            (true, true, false) => self.cells::<true, true, false>(),
            (true, true, true) => self.cells::<true, true, true>(),
        }
    }
}

impl Transport<'_> {
    /// The update loop over chunks of [`WIDTH`] cells, the energy terms added lane by lane
    /// into [`WIDTH`] accumulators (a fixed order, so every instruction set gives the same
    /// bits; the chunk's cells side by side in vector registers), the lanes summed at the end.
    #[inline(always)]
    fn cells<const REGULARISED: bool, const UPWIND: bool, const DAMPED: bool>(self) -> Sums {
        let Transport { a_prev, a, b, b_next, stop, slip, an, bn, c, src } = self;
        let n = a.len();
        let k = Consts::new(c, src);
        let mut jump = [0.0; WIDTH];
        let mut fric = [0.0; WIDTH];
        let mut damp = [0.0; WIDTH];
        let whole = n - n % WIDTH;
        for start in (0..whole).step_by(WIDTH) {
            let r = start..start + WIDTH;
            let chunk = |x: &[f64]| -> [f64; WIDTH] { x[r.clone()].try_into().expect("a whole chunk") };
            let (ap, aa, bb, bx, st, sl) = (chunk(a_prev), chunk(a), chunk(b), chunk(b_next), chunk(stop), chunk(slip));
            let mut new_a = [0.0; WIDTH];
            let mut new_b = [0.0; WIDTH];
            for l in 0..WIDTH {
                let cell = update::<REGULARISED, UPWIND>(ap[l], aa[l], bb[l], bx[l], st[l], sl[l], &k);
                new_a[l] = cell.an;
                new_b[l] = cell.bn;
                if UPWIND {
                    jump[l] += cell.jump;
                }
                fric[l] += cell.friction;
                if DAMPED {
                    damp[l] += cell.damping;
                }
            }
            an[r.clone()].copy_from_slice(&new_a);
            bn[r].copy_from_slice(&new_b);
        }
        for i in whole..n {
            let l = i - whole;
            let cell = update::<REGULARISED, UPWIND>(a_prev[i], a[i], b[i], b_next[i], stop[i], slip[i], &k);
            an[i] = cell.an;
            bn[i] = cell.bn;
            if UPWIND {
                jump[l] += cell.jump;
            }
            fric[l] += cell.friction;
            if DAMPED {
                damp[l] += cell.damping;
            }
        }
        let total = |x: &[f64; WIDTH]| x.iter().sum::<f64>();
        Sums { jumps: total(&jump), friction: total(&fric), damping: total(&damp), peak: 0.0 }
    }
}

/// Cells side by side in [`Transport::cells`] (and accumulators of its energy terms).
const WIDTH: usize = 16;

/// What one cell's update adds and writes.
struct Cell {
    an: f64,
    bn: f64,
    jump: f64,
    friction: f64,
    damping: f64,
}

/// The constants of [`update`] and [`source`].
struct Consts {
    c: f64,
    damping: f64,
    /// A cell is slow below this speed: the stick speed, or with stick speed 0 the least
    /// positive double (then only a cell exactly at rest is slow, and the sign taken in
    /// [`source`] is never that of a zero).
    slow_below: f64,
    kr: f64,
    inv_vr: f64,
}

impl Consts {
    fn new(c: f64, src: &Sources) -> Self {
        Consts {
            c,
            damping: src.damping,
            slow_below: if src.stick_speed > 0.0 { src.stick_speed } else { f64::from_bits(1) },
            kr: src.kinetic_ratio,
            inv_vr: src.regularised.map_or(0.0, |v| 1.0 / v),
        }
    }
}

/// One cell: upwind transport of the invariants from `(a_prev, a)` and `(b, b_next)` (at
/// Courant number 1, `!UPWIND`, the exact shift `a_prev`, `b_next`), then the damping and
/// friction sources (see the module); branch-free (selects) so that blocks vectorise.
#[inline(always)]
fn update<const REGULARISED: bool, const UPWIND: bool>(
    a_prev: f64,
    a: f64,
    b: f64,
    b_next: f64,
    lim: f64,
    slip: f64,
    k: &Consts,
) -> Cell {
    let (da, db) = (a - a_prev, b - b_next);
    let (a1, b1) = if UPWIND { (a - k.c * da, b - k.c * db) } else { (a_prev, b_next) };
    let w1 = 0.5 * (a1 + b1);
    let (dd, df, stuck) = source::<REGULARISED>(w1, lim, slip, k);
    let d = dd + df;
    let wbar = w1 + 0.5 * d;
    // Stuck: stopped exactly (omega = 0), the torque kept.
    let s1 = 0.5 * (a1 - b1);
    Cell {
        an: if stuck { s1 } else { a1 + d },
        bn: if stuck { -s1 } else { b1 + d },
        jump: da * da + db * db,
        friction: df * wbar,
        damping: dd * wbar,
    }
}

/// The sources of a cell whose transported speed is `w1`, with the stop limit `lim`
/// (`dt limit / (rho J)`) and `slip = -kinetic_ratio lim`: the damping change `dd = -dt d w1`,
/// the friction change `df` and whether the cell sticks (see the module).
#[inline(always)]
fn source<const REGULARISED: bool>(w1: f64, lim: f64, slip: f64, k: &Consts) -> (f64, f64, bool) {
    let dd = -k.damping * w1;
    let wd = w1 + dd;
    // Friction never reverses a cell within a step: a change larger than the speed after
    // damping (`wd`, of the sign of `w1` since `dt d <= 1`) stops the cell instead.
    let (df, stuck) = if REGULARISED {
        let df = -k.kr * lim * (w1 * k.inv_vr).tanh();
        (if df.abs() > wd.abs() { -wd } else { df }, false)
    } else {
        // Slow: |w1| < stick speed, or w1 = 0 (`slow_below`). Selects and bit operations
        // only, so that the loop vectorises.
        let slow = w1.abs() < k.slow_below;
        let clipped = if wd > lim { lim } else { wd };
        let clipped = if clipped < -lim { -lim } else { clipped };
        // Kinetic: -min(kinetic_ratio lim, |wd|) copysign w1, i.e. the larger of `slip` (<= -0)
        // and -|wd|, with its sign flipped when w1 is negative; at -|wd| it stops the cell.
        let room = -wd.abs();
        let stops = slip <= room;
        let kinetic = if stops { room } else { slip };
        let kinetic = f64::from_bits(kinetic.to_bits() ^ (w1.to_bits() & SIGN_BIT));
        let df = if slow { -clipped } else { kinetic };
        (df, (slow & (wd.abs() <= lim)) | (!slow & stops))
    };
    (dd, df, stuck)
}

/// The sign bit of an `f64`.
const SIGN_BIT: u64 = 1 << 63;
