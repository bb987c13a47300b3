"""``drillstring sweep``: the Galerkin model over a parameter grid (parallel, resumable, on Dask)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

from .. import _core
from ..errors import ValidationError
from ..io.output import check_destination
from ..io.toml import load_toml
from ..limits import INT64_MAX
from ..model.parameters import Parameters
from ._common import dask_client, int_in, say

#: Keys of a sweep file's [solver] table and their types.
SWEEP_SOLVER_KEYS = {
    "modes": int,
    "rigid_mode": bool,
    "t_end": float,
    "method": str,
    "rtol": float,
    "atol": float,
    "samples": int,
    "dt": float,
    "max_steps": int,
    "z": float,
}


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring sweep`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "sweep",
        help="solve the Galerkin model over a parameter grid (parallel, resumable, optionally on Dask)",
        description="Solve the n-mode Galerkin model for every parameter set of a grid and write one row per "
        "run (results.parquet, results.csv) and a plot per metric. Re-running with the same --out resumes an "
        "interrupted sweep. The file has a [base] table (preset = ... and field overrides), a [solver] table "
        "(modes, rigid_mode, t_end, method, rtol, atol, samples, dt, max_steps, z) and a [grid] table of "
        "Parameters fields with lists or {linspace = [start, stop, count]} / {logspace = [start, stop, count]} "
        "(end values, not exponents).",
        epilog="example: drillstring sweep examples/sweep_length_speed.toml --out sweep-results",
    )
    p.add_argument("config", metavar="SWEEP.toml", help="sweep file with [base], [solver] and [grid] tables")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created; reused to resume)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the chunks on this Dask distributed scheduler, e.g. tcp://head-node:8786")
    p.add_argument("--threads", type=int_in(1, _core.MAX_THREADS),
                   help=f"threads per batch solve, 1..{_core.MAX_THREADS} (default: all cores)")
    p.add_argument("--chunk-size", type=int_in(1, INT64_MAX), help="runs per chunk (default 500)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: when stderr is a terminal)")
    p.add_argument("--no-plots", action="store_true", help="skip the PNG per metric")
    p.set_defaults(func=run)


def _sweep_config(path: str) -> tuple[Parameters, dict[str, Any], dict[str, Any]]:
    """[base] parameters, [solver] options and the [grid] table of a sweep file."""
    document = load_toml(path)
    unknown = sorted(set(document) - {"base", "solver", "grid"})
    if unknown:
        raise ValidationError(unknown[0], document[unknown[0]], "only the tables [base], [solver], [grid]", source=path)
    base = Parameters.from_dict(document.get("base", {}), source=path)
    solver: dict[str, Any] = {}
    table = document.get("solver", {})
    if not isinstance(table, dict):
        raise ValidationError("solver", table, "a TOML table [solver]", source=path)
    for key, value in table.items():
        kind = SWEEP_SOLVER_KEYS.get(key)
        if kind is None:
            allowed = "one of the keys " + ", ".join(SWEEP_SOLVER_KEYS)
            raise ValidationError(f"solver.{key}", value, allowed, source=path)
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            kind = int  # kept an int: the sweep's check converts it (and refuses 10**400)
        if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
            raise ValidationError(f"solver.{key}", value, f"a {kind.__name__}", source=path)
        solver[key] = value
    grid = document.get("grid", {})
    if not isinstance(grid, dict):
        raise ValidationError("grid", grid, "a TOML table [grid] of Parameters fields", source=path)
    return base, solver, grid


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring sweep``; returns its exit status."""
    import time

    from ..io.sweep_store import MANIFEST, RESULTS_CSV, RESULTS_PARQUET
    from ..studies.sweeps import sweep

    base, solver, grid = _sweep_config(args.config)
    check_destination(args.out, field="--out", directory=True, files=(MANIFEST, RESULTS_PARQUET, RESULTS_CSV))
    client = dask_client(args.scheduler)
    options: dict[str, Any] = {"threads": args.threads, "progress": args.progress}
    if args.chunk_size is not None:
        options["chunk_size"] = args.chunk_size
    start = time.perf_counter()
    try:
        try:
            table = sweep(base, grid, out_dir=args.out, client=client, **solver, **options)
        except ImportError as exc:  # pandas / pyarrow missing
            print(f"drillstring: error: {exc}", file=sys.stderr)
            return 2
        except ValidationError as exc:
            if exc.source is None and exc.field.startswith(("grid", "modes", "rigid_mode", "samples")):
                raise ValidationError(exc.field, exc.value, exc.allowed, source=args.config) from exc
            raise
        except KeyboardInterrupt:
            print(f"drillstring: the finished runs are kept in {args.out}; run the same command again to resume",
                  file=sys.stderr)
            raise
    finally:
        if client is not None:
            client.close()
    seconds = time.perf_counter() - start
    counts = table["status"].value_counts()
    ok = int(counts.get("success", 0))
    invalid = int(counts.get("invalid", 0))
    failed = len(table) - ok - invalid
    say(f"{len(table)} runs in {seconds:.1f} s ({len(table) / seconds:.0f} runs/s): "
         f"{ok} ok, {failed} failed, {invalid} invalid")
    say(f"wrote {os.path.join(args.out, 'results.parquet')} and {os.path.join(args.out, 'results.csv')}")
    if not args.no_plots:
        from ..plots import sweep_plots

        written = sweep_plots(table, os.path.join(args.out, "plots"))
        if written:
            say(f"wrote {len(written)} plots to {os.path.join(args.out, 'plots')}")
    return 0
