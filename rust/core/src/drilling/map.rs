//! Stick-slip maps: many drilling runs of one base configuration, each with its own field
//! overrides, solved in parallel; one row of metrics per run (no time series are kept).
//!
//! Each run is the base configuration (JSON) with its overrides set by dotted path
//! (`top_drive.rpm`, `sections[1].length`, `top_drive.controller.type`; [`apply_overrides`], as
//! for Python's `DrillConfig.with_overrides`), then [`DrillConfig::from_json`] and [`DrillConfig::validate`] as for a single run, and
//! [`solve`] with the field snapshots switched off (`numerics.field_interval = 0`: they do not
//! change the dynamics, the series or the metrics). The metrics are the solve's own
//! ([`crate::metrics::stick_slip`] over its window; a coupled run's also its
//! [`CoupledMetrics`] with the regime, [`super::axial::regime`]); the series are dropped when the run ends,
//! so a row's memory does not depend on the duration (a thread holds the series of the one run
//! it is solving).
//!
//! A run whose configuration is refused is a row with status `invalid` and the message naming
//! the field; it never fails the map. An axis that changes nothing (a key without effect in
//! every run's configuration, [`super::effect::no_effect`]: `top_drive.rpm` under
//! `top_drive.mode = "measured_speed"`) fails it, naming the key and why ([`check_axes`]). The runs go on a thread pool made for the call (never
//! rayon's global pool, so a process that forks can run maps in the child), as
//! [`crate::sweep::batch_solve_with`] does.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde_json::Value;

pub use super::config::{apply_overrides, set_path, Override};
use super::config::{override_pairs, DrillConfig, SERIES};
use super::effect::no_effect;
use super::engine::CoupledMetrics;
use super::solver::{solve, DrillStats};
use crate::error::{Error, Result};
use crate::interrupt::{CancelFlag, Interrupt};
use crate::metrics::StickSlip;
use crate::outputs::{coupled_columns, metric_columns, Columns, RunValues};
use crate::solution::Status;
use crate::sweep::batch::run_on_pool;
use crate::sweep::{resolve_threads, RunStatus};

/// The outcome of one run of a map. `metrics` is `None` unless the run succeeded.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRow {
    pub status: RunStatus,
    /// Why the run failed or was refused (`""` on success).
    pub message: String,
    pub metrics: Option<StickSlip>,
    /// The metrics window `[t_start, t_end]` asked for (NaN for an invalid run).
    pub window: [f64; 2],
    /// Static break-off torque, N m (NaN for an invalid run).
    pub breakoff_torque: f64,
    /// Minimum cycle torque implied by break-off, N m (NaN for an invalid run).
    pub min_cycle_torque: f64,
    pub stats: DrillStats,
    /// Relative energy balance error of the run (NaN for an invalid run).
    pub balance_error: f64,
    /// A coupled run's metrics and regime (`None` unless a coupled run succeeded).
    pub coupled: Option<CoupledMetrics>,
}

/// The rows of a map as the columns of its table: one entry per run. A run without metrics
/// (refused, failed, interrupted) has NaN in every metric column; the verdicts `stick_slip` and
/// `settled` are 1 or 0 (NaN without metrics), so that every metric column but the three-way
/// `stick_slip_verdict` (its name) is a float column. The metric and coupled columns are the
/// registry's ([`crate::outputs::metric_columns`], [`crate::outputs::coupled_columns`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MapColumns {
    /// The run's status name (`success`, `invalid`, ...).
    pub status: Vec<&'static str>,
    pub message: Vec<String>,
    pub metrics: Columns,
    pub stats: StatColumns,
    /// A coupled run's metrics (NaN, regime `undetermined`, for a run without them: a
    /// torsion-only or failed run).
    pub coupled: Columns,
}

/// The solver columns of [`MapColumns`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StatColumns {
    pub cells: Vec<u64>,
    pub steps: Vec<u64>,
    pub dt: Vec<f64>,
    pub balance_error: Vec<f64>,
    pub courant_peak: Vec<f64>,
}

impl MapColumns {
    pub fn new(rows: &[MapRow]) -> MapColumns {
        let row = |f: fn(&MapRow) -> f64| -> Vec<f64> { rows.iter().map(f).collect() };
        let values: Vec<(bool, RunValues<'_>)> = rows
            .iter()
            .map(|r| {
                let values = RunValues {
                    metrics: r.metrics.as_ref().unwrap_or(&StickSlip::UNDEFINED),
                    window: r.window,
                    breakoff_torque: r.breakoff_torque,
                    min_cycle_torque: r.min_cycle_torque,
                };
                (r.metrics.is_some(), values)
            })
            .collect();
        let coupled: Vec<Option<CoupledMetrics>> = rows.iter().map(|r| r.coupled).collect();
        MapColumns {
            status: rows.iter().map(|r| r.status.name()).collect(),
            message: rows.iter().map(|r| r.message.clone()).collect(),
            metrics: metric_columns(&values),
            stats: StatColumns {
                cells: rows.iter().map(|r| r.stats.cells as u64).collect(),
                steps: rows.iter().map(|r| r.stats.steps).collect(),
                dt: row(|r| r.stats.dt),
                balance_error: row(|r| r.balance_error),
                courant_peak: row(|r| r.stats.courant_peak),
            },
            coupled: coupled_columns(&coupled),
        }
    }
}

impl MapRow {
    fn failed(status: RunStatus, message: String) -> Self {
        MapRow {
            status,
            message,
            metrics: None,
            window: [f64::NAN; 2],
            breakoff_torque: f64::NAN,
            min_cycle_torque: f64::NAN,
            stats: DrillStats::default(),
            balance_error: f64::NAN,
            coupled: None,
        }
    }
}

/// The configuration of one run: `base` with `overrides` set in order
/// ([`apply_overrides`]), parsed and validated.
pub fn run_config(base: &Value, overrides: &[Override]) -> Result<DrillConfig> {
    let mut value = base.clone();
    apply_overrides(&mut value, overrides, "axis")?;
    let mut cfg = DrillConfig::from_value(value)?;
    // a map keeps no snapshots: their size is neither checked nor counted
    cfg.numerics.field_interval = 0.0;
    cfg.validate()?;
    Ok(cfg)
}

/// The runs of a map from JSON: a list (one item per run) of lists of `[path, value]` pairs.
pub fn parse_runs(json: &str) -> Result<Vec<Vec<Override>>> {
    let form = "a JSON list of runs, each a list of [dotted path, value] pairs";
    let value: Value =
        serde_json::from_str(json).map_err(|e| Error::invalid("runs", format!("text that is not JSON ({e})"), form))?;
    let Value::Array(runs) = value else { return Err(Error::invalid("runs", "not a list", form)) };
    runs.into_iter()
        .enumerate()
        .map(|(i, run)| {
            let Value::Array(pairs) = run else { return Err(Error::invalid(format!("runs[{i}]"), "not a list", form)) };
            override_pairs(pairs, &format!("runs[{i}]"), form)
        })
        .collect()
}

/// An upper estimate of the bytes one run holds while it is solved: its series
/// (`SERIES` values per sample, the bit speed in rad/s for the metrics and one more for
/// allocator slack), its grid (about 16 values per cell) and the metrics' bounded buffers
/// (the period estimator's resampled series and FFT, [`crate::metrics::stickslip::PERIOD_SAMPLES`]).
/// Measured: a map run of 600,001 samples on 200 cells raised the peak RSS by 50.7 bytes per
/// sample (`ru_maxrss`, 2026-12-03), against 56 counted here.
pub fn run_bytes(cfg: &DrillConfig) -> u64 {
    let samples = cfg.series_samples() as u64;
    let cells = cfg.numerics.cells as u64;
    let metrics = (crate::metrics::stickslip::PERIOD_SAMPLES as u64) * 8 * 8;
    samples
        .saturating_mul((SERIES as u64 + 2) * 8)
        .saturating_add(cells.saturating_mul(16 * 8))
        .saturating_add(metrics)
        .saturating_add(4096)
}

/// Refuses a map with an axis that changes nothing: a key the runs set that is without effect
/// ([`super::effect::no_effect`]) in the configuration of every run without it (`base` with the
/// run's other overrides, parsed: what the key would change; runs that do not parse are left
/// to their `invalid` rows). The error names the key and why.
pub fn check_axes(base: &Value, runs: &[Vec<Override>]) -> Result<()> {
    let mut keys: Vec<&str> = Vec::new();
    for (key, _) in runs.iter().flatten() {
        if !keys.contains(&key.as_str()) {
            keys.push(key);
        }
    }
    for key in keys {
        let mut first: Option<String> = None;
        let mut all = true;
        for run in runs {
            let others: Vec<Override> = run.iter().filter(|(k, _)| k != key).cloned().collect();
            let mut value = base.clone();
            if apply_overrides(&mut value, &others, "axis").is_err() {
                continue;
            }
            let Ok(cfg) = DrillConfig::from_value(value) else { continue };
            match no_effect(&cfg, key) {
                Some(why) => {
                    first.get_or_insert(why);
                }
                None => {
                    all = false;
                    break;
                }
            }
        }
        if let (true, Some(why)) = (all, first) {
            return Err(Error::invalid(
                format!("axis {key}"),
                "a key without effect in every run of the map (its rows would all be the same)",
                format!("an axis that changes the runs: {why}"),
            ));
        }
    }
    Ok(())
}

/// Bytes of one row (an upper estimate, without the message text).
pub const ROW_BYTES: u64 = 512;

/// Solves every run of a map: `base` (a JSON configuration) with each run's overrides, on
/// `threads` threads (every core for `None`, at most [`crate::sweep::MAX_THREADS`]). One row
/// per run, in input order.
///
/// Errors only for a shared input the map cannot use: `base` not a JSON object, `threads`, an
/// axis without effect ([`check_axes`]), or a map over `memory_budget` bytes (the rows, and on
/// each thread the run it solves). A run whose configuration is refused is a row with status
/// `invalid`; a failed solve a row with its status.
///
/// The calling thread waits for the pool and, every few milliseconds, asks
/// `interrupt.interrupted_at(finished runs)` (so a hook that must run on that thread, such as
/// Python's signal check, works; the "time" it receives is the number of runs finished) and
/// calls `progress(finished, total)` when the count changed. When the hook answers `true`, the
/// runs under way stop within milliseconds with status `interrupted`, the runs not started are
/// rows with that status, and the finished runs keep their rows.
pub fn solve_map(
    base: &str,
    runs: &[Vec<Override>],
    threads: Option<usize>,
    memory_budget: Option<u64>,
    interrupt: &dyn Interrupt,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<MapRow>> {
    solve_map_part(base, runs, true, threads, memory_budget, interrupt, progress)
}

/// The base configuration of a map: a JSON object.
pub fn map_base(base: &str) -> Result<Value> {
    let base: Value = serde_json::from_str(base)
        .map_err(|e| Error::invalid("config", format!("text that is not JSON ({e})"), "a JSON object"))?;
    if !base.is_object() {
        return Err(Error::invalid("config", "not an object", "a JSON object"));
    }
    Ok(base)
}

/// [`solve_map`] of one part of a map, whose axes ([`check_axes`]) are checked with every run
/// of the map (once, before its parts) when `check` is false.
pub fn solve_map_part(
    base: &str,
    runs: &[Vec<Override>],
    check: bool,
    threads: Option<usize>,
    memory_budget: Option<u64>,
    interrupt: &dyn Interrupt,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<MapRow>> {
    let base = map_base(base)?;
    if check {
        check_axes(&base, runs)?;
    }
    let threads = resolve_threads(threads)?;
    let configs: Vec<Result<DrillConfig>> = runs.iter().map(|o| run_config(&base, o)).collect();
    if let Some(budget) = memory_budget {
        let largest = configs.iter().filter_map(|c| c.as_ref().ok()).map(run_bytes).max().unwrap_or(0);
        let active = threads.min(runs.len().max(1)) as u64;
        let need = largest.saturating_mul(active).saturating_add(ROW_BYTES.saturating_mul(runs.len() as u64));
        if need > budget {
            return Err(Error::invalid(
                "threads",
                threads,
                format!(
                    "a map that fits the memory budget of {budget} bytes (DRILLSTRING_MEMORY_BUDGET): {} runs on \
                     {active} threads would need {need} bytes; use fewer threads, runs or samples",
                    runs.len()
                ),
            ));
        }
    }
    let cancel = CancelFlag::new();
    let finished = AtomicUsize::new(0);
    let total = runs.len();
    let work = || {
        configs
            .par_iter()
            .map(|cfg| {
                let row = match cfg {
                    Ok(cfg) => run_guarded(cfg, &cancel),
                    Err(e) => MapRow::failed(RunStatus::Invalid, e.to_string()),
                };
                finished.fetch_add(1, Ordering::Relaxed);
                row
            })
            .collect::<Vec<_>>()
    };
    progress(0, total);
    let mut reported = 0;
    let tick = || {
        let n = finished.load(Ordering::Relaxed);
        if n != reported {
            reported = n;
            progress(n, total);
        }
        n as f64
    };
    run_on_pool(threads, total, &cancel, interrupt, tick, work)
}

/// [`run_one`], with a panic turned into a row of this run only.
fn run_guarded(cfg: &DrillConfig, cancel: &CancelFlag) -> MapRow {
    catch_unwind(AssertUnwindSafe(|| run_one(cfg, cancel))).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        MapRow::failed(RunStatus::Error, format!("internal error: {what}"))
    })
}

/// One run: the solve without field snapshots, reduced to its row.
pub fn run_one(cfg: &DrillConfig, cancel: &CancelFlag) -> MapRow {
    if cancel.is_cancelled() {
        return MapRow::failed(RunStatus::Solved(Status::Interrupted), "interrupted before this run started".into());
    }
    let mut cfg = cfg.clone();
    cfg.numerics.field_interval = 0.0;
    match solve(&cfg, cancel, &mut |_| {}) {
        Err(e) => MapRow::failed(RunStatus::Invalid, e.to_string()),
        Ok(run) => {
            let status = RunStatus::Solved(run.status);
            MapRow {
                status,
                message: run.message,
                metrics: if status.is_success() { run.metrics } else { None },
                window: run.window,
                breakoff_torque: run.breakoff_torque,
                min_cycle_torque: run.min_cycle_torque,
                stats: run.stats,
                balance_error: run.energy.balance_error,
                coupled: if status.is_success() { run.coupled } else { None },
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interrupt::Never;
    use crate::outputs::Column;
    use serde_json::json;

    fn base() -> String {
        json!({
            "sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
            "well": {"inclination_deg": 30.0},
            "numerics": {"cells": 50, "duration": 4.0, "field_interval": 0.5}
        })
        .to_string()
    }

    #[test]
    fn rows_equal_single_runs() {
        let runs: Vec<Vec<Override>> = [20.0, 80.0]
            .iter()
            .map(|&rpm| vec![("top_drive.rpm".to_string(), json!(rpm)), ("friction.static".into(), json!(0.4))])
            .collect();
        let rows = solve_map(&base(), &runs, Some(2), None, &Never, &mut |_, _| {}).unwrap();
        assert_eq!(rows.len(), 2);
        for (row, rpm) in rows.iter().zip([20.0, 80.0]) {
            let mut cfg = DrillConfig::from_json(&base()).unwrap();
            cfg.top_drive.rpm = rpm;
            cfg.friction.static_coefficient = 0.4;
            let single = solve(&cfg, &Never, &mut |_| {}).unwrap();
            assert!(row.status.is_success(), "{}", row.message);
            assert_eq!(format!("{:?}", row.metrics), format!("{:?}", single.metrics));
            assert_eq!(row.breakoff_torque, single.breakoff_torque);
            assert_eq!(row.stats, single.stats);
        }
    }

    #[test]
    fn coupled_rows_carry_the_coupled_metrics_of_single_runs() {
        let base = json!({
            "sections": [{"length": 200.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
            "well": {"inclination_deg": 0.0},
            "friction": {"static": 0.0},
            "top_drive": {"rpm": 120.0, "controller": {"type": "speed"}},
            "bit": {"law": "detournay"},
            "hoist": {"mode": "weight_on_bit", "weight_on_bit": 40e3},
            "numerics": {"cells": 50, "duration": 6.0}
        })
        .to_string();
        let runs: Vec<Vec<Override>> =
            [30e3, 45e3].iter().map(|&w| vec![("hoist.weight_on_bit".to_string(), json!(w))]).collect();
        let rows = solve_map(&base, &runs, Some(2), None, &Never, &mut |_, _| {}).unwrap();
        let columns = MapColumns::new(&rows);
        for (k, (row, w)) in rows.iter().zip([30e3, 45e3]).enumerate() {
            let mut cfg = DrillConfig::from_json(&base).unwrap();
            cfg.hoist.as_mut().unwrap().weight_on_bit = w;
            let single = solve(&cfg, &Never, &mut |_| {}).unwrap();
            assert!(row.status.is_success(), "{}", row.message);
            let c = single.coupled.unwrap();
            assert_eq!(row.coupled, Some(c));
            assert_eq!(
                columns.coupled.get("wob_mean_N"),
                Some(&Column::Numbers(vec![rows[0].coupled.unwrap().wob_mean_n, rows[1].coupled.unwrap().wob_mean_n]))
            );
            let Some(Column::Texts(regime)) = columns.coupled.get("regime") else { panic!("no regime column") };
            assert_eq!((k, regime[k].as_ref()), (k, c.regime.name()));
        }
        // A torsion-only map: NaN and undetermined.
        let rows = solve_map(&super::tests::base(), &[vec![]], Some(1), None, &Never, &mut |_, _| {}).unwrap();
        let columns = MapColumns::new(&rows);
        let Some(Column::Numbers(rop)) = columns.coupled.get("rop_mean_m_per_h") else { panic!("no ROP column") };
        let Some(Column::Texts(regime)) = columns.coupled.get("regime") else { panic!("no regime column") };
        assert!(rop[0].is_nan() && regime[0] == "undetermined");
    }

    #[test]
    fn an_invalid_run_is_a_row() {
        let runs = vec![
            vec![("top_drive.inertia".to_string(), json!(-1.0))],
            vec![("top_drive.nope".to_string(), json!(1.0))],
            vec![("sections[3].length".to_string(), json!(1.0))],
            vec![("top_drive.rpm".to_string(), json!(60.0))],
        ];
        let rows = solve_map(&base(), &runs, Some(2), None, &Never, &mut |_, _| {}).unwrap();
        for row in &rows[..3] {
            assert_eq!(row.status, RunStatus::Invalid);
            assert!(row.metrics.is_none());
        }
        assert!(rows[0].message.contains("top_drive.inertia"), "{}", rows[0].message);
        assert!(rows[1].message.contains("top_drive.nope"), "{}", rows[1].message);
        assert!(rows[2].message.contains("sections[3]"), "{}", rows[2].message);
        assert!(rows[3].status.is_success());
    }

    #[test]
    fn interrupt_keeps_finished_rows() {
        let runs: Vec<Vec<Override>> = (0..6).map(|_| vec![("numerics.duration".to_string(), json!(200.0))]).collect();
        // The hook receives the number of finished runs.
        struct StopAfterFirst;
        impl Interrupt for StopAfterFirst {
            fn interrupted(&self) -> bool {
                false
            }
            fn interrupted_at(&self, finished: f64) -> bool {
                finished >= 1.0
            }
        }
        let mut seen = Vec::new();
        let rows =
            solve_map(&base(), &runs, Some(1), None, &StopAfterFirst, &mut |n, total| seen.push((n, total))).unwrap();
        assert!(rows[0].status.is_success());
        assert!(rows.iter().any(|r| r.status == RunStatus::Solved(Status::Interrupted)));
        assert_eq!(seen.first(), Some(&(0, 6)));
        assert_eq!(seen.last().map(|s| s.0), Some(6));
    }

    #[test]
    fn memory_budget_and_base_errors() {
        let runs = vec![vec![]];
        let e = solve_map(&base(), &runs, Some(1), Some(10), &Never, &mut |_, _| {}).unwrap_err();
        assert!(e.to_string().contains("memory budget"), "{e}");
        assert!(solve_map("[1]", &runs, Some(1), None, &Never, &mut |_, _| {}).is_err());
        assert!(solve_map(&base(), &runs, Some(0), None, &Never, &mut |_, _| {}).is_err());
    }

    #[test]
    fn runs_from_json() {
        let runs =
            parse_runs(r#"[[["top_drive.rpm", 60]], [], [["top_drive.controller.type", "pi"], ["a", null]]]"#).unwrap();
        assert_eq!(runs.len(), 3);
        assert_eq!(runs[0], vec![("top_drive.rpm".to_string(), json!(60))]);
        assert_eq!(runs[2][1], ("a".to_string(), Value::Null));
        assert!(parse_runs("[[1]]").is_err());
        assert!(parse_runs("{}").is_err());
    }

    #[test]
    fn paths() {
        let mut v = json!({"a": {"b": [1, {"c": 2}], "t": {"x": 1, "y": 2}}});
        set_path(&mut v, "a.b[1].c", &json!(5), "axis").unwrap();
        set_path(&mut v, "a.d", &json!("x"), "axis").unwrap();
        set_path(&mut v, "a.d", &Value::Null, "axis").unwrap();
        set_path(&mut v, "a.t", &json!({"y": 3}), "axis").unwrap();
        assert_eq!(v, json!({"a": {"b": [1, {"c": 5}], "d": null, "t": {"x": 1, "y": 3}}}));
        let message = |path: &str| set_path(&mut v.clone(), path, &json!(1), "axis").unwrap_err().to_string();
        assert_eq!(message("a.b[2].c"), "invalid a.b[2]: got 1, expected an index 0..1 of a.b");
        assert_eq!(message("a..b"), format!("invalid axis: got a..b, expected {}", super::super::config::PATH_FORM));
        assert!(message("a.b[x]").starts_with("invalid axis: got a.b[x]"));
        assert_eq!(message("a.b[0].c"), "invalid a.b[0].c: got 1, expected a key of a table: a.b[0] is 1, not a table");
        assert_eq!(message("a.b.c"), "invalid a.b.c: got 1, expected an index first: a.b is a list of 2 (a.b[0].c)");
        assert_eq!(message("a.d[0]"), "invalid a.d[0]: got 1, expected a key without an index: a.d is not a list");
    }
}
