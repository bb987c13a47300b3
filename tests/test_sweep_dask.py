"""The Dask path: chunks as tasks on a (local, in-process) cluster give the local table."""

from __future__ import annotations

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")
distributed = pytest.importorskip("distributed")

import drillstring as ds  # noqa: E402

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
