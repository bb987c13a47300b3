//! The configuration of a drilling-system run: JSON in (every field optional except
//! `sections` and each section's `length`, `outer_diameter`, `inner_diameter`), defaults from
//! the `Default` impls of each table (one place each), validation naming dotted fields
//! (`sections[1].outer_diameter`, `top_drive.controller.kp`), the limits of a run
//! ([`MAX_CELLS`], [`MAX_DURATION`], [`MAX_OUTPUT_BYTES`], [`MAX_SECTIONS`]).
//!
//! Units: SI, except angles in degrees (`inclination_deg`) and speeds in rpm (`rpm`, `steps`);
//! stick speeds are rad/s.
//!
//! One file per table, each with its structs, their defaults and its `validate_*` check;
//! `parse.rs` reads a configuration, `overrides.rs` sets dotted paths in one.

mod bit;
mod changes;
mod friction;
mod hoist;
mod metrics;
mod numerics;
mod overrides;
mod parse;
mod sections;
mod top_drive;
mod torque_drag;
mod well;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Num, Result};

use super::grid::Grid;

pub use bit::{Bit, BitRockLaw, CutSurfaceScheme, Detournay, Weakening, MAX_CUT_SURFACE_CELLS};
pub use changes::{changes_from_json, settable_config, Change, SETTABLE};
pub use friction::{Contact, Friction, FrictionCoupling, FrictionInterval, FrictionModel};
pub use hoist::{Autodriller, AutodrillerTarget, Hoist, HoistMode};
pub use metrics::MetricsConfig;
pub use numerics::{Numerics, SourceSpeed};
pub(crate) use overrides::override_pairs;
pub use overrides::{apply_overrides, override_json, override_value, set_path, Override, PATH_FORM};
use parse::bit_size_conflict;
pub(crate) use parse::{REQUIRED_SECTION, REQUIRED_TOP};
pub use sections::{Nonlinearity, Section};
pub use top_drive::{Controller, ControllerKind, ControllerPreset, TopDrive, TopMode};
pub use torque_drag::TorqueDragConfig;
pub use well::{Inclination, Well};

/// Largest number of cells a run may have (`numerics.max_cells` may lower it).
pub const MAX_CELLS: usize = 10_000_000;
/// Largest number of string sections.
pub const MAX_SECTIONS: usize = 1_000;
/// Longest simulated duration, s (one day).
pub const MAX_DURATION: f64 = 86_400.0;
/// Largest memory of a run's outputs (series and field snapshots), bytes (512 MiB).
pub const MAX_OUTPUT_BYTES: usize = 512 << 20;
/// The default motor torque limit, N m ([`TopDrive::torque_limit`]).
pub const DEFAULT_TORQUE_LIMIT: f64 = 60e3;
/// Largest number of cell updates (cells times time steps) of one run: about half an hour at
/// the 6e8 cell updates per second one core of a 2-core AMD EPYC reaches (Well B, 1000 cells,
/// 60 s in 0.11 s). A run asking more is refused before it starts, naming what makes it long.
pub const MAX_CELL_STEPS: f64 = 1e12;
/// Largest outer diameter of a section, m (a hard limit against unit mistakes and overflow;
/// drill strings are below 0.5 m).
pub const MAX_DIAMETER: f64 = 10.0;
/// Longest section, m.
pub const MAX_SECTION_LENGTH: f64 = 100_000.0;
/// Number of output series stored per sample (`t`, surface and bit speed, motor and bit torque).
pub(crate) const SERIES: usize = 5;

/// A drilling-system run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DrillConfig {
    /// The string's sections from the top, 1 to 1000 (required).
    #[schemars(extend("label" = "sections"))]
    pub sections: Vec<Section>,
    #[schemars(extend("label" = "well"))]
    pub well: Well,
    #[schemars(extend("label" = "wall friction"))]
    pub friction: Friction,
    /// Viscous damping rate `c`, >= 0: the force `-rho J c omega` per unit length.
    #[schemars(extend("unit" = "1/s", "label" = "damping rate"))]
    pub damping_rate: f64,
    /// The torque-twist law: `linear` (default) or `consistent` (finite strain).
    #[schemars(extend("label" = "torque-twist law"))]
    pub nonlinearity: Nonlinearity,
    #[schemars(extend("label" = "top drive"))]
    pub top_drive: TopDrive,
    #[schemars(extend("label" = "bit"))]
    pub bit: Bit,
    #[schemars(extend("label" = "numerics"))]
    pub numerics: Numerics,
    #[schemars(extend("label" = "metrics"))]
    pub metrics: MetricsConfig,
    #[schemars(extend("label" = "torque and drag"))]
    pub torque_drag: TorqueDragConfig,
    /// The hoist: null (default) for a torsion-only run.
    #[schemars(extend("label" = "hoist"))]
    pub hoist: Option<Hoist>,
    /// Values changed during the run, `[[changes]]` entries of `time`, `key` and `value`
    /// (what a session's changes replay as): each from the step starting at the step boundary
    /// nearest its time, in time order.
    #[schemars(extend("label" = "changes"))]
    pub changes: Vec<Change>,
}

impl Default for DrillConfig {
    /// One template section ([`Section::default`]); every other part its own default.
    fn default() -> Self {
        DrillConfig {
            sections: vec![Section::default()],
            well: Well::default(),
            friction: Friction::default(),
            damping_rate: 0.0,
            nonlinearity: Nonlinearity::Linear,
            top_drive: TopDrive::default(),
            bit: Bit::default(),
            numerics: Numerics::default(),
            metrics: MetricsConfig::default(),
            torque_drag: TorqueDragConfig::default(),
            hoist: None,
            changes: Vec::new(),
        }
    }
}

impl DrillConfig {
    /// Checks every value's range, naming the dotted field; also the discretisation (cell
    /// count, time step) and the output size against [`MAX_OUTPUT_BYTES`].
    pub fn validate(&self) -> Result<()> {
        self.validate_values()?;
        self.validate_changes()
    }

    /// [`DrillConfig::validate`] but for `[[changes]]`.
    pub fn validate_values(&self) -> Result<()> {
        self.validate_sections()?;
        self.validate_well()?;
        self.validate_friction_intervals()?;
        super::limits::validate_torque_drag(self)?;
        super::pipe::validate(self)?;
        self.validate_friction()?;
        nonneg("damping_rate", self.damping_rate, "1/s")?;
        self.validate_coupled()?;
        self.validate_top_drive()?;
        self.validate_bit()?;
        self.validate_numerics()?;
        self.validate_metrics()?;
        super::limits::validate_loads(self)?;
        let grid = Grid::new(self)?;
        self.check_outputs(&grid)?;
        super::limits::check_cut_surface_work(self, &grid)
    }
}

/// Validation helpers: an error naming `field` unless `x` is in range.
pub(super) fn pos(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number > 0 ({unit})")))
    }
}
pub(super) fn nonneg(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number >= 0 ({unit})")))
    }
}
pub(super) fn within(field: impl Into<String>, x: f64, lo: f64, hi: f64, unit: &str) -> Result<()> {
    if x.is_finite() && (lo..=hi).contains(&x) {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a number in [{}, {}] ({unit})", Num(lo), Num(hi))))
    }
}
pub(super) fn finite(field: impl Into<String>, x: f64, unit: &str) -> Result<()> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, Num(x), format!("a finite number ({unit})")))
    }
}
