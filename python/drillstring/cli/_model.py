"""The paper model's inputs of ``drillstring simulate`` and ``drillstring pde``: the configuration
file's ``[parameters]`` and ``[solver]`` tables, a preset, the options that override them, the
section; and the summary line of a run."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any, TextIO

from ..errors import ValidationError
from ..io.extras import require
from ..io.toml import load_toml, toml_line, with_toml_line
from ..limits import as_float
from ..model.parameters import MODELS, PRESETS, Parameters, load, preset
from ..solvers.trajectory import TrajectoryResult, default_section
from ._common import say

#: Keys of a config file's [solver] table and their types.
SOLVER_KEYS = {
    "modes": int,
    "rigid_mode": bool,
    "t_end": float,
    "method": str,
    "rtol": float,
    "atol": float,
    "dt": float,
    "samples": int,
    "z": float,
}


def _floats(text: str) -> tuple[float, ...]:
    try:
        return tuple(float(x) for x in text.split(",") if x.strip())
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from exc


def solver_table(path: str) -> dict[str, Any]:
    table = load_toml(path).get("solver", {})
    if not isinstance(table, dict):
        raise ValidationError("solver", table, "a TOML table [solver]", source=path)
    out: dict[str, Any] = {}
    for key, value in table.items():
        if key not in SOLVER_KEYS:
            raise ValidationError(
                f"solver.{key}", value, "one of the keys " + ", ".join(SOLVER_KEYS), source=path,
                line=toml_line(path, f"solver.{key}"),
            )
        kind = SOLVER_KEYS[key]
        ok = isinstance(value, kind) and not (kind is not bool and isinstance(value, bool))
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            ok = True  # kept an int: the solver's check converts it (and refuses 10**400)
        if not ok:
            kinds = {int: "an integer", float: "a number", bool: "true or false", str: "a string"}
            raise ValidationError(
                f"solver.{key}", value, kinds[kind], source=path, line=toml_line(path, f"solver.{key}")
            )
        out[key] = value
    return out


def from_config(exc: ValidationError, args: argparse.Namespace) -> ValidationError:
    """A solver option that came from the config file and was refused by the solver: the error
    names the file and the line."""
    if args.config and exc.source is None and exc.field in getattr(args, "file_solver_keys", ()):
        return with_toml_line(exc, args.config, "solver")
    return exc


def add_model_arguments(p: argparse.ArgumentParser, methods: Sequence[str]) -> None:
    """Arguments shared by `simulate` and `pde`: the configuration, overrides and outputs."""
    p.add_argument("config", nargs="?", help="TOML file with [parameters] and optional [solver] tables")
    p.add_argument("--preset", choices=(*PRESETS, "aluminium"), help="start from a preset (default: aluminum)")
    p.add_argument("--length", type=float, help="string length l, m")
    p.add_argument("--omega", type=float, help="rotation speed Omega, rad/s")
    p.add_argument("--initial-velocities", type=_floats, metavar="C1,C2,...", help="initial modal velocities, rad/s")
    p.add_argument("--k5-variant", choices=("paper", "energy"), help="k5 as printed or re-derived")
    p.add_argument("--model", choices=MODELS,
                   help="equations of motion: 'paper' as printed (default) or 'consistent' (finite strain)")
    p.add_argument("--damping-rate", type=float, metavar="C",
                   help="viscous damping rate c, 1/s (default 0: undamped; linear modes decay as exp(-c t/2))")
    p.add_argument("--t-end", type=float, help="end time, s (default 1)")
    p.add_argument("--method", choices=methods, help="integrator (default dop853)")
    p.add_argument("--rtol", type=float, help="relative tolerance (default 1e-9)")
    p.add_argument("--atol", type=float, help="absolute tolerance (default 1e-12)")
    p.add_argument("--dt", type=float, help="step of the fixed-step methods, s")
    p.add_argument("--samples", type=int, help="number of uniform output times (default: 20 per period of the "
                   "fastest retained mode, at least 1001)")
    p.add_argument("--z", type=float, help="section z, m (default 2l/3)")
    p.add_argument("--out", help="write CSV with columns t,theta,theta_dot,... ('-': standard output); a name "
                   "ending in .nc: the whole run as netCDF-4 (the extra netcdf)")


def check_run_output(out: Any) -> None:
    """Before any work: a netCDF ``--out`` (``.nc``) needs the extra ``netcdf``."""
    if _netcdf(out):
        require("netcdf", "--out as netCDF (.nc)")


def write_run(result: TrajectoryResult, out: Any, z: float) -> Any:
    """Writes ``--out``: the whole run as netCDF-4 for a name ending in ``.nc``, else the CSV of
    section ``z``; returns the path written."""
    return result.save(out) if _netcdf(out) else result.to_csv(out, z)


def _netcdf(out: Any) -> bool:
    return out is not None and str(out).lower().endswith(".nc")


def model_inputs(args: argparse.Namespace, keys: Sequence[str]) -> tuple[Parameters, dict[str, Any], float]:
    """Parameters, solver options (file, then command line) and the section z of a run."""
    if args.config and args.preset:
        raise ValidationError("--preset", args.preset, "either a config file or --preset, not both")
    params: Parameters = load(args.config) if args.config else preset(args.preset or "aluminum")
    solver = solver_table(args.config) if args.config else {}
    overrides = {
        "length": args.length,
        "omega": args.omega,
        "initial_velocities": args.initial_velocities,
        "k5_variant": args.k5_variant,
        "model": args.model,
        "damping_rate": args.damping_rate,
    }
    params = params.replace(**{k: v for k, v in overrides.items() if v is not None})
    for key in keys:
        value = getattr(args, key)
        if value is not None:
            solver[key] = value
        elif key in solver:
            args.file_solver_keys = (*getattr(args, "file_solver_keys", ()), key)
    unknown = sorted(set(solver) - set(keys))
    if unknown:
        raise ValidationError(f"solver.{unknown[0]}", solver[unknown[0]], f"one of {', '.join(keys)} for this command")
    z = solver.pop("z", default_section(params.length))
    allowed = f"a section 0 <= z <= length = {params.length:g} m"
    try:
        z = as_float("z", z, allowed)
        if not 0.0 <= z <= params.length:
            raise ValidationError("z", z, allowed)
    except ValidationError as exc:
        raise from_config(exc, args) from exc
    return params, solver, z


def summary(result: Any, z: float, what: str, file: TextIO) -> None:
    theta = result.theta(z)
    say(
        f"{result.method}: {result.t.size} samples over 0 <= t <= {result.t[-1]:g} s, {what}\n"
        f"max |theta(z={z:.4g} m)| = {abs(theta).max():.6e} rad, "
        f"{'energy balance error' if result.dissipated is not None else 'energy drift'} "
        f"{result.energy_drift():.2e}, "
        f"{result.stats.nfev} rhs evaluations, {result.stats.naccept} steps "
        f"({result.stats.nreject} rejected)",
        file,
    )
