"""What the verbs share: argument types and arguments, the report's lines, the output checks, the
one-line errors and their exit status (:func:`run_command`)."""

from __future__ import annotations

import argparse
import errno
import math
import os
import sys
import warnings
from collections.abc import Mapping, Sequence
from typing import Any, NoReturn, Optional, TextIO

from ..errors import DrillstringError, DrillstringWarning, ValidationError
from ..io.output import STDOUT, OutputError, check_destination, command_inputs, is_stdout
from ..io.progress import on_terminal
from ..limits import INT64_MAX, check_run_count, memory_budget


def int_in(low: int, high: int) -> Any:
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


def finite_float(text: str) -> float:
    """An argparse type: a finite number, else a one-line usage error naming the option."""
    shown = text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"got {shown!r}, expected a finite number")
    return value


def say(text: str, file: Optional[TextIO] = None) -> None:
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


def check_outputs(outputs: Mapping[str, Any]) -> TextIO:
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


def wrote(path: Any, file: TextIO) -> None:
    """Reports a file written (the path the writer returns: with an appended extension)."""
    if path is not None and not is_stdout(path):
        say(f"wrote {os.fsdecode(path)}", file)


def add_progress(p: argparse.ArgumentParser) -> None:
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr (default: when stderr is a terminal)")


def show_progress(args: argparse.Namespace) -> bool:
    return on_terminal() if args.progress is None else bool(args.progress)


def figure_workers() -> int:
    """How many forked processes draw a command's figures beside the command's own: one fewer
    than the cores this process may run on (none on one core)."""
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(cores - 1, 0)


def plot_target(args: argparse.Namespace) -> Any:
    """The file ``--plot`` writes (an extension appended as matplotlib does), or ``None``."""
    if not args.plot:
        return None
    from ..io.figures import plot_path

    return plot_path(args.plot, "--plot")


def add_units(p: argparse.ArgumentParser) -> None:
    """``--units si|field``, the unit system of a command's console lines and figures."""
    p.add_argument("--units", choices=("si", "field"), default=None,
                   help="the unit system of the console lines and the figures (field: ft, klbf, kft-lbf, ...) and, "
                   "for drill, of report.md and of a converted copy of the metrics in metrics.json (output_units); "
                   "the data files keep their SI values (default: the configuration's units key, si without one)")


def add_drilling_config_arguments(p: argparse.ArgumentParser) -> None:
    """The arguments of a command on one drilling configuration: CONFIG.toml, --out, --set, --no-plots."""
    p.add_argument("config", metavar="CONFIG.toml", help="drilling configuration (examples/*.toml; one file "
                   "describes a well for drill and torque-drag)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created if needed)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help="change a field: dotted key with indices and a TOML value, e.g. top_drive.rpm=60, "
                   "sections[0].length=3000, bit.on_bottom=true, top_drive.controller.type=soft_torque "
                   "(repeatable)")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")


def drilling_config(args: argparse.Namespace, load: Any = None, extra: Sequence[str] = ()) -> Any:
    """The configuration of a command on one drilling configuration: ``args.config`` read (by
    ``load``, default :func:`~drillstring.drilling.load_drill_config`) and ``args.overrides``
    (with ``extra``) set. With ``--units field`` an error of a value gives its range in field
    units too (a field file's errors do already)."""
    from ..drilling import load_drill_config
    from ..drilling.units import field_error

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


def dask_client(address: Optional[str]) -> Any:
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


def map_axis(text: str, field: str = "--axis") -> tuple[str, list[Any]]:
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
    from ..drilling.config import parse_values

    return key, parse_values(raw, field, text)


class Parser(argparse.ArgumentParser):
    """Usage errors as one line (``prog: error: ...``) with exit status 2."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def flush_stdout() -> None:
    """Flushes standard output at the end of a command: output that cannot be written (a closed
    descriptor, a full disk, a reader that went away) is an error, not silently lost."""
    if sys.stdout is None:
        raise OutputError(errno.EBADF, "it is closed", "standard output")
    try:
        sys.stdout.flush()
    except OSError as exc:
        raise OutputError(exc.errno or errno.EIO, exc.strerror or str(exc), "standard output") from exc


def drop_failed_stdout() -> None:
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


def show_warning(message: Any, category: Any, *_: Any, **__: Any) -> None:
    """A warning as one line on stderr (``drillstring: warning: ...``)."""
    print(f"drillstring: warning: {message}".replace("\n", " "), file=sys.stderr, flush=True)


def run_command(args: argparse.Namespace) -> int:
    """Runs the verb of parsed arguments (``args.func``) and returns the exit status: 0 or what
    the verb returns; an error as one line on stderr with 2 (no traceback), Ctrl-C with
    "drillstring: interrupted" and 130. Warnings of the package are one line each on stderr; a
    closed or failing standard output is an error."""
    try:
        with command_inputs(getattr(args, "config", None)), warnings.catch_warnings():
            warnings.simplefilter("always", DrillstringWarning)
            warnings.showwarning = show_warning
            if sys.stdout is None:  # started with descriptor 1 closed (`drillstring ... >&-`)
                raise OutputError(errno.EBADF, "it is closed", "standard output")
            memory_budget()  # every command: a bad $DRILLSTRING_MEMORY_BUDGET is refused before any work
            status = int(args.func(args))
            flush_stdout()
            return status
    except (DrillstringError, ValueError, OSError, MemoryError, ArithmeticError, RecursionError) as exc:
        drop_failed_stdout()
        print(f"drillstring: error: {exc}".replace("\n", " "), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("drillstring: interrupted", file=sys.stderr)
        return 130
