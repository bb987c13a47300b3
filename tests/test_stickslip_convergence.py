"""Stick-slip metrics that do not depend on the grid or on where the metrics window starts.

The corrected Well B of Aarsnes & Shor (examples/aarsnes-shor-well-b-corrected.toml), bit off
bottom, in a stick-slip limit cycle. Before the bit speed was taken as at rest below a stuck
last cell, its stuck fraction was 0.009 / 0.017 / 0.50 at 500 / 1000 / 2000 cells (the free end
crept at a speed proportional to the cell size), and the period 6.94 s over 20-60 s against
7.24 s over 30-60 s (a mean-crossing count that a wiggle of the torque fooled).
"""

from __future__ import annotations

from pathlib import Path

import pytest

import drillstring as ds

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-shor-well-b-corrected.toml"


@pytest.fixture(scope="module")
def runs() -> dict[int, ds.DrillResult]:
    cfg = ds.load_drill_config(EXAMPLE)
    return {n: ds.drill(cfg.with_overrides([f"numerics.cells={n}", "metrics.window=[20.0, 60.0]"]), progress=False)
            for n in (500, 1000, 2000)}


def test_metrics_converge_with_the_grid(runs: dict[int, ds.DrillResult]) -> None:
    fine = runs[2000].metrics
    # the independent solution: the autocorrelation of the same run's torque gives 7.25 s
    assert fine.period_s == pytest.approx(7.25, abs=0.05)
    assert 0.45 < fine.stuck_fraction < 0.55
    for n in (500, 1000):
        m = runs[n].metrics
        assert m.stuck_fraction == pytest.approx(fine.stuck_fraction, rel=0.03), n
        assert m.ssi == pytest.approx(fine.ssi, rel=0.03), n
        assert m.period_s == pytest.approx(fine.period_s, rel=0.01), n
    for n, r in runs.items():
        m = r.metrics
        assert m.stick_slip and m.settled, n
        # the two period estimates agree: cycles counted from the bit's slip onsets
        assert m.slip_period_s == pytest.approx(m.period_s, rel=0.01), n
        assert r.warnings == (), (n, r.warnings)


@pytest.mark.parametrize("start", [20.0, 25.0, 30.0])
def test_the_period_does_not_depend_on_the_window_start(runs: dict[int, ds.DrillResult], start: float) -> None:
    r = runs[1000]
    m = ds.drilling.metrics.stick_slip_metrics(r.t, r.bit_rpm * (2 * 3.141592653589793 / 60), r.motor_torque,
                                               window=(start, 60.0), stick_speed=r.config.metrics.stick_speed)
    assert m.period_s == pytest.approx(r.metrics.period_s, rel=0.01)
    assert m.period_s * 2 <= 60.0 - start


def test_a_bit_at_rest_below_a_stuck_string_reads_zero(runs: dict[int, ds.DrillResult]) -> None:
    # during the stuck phases the reported bit speed is exactly 0, at every grid
    for n, r in runs.items():
        stuck = r.bit_rpm[(r.t >= 20.0)] == 0.0
        assert 0.4 < stuck.mean() < 0.6, n


def test_metrics_json_states_the_verdict_and_the_definitions(runs: dict[int, ds.DrillResult]) -> None:
    summary = runs[1000].summary()
    assert summary["stick_slip"] is True and summary["settled"] is True
    assert "stuck_fraction" in summary["stick_slip_criterion"]
    assert summary["warnings"] == []
    for key in ("ssi", "stuck_fraction", "period_s", "stick_slip", "settled", "bit_rpm_min"):
        assert summary["definitions"][key]


def test_a_transient_is_not_settled_and_says_so() -> None:
    cfg = ds.load_drill_config(EXAMPLE)
    # the first stick-slip cycles, from rest: the wind-up and the first slip are no limit cycle
    r = ds.drill(cfg.with_overrides(["numerics.duration=30", "metrics.window=[0.0, 30.0]"]), progress=False)
    assert not r.metrics.settled
    assert any(w.startswith("not settled") for w in r.warnings)


def test_a_window_outside_the_run_is_refused() -> None:
    # before: all-null metrics and "success"
    cfg = ds.load_drill_config(EXAMPLE)
    with pytest.raises(ds.ValidationError, match="metrics.window"):
        cfg.with_overrides(["numerics.duration=2", "metrics.window=[5.0, 8.0]"])


def test_check_grid_reports_every_metric_against_twice_the_cells() -> None:
    cfg = ds.load_drill_config(EXAMPLE)
    r = ds.drill(cfg, check_grid=True, progress=False)
    g = r.grid_check
    assert g is not None and (g.cells, g.refined_cells) == (1000, 2000)
    rows = {row.metric: row for row in g.rows}
    # the rows are the two runs' own metrics
    fine = ds.drill(cfg.with_overrides(["numerics.cells=2000"]), progress=False).metrics
    assert rows["ssi"].value == r.metrics.ssi and rows["ssi"].refined == fine.ssi
    assert rows["ssi"].change == pytest.approx(fine.ssi / r.metrics.ssi - 1, rel=1e-12)
    for name in ("ssi", "stuck_fraction", "period_s", "bit_rpm_mean", "motor_torque_max_Nm", "stick_slip", "settled"):
        assert rows[name].within, rows[name]
    # the reverse rotation at re-stick is not converged (-2.35 rpm at 1000 cells, -0.56 at 2000):
    # the check says so, and the run's warnings carry it
    assert not rows["bit_rpm_min"].within and not g.converged
    assert any(w.startswith("grid check: bit_rpm_min") for w in r.warnings)
    assert r.summary()["grid_check"]["rows"][0]["metric"] == "ssi"


def test_check_grid_needs_a_grid_whose_double_the_core_accepts() -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.max_cells=1500"])
    with pytest.raises(ds.ValidationError, match="check_grid"):
        ds.drill(cfg, check_grid=True)
    with pytest.raises(ds.ValidationError, match="check_grid"):
        ds.drill(cfg, check_grid="yes")  # type: ignore[arg-type]
