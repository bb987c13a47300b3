//! The one list of what a run reports: every metric and every series channel, declared once
//! ([`OUTPUTS`]) with its name, SI unit, definition, the runs that have it, whether it is a
//! column of a stick-slip map, its kind and where its value comes from. Everything that names
//! an output reads it here: the metrics dicts of the bindings ([`MetricsView`]), the columns of
//! a map ([`metric_columns`], [`coupled_columns`]), the tolerances of the grid and start checks
//! ([`tolerances`]), the headline metrics of a result ([`headline`]), and through
//! `_core.drill_outputs()` Python's `metrics.json`, map tables, units and the documentation's
//! table of metrics.
//!
//! Names follow one rule: a metric with a unit ends in its SI unit's symbol (`_s`, `_N`, `_Nm`,
//! `_Pa`, `_Hz`, `/` written `_per_`: `_m_per_h`), except a speed in rpm, which carries the unit
//! as the word `rpm` (`bit_rpm_mean`, `surface_rpm`), and the bounds of the metrics window on the
//! run's clock (`window_start`, `window_end`, s); a dimensionless metric, a verdict, a count or a
//! text has no suffix. A series channel is named by its quantity; its unit is its entry's.
//!
//! A new stick-slip metric is a field of [`StickSlip`] computed in `metrics/stickslip.rs` and one
//! entry here; `metrics.json`, a map's columns, `DrillResult.metrics` and the documentation
//! follow.

use std::borrow::Cow;

use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

use crate::drilling::compare::Kind as Judge;
use crate::drilling::engine::CoupledMetrics;
use crate::metrics::StickSlip;

/// What an output is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// A number (NaN: undefined).
    Number,
    /// True or false (1 or 0 in a map's table).
    Verdict,
    /// A whole number.
    Count,
    /// A word or sentence.
    Text,
    /// A series channel: one value per output time.
    Series,
}

/// The runs that report an output: a drilling run of the string (`torsional`, also each run of
/// a map), its coupled axial-torsional part (`coupled`, a run with a `[hoist]`), the lumped
/// two-inertia model (`lumped`). A stick-slip metric of any series (`stick_slip_metrics`) has
/// every entry whose value comes from [`StickSlip`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Runs {
    pub torsional: bool,
    pub coupled: bool,
    pub lumped: bool,
}

const STICK: Runs = Runs { torsional: true, coupled: false, lumped: true };
const STRING: Runs = Runs { torsional: true, coupled: false, lumped: false };
const COUPLED: Runs = Runs { torsional: false, coupled: true, lumped: false };

/// One value of an output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell<'a> {
    Number(f64),
    Verdict(bool),
    Count(usize),
    Text(&'a str),
}

impl Cell<'_> {
    /// The value in a map's numeric column: a verdict 1 or 0, a count as a float (NaN for a text).
    pub fn number(self) -> f64 {
        match self {
            Cell::Number(x) => x,
            Cell::Verdict(b) => f64::from(u8::from(b)),
            Cell::Count(n) => n as f64,
            Cell::Text(_) => f64::NAN,
        }
    }
}

impl Serialize for Cell<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match *self {
            Cell::Number(x) => s.serialize_f64(x),
            Cell::Verdict(b) => s.serialize_bool(b),
            Cell::Count(n) => s.serialize_u64(n as u64),
            Cell::Text(t) => s.serialize_str(t),
        }
    }
}

/// The values of a run that its metrics read: the stick-slip metrics of its window (or
/// [`StickSlip::UNDEFINED`]), the window asked for and the static torques of the string.
#[derive(Debug, Clone, Copy)]
pub struct RunValues<'a> {
    pub metrics: &'a StickSlip,
    /// `[start, end]` of the metrics window, s: the window asked for in a drilling run; the
    /// first and last sample in it of a series alone.
    pub window: [f64; 2],
    pub breakoff_torque: f64,
    pub min_cycle_torque: f64,
}

impl<'a> RunValues<'a> {
    /// The values of stick-slip metrics alone (a series, the lumped model): the window of their
    /// samples, no static torques.
    pub fn of(metrics: &'a StickSlip) -> Self {
        RunValues {
            metrics,
            window: [metrics.window_start, metrics.window_end],
            breakoff_torque: f64::NAN,
            min_cycle_torque: f64::NAN,
        }
    }
}

/// Where an output's value comes from.
#[derive(Clone, Copy)]
pub enum Source {
    /// A stick-slip metric of any series ([`crate::metrics::stick_slip`]).
    StickSlip(for<'a> fn(&'a StickSlip) -> Cell<'a>),
    /// A value of a drilling run beside its stick-slip metrics ([`RunValues`]).
    Run(fn(&RunValues) -> f64),
    /// A coupled run's metric ([`CoupledMetrics`]).
    Coupled(fn(&CoupledMetrics) -> Cell<'static>),
    /// A series channel of a run's output.
    Series,
}

/// How a metric may move between the two runs of a grid or start check
/// ([`crate::drilling::compare`]): the kind, the tolerance and the floor (a change at most this
/// large, in the metric's unit, is within whatever its relative size).
pub type Tolerance = (Judge, f64, f64);

/// One output of a run.
#[derive(Clone, Copy)]
pub struct Output {
    pub name: &'static str,
    /// The few words the console, `report.md` and the figures name it by (`ROP`, `stuck
    /// fraction`), without its unit.
    pub label: &'static str,
    /// SI unit as pint parses it (`""` dimensionless); None for a verdict, a count or a text.
    pub unit: Option<&'static str>,
    pub definition: &'static str,
    pub runs: Runs,
    /// A column of a stick-slip map's table and an entry of `metrics.json` (its `coupled` block
    /// for a coupled metric).
    pub map_column: bool,
    pub kind: Kind,
    pub source: Source,
    /// Its tolerance in the grid and start checks (None: not compared).
    pub tolerance: Option<Tolerance>,
    /// A headline metric: finite in every run that has metrics, or the run is not a result.
    pub headline: bool,
    /// On the console's summary of a run (`drillstring drill`), by its label, in this order.
    pub console: bool,
}

impl Output {
    /// The value of a drilling run's or a series' metric (NaN for a coupled metric or a series).
    pub fn value<'a>(&self, run: &RunValues<'a>) -> Cell<'a> {
        match self.source {
            Source::StickSlip(get) => get(run.metrics),
            Source::Run(get) => Cell::Number(get(run)),
            Source::Coupled(_) | Source::Series => Cell::Number(f64::NAN),
        }
    }

    /// Whether a run's (or a series') stick-slip metrics have it.
    pub fn is_stick_slip(&self) -> bool {
        matches!(self.source, Source::StickSlip(_) | Source::Run(_))
    }
}

const fn metric(
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    definition: &'static str,
    source: Source,
) -> Output {
    Output {
        name,
        label,
        unit: Some(unit),
        definition,
        runs: STICK,
        map_column: true,
        kind: Kind::Number,
        source,
        tolerance: None,
        headline: false,
        console: false,
    }
}

const fn tolerance(output: Output, judge: Judge, tolerance: f64, floor: f64) -> Output {
    Output { tolerance: Some((judge, tolerance, floor)), ..output }
}

const fn headline(output: Output) -> Output {
    Output { headline: true, ..output }
}

const fn console(output: Output) -> Output {
    Output { console: true, ..output }
}

const fn of_kind(output: Output, kind: Kind) -> Output {
    Output { kind, unit: None, ..output }
}

const fn string_only(output: Output) -> Output {
    Output { runs: STRING, ..output }
}

const fn not_a_column(output: Output) -> Output {
    Output { map_column: false, ..output }
}

const fn coupled(
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    definition: &'static str,
    tol: Tolerance,
) -> Output {
    Output {
        runs: COUPLED,
        tolerance: Some(tol),
        console: true,
        ..metric(name, label, unit, definition, Source::Series)
    }
}

const fn series(
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    definition: &'static str,
    runs: Runs,
) -> Output {
    Output { runs, map_column: false, kind: Kind::Series, ..metric(name, label, unit, definition, Source::Series) }
}

/// The criterion of the boolean `stick_slip`.
const STOPS: &str = "the verdict as true/false: the bit stops (|bit speed| <= metrics.stick_speed) during part of the \
     metrics window: 0 < stuck_fraction < 1 (stick_slip_verdict is yes)";

/// Every output of a run, in the order of `metrics.json`, a map's table and the documentation:
/// the stick-slip metrics, the coupled metrics, the series channels.
pub static OUTPUTS: &[Output] = &[
    metric("window_start", "window start", "s", "start of the metrics window, s", Source::Run(|r| r.window[0])),
    metric("window_end", "window end", "s", "end of the metrics window, s", Source::Run(|r| r.window[1])),
    tolerance(
        console(headline(metric(
            "ssi",
            "SSI",
            "",
            "stick-slip severity (max - min) / (2 |mean|) of the bit speed over the window",
            Source::StickSlip(|m| Cell::Number(m.ssi)),
        ))),
        Judge::Rel,
        0.05,
        0.01,
    ),
    tolerance(
        console(headline(metric(
            "stuck_fraction",
            "stuck fraction",
            "",
            "fraction of the window's time with |bit speed| <= metrics.stick_speed; the bit is at rest while the \
             string above it is stuck (converges with the grid)",
            Source::StickSlip(|m| Cell::Number(m.stuck_fraction)),
        ))),
        Judge::Abs,
        0.03,
        0.0,
    ),
    tolerance(
        console(metric(
            "period_s",
            "period",
            "s",
            "stick-slip period from the autocorrelation of the motor torque, s; null with fewer than two cycles in \
             the window",
            Source::StickSlip(|m| Cell::Number(m.period_s)),
        )),
        Judge::Rel,
        0.02,
        0.0,
    ),
    tolerance(
        console(headline(metric(
            "bit_rpm_min",
            "lowest bit speed",
            "rpm",
            "lowest bit speed, rpm; off bottom the stopping front reflects at the free end at re-stick and turns the \
             bit back by a few rpm for some tens of ms, an amount that varies from cycle to cycle and between grids \
             (not converged: check it with check_grid)",
            Source::StickSlip(|m| Cell::Number(m.bit_rpm_min)),
        ))),
        Judge::Abs,
        1.0,
        0.0,
    ),
    tolerance(
        console(headline(metric(
            "bit_rpm_max",
            "highest bit speed",
            "rpm",
            "highest bit speed, rpm",
            Source::StickSlip(|m| Cell::Number(m.bit_rpm_max)),
        ))),
        Judge::Rel,
        0.05,
        0.0,
    ),
    tolerance(
        console(headline(metric(
            "bit_rpm_mean",
            "mean bit speed",
            "rpm",
            "time-weighted mean bit speed, rpm",
            Source::StickSlip(|m| Cell::Number(m.bit_rpm_mean)),
        ))),
        Judge::Rel,
        0.02,
        0.0,
    ),
    tolerance(
        console(headline(metric(
            "motor_torque_min_Nm",
            "lowest motor torque",
            "N*m",
            "lowest motor torque, N m (the lumped model: its spring torque)",
            Source::StickSlip(|m| Cell::Number(m.motor_torque_min_nm)),
        ))),
        Judge::Rel,
        0.03,
        0.0,
    ),
    tolerance(
        console(headline(metric(
            "motor_torque_max_Nm",
            "highest motor torque",
            "N*m",
            "highest motor torque, N m",
            Source::StickSlip(|m| Cell::Number(m.motor_torque_max_nm)),
        ))),
        Judge::Rel,
        0.03,
        0.0,
    ),
    tolerance(
        string_only(console(metric(
            "breakoff_torque_Nm",
            "break-off torque",
            "N*m",
            "static break-off torque of the string in the well, N m",
            Source::Run(|r| r.breakoff_torque),
        ))),
        Judge::Rel,
        0.001,
        0.0,
    ),
    metric(
        "period_cycles",
        "periods in the window",
        "",
        "the window's length in periods",
        Source::StickSlip(|m| Cell::Number(m.period_cycles)),
    ),
    metric(
        "periodicity",
        "periodicity",
        "",
        "similarity of the motor torque with itself one period later (1: exactly periodic)",
        Source::StickSlip(|m| Cell::Number(m.periodicity)),
    ),
    metric(
        "slip_period_s",
        "period from the slip onsets",
        "s",
        "mean interval between the bit's slip onsets (slips that carry it above its mean speed), s (cross-check of \
         period_s)",
        Source::StickSlip(|m| Cell::Number(m.slip_period_s)),
    ),
    tolerance(
        of_kind(
            metric("stick_slip", "stick-slip", "", STOPS, Source::StickSlip(|m| Cell::Verdict(m.stick_slip))),
            Kind::Verdict,
        ),
        Judge::Equal,
        0.0,
        0.0,
    ),
    tolerance(
        of_kind(
            metric(
                "settled",
                "settled",
                "",
                "the first and the last whole periods of the window (as many as half of it holds) agree in means and \
                 ranges to 5 %: not a transient",
                Source::StickSlip(|m| Cell::Verdict(m.settled)),
            ),
            Kind::Verdict,
        ),
        Judge::Equal,
        0.0,
        0.0,
    ),
    string_only(console(metric(
        "min_cycle_torque_Nm",
        "minimum cycle torque",
        "N*m",
        "minimum motor torque of a stick-slip cycle that break-off implies, N m",
        Source::Run(|r| r.min_cycle_torque),
    ))),
    of_kind(
        metric(
            "stick_slip_verdict",
            "stick-slip verdict",
            "",
            "the verdict yes / no / undetermined (stick_slip_criterion; stick_slip_reason says why)",
            Source::StickSlip(|m| Cell::Text(m.stick_slip_verdict.name())),
        ),
        Kind::Text,
    ),
    metric(
        "stick_duration_mean_s",
        "mean stick duration",
        "s",
        "mean duration of the bit's stick phases (its time at |bit speed| <= metrics.stick_speed between two slips \
         that carry it above its mean speed, so a partial slip does not split a phase) that begin and end within the \
         window, s; null without a complete one",
        Source::StickSlip(|m| Cell::Number(m.stick_duration_mean_s)),
    ),
    not_a_column(of_kind(
        metric(
            "slip_onsets",
            "slip onsets",
            "",
            "slip onsets of the bit in the window",
            Source::StickSlip(|m| Cell::Count(m.slip_onsets)),
        ),
        Kind::Count,
    )),
    not_a_column(of_kind(
        metric(
            "stick_slip_reason",
            "reason",
            "",
            "why the verdict is what it is, in a few words",
            Source::StickSlip(|m| Cell::Text(&m.stick_slip_reason)),
        ),
        Kind::Text,
    )),
    Output {
        source: Source::Coupled(|c| Cell::Number(c.rop_mean_m_per_h)),
        ..coupled(
            "rop_mean_m_per_h",
            "ROP",
            "m/h",
            "mean rate of penetration over the window, m/h",
            (Judge::Rel, 0.02, 0.0),
        )
    },
    Output {
        source: Source::Coupled(|c| Cell::Number(c.wob_mean_n)),
        ..coupled("wob_mean_N", "weight on bit", "N", "mean weight on bit over the window, N", (Judge::Rel, 0.02, 0.0))
    },
    Output {
        source: Source::Coupled(|c| Cell::Number(c.tob_mean_nm)),
        ..coupled(
            "tob_mean_Nm",
            "torque on bit",
            "N*m",
            "mean torque on bit over the window, N m",
            (Judge::Rel, 0.02, 0.0),
        )
    },
    Output {
        source: Source::Coupled(|c| Cell::Number(c.bounce_fraction)),
        ..coupled(
            "bounce_fraction",
            "bit bounce",
            "",
            "fraction of the window's samples with no weight on bit (bit bounce, or off bottom)",
            (Judge::Abs, 0.02, 0.0),
        )
    },
    Output {
        source: Source::Coupled(|c| Cell::Number(c.hook_load_mean_n)),
        ..coupled(
            "hook_load_mean_N",
            "hook load",
            "N",
            "mean hook load over the window, N (a pick-up's or slack-off's load off bottom)",
            (Judge::Rel, 0.01, 0.0),
        )
    },
    Output {
        source: Source::Coupled(|c| Cell::Number(c.mse_mean_pa)),
        ..coupled(
            "mse_mean_Pa",
            "MSE",
            "Pa",
            "Teale's mechanical specific energy of the window's means (weight and torque on bit, bit speed, ROP), Pa; \
             inf when nothing was drilled while the bit turned",
            (Judge::Rel, 0.03, 0.0),
        )
    },
    Output {
        source: Source::Coupled(|c| Cell::Text(c.regime.name())),
        kind: Kind::Text,
        console: false,
        unit: None,
        ..coupled(
            "regime",
            "regime",
            "",
            "the window's regime from the stick-slip verdict and the bounce fraction (coupled_regime_criterion)",
            (Judge::Equal, 0.0, 0.0),
        )
    },
    series("surface_rpm", "surface speed", "rpm", "top drive (surface) speed", STRING),
    series("bit_rpm", "bit speed", "rpm", "bit speed", STRING),
    series("motor_torque", "motor torque", "N*m", "motor torque of the top drive", STRING),
    series("bit_torque", "torque on bit", "N*m", "torque on bit", STRING),
    series("bit_axial_speed", "bit axial speed", "m/s", "axial speed of the bit, down positive", COUPLED),
    series("rop", "ROP", "m/h", "rate of penetration", COUPLED),
    series("weight_on_bit", "weight on bit", "N", "weight on bit", COUPLED),
    series("hook_load", "hook load", "N", "hook load", COUPLED),
    series("bit_depth", "bit depth", "m", "bit depth drilled since the start", COUPLED),
    series("depth_of_cut", "depth of cut", "m", "depth of cut per revolution of the bit", COUPLED),
    series(
        "block_position",
        "block position",
        "m",
        "the block's (the top of the string's) position from the start, down positive",
        COUPLED,
    ),
];

/// The output named `name`.
pub fn output(name: &str) -> Option<&'static Output> {
    OUTPUTS.iter().find(|o| o.name == name)
}

/// The tolerances of the grid and start checks: `(metric, kind, tolerance, floor)` in the
/// order of [`OUTPUTS`].
pub fn tolerances() -> Vec<(&'static str, Judge, f64, f64)> {
    OUTPUTS.iter().filter_map(|o| o.tolerance.map(|(k, t, f)| (o.name, k, t, f))).collect()
}

/// The headline metrics of a run with their values: each finite in a run that has metrics.
pub fn headline_values(m: &StickSlip) -> Vec<(&'static str, f64)> {
    let run = RunValues::of(m);
    OUTPUTS.iter().filter(|o| o.headline).map(|o| (o.name, o.value(&run).number())).collect()
}

/// Which metrics a [`MetricsView`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Report {
    /// A drilling run's: every torsional stick-slip metric.
    Drilling,
    /// The lumped model's.
    Lumped,
    /// The stick-slip metrics of a series alone.
    Series,
}

impl Report {
    fn has(self, o: &Output) -> bool {
        match self {
            Report::Drilling => o.runs.torsional && o.is_stick_slip(),
            Report::Lumped => o.runs.lumped && o.is_stick_slip(),
            Report::Series => matches!(o.source, Source::StickSlip(_)) || o.name.starts_with("window_"),
        }
    }
}

/// A run's metrics as a map of name to value (the dicts of the bindings), with the warnings the
/// core chose for them.
pub struct MetricsView<'a> {
    pub run: RunValues<'a>,
    pub report: Report,
    pub warnings: Vec<String>,
}

impl Serialize for MetricsView<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for o in OUTPUTS.iter().filter(|o| self.report.has(o)) {
            map.serialize_entry(o.name, &o.value(&self.run))?;
        }
        map.serialize_entry("warnings", &List(&self.warnings))?;
        map.end()
    }
}

/// A list of texts serialised as a list (not an array).
struct List<'a>(&'a [String]);

impl Serialize for List<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        crate::solution::serialize_list(self.0, s)
    }
}

/// One column of a map's table.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Column {
    Numbers(Vec<f64>),
    Texts(Vec<Cow<'static, str>>),
}

/// Named columns in the order of [`OUTPUTS`], serialised as a map.
#[derive(Debug, Clone, PartialEq)]
pub struct Columns(pub Vec<(&'static str, Column)>);

impl Columns {
    /// The column named `name`.
    pub fn get(&self, name: &str) -> Option<&Column> {
        self.0.iter().find(|(n, _)| *n == name).map(|(_, c)| c)
    }
}

impl Serialize for Columns {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, column) in &self.0 {
            map.serialize_entry(name, column)?;
        }
        map.end()
    }
}

/// A column of texts or numbers (a verdict 1 or 0, a count as a float) of `cells`.
fn column<'a>(kind: Kind, cells: impl Iterator<Item = Option<Cell<'a>>>) -> Column {
    if kind == Kind::Text {
        let text = |c: Option<Cell<'_>>| match c {
            Some(Cell::Text(t)) => Cow::Owned(t.to_string()),
            _ => Cow::Borrowed(""),
        };
        Column::Texts(cells.map(text).collect())
    } else {
        Column::Numbers(cells.map(|c| c.map_or(f64::NAN, Cell::number)).collect())
    }
}

/// The stick-slip metric columns of a map (its [`Output::map_column`] entries of a drilling run):
/// one value per run (`rows`: whether it has metrics, and its values), NaN (the verdict
/// `undetermined`) for a run without metrics; the window and static torques of every run.
pub fn metric_columns(rows: &[(bool, RunValues<'_>)]) -> Columns {
    let undefined = RunValues::of(&StickSlip::UNDEFINED);
    Columns(
        OUTPUTS
            .iter()
            .filter(|o| o.map_column && Report::Drilling.has(o))
            .map(|o| {
                let cells = rows.iter().map(|(has, r)| match (o.source, has, o.kind) {
                    // a run's own values are there without metrics too
                    (Source::Run(_), _, _) | (_, true, _) => Some(o.value(r)),
                    (_, false, Kind::Text) => Some(o.value(&undefined)),
                    _ => None,
                });
                (o.name, column(o.kind, cells))
            })
            .collect(),
    )
}

/// The coupled metric columns of a map: one value per run, NaN (regime `undetermined`) for a
/// run without them.
pub fn coupled_columns(rows: &[Option<CoupledMetrics>]) -> Columns {
    let undefined = Cell::Text(crate::drilling::axial::regime::Regime::Undetermined.name());
    Columns(
        OUTPUTS
            .iter()
            .filter(|o| o.map_column && o.runs.coupled)
            .filter_map(|o| match o.source {
                Source::Coupled(get) => {
                    let cells = rows.iter().map(|c| match (c, o.kind) {
                        (Some(c), _) => Some(get(c)),
                        (None, Kind::Text) => Some(undefined),
                        (None, _) => None,
                    });
                    Some((o.name, column(o.kind, cells)))
                }
                _ => None,
            })
            .collect(),
    )
}

/// A coupled run's metrics by name (the `coupled` block of a run).
pub fn coupled_values(c: &CoupledMetrics) -> Vec<(&'static str, Cell<'static>)> {
    OUTPUTS
        .iter()
        .filter_map(|o| match o.source {
            Source::Coupled(get) => Some((o.name, get(c))),
            _ => None,
        })
        .collect()
}

/// One entry of [`describe`].
#[derive(Debug, Clone, Serialize)]
pub struct Description {
    pub name: &'static str,
    pub label: &'static str,
    pub unit: Option<&'static str>,
    pub definition: &'static str,
    pub runs: Vec<&'static str>,
    pub map_column: bool,
    pub kind: Kind,
    /// `(kind, tolerance, floor)` of the grid and start checks.
    pub tolerance: Option<Tolerance>,
    pub headline: bool,
    /// On the console's summary of a run.
    pub console: bool,
    /// Computed by the stick-slip metrics of any series (`stick_slip_metrics`).
    pub of_any_series: bool,
}

/// Every output as data, in order (`_core.drill_outputs()`).
pub fn describe() -> Vec<Description> {
    OUTPUTS
        .iter()
        .map(|o| Description {
            name: o.name,
            label: o.label,
            unit: o.unit,
            definition: o.definition,
            runs: [("torsional", o.runs.torsional), ("coupled", o.runs.coupled), ("lumped", o.runs.lumped)]
                .into_iter()
                .filter_map(|(n, has)| has.then_some(n))
                .collect(),
            map_column: o.map_column,
            kind: o.kind,
            tolerance: o.tolerance,
            headline: o.headline,
            console: o.console,
            of_any_series: Report::Series.has(o),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_follow_the_unit_rule() {
        for (i, o) in OUTPUTS.iter().enumerate() {
            assert!(OUTPUTS[..i].iter().all(|p| p.name != o.name), "{} twice", o.name);
            if o.kind != Kind::Series && o.kind != Kind::Number {
                assert_eq!(o.unit, None, "{}", o.name);
                continue;
            }
            let unit = o.unit.unwrap_or_else(|| panic!("{} has no unit", o.name));
            let suffix = match unit {
                "" => None,
                "s" if o.name.starts_with("window_") => None,
                "s" => Some("_s"),
                "N" => Some("_N"),
                "N*m" => Some("_Nm"),
                "Pa" => Some("_Pa"),
                "Hz" => Some("_Hz"),
                "m/h" => Some("_m_per_h"),
                "rpm" => {
                    assert!(o.name.contains("rpm"), "{}", o.name);
                    None
                }
                _ => None,
            };
            if o.kind == Kind::Number {
                if let Some(suffix) = suffix {
                    assert!(o.name.ends_with(suffix), "{} in {unit} does not end in {suffix}", o.name);
                }
                if suffix.is_none() && unit.is_empty() {
                    assert!(!["_s", "_N", "_Nm", "_Pa", "_Hz"].iter().any(|s| o.name.ends_with(s)), "{}", o.name);
                }
            }
        }
    }

    /// Every stick-slip metric of the registry is a field of [`StickSlip`] under its name, and
    /// every field but the metrics' own bookkeeping is in the registry.
    #[test]
    fn the_stick_slip_fields_are_the_registry() {
        let value = serde_json::to_value(StickSlip::UNDEFINED).unwrap();
        let fields: Vec<&str> = value.as_object().unwrap().keys().map(String::as_str).collect();
        for o in OUTPUTS.iter().filter(|o| matches!(o.source, Source::StickSlip(_))) {
            assert!(fields.contains(&o.name), "{} is not a field of StickSlip", o.name);
        }
        for f in fields {
            assert!(output(f).is_some_and(|o| Report::Series.has(o)), "StickSlip.{f} is not in the registry");
        }
    }

    #[test]
    fn tolerances_and_headlines() {
        let t = tolerances();
        assert_eq!(t.len(), 18);
        assert_eq!(t.iter().filter(|t| t.1 == Judge::Equal).count(), 3);
        assert_eq!(t.iter().filter(|t| t.3 > 0.0).count(), 1);
        let names: Vec<_> = headline_values(&StickSlip::UNDEFINED).into_iter().map(|h| h.0).collect();
        assert_eq!(names.len(), 7);
        assert!(names.contains(&"ssi") && names.contains(&"motor_torque_max_Nm"));
    }
}
