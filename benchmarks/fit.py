"""Calibration speed: a four-parameter fit of one 30 s start-up of the Aarsnes-Shor Well B
example (``examples/aarsnes-shor-well-b.toml``: 2500 m, 1000 cells, PI control to 40 rpm).

The data are the example's own surface torque at 20 Hz (``--rate``) with 500 N m of sensor
noise (seed 0) and its surface speed; the fit estimates ``friction.static``, ``friction.kinetic_ratio``,
``friction.stick_speed`` and ``top_drive.inertia`` (``--fourth damping``: ``damping_rate``) in
wide bounds by :func:`drillstring.fit`: a global Sobol stage of 128 points over the first 7.5 s,
least-squares refinement from the 2 best starts over 7.5 s, the better one carried on (early
stopping, ``carry=1``) over 15 and 30 s, intervals; ``--landscape`` adds the six pair
landscapes. Reports the wall time, the model runs, the CPU seconds the machine used meanwhile
(the machine may be shared) and its load average, the recovered values against the truth and
whether each interval holds it.

    python benchmarks/fit.py [--duration 30] [--cells 1000] [--threads 2] [--landscape] [--samples 128]
                             [--starts 2] [--horizon 5] [--carry 1] [--top controller|measured]
                             [--fourth inertia|damping]

``--skip S`` starts the windows at S s; ``--rate HZ`` samples the data at HZ; ``--carry 0``
carries every start past the first horizon (no early stopping; the settings before 2026-12-03
were ``--samples 256 --starts 4 --carry 0 --fourth damping``); ``--top measured`` drives the
model by the data's surface speed (the example's own, without noise: an encoder's) instead of
the PI controller.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from drill_map import machine_cpu  # benchmarks/drill_map.py: CPU seconds of the whole machine

import drillstring as ds
from drillstring.calibration.data import MeasuredData

ROOT = Path(__file__).resolve().parents[1]
#: ``--fourth inertia``: the top-drive inertia in place of the damping rate.
INERTIA = ("top_drive.inertia", 2900.0, (1500.0, 5000.0))
TRUTH = {"friction.static": 0.3, "friction.kinetic_ratio": 0.65, "friction.stick_speed": 1.5,
         "damping_rate": 0.08333333333333333}
BOUNDS = {"friction.static": (0.1, 0.6), "friction.kinetic_ratio": (0.3, 0.95), "friction.stick_speed": (0.5, 3.0),
          "damping_rate": (0.0, 0.3)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--cells", type=int, default=1000)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--landscape", action="store_true")
    parser.add_argument("--samples", type=int, default=128, help="points of the global stage")
    parser.add_argument("--starts", type=int, default=2)
    parser.add_argument("--horizon", type=float, default=5.0)
    parser.add_argument("--carry", type=int, default=1, help="starts carried past the first horizon (0: all)")
    parser.add_argument("--top", choices=("controller", "measured"), default="controller")
    parser.add_argument("--diff-step", type=float, default=1e-2, help="fit's diff_step (of the box)")
    parser.add_argument("--skip", type=float, default=0.0, help="the windows start here, s (default 0)")
    parser.add_argument("--rate", type=float, default=20.0, help="the data's sampling rate, Hz (100 / k)")
    parser.add_argument("--fourth", choices=("damping", "inertia"), default="inertia",
                        help="the fourth parameter: damping_rate or top_drive.inertia")
    args = parser.parse_args()
    cfg = ds.load_drill_config(ROOT / "examples" / "aarsnes-shor-well-b.toml").with_overrides(
        {"numerics.cells": args.cells, "numerics.duration": args.duration, "numerics.field_interval": 0.0})
    truth = ds.drill(cfg)
    rng = np.random.default_rng(0)
    k = max(int(round(1.0 / (args.rate * cfg.numerics.output_interval))), 1)
    data = MeasuredData(truth.t[::k], {"motor_torque": truth.motor_torque[::k]
                                       + rng.normal(0.0, 500.0, truth.t[::k].size),
                                       "surface_rpm": truth.surface_rpm[::k]})
    truths, bounds = dict(TRUTH), dict(BOUNDS)
    if args.fourth == "inertia":
        del truths["damping_rate"], bounds["damping_rate"]
        truths[INERTIA[0]], bounds[INERTIA[0]] = INERTIA[1], INERTIA[2]
    cpu, start = machine_cpu(), time.perf_counter()
    res = ds.fit(cfg, data, bounds, threads=args.threads, landscape=args.landscape, samples=args.samples,
                 starts=args.starts, horizon=args.horizon, carry=args.carry or None, top=args.top,
                 diff_step=args.diff_step, windows=[(args.skip, args.duration)] if args.skip > 0 else None)
    wall, used = time.perf_counter() - start, machine_cpu() - cpu
    print(f"fit of a {args.duration:g} s start-up, {args.cells} cells, 4 parameters ({args.fourth}), {args.threads} "
          f"threads, {args.samples} global points, {args.starts} starts: "
          f"{wall:.1f} s wall, {res.evaluations} runs ({res.evaluations / wall:.1f} runs/s), machine CPU "
          f"{used:.1f} s on {os.cpu_count()} cores (load average {os.getloadavg()[0]:.1f} at the end); landscape "
          f"{'on' if args.landscape else 'off'}, top {args.top}, carry {args.carry}")
    for key, true in truths.items():
        p = res.parameters[key]
        print(f"  {key:24s} {p.value:.5g}  ({p.ci_low:.5g} .. {p.ci_high:.5g}, {p.method})  truth {true:.5g}  "
              f"{'inside' if p.ci_low <= true <= p.ci_high else 'OUTSIDE'}")
    print(f"  misfit {res.ssr:.4g} over {res.points} samples, RMS {res.rms[0]['motor_torque']:.0f} N m; "
          f"condition {res.condition:.3g}")
    print(f"  global stage: {res.global_stage['points']} points, best misfit {res.global_stage['best_ssr']:.4g}; "
          f"refinement: misfit of each start {[round(v, 4) for v in res.refinement['ssr_of_starts']]} "
          f"({res.refinement['message']})")
    for warning in res.warnings:
        print(f"  warning: {warning}")


if __name__ == "__main__":
    main()
