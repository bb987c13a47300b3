"""drillstring vs scipy.integrate.solve_ivp(method="DOP853") on the 3-mode reference case.

Table 1 parameters, C = (0.1, 0.05, 0.02), 0 <= t <= 1, rtol = atol = 1e-12, 1001 output times.
scipy gets the fastest numpy right-hand side we could write for it (precomputed diagonal
M^-1 K, the quartic terms as index arrays). Both solutions are compared; times are the best of
several repeats; the ratio is scipy time / drillstring time.

Each side also gets its floor: nfev x the measured cost of one right-hand-side evaluation, and
the ratio total / floor (how much of the solve is not spent evaluating the right-hand side).
scipy's evaluation is its numpy rhs called from Python (best per-call time in a loop).
drillstring's is timed inside the Rust solver: a fixed-step RK4 solve of the
same modal system minus the same solve of a same-size system without quartic terms, per
evaluation (``_evalcost.py``): a lower bound of the evaluation cost.

    python benchmarks/compare_scipy.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np
from _evalcost import evaluation_cost, per_call_time
from scipy.integrate import solve_ivp

import drillstring as ds
from drillstring import _core


def best_of(repeat: int, fn):
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    params = ds.preset("aluminum")
    tol = 1e-12
    t_eval = np.linspace(0.0, 1.0, 1001)
    coeff = ds.galerkin.project(params, modes=3)
    q0, v0 = coeff.initial_state(params)
    m = len(coeff.indices)
    inv_mass = 1.0 / coeff.mass
    k_over_m = coeff.stiffness * inv_mass
    idx = coeff.quartic_index
    a, b, c, d = (idx[:, j] for j in range(4))
    cm = coeff.quartic_coef

    def rhs(_t, y):
        q, v = y[:m], y[m:]
        qa, qb, qc, qd = q[a], q[b], q[c], q[d]
        force = np.zeros(m)
        np.add.at(force, a, cm * qb * qc * qd)
        np.add.at(force, b, cm * qa * qc * qd)
        np.add.at(force, c, cm * qa * qb * qd)
        np.add.at(force, d, cm * qa * qb * qc)
        return np.concatenate([v, -k_over_m * q - force * inv_mass])

    y0 = np.concatenate([q0, v0])
    t_scipy, ref = best_of(
        max(1, args.repeat // 2),
        lambda: solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", t_eval=t_eval, rtol=tol, atol=tol),
    )
    t_ds, res = best_of(args.repeat, lambda: ds.simulate(params, modes=3, t_eval=t_eval, rtol=tol, atol=tol))
    diff = np.abs(res.q - ref.y[:m]).max()
    scale = np.abs(ref.y[:m]).max()
    # cost of one evaluation at a state from the middle of the solution
    y_mid = ref.y[:, ref.y.shape[1] // 2].copy()
    cost_sp = per_call_time(lambda: rhs(0.5, y_mid))
    system = _core.ModalSystem(
        coeff.mass, coeff.stiffness, np.ascontiguousarray(idx, dtype=np.int64), coeff.quartic_coef
    )
    cost_ds, timed = evaluation_cost(system, q0, v0, 1e-4)
    floor_sp, floor_ds = ref.nfev * cost_sp, res.stats.nfev * cost_ds
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"numpy {np.__version__}, python {platform.python_version()}, core kernels {ds.simd_path()}")
    print("case: 3 modes, Table 1, C = (0.1, 0.05, 0.02), 0 <= t <= 1, DOP853, rtol = atol = 1e-12")
    print(f"scipy solve_ivp DOP853 : {t_scipy * 1e3:9.2f} ms  ({ref.nfev} rhs evaluations)")
    print(f"drillstring.simulate   : {t_ds * 1e3:9.3f} ms  ({res.stats.nfev} rhs evaluations, "
          f"{res.stats.naccept} steps)")
    print(f"max |q_drillstring - q_scipy| = {diff:.3e} rad ({diff / scale:.2e} of max |q|)")
    print(f"speed-up (scipy / drillstring): {t_scipy / t_ds:.0f}x")
    print("floor = nfev x cost of one rhs evaluation (measured in this run):")
    print(f"  scipy       : {cost_sp * 1e6:8.3f} us/eval -> floor {floor_sp * 1e3:9.3f} ms, "
          f"total {t_scipy * 1e3:9.3f} ms, total/floor {t_scipy / floor_sp:5.2f}")
    print(f"  drillstring : {cost_ds * 1e6:8.3f} us/eval -> floor {floor_ds * 1e3:9.3f} ms, "
          f"total {t_ds * 1e3:9.3f} ms, total/floor "
          + (f"{t_ds / floor_ds:5.2f}" if floor_ds > 0 else "n/a (cost below resolution)"))
    print(f"  (drillstring's cost: RK4 solve of this system minus that of a {m}-coordinate system without "
          f"quartic terms, {timed} evaluations each, best of 5)")


if __name__ == "__main__":
    main()
