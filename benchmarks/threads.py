"""Threaded solves: speed-up of solves started from several Python threads over the same solves
run one after another.

The Rust core releases the GIL while it computes, so solves started from ``--threads`` Python
threads (a ``ThreadPoolExecutor``) run on several cores at once. Measured: the wall time of
``--jobs`` PDE solves (the aluminium reference, ``--nodes`` nodes, ``0 <= t <= --t-end``,
different initial velocities) run sequentially and threaded, their ratio, and the CPU time per
wall second of the threaded run (about the number of cores kept busy; 1.0 would mean the solves
ran one at a time). The threaded results are checked to be bit-identical to the sequential ones
(the tests check that too: ``tests/test_threads.py``). Each variant is timed ``--repeat`` times,
alternating, and the fastest is kept; the CPU seconds other processes used meanwhile are shown,
since the machine may be shared (run it when nothing else is busy).

    python benchmarks/threads.py [--jobs 4] [--threads 4] [--nodes 400] [--t-end 2] [--repeat 3]
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Callable

import numpy as np

import drillstring as ds


def machine_cpu() -> float:
    """CPU seconds used by every process so far, from /proc/stat (0 where it does not exist)."""
    try:
        with open("/proc/stat") as handle:
            fields = [int(v) for v in handle.readline().split()[1:9]]
    except OSError:
        return 0.0
    user, nice, system, _idle, _iowait, irq, softirq, _steal = fields
    return (user + nice + system + irq + softirq) / os.sysconf("SC_CLK_TCK")


def timed(run: Callable[[], list[Any]]) -> tuple[list[Any], float, float, float]:
    """(results, wall s, CPU s of this process, CPU s of other processes) of ``run()``."""
    busy0, wall0, cpu0 = machine_cpu(), time.perf_counter(), time.process_time()
    out = run()
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    return out, wall, cpu, max(0.0, machine_cpu() - busy0 - cpu)


def same(a: Any, b: Any) -> bool:
    return bool(
        np.array_equal(a.t, b.t) and np.array_equal(a.q, b.q) and np.array_equal(a.qdot, b.qdot)
        and a.stats == b.stats and a.status == b.status
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--jobs", type=int, default=4, help="number of solves (default 4)")
    parser.add_argument("--threads", type=int, default=4, help="Python threads of the threaded run (default 4)")
    parser.add_argument("--nodes", type=int, default=400, help="PDE grid points (default 400)")
    parser.add_argument("--t-end", type=float, default=2.0, help="end time of each solve, s (default 2)")
    parser.add_argument("--repeat", type=int, default=3, help="timings of each variant (the fastest is kept)")
    args = parser.parse_args()

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    print(f"machine: {platform.machine()}, {cores} cores available ({os.cpu_count()} in total), "
          f"Python {platform.python_version()}, drillstring {ds.__version__}")
    print(f"{args.jobs} PDE solves of {args.nodes} nodes over 0 <= t <= {args.t_end:g} s, "
          f"sequential vs {args.threads} threads\n")

    base = ds.preset("aluminum")
    jobs = [base.replace(initial_velocities=(0.1 * (k + 1), 0.05, 0.02)) for k in range(args.jobs)]

    def solve(params: ds.Parameters) -> Any:
        return ds.solve_pde(params, nodes=args.nodes, t_end=args.t_end, samples=51)

    def threaded() -> list[Any]:
        with ThreadPoolExecutor(max_workers=args.threads) as pool:
            return list(pool.map(solve, jobs))

    solve(jobs[0])  # warm-up
    best: dict[str, tuple[list[Any], float, float, float]] = {}
    for _ in range(args.repeat):  # alternate; keep the fastest of each
        for name, run in (("sequential", lambda: [solve(p) for p in jobs]), ("threaded", threaded)):
            timing = timed(run)
            if name not in best or timing[1] < best[name][1]:
                best[name] = timing
    for name, (_, wall, cpu, others) in best.items():
        print(f"{name:10s}: {wall:6.2f} s wall, {cpu:6.2f} s CPU = {cpu / wall:4.2f} CPU/wall; "
              f"other processes used {others:.2f} CPU-s meanwhile")
    seq, par = best["sequential"], best["threaded"]
    ideal = min(args.threads, args.jobs, cores or 1)
    print(f"\nthreaded / sequential wall time: {par[1] / seq[1]:.2f} (speed-up {seq[1] / par[1]:.2f}x; "
          f"ideal on {ideal} cores {1 / ideal:.2f})")
    print(f"CPU / wall of the threaded run: {par[2] / par[1]:.2f} (cores kept busy; the GIL-bound limit is 1.0)")
    print(f"threaded results bit-identical to sequential: {all(same(a, b) for a, b in zip(seq[0], par[0]))}")


if __name__ == "__main__":
    main()
