"""Cost of one right-hand-side evaluation of a core system, measured inside the Rust solver.

A Python call of ``system.acceleration(q)`` costs ~0.5 us of call overhead (argument
conversion, a copy of ``q``, the new output array), more than a whole 3-mode evaluation, so the
evaluation is timed where the solver calls it instead: a fixed-step RK4 solve of the system
(``nfev`` = 4 x steps, no step-size control) against the same solve of a "null" system of the
same size, a ``ModalSystem`` without quartic terms whose acceleration is n multiply-adds. The
difference of the two solve times divided by ``nfev`` is the cost of one evaluation minus n
multiply-adds, so ``nfev x cost`` is a lower bound (the "floor") of the time a solve spends in
its right-hand side. Both solves are timed interleaved, best of ``repeat``, which suppresses
(not removes) the influence of other load on the machine.
"""

from __future__ import annotations

import time
from typing import Any, Callable

import numpy as np

from drillstring import _core


def null_system(size: int) -> Any:
    """A ``ModalSystem`` of ``size`` coordinates without quartic terms (the reference)."""
    return _core.ModalSystem(np.ones(size), np.ones(size), np.zeros((0, 4), dtype=np.int64), np.zeros(0))


def per_call_time(fn: Callable[[], Any], repeat: int = 7, batch_s: float = 0.02) -> float:
    """Best per-call time of ``fn()`` over ``repeat`` batches of about ``batch_s`` seconds."""

    def batch(calls: int) -> float:
        start = time.perf_counter()
        for _ in range(calls):
            fn()
        return (time.perf_counter() - start) / calls

    calls = max(1, int(batch_s / max(batch(1), 1e-9)))
    return min(batch(calls) for _ in range(repeat))


def _rk4(solver: Callable[..., Any], system: Any, q0: np.ndarray, v0: np.ndarray, dt: float, steps: int):
    t_end = steps * dt
    start = time.perf_counter()
    out = solver(system, q0, v0, t_end, np.array([0.0, t_end]), "rk4", 1e-6, 1e-6, dt=dt)
    elapsed = time.perf_counter() - start
    if out["status"] != "success":
        raise RuntimeError(f"RK4 timing solve ended with {out['status']}: {out['message']}")
    return elapsed, int(out["nfev"])


def evaluation_cost(
    system: Any,
    q0: np.ndarray,
    v0: np.ndarray,
    dt: float,
    *,
    pde: bool = False,
    repeat: int = 5,
    target_s: float = 0.05,
) -> tuple[float, int]:
    """``(cost in s per evaluation, evaluations timed per solve)`` of ``system`` (a
    ``ModalSystem``, or a ``PdeSystem`` with ``pde=True``: there the null system is no cheaper
than a small PDE grid, so use it only where the evaluation dominates) from ``(q0, v0)`` with RK4 step
    ``dt`` (stable for the system); each timed solve lasts about ``target_s``."""
    q0 = np.ascontiguousarray(q0, dtype=np.float64)
    v0 = np.ascontiguousarray(v0, dtype=np.float64)
    solver = _core.solve_pde if pde else _core.solve_modal
    null = null_system(q0.size)
    steps = 1
    while True:  # calibrate: solves of about target_s
        elapsed, _ = _rk4(solver, system, q0, v0, dt, steps)
        if elapsed >= target_s / 4:
            break
        steps *= 4
    steps = max(2, int(steps * target_s / elapsed))
    best, best_null, nfev = float("inf"), float("inf"), 0
    for _ in range(repeat):
        elapsed, nfev = _rk4(solver, system, q0, v0, dt, steps)
        best = min(best, elapsed)
        elapsed, nfev_null = _rk4(_core.solve_modal, null, q0, v0, dt, steps)
        best_null = min(best_null, elapsed)
        if nfev_null != nfev:  # pragma: no cover - both are fixed-step RK4 over the same steps
            raise RuntimeError(f"evaluation counts differ: {nfev} vs {nfev_null}")
    return max(best - best_null, 0.0) / nfev, nfev
