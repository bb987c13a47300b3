"""``drillstring convergence``: the Galerkin truncation error against the converged PDE solution."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..errors import ValidationError
from ..io.output import check_destination
from ..model.parameters import PRESETS, load, preset
from ._common import add_progress, say, show_progress, wrote


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring convergence`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "convergence",
        help="Galerkin truncation error against the converged PDE solution",
        description="Refine the finite-difference PDE until two (Richardson-extrapolated) grids agree, then "
        "measure the 1-, 2-, 3-, ... mode Galerkin models with and without the rigid mode against it.",
        epilog="example: drillstring convergence --out convergence",
    )
    p.add_argument("config", nargs="?", help="TOML file with a [parameters] table (default: the aluminium preset)")
    p.add_argument("--preset", choices=(*PRESETS, "aluminium"), help="start from a preset (default: aluminum)")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--t-end", type=float, default=1.0, help="end time, s (default 1)")
    p.add_argument("--modes", type=_ints, default=None, metavar="1,2,3,...", help="Galerkin sizes to measure")
    p.add_argument("--max-nodes", type=int, default=1921, help="largest PDE grid (default 1921)")
    p.add_argument("--tol", type=float, default=1e-4, help="agreement of successive grids (default 1e-4)")
    add_progress(p)
    p.set_defaults(func=run)


def _ints(text: str) -> tuple[int, ...]:
    try:
        return tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected comma-separated integers, got {text!r}") from exc


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring convergence``; returns its exit status."""
    from ..studies import convergence

    if args.config and args.preset:
        raise ValidationError("--preset", args.preset, "either a config file or --preset, not both")
    params = load(args.config) if args.config else preset(args.preset or "aluminum")
    check_destination(args.out, field="--out", directory=True, files=convergence.FILES)
    kwargs: dict[str, Any] = {"t_end": args.t_end, "max_nodes": args.max_nodes, "tol": args.tol}
    if args.modes:
        kwargs["modes"] = args.modes
    result = convergence.study(params, progress=show_progress(args), **kwargs)
    for path in convergence.write(result, args.out):
        wrote(path, sys.stdout)
    say("\n".join(convergence.summary(result)))
    return 0
