"""How the cost of a modal solve grows with the number of modes.

Aluminium preset (Table 1), C = (0.1, 0.05, 0.02) on modes 1-3, the rigid mode included (n + 1
coordinates), DOP853, rtol = 1e-10, atol = 1e-12, output only at t = 0 and t_end. Per size n:

* terms: quartic terms of the basis (``drillstring.model.galerkin.dimensionless_integrals(n, True)``);
* setup: ``galerkin.project`` + building the core ``ModalSystem`` (``core_system()``: the term
  sum below ``_core.SPECTRAL_MIN_MODES`` retained modes, the pseudo-spectral evaluation from there
  on; column "rhs") (best of the repeats), which ``ds.simulate`` does before it integrates;
* wall: ``ds.simulate`` (best of ``--repeat``; one run when a run takes over 2 s), nfev;
* s per simulated s: (wall - setup) / t_end;
* us/eval: one right-hand-side evaluation, timed inside the Rust solver (fixed-step RK4 solve of
  the system minus the same solve of a same-size system without quartic terms, per evaluation;
  see ``_evalcost.py``), and its ratio to n = 16;
* total/floor: (wall - setup) / (nfev x us/eval): how much of the solve is not the right-hand side.

Time cap: each solve aims at t = 1 s but stops after ``--budget`` / (12 x us/eval) steps (about
``--budget`` seconds); the t reached is printed (marked ``*`` when short of 1 s) and "s per simulated
s" is measured over [0, t reached]. The step size changes as the motion spreads over the modes,
so a short span is not representative of a full second. With ``--eval-only N`` sizes >= N are
not solved at all, only their evaluation is timed.

    python benchmarks/mode_scaling.py [--modes 3 4 8 16 32 64 128 256] [--budget 20] [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np
from _evalcost import evaluation_cost

import drillstring as ds

RTOL, ATOL = 1e-10, 1e-12


def build(params: ds.Parameters, n: int):
    coeff = ds.model.galerkin.project(params, modes=n, rigid_mode=True)
    return coeff, coeff.core_system()


def timed_simulate(params: ds.Parameters, n: int, max_steps: int):
    """``(wall s, result, t reached)`` of a solve to t = 1 s stopped after ``max_steps`` steps."""
    reached = [0.0]

    def progress(t: float, _t_end: float) -> None:
        reached[0] = t

    start = time.perf_counter()
    res = ds.simulate(params, modes=n, rigid_mode=True, t_end=1.0, rtol=RTOL, atol=ATOL, t_eval=np.array([0.0, 1.0]),
                      max_steps=max_steps, check=False, progress=progress)
    wall = time.perf_counter() - start
    return wall, res, (1.0 if res.status == "success" else reached[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--modes", type=int, nargs="+", default=[3, 4, 8, 16, 32, 64, 128, 256])
    parser.add_argument("--budget", type=float, default=20.0, help="about this many seconds per solve (step cap)")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--eval-only", type=int, default=None, metavar="N", help="do not solve sizes >= N")
    args = parser.parse_args()

    params = ds.preset("aluminum")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"numpy {np.__version__}, python {platform.python_version()}, core kernels {ds.simd_path()}")
    print(f"case: aluminium preset, C = (0.1, 0.05, 0.02), n elastic modes + the rigid mode, DOP853, "
          f"rtol = {RTOL:g}, atol = {ATOL:g}")
    head = (f"{'n':>4} {'terms':>8} {'rhs':>8} {'setup s':>8} {'t_end':>6} {'wall s':>8} {'nfev':>7} {'s/sim s':>8} "
            f"{'us/eval':>9} {'vs n=16':>7} {'ns/term':>7} {'tot/floor':>9}")
    print(head)
    print("-" * len(head))
    rows = []
    for n in args.modes:
        terms = ds.model.galerkin.dimensionless_integrals(n, True).n_terms
        setup = float("inf")
        for _ in range(max(1, args.repeat)):
            start = time.perf_counter()
            coeff, system = build(params, n)
            setup = min(setup, time.perf_counter() - start)
        q0, v0 = coeff.initial_state(params)
        omega_max = float(np.sqrt(np.abs(coeff.stiffness / coeff.mass)).max())
        cost, _ = evaluation_cost(system, q0, v0, min(1e-4, 0.5 / omega_max))
        row = {"n": n, "terms": terms, "setup": setup, "cost": cost}
        if args.eval_only is None or n < args.eval_only:
            cap = max(20, int(args.budget / (12 * max(cost, 1e-9))))  # DOP853: 12 evaluations per step
            wall, res, reached = timed_simulate(params, n, cap)
            if wall < 2.0:
                for _ in range(max(1, args.repeat) - 1):
                    again = timed_simulate(params, n, cap)
                    if again[0] < wall:
                        wall, res, reached = again
            if res.status not in ("success", "max_steps"):
                raise RuntimeError(f"n = {n}: {res.status} {res.message}")
            t_end = reached
            solve = max(wall - setup, 0.0)
            row.update(t_end=t_end, wall=wall, nfev=res.stats.nfev, per_s=solve / t_end,
                       ratio=solve / (res.stats.nfev * cost) if cost > 0 else float("nan"))
        rows.append(row)
        ref = next((r["cost"] for r in rows if r["n"] == 16), None)
        vs16 = f"{row['cost'] / ref:7.1f}" if ref else f"{'':>7}"
        solved = (f"{row['t_end']:5.2g}{'*' if row['t_end'] < 1 else ' '} {row['wall']:8.3f} {row['nfev']:7d} "
                  f"{row['per_s']:8.3f}" if "wall" in row else f"{'(evaluation only)':>32}")
        floor = f"{row['ratio']:9.2f}" if "wall" in row else f"{'':>9}"
        print(f"{n:4d} {terms:8d} {system.evaluation:>8} {setup:8.3f} {solved} {cost * 1e6:9.3f} {vs16} "
              f"{cost / max(terms, 1) * 1e9:7.2f} {floor}", flush=True)
    by_n = {r["n"]: r for r in rows}
    if 16 in by_n and 64 in by_n:
        ratio = by_n[64]["cost"] / by_n[16]["cost"]
        terms = by_n[64]["terms"] / by_n[16]["terms"]
        print(f"per-evaluation cost, 64 modes / 16 modes: {ratio:.1f}x (quartic terms {terms:.1f}x; target: within 8x)")
    print("* stopped at the step cap (--budget): t_end is the time reached, s/sim s is over [0, t_end]")


if __name__ == "__main__":
    main()
