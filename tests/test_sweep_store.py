"""Chunked, resumable sweep storage: resume equals uninterrupted, foreign sweeps refused."""

from __future__ import annotations

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

import importlib  # noqa: E402

import drillstring as ds  # noqa: E402

# the module (``drillstring.sweep`` the attribute is the function)
sweep_module = importlib.import_module("drillstring.sweep")

GRID = {"length": ds.linspace(100.0, 200.0, 5), "omega": [0.0, 30.0, 60.0, 90.0]}  # 20 runs
OPTIONS = {"t_end": 0.2, "samples": 256, "chunk_size": 3}  # 7 chunks, the last one short
BASE = ds.preset("aluminum")


@pytest.fixture
def count_chunks(monkeypatch):
    """Counts the chunks actually solved; ``interrupt_at`` raises KeyboardInterrupt at that call."""
    state = {"solved": [], "interrupt_at": None}
    real = sweep_module._solve_chunk_raw

    def counting(task):
        if state["interrupt_at"] is not None and len(state["solved"]) == state["interrupt_at"]:
            raise KeyboardInterrupt
        state["solved"].append(task.index)
        return real(task)

    monkeypatch.setattr(sweep_module, "_solve_chunk_raw", counting)
    return state


def test_resume_after_interruption_equals_uninterrupted(tmp_path, count_chunks):
    reference = ds.sweep(BASE, GRID, **OPTIONS)  # in memory, no out_dir
    out = tmp_path / "run"
    count_chunks.update(solved=[], interrupt_at=4)
    with pytest.raises(KeyboardInterrupt):
        ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    chunks = sorted(p.name for p in (out / "chunks").iterdir())
    assert chunks == [f"chunk-{i:05d}.parquet" for i in range(4)]
    assert not (out / "results.parquet").exists()
    # an interrupted write leaves at most a temporary file, never a partial chunk
    (out / "chunks" / ".chunk-00004.parquet.123.abcd.tmp").write_bytes(b"PAR1 half")
    count_chunks.update(solved=[], interrupt_at=None)
    resumed = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    assert count_chunks["solved"] == [4, 5, 6]  # finished chunks skipped
    pd.testing.assert_frame_equal(resumed, reference)
    pd.testing.assert_frame_equal(pd.read_parquet(out / "results.parquet"), reference)
    csv = pd.read_csv(out / "results.csv", keep_default_na=False, na_values={"unstable_modes": [""]})
    assert list(csv.columns) == list(reference.columns) and len(csv) == 20
    assert csv["max_theta"].tolist() == pytest.approx(reference["max_theta"].tolist(), rel=1e-15)
    assert not list((out / "chunks").glob(".*.tmp"))


def test_deleted_chunks_are_recomputed_and_the_table_is_unchanged(tmp_path, count_chunks):
    out = tmp_path / "run"
    first = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    assert count_chunks["solved"] == list(range(7))
    for i in (1, 5):
        (out / "chunks" / f"chunk-{i:05d}.parquet").unlink()
    count_chunks["solved"] = []
    again = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    assert count_chunks["solved"] == [1, 5]
    pd.testing.assert_frame_equal(again, first)
    count_chunks["solved"] = []
    ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)  # complete: nothing to solve
    assert count_chunks["solved"] == []


def test_a_different_sweep_in_the_same_directory_is_refused(tmp_path):
    out = tmp_path / "run"
    ds.sweep(BASE, {"length": [100.0, 150.0]}, out_dir=out, **OPTIONS)
    with pytest.raises(ds.ValidationError, match="different sweep.*solver"):
        ds.sweep(BASE, {"length": [100.0, 150.0]}, out_dir=out, **{**OPTIONS, "t_end": 0.3})
    with pytest.raises(ds.ValidationError, match="different sweep"):
        ds.sweep(BASE, {"length": [100.0, 160.0]}, out_dir=out, **OPTIONS)
    with pytest.raises(ds.ValidationError, match="chunk_size"):
        ds.sweep(BASE, {"length": [100.0, 150.0]}, out_dir=out, **{**OPTIONS, "chunk_size": 1})
    # a directory with results but no manifest is not taken over
    stray = tmp_path / "stray"
    stray.mkdir()
    (stray / "results.csv").write_text("x\n")
    with pytest.raises(ds.ValidationError, match="manifest"):
        ds.sweep(BASE, {"length": [100.0]}, out_dir=stray, **OPTIONS)


def test_trajectories_stay_in_memory(tmp_path):
    with pytest.raises(ds.ValidationError, match="trajectories"):
        ds.sweep(BASE, {"length": [100.0]}, out_dir=tmp_path / "x", trajectories=True, **OPTIONS)
