"""Ctrl-C during a long Rust solve (minutes to days if not stopped): control returns to Python as
KeyboardInterrupt (each test prints the latency, in practice a few ms; none bounds it, since a
wall-clock bound fails on a loaded machine), the interpreter stays usable, the command line exits with status 130 and no
output file is left half-written (every output is written to a temporary file and renamed).

The children run through :func:`_children.python_child`: each sets its own SIGINT handler (a test
run started with ``nohup`` or ``&`` hands its children SIGINT ignored), runs in its own process
group and is killed with that group when the test ends, whatever the outcome.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _children import Child, python_child

import drillstring as ds
from drillstring.io.atomic import atomic_path, atomic_write

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

SIGNAL_DELAY = 1.0  # s after the child reports that it is about to solve
#: Seconds a child may take to finish after the signal (a liveness bound: the solves run for
#: minutes or more if the signal does not stop them).
EXIT_TIMEOUT = 120.0


def _interrupt(child: Child) -> float:
    """Sends SIGINT after SIGNAL_DELAY; returns the time.monotonic() of the signal."""
    time.sleep(SIGNAL_DELAY)
    return child.interrupt()


LONG_SOLVES = {
    "simulate": "ds.simulate(ds.preset('aluminum'), modes=8, rigid_mode=True, t_end=1e5, samples=11)",
    "solve_pde": "ds.solve_pde(ds.preset('aluminum'), nodes=2000, t_end=1e3, samples=11)",
    "simulate-rk4": "ds.simulate(ds.preset('aluminum'), modes=4, t_end=9e3, method='rk4', dt=1e-4, samples=11)",
    "solve_pde-verlet": "ds.solve_pde(ds.preset('aluminum'), nodes=2000, t_end=1e2, method='verlet', samples=11)",
}


@pytest.mark.parametrize("call", list(LONG_SOLVES.values()), ids=list(LONG_SOLVES))
def test_ctrl_c_interrupts_a_long_solve(tmp_path: Path, call: str) -> None:
    script = f"""
        import time
        import drillstring as ds
        print("ready", flush=True)
        try:
            {call}
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
        # The interpreter is still usable: another solve works.
        res = ds.simulate(ds.preset("aluminum"), t_end=0.01, samples=5)
        print("after", res.status, flush=True)
        """
    with python_child(script, tmp_path) as child:
        sent = _interrupt(child)
        out, err = child.communicate(timeout=EXIT_TIMEOUT)
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), (out, err)
    latency = float(lines[0].split()[1]) - sent
    print(f"{call}: KeyboardInterrupt {1000 * latency:.1f} ms after SIGINT")
    assert lines[1] == "after success" and child.proc.returncode == 0, (out, err)


def test_a_python_signal_handler_runs_during_the_solve(tmp_path: Path) -> None:
    """Signal handlers run while the core computes (not only after it); one that does not raise
    lets the solve go on.

    The child's handler reports each SIGINT on stdout the moment it runs and raises
    KeyboardInterrupt only at the second one. The solve would run for hours: the report of the
    first signal can only arrive while the solve is running if handlers run during it, and the
    second signal finding the solve still running shows that the first one did not stop it. No
    timing is involved, so load does not matter.
    """
    script = """
        import signal
        import drillstring as ds
        count = 0
        def handler(signum, frame):
            global count
            count += 1
            print("handled", count, flush=True)
            if count == 2:
                raise KeyboardInterrupt
        signal.signal(signal.SIGINT, handler)
        print("ready", flush=True)
        try:
            res = ds.solve_pde(ds.preset("aluminum"), nodes=1000, t_end=1e4, samples=11)  # hours
            print("finished", res.status, flush=True)
        except KeyboardInterrupt:
            print("interrupted after", count, flush=True)
        """
    with python_child(script, tmp_path) as child:
        _interrupt(child)
        assert child.read_line(EXIT_TIMEOUT) == "handled 1"  # while the solve runs ...
        assert child.proc.poll() is None  # ... and it goes on
        child.interrupt()
        out, err = child.communicate(timeout=EXIT_TIMEOUT)
    assert out.split("\n")[:2] == ["handled 2", "interrupted after 2"], (out, err)
    assert child.proc.returncode == 0, (out, err)


def test_cli_ctrl_c_exits_130_and_writes_no_partial_files(tmp_path: Path) -> None:
    old = tmp_path / "run.csv"
    old.write_text("previous results\n")
    script = """
        import sys, time
        from drillstring import cli, plots
        from drillstring.solvers import pde
        print("ready", flush=True)
        code = cli.main(["pde", "--preset", "aluminum", "--nodes", "2000", "--t-end", "1000", "--samples", "11",
                         "--out", "run.csv", "--field", "field.npz", "--plot", "plot.png"])
        print(time.monotonic(), flush=True)
        sys.exit(code)
        """
    with python_child(script, tmp_path) as child:
        # 11 samples over 1000 s cannot resolve the motion: one warning line says so before the
        # solve (waited for, so that the signal comes during the solve on a loaded machine too)
        warning = child.read_line(stream="stderr")
        sent = _interrupt(child)
        out, err = child.communicate(timeout=EXIT_TIMEOUT)
    assert child.proc.returncode == 130, (out, err)
    (interrupted,) = err.splitlines()
    assert warning.startswith("drillstring: warning: under-resolved output: samples = 11") and err.endswith("\n")
    assert interrupted == "drillstring: interrupted"
    latency = float(out.split()[0]) - sent
    print(f"CLI exits {1000 * latency:.1f} ms after SIGINT")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]
    assert old.read_text() == "previous results\n"


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, does not count)."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            return handle.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False
    except OSError:  # no /proc (macOS): signal 0 tells whether the pid exists
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True


def test_a_child_and_its_own_children_are_killed_when_a_test_fails(tmp_path: Path) -> None:
    """The helper's guarantee: however the test ends, the child and every process it started
    are killed (its whole process group), so nothing CPU-heavy outlives the test."""
    script = """
        import subprocess, sys, time
        grandchild = subprocess.Popen([sys.executable, "-c", "while True: pass"])  # busy, like a solve
        print("ready", flush=True)
        print(grandchild.pid, flush=True)
        time.sleep(600)
        """
    with pytest.raises(AssertionError, match="a failing check"), python_child(script, tmp_path) as child:
        grandchild = int(child.read_line())
        assert _alive(grandchild)
        raise AssertionError("a failing check")
    assert child.proc.returncode == -signal.SIGKILL
    for _ in range(300):  # the orphaned grandchild is reaped by init: wait for that, up to 30 s
        if not _alive(grandchild):
            break
        time.sleep(0.1)
    assert not _alive(grandchild)


# ------------------------------------------------------------------ atomic writes


def test_an_interrupted_write_leaves_the_old_file_and_no_temporary(tmp_path: Path) -> None:
    target = tmp_path / "out.csv"
    target.write_text("old\n")

    def writer(path: str) -> None:
        with open(path, "w") as handle:
            handle.write("half of the new content")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(target, writer)
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]

    with pytest.raises(ZeroDivisionError), atomic_path(tmp_path / "new.txt") as tmp:
        Path(tmp).write_text("partial")
        1 / 0  # noqa: B018
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]

    atomic_write(target, lambda path: Path(path).write_text("new\n"))
    assert target.read_text() == "new\n" and [p.name for p in tmp_path.iterdir()] == ["out.csv"]


def test_result_files_are_written_atomically_with_their_formats(tmp_path: Path) -> None:
    res = ds.solve_pde(ds.preset("aluminum"), nodes=20, t_end=0.01, samples=11, save_field_every=2)
    res.to_csv(tmp_path / "pde.csv", 10.0)
    res.save_field(tmp_path / "field")  # .npz appended, as numpy does
    fig = ds.plots.space_time(res, 10.0)
    ds.plots.save(fig, tmp_path / "plot.png")
    ds.plots.save(fig, tmp_path / "plot.svg")
    ds.preset("steel").save(tmp_path / "steel.toml")
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["field.npz", "pde.csv", "plot.png", "plot.svg", "steel.toml"]
    assert (tmp_path / "plot.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "plot.svg").read_text().lstrip().startswith("<?xml")
    with np.load(tmp_path / "field.npz") as data:
        assert data["theta"].shape == (20, 6)
    assert ds.load(tmp_path / "steel.toml") == ds.preset("steel")
    assert (tmp_path / "pde.csv").read_text().splitlines()[0] == "t,theta,theta_dot"
    assert np.loadtxt(tmp_path / "pde.csv", delimiter=",", skiprows=1).shape == (11, 3)
    # File objects are written directly.
    with open(tmp_path / "direct.csv", "w") as handle:
        res.to_csv(handle, 10.0)
    assert (tmp_path / "direct.csv").stat().st_size > 0
    assert os.access(tmp_path / "pde.csv", os.R_OK)


def test_sweep_ctrl_c_stops_and_keeps_what_finished(tmp_path: Path) -> None:
    # 20 x 20 runs in chunks of 5: finished chunks (and the finished runs of the chunk under
    # way) are kept, none is half-written, and the same command then resumes to the same table
    # as an uninterrupted sweep
    (tmp_path / "sweep.toml").write_text(
        "[base]\npreset = \"aluminum\"\n[solver]\nmodes = 6\nrigid_mode = true\nt_end = 3.0\n"
        "[grid]\nlength = {linspace = [100.0, 500.0, 20]}\nomega = {linspace = [0.0, 50.0, 20]}\n"
    )
    script = """
        import sys, time
        import pandas, pyarrow  # imported by the sweep: before "ready", so that the delay is spent solving
        from drillstring import cli, sweep
        print("ready", flush=True)
        code = cli.main(["sweep", "sweep.toml", "--out", "out", "--chunk-size", "5", "--threads", "1",
                         "--no-plots"])
        print(time.monotonic(), flush=True)
        sys.exit(code)
        """
    with python_child(script, tmp_path) as child:
        # the first chunk is stored before the signal (waited for: a fixed delay may end before
        # it on a loaded machine)
        deadline = time.monotonic() + EXIT_TIMEOUT
        while not list((tmp_path / "out" / "chunks").glob("chunk-*.parquet")):
            assert time.monotonic() < deadline and child.proc.poll() is None, "no chunk was stored"
            time.sleep(0.02)
        sent = child.interrupt()
        out, err = child.communicate(timeout=EXIT_TIMEOUT)
    assert child.proc.returncode == 130, (out, err)
    latency = float(out.split()[-1]) - sent
    print(f"sweep exits {1000 * latency:.1f} ms after SIGINT")
    # every stored chunk (also the one under way, with its finished runs) has its record
    chunks = sorted((tmp_path / "out" / "chunks").glob("chunk-*.parquet"))
    assert 0 < len(chunks) < 80
    assert sorted(p.name for p in (tmp_path / "out" / "chunks").iterdir()) == sorted(
        [p.name for p in chunks] + [p.with_suffix(".json").name for p in chunks])
    assert not (tmp_path / "out" / "results.parquet").exists()
    import pandas as pd

    from drillstring.cli import main

    for out_dir in ("out", "fresh"):  # resume with the same options; then an uninterrupted sweep
        args = ["sweep", str(tmp_path / "sweep.toml"), "--out", str(tmp_path / out_dir), "--chunk-size", "5"]
        assert main([*args, "--no-plots"]) == 0
    resumed = pd.read_parquet(tmp_path / "out" / "results.parquet")
    fresh = pd.read_parquet(tmp_path / "fresh" / "results.parquet")
    pd.testing.assert_frame_equal(resumed, fresh)
