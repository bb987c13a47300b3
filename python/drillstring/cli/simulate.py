"""``drillstring simulate``: the n-mode Galerkin model, ``theta(z, t)`` at one section."""

from __future__ import annotations

import argparse
from typing import Any

from ..errors import ValidationError
from ..solvers.modal import METHODS, simulate
from ._common import add_progress, check_outputs, plot_target, show_progress, wrote
from ._model import add_model_arguments, check_run_output, from_config, model_inputs, summary, write_run


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring simulate`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "simulate",
        help="integrate the n-mode Galerkin model",
        description="Integrate the n-mode Galerkin model and write theta(z, t) at one section.",
        epilog="example: drillstring simulate --preset aluminum --modes 3 --t-end 1 --out run.csv --plot run.png",
    )
    add_model_arguments(p, METHODS)
    p.add_argument("--modes", type=int, help="number of elastic modes n (default 3)")
    p.add_argument("--rigid-mode", action="store_true", default=None, help="include the rigid mode i = 0")
    p.add_argument("--plot", help="write a time-history and phase-portrait PNG "
                   "(format from the extension; .png is appended to a name without one)")
    add_progress(p)
    p.set_defaults(func=run)


SIMULATE_KEYS = ("modes", "rigid_mode", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring simulate``; returns its exit status."""
    params, solver, z = model_inputs(args, SIMULATE_KEYS)
    plot = plot_target(args)
    info = check_outputs({"--out": args.out, "--plot": plot})
    check_run_output(args.out)
    try:
        result = simulate(params, progress=show_progress(args), **solver)
    except ValidationError as exc:
        raise from_config(exc, args) from exc
    summary(result, z, f"modes {', '.join(map(str, result.indices))}", info)
    if args.out:
        wrote(write_run(result, args.out, z), info)
    if plot:
        from ..io.figures import save
        from ..plots import time_history_and_phase

        wrote(save(time_history_and_phase(result, z), plot), info)
    return 0
