"""Solves started from several Python threads give bit-identical results to the same solves run
one after another, and the Rust core releases the GIL while it computes.

What threads guarantee is tested here without timing: identical results, and that other Python
threads keep running during a solve (overlap, shown by ordering, not by speed). How much faster
threaded solves are is measured in ``benchmarks/threads.py``.
"""

from __future__ import annotations

import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Callable

import numpy as np
import pytest

import drillstring as ds

P = ds.preset("aluminum")


def _same(a: Any, b: Any) -> bool:
    return (
        np.array_equal(a.t, b.t)
        and np.array_equal(a.q, b.q)
        and np.array_equal(a.qdot, b.qdot)
        and a.stats == b.stats
        and a.status == b.status
    )


def _main_thread_during(call: Callable[[], Any]) -> tuple[float, float, list[float], Any]:
    """Runs ``call`` in a worker thread while this (the main) thread keeps executing Python code.

    Returns the worker's timestamps just before and just after ``call``, the timestamps of the
    main thread's loop iterations meanwhile, and what ``call`` returned. The main thread needs the
    GIL for every iteration: if ``call`` held the GIL, no iteration could fall inside it except
    at its very ends (while the worker is still or again running Python code).
    """
    started = threading.Event()
    box: dict[str, Any] = {}

    def worker() -> None:
        try:
            started.set()
            box["t0"] = time.perf_counter()
            box["value"] = call()
            box["t1"] = time.perf_counter()
        except BaseException as exc:  # reported by the main thread
            box["error"] = exc

    thread = threading.Thread(target=worker, daemon=True)
    stamps: list[float] = []
    thread.start()
    started.wait()
    while thread.is_alive():
        sum(range(100))  # Python work: needs the GIL
        stamps.append(time.perf_counter())
    thread.join()
    if "error" in box:
        raise box["error"]
    return box["t0"], box["t1"], stamps, box["value"]


def _inside(t0: float, t1: float, stamps: list[float]) -> int:
    """How many of ``stamps`` fall in the middle half of ``[t0, t1]``."""
    quarter = (t1 - t0) / 4
    return sum(1 for t in stamps if t0 + quarter < t < t1 - quarter)


GIL_DISABLED = hasattr(sys, "_is_gil_enabled") and not sys._is_gil_enabled()


@pytest.mark.parametrize(
    "solve",
    [
        lambda: ds.solve_pde(P, nodes=400, t_end=6.0, samples=51),  # about 1 s on one core
        lambda: ds.simulate(P, modes=8, rigid_mode=True, t_end=60.0, samples=51),
    ],
    ids=["solve_pde", "simulate"],
)
def test_the_main_thread_runs_python_code_during_a_solve_in_another_thread(solve: Callable[[], Any]) -> None:
    t0, t1, stamps, result = _main_thread_during(solve)
    assert result.success
    inside = _inside(t0, t1, stamps)
    print(f"solve {t1 - t0:.2f} s; {len(stamps)} main-thread iterations, {inside} in its middle half")
    assert inside > 0, "the main thread was blocked during the whole solve: the GIL was not released"


@pytest.mark.skipif(GIL_DISABLED, reason="a free-threaded build has no GIL to hold")
def test_the_overlap_check_detects_a_call_that_holds_the_gil() -> None:
    """The control: the same measurement around a C loop that keeps the GIL (builtin sum over
    a range runs without giving it up) finds no main-thread iteration in the middle of it."""
    t0, t1, stamps, total = _main_thread_during(lambda: sum(range(30_000_000)))
    assert total == 30_000_000 * 29_999_999 // 2
    print(f"sum {t1 - t0:.2f} s; {len(stamps)} main-thread iterations")
    assert _inside(t0, t1, stamps) == 0


def test_threaded_pde_solves_match_sequential_runs() -> None:
    jobs = [P.replace(initial_velocities=(0.1 * (k + 1), 0.05, 0.02)) for k in range(4)]

    def solve(params: ds.Parameters) -> Any:
        return ds.solve_pde(params, nodes=400, t_end=0.5, samples=51)

    sequential = [solve(p) for p in jobs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(solve, jobs))
    assert all(_same(a, b) for a, b in zip(sequential, threaded)), "threaded results differ"
    assert not _same(sequential[0], sequential[1])  # the jobs differ, so the comparison means something


def test_threaded_modal_solves_are_bit_identical_for_every_method() -> None:
    jobs = [
        {"modes": 3, "t_end": 1.0, "method": method, **({"dt": 1e-4, "samples": 101} if method in
                                                         ("rk4", "central", "verlet") else {})}
        for method in ds.METHODS
    ] * 2
    sequential = [ds.simulate(P, **kw) for kw in jobs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda kw: ds.simulate(P, **kw), jobs))
    assert all(_same(a, b) for a, b in zip(sequential, threaded))
    assert all(_same(a, b) for a, b in zip(threaded[: len(ds.METHODS)], threaded[len(ds.METHODS):]))
