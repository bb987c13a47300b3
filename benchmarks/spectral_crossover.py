"""Where the pseudo-spectral quartic force becomes cheaper than the term sum.

Per size n (n elastic modes + the rigid mode, aluminium preset): the cost of one right-hand-side
evaluation inside the Rust solver (``_evalcost.evaluation_cost``) of the same model built with
``evaluation="terms"`` (the merged cubic monomials) and ``evaluation="spectral"`` (the exact
quadrature of the quartic density), and their ratio. The crossover
``drillstring_core::modal::SPECTRAL_MIN_MODES`` is the first size (retained modes) from which
the spectral evaluation is not slower.

    python benchmarks/spectral_crossover.py [--modes 4 6 8 10 12 16 24 32 64 128 256]
"""

from __future__ import annotations

import argparse
import os
import platform

import numpy as np
from _evalcost import evaluation_cost

import drillstring as ds
from drillstring import _core


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--modes", type=int, nargs="+", default=[4, 6, 8, 10, 12, 16, 24, 32, 64, 128, 256])
    args = parser.parse_args()
    params = ds.preset("aluminum")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"core kernels {ds.simd_path()}, SPECTRAL_MIN_MODES = {_core.SPECTRAL_MIN_MODES}")
    head = f"{'n':>4} {'retained':>8} {'terms us':>9} {'spectral us':>11} {'terms/spectral':>14}"
    print(head)
    print("-" * len(head))
    for n in args.modes:
        coeff = ds.model.galerkin.project(params, modes=n, rigid_mode=True)
        q0, v0 = coeff.initial_state(params)
        omega_max = float(np.sqrt(np.abs(coeff.stiffness / coeff.mass)).max())
        dt = min(1e-4, 0.5 / omega_max)
        cost = {}
        for evaluation in ("terms", "spectral"):
            system = coeff.core_system(evaluation=evaluation)
            cost[evaluation], _ = evaluation_cost(system, q0, v0, dt)
        ratio = cost["terms"] / cost["spectral"] if cost["spectral"] > 0 else float("inf")
        print(f"{n:4d} {coeff.n_modes:8d} {cost['terms'] * 1e6:9.3f} {cost['spectral'] * 1e6:11.3f} {ratio:14.2f}",
              flush=True)


if __name__ == "__main__":
    main()
