"""``drillstring fit``: configuration values calibrated from measured data."""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from typing import Any

from .. import _core
from ..errors import ValidationError
from ..limits import INT64_MAX
from ._common import add_drilling_config_arguments, drilling_config, finite_float, int_in, say


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring fit`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
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
    add_drilling_config_arguments(p)
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
    p.add_argument("--start", type=finite_float, default=0.0, metavar="S",
                   help="the data's time of the start-up (the model's t = 0), s (default 0)")
    p.add_argument("--samples", type=int_in(1, 1 << 20), default=None,
                   help="points of the global stage (default 64 per parameter, at least 128)")
    p.add_argument("--threads", type=int_in(1, _core.MAX_THREADS), default=None,
                   help=f"threads, 1..{_core.MAX_THREADS} (default: every core)")
    p.add_argument("--landscape-points", type=int_in(2, 101), default=9,
                   help="grid points per parameter of the landscapes (default 9)")
    p.add_argument("--no-landscape", action="store_true", help="skip the misfit landscapes")
    p.add_argument("--seed", type=int_in(0, INT64_MAX), default=0, help="seed of the global stage (default 0)")
    p.add_argument("--top", choices=("controller", "measured"), default="controller",
                   help="the model's top boundary: the configuration's controller and setpoint (default), or the "
                   "data's surface_rpm imposed as the top speed (the controller's gains need not be known)")
    p.add_argument("--misfit", choices=("least_squares", "features"), default="least_squares",
                   help="what is minimised: the residuals sample by sample (default), or the cycle features (break-off "
                   "torque, each cycle's maximum and minimum, period, mean) with their uncertainties, which a period "
                   "differing slightly from the well's, a phase shift or a sensor's lag leave unchanged: for field "
                   "data and data of another model")
    p.add_argument("--offset", choices=("none", "constant", "linear"), default="none",
                   help="a sensor offset of each target series estimated with the values (profiled out at every "
                   "run): a constant, or a constant and a rate (a drift linear in time); reported in fit.json and "
                   "the console (default none)")
    p.add_argument("--interval", choices=("auto", "jacobian", "bootstrap"), default="auto",
                   help="the intervals of a sample-by-sample fit: the Jacobian's, joined with the block bootstrap's "
                   "over the stick-slip cycles and the discretisation error's where the residuals show a model error "
                   "(auto, default), never (jacobian) or always (bootstrap)")
    p.set_defaults(func=run)


def _pairs(texts: Sequence[str], field: str, form: str) -> list[tuple[str, str]]:
    out = []
    for text in texts:
        key, sep, value = text.partition("=")
        if not sep or not key.strip() or not value.strip():
            raise ValidationError(field, text, form)
        out.append((key.strip(), value.strip()))
    return out


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring fit``; returns its exit status."""
    from ..calibration.checks import SERIES_UNITS
    from ..calibration.data import read_measured
    from ..calibration.fit import fit
    from ..calibration.output import next_commands, next_heading, write_files
    from ..calibration.output import owned as fit_owned
    from ..drilling.output import output_folder
    from ..drilling.units import annotate, field_value

    config = drilling_config(args)
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
                     landscape_points=args.landscape_points, progress=lambda msg: say(f"fit: {msg}"),
                     top=args.top, misfit=args.misfit, offset=args.offset, interval=args.interval)
        system = config.units
        for key, p in result.parameters.items():
            low, high = field_value(key, p.ci_low, system), field_value(key, p.ci_high, system)
            field = (f"; {field_value(key, p.value, system)} ({low.split(' ', 1)[0]} .. {high})"
                     if low is not None and high is not None else "")
            say(f"{key} = {p.value:.6g} ({result.level:.0%}: {p.ci_low:.6g} .. {p.ci_high:.6g}, {p.method}{field})"
                 + ("" if p.identifiable else " NOT identifiable"))
        for e, found in enumerate(result.offsets):
            for series, o in found.items():
                unit = SERIES_UNITS.get(series, "")
                event = f" (event {e})" if len(result.offsets) > 1 else ""
                say(f"offset of {series}{event}: {o['constant']:.6g} {unit} at t = {o['t_ref']:.4g} s"
                    + (f", drifting {o['rate_per_s']:.4g} {unit}/s" if result.offset == "linear" else ""))
        say(f"misfit {result.ssr:.5g} over {result.points} samples; {result.evaluations} runs in "
             f"{result.seconds:.3g} s")
        for warning in result.warnings:
            say(f"warning: {annotate(warning, system)}")
        written = write_files(result, folder.directory, plots, shown=folder.path)
    say(f"wrote {len(written)} files to {args.out} (report: {os.path.join(args.out, 'report.md')})")
    say(next_heading(result))
    for command in next_commands(os.fspath(args.out), result):
        say(f"  {command}")
    return 0
