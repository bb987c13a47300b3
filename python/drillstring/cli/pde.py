"""``drillstring pde``: the torsion PDE by the method of lines."""

from __future__ import annotations

import argparse
from typing import Any

from ..errors import ValidationError
from ..solvers.modal import PDE_METHODS
from ._common import add_progress, check_outputs, plot_target, show_progress, wrote
from ._model import add_model_arguments, check_run_output, from_config, model_inputs, summary, write_run


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring pde`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "pde",
        help="solve the PDE itself (method of lines)",
        description="Solve the nonlinear torsion PDE by an energy-conserving finite-difference method of lines.",
        epilog="example: drillstring pde --preset aluminum --nodes 240 --t-end 1 --out pde.csv --plot pde.png "
        "--field field.npz",
    )
    add_model_arguments(p, PDE_METHODS)
    p.add_argument("--nodes", type=int, help="grid points N >= 3, ends included (default 240)")
    p.add_argument("--field", help="write theta(z, t) on the grid to a compressed .npz (t, z, theta); "
                   ".npz is appended to a name without it")
    p.add_argument("--save-field-every", type=int, help="keep every k-th output sample in --field (default 1)")
    p.add_argument("--plot", help="write a space-time map of theta(z, t) and theta(z_k, t) as PNG "
                   "(format from the extension; .png is appended to a name without one)")
    add_progress(p)
    p.set_defaults(func=run)


PDE_KEYS = ("nodes", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring pde``; returns its exit status."""
    from ..solvers.pde import field_path, solve_pde

    params, solver, z = model_inputs(args, PDE_KEYS)
    field = field_path(args.field) if args.field else None
    plot = plot_target(args)
    info = check_outputs({"--out": args.out, "--field": field, "--plot": plot})
    check_run_output(args.out)
    every = args.save_field_every if args.save_field_every is not None else (1 if args.field or args.plot else None)
    try:
        result = solve_pde(params, save_field_every=every, progress=show_progress(args), **solver)
    except ValidationError as exc:
        raise from_config(exc, args) from exc
    summary(result, z, f"{result.nodes} nodes", info)
    if args.out:
        wrote(write_run(result, args.out, z), info)
    if field:
        wrote(result.save_field(field), info)
    if plot:
        from ..io.figures import save
        from ..plots import space_time

        wrote(save(space_time(result, z), plot), info)
    return 0
