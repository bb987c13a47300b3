"""drillstring's drilling solver vs the numpy port of Aarsnes & Shor's scheme, same case, same run.

Well B of Aarsnes & Shor (2018), MD 2500 m, mu 0.3, fRat 0.65, oThres 1.5 rad/s, 40 rpm, 60 s,
1000 cells, off bottom. drillstring gets the string with the same continuum equations as their
scheme (tests/data/aarsnes_shor/reference.json, ``drillstring_equivalent_collar``: the collar with
their J (extra pi), A, contact radius, G = 67 GPa and density rho*Gc/Gp; damping rate
2*kt*dt_sub). Times are the best of ``--repeat`` runs; the ratio is numpy / drillstring. The
metrics over 30..60 s of both are printed next to the Octave reference.

It also times the published Python port of the same scheme (the repository's pull request 1,
commit b73329e: ``python/torsionalWaveStep.py`` and ``python/parameters_WellB.py``, vectorised
numpy, copied unchanged into ``benchmarks/aarsnes_shor_published/`` under its MIT licence; not part
of the package), driven by the loop of that pull request's ``main.ipynb`` without its plotting
(same case: 40 rpm, 1 s setpoint ramp, PI 38e3/100e3, 10 ms control interval, 1000 cells; its CFL
factor 0.99, as in the MATLAB code and the numpy port, gives 1 % more steps than drillstring's
Courant number 1; ``tests/test_benchmark_baselines.py`` checks that both ports reproduce the
Octave run of the MATLAB code). It takes about 10 s per simulated minute: ``--published DIR``
times another copy, ``--no-published`` leaves it out.

    python benchmarks/drill_vs_numpy.py [--repeat 3] [--duration 60] [--published DIR | --no-published]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import aarsnes_shor_numpy as asn

from drillstring import _core

REFERENCE = Path(__file__).resolve().parents[1] / "tests" / "data" / "aarsnes_shor" / "reference.json"
PUBLISHED = Path(__file__).resolve().parent / "aarsnes_shor_published"


def drill_config(duration: float, cells: int) -> dict:
    p = asn.parameters_well_b(cells=cells)
    _, dt_sub = asn.substeps(p)
    g_ratio = p["Gc"] / p["Gp"]
    collar_od = 2 * p["Cro"]
    collar_id = math.sqrt(collar_od ** 2 - 4 * p["Ac"] / math.pi)   # consistent with A; J and A are overridden
    return {
        "sections": [
            {"name": "drill pipe", "length": p["Lp"], "outer_diameter": 2 * p["Pro"], "inner_diameter": 2 * p["Pri"],
             "shear_modulus": p["Gp"], "density": p["rho"], "polar_moment": p["Jp"], "area": p["Ap"]},
            {"name": "collar (Aarsnes-Shor equivalent)", "length": p["Lc"], "outer_diameter": collar_od,
             "inner_diameter": collar_id, "shear_modulus": p["Gc"], "density": p["rho"] * g_ratio,
             "contact_diameter": collar_od, "polar_moment": p["Jc"], "area": p["Ac"]},
        ],
        "well": {"md": [0.0, 500.0, 1600.0, 4000.0], "inclination_deg": [0.0, 0.0, 60.0, 60.0],
                 "mud_density": 0.0, "gravity": 9.81},
        "friction": {"static": 0.3, "kinetic_ratio": 0.65, "stick_speed": 1.5, "model": "set_valued"},
        "damping_rate": 2 * p["kt"] * dt_sub,
        "top_drive": {"inertia": p["I_TD"], "torque_limit": 1e12, "rpm": 40.0, "ramp_time": 1.0, "steps": [],
                      "controller": {"type": "pi", "kp": 38e3, "ki": 100e3}, "control_interval": 0.01},
        "bit": {"on_bottom": False},
        "numerics": {"cells": cells, "duration": duration, "output_interval": 0.01, "field_interval": 0.0},
    }


def published_port(directory: str, duration: float) -> dict:
    """The published port's Well B run (their step function and parameters from ``directory``;
    the loop of their notebook): time series of motor torque and bit speed."""
    sys.path.insert(0, str(Path(directory).resolve()))
    try:
        from parameters_WellB import parameters_WellB  # type: ignore[import-not-found]
        from torsionalWaveStep import torsionalWaveStep  # type: ignore[import-not-found]
    finally:
        sys.path.pop(0)
    p = parameters_WellB(2500, 0.3, 0.65, 1.5)
    omega_stat = 40 / 60 * 2 * math.pi
    dt = 0.01
    t = np.arange(0, duration + dt, dt)
    cells = p.Pp + p.Pc
    x = np.zeros((2 * cells + 1, len(t)))
    torque = np.zeros(len(t))
    omega_sp, integral = 0.0, 0.0
    for k in range(len(t) - 1):
        omega_sp = omega_sp + (omega_stat - omega_sp) / (1 / dt)
        otd = x[2 * cells, k]
        torque[k] = (omega_sp - otd) * 38e3 + integral * 100e3
        integral += dt * (omega_sp - otd)
        x[:, k + 1] = torsionalWaveStep(p, x[:, k], dt, torque[k])
    torque[-1] = torque[-2]
    return {"t": t, "motor_torque": torque, "bit_speed": x[2 * cells - 1]}


def best_of(fn, repeat: int):
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--cells", type=int, default=1000)
    ap.add_argument("--published", metavar="DIR", default=str(PUBLISHED),
                    help="directory of the published Python port (default: the copy beside this script)")
    ap.add_argument("--no-published", action="store_true", help="do not time the published port")
    args = ap.parse_args()

    cfg = json.dumps(drill_config(args.duration, args.cells))
    t_ds, run = best_of(lambda: _core.drill_solve(cfg, None), args.repeat)
    t_np, res = best_of(lambda: asn.simulate(duration=args.duration, cells=args.cells), args.repeat)

    affinity = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores ({affinity} usable), "
          f"Python {platform.python_version()}, numpy {np.__version__}, "
          f"load average {os.getloadavg()[0]:.2f} (other processes share the cores)")
    print(f"case: Aarsnes & Shor Well B, 2500 m, 40 rpm, {args.duration:g} s, {args.cells} cells, "
          f"best of {args.repeat}")
    print(f"drillstring drill_solve: {t_ds:8.3f} s  ({t_ds / args.duration * 60:.3f} s per simulated minute), "
          f"status {run['status']}, stats {run.get('stats')}")
    print(f"numpy port:              {t_np:8.3f} s  ({t_np / args.duration * 60:.3f} s per simulated minute)")
    print(f"ratio numpy / drillstring: {t_np / t_ds:.1f}")
    published = None
    if not args.no_published:
        if args.cells != 1000:
            raise SystemExit("--published runs the published port's own 1000 cells: leave --cells at 1000 "
                             "(or --no-published)")
        files = ("torsionalWaveStep.py", "parameters_WellB.py")
        missing = [f for f in files if not (Path(args.published) / f).is_file()]
        if missing:
            raise SystemExit(f"--published {args.published}: not a directory with the published port "
                             f"(missing {', '.join(missing)}); see the script's docstring, or --no-published")
        t_pub, published = best_of(lambda: published_port(args.published, args.duration), 1)
        print(f"published port (1 run):  {t_pub:8.3f} s  ({t_pub / args.duration * 60:.3f} s per simulated minute)")
        print(f"ratio published port / drillstring: {t_pub / t_ds:.1f}; published port / numpy port: "
              f"{t_pub / t_np:.1f}")

    ds_res = {"t": np.asarray(run["t"]), "motor_torque": np.asarray(run["motor_torque"]),
              "bit_speed": np.asarray(run["bit_rpm"]) * 2 * math.pi / 60}
    rows = [("numpy port", asn.summary(res)), ("drillstring", asn.summary(ds_res))]
    if published is not None:
        rows.append(("published port", asn.summary(published)))
    if REFERENCE.exists() and args.duration == 60.0 and args.cells == 1000:
        ref = json.loads(REFERENCE.read_text())
        rows.append(("Octave reference", {"motor_torque_min": ref["motor_torque_min_Nm"],
                                          "motor_torque_max": ref["motor_torque_max_Nm"],
                                          "cycle_period_s": ref["cycle_period_s"],
                                          "bit_rpm_min": ref["bit_rpm_min"], "bit_rpm_max": ref["bit_rpm_max"],
                                          "bit_rpm_mean": ref["bit_rpm_mean"]}))
    print("last half:            torque min   torque max   period s   bit rpm min/max/mean")
    for name, s in rows:
        print(f"  {name:17s} {s['motor_torque_min']:11.1f}  {s['motor_torque_max']:11.1f}  {s['cycle_period_s']:8.3f}"
              f"   {s['bit_rpm_min']:.2f} / {s['bit_rpm_max']:.2f} / {s['bit_rpm_mean']:.2f}")


if __name__ == "__main__":
    main()
