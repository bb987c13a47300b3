"""drillstring.solve_pde vs scipy.integrate.solve_ivp(method="DOP853") on the same discretisation.

Table 1 parameters, N = 240 nodes, C = (0.1, 0.05, 0.02) on modes 1-3, 0 <= t <= 1,
rtol = 1e-10 (atol = 1e-13), 101 output times. scipy gets a vectorised numpy right-hand side of
exactly the energy-conserving scheme that drillstring integrates (cell fluxes, trapezoid node
weights). Both solutions are compared; times are the best of the repeats; the ratio is
scipy / drillstring, also per right-hand-side evaluation; scipy's floor (nfev x the cost of one
call of its rhs) is printed next to its total. The machine line names the code
path of the core's kernels (``avx2+fma`` or ``baseline``; ``DRILLSTRING_SIMD=baseline`` pins the
latter). Peak resident memory of a drillstring solve for N = 240 and N = 2400 is
measured in a fresh subprocess each (ru_maxrss of the solve minus that of the set-up).

    python benchmarks/compare_scipy_pde.py [--repeat 3] [--nodes 240]
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time

import numpy as np
from _evalcost import per_call_time

import drillstring as ds
from drillstring.model.coefficients import PDECoefficients

RTOL, ATOL = 1e-10, 1e-13


def numpy_rhs(params: ds.Parameters, nodes: int):
    k = PDECoefficients.from_parameters(params)
    h = params.length / (nodes - 1)
    w = np.full(nodes, h)
    w[0] = w[-1] = h / 2
    inv_mass = 1.0 / (w * k.k1)
    half_k4 = 0.5 * k.k4

    def rhs(_t, y):
        th, v = y[:nodes], y[nodes:]
        g = np.diff(th) / h
        g2 = g * g
        flux = (k.k2 + half_k4 * (th[:-1] ** 2 + th[1:] ** 2) + k.k5 * g2) * g
        dv = w * (k.k3 * th**3 - k.k6 * th)
        dv[1:] += flux + h * half_k4 * th[1:] * g2
        dv[:-1] += -flux + h * half_k4 * th[:-1] * g2
        return np.concatenate([v, -dv * inv_mass])

    return rhs


def best_of(repeat: int, fn):
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


MEMORY_PROBE = """
import resource, sys
import numpy as np
import drillstring as ds
nodes = int(sys.argv[1])
params = ds.preset("aluminum")
ds.solve_pde(params, nodes=nodes, t_end=1e-4, rtol=1e-10, atol=1e-13, samples=2)  # warm-up: imports, pages
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
sol = ds.solve_pde(params, nodes=nodes, t_end=1.0, rtol=1e-10, atol=1e-13, samples=101)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(after - before, after, sol.stats.naccept)
"""


def peak_memory(nodes: int) -> tuple[int, int, int]:
    out = subprocess.run([sys.executable, "-c", MEMORY_PROBE, str(nodes)], capture_output=True, text=True, check=True)
    extra, total, steps = (int(x) for x in out.stdout.split())
    return extra, total, steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--nodes", type=int, default=240)
    parser.add_argument("--no-memory", action="store_true", help="skip the memory measurement")
    args = parser.parse_args()

    params = ds.preset("aluminum")
    nodes = args.nodes
    t_eval = np.linspace(0.0, 1.0, 101)
    system = ds.solvers.pde.pde_system(params, nodes)
    v0 = np.asarray(system.initial_velocity_from_modes(np.asarray(params.initial_velocities)))
    y0 = np.concatenate([np.zeros(nodes), v0])
    rhs = numpy_rhs(params, nodes)
    np.testing.assert_allclose(rhs(0.0, y0)[nodes:], system.acceleration(np.zeros(nodes)), atol=0)

    from scipy.integrate import solve_ivp

    t_ds, sol = best_of(args.repeat, lambda: ds.solve_pde(params, nodes=nodes, t_eval=t_eval, rtol=RTOL, atol=ATOL))
    t_sp, ref = best_of(1, lambda: solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", t_eval=t_eval, rtol=RTOL, atol=ATOL))
    diff = np.abs(sol.q - ref.y[:nodes]).max()
    scale = np.abs(ref.y[:nodes]).max()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"numpy {np.__version__}, python {platform.python_version()}, core kernels {ds.simd_path()}")
    print(f"case: PDE, N = {nodes} nodes, Table 1, C = (0.1, 0.05, 0.02), 0 <= t <= 1, DOP853, "
          f"rtol = {RTOL:g}, atol = {ATOL:g}")
    print(f"scipy solve_ivp DOP853, numpy rhs : {t_sp:8.3f} s  ({ref.nfev} rhs evaluations)")
    print(f"drillstring.solve_pde            : {t_ds:8.3f} s  ({sol.stats.nfev} rhs evaluations, "
          f"{sol.stats.naccept} steps)")
    print(f"max |theta_drillstring - theta_scipy| = {diff:.3e} rad ({diff / scale:.2e} of max |theta|)")
    print(f"energy drift of drillstring's solve: {sol.energy_drift():.2e}")
    print(f"speed-up (scipy / drillstring): {t_sp / t_ds:.1f}x")
    # The step sequence at this tolerance is sensitive to rounding (the step size sits at the
    # stability limit of the finest grid modes), so the evaluation counts differ by a few %.
    per_sp, per_ds = t_sp / ref.nfev, t_ds / sol.stats.nfev
    print(f"per rhs evaluation (stages included): scipy {per_sp * 1e6:.1f} us, drillstring {per_ds * 1e6:.2f} us "
          f"({per_sp / per_ds:.1f}x)")
    # scipy's floor: nfev x its numpy rhs called from Python (best per-call time in a loop).
    # drillstring's evaluation is not timed here: from Python its ~0.5 us call overhead is as large
    # as the evaluation; `cargo bench -p drillstring-core --bench pde` times it in Rust alone.
    y_mid = ref.y[:, ref.y.shape[1] // 2].copy()
    cost_sp = per_call_time(lambda: rhs(0.5, y_mid))
    print(f"scipy floor = nfev x {cost_sp * 1e6:.1f} us per rhs evaluation = {ref.nfev * cost_sp:.3f} s "
          f"(total/floor {t_sp / (ref.nfev * cost_sp):.2f})")
    if not args.no_memory:
        for n in (240, 2400):
            extra, total, steps = peak_memory(n)
            print(f"peak memory N = {n:5d}: +{extra / 1024:.1f} MiB during the solve "
                  f"(process peak {total / 1024:.0f} MiB; {steps} steps, 101 samples)")


if __name__ == "__main__":
    main()
