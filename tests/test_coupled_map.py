"""Maps of coupled axial-torsional runs over rotary speed x weight on bit: the hoist's
``weight_on_bit`` mode, the regime of each run (smooth drilling, stick-slip, bit bounce) from the
core, the coupled columns of the table equal to single runs, the stored and resumed map, and the
regime figure."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import drillstring as ds
from drillstring.drilling import DrillConfig, drill, drill_map, load_drill_config
from drillstring.drilling.map_plots import map_figures, regime_map
from drillstring.drilling.map_table import COUPLED_COLUMNS
from drillstring.drilling.result import COUPLED_REGIME_CRITERION, COUPLED_REGIMES
from drillstring.errors import ResumeWarning, ValidationError

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "coupled-rpm-wob-map.toml"

#: 6 runs (about 1 s on 2 threads): smooth drilling at 120 kN, bit bounce at 400 rpm and 200 kN,
#: stick-slip at 280 kN (regimes found on the 12 x 12 map of docs/guide/maps.md; these six keep
#: their regimes on 400 cells, and 400 rpm and 200 kN bounces on 200 to 1600 cells).
AXES = {"top_drive.rpm": [200.0, 400.0], "hoist.weight_on_bit": [120e3, 200e3, 280e3]}


@pytest.fixture(scope="module")
def frame() -> pd.DataFrame:
    return drill_map(EXAMPLE, AXES, threads=2)


def _cfg(rpm: float, wob: float) -> DrillConfig:
    return load_drill_config(EXAMPLE).with_overrides({"top_drive.rpm": rpm, "hoist.weight_on_bit": wob,
                                                      "numerics.field_interval": 0.0})


def test_the_map_shows_smooth_drilling_stick_slip_and_bit_bounce(frame: pd.DataFrame) -> None:
    assert (frame["status"] == "success").all()
    regime = {(r, w): g for r, w, g in zip(frame["top_drive.rpm"], frame["hoist.weight_on_bit"], frame["regime"])}
    assert regime[(200.0, 120e3)] == regime[(400.0, 120e3)] == regime[(200.0, 200e3)] == "smooth drilling"
    assert regime[(400.0, 200e3)] == "bit bounce"
    assert regime[(200.0, 280e3)] == regime[(400.0, 280e3)] == "stick-slip"
    # the regime follows the criterion from the verdict and the bounce fraction
    for _, row in frame.iterrows():
        bounce, verdict = row["bounce_fraction"], row["stick_slip_verdict"]
        assert row["regime"] in COUPLED_REGIMES
        assert (row["regime"] == "smooth drilling") == (bounce == 0.0 and verdict == "no")
        assert (row["regime"] == "bit bounce") == (0.0 < bounce < 1.0 and verdict != "yes")
        assert (row["regime"] == "stick-slip") == (bounce == 0.0 and verdict == "yes")
    # the stick-slip runs stop, the bouncing run leaves the rock for about a quarter of the window
    assert frame.loc[frame["regime"] == "stick-slip", "stuck_fraction"].min() > 0.1
    assert 0.1 < frame.loc[frame["regime"] == "bit bounce", "bounce_fraction"].iloc[0] < 0.6
    assert list(frame.columns[-len(COUPLED_COLUMNS) - 5:-5]) == list(COUPLED_COLUMNS)


def test_smooth_cells_drill_at_the_imposed_weight(frame: pd.DataFrame) -> None:
    """In steady drilling the weight on bit is the one imposed less the string's velocity damping
    rho A L k_d ROP (the string moving down at the ROP; 0.4 to 2.5 % here), to the first-order
    cell error of the end forces; ROP grows with weight and speed, MSE falls with weight."""
    area = math.pi / 4 * (0.127**2 - 0.108**2)
    smooth = frame[frame["regime"] == "smooth drilling"]
    assert len(smooth) == 3
    for _, row in smooth.iterrows():
        drag = 8000.0 * area * 1000.0 * 1.0 * row["rop_mean_m_per_h"] / 3600
        want = row["hoist.weight_on_bit"] - drag
        assert row["wob_mean_N"] == pytest.approx(want, rel=3e-3), (row["wob_mean_N"], want)
    at = frame.set_index(["top_drive.rpm", "hoist.weight_on_bit"])
    assert at.loc[(400.0, 120e3), "rop_mean_m_per_h"] > at.loc[(200.0, 120e3), "rop_mean_m_per_h"]
    assert at.loc[(200.0, 200e3), "rop_mean_m_per_h"] > at.loc[(200.0, 120e3), "rop_mean_m_per_h"]
    assert at.loc[(200.0, 200e3), "mse_mean_Pa"] < at.loc[(200.0, 120e3), "mse_mean_Pa"]


@pytest.mark.parametrize("rpm, wob", [(200.0, 120e3), (400.0, 200e3), (200.0, 280e3)])
def test_cells_equal_single_runs(frame: pd.DataFrame, rpm: float, wob: float) -> None:
    result = drill(_cfg(rpm, wob))
    row = frame[(frame["top_drive.rpm"] == rpm) & (frame["hoist.weight_on_bit"] == wob)].iloc[0]
    assert result.coupled_metrics is not None
    for name, value in result.coupled_metrics.items():
        assert row[name] == value, name
    assert row["regime"] == result.coupled_regime
    assert row["ssi"] == result.metrics.ssi and row["stick_slip_verdict"] == result.metrics.stick_slip_verdict
    summary = result.summary()["coupled"]
    assert summary["regime"] == result.coupled_regime and summary["regime_criterion"] == COUPLED_REGIME_CRITERION


def test_the_stored_map_resumes_and_equals_the_one_in_memory(frame: pd.DataFrame, tmp_path: Path) -> None:
    stored = drill_map(EXAMPLE, AXES, out=tmp_path / "m", chunk_size=4)
    pd.testing.assert_frame_equal(stored, frame, check_like=False)
    on_disk = pd.read_parquet(tmp_path / "m" / "map.parquet")
    assert list(on_disk["regime"]) == list(frame["regime"])
    (tmp_path / "m" / "chunks" / "chunk-00001.parquet").unlink()
    with pytest.warns(ResumeWarning, match="chunk 1"):
        again = drill_map(EXAMPLE, AXES, out=tmp_path / "m", chunk_size=4)
    pd.testing.assert_frame_equal(again, frame)


def test_a_torsion_only_map_has_no_coupled_columns() -> None:
    cfg = DrillConfig.from_dict({"sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
                                 "numerics": {"cells": 40, "duration": 2.0}})
    table = drill_map(cfg, {"top_drive.rpm": [40.0, 80.0], "friction.static": [0.2, 0.3]})
    assert not set(COUPLED_COLUMNS) & set(table.columns)
    assert set(map_figures(table)) == {"ssi_map.png"}


def test_the_figures_show_the_regimes(frame: pd.DataFrame) -> None:
    figures = map_figures(frame)
    assert set(figures) == {"ssi_map.png", "regime_map.png"}
    fig = figures["regime_map.png"]
    titles = [ax.get_title() for ax in fig.axes]
    assert {"regime", "mean ROP", "mechanical specific energy"} <= set(titles)
    legend = fig.axes[0].get_legend()
    assert legend is not None
    assert [t.get_text() for t in legend.get_texts()] == ["smooth drilling", "stick-slip", "bit bounce"]
    with pytest.raises(ValidationError, match="coupled"):
        regime_map(frame.drop(columns="regime"), "top_drive.rpm", "hoist.weight_on_bit")


def test_the_weight_on_bit_mode_is_checked() -> None:
    with pytest.raises(ValidationError) as info:
        _cfg(120.0, -1.0)
    assert info.value.field == "hoist.weight_on_bit"
    assert load_drill_config(EXAMPLE).hoist.mode == "weight_on_bit"  # type: ignore[union-attr]


def test_the_cli_writes_the_regime(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from drillstring.cli import main

    args = ["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=400", "--axis", "hoist.weight_on_bit=120e3,200e3",
            "--out", str(tmp_path / "m")]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "regimes: smooth drilling in 1 runs, bit bounce in 1 runs" in out
    assert (tmp_path / "m" / "regime_map.png").stat().st_size > 0
    assert main(["drill", str(EXAMPLE), "--set", "top_drive.rpm=400", "--set", "hoist.weight_on_bit=200e3",
                 "--out", str(tmp_path / "run"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    assert "; regime: bit bounce" in out
    summary = json.loads((tmp_path / "run" / "metrics.json").read_text())
    assert summary["coupled"]["regime"] == "bit bounce"
    assert "**Regime: bit bounce**" in (tmp_path / "run" / "report.md").read_text()
    assert ds.drilling.map_table.COUPLED_COLUMNS[-1] == "regime"
