"""The ``drillstring`` command line.

    drillstring simulate [CONFIG.toml] [--preset NAME] [overrides] [--out FILE.csv] [--plot FILE.png]
    drillstring table2 [--json]

Errors are reported as one line on stderr with exit status 2 (no traceback).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from typing import Any, Optional

from . import __version__
from .errors import DrillstringError, ValidationError
from .parameters import PRESETS, Parameters, load, load_toml, preset
from .simulate import METHODS, PDE_METHODS, simulate
from .table2 import format_table2, table2, table2_json

__all__ = ["main"]

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


def _solver_table(path: str) -> dict[str, Any]:
    table = load_toml(path).get("solver", {})
    if not isinstance(table, dict):
        raise ValidationError("solver", table, "a TOML table [solver]", source=path)
    out: dict[str, Any] = {}
    for key, value in table.items():
        if key not in SOLVER_KEYS:
            raise ValidationError(
                f"solver.{key}", value, "one of the keys " + ", ".join(SOLVER_KEYS), source=path
            )
        kind = SOLVER_KEYS[key]
        ok = isinstance(value, kind) and not (kind is not bool and isinstance(value, bool))
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            ok, value = True, float(value)
        if not ok:
            raise ValidationError(f"solver.{key}", value, f"a {kind.__name__}", source=path)
        out[key] = value
    return out


def _add_model_arguments(p: argparse.ArgumentParser, methods: Sequence[str]) -> None:
    """Arguments shared by `simulate` and `pde`: the configuration, overrides and outputs."""
    p.add_argument("config", nargs="?", help="TOML file with [parameters] and optional [solver] tables")
    p.add_argument("--preset", choices=PRESETS, help="start from a preset (default: aluminum)")
    p.add_argument("--length", type=float, help="string length l, m")
    p.add_argument("--omega", type=float, help="rotation speed Omega, rad/s")
    p.add_argument("--initial-velocities", type=_floats, metavar="C1,C2,...", help="initial modal velocities, rad/s")
    p.add_argument("--k5-variant", choices=("paper", "energy"), help="k5 as printed or re-derived")
    p.add_argument("--t-end", type=float, help="end time, s (default 1)")
    p.add_argument("--method", choices=methods, help="integrator (default dop853)")
    p.add_argument("--rtol", type=float, help="relative tolerance (default 1e-9)")
    p.add_argument("--atol", type=float, help="absolute tolerance (default 1e-12)")
    p.add_argument("--dt", type=float, help="step of the fixed-step methods, s")
    p.add_argument("--samples", type=int, help="number of uniform output times (default 1001)")
    p.add_argument("--z", type=float, help="section z, m (default 2l/3)")
    p.add_argument("--out", help="write CSV with columns t,theta,theta_dot,...")


def _model_inputs(args: argparse.Namespace, keys: Sequence[str]) -> tuple[Parameters, dict[str, Any], float]:
    """Parameters, solver options (file, then command line) and the section z of a run."""
    if args.config and args.preset:
        raise ValidationError("--preset", args.preset, "either a config file or --preset, not both")
    params: Parameters = load(args.config) if args.config else preset(args.preset or "aluminum")
    solver = _solver_table(args.config) if args.config else {}
    overrides = {
        "length": args.length,
        "omega": args.omega,
        "initial_velocities": args.initial_velocities,
        "k5_variant": args.k5_variant,
    }
    params = params.replace(**{k: v for k, v in overrides.items() if v is not None})
    for key in keys:
        value = getattr(args, key)
        if value is not None:
            solver[key] = value
    unknown = sorted(set(solver) - set(keys))
    if unknown:
        raise ValidationError(f"solver.{unknown[0]}", solver[unknown[0]], f"one of {', '.join(keys)} for this command")
    z = solver.pop("z", 2 * params.length / 3)
    return params, solver, z


def _summary(result: Any, z: float, what: str) -> None:
    theta = result.theta(z)
    print(
        f"{result.method}: {result.t.size} samples over 0 <= t <= {result.t[-1]:g} s, {what}\n"
        f"max |theta(z={z:.4g} m)| = {abs(theta).max():.6e} rad, "
        f"energy drift {result.energy_drift():.2e}, "
        f"{result.stats.nfev} rhs evaluations, {result.stats.naccept} steps "
        f"({result.stats.nreject} rejected)"
    )


def _add_simulate(sub: Any) -> None:
    p = sub.add_parser(
        "simulate",
        help="integrate the n-mode Galerkin model",
        description="Integrate the n-mode Galerkin model and write theta(z, t) at one section.",
        epilog="example: drillstring simulate --preset aluminum --modes 3 --t-end 1 --out run.csv --plot run.png",
    )
    _add_model_arguments(p, METHODS)
    p.add_argument("--modes", type=int, help="number of elastic modes n (default 3)")
    p.add_argument("--rigid-mode", action="store_true", default=None, help="include the rigid mode i = 0")
    p.add_argument("--plot", help="write a time-history and phase-portrait PNG")
    p.set_defaults(func=_cmd_simulate)


SIMULATE_KEYS = ("modes", "rigid_mode", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def _cmd_simulate(args: argparse.Namespace) -> int:
    params, solver, z = _model_inputs(args, SIMULATE_KEYS)
    result = simulate(params, **solver)
    _summary(result, z, f"modes {', '.join(map(str, result.indices))}")
    if args.out:
        result.to_csv(args.out, z)
        print(f"wrote {args.out}")
    if args.plot:
        from .plots import save, time_history_and_phase

        save(time_history_and_phase(result, z), args.plot)
        print(f"wrote {args.plot}")
    return 0


def _add_pde(sub: Any) -> None:
    p = sub.add_parser(
        "pde",
        help="solve the PDE itself (method of lines)",
        description="Solve the nonlinear torsion PDE by an energy-conserving finite-difference method of lines.",
        epilog="example: drillstring pde --preset aluminum --nodes 240 --t-end 1 --out pde.csv --plot pde.png "
        "--field field.npz",
    )
    _add_model_arguments(p, PDE_METHODS)
    p.add_argument("--nodes", type=int, help="grid points N >= 3, ends included (default 240)")
    p.add_argument("--field", help="write theta(z, t) on the grid to a compressed .npz (t, z, theta)")
    p.add_argument("--save-field-every", type=int, help="keep every k-th output sample in --field (default 1)")
    p.add_argument("--plot", help="write a space-time map of theta(z, t) and theta(z_k, t) as PNG")
    p.set_defaults(func=_cmd_pde)


PDE_KEYS = ("nodes", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def _cmd_pde(args: argparse.Namespace) -> int:
    from .pde import solve_pde

    params, solver, z = _model_inputs(args, PDE_KEYS)
    every = args.save_field_every if args.save_field_every is not None else (1 if args.field or args.plot else None)
    result = solve_pde(params, save_field_every=every, **solver)
    _summary(result, z, f"{result.nodes} nodes")
    if args.out:
        result.to_csv(args.out, z)
        print(f"wrote {args.out}")
    if args.field:
        result.save_field(args.field)
        print(f"wrote {args.field}")
    if args.plot:
        from .plots import save, space_time

        save(space_time(result, z), args.plot)
        print(f"wrote {args.plot}")
    return 0


def _add_convergence(sub: Any) -> None:
    p = sub.add_parser(
        "convergence",
        help="Galerkin truncation error against the converged PDE solution",
        description="Refine the finite-difference PDE until two (Richardson-extrapolated) grids agree, then "
        "measure the 1-, 2-, 3-, ... mode Galerkin models with and without the rigid mode against it.",
        epilog="example: drillstring convergence --out convergence",
    )
    p.add_argument("config", nargs="?", help="TOML file with a [parameters] table (default: the aluminium preset)")
    p.add_argument("--preset", choices=PRESETS, help="start from a preset (default: aluminum)")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--t-end", type=float, default=1.0, help="end time, s (default 1)")
    p.add_argument("--modes", type=_ints, default=None, metavar="1,2,3,...", help="Galerkin sizes to measure")
    p.add_argument("--max-nodes", type=int, default=1921, help="largest PDE grid (default 1921)")
    p.add_argument("--tol", type=float, default=1e-4, help="agreement of successive grids (default 1e-4)")
    p.set_defaults(func=_cmd_convergence)


def _ints(text: str) -> tuple[int, ...]:
    try:
        return tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected comma-separated integers, got {text!r}") from exc


def _cmd_convergence(args: argparse.Namespace) -> int:
    from . import convergence

    if args.config and args.preset:
        raise ValidationError("--preset", args.preset, "either a config file or --preset, not both")
    params = load(args.config) if args.config else preset(args.preset or "aluminum")
    kwargs: dict[str, Any] = {"t_end": args.t_end, "max_nodes": args.max_nodes, "tol": args.tol}
    if args.modes:
        kwargs["modes"] = args.modes
    result = convergence.study(params, progress=lambda line: print(line, file=sys.stderr, flush=True), **kwargs)
    for path in convergence.write(result, args.out):
        print(f"wrote {path}")
    print("\n".join(convergence.summary(result)))
    return 0


def _add_table2(sub: Any) -> None:
    p = sub.add_parser(
        "table2",
        help="reproduce the paper's Table 2",
        description="RK4 at dt = 1e-4 vs central differences at four steps: max |theta_1| over 0 <= t <= 1.",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.set_defaults(func=_cmd_table2)


def _cmd_table2(args: argparse.Namespace) -> int:
    rows = table2()
    print(table2_json(rows) if args.json else format_table2(rows))
    return 0


def _add_paper(sub: Any) -> None:
    p = sub.add_parser(
        "paper",
        help="reproduce every figure and table of the paper as a report",
        description="Regenerate Figs. 1-15 (PNG + CSV), Table 2, the stability table and a report "
        "(report.md, report.html) checking each claim of the paper against the numbers.",
        epilog="example: drillstring paper --out paper-results",
    )
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created if needed)")
    p.add_argument("--quick", action="store_true",
                   help="short test run: times x0.1 and 1000 samples per second (numbers are not the paper's)")
    p.add_argument("--t-end-scale", type=float, metavar="X",
                   help="multiply every time span by X (default 1, or 0.1 with --quick)")
    p.set_defaults(func=_cmd_paper)


def _cmd_paper(args: argparse.Namespace) -> int:
    from . import paper

    scale = args.t_end_scale if args.t_end_scale is not None else (
        paper.QUICK_T_END_SCALE if args.quick else 1.0)
    per_second = paper.QUICK_SAMPLES_PER_SECOND if args.quick else paper.SAMPLES_PER_SECOND
    command = f"drillstring paper --out {args.out}" + (" --quick" if args.quick else "") + (
        f" --t-end-scale {args.t_end_scale:g}" if args.t_end_scale is not None else "")
    report = paper.reproduce(args.out, t_end_scale=scale, samples_per_second=per_second, command=command)
    verdicts = [f.verdict for f in report.figures]
    print(f"wrote {len(report.files)} files to {report.out_dir} in {report.total_seconds:.1f} s")
    print(f"figure claims: {verdicts.count('supported')} supported, "
          f"{verdicts.count('partly supported')} partly, {verdicts.count('contradicted')} contradicted")
    for number, finding in report.contradictions:
        print(f"  Fig. {number}: {finding}")
    print(f"report: {report.report_html}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="drillstring",
        description="Nonlinear torsional dynamics of rotating drill strings.",
    )
    parser.add_argument("--version", action="version", version=f"drillstring {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    _add_simulate(sub)
    _add_pde(sub)
    _add_convergence(sub)
    _add_table2(sub)
    _add_paper(sub)
    return parser


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``drillstring`` command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args))
    except (DrillstringError, ValueError, OSError) as exc:
        print(f"drillstring: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("drillstring: interrupted", file=sys.stderr)
        return 130




if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
