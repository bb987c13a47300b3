"""Chunked, resumable sweep storage: resume equals uninterrupted, foreign sweeps refused."""

from __future__ import annotations

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

import importlib  # noqa: E402

import drillstring as ds  # noqa: E402
from drillstring.errors import ResumeWarning  # noqa: E402

# the module (``drillstring.studies.sweeps`` the attribute is the function)
sweep_module = importlib.import_module("drillstring.studies.sweeps")

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
    assert chunks == sorted(f"chunk-{i:05d}.{ext}" for i in range(4) for ext in ("parquet", "json"))
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
    assert not list((out / "chunks").glob(".*.tmp*"))


def test_deleted_chunks_are_recomputed_and_the_table_is_unchanged(tmp_path, count_chunks):
    out = tmp_path / "run"
    first = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    assert count_chunks["solved"] == list(range(7))
    for i in (1, 5):
        (out / "chunks" / f"chunk-{i:05d}.parquet").unlink()
    count_chunks["solved"] = []
    with pytest.warns(ResumeWarning, match="chunk 1: its file is missing; chunk 5: its file is missing"):
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


# ------------------------------------------------------------------ verified resume

import json  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import warnings  # noqa: E402


def _chunk(out, i, ext="parquet"):
    return out / "chunks" / f"chunk-{i:05d}.{ext}"


@pytest.fixture
def finished_sweep(tmp_path, count_chunks):
    """A finished sweep in ``tmp_path / "run"`` and its table; the chunk counter reset."""
    out = tmp_path / "run"
    table = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    count_chunks["solved"] = []
    return out, table


def _resume(out):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    return table, [str(w.message) for w in caught if issubclass(w.category, ResumeWarning)]


def _alter_a_value(path):
    """The chunk with one metric changed, written as a valid parquet file."""
    frame = pd.read_parquet(path)
    frame.loc[frame.index[0], "max_theta"] = 123.0
    frame.to_parquet(path)


def test_a_chunk_with_altered_bytes_is_recomputed_and_named(finished_sweep, count_chunks):
    out, reference = finished_sweep
    _alter_a_value(_chunk(out, 2))  # valid parquet, wrong numbers
    data = bytearray(_chunk(out, 4).read_bytes())
    data[len(data) // 2] ^= 0xFF  # one flipped byte
    _chunk(out, 4).write_bytes(bytes(data))
    table, messages = _resume(out)
    assert count_chunks["solved"] == [2, 4]
    pd.testing.assert_frame_equal(table, reference)
    assert len(messages) == 1 and "chunk 2: its bytes differ" in messages[0] and "chunk 4" in messages[0]
    assert table.attrs["resume"]["recomputed"].keys() == {2, 4}
    # the rewritten chunks verify again: nothing is recomputed next time
    count_chunks["solved"] = []
    assert _resume(out)[1] == [] and count_chunks["solved"] == []


@pytest.mark.parametrize("how", ["swapped", "copied", "hard-linked", "symlinked", "record-copied"])
def test_a_chunk_of_another_chunk_is_recomputed(finished_sweep, count_chunks, how):
    out, reference = finished_sweep
    one, three = _chunk(out, 1), _chunk(out, 3)
    if how == "swapped":  # file and record of 1 and 3 exchanged
        for ext in ("parquet", "json"):
            a, b = _chunk(out, 1, ext), _chunk(out, 3, ext)
            tmp = a.with_name("x")
            a.rename(tmp)
            b.rename(a)
            tmp.rename(b)
    elif how == "copied":
        for ext in ("parquet", "json"):
            shutil.copy(_chunk(out, 1, ext), _chunk(out, 3, ext))
    elif how == "hard-linked":
        three.unlink()
        os.link(one, three)
    elif how == "symlinked":
        three.unlink()
        three.symlink_to(one.name)
    else:  # a record of chunk 1 beside chunk 3's file
        shutil.copy(_chunk(out, 1, "json"), _chunk(out, 3, "json"))
    table, messages = _resume(out)
    expected = [1, 3] if how == "swapped" else [3]
    assert count_chunks["solved"] == expected
    pd.testing.assert_frame_equal(table, reference)
    assert messages and all(f"chunk {i}:" in messages[0] for i in expected)


def test_a_consistent_chunk_of_other_parameters_is_recomputed(finished_sweep, count_chunks):
    # the record re-written to match altered parameters: the plan check catches it
    out, reference = finished_sweep
    path = _chunk(out, 5)
    frame = pd.read_parquet(path)
    frame["length"] = frame["length"] + 1.0
    path.write_bytes(frame.to_parquet())
    record = json.loads(_chunk(out, 5, "json").read_text())
    import hashlib

    record["sha256"] = hashlib.sha256(path.read_bytes()).hexdigest()
    _chunk(out, 5, "json").write_text(json.dumps(record))
    table, messages = _resume(out)
    assert count_chunks["solved"] == [5]
    assert "parameter columns differ" in messages[0]
    pd.testing.assert_frame_equal(table, reference)


def test_a_chunk_without_its_record_is_recomputed(finished_sweep, count_chunks):
    out, reference = finished_sweep
    _chunk(out, 0, "json").unlink()
    table, messages = _resume(out)
    assert count_chunks["solved"] == [0] and "no record" in messages[0]
    pd.testing.assert_frame_equal(table, reference)


@pytest.mark.parametrize("content", ["[1, 2]", "{broken", "{\"fingerprint\": 3}", "[" * 100000])
def test_a_malformed_manifest_is_a_clear_error(tmp_path, content):
    out = tmp_path / "run"
    out.mkdir()
    (out / "manifest.json").write_text(content)
    with pytest.raises(ds.ValidationError, match="out_dir.*manifest"):
        ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)


def test_two_writers_on_one_directory_are_refused_with_the_holder_named(tmp_path):
    out = tmp_path / "run"
    ds.sweep(BASE, {"length": [100.0]}, out_dir=out, **OPTIONS)
    # another process holds the directory: a sweep started meanwhile is refused, its
    # temporary files are left alone
    stale = out / "chunks" / ".chunk-00000.parquet.0123.tmp.parquet"
    stale.write_bytes(b"being written")
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys, drillstring.io.sweep_store as s; from pathlib import Path\n"
         "store = s.SweepStore(Path(sys.argv[1]), {}, s._lock(Path(sys.argv[1])))\n"
         "print('locked', flush=True); sys.stdin.read()", str(out)],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
    )
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "locked"
        with pytest.raises(ds.ValidationError, match=f"locked by process {holder.pid} on "):
            ds.sweep(BASE, {"length": [100.0]}, out_dir=out, **OPTIONS)
        assert stale.exists()
    finally:
        holder.kill()
        holder.wait(timeout=30)
    # the lock dies with its process: the directory is usable again, and the stale file goes
    ds.sweep(BASE, {"length": [100.0]}, out_dir=out, **OPTIONS)
    assert not stale.exists()


def test_the_lock_is_held_for_the_whole_sweep_and_released_after(tmp_path, monkeypatch):
    out = tmp_path / "run"
    from drillstring.io.sweep_store import SweepStore

    seen = []
    real = sweep_module._solve_chunk_raw

    def solve(task):  # while solving, the directory cannot be opened by anyone else
        with pytest.raises(ds.ValidationError, match="locked by process"):
            SweepStore.open(out, {"fingerprint": "x"})
        seen.append(task.index)
        return real(task)

    monkeypatch.setattr(sweep_module, "_solve_chunk_raw", solve)
    ds.sweep(BASE, GRID, out_dir=out, **OPTIONS)
    assert seen == list(range(7))
    with pytest.raises(ds.ValidationError, match="different sweep"):  # the lock is free again
        SweepStore.open(out, {"fingerprint": "x"})


def test_a_ctrl_c_during_a_chunk_save_is_raised_after_chunk_and_record(tmp_path, monkeypatch):
    # the chunk file and its record are one unit: a SIGINT between the two writes is held back
    # and handed to the handler in force once both exist (this test installs its own handler, so
    # it behaves the same when SIGINT is ignored, e.g. under nohup)
    import signal

    import pandas as pd

    from drillstring.io import sweep_store

    seen: list[list[str]] = []
    store_dir = tmp_path / "store"
    store_dir.mkdir()
    (store_dir / "chunks").mkdir()
    store = sweep_store.SweepStore(store_dir, {"fingerprint": "x"})
    real_write = sweep_store._atomic_write

    def write_then_signal(path, data):
        real_write(path, data)
        if path.suffix == ".parquet":
            signal.raise_signal(signal.SIGINT)   # arrives between the chunk and its record

    def handler(signum, frame):
        seen.append(sorted(p.name for p in (store_dir / "chunks").iterdir()))

    monkeypatch.setattr(sweep_store, "_atomic_write", write_then_signal)
    previous = signal.signal(signal.SIGINT, handler)
    try:
        store.save_chunk(0, "plan", pd.DataFrame({"a": [1.0, 2.0]}), True)
        assert signal.getsignal(signal.SIGINT) is handler
    finally:
        signal.signal(signal.SIGINT, previous)
    assert seen == [["chunk-00000.json", "chunk-00000.parquet"]]
