"""The Dask path: chunks as tasks on a (local, in-process) cluster give the local table."""

from __future__ import annotations

from pathlib import Path

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")
distributed = pytest.importorskip("distributed")

import drillstring as ds  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

GRID = {"length": ds.linspace(100.0, 200.0, 4), "omega": [0.0, 50.0, 100.0], "inner_diameter": [0.12, 0.25]}
OPTIONS = {"modes": 2, "t_end": 0.2, "samples": 256, "chunk_size": 5}  # 24 runs, 12 invalid, 5 chunks


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


def test_dask_equals_local(client, tmp_path):
    local = ds.sweep(ds.preset("aluminum"), GRID, **OPTIONS)
    assert (local["status"] == "invalid").sum() == 12  # inner_diameter 0.25 > outer 0.2
    on_cluster = ds.sweep(ds.preset("aluminum"), GRID, client=client, out_dir=tmp_path / "d", **OPTIONS)
    pd.testing.assert_frame_equal(on_cluster, local)
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "d" / "results.parquet"), local)
    assert len(list((tmp_path / "d" / "chunks").glob("chunk-*.parquet"))) == 5
    # resuming a finished sweep on the cluster submits nothing and returns the same table
    again = ds.sweep(ds.preset("aluminum"), GRID, client=client, out_dir=tmp_path / "d", **OPTIONS)
    pd.testing.assert_frame_equal(again, local)


def test_scheduler_address_string(client):
    local = ds.sweep(ds.preset("aluminum"), {"length": [100.0, 150.0]}, **OPTIONS)
    remote = ds.sweep(ds.preset("aluminum"), {"length": [100.0, 150.0]}, client=client.scheduler.address, **OPTIONS)
    pd.testing.assert_frame_equal(remote, local)


# ----------------------------------------------------------------------------- drilling maps

def _drill_config():
    from drillstring.drilling import DrillConfig

    return DrillConfig.from_dict({
        "sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "well": {"inclination_deg": 30.0},
        "numerics": {"cells": 40, "duration": 3.0, "field_interval": 0.5},
    })


DRILL_AXES = {"top_drive.rpm": [20.0, 60.0, 100.0], "friction.static": [0.2, 0.4],
              "top_drive.inertia": [2900.0, -1.0]}   # 12 runs, 6 invalid


def test_drill_map_on_dask_equals_local(client, tmp_path, monkeypatch):
    from drillstring.drilling import drill_map, maps

    local = drill_map(_drill_config(), DRILL_AXES, threads=1)
    assert (local["status"] == "invalid").sum() == 6 and (local["status"] == "success").sum() == 6

    def not_here(*args, **kwargs):
        raise AssertionError("solved in the calling process instead of on the cluster")

    monkeypatch.setattr(maps, "_solve", not_here)   # the workers are other processes
    remote = drill_map(_drill_config(), DRILL_AXES, client=client, chunk_size=5)   # in memory, 3 tasks
    pd.testing.assert_frame_equal(remote, local)
    stored = drill_map(_drill_config(), DRILL_AXES, client=client, chunk_size=5, out=tmp_path / "m")
    pd.testing.assert_frame_equal(stored, local)
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "m" / "map.parquet"), local.reset_index(drop=True),
                                  check_like=False)
    assert len(list((tmp_path / "m" / "chunks").glob("chunk-*.parquet"))) == 3
    # a deleted chunk is solved again on the cluster; the others are reused
    (tmp_path / "m" / "chunks" / "chunk-00001.parquet").unlink()
    (tmp_path / "m" / "chunks" / "chunk-00001.json").unlink()
    again = drill_map(_drill_config(), DRILL_AXES, client=client.scheduler.address, chunk_size=5, out=tmp_path / "m")
    pd.testing.assert_frame_equal(again, local)


def test_drill_map_cli_scheduler(client, tmp_path):
    from drillstring.cli import main

    config = tmp_path / "c.toml"
    config.write_text(_drill_config().to_toml())
    args = ["drill-map", str(config), "--axis", "top_drive.rpm=20,100", "--out", str(tmp_path / "m"), "--no-plots"]
    assert main([*args, "--scheduler", client.scheduler.address]) == 0
    assert main([*args[:-3], "--out", str(tmp_path / "local"), "--no-plots"]) == 0
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "m" / "map.parquet"),
                                  pd.read_parquet(tmp_path / "local" / "map.parquet"))


def test_a_coupled_drill_map_on_dask_equals_local(client):
    from drillstring.drilling import drill_map

    example = ROOT / "examples" / "coupled-rpm-wob-map.toml"
    axes = {"top_drive.rpm": [200.0, 400.0], "hoist.weight_on_bit": [200e3]}
    local = drill_map(example, axes, threads=1)
    remote = drill_map(example, axes, client=client, chunk_size=1)
    pd.testing.assert_frame_equal(remote, local)
    assert list(remote["regime"]) == ["smooth drilling", "bit bounce"]
