"""Coverage of the fit's intervals on data drillstring did not make.

The data: Well B of Aarsnes & Shor (their published code's case, bit off bottom, PI control to
40 rpm), a start-up of 45 s at 100 Hz with the true friction ``static = 0.36``,
``kinetic_ratio = 0.72``, computed by

* ``numpy``: the numpy port of their scheme (``aarsnes_shor_numpy.py``) on ``--cells`` cells
  (default 700: another grid than the model's 1000), with ``--draws`` seeded noise draws
  (500 N m on the motor torque, 0.3 rpm on the surface speed);
* ``numpy-fine``: the same port on 1500 cells (one draw);
* ``published``: their published Python port (``aarsnes_shor_published/``) on 4000 cells (one
  draw; its cell count is set after their parameters are built, the one line that fixes it).

The model is ``examples/aarsnes-shor-well-b.toml`` (their case in drillstring, 1000 cells, the
solver's own scheme, which evaluates the wall friction after the transport where theirs does it
before) with the damping rate their code applies on the data's grid: their viscous source is
multiplied by the sub-step twice, a rate ``2 kt dt_sub`` (0.0833 1/s on their 1000 cells, 0.125
on 700, 0.0588 on 1500, 0.0217 on 4000), a physical difference, not a numerical one.
Each data set is fitted for ``friction.static`` in 0.2..0.5 and
``friction.kinetic_ratio`` in 0.5..0.9 (``--misfit``, ``--top``), 2 threads; the table gives the
values, the 95 % intervals, whether they hold the truth, the share that do and the largest
relative error; where the fit's block bootstrap applied (``--interval``), also the share of the
Jacobian's intervals alone that hold it (``--log`` keeps every fit's pieces as JSON lines).

    python benchmarks/fit_coverage.py [--misfit features|least_squares] [--top controller|measured]
                                      [--draws 20] [--cells 700] [--cache DIR] [--threads 2]
                                      [--starts N] [--carry K] [--interval auto|jacobian|bootstrap]
                                      [--log FILE.jsonl] [--skip-fine] [--skip-published]

``--cache DIR`` keeps the noiseless runs of the other codes in DIR (the published port on 4000
cells takes minutes).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

import drillstring as ds
from drillstring.calibration.data import MeasuredData

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
TRUTH = {"friction.static": 0.36, "friction.kinetic_ratio": 0.72}
BOUNDS = {"friction.static": (0.2, 0.5), "friction.kinetic_ratio": (0.5, 0.9)}
DURATION = 45.0
TORQUE_NOISE = 500.0  # N m
SPEED_NOISE = 0.3  # rpm


def damping_rate(cells: int) -> float:
    """The damping rate of their code on ``cells`` cells: ``2 kt dt_sub``."""
    sys.path.insert(0, str(HERE))
    import aarsnes_shor_numpy as asn

    p = asn.parameters_well_b(cells=cells)
    return 2 * p["kt"] * asn.substeps(p)[1]


def numpy_port(cells: int) -> dict[str, np.ndarray]:
    """The numpy port's start-up at the truth on ``cells`` cells."""
    sys.path.insert(0, str(HERE))
    import aarsnes_shor_numpy as asn

    run = asn.simulate(duration=DURATION, cells=cells, mu=TRUTH["friction.static"],
                       f_rat=TRUTH["friction.kinetic_ratio"])
    return {"t": run["t"], "motor_torque": run["motor_torque"],
            "surface_rpm": run["top_drive_speed"] * 60 / (2 * math.pi)}


def published_port(cells: int) -> dict[str, np.ndarray]:
    """Their published Python port's start-up at the truth on ``cells`` cells: their parameters
    with the grid quantities of ``parameters_WellB.py`` recomputed for ``Pt = cells``, their step,
    the loop of their notebook."""
    from scipy.interpolate import interp1d

    sys.path.insert(0, str(HERE / "aarsnes_shor_published"))
    from parameters_WellB import parameters_WellB  # type: ignore[import-not-found]
    from torsionalWaveStep import torsionalWaveStep  # type: ignore[import-not-found]

    p = parameters_WellB(2500, TRUTH["friction.static"], TRUTH["friction.kinetic_ratio"], 1.5)
    p.Pp = round(cells * p.Lp / (p.Lp + p.Lc))  # their lines with Pt = cells
    p.Pc = cells - p.Pp
    p.xp = np.linspace(0, p.Lp, p.Pp)
    p.xc = p.Lp + np.linspace(0, p.Lc, p.Pc)
    md_prof, inc_prof = np.array([0, 500, 1600, 4000]), np.array([0, 0, 60, 60])
    p.PthetaVec = interp1d(md_prof, inc_prof)(p.xp) * math.pi / 180
    p.CthetaVec = interp1d(md_prof, inc_prof)(p.xc) * math.pi / 180
    g = 9.81
    p.P_thresProfile = g * np.sin(p.PthetaVec) * p.rho * p.Ap * p.Pro * p.f_thres
    p.C_thresProfile = g * np.sin(p.CthetaVec) * p.rho * p.Ac * p.Cro * p.f_thres
    omega_stat, dt = 40 / 60 * 2 * math.pi, 0.01
    t = np.arange(0, DURATION + dt / 2, dt)
    n = p.Pp + p.Pc
    x = np.zeros(2 * n + 1)
    torque, speed = np.zeros(t.size), np.zeros(t.size)
    omega_sp, integral = 0.0, 0.0
    for k in range(t.size):
        omega_sp = omega_sp + (omega_stat - omega_sp) / (1 / dt)
        otd = x[2 * n]
        speed[k] = otd
        torque[k] = (omega_sp - otd) * 38e3 + integral * 100e3
        integral += dt * (omega_sp - otd)
        x = torsionalWaveStep(p, x, dt, torque[k])
    return {"t": t, "motor_torque": torque, "surface_rpm": speed * 60 / (2 * math.pi)}


def cached(name: str, make, cache: Path | None) -> dict[str, np.ndarray]:
    if cache is None:
        return make()
    path = cache / f"{name}.npz"
    if path.exists():
        with np.load(path) as f:
            return {k: f[k] for k in f.files}
    run = make()
    cache.mkdir(parents=True, exist_ok=True)
    np.savez(path, **run)
    return run


def noisy(run: dict[str, np.ndarray], seed: int) -> MeasuredData:
    rng = np.random.default_rng(seed)
    t = run["t"]
    return MeasuredData(t, {"motor_torque": run["motor_torque"] + rng.normal(0.0, TORQUE_NOISE, t.size),
                            "surface_rpm": run["surface_rpm"] + rng.normal(0.0, SPEED_NOISE, t.size)},
                        source=f"seed {seed}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--misfit", choices=("features", "least_squares"), default="features")
    parser.add_argument("--top", choices=("controller", "measured"), default="controller")
    parser.add_argument("--draws", type=int, default=20)
    parser.add_argument("--first-seed", type=int, default=0, help="the first noise draw's seed")
    parser.add_argument("--cells", type=int, default=700)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--cache", type=Path, default=None)
    parser.add_argument("--starts", type=int, default=None, help="fit's starts (default: the fit's)")
    parser.add_argument("--carry", type=int, default=None, help="fit's carry: starts past the first horizon")
    parser.add_argument("--skip-published", action="store_true", help="leave out the published port (4000 cells)")
    parser.add_argument("--interval", choices=("auto", "jacobian", "bootstrap"), default="auto",
                        help="fit's interval (default: the fit's)")
    parser.add_argument("--skip-fine", action="store_true", help="leave out the numpy port on 1500 cells")
    parser.add_argument("--log", type=Path, default=None,
                        help="append each fit's values and every method's intervals to this JSON-lines file")
    args = parser.parse_args()
    cfg = ds.load_drill_config(ROOT / "examples" / "aarsnes-shor-well-b.toml").with_overrides(
        {"numerics.duration": DURATION, "numerics.field_interval": 0.0})
    cases = [(f"numpy port, {args.cells} cells", f"numpy-{args.cells}", lambda: numpy_port(args.cells), seed,
              args.cells) for seed in range(args.first_seed, args.first_seed + args.draws)]
    if not args.skip_fine:
        cases.append(("numpy port, 1500 cells", "numpy-1500", lambda: numpy_port(1500), 100, 1500))
    if not args.skip_published:
        cases.append(("published port, 4000 cells", "published-4000", lambda: published_port(4000), 200, 4000))
    print(f"misfit {args.misfit}, top {args.top}; truth {TRUTH}")
    print("| data | seed | static | 95 % interval | holds | kinetic ratio | 95 % interval | holds | s | warnings |")
    print("|---|---:|---:|---|---|---:|---|---|---:|---|")
    held = {k: 0 for k in TRUTH}
    worst = {k: 0.0 for k in TRUTH}
    # where the bootstrap applied: the share of the Jacobian's intervals alone holding the truth
    jacobian = {k: [0, 0] for k in TRUTH}
    seconds = []
    for label, name, make, seed, cells in cases:
        run = cached(name, make, args.cache)
        start = time.perf_counter()
        model = cfg.with_overrides({"damping_rate": damping_rate(cells)})
        res = ds.fit(model, noisy(run, seed), BOUNDS, threads=args.threads, landscape=False, misfit=args.misfit,
                     top=args.top, starts=args.starts, carry=args.carry, interval=args.interval)
        seconds.append(time.perf_counter() - start)
        for key, true in TRUTH.items():
            found = res.intervals.get("parameters", {}).get(key)
            if found is not None:
                jacobian[key][0] += found["jacobian"][0] <= true <= found["jacobian"][1]
                jacobian[key][1] += 1
        if args.log is not None:
            with open(args.log, "a", encoding="utf-8") as f:
                f.write(json.dumps({"data": label, "seed": seed, "misfit": args.misfit, "top": args.top,
                                    "seconds": seconds[-1], "warnings": res.warnings, "evaluations": res.evaluations,
                                    "parameters": {k: p.to_dict() for k, p in res.parameters.items()},
                                    "intervals": res.intervals}) + "\n")
        row = []
        for key, true in TRUTH.items():
            p = res.parameters[key]
            inside = p.ci_low <= true <= p.ci_high
            held[key] += inside
            worst[key] = max(worst[key], abs(p.value / true - 1))
            row += [f"{p.value:.4f}", f"{p.ci_low:.4f}..{p.ci_high:.4f}", "yes" if inside else "**no**"]
        print(f"| {label} | {seed} | {' | '.join(row)} | {seconds[-1]:.0f} | {len(res.warnings)} |", flush=True)
    n = len(cases)
    for key in TRUTH:
        print(f"{key}: {held[key]} of {n} intervals hold the truth ({held[key] / n:.0%}); largest error "
              f"{worst[key]:.1%}")
    for key, (inside, of) in jacobian.items():
        if of:
            print(f"{key}: the Jacobian's intervals alone held the truth in {inside} of the {of} fits with the "
                  "bootstrap")
    print(f"fit time: median {np.median(seconds):.0f} s, largest {max(seconds):.0f} s ({args.threads} threads)")


if __name__ == "__main__":
    main()
