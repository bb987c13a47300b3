//! The discretisation and outputs (`[numerics]`), and the size of a run's outputs.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::super::grid::Grid;
use super::{
    nonneg, DrillConfig, FrictionModel, Nonlinearity, MAX_CELLS, MAX_CELL_STEPS, MAX_DURATION, MAX_OUTPUT_BYTES, SERIES,
};

/// Discretisation and outputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Numerics {
    /// Target number of cells: `dt = min(sum(L_i / c_i) / cells, min_i L_i / c_i)`, section `i`
    /// gets `floor(L_i / (c_i dt)) >= 1` cells (Courant number `<= 1`, `= 1` when uniform); a
    /// section shorter than a cell of the others raises the count.
    #[schemars(extend("unit" = "", "label" = "cells"))]
    pub cells: usize,
    /// Simulated time, > 0 and at most one day.
    #[schemars(extend("unit" = "s", "label" = "duration"))]
    pub duration: f64,
    /// Sampling interval of the time series, > 0 and at most `duration`.
    #[schemars(extend("unit" = "s", "label" = "output interval"))]
    pub output_interval: f64,
    /// Sampling interval of the space-time snapshots, >= 0 (0: none).
    #[schemars(extend("unit" = "s", "label" = "snapshot interval"))]
    pub field_interval: f64,
    /// A ceiling on `cells`, from 1 to 10 million (a guard against typos).
    #[schemars(extend("unit" = "", "label" = "maximum cells"))]
    pub max_cells: usize,
    /// `consistent` only: the largest shear strain at the outer surface, `gamma = (OD / 2) eps`,
    /// the time step is made for, in (0, 1].
    ///
    /// The step respects the tangent wave speed
    /// `sqrt((k2 + 3 k5 eps^2) / (rho J))` at this strain in every section (Courant number
    /// `<= 1`; every section's speed is raised by the largest of these hardening factors); a run
    /// whose strains exceed it reports a tangent Courant number above 1
    /// (`DrillStats::courant_peak`) in its message. Default 0.005: below the shear yield strain
    /// of high-strength drill-pipe steel (S-135: `931 MPa / sqrt(3) / G ~ 0.0068`), where the
    /// elastic law ends. A larger bound lowers the Courant numbers of the small strains below 1,
    /// where the first-order transport dissipates.
    #[schemars(extend("unit" = "", "label" = "maximum shear strain"))]
    pub max_shear_strain: f64,
    /// The Courant number `c dt / h` the step is made for, in `(0, 1]`: the step is this
    /// fraction of the Courant-1 step of the grid (the cells unchanged).
    ///
    /// Default 1: the exact shift, no numerical diffusion; below 1 the first-order upwind
    /// transport diffuses (`upwind_loss`), as the scheme of Aarsnes & Shor's code does at its 0.929.
    #[schemars(extend("unit" = "", "label" = "Courant number"))]
    pub courant: f64,
    /// The speed of a cell its sources are evaluated at: `after_transport` (default; the
    /// material now in the cell) or `before_transport` (the speed at the step start, as
    /// torsionalWaveStep.m of Aarsnes & Shor).
    ///
    /// With `before_transport` the wall friction's stick threshold (`friction.stick_speed`), the
    /// kinetic friction's direction and the viscous damping take the speed before the transport;
    /// the torque that stops a slow cell stays the one at the transported speed, and the kinetic
    /// friction is not clipped (it may reverse a cell within a step, as in their code). It exists
    /// to reproduce their published scheme; both converge to the same solution as the grid is
    /// refined. Linear torque-twist law and set-valued friction only.
    #[schemars(extend("label" = "source speed"))]
    pub source_speed: SourceSpeed,
    /// Where a coupled run starts: `rest` (default; the string at rest under its static
    /// tension, the bit just touching the rock, the setpoints ramping up) or `steady` (the bit
    /// law's steady drilling at the setpoints of t = 0, where Aarsnes & van de Wouw's code starts:
    /// turning at the top-drive speed with the torque of steady rotation, moving down at the
    /// hoist's rate, compressed to the steady weight on bit less the wall's drag, the bit at its
    /// steady depth of cut; [`super::start`]). `steady` needs a `[hoist]` that drills at t = 0.
    #[schemars(extend("label" = "initial state"))]
    pub initial_state: crate::drilling::start::InitialState,
    /// Whether the run keeps its energy ledger (default `true`): the work of the motor, the
    /// hoist, gravity and every loss as it is done, the stored energies at the end and
    /// `balance_error`, the check that the discrete energy balance closes.
    ///
    /// `false` leaves the energy terms out of the cell updates (a faster step) and reports
    /// every energy output as NaN, with a warning saying so; the series, snapshots and
    /// metrics are bit for bit those of the run with the ledger.
    #[schemars(extend("label" = "energy balance"))]
    pub energy_balance: bool,
}

/// The speed of a cell its sources are evaluated at ([`Numerics::source_speed`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SourceSpeed {
    /// The transported speed (the solver's scheme).
    #[default]
    AfterTransport,
    /// The speed before the transport (the scheme of torsionalWaveStep.m).
    BeforeTransport,
}

impl Default for Numerics {
    /// Aarsnes & Shor (2018), parameters_WellB.m and MAIN.m: 1000 cells, 60 s.
    fn default() -> Self {
        Numerics {
            cells: 1000,
            duration: 60.0,
            output_interval: 0.01,
            field_interval: 0.5,
            max_cells: 1_000_000,
            max_shear_strain: 0.005,
            courant: 1.0,
            source_speed: SourceSpeed::AfterTransport,
            initial_state: crate::drilling::start::InitialState::Rest,
            energy_balance: true,
        }
    }
}

impl DrillConfig {
    /// `numerics`: cells, duration, intervals, strain bound, Courant number, source speed.
    pub(super) fn validate_numerics(&self) -> Result<()> {
        let nu = &self.numerics;
        if !(1..=MAX_CELLS).contains(&nu.max_cells) {
            return Err(Error::invalid("numerics.max_cells", nu.max_cells, format!("an integer in 1..={MAX_CELLS}")));
        }
        if !(1..=nu.max_cells).contains(&nu.cells) {
            return Err(Error::invalid(
                "numerics.cells",
                nu.cells,
                format!("an integer in 1..={} (numerics.max_cells)", nu.max_cells),
            ));
        }
        if !(nu.duration.is_finite() && nu.duration > 0.0 && nu.duration <= MAX_DURATION) {
            return Err(Error::invalid(
                "numerics.duration",
                Num(nu.duration),
                format!("a number in (0, {MAX_DURATION}] s"),
            ));
        }
        if !(nu.output_interval.is_finite() && nu.output_interval > 0.0 && nu.output_interval <= nu.duration) {
            return Err(Error::invalid(
                "numerics.output_interval",
                Num(nu.output_interval),
                format!("a number in (0, numerics.duration = {}] s", Num(nu.duration)),
            ));
        }
        nonneg("numerics.field_interval", nu.field_interval, "s, 0 for no snapshots")?;
        if !(nu.max_shear_strain.is_finite() && nu.max_shear_strain > 0.0 && nu.max_shear_strain <= 1.0) {
            return Err(Error::invalid(
                "numerics.max_shear_strain",
                Num(nu.max_shear_strain),
                "a number in (0, 1] (-)",
            ));
        }
        if !(nu.courant.is_finite() && nu.courant > 0.0 && nu.courant <= 1.0) {
            return Err(Error::invalid("numerics.courant", Num(nu.courant), "a number in (0, 1] (-)"));
        }
        if nu.source_speed == SourceSpeed::BeforeTransport
            && (self.nonlinearity != Nonlinearity::Linear || self.friction.model != FrictionModel::SetValued)
        {
            return Err(Error::invalid(
                "numerics.source_speed",
                "before_transport",
                "after_transport, or before_transport with nonlinearity = linear and friction.model = set_valued",
            ));
        }
        Ok(())
    }

    /// Number of series samples (`t = k output_interval <= duration`).
    pub(crate) fn series_samples(&self) -> usize {
        samples(self.numerics.duration, self.numerics.output_interval)
    }

    /// Number of field snapshots (0 without).
    pub(crate) fn field_samples(&self) -> usize {
        if self.numerics.field_interval > 0.0 {
            samples(self.numerics.duration, self.numerics.field_interval)
        } else {
            0
        }
    }

    pub(super) fn check_outputs(&self, grid: &Grid) -> Result<()> {
        let series = self.series_samples().saturating_mul(SERIES).saturating_mul(8);
        if series > MAX_OUTPUT_BYTES {
            return Err(Error::invalid(
                "numerics.output_interval",
                Num(self.numerics.output_interval),
                format!(
                    "an interval giving at most {} MiB of series ({} samples need {} MiB)",
                    MAX_OUTPUT_BYTES >> 20,
                    self.series_samples(),
                    series >> 20
                ),
            ));
        }
        let fields = self.field_samples().saturating_mul(2 * grid.cells() + 1).saturating_mul(8);
        if series.saturating_add(fields) > MAX_OUTPUT_BYTES {
            return Err(Error::invalid(
                "numerics.field_interval",
                Num(self.numerics.field_interval),
                format!(
                    "an interval giving at most {} MiB of outputs ({} snapshots of {} cells need {} MiB)",
                    MAX_OUTPUT_BYTES >> 20,
                    self.field_samples(),
                    grid.cells(),
                    fields >> 20
                ),
            ));
        }
        let steps = (self.numerics.duration / grid.dt).ceil();
        let work = steps * grid.cells() as f64;
        if work > MAX_CELL_STEPS {
            // a section shorter than a cell of the others sets the step
            let travel: f64 = grid.props.iter().zip(&grid.speed).map(|(p, c)| p.length / c).sum();
            let short = (0..grid.props.len()).find(|&i| {
                grid.counts[i] == 1 && grid.props[i].length / grid.speed[i] < travel / self.numerics.cells as f64
            });
            let what = format!(
                "a run of at most {} cell updates (cells x time steps; this one needs {}: {} cells x {} steps of {} s, \
                 about {} h)",
                Num(MAX_CELL_STEPS),
                Num(work),
                grid.cells(),
                Num(steps),
                Num(grid.dt),
                Num((work / 6e8 / 3600.0 * 10.0).round() / 10.0)
            );
            return Err(match short {
                Some(i) => Error::invalid(
                    format!("sections[{i}].length"),
                    Num(self.sections[i].length),
                    format!("a section long enough for a reasonable time step (its travel time sets the step): {what}"),
                ),
                None => Error::invalid(
                    "numerics.cells",
                    self.numerics.cells,
                    format!("fewer cells or a shorter numerics.duration: {what}"),
                ),
            });
        }
        Ok(())
    }
}

/// Samples `k interval` for `k = 0, 1, ...` up to `duration` (with a relative tolerance).
fn samples(duration: f64, interval: f64) -> usize {
    let n = (duration / interval * (1.0 + 1e-12)).floor();
    if n.is_finite() && n < usize::MAX as f64 / 2.0 {
        n as usize + 1
    } else {
        usize::MAX
    }
}
