"""Sweeps under stress: Ctrl-C inside a heavy chunk keeps its finished runs, a forked child can
sweep after its parent did, one bad row never aborts a sweep, and requests that cannot fit in
memory are refused up front (never an abort inside the core)."""

from __future__ import annotations

import json
import sys
import textwrap
from pathlib import Path

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from _children import python_child  # noqa: E402

import drillstring as ds  # noqa: E402
import drillstring._core as core  # noqa: E402

BASE = ds.preset("aluminum")
EXIT_TIMEOUT = 120.0

# ------------------------------------------------------------------ Ctrl-C inside a chunk

#: One chunk of 60 runs with 12 modes and the rigid mode over 8 s (~0.1 s each on one core, with
#: the pseudo-spectral right-hand side): a Ctrl-C after the child has used 1.5 s of CPU (its
#: chunk under way, however loaded the machine) finds some runs finished and others under way
#: or not started.
HEAVY = {"modes": 12, "rigid_mode": True, "t_end": 8.0, "chunk_size": 60, "threads": 2}
HEAVY_GRID = {"length": {"linspace": [100.0, 300.0, 60]}}


@pytest.mark.slow
@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_inside_a_heavy_chunk_stops_and_keeps_its_finished_runs(tmp_path: Path) -> None:
    script = f"""
        import sys, time
        import pandas, pyarrow
        import drillstring as ds
        print("ready", flush=True)
        try:
            ds.sweep(ds.preset("aluminum"), {HEAVY_GRID!r}, out_dir="out", **{HEAVY!r})
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
        """
    with python_child(script, tmp_path) as child:
        child.wait_cpu(1.5)
        sent = child.interrupt()
        out, err = child.communicate(timeout=EXIT_TIMEOUT)
    word, when = out.split()[:2]
    assert word == "interrupted", (out, err)
    latency = float(when) - sent
    print(f"sweep chunk interrupted {1000 * latency:.1f} ms after SIGINT")
    # The chunk is stored with its finished runs; the others say they were interrupted.
    chunks = tmp_path / "out" / "chunks"
    record = json.loads((chunks / "chunk-00000.json").read_text())
    assert record["complete"] is False and record["rows"] == 60
    stored = pd.read_parquet(chunks / "chunk-00000.parquet")
    done = stored["status"] == "success"
    assert set(stored["status"]) <= {"success", "interrupted"}
    assert 0 < (~done).sum(), "nothing was interrupted"
    assert stored.loc[~done, "message"].str.contains("interrupted").all()
    assert not (tmp_path / "out" / "results.parquet").exists()
    # The finished runs are those of the same runs solved alone ...
    if done.any():
        alone = ds.sweep(BASE, runs=[{"length": v} for v in stored.loc[done, "length"]],
                         **{k: v for k, v in HEAVY.items() if k != "chunk_size"})
        columns = ["length", "max_theta", "rms_theta", "dominant_frequency_hz", "nfev"]
        pd.testing.assert_frame_equal(stored.loc[done, columns].reset_index(drop=True), alone[columns])
    # ... and resuming solves only the interrupted ones and completes the table.
    table = ds.sweep(BASE, HEAVY_GRID, out_dir=tmp_path / "out", **HEAVY)
    assert table.attrs["resume"]["resumed_runs"] == int((~done).sum())
    assert (table["status"] == "success").all()
    pd.testing.assert_frame_equal(table.loc[done.to_numpy()], stored.loc[done].set_axis(table.index[done.to_numpy()]))
    assert json.loads((chunks / "chunk-00000.json").read_text())["complete"] is True


# ------------------------------------------------------------------ fork


@pytest.mark.skipif(not hasattr(__import__("os"), "fork"), reason="needs os.fork")
@pytest.mark.parametrize("how", ["os.fork", "multiprocessing"])
def test_a_forked_child_can_sweep_after_its_parent_did(tmp_path: Path, how: str) -> None:
    # Before: the child hung forever on the parent's (dead) thread pool. The child script runs
    # in its own process group, so a hang is a failed assertion and the group is killed.
    body = {
        "os.fork": """
            pid = os.fork()
            if pid == 0:
                child = sweep()
                os._exit(0 if child.equals(parent) else 3)
            _, status = os.waitpid(pid, 0)
            print("child", os.waitstatus_to_exitcode(status), flush=True)
            """,
        "multiprocessing": """
            import multiprocessing as mp
            with mp.get_context("fork").Pool(2) as pool:
                tables = pool.map(lambda_free, [0, 1])
            print("child", 0 if all(t.equals(parent) for t in tables) else 3, flush=True)
            """,
    }[how]
    script = textwrap.dedent("""
        import os
        import drillstring as ds

        def sweep():
            return ds.sweep(ds.preset("aluminum"), {"length": [100.0, 150.0, 200.0, 250.0]}, t_end=0.1,
                            samples=64, threads=2)

        def lambda_free(_):
            return sweep()

        parent = sweep()
        print("ready", flush=True)
        """) + textwrap.dedent(body)
    with python_child(script, tmp_path) as child:
        line = child.read_line(timeout=60)
        assert line == "child 0", line


# ------------------------------------------------------------------ per-run problems are rows


def test_values_that_overflow_are_that_rows_message_not_the_sweeps() -> None:
    table = ds.sweep(BASE, {"omega": [1.0, 1e200, 2.0]}, t_end=0.05, samples=64)
    assert table["status"].tolist() == ["success", "invalid", "success"]
    assert "omega" in table.loc[1, "message"] and "finite" in table.loc[1, "message"]
    huge = ds.sweep(BASE, runs=[{"length": 100.0}, {"length": 10**400}, {"length": 150.0}], t_end=0.05, samples=64)
    assert huge["status"].tolist() == ["success", "invalid", "success"]
    assert "length" in huge.loc[1, "message"]
    assert huge.loc[1, "length"] == float("inf")  # shown as the nearest float, not an error
    assert (huge.loc[[0, 2], "max_theta"] > 0).all()
    # the good rows are exactly those of a sweep without the bad one
    alone = ds.sweep(BASE, runs=[{"length": 100.0}, {"length": 150.0}], t_end=0.05, samples=64)
    pd.testing.assert_frame_equal(huge.loc[[0, 2], ["max_theta", "nfev"]].reset_index(drop=True),
                                  alone[["max_theta", "nfev"]])


# ------------------------------------------------------------------ memory and size limits


def test_sample_counts_beyond_memory_are_refused_before_any_work(monkeypatch) -> None:
    # Before: 1e9 samples aborted the process inside the core (SIGABRT).
    calls = []
    monkeypatch.setattr(core, "batch_solve", lambda *a, **k: calls.append(1))
    need = r"invalid samples: got '?1000000000'?, .*memory budget of 2.000 GiB.*would need 458"
    with pytest.raises(ds.ValidationError, match=need):
        ds.sweep(BASE, {"length": [100.0]}, t_end=0.05, samples=10**9)
    # kept trajectories: 2000 runs x 1e6 samples (~200 GB; a chunk alone would not fit), and
    # 2000 x 2e4 samples (~4.5 GB, a chunk would fit) are refused
    for samples, runs in ((10**6, 500), (20_000, 2000)):
        with pytest.raises(ds.ValidationError, match=rf"samples.* {runs} runs with their trajectories"):
            ds.sweep(BASE, {"length": ds.linspace(100.0, 200.0, 2000)}, t_end=0.05, samples=samples,
                     trajectories=True)
    with pytest.raises(ds.ValidationError, match="samples"):
        ds.sweep(BASE, {"length": [100.0]}, t_end=0.05, samples=10**400)
    assert calls == []


def test_grids_too_large_to_plan_are_refused_before_listing_their_runs() -> None:
    # Before: a 10^4 x 10^4 grid listed 10^8 runs (tens of GB) before anything else happened;
    # the size is checked from the axis lengths (limits.check_run_count) before the product.
    with pytest.raises(ds.ValidationError, match=r"invalid grid: got '10000 length x 10000 omega'.*at most"):
        ds.sweep(BASE, {"length": ds.linspace(100.0, 200.0, 10**4), "omega": ds.linspace(0.0, 1.0, 10**4)})
    with pytest.raises(ds.ValidationError, match=r"grid.length.count"):
        ds.sweep(BASE, {"length": ds.linspace(100.0, 200.0, 10**12)})
    with pytest.raises(ds.ValidationError, match="grid"):
        ds.sweep(BASE, {"c1000000": [0.1]})  # a velocity column per mode up to a million: refused


def test_the_memory_estimate_follows_the_budget(monkeypatch) -> None:
    plan = core.batch_plan(3, 1024, 500, 2, False, None)
    assert plan["threads"] == 2 and plan["bytes"] > 0
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", str(plan["bytes"] - 1))
    with pytest.raises(ds.ValidationError, match="samples"):
        ds.sweep(BASE, runs=[{"length": 100.0}] * 500, samples=1024, threads=2, chunk_size=500)
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", str(plan["bytes"]))
    core.batch_plan(3, 1024, 500, 2, False, plan["bytes"])  # fits exactly


@pytest.mark.parametrize("threads", [0, core.MAX_THREADS + 1, 10**6, 10**400, -1])
def test_thread_counts_out_of_range_are_refused_at_once(threads: int, monkeypatch) -> None:
    # Before: 10**6 spent 208 s spawning threads before failing; now refused before any solve.
    monkeypatch.setattr(core, "batch_solve", lambda *a, **k: pytest.fail("a batch was started"))
    with pytest.raises(ds.ValidationError, match="threads"):
        ds.sweep(BASE, {"length": [100.0]}, t_end=0.05, samples=64, threads=threads)
