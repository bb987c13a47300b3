"""``drillstring lumped``: the lumped two-inertia stick-slip model, one run or a sweep of one parameter."""

from __future__ import annotations

import argparse
import math
import os
from typing import Any

from ..errors import ValidationError
from ..io.output import check_destination
from ..limits import as_float
from ._common import finite_float, map_axis, say


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring lumped`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "lumped",
        help="the lumped two-inertia stick-slip model (Navarro-Lopez & Cortes 2007): equilibria and a run",
        description="Print the steady rotations of the lumped two-inertia model, their stability and what they "
        "predict (equilibrium), "
        "then run it from the initial state and print the stick-slip metrics over the last half of the run. "
        "Parameters default to the published ones (tm = 6000 N m, wob = 50 kN). With --sweep, do both at each "
        "value of one parameter and print one line per value; with --out DIR also write the table "
        "(lumped_sweep.csv) and the figure of the steady speeds against the runs (lumped_sweep.png), or for a "
        "single run its time series (lumped.csv) and time histories (lumped.png).",
        epilog="examples: drillstring lumped --set wob=55e3 --duration 200; "
        "drillstring lumped --sweep wob=40e3:62e3:23 --out wob-sweep",
    )
    p.add_argument("--sweep", metavar="NAME=START:STOP:COUNT", default=None,
                   help="sweep one parameter over COUNT evenly spaced values (or NAME=v1,v2,...)")
    p.add_argument("--out", metavar="DIR", default=None, help="write the table or series and the figure to DIR")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", dest="overrides",
                   help="a parameter: jr, jb, kt, ct, cr, cb, rb, mu_cb, mu_sb, gamma_b, v_f, d_v, tm, wob "
                   "(SI units; repeatable)")
    p.add_argument("--duration", type=finite_float, default=200.0, metavar="S",
                   help="simulated time, s (default 200)")
    p.add_argument("--initial", type=finite_float, nargs=3, default=(0.0, 0.0, 0.0), metavar=("WR", "PHI", "WB"),
                   help="initial top speed rad/s, twist rad, bit speed rad/s (default: at rest)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring lumped``; returns its exit status."""
    from ..drilling.lumped import lumped, lumped_equilibria
    from ..drilling.metrics import OUTPUTS
    from ..drilling.units import metric_texts

    params: dict[str, Any] = {}
    for item in args.overrides:
        name, sep, value = item.partition("=")
        if not sep:
            raise ValidationError("--set", item, "NAME=VALUE, e.g. wob=55e3")
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        params[name.strip()] = as_float(name.strip(), number if math.isfinite(number) else value, "a finite number")
    if args.sweep is not None:
        return _lumped_sweep(args, params)
    if args.out is not None:
        check_destination(args.out, field="--out", directory=True, files=LUMPED_FILES)
    eq = lumped_equilibria(params)
    for r in eq.rotations:
        growth = max(e.real for e in r.eigenvalues)
        say(f"steady rotation {r.speed:.6g} rad/s: {'stable' if r.stable else 'unstable'} "
             f"(largest eigenvalue real part {growth:.4g} 1/s)")
    say(f"equilibrium: {eq.equilibrium}; bit at rest an equilibrium: {'yes' if eq.stuck_possible else 'no'} "
         f"(static limit {eq.static_limit:.6g} N m)")
    res = lumped(params, duration=args.duration, initial=args.initial)
    m = res.metrics
    shown = [n for n, o in OUTPUTS.items() if o.console and "lumped" in o.runs]  # the registry's, by label
    say(f"run from ({', '.join(f'{x:g}' for x in args.initial)}), window {res.window[0]:g}-{res.window[1]:g} s: "
         f"{', '.join(metric_texts(m.values, shown, 'si'))}, energy balance {res.energy['balance_error']:.2g}")
    say(f"stick-slip: {m.stick_slip_verdict} ({m.stick_slip_reason}); {'' if m.settled else 'not '}settled")
    for warning in m.warnings:
        say(f"warning: {warning}")
    if args.out is not None:
        import pandas as pd

        from ..drilling.lumped import lumped_figure
        from ..io.figures import save
        from ..io.output import make_directory, write_text

        make_directory(args.out)
        series = pd.DataFrame({"t_s": res.t, "top_speed_rad_s": res.top_speed, "bit_speed_rad_s": res.bit_speed,
                               "spring_torque_Nm": res.spring_torque, "bit_torque_Nm": res.bit_torque})
        written = [write_text(os.path.join(args.out, "lumped.csv"), series.to_csv(index=False)),
                   save(lumped_figure(res), os.path.join(args.out, "lumped.png"))]
        say(f"wrote {', '.join(str(w) for w in written)}")
    return 0


#: What ``drillstring lumped --out DIR`` writes (a single run; with --sweep).
LUMPED_FILES = ("lumped.csv", "lumped.png")


LUMPED_SWEEP_FILES = ("lumped_sweep.csv", "lumped_sweep.png")


def _lumped_sweep(args: argparse.Namespace, params: dict[str, Any]) -> int:
    from ..drilling.lumped import RPM_PER_RAD_S, lumped_defaults, lumped_sweep, lumped_sweep_figure
    from ..drilling.metrics import BIT_RPM_MAX, BIT_RPM_MIN, SSI, STUCK_FRACTION

    name, values = map_axis(args.sweep, field="--sweep")
    if name not in lumped_defaults():
        raise ValidationError("--sweep", args.sweep, f"NAME=... with NAME one of {', '.join(lumped_defaults())}")
    if args.out is not None:
        check_destination(args.out, field="--out", directory=True, files=LUMPED_SWEEP_FILES)
    frame = lumped_sweep(name, values, params, duration=args.duration, initial=args.initial)
    rpm = RPM_PER_RAD_S
    for _, row in frame.iterrows():
        speeds = ", ".join(f"{row[f'rotation_{k}'] * rpm:.4g} rpm {'stable' if row[f'stable_{k}'] else 'unstable'}"
                           for k in (1, 2) if row[f"stable_{k}"] is not None) or "none"
        say(f"{name} = {row[name]:.6g}: steady rotations {speeds}; equilibrium {row['equilibrium']}; "
             f"run {row['status']}: "
             f"SSI {row[SSI]:.3g}, stuck fraction {row[STUCK_FRACTION]:.3g}, "
             f"bit {row[BIT_RPM_MIN]:.4g}..{row[BIT_RPM_MAX]:.4g} rpm")
    if args.out is not None:
        from ..io.figures import save
        from ..io.output import make_directory, write_text

        make_directory(args.out)
        written = [write_text(os.path.join(args.out, "lumped_sweep.csv"), frame.to_csv(index=False)),
                   save(lumped_sweep_figure(frame), os.path.join(args.out, "lumped_sweep.png"))]
        say(f"wrote {', '.join(str(w) for w in written)}")
    return 0
