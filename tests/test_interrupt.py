"""Ctrl-C during a long Rust solve: control returns to Python within 1 s (in practice a few ms)
as KeyboardInterrupt, the interpreter stays usable, the command line exits with status 130 and no
output file is left half-written (every output is written to a temporary file and renamed)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import drillstring as ds
from drillstring._atomic import atomic_path, atomic_write

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

SIGNAL_DELAY = 1.0  # s after the child reports that it is about to solve


def _start(script: str, cwd: Path) -> subprocess.Popen[str]:
    proc = subprocess.Popen(
        [sys.executable, "-c", textwrap.dedent(script)],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout is not None
    line = proc.stdout.readline()
    assert line.strip() == "ready", (line, proc.stderr.read() if proc.stderr else "")
    return proc


def _interrupt(proc: subprocess.Popen[str]) -> float:
    """Sends SIGINT after SIGNAL_DELAY; returns the time.monotonic() of the signal."""
    time.sleep(SIGNAL_DELAY)
    assert proc.poll() is None, "the solve ended before the signal"
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    return sent


LONG_SOLVES = {
    "simulate": "ds.simulate(ds.preset('aluminum'), modes=8, rigid_mode=True, t_end=1e5, samples=11)",
    "solve_pde": "ds.solve_pde(ds.preset('aluminum'), nodes=2000, t_end=1e3, samples=11)",
    "simulate-rk4": "ds.simulate(ds.preset('aluminum'), modes=4, t_end=9e3, method='rk4', dt=1e-4, samples=11)",
    "solve_pde-verlet": "ds.solve_pde(ds.preset('aluminum'), nodes=2000, t_end=1e2, method='verlet', samples=11)",
}


@pytest.mark.parametrize("call", list(LONG_SOLVES.values()), ids=list(LONG_SOLVES))
def test_ctrl_c_interrupts_a_long_solve_within_a_second(tmp_path: Path, call: str) -> None:
    proc = _start(
        f"""
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
        """,
        tmp_path,
    )
    sent = _interrupt(proc)
    out, err = proc.communicate(timeout=60)
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), (out, err)
    latency = float(lines[0].split()[1]) - sent
    print(f"{call}: KeyboardInterrupt {1000 * latency:.1f} ms after SIGINT")
    assert 0 <= latency < 1.0
    assert lines[1] == "after success" and proc.returncode == 0, (out, err)


def test_a_python_signal_handler_runs_during_the_solve(tmp_path: Path) -> None:
    """Signal handlers run while the core computes (not only after it); one that does not raise
    lets the solve go on."""
    proc = _start(
        """
        import signal, time
        import drillstring as ds
        handled = []
        signal.signal(signal.SIGINT, lambda *_: handled.append(time.monotonic()))
        print("ready", flush=True)
        res = ds.solve_pde(ds.preset("aluminum"), nodes=1000, t_end=3.0, samples=11)  # a few seconds
        print(res.status, time.monotonic(), *handled, flush=True)
        """,
        tmp_path,
    )
    sent = _interrupt(proc)
    out, err = proc.communicate(timeout=120)
    status, finished, handled = out.split()
    assert status == "success", (out, err)
    assert float(handled) - sent < 0.2 and float(finished) - float(handled) > 0.1, out


def test_cli_ctrl_c_exits_130_and_writes_no_partial_files(tmp_path: Path) -> None:
    old = tmp_path / "run.csv"
    old.write_text("previous results\n")
    proc = _start(
        """
        import sys, time
        from drillstring import cli, pde, plots
        print("ready", flush=True)
        code = cli.main(["pde", "--preset", "aluminum", "--nodes", "2000", "--t-end", "1000", "--samples", "11",
                         "--out", "run.csv", "--field", "field.npz", "--plot", "plot.png"])
        print(time.monotonic(), flush=True)
        sys.exit(code)
        """,
        tmp_path,
    )
    sent = _interrupt(proc)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, (out, err)
    assert err == "drillstring: interrupted\n"
    latency = float(out.split()[0]) - sent
    print(f"CLI exits {1000 * latency:.1f} ms after SIGINT")
    assert 0 <= latency < 1.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]
    assert old.read_text() == "previous results\n"


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


def test_sweep_ctrl_c_stops_within_a_second_and_keeps_only_whole_chunks(tmp_path: Path) -> None:
    # 20 x 20 runs in chunks of 5: finished chunks are kept, none is half-written, and the
    # same command then resumes to the same table as an uninterrupted sweep
    (tmp_path / "sweep.toml").write_text(
        "[base]\npreset = \"aluminum\"\n[solver]\nmodes = 6\nrigid_mode = true\nt_end = 3.0\n"
        "[grid]\nlength = {linspace = [100.0, 500.0, 20]}\nomega = {linspace = [0.0, 50.0, 20]}\n"
    )
    proc = _start(
        """
        import sys, time
        from drillstring import cli, sweep
        print("ready", flush=True)
        code = cli.main(["sweep", "sweep.toml", "--out", "out", "--chunk-size", "5", "--threads", "1",
                         "--no-plots"])
        print(time.monotonic(), flush=True)
        sys.exit(code)
        """,
        tmp_path,
    )
    sent = _interrupt(proc)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, (out, err)
    latency = float(out.split()[-1]) - sent
    print(f"sweep exits {1000 * latency:.1f} ms after SIGINT")
    assert 0 <= latency < 1.0
    chunks = sorted((tmp_path / "out" / "chunks").iterdir())
    assert 0 < len(chunks) < 80 and all(p.suffix == ".parquet" for p in chunks)
    assert not (tmp_path / "out" / "results.parquet").exists()
    import pandas as pd

    from drillstring.cli import main

    for out_dir in ("out", "fresh"):  # resume with the same options; then an uninterrupted sweep
        args = ["sweep", str(tmp_path / "sweep.toml"), "--out", str(tmp_path / out_dir), "--chunk-size", "5"]
        assert main([*args, "--no-plots"]) == 0
    resumed = pd.read_parquet(tmp_path / "out" / "results.parquet")
    fresh = pd.read_parquet(tmp_path / "fresh" / "results.parquet")
    pd.testing.assert_frame_equal(resumed, fresh)
