"""Figures drawn in forked processes (``drillstring.io.figures.FigureJobs``, what ``drillstring
drill`` uses on more than one core): the same files, byte for byte, as drawing them one after the
other here; a failure in a forked process raised here; the processes ended after one."""

from __future__ import annotations

import os
import threading
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from drillstring.io.figures import FigureJobs

fork_only = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")


def _figure(seed: int) -> Any:
    from matplotlib.figure import Figure

    rng = np.random.default_rng(seed)
    fig = Figure(figsize=(4, 3), layout="constrained")
    ax = fig.subplots()
    ax.plot(np.cumsum(rng.standard_normal(500)))
    ax.set_title(f"figure {seed}")
    return fig


def _broken() -> Any:
    raise ValueError("no data to draw")


def _jobs(folder: Path, seeds: range) -> list[tuple[Any, Any]]:
    return [(partial(_figure, seed), str(folder / f"f{seed}.png")) for seed in seeds]


@fork_only
@pytest.mark.parametrize("workers", [1, 2, 5])
def test_forked_figures_are_the_files_drawn_here(tmp_path: Path, workers: int) -> None:
    if threading.active_count() > 1:
        pytest.skip("another thread runs: FigureJobs draws everything here")
    here, forked = tmp_path / "here", tmp_path / "forked"
    here.mkdir(), forked.mkdir()
    serial = FigureJobs(_jobs(here, range(4)), workers=0).finish()
    jobs = FigureJobs(_jobs(forked, range(4)), workers=workers)
    assert len(jobs._children) == min(workers, 3)  # the figures are drawn elsewhere, not here
    paths = jobs.finish()
    assert [os.path.basename(p) for p in paths] == [os.path.basename(p) for p in serial]
    for name in ("f0.png", "f1.png", "f2.png", "f3.png"):
        assert (forked / name).read_bytes() == (here / name).read_bytes(), name


@fork_only
def test_a_failure_in_a_forked_process_is_raised_here(tmp_path: Path) -> None:
    if threading.active_count() > 1:
        pytest.skip("another thread runs: FigureJobs draws everything here")
    jobs = _jobs(tmp_path, range(3))
    jobs[0] = (_broken, str(tmp_path / "broken.png"))  # the first figure goes to a forked process
    started = FigureJobs(jobs, workers=1)
    assert started._children
    with pytest.raises(ValueError, match="no data to draw"):
        started.finish()
    assert started._children == []


@fork_only
def test_cancel_ends_the_forked_processes(tmp_path: Path) -> None:
    if threading.active_count() > 1:
        pytest.skip("another thread runs: FigureJobs draws everything here")
    started = FigureJobs(_jobs(tmp_path, range(3)), workers=2)
    pids = [pid for pid, _, _ in started._children]
    assert pids
    started.cancel()
    for pid in pids:
        with pytest.raises(ChildProcessError):
            os.waitpid(pid, os.WNOHANG)  # reaped: no such child any more
