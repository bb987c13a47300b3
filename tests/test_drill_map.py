"""Stick-slip maps (drillstring.drilling.maps, _core.drill_map, drillstring drill-map)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import drillstring as ds
from drillstring.cli import main
from drillstring.drilling import DrillConfig, drill, drill_map, load_drill_config
from drillstring.drilling.map_labels import axis_label
from drillstring.drilling.map_plots import controller_maps, map_figures, ssi_lines, ssi_map
from drillstring.drilling.map_table import METRIC_COLUMNS
from drillstring.errors import ValidationError

ROOT = Path(__file__).resolve().parents[1]
ON_BOTTOM = ROOT / "examples" / "on-bottom-3000m.toml"


def _small() -> DrillConfig:
    return DrillConfig.from_dict({
        "sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "well": {"inclination_deg": 30.0},
        "numerics": {"cells": 40, "duration": 4.0, "field_interval": 0.5},
    })


def _same(a: object, b: object) -> bool:
    both_nan = isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)
    return both_nan or a == b


def test_rows_equal_single_runs() -> None:
    cfg = _small()
    axes = {"top_drive.rpm": [20.0, 90.0], "friction.static": [0.2, 0.4],
            "top_drive.controller.type": ["pi", "soft_torque"]}
    frame = drill_map(cfg, axes, threads=2)
    assert len(frame) == 8
    assert list(frame.columns[:5]) == [*axes, "status", "message"]
    assert set(METRIC_COLUMNS) <= set(frame.columns)
    for _, row in frame.iterrows():
        single = drill(cfg.with_overrides({k: row[k] for k in axes}))
        assert row["status"] == single.status == "success"
        expected = single.metrics.to_dict()
        for name in METRIC_COLUMNS:
            value = expected[name]
            assert _same(row[name], math.nan if value is None else value), name
        assert row["steps"] == single.stats["steps"]
        assert row["courant_peak"] == single.stats["courant_peak"] == 1.0


def test_an_invalid_row_does_not_fail_the_map() -> None:
    frame = drill_map(_small(), {"top_drive.inertia": [2900.0, -1.0], "top_drive.rpm": [60.0]}, threads=1)
    assert list(frame["status"]) == ["success", "invalid"]
    assert "top_drive.inertia" in frame["message"][1]
    assert np.isnan(frame["ssi"][1]) and np.isfinite(frame["ssi"][0])


def test_bad_axes() -> None:
    cfg = _small()
    with pytest.raises(ValidationError, match="axes"):
        drill_map(cfg, {})
    with pytest.raises(ValidationError, match="top_drive.rmp"):
        drill_map(cfg, {"top_drive.rmp": [1.0]})
    with pytest.raises(ValidationError, match="sections\\[3\\]"):
        drill_map(cfg, {"sections[3].length": [1.0]})
    with pytest.raises(ValidationError, match="non-empty list"):
        drill_map(cfg, {"top_drive.rpm": []})
    with pytest.raises(ValidationError, match="threads"):
        drill_map(cfg, {"top_drive.rpm": [1.0]}, threads=0)
    with pytest.raises(ValidationError, match="progress"):
        drill_map(cfg, {"top_drive.rpm": [1.0]}, progress="yes")


def test_too_many_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "100000")
    with pytest.raises(ValidationError, match="axes"):
        drill_map(_small(), {"top_drive.rpm": list(range(1, 1001)), "friction.static": [0.1] * 100})


def test_interrupt_keeps_finished_rows() -> None:
    cfg = _small().with_overrides(["numerics.duration=300", "numerics.cells=200"])
    seen: list[tuple[int, int]] = []

    class Stop(Exception):
        pass

    def progress(done: int, total: int) -> None:
        seen.append((done, total))
        if done >= 1:
            raise Stop

    with pytest.raises(Stop) as info:
        drill_map(cfg, {"top_drive.rpm": [30.0, 40.0, 50.0, 60.0, 70.0, 80.0] * 2}, threads=1, progress=progress)
    frame = info.value.frame  # type: ignore[attr-defined]
    assert len(frame) == 12
    assert (frame["status"] == "success").sum() >= 1
    assert (frame["status"] == "interrupted").sum() >= 1
    assert frame.loc[frame["status"] == "success", "ssi"].notna().all()
    assert seen[0] == (0, 12)


@pytest.mark.skipif(not ON_BOTTOM.exists(), reason="examples/on-bottom-3000m.toml")
def test_on_bottom_example_sticks_at_low_rpm_only() -> None:
    cfg = load_drill_config(ON_BOTTOM).with_overrides(["numerics.duration=30"])
    frame = drill_map(cfg, {"top_drive.rpm": [40.0, 120.0]}, threads=2)
    assert (frame["status"] == "success").all()
    low, high = frame.iloc[0], frame.iloc[1]
    assert low["stuck_fraction"] > 0.05 and low["ssi"] > 1.0
    assert high["stuck_fraction"] == 0.0 and high["ssi"] < 0.5


def test_figures() -> None:
    frame = drill_map(_small(), {"top_drive.rpm": [10.0, 60.0, 120.0], "friction.static": [0.1, 0.5],
                                 "top_drive.controller.type": ["pi", "soft_torque"]}, threads=2)
    figs = map_figures(frame)
    assert set(figs) == {"ssi_map.png", "controllers.png"}
    assert len(controller_maps(frame, "top_drive.rpm", "friction.static").axes) == 3  # 2 panels + colour bar
    # the map's cells and the lines are the runs' own SSI: one panel / line per controller
    rpm, static, kind = (frame[k].to_numpy() for k in ("top_drive.rpm", "friction.static",
                                                        "top_drive.controller.type"))
    ssi = frame["ssi"].to_numpy(dtype=float)
    kinds = ("pi", "soft_torque")
    panels = ssi_map(frame, "top_drive.rpm", "friction.static").axes[:2]
    for ax, k in zip(panels, kinds):
        assert ax.get_title() == f"{k} controller"
        cells = ax.collections[0].get_array()
        expected = [[ssi[(rpm == r) & (static == s) & (kind == k)][0] for r in (10.0, 60.0, 120.0)]
                    for s in (0.1, 0.5)]
        np.testing.assert_array_equal(np.ma.filled(cells, np.nan).reshape(2, 3), expected)
    lines = ssi_lines(frame, "top_drive.rpm", "top_drive.controller.type").axes[0].get_lines()
    pairs = [(k, s) for k in kinds for s in (0.1, 0.5)]
    friction = axis_label("friction.static", [0.1, 0.5])[0]  # dimensionless: no unit
    assert [line.get_label() for line in lines[:4]] == [f"{k} controller, {friction} = {s:g}" for k, s in pairs]
    for line, (k, s) in zip(lines, pairs):
        np.testing.assert_array_equal(line.get_xdata(), [10.0, 60.0, 120.0])
        own = [ssi[(rpm == r) & (kind == k) & (static == s)][0] for r in (10.0, 60.0, 120.0)]
        np.testing.assert_array_equal(line.get_ydata(), own)
    assert np.ptp(ssi) > 0.1  # the runs differ
    with pytest.raises(ValidationError, match="numeric axis"):
        ssi_map(frame, "top_drive.controller.type", "friction.static")


def test_exported() -> None:
    assert ds.drill_map is drill_map


def test_cli_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "c.toml"
    _small().save(config)
    out = tmp_path / "map"
    code = main(["drill-map", str(config), "--axis", "top_drive.rpm=20:100:3", "--axis",
                 "top_drive.controller.type=pi,soft_torque", "--set", "numerics.duration=3", "--out", str(out),
                 "--threads", "2"])
    assert code == 0, capsys.readouterr().err
    names = set(os.listdir(out))
    assert {"map.parquet", "map.csv", "config.toml", "ssi_lines.png"} <= names
    table = pd.read_parquet(out / "map.parquet")
    assert list(table["top_drive.rpm"]) == [20.0, 20.0, 60.0, 60.0, 100.0, 100.0]
    assert list(table["top_drive.controller.type"]) == ["pi", "soft_torque"] * 3
    assert (table["status"] == "success").all()
    assert "6 runs" in capsys.readouterr().out


@pytest.mark.parametrize("axis", ["top_drive.rmp=1:2:2", "top_drive.rpm=1:2", "top_drive.rpm", "top_drive.rpm=1:x:3",
                                  "top_drive.rpm=1:2:0"])
def test_cli_bad_axis_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str], axis: str) -> None:
    config = tmp_path / "c.toml"
    _small().save(config)
    code = main(["drill-map", str(config), "--axis", axis, "--out", str(tmp_path / "m")])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("drillstring: error:") and err.count("\n") == 1
    assert not (tmp_path / "m").exists()


def test_stored_map_resumes(tmp_path: Path) -> None:
    cfg = _small()
    axes = {"top_drive.rpm": [20.0, 50.0, 90.0], "top_drive.controller.type": ["pi", "soft_torque"]}
    memory = drill_map(cfg, axes, threads=2)
    out = tmp_path / "m"
    first = drill_map(cfg, axes, threads=2, out=out, chunk_size=4)
    assert sorted(os.listdir(out / "chunks")) == ["chunk-00000.json", "chunk-00000.parquet", "chunk-00001.json",
                                                  "chunk-00001.parquet"]
    columns = [c for c in memory.columns if c != "message"]
    pd.testing.assert_frame_equal(first[columns], memory[columns], check_dtype=False)
    pd.testing.assert_frame_equal(pd.read_parquet(out / "map.parquet")[columns], memory[columns], check_dtype=False)
    # a tampered chunk is recomputed (with a warning), the other one reused
    data = (out / "chunks" / "chunk-00001.parquet").read_bytes()
    (out / "chunks" / "chunk-00001.parquet").write_bytes(data[:-10] + b"0123456789")
    with pytest.warns(ds.errors.ResumeWarning, match="chunk 1"):
        again = drill_map(cfg, axes, threads=2, out=out, chunk_size=4)
    assert again.attrs["resume"]["recomputed"].keys() == {1}
    pd.testing.assert_frame_equal(again[columns], memory[columns], check_dtype=False)
    # another map in the same directory is refused
    with pytest.raises(ValidationError, match="out_dir"):
        drill_map(cfg, {"top_drive.rpm": [20.0]}, out=out)


def test_stored_map_interrupt_then_resume(tmp_path: Path) -> None:
    cfg = _small().with_overrides(["numerics.duration=300", "numerics.cells=200"])
    axes = {"top_drive.rpm": [30.0, 40.0, 50.0, 60.0, 70.0, 80.0]}
    out = tmp_path / "m"

    class Stop(Exception):
        pass

    def progress(done: int, total: int) -> None:
        if done >= 1:
            raise Stop

    with pytest.raises(Stop) as info:
        drill_map(cfg, axes, threads=1, progress=progress, out=out, chunk_size=6)
    partial = info.value.frame  # type: ignore[attr-defined]
    finished = partial.loc[partial["status"] == "success", "top_drive.rpm"].tolist()
    assert finished and (partial["status"] == "interrupted").any()
    assert not (out / "map.parquet").exists()
    solved: list[int] = []
    frame = drill_map(cfg, axes, threads=1, progress=lambda done, total: solved.append(done), out=out, chunk_size=6)
    assert (frame["status"] == "success").all()
    # the stored runs count as done from the start; only the interrupted ones are solved
    assert solved[0] == 0 and solved[-1] == 6 and all(n >= len(finished) for n in solved[1:])
    assert frame.attrs["resume"]["recomputed"] == {}
    single = drill(cfg.with_overrides({"top_drive.rpm": finished[0]})).metrics
    assert frame.loc[frame["top_drive.rpm"] == finished[0], "ssi"].item() == single.ssi


@pytest.mark.parametrize("client", [5, "", object()])
def test_a_client_that_is_not_dask_is_refused(client) -> None:
    with pytest.raises(ValidationError) as info:
        drill_map(_small(), {"top_drive.rpm": [20.0]}, client=client)
    assert info.value.field == "client" and "Client" in info.value.allowed
    with pytest.raises(ValidationError) as info:
        ds.sweep(ds.preset("aluminum"), {"length": [100.0]}, client=client)
    assert info.value.field == "client"
