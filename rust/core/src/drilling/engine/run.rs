//! The run: a [`Simulation`] set up from a configuration (field, sources, ends, controller),
//! its step (ends, junctions, cells) and its loop (step limit, interrupt polling, runaway
//! guard, sampling, status), the energy balance and the metrics at the end.

use serde::Serialize;

use super::axial_field::Axial;
use super::boundary::{BitEnd, TopDriveEnd};
use super::controller::{Setpoint, SpeedSeries, Top, TopInput, RPM_PER_RAD_S};
use super::coupled_friction::CoupledFriction;
use super::energy::{EnergyBalance, Ledger, Stored};
use super::field::{Field, StringField};
use super::sampler::{Point, BIT_SPEED, BIT_TORQUE, MOTOR_TORQUE, TIME, TOP_SPEED};
use super::session::Session;
use super::sources::{Sources, StepSource, WallFriction};
use super::torsion::Torsion;
use crate::drilling::axial::bitrock::{bit_area, mechanical_specific_energy};
use crate::drilling::axial::regime::{regime, Regime};
use crate::drilling::config::{DrillConfig, FrictionCoupling, Nonlinearity};
use crate::drilling::grid::{first_natural_frequency, Grid};
use crate::drilling::start::{steady_point, InitialState, Wall};
use crate::error::{Error, Num, Result};
use crate::interrupt::Interrupt;
use crate::metrics::{stick_slip, StickSlip};
use crate::solution::{serialize_list, Status};

/// A run whose top-drive or bit speed exceeds this many times the largest setpoint (or 1 rad/s)
/// has diverged: it ends with the status `non_finite` and a message saying so.
pub const RUNAWAY_FACTOR: f64 = 1000.0;

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
    /// A coupled run's series at the same times (empty without a hoist): the bit's axial speed
    /// m/s (down positive), the rate of penetration m/h (the rate the deepest bit position
    /// advances), weight on bit N, hook load N, the bit's depth below its start m, and the depth
    /// of cut per revolution m used by the bit law (0 while the rate form's bit does not turn),
    /// the block's position. The torque on bit is `bit_torque`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bit_axial_speed: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rop: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub weight_on_bit: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub hook_load: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bit_depth: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub depth_of_cut: Vec<f64>,
    /// The block's (the top of the string's) position from the start, m, down positive.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub block_position: Vec<f64>,
    /// A coupled run's axial cells (empty without a hoist): their centres, m, and at the
    /// snapshot times `field_t` (`field_t.len() x axial_z.len()`, row-major) the axial speed m/s
    /// (down positive) and the axial force N (compression positive, tension negative).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axial_z: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axial_speed_field: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axial_force_field: Vec<f64>,
    /// A coupled run's metrics over the window (None without a hoist or a window).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coupled: Option<CoupledMetrics>,
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
    /// ([`crate::drilling::grid::min_cycle_torque`]), N m.
    #[serde(skip)]
    pub min_cycle_torque: f64,
    pub status: Status,
    pub message: String,
    /// What the configuration makes doubtful (a torque limit the string's static torque
    /// exceeds); the metrics' own are [`StickSlip::warnings`].
    #[serde(serialize_with = "serialize_list")]
    pub warnings: Vec<String>,
    /// False when a headline metric is not finite or the window has none
    /// ([`crate::drilling::plausibility::non_finite_metrics`]): not a result, whatever `status` says.
    pub metrics_finite: bool,
    /// Whether the top drive is asked to turn ([`crate::drilling::plausibility::rotation_commanded`]):
    /// without rotation (a coupled pick-up or slack-off) the torsional metrics are undefined by
    /// design, and the warnings say so once.
    pub rotating: bool,
    pub stats: DrillStats,
}

impl DrillRun {
    /// The stick-slip metrics' warnings ([`StickSlip::warnings`]); in a coupled run without
    /// rotation, less those that only restate it (an undefined SSI, a bit that never turns).
    pub fn metric_warnings(&self) -> Vec<String> {
        let Some(m) = &self.metrics else { return Vec::new() };
        let mut out = m.warnings();
        if !self.rotating && self.coupled.is_some() {
            out.retain(|w| !(w.starts_with("ssi undefined") || w.starts_with("the bit never turns")));
        }
        out
    }
}

/// A drilling-system run being set up (initial state) and stepped; it owns its configuration
/// (a [`super::session::Session`] changes parts of it during a run).
#[derive(Clone)]
pub struct Simulation {
    pub(super) cfg: DrillConfig,
    pub(super) grid: Grid,
    /// The torsional field with its wall friction and sources.
    pub(super) torsion: Torsion,
    pub(super) top: TopDriveEnd,
    pub(super) bit: BitEnd,
    pub(super) setpoint: Setpoint,
    /// What drives the top: a controller, or the measured speed (`top_drive.mode`).
    pub(super) drive: Top,
    pub(super) ledger: Ledger,
    pub(super) first_mode: f64,
    /// The axial field of a coupled run (`[hoist]`).
    pub(super) axial: Option<Axial>,
    /// A coupled run's wall friction on both fields (`friction.coupling = "axial_torsional"`;
    /// then the torsional `wall` is zero and the torsional kernel applies none), a
    /// [`StepSource`].
    pub(super) coupled_friction: Option<CoupledFriction>,
}

impl Simulation {
    /// Validates `cfg` and sets the system at rest (on a copy of `cfg`).
    pub fn new(cfg: &DrillConfig) -> Result<Self> {
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
        let field = Field::torsional(&grid, cfg.nonlinearity == Nonlinearity::Consistent);
        let mut wall = WallFriction::torsional(cfg, &grid, &field);
        let first_mode = first_natural_frequency(&grid.props, cfg.bit.bha_inertia);
        let drive = Top::new(cfg, &grid, first_mode)?;
        let mut axial = match &cfg.hoist {
            Some(h) => Some(Axial::new(cfg, &grid, h)?),
            None => None,
        };
        let coupled_friction = match &mut axial {
            Some(ax) if cfg.friction.coupling == FrictionCoupling::AxialTorsional => {
                let cf = CoupledFriction::new(cfg, &grid, &field, &ax.field, &ax.half_kicks())?;
                if cf.is_some() {
                    ax.start_at_rest();
                }
                ax.end_hold = cf.as_ref().map_or(0.0, CoupledFriction::end_hold);
                cf
            }
            _ => None,
        };
        if coupled_friction.is_some() {
            // The torsional kernel's friction off (the values of a zero limit).
            wall.off();
        }
        let mut sim = Simulation {
            axial,
            coupled_friction,
            cfg: cfg.clone(),
            torsion: Torsion { field, wall, sources: Sources::new(cfg, dt), source_speed: cfg.numerics.source_speed },
            top: TopDriveEnd::new(cfg, dt),
            bit: BitEnd::new(cfg),
            grid,
            setpoint: Setpoint::new(&cfg.top_drive, dt),
            drive,
            ledger: Ledger::default(),
            first_mode,
        };
        if cfg.numerics.initial_state == InitialState::Steady {
            sim.start_steady()?;
        }
        Ok(sim)
    }

    /// Sets the steady drilling state of a coupled run ([`crate::drilling::start`]): every cell
    /// turning at the top drive's speed at `t = 0` with the torque of steady rotation, the
    /// controller holding the top torque, the axial field, bit and hoist by
    /// [`Axial::set_steady`]. Refused without a hoist, rotation or a drilling hoist.
    fn start_steady(&mut self) -> Result<()> {
        let cfg = &self.cfg;
        let td = &cfg.top_drive;
        let omega = match SpeedSeries::new(td) {
            Some(mut series) => series.at(0.0),
            None => Setpoint::target(td, 0.0),
        };
        let wall = Wall::new(cfg, &self.grid, self.coupled_friction.is_some());
        let point = steady_point(cfg, &wall, omega)?;
        let (torque, top) = wall.torques(point.rop, omega, point.bit.torque_on_bit);
        self.set_state(&vec![omega; self.grid.cells()], &torque, omega, omega)?;
        self.setpoint.value = omega;
        self.drive.hold(top);
        if let Some(ax) = &mut self.axial {
            ax.set_steady(&self.cfg, &point, &wall)?;
        }
        Ok(())
    }

    /// Sets `k5 = 0` in every section (the `consistent` scheme with the linear law), for tests
    /// of its linear limit.
    #[cfg(test)]
    pub(crate) fn zero_quartic(&mut self) {
        if let Some(nl) = &mut self.torsion.field.nl {
            for law in &mut nl.laws {
                law.quartic = 0.0;
            }
        }
    }

    /// The discretisation.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Sets the initial state: the speed (rad/s) and torque (N m) of every cell (top to
    /// bottom, `grid().cells()` each), the top-drive and the bit speed (rad/s). With the
    /// `consistent` law a cell's twist is the one carrying its torque
    /// ([`crate::drilling::grid::SectionProps::strain`]).
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
        let field = &mut self.torsion.field;
        for s in 0..field.sections.len() {
            for j in 1..=field.sections[s].cells {
                field.set_cell(s, j, omega[k], torque[k]);
                k += 1;
            }
        }
        self.top.omega = omega_top;
        self.bit.omega = omega_bit;
        Ok(())
    }

    /// Speeds (rad/s) and torques (N m) of the cells.
    pub fn fields(&self) -> (Vec<f64>, Vec<f64>) {
        let mut w = Vec::with_capacity(self.grid.cells());
        let mut t = Vec::with_capacity(self.grid.cells());
        self.torsion.each_cell(|wj, tj| {
            w.push(wj);
            t.push(tj);
        });
        (w, t)
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
    pub(super) fn bit_speed(&self) -> f64 {
        let field = &self.torsion.field;
        let s = field.sections.len() - 1;
        let (w, _) = field.cell(s, field.sections[s].cells);
        let fr = &self.cfg.friction;
        let stuck = self.torsion.sources.sticks() && w == 0.0;
        if stuck && self.bit.omega.abs() < fr.stick_speed.max(self.cfg.metrics.stick_speed) {
            0.0
        } else {
            self.bit.omega
        }
    }

    /// The energies stored, J.
    pub(super) fn stored(&self) -> Stored {
        let (kinetic, elastic) = self.torsion.stored();
        let mut s = Stored {
            kinetic,
            elastic,
            top_drive: 0.5 * self.top.inertia * self.top.omega * self.top.omega,
            bha: 0.5 * self.bit.inertia * self.bit.omega * self.bit.omega,
            axial_kinetic: 0.0,
            axial_elastic: 0.0,
        };
        if let Some(ax) = &self.axial {
            (s.axial_kinetic, s.axial_elastic) = ax.stored();
            s.bha += ax.bha_kinetic();
        }
        s
    }

    /// One step from `t` (start of the step); returns `(motor torque, bit torque)` applied.
    /// The order: the setpoint, the top drive against the torsional field's top, then a coupled
    /// run's axial field (the hoist, the bit on both fields' ends, its junctions and cells) or
    /// the torsional bit, the torsional bottom, junctions and cells, then the sources of the
    /// step on both fields ([`StepSource`]).
    pub(super) fn step(&mut self, t: f64) -> (f64, f64) {
        let dt = self.grid.dt;
        let td = &self.cfg.top_drive;
        let booked = self.cfg.numerics.energy_balance;
        let setpoint = self.setpoint.advance(td, t, dt);

        // Top drive.
        let torsion = &mut self.torsion;
        let arriving = torsion.arriving_top();
        let input = TopInput { t, dt, setpoint, omega: self.top.omega, arriving };
        let command = self.drive.command(td, &input);
        let (omega1, motor, tau_top) = self.top.step(command, arriving, dt, &mut self.ledger);
        self.drive.observe(tau_top);
        torsion.set_top(arriving, omega1, tau_top);

        // Bit.
        let arriving = torsion.arriving_bottom();
        let (wb1, tbit) = match &mut self.axial {
            Some(ax) => {
                ax.top(dt, &mut self.ledger);
                let (wb1, tbit) = ax.bit(arriving, self.bit.inertia, self.bit.omega, dt, &mut self.ledger);
                self.bit.omega = wb1;
                ax.junctions();
                ax.advance(dt, &mut self.ledger, booked);
                (wb1, tbit)
            }
            None => self.bit.step(arriving, dt, &mut self.ledger),
        };
        torsion.set_bottom(arriving, wb1);

        torsion.junctions();
        torsion.advance(dt, &mut self.ledger, booked);
        if let (Some(cf), Some(ax)) = (&mut self.coupled_friction, &mut self.axial) {
            StepSource::apply(cf, &mut torsion.field, ax, &mut self.ledger);
        }
        (motor, tbit)
    }

    /// Runs to `numerics.duration` (or until `interrupt` asks to stop, or a non-finite value),
    /// calling `progress` with the fraction done (every ~0.1 %): a [`Session`] stepped to the
    /// duration and finished, the one loop of every run.
    pub fn run(self, interrupt: &dyn Interrupt, progress: &mut dyn FnMut(f64)) -> DrillRun {
        Session::batch(self).run_to_end(interrupt, progress)
    }

    /// The series' values at `t` after a step with the motor and bit torques `motor` and `bit`
    /// ([`super::sampler`]'s channels; a coupled run's from [`Axial::sample`], zeros without a
    /// hoist).
    pub(super) fn sample(&self, t: f64, motor: f64, bit: f64) -> Point {
        let mut point = Point::default();
        point[TIME] = t;
        point[TOP_SPEED] = self.top.omega;
        point[BIT_SPEED] = self.bit_speed();
        point[MOTOR_TORQUE] = motor;
        point[BIT_TORQUE] = bit;
        if let Some(ax) = &self.axial {
            ax.sample(&mut point);
        }
        point
    }

    /// `consistent`: the largest tangent Courant number met, with a note when above 1.
    pub(super) fn courant_peak(&self, run: &mut DrillRun) {
        let Some(nl) = &self.torsion.field.nl else { return };
        let dt = self.grid.dt;
        let peak = (self.torsion.field.sections.iter().zip(&nl.laws).zip(&nl.peak_strain))
            .map(|((sp, law), &eps)| law.tangent_speed(eps) * dt / sp.h)
            .fold(0.0, f64::max);
        run.stats.courant_peak = peak;
        if peak > 1.0 + 1e-12 {
            let bound = self.cfg.numerics.max_shear_strain;
            let strain = (nl.peak_strain.iter().zip(&self.grid.strain_bound))
                .map(|(&eps, &b)| bound * eps / b)
                .fold(0.0, f64::max);
            let note = format!(
                "the shear strain reached {} > numerics.max_shear_strain = {}: the tangent Courant number \
                 reached {} > 1 (raise numerics.max_shear_strain)",
                Num(strain),
                Num(bound),
                Num(peak)
            );
            run.message = if run.message.is_empty() { note } else { format!("{}; {note}", run.message) };
        }
    }
}

/// A coupled run's metrics over the window `metrics.window` (the series' samples in it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CoupledMetrics {
    /// Mean rate of penetration, m/h.
    pub rop_mean_m_per_h: f64,
    /// Mean weight on bit, N.
    #[serde(rename = "wob_mean_N")]
    pub wob_mean_n: f64,
    /// Mean torque on bit, N m.
    #[serde(rename = "tob_mean_Nm")]
    pub tob_mean_nm: f64,
    /// Fraction of the samples with no weight on bit (bit bounce).
    pub bounce_fraction: f64,
    /// Mean hook load, N (a pick-up's or slack-off's load off bottom).
    #[serde(rename = "hook_load_mean_N")]
    pub hook_load_mean_n: f64,
    /// Teale's mechanical specific energy of the means (WOB, TOB, bit speed, ROP), Pa
    /// ([`mechanical_specific_energy`]; `inf` when nothing was drilled while the bit turned).
    #[serde(rename = "mse_mean_Pa")]
    pub mse_mean_pa: f64,
    /// The window's regime from the torsional verdict and the bounce fraction
    /// ([`crate::drilling::axial::regime::regime`]).
    pub regime: Regime,
}

/// The coupled metrics of `run`'s series over its window (None when it holds no sample); the
/// regime from `run.metrics` (set before).
pub fn coupled_metrics(run: &DrillRun, radius: f64) -> Option<CoupledMetrics> {
    let [a, b] = run.window;
    let idx: Vec<usize> = (0..run.t.len().min(run.rop.len())).filter(|&k| run.t[k] >= a && run.t[k] <= b).collect();
    if idx.is_empty() {
        return None;
    }
    let n = idx.len() as f64;
    let mean = |x: &[f64]| idx.iter().map(|&k| x[k]).sum::<f64>() / n;
    let (rop, wob, tob, rpm) = (mean(&run.rop), mean(&run.weight_on_bit), mean(&run.bit_torque), mean(&run.bit_rpm));
    let bounce = idx.iter().filter(|&&k| run.weight_on_bit[k] == 0.0).count() as f64 / n;
    let mse = mechanical_specific_energy(wob, tob, rpm / RPM_PER_RAD_S, rop / 3600.0, bit_area(radius));
    Some(CoupledMetrics {
        rop_mean_m_per_h: rop,
        wob_mean_n: wob,
        tob_mean_nm: tob,
        bounce_fraction: bounce,
        hook_load_mean_n: mean(&run.hook_load),
        mse_mean_pa: mse,
        regime: regime(run.metrics.as_ref().map(|m| m.stick_slip_verdict), bounce, axial_transient(run).is_some()),
    })
}

/// [`crate::drilling::plausibility::axial_transient`] of a coupled run's series over its window.
pub fn axial_transient(run: &DrillRun) -> Option<String> {
    crate::drilling::plausibility::axial_transient(&run.t, &run.rop, &run.weight_on_bit, run.window)
}

/// The stick-slip metrics of a run's series over its window, or a note why there are none.
pub(super) fn metrics(cfg: &DrillConfig, run: &mut DrillRun) {
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
}
