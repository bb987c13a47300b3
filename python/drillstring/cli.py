"""The ``drillstring`` command line.

    drillstring simulate [CONFIG.toml] [--preset NAME] [overrides] [--out FILE.csv] [--plot FILE.png]
    drillstring table2 [--json]
    drillstring drill CONFIG.toml --out DIR [--set key=value ...] [--no-plots]
    drillstring drill-map CONFIG.toml --axis key=start:stop:count --axis key=v1,v2 --out DIR [--set ...]
    drillstring tune CONFIG.toml [--set key=value ...]

Errors are reported as one line on stderr with exit status 2 (no traceback); an error in a
TOML file names the file, the line and the key. A ``drillstring drill`` run that reached its end
with a headline metric that is not finite says so on its first line and in a warning, and writes
``"metrics_finite": false`` to metrics.json (not a result).
Ctrl-C stops a run within a fraction of a second with "drillstring: interrupted" and exit status
130; output files are written atomically, so an interrupted run leaves none half-written.

Every output destination is checked before any work is done (:func:`_check_outputs`,
:func:`drillstring.io.output.check_destination`); a command never writes over its own input file;
``-`` writes a file output to standard output (the messages then go to stderr); a closed or
failing standard output is an error (exit status 2), never silently lost output.
"""

from __future__ import annotations

import argparse
import errno
import math
import os
import sys
import warnings
from collections.abc import Mapping, Sequence
from typing import Any, NoReturn, Optional, TextIO

from . import _core
from ._core import __version__
from .errors import DrillstringError, DrillstringWarning, ValidationError
from .io.output import STDOUT, OutputError, check_destination, command_inputs, is_stdout
from .io.progress import on_terminal
from .io.toml import load_toml, toml_key_line, with_toml_line
from .limits import INT64_MAX, as_float, check_run_count, memory_budget
from .model.parameters import MODELS, PRESETS, Parameters, load, preset
from .solvers.modal import METHODS, PDE_METHODS, simulate
from .solvers.trajectory import default_section
from .studies.table2 import format_table2, table2, table2_json

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


def _int_in(low: int, high: int) -> Any:
    """An argparse type: an integer ``low <= n <= high``, else a one-line usage error naming the
    option and the range (exit status 2) before any work."""
    top = "2**63 - 1" if high == INT64_MAX else str(high)

    def convert(text: str) -> int:
        shown = text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"
        try:
            value = int(text.strip(), 10) if len(text) <= 40 else None
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(f"got {shown!r}, expected an integer in {low}..{top}")
        return value

    return convert


def _finite_float(text: str) -> float:
    """An argparse type: a finite number, else a one-line usage error naming the option."""
    shown = text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"got {shown!r}, expected a finite number")
    return value


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
                f"solver.{key}", value, "one of the keys " + ", ".join(SOLVER_KEYS), source=path,
                line=toml_key_line(path, "solver", key),
            )
        kind = SOLVER_KEYS[key]
        ok = isinstance(value, kind) and not (kind is not bool and isinstance(value, bool))
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            ok = True  # kept an int: the solver's check converts it (and refuses 10**400)
        if not ok:
            kinds = {int: "an integer", float: "a number", bool: "true or false", str: "a string"}
            raise ValidationError(
                f"solver.{key}", value, kinds[kind], source=path, line=toml_key_line(path, "solver", key)
            )
        out[key] = value
    return out


def _from_config(exc: ValidationError, args: argparse.Namespace) -> ValidationError:
    """A solver option that came from the config file and was refused by the solver: the error
    names the file and the line."""
    if args.config and exc.source is None and exc.field in getattr(args, "file_solver_keys", ()):
        return with_toml_line(exc, args.config, "solver")
    return exc


def _add_model_arguments(p: argparse.ArgumentParser, methods: Sequence[str]) -> None:
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
    p.add_argument("--out", help="write CSV with columns t,theta,theta_dot,... ('-': standard output)")


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
        raise _from_config(exc, args) from exc
    return params, solver, z


def _say(text: str, file: Optional[TextIO] = None) -> None:
    """Prints a line of the command's report; a failing standard output raises
    :class:`~drillstring.io.output.OutputError` naming it (never silently lost output)."""
    stream = sys.stdout if file is None else file
    if stream is None:
        raise OutputError(errno.EBADF, "it is closed", "standard output")
    try:
        print(text, file=stream)
    except OSError as exc:
        if stream is sys.stdout:
            raise OutputError(exc.errno or errno.EIO, exc.strerror or str(exc), "standard output") from exc
        raise


def _check_outputs(outputs: Mapping[str, Any]) -> TextIO:
    """Checks the file outputs of a command (option -> path as it will be written, ``None`` when
    not asked for) before any work is done: each with :func:`check_destination`, and no two
    options naming the same destination. Returns the stream for the command's messages: stderr
    when an output goes to standard output (``-``), else stdout."""
    seen: dict[str, str] = {}
    for option, path in outputs.items():
        if path is None:
            continue
        check_destination(path, field=option)
        key = STDOUT if is_stdout(path) else os.path.realpath(path)
        if key in seen:
            raise ValidationError(option, path, f"a destination other than that of {seen[key]}")
        seen[key] = option
    return sys.stderr if STDOUT in seen else sys.stdout


def _wrote(path: Any, file: TextIO) -> None:
    """Reports a file written (the path the writer returns: with an appended extension)."""
    if path is not None and not is_stdout(path):
        _say(f"wrote {os.fsdecode(path)}", file)


def _summary(result: Any, z: float, what: str, file: TextIO) -> None:
    theta = result.theta(z)
    _say(
        f"{result.method}: {result.t.size} samples over 0 <= t <= {result.t[-1]:g} s, {what}\n"
        f"max |theta(z={z:.4g} m)| = {abs(theta).max():.6e} rad, "
        f"{'energy balance error' if result.dissipated is not None else 'energy drift'} "
        f"{result.energy_drift():.2e}, "
        f"{result.stats.nfev} rhs evaluations, {result.stats.naccept} steps "
        f"({result.stats.nreject} rejected)",
        file,
    )


def _add_progress(p: argparse.ArgumentParser) -> None:
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr (default: when stderr is a terminal)")


def _show_progress(args: argparse.Namespace) -> bool:
    return on_terminal() if args.progress is None else bool(args.progress)


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
    p.add_argument("--plot", help="write a time-history and phase-portrait PNG "
                   "(format from the extension; .png is appended to a name without one)")
    _add_progress(p)
    p.set_defaults(func=_cmd_simulate)


SIMULATE_KEYS = ("modes", "rigid_mode", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def _plot_target(args: argparse.Namespace) -> Any:
    """The file ``--plot`` writes (an extension appended as matplotlib does), or ``None``."""
    if not args.plot:
        return None
    from .io.figures import plot_path

    return plot_path(args.plot, "--plot")


def _cmd_simulate(args: argparse.Namespace) -> int:
    params, solver, z = _model_inputs(args, SIMULATE_KEYS)
    plot = _plot_target(args)
    info = _check_outputs({"--out": args.out, "--plot": plot})
    try:
        result = simulate(params, progress=_show_progress(args), **solver)
    except ValidationError as exc:
        raise _from_config(exc, args) from exc
    _summary(result, z, f"modes {', '.join(map(str, result.indices))}", info)
    if args.out:
        _wrote(result.to_csv(args.out, z), info)
    if plot:
        from .io.figures import save
        from .plots import time_history_and_phase

        _wrote(save(time_history_and_phase(result, z), plot), info)
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
    p.add_argument("--field", help="write theta(z, t) on the grid to a compressed .npz (t, z, theta); "
                   ".npz is appended to a name without it")
    p.add_argument("--save-field-every", type=int, help="keep every k-th output sample in --field (default 1)")
    p.add_argument("--plot", help="write a space-time map of theta(z, t) and theta(z_k, t) as PNG "
                   "(format from the extension; .png is appended to a name without one)")
    _add_progress(p)
    p.set_defaults(func=_cmd_pde)


PDE_KEYS = ("nodes", "t_end", "method", "rtol", "atol", "dt", "samples", "z")


def _cmd_pde(args: argparse.Namespace) -> int:
    from .solvers.pde import field_path, solve_pde

    params, solver, z = _model_inputs(args, PDE_KEYS)
    field = field_path(args.field) if args.field else None
    plot = _plot_target(args)
    info = _check_outputs({"--out": args.out, "--field": field, "--plot": plot})
    every = args.save_field_every if args.save_field_every is not None else (1 if args.field or args.plot else None)
    try:
        result = solve_pde(params, save_field_every=every, progress=_show_progress(args), **solver)
    except ValidationError as exc:
        raise _from_config(exc, args) from exc
    _summary(result, z, f"{result.nodes} nodes", info)
    if args.out:
        _wrote(result.to_csv(args.out, z), info)
    if field:
        _wrote(result.save_field(field), info)
    if plot:
        from .io.figures import save
        from .plots import space_time

        _wrote(save(space_time(result, z), plot), info)
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
    p.add_argument("--preset", choices=(*PRESETS, "aluminium"), help="start from a preset (default: aluminum)")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--t-end", type=float, default=1.0, help="end time, s (default 1)")
    p.add_argument("--modes", type=_ints, default=None, metavar="1,2,3,...", help="Galerkin sizes to measure")
    p.add_argument("--max-nodes", type=int, default=1921, help="largest PDE grid (default 1921)")
    p.add_argument("--tol", type=float, default=1e-4, help="agreement of successive grids (default 1e-4)")
    _add_progress(p)
    p.set_defaults(func=_cmd_convergence)


def _ints(text: str) -> tuple[int, ...]:
    try:
        return tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected comma-separated integers, got {text!r}") from exc


def _cmd_convergence(args: argparse.Namespace) -> int:
    from .studies import convergence

    if args.config and args.preset:
        raise ValidationError("--preset", args.preset, "either a config file or --preset, not both")
    params = load(args.config) if args.config else preset(args.preset or "aluminum")
    check_destination(args.out, field="--out", directory=True, files=convergence.FILES)
    kwargs: dict[str, Any] = {"t_end": args.t_end, "max_nodes": args.max_nodes, "tol": args.tol}
    if args.modes:
        kwargs["modes"] = args.modes
    result = convergence.study(params, progress=_show_progress(args), **kwargs)
    for path in convergence.write(result, args.out):
        _wrote(path, sys.stdout)
    _say("\n".join(convergence.summary(result)))
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
    _say(table2_json(rows) if args.json else format_table2(rows))
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
                   help="short test run: times x0.1 and 2000 samples per second (numbers are not the paper's)")
    p.add_argument("--t-end-scale", type=float, metavar="X",
                   help="multiply every time span by X (default 1, or 0.1 with --quick)")
    _add_progress(p)
    p.set_defaults(func=_cmd_paper)


def _cmd_paper(args: argparse.Namespace) -> int:
    from . import report as paper

    scale = args.t_end_scale if args.t_end_scale is not None else (
        paper.QUICK_T_END_SCALE if args.quick else 1.0)
    per_second = paper.QUICK_SAMPLES_PER_SECOND if args.quick else paper.SAMPLES_PER_SECOND
    command = f"drillstring paper --out {args.out}" + (" --quick" if args.quick else "") + (
        f" --t-end-scale {args.t_end_scale:g}" if args.t_end_scale is not None else "")
    check_destination(args.out, field="--out", directory=True, files=paper.output_names())
    report = paper.reproduce(args.out, t_end_scale=scale, samples_per_second=per_second, command=command,
                             progress=_show_progress(args))
    verdicts = [f.verdict for f in report.figures]
    _say(f"wrote {len(report.files)} files to {report.out_dir} in {report.total_seconds:.1f} s")
    _say(f"figure claims: {verdicts.count('supported')} supported, "
         f"{verdicts.count('partly supported')} partly, {verdicts.count('contradicted')} contradicted")
    for number, finding in report.contradictions:
        _say(f"  Fig. {number}: {finding}")
    _say(f"report: {report.report_html}")
    return 0


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


def _add_sweep(sub: Any) -> None:
    p = sub.add_parser(
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
    p.add_argument("--threads", type=_int_in(1, _core.MAX_THREADS),
                   help=f"threads per batch solve, 1..{_core.MAX_THREADS} (default: all cores)")
    p.add_argument("--chunk-size", type=_int_in(1, INT64_MAX), help="runs per chunk (default 500)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: when stderr is a terminal)")
    p.add_argument("--no-plots", action="store_true", help="skip the PNG per metric")
    p.set_defaults(func=_cmd_sweep)


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


def _dask_client(address: Optional[str]) -> Any:
    """A ``dask.distributed.Client`` of the scheduler at ``address`` (``--scheduler``), or None."""
    if not address:
        return None
    try:
        from distributed import Client
    except ImportError as exc:
        raise ValidationError(
            "--scheduler", address, "dask.distributed installed: pip install '.[dask]' in the drillstring checkout",
        ) from exc
    return Client(address)


def _cmd_sweep(args: argparse.Namespace) -> int:
    import time

    from .io.sweep_store import MANIFEST, RESULTS_CSV, RESULTS_PARQUET
    from .studies.sweeps import sweep

    base, solver, grid = _sweep_config(args.config)
    check_destination(args.out, field="--out", directory=True, files=(MANIFEST, RESULTS_PARQUET, RESULTS_CSV))
    client = _dask_client(args.scheduler)
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
    _say(f"{len(table)} runs in {seconds:.1f} s ({len(table) / seconds:.0f} runs/s): "
         f"{ok} ok, {failed} failed, {invalid} invalid")
    _say(f"wrote {os.path.join(args.out, 'results.parquet')} and {os.path.join(args.out, 'results.csv')}")
    if not args.no_plots:
        from .plots import sweep_plots

        written = sweep_plots(table, os.path.join(args.out, "plots"))
        if written:
            _say(f"wrote {len(written)} plots to {os.path.join(args.out, 'plots')}")
    return 0


def _add_drilling_config_arguments(p: argparse.ArgumentParser) -> None:
    """The arguments of a command on one drilling configuration: CONFIG.toml, --out, --set, --no-plots."""
    p.add_argument("config", metavar="CONFIG.toml", help="drilling configuration (examples/*.toml; one file "
                   "describes a well for drill and torque-drag)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created if needed)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help="change a field: dotted key with indices and a TOML value, e.g. top_drive.rpm=60, "
                   "sections[0].length=3000, bit.on_bottom=true, top_drive.controller.type=soft_torque "
                   "(repeatable)")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")


def _drilling_config(args: argparse.Namespace, load: Any = None, extra: Sequence[str] = ()) -> Any:
    """The configuration of a command on one drilling configuration: ``args.config`` read (by
    ``load``, default :func:`~drillstring.drilling.load_drill_config`) and ``args.overrides``
    (with ``extra``) set. With ``--units field`` an error of a value gives its range in field
    units too (a field file's errors do already)."""
    from .drilling import load_drill_config
    from .drilling.units import field_error

    try:
        config = (load or load_drill_config)(args.config)
        if args.overrides:
            config = config.with_overrides([*args.overrides, *extra])
    except ValidationError as exc:
        units = getattr(args, "units", None)  # fit's --unit (the data's columns) is a list: not a system
        error = field_error(exc, units if isinstance(units, str) else "si")
        if error is exc:
            raise
        raise error from None
    return config


def _add_drill(sub: Any) -> None:
    p = sub.add_parser(
        "drill",
        help="stick-slip of the drilling system: a string in a well, top drive, wall friction, bit",
        description="Solve the torsional waves of a drill string in a deviated well (sections from the top, "
        "Coulomb wall friction, a top drive with its speed controller, the bit off or on bottom) and write the "
        "time series (series.parquet, series.csv), the stick-slip metrics (metrics.json), the space-time fields "
        "(fields.npz), figures, the configuration solved (config.toml) and report.md into DIR.",
        epilog="example: drillstring drill examples/on-bottom-3000m.toml --out drill-run --set top_drive.rpm=120",
    )
    _add_drilling_config_arguments(p)
    p.add_argument("--check-grid", action="store_true",
                   help="also solve on twice the cells and report how much every metric moves (about four "
                   "times the work); metrics.json gets grid_check, a move beyond its tolerance a warning (a "
                   "coupled run's ROP, weight and torque on bit, hook load, MSE and regime too)")
    p.add_argument("--check-start", action="store_true",
                   help="a coupled run ([hoist]): also solve it from the other start, numerics.initial_state = rest "
                   "or steady (the bit law's steady drilling), and warn where the regimes or metrics disagree (more "
                   "than one attractor); metrics.json gets start_check")
    _add_units(p)
    _add_progress(p)
    p.set_defaults(func=_cmd_drill)


def _add_units(p: argparse.ArgumentParser) -> None:
    """``--units si|field``, the unit system of a command's console lines and figures."""
    p.add_argument("--units", choices=("si", "field"), default=None,
                   help="the unit system of the console lines and the figures (field: ft, klbf, kft-lbf, ...) and, "
                   "for drill, of report.md and of a converted copy of the metrics in metrics.json (output_units); "
                   "the data files keep their SI values (default: the configuration's units key, si without one)")


def _change(kind: str, change: Optional[float]) -> str:
    """A grid check's change as the console shows it."""
    if change is None:
        return "n/a"
    return f"{100 * change:+.2g} %" if kind == "rel" else f"{change:+.3g}"


def _cmd_drill(args: argparse.Namespace) -> int:
    import time

    from .drilling import drill
    from .drilling.output import _write_files, output_folder
    from .drilling.units import annotate, convert, shown

    config = _drilling_config(args)
    plots = not args.no_plots
    # the folder is checked, created and locked before solving: a second run into it is refused now
    with output_folder(args.out, plots=plots, field="--out") as folder:
        start = time.perf_counter()
        result = drill(config, progress=_show_progress(args), check_grid=args.check_grid,
                       check_start=args.check_start)
        result.name = os.path.splitext(os.path.basename(os.fsdecode(args.config)))[0]
        seconds = time.perf_counter() - start
        m = result.metrics
        system = args.units or config.units
        status = (result.status if result.metrics_finite
                  else f"{result.status}; no rotation: no torsional metrics"
                  if not result.rotating and result.coupled_metrics is not None
                  else f"{result.status}, but metrics not finite: not a result")

        def torque(x: float) -> str:  # kN m, or kft-lbf in field units
            return shown(x, "N*m", system, kilo=True)

        low = (convert(m.motor_torque_min_Nm, "N*m", system)[0] or 0.0) / 1e3
        _say(f"drill: {shown(config.length, 'm', system, digits=6)} string, {config.numerics.cells} cells, "
             f"{config.numerics.duration:g} s simulated in {seconds:.2g} s ({status})")
        _say(f"wall contact: {config.friction.contact} ("
             + ("soft-string normal force: buoyed weight and tension times curvature"
                if config.friction.contact == "soft_string" else "buoyed weight times sin(inclination)")
             + f"), break-off torque {torque(result.metrics.breakoff_torque_Nm)}")
        _say(f"window {m.window_start:g}-{m.window_end:g} s: SSI {m.ssi:.3g}, stuck fraction {m.stuck_fraction:.3g}, "
             f"period {m.period_s:.4g} s, bit {m.bit_rpm_min:.4g}..{m.bit_rpm_max:.4g} rpm "
             f"(mean {m.bit_rpm_mean:.4g}), motor torque {low:.4g}..{torque(m.motor_torque_max_Nm)}, "
             f"wall break-off {torque(m.breakoff_torque_Nm)}, implied cycle minimum {torque(m.min_cycle_torque_Nm)}")
        _say(f"stick-slip: {m.stick_slip_verdict} ({m.stick_slip_reason}); "
             f"{'settled' if m.settled else 'not settled'}")
        if result.coupled_metrics is not None:  # a coupled axial-torsional run ([hoist])
            c = result.coupled_metrics
            mse = f"{c['mse_mean_Pa'] / 1e6:.4g} MPa" if system == "si" else shown(c["mse_mean_Pa"], "Pa", system)
            wob = shown(c["wob_mean_N"], "N", system, kilo=system == "si")
            hook = shown(c["hook_load_mean_N"], "N", system, kilo=system == "si")
            if c["bounce_fraction"] >= 1.0:  # a pick-up or slack-off: the hook load is the number
                _say(f"off bottom: hook load {hook} (mean over the window); regime: {result.coupled_regime}")
            else:
                _say(f"on bottom: ROP {shown(c['rop_mean_m_per_h'], 'm/h', system)}, weight on bit {wob}, "
                     f"torque on bit {torque(c['tob_mean_Nm'])}, bit bounce {c['bounce_fraction']:.3g} of the window, "
                     f"MSE {mse}, hook load {hook}; regime: {result.coupled_regime}")
        if result.profile.bit_static_torque > 0:
            p = result.profile
            _say(f"static torque to break free {torque(p.static_torque)} (wall {torque(p.breakoff_torque)} "
                 f"+ bit {torque(p.bit_static_torque)})")
        if result.grid_check is not None:
            g = result.grid_check
            moves = ", ".join(f"{r.metric} {_change(r.kind, r.change)}" for r in g.rows if r.kind != "equal")
            _say(f"grid check, {g.cells} -> {g.refined_cells} cells: "
                 f"{'converged' if g.converged else 'NOT converged'} ({moves})")
        if result.start_check is not None:
            s = result.start_check
            moved = [r for r in s.rows if not r.within]
            _say("start check, rest -> steady: " + ("the same answer" if s.agree else "DISAGREE (" + ", ".join(
                f"{r.metric} {r.rest!r} -> {r.steady!r}" if r.change is None or r.kind == "equal"
                else f"{r.metric} {_change(r.kind, r.change)}" for r in moved) + ")"))
        for warning in result.warnings:
            _say(f"warning: {annotate(warning, system)}")
        written = _write_files(result, folder.directory, plots, system)
    _say(f"wrote {len(written)} files to {args.out} (report: {os.path.join(args.out, 'report.md')})")
    return 0


def _add_tune(sub: Any) -> None:
    p = sub.add_parser(
        "tune",
        help="the recommended top-drive controller settings of each preset for a string",
        description="Print the settings of each controller preset (stiff, soft_torque, z_torque) for the string of "
        "CONFIG.toml: one line per preset with the gains and their units, the rule and the numbers it was computed "
        "from (the top pipe's impedance Z, the string's first natural frequency f1, the top-drive inertia). Use one "
        "with top_drive.controller.preset = NAME (or --set top_drive.controller.preset=NAME).",
        epilog="example: drillstring tune examples/on-bottom-3000m.toml",
    )
    p.add_argument("config", metavar="CONFIG.toml", help="drilling configuration (examples/*.toml)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help="change a field first, e.g. sections[0].length=4000 (repeatable)")
    p.add_argument("--units", choices=("si", "field"), default=None,
                   help="field: each SI number followed by its field value (ft-lbf s/rad, ...) (default: the "
                   "configuration's units key, si without one)")
    p.set_defaults(func=_cmd_tune)


def _cmd_tune(args: argparse.Namespace) -> int:
    from .drilling import recommend_controllers

    config = _drilling_config(args)
    for line in recommend_controllers(config).lines(args.units or config.units):
        print(line)
    return 0


def _add_torque_drag(sub: Any) -> None:
    p = sub.add_parser(
        "torque-drag",
        help="static soft-string torque and drag: hook loads, surface torques, profiles, broomstick plot",
        description="Solve the static soft-string torque and drag (Johancsik et al. 1984) of the configuration's "
        "string in its well (minimum-curvature survey) for pick-up, slack-off, rotating off bottom and on bottom, "
        "and the hook loads over bit depth for the friction factors of torque_drag.friction_factors; write "
        "torque_drag.json, profiles.csv, broomstick.csv, survey.csv, config.toml and the figures into DIR.",
        epilog="example: drillstring torque-drag examples/s-well-3d.toml --out s-well-td",
    )
    _add_drilling_config_arguments(p)
    _add_units(p)
    p.set_defaults(func=_cmd_torque_drag)


def _cmd_torque_drag(args: argparse.Namespace) -> int:
    import time

    from .drilling.torque_drag import torque_drag, write_torque_drag
    from .drilling.units import axis_unit

    config = _drilling_config(args)
    start = time.perf_counter()
    result = torque_drag(config)
    seconds = time.perf_counter() - start
    s = result.summary
    units = args.units or config.units
    force, force_unit = axis_unit("N", units, kilo=True)  # kN or klbf
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    normal, normal_unit = axis_unit("N/m", units)
    depth, depth_unit = axis_unit("m", units)
    _say(f"torque-drag: {config.length * depth:.6g} {depth_unit} string, solved in {seconds:.2g} s (with the "
         "broomstick sweep)")
    _say(f"hook load: pick-up {s['hook_load_pickup_N'] * force:.1f} {force_unit}, slack-off "
         f"{s['hook_load_slackoff_N'] * force:.1f} {force_unit}, rotating {s['hook_load_rotating_N'] * force:.1f} "
         f"{force_unit}, rotating on bottom {s['hook_load_rotating_on_bottom_N'] * force:.1f} {force_unit} (with the "
         "block weight; effective tension)")
    _say(f"surface torque: off bottom {s['surface_torque_off_bottom_Nm'] * torque:.2f} {torque_unit}, on bottom "
         f"{s['surface_torque_on_bottom_Nm'] * torque:.2f} {torque_unit}; largest normal force "
         f"{s['max_normal_force_N_per_m'] * normal:.0f} {normal_unit} at {s['max_normal_force_md'] * depth:.0f} "
         f"{depth_unit} ({s['max_normal_force_operation']})")
    written = write_torque_drag(result, args.out, plots=not args.no_plots, field="--out", units=units)
    _say(f"wrote {len(written)} files to {args.out}")
    return 0


def _add_lumped(sub: Any) -> None:
    p = sub.add_parser(
        "lumped",
        help="the lumped two-inertia stick-slip model (Navarro-Lopez & Cortes 2007): equilibria and a run",
        description="Print the steady rotations of the lumped two-inertia model, their stability and the regime, "
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
    p.add_argument("--duration", type=_finite_float, default=200.0, metavar="S",
                   help="simulated time, s (default 200)")
    p.add_argument("--initial", type=_finite_float, nargs=3, default=(0.0, 0.0, 0.0), metavar=("WR", "PHI", "WB"),
                   help="initial top speed rad/s, twist rad, bit speed rad/s (default: at rest)")
    p.set_defaults(func=_cmd_lumped)


def _cmd_lumped(args: argparse.Namespace) -> int:
    from .drilling.lumped import lumped, lumped_equilibria

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
        _say(f"steady rotation {r.speed:.6g} rad/s: {'stable' if r.stable else 'unstable'} "
             f"(largest eigenvalue real part {growth:.4g} 1/s)")
    _say(f"regime: {eq.regime}; bit at rest an equilibrium: {'yes' if eq.stuck_possible else 'no'} "
         f"(static limit {eq.static_limit:.6g} N m)")
    res = lumped(params, duration=args.duration, initial=args.initial)
    m = res.metrics
    _say(f"run from ({', '.join(f'{x:g}' for x in args.initial)}), window {res.window[0]:g}-{res.window[1]:g} s: "
         f"SSI {m.ssi:.3g}, stuck fraction {m.stuck_fraction:.3g}, period {m.period_s:.4g} s, "
         f"bit {m.bit_rpm_min:.4g}..{m.bit_rpm_max:.4g} rpm (mean {m.bit_rpm_mean:.4g}), energy balance "
         f"{res.energy['balance_error']:.2g}")
    _say(f"stick-slip: {m.stick_slip_verdict} ({m.stick_slip_reason}); "
         f"{'settled' if m.settled else 'not settled'}")
    for warning in m.warnings:
        _say(f"warning: {warning}")
    if args.out is not None:
        import pandas as pd

        from .drilling.lumped import lumped_figure
        from .io.figures import save
        from .io.output import make_directory, write_text

        make_directory(args.out)
        series = pd.DataFrame({"t_s": res.t, "top_speed_rad_s": res.top_speed, "bit_speed_rad_s": res.bit_speed,
                               "spring_torque_Nm": res.spring_torque, "bit_torque_Nm": res.bit_torque})
        written = [write_text(os.path.join(args.out, "lumped.csv"), series.to_csv(index=False)),
                   save(lumped_figure(res), os.path.join(args.out, "lumped.png"))]
        _say(f"wrote {', '.join(str(w) for w in written)}")
    return 0


#: What ``drillstring lumped --out DIR`` writes (a single run; with --sweep).
LUMPED_FILES = ("lumped.csv", "lumped.png")
LUMPED_SWEEP_FILES = ("lumped_sweep.csv", "lumped_sweep.png")


def _lumped_sweep(args: argparse.Namespace, params: dict[str, Any]) -> int:
    from .drilling.lumped import RPM_PER_RAD_S, lumped_defaults, lumped_sweep, lumped_sweep_figure

    name, values = _map_axis(args.sweep, field="--sweep")
    if name not in lumped_defaults():
        raise ValidationError("--sweep", args.sweep, f"NAME=... with NAME one of {', '.join(lumped_defaults())}")
    if args.out is not None:
        check_destination(args.out, field="--out", directory=True, files=LUMPED_SWEEP_FILES)
    frame = lumped_sweep(name, values, params, duration=args.duration, initial=args.initial)
    rpm = RPM_PER_RAD_S
    for _, row in frame.iterrows():
        speeds = ", ".join(f"{row[f'rotation_{k}'] * rpm:.4g} rpm {'stable' if row[f'stable_{k}'] else 'unstable'}"
                           for k in (1, 2) if row[f"stable_{k}"] is not None) or "none"
        _say(f"{name} = {row[name]:.6g}: steady rotations {speeds}; regime {row['regime']}; run {row['status']}: "
             f"SSI {row['ssi']:.3g}, stuck fraction {row['stuck_fraction']:.3g}, "
             f"bit {row['bit_rpm_min']:.4g}..{row['bit_rpm_max']:.4g} rpm")
    if args.out is not None:
        from .io.figures import save
        from .io.output import make_directory, write_text

        make_directory(args.out)
        written = [write_text(os.path.join(args.out, "lumped_sweep.csv"), frame.to_csv(index=False)),
                   save(lumped_sweep_figure(frame), os.path.join(args.out, "lumped_sweep.png"))]
        _say(f"wrote {', '.join(str(w) for w in written)}")
    return 0


def _add_drill_map(sub: Any) -> None:
    p = sub.add_parser(
        "drill-map",
        help="stick-slip map of the drilling system over configuration values (SSI heat map)",
        description="Solve the drilling system at every combination of the axis values (any dotted configuration "
        "key) in parallel and write one row of stick-slip metrics per run (map.parquet, map.csv), the base "
        "configuration (config.toml) and the figures: with two numeric axes the SSI heat map with the stick-slip "
        "boundary SSI = 1 (ssi_map.png) and, with a top_drive.controller.type axis, one panel per controller "
        "(controllers.png), and for a coupled configuration ([hoist]) the regimes (smooth drilling, stick-slip, bit "
        "bounce), ROP and MSE (regime_map.png); with one numeric axis SSI against it (ssi_lines.png). A run whose "
        "values the core "
        "refuses is a row with status 'invalid'. DIR also holds the map's chunked, verified store (manifest.json, "
        "chunks/): the same command again resumes an interrupted map, solving only what is missing.",
        epilog="example: drillstring drill-map examples/on-bottom-3000m.toml --axis top_drive.rpm=40:160:13 "
        "--axis bit.weight_on_bit=40e3:120e3:9 --out rpm-wob",
    )
    p.add_argument("config", metavar="CONFIG.toml", help="drilling-system configuration (examples/*.toml)")
    p.add_argument("--axis", action="append", default=[], required=True, metavar="KEY=VALUES", dest="axes",
                   help="an axis: KEY=start:stop:count (evenly spaced, numpy.linspace) or KEY=v1,v2,... (TOML "
                   "values; bare words are strings, e.g. top_drive.controller.type=pi,soft_torque) (repeatable)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help="change a field of the base configuration (as drill --set; repeatable)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created if needed)")
    p.add_argument("--threads", type=_int_in(1, _core.MAX_THREADS), default=None,
                   help=f"threads, 1..{_core.MAX_THREADS} (default: every core)")
    p.add_argument("--chunk-size", type=_int_in(1, INT64_MAX), default=None,
                   help="runs per stored chunk (default 100)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="solve the chunks on this Dask distributed scheduler, e.g. tcp://head-node:8786")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")
    _add_units(p)
    _add_progress(p)
    p.set_defaults(func=_cmd_drill_map)


#: The files ``drill-map --out DIR`` may write (``drillstring.drilling.maps.MAP_FILES`` and the manifest).
DRILL_MAP_FILES = ("map.parquet", "map.csv", "config.toml", "ssi_map.png", "regime_map.png", "controllers.png",
                   "ssi_lines.png", "manifest.json")


def _map_axis(text: str, field: str = "--axis") -> tuple[str, list[Any]]:
    """``KEY=start:stop:count`` or ``KEY=v1,v2,...`` as (key, values); errors name ``field``."""
    import numpy as np

    form = "KEY=start:stop:count or KEY=v1,v2,... (e.g. top_drive.rpm=40:160:13)"
    key, sep, raw = text.partition("=")
    key, raw = key.strip(), raw.strip()
    if not sep or not key or not raw:
        raise ValidationError(field, text, form)
    if ":" in raw:
        parts = raw.split(":")
        try:
            if len(parts) != 3:
                raise ValueError
            start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
        except ValueError:
            raise ValidationError(field, text, form + " with numbers and an integer count") from None
        if count < 1 or not (np.isfinite(start) and np.isfinite(stop)):
            raise ValidationError(field, text, form + " with finite numbers and a count >= 1")
        check_run_count(field, text, count)
        return key, [float(v) for v in np.linspace(start, stop, count)]
    from .drilling.config import parse_values

    return key, parse_values(raw, field, text)


def _cmd_drill_map(args: argparse.Namespace) -> int:
    import time

    from .drilling.maps import _map_config, check_axis, drill_map
    from .io.output import refuse_foreign_folder

    config = _drilling_config(args, _map_config, ["numerics.field_interval=0"])  # a map keeps no snapshots
    system = args.units or config.units
    axes: dict[str, list[Any]] = {}
    for text in args.axes:
        key, values = _map_axis(text)
        if key in axes:
            raise ValidationError("--axis", text, f"each key once ({key} is given twice)")
        axes[key] = check_axis(key, values, "--axis", config)
    check_destination(args.out, field="--out", directory=True, files=DRILL_MAP_FILES)
    refuse_foreign_folder(args.out, "drill-map", field="--out")
    client = _dask_client(args.scheduler)
    start = time.perf_counter()
    written: list[Any] = []

    def also_write(table: Any, directory: str) -> None:  # swapped in with map.parquet and map.csv
        from .io.output import write_text

        write_text(os.path.join(directory, "config.toml"), config.to_toml())
        written[:] = [os.path.join(args.out, name) for name in ("map.parquet", "map.csv", "config.toml")]
        if not args.no_plots:
            from .drilling.maps import map_figures
            from .io.figures import save

            for name, fig in map_figures(table, system).items():
                save(fig, os.path.join(directory, name))
                written.append(os.path.join(args.out, name))

    try:
        # the axes are SI now (check_axis read them in the configuration's units)
        frame = drill_map(config.with_units("si"), axes, threads=args.threads, progress=_show_progress(args),
                          out=args.out, chunk_size=args.chunk_size, client=client,
                          name=os.path.splitext(os.path.basename(os.fsdecode(args.config)))[0], also_write=also_write)
    except KeyboardInterrupt:
        print(f"drillstring: the finished runs are stored in {args.out}; the same command resumes the map",
              file=sys.stderr)
        raise
    finally:
        if client is not None:
            client.close()
    seconds = time.perf_counter() - start
    counts = frame["status"].value_counts()
    ok = frame[frame["status"] == "success"]
    redone = len(frame.attrs.get("resume", {}).get("recomputed", {}))
    _say(f"drill-map: {len(frame)} runs ({', '.join(f'{n} {s}' for s, n in counts.items())}) in {seconds:.3g} s "
         f"({len(frame) / seconds:.3g} runs/s){f', {redone} stored chunk(s) recomputed' if redone else ''}")
    if len(ok):
        verdicts = ok["stick_slip_verdict"].value_counts()
        _say(f"SSI {ok['ssi'].min():.3g}..{ok['ssi'].max():.3g}; stick-slip: yes in {int(verdicts.get('yes', 0))} "
             f"runs (the bit stops during part of the window), no in {int(verdicts.get('no', 0))}, undetermined in "
             f"{int(verdicts.get('undetermined', 0))}; settled in {int((ok['settled'] == 1).sum())} of {len(ok)}")
        if "regime" in ok.columns:  # a coupled map ([hoist])
            from .drilling.units import axis_unit

            regimes = ok["regime"].value_counts()
            rop, rop_unit = axis_unit("m/h", system)
            mse, mse_unit = (1e-6, "MPa") if system == "si" else axis_unit("Pa", system)
            _say("regimes: " + ", ".join(f"{r} in {n} runs" for r, n in regimes.items())
                 + f"; ROP {ok['rop_mean_m_per_h'].min() * rop:.3g}..{ok['rop_mean_m_per_h'].max() * rop:.3g} "
                 f"{rop_unit}, MSE {ok['mse_mean_Pa'].min() * mse:.3g}..{ok['mse_mean_Pa'].max() * mse:.3g} {mse_unit}")
    from .drilling.maps import controller_recommendation

    ranking = controller_recommendation(frame)
    if ranking:
        _say(f"controller recommendation: {ranking[0].controller} (" + "; ".join(s.line() for s in ranking)
             + f"); set it with --set top_drive.controller.type={ranking[0].controller}; the presets' settings: "
             f"drillstring tune {os.fsdecode(args.config)}")
    _say(f"wrote {len(written)} files to {args.out} (and the resumable store: manifest.json, chunks/)")
    return 0


def _add_fit(sub: Any) -> None:
    p = sub.add_parser(
        "fit",
        help="calibrate configuration values (friction, damping, ...) from measured surface data",
        description="Fit configuration values (dotted keys, --param KEY=LOW:HIGH) to a measured time series "
        "(CSV or Parquet with the column names of drill's series.csv: t, surface_rpm, motor_torque, bit_rpm, "
        "bit_torque; SI units unless a units row, a header suffix 'name [unit]' or --unit says otherwise): a global "
        "quasi-random stage solved in parallel, a least-squares refinement, intervals from the Jacobian or the "
        "profile likelihood, the misfit landscape over each pair; write the fitted config.toml, fit.json, "
        "fit_series.csv, figures and report.md into DIR and print the next command (the stick-slip map of the "
        "calibrated well and the controllers).",
        epilog="example: drillstring fit well.toml --data startup.csv --param friction.static=0.1:0.6 "
        "--param friction.kinetic_ratio=0.3:0.95 --out well-fit",
    )
    _add_drilling_config_arguments(p)
    p.add_argument("--data", action="append", required=True, metavar="FILE",
                   help="measured data, CSV or Parquet (repeat for several events fitted jointly)")
    p.add_argument("--param", action="append", required=True, metavar="KEY=LOW:HIGH", dest="params",
                   help="a configuration value to fit and its bounds, e.g. friction.static=0.1:0.6, in the "
                   "configuration's units (a field file's bit.weight_on_bit=10:40 is klbf) or with units "
                   "('bit.weight_on_bit=10 klbf:40 klbf') (repeatable)")
    p.add_argument("--per-event", action="append", default=[], metavar="KEY",
                   help="a --param key with one value per event (the others are shared) (repeatable)")
    p.add_argument("--target", action="append", default=[], metavar="NAME[=WEIGHT]", dest="targets",
                   help="a series compared, with its weight (default motor_torque) (repeatable)")
    p.add_argument("--window", action="append", default=[], metavar="START:END", dest="windows",
                   help="times compared, s from the start-up (default: the whole data) (repeatable)")
    p.add_argument("--column", action="append", default=[], metavar="NAME=COLUMN", dest="columns",
                   help="the data file's column of a model name, e.g. motor_torque=TQ (repeatable)")
    p.add_argument("--unit", action="append", default=[], metavar="NAME=UNIT", dest="units",
                   help="the unit of a column, e.g. 'motor_torque=kN m', surface_rpm=rad/s (repeatable)")
    p.add_argument("--start", type=_finite_float, default=0.0, metavar="S",
                   help="the data's time of the start-up (the model's t = 0), s (default 0)")
    p.add_argument("--samples", type=_int_in(1, 1 << 20), default=None,
                   help="points of the global stage (default 64 per parameter, at least 128)")
    p.add_argument("--threads", type=_int_in(1, _core.MAX_THREADS), default=None,
                   help=f"threads, 1..{_core.MAX_THREADS} (default: every core)")
    p.add_argument("--landscape-points", type=_int_in(2, 101), default=9,
                   help="grid points per parameter of the landscapes (default 9)")
    p.add_argument("--no-landscape", action="store_true", help="skip the misfit landscapes")
    p.add_argument("--seed", type=_int_in(0, INT64_MAX), default=0, help="seed of the global stage (default 0)")
    p.add_argument("--top", choices=("controller", "measured"), default="controller",
                   help="the model's top boundary: the configuration's controller and setpoint (default), or the "
                   "data's surface_rpm imposed as the top speed (the controller's gains need not be known)")
    p.set_defaults(func=_cmd_fit)


def _pairs(texts: Sequence[str], field: str, form: str) -> list[tuple[str, str]]:
    out = []
    for text in texts:
        key, sep, value = text.partition("=")
        if not sep or not key.strip() or not value.strip():
            raise ValidationError(field, text, form)
        out.append((key.strip(), value.strip()))
    return out


def _cmd_fit(args: argparse.Namespace) -> int:
    from .calibration.data import read_measured
    from .calibration.fit import fit
    from .calibration.output import next_commands, next_heading, write_files
    from .calibration.output import owned as fit_owned
    from .drilling.output import output_folder
    from .drilling.units import annotate, field_value

    config = _drilling_config(args)
    params: dict[str, tuple[Any, Any]] = {}
    for key, value in _pairs(args.params, "--param", "KEY=LOW:HIGH (e.g. friction.static=0.1:0.6)"):
        bounds: list[Any] = []
        for v in value.split(":"):  # numbers in the configuration's units, or quantities ("10 klbf")
            try:
                bounds.append(float(v))
            except ValueError:
                bounds.append(v.strip() if v.strip()[:1].isdigit() or v.strip()[:1] in "+-." else None)
        if len(bounds) != 2 or None in bounds:
            raise ValidationError("--param", f"{key}={value}", "KEY=LOW:HIGH with two numbers (in the configuration's "
                                  "units) or quantities (10 klbf:40 klbf)")
        params[key] = (bounds[0], bounds[1])
    targets: dict[str, float] = {}
    for text in args.targets or ["motor_torque"]:
        name, _, weight = text.partition("=")
        try:
            targets[name.strip()] = float(weight) if weight.strip() else 1.0
        except ValueError:
            raise ValidationError("--target", text, "NAME or NAME=WEIGHT with a number") from None
    windows = []
    for text in args.windows:
        try:
            a, b = (float(v) for v in text.split(":"))
        except ValueError:
            raise ValidationError("--window", text, "START:END in s (e.g. 0:30)") from None
        windows.append((a, b))
    columns = dict(_pairs(args.columns, "--column", "NAME=COLUMN (e.g. motor_torque=TQ)"))
    units = dict(_pairs(args.units, "--unit", "NAME=UNIT (e.g. 'motor_torque=kN m')"))
    data = [read_measured(path, columns=columns, units=units, start=args.start) for path in args.data]
    plots = not args.no_plots
    with output_folder(args.out, plots=plots, field="--out", command="fit", owns=fit_owned) as folder:
        result = fit(config, data, params, targets=targets, windows=windows or None, per_event=args.per_event,
                     samples=args.samples, threads=args.threads, seed=args.seed, landscape=not args.no_landscape,
                     landscape_points=args.landscape_points, progress=lambda msg: _say(f"fit: {msg}"),
                     top=args.top)
        system = config.units
        for key, p in result.parameters.items():
            low, high = field_value(key, p.ci_low, system), field_value(key, p.ci_high, system)
            field = (f"; {field_value(key, p.value, system)} ({low.split(' ', 1)[0]} .. {high})"
                     if low is not None and high is not None else "")
            _say(f"{key} = {p.value:.6g} ({result.level:.0%}: {p.ci_low:.6g} .. {p.ci_high:.6g}, {p.method}{field})"
                 + ("" if p.identifiable else " NOT identifiable"))
        _say(f"misfit {result.ssr:.5g} over {result.points} samples; {result.evaluations} runs in "
             f"{result.seconds:.3g} s")
        for warning in result.warnings:
            _say(f"warning: {annotate(warning, system)}")
        written = write_files(result, folder.directory, plots, shown=folder.path)
    _say(f"wrote {len(written)} files to {args.out} (report: {os.path.join(args.out, 'report.md')})")
    _say(next_heading(result))
    for command in next_commands(os.fspath(args.out), result):
        _say(f"  {command}")
    return 0


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line (``prog: error: ...``) with exit status 2."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
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
    _add_sweep(sub)
    _add_drill(sub)
    _add_torque_drag(sub)
    _add_drill_map(sub)
    _add_lumped(sub)
    _add_tune(sub)
    _add_fit(sub)
    return parser


def _flush_stdout() -> None:
    """Flushes standard output at the end of a command: output that cannot be written (a closed
    descriptor, a full disk, a reader that went away) is an error, not silently lost."""
    if sys.stdout is None:
        raise OutputError(errno.EBADF, "it is closed", "standard output")
    try:
        sys.stdout.flush()
    except OSError as exc:
        raise OutputError(exc.errno or errno.EIO, exc.strerror or str(exc), "standard output") from exc


def _drop_failed_stdout() -> None:
    """After standard output failed: close the process's own stdout (what is still buffered
    cannot be written), so that the interpreter's flush at exit does not fail a second time
    with a traceback. Other streams (a test's capture) are left alone."""
    stream = sys.stdout
    if stream is not sys.__stdout__ or stream is None:
        return
    try:
        stream.flush()
    except OSError:
        try:
            stream.close()
        except OSError:
            pass


def _show_warning(message: Any, category: Any, *_: Any, **__: Any) -> None:
    """A warning as one line on stderr (``drillstring: warning: ...``)."""
    print(f"drillstring: warning: {message}".replace("\n", " "), file=sys.stderr, flush=True)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``drillstring`` command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        with command_inputs(getattr(args, "config", None)), warnings.catch_warnings():
            warnings.simplefilter("always", DrillstringWarning)
            warnings.showwarning = _show_warning
            if sys.stdout is None:  # started with descriptor 1 closed (`drillstring ... >&-`)
                raise OutputError(errno.EBADF, "it is closed", "standard output")
            memory_budget()  # every command: a bad $DRILLSTRING_MEMORY_BUDGET is refused before any work
            status = int(args.func(args))
            _flush_stdout()
            return status
    except (DrillstringError, ValueError, OSError, MemoryError, ArithmeticError, RecursionError) as exc:
        _drop_failed_stdout()
        print(f"drillstring: error: {exc}".replace("\n", " "), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("drillstring: interrupted", file=sys.stderr)
        return 130




if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
