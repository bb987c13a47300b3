"""The ``drillstring`` command line.

    drillstring simulate [CONFIG.toml] [--preset NAME] [overrides] [--out FILE.csv] [--plot FILE.png]
    drillstring table2 [--json]
    drillstring drill CONFIG.toml --out DIR [--set key=value ...] [--no-plots]
    drillstring drill-map CONFIG.toml --axis key=start:stop:count --axis key=v1,v2 --out DIR [--set ...]
    drillstring tune CONFIG.toml [--set key=value ...]
    drillstring rig-log LOG.csv --start-depth "3000 ft" --out DIR
    drillstring live CONFIG.toml [--port N] [--no-browser] [--speed X|max] [--set key=value ...]

One module per verb (``simulate.py`` for ``drillstring simulate``, ``torque_drag.py`` for
``drillstring torque-drag``, ...), each with ``add_parser(subparsers)`` (its arguments, help and
example) and ``run(args) -> int`` (the command, returning its exit status); :data:`VERBS` lists
them in the order of ``drillstring --help``. A new verb is a new module and a line in
:data:`VERBS`. What verbs share is in ``_common.py`` (argument types, the messages, the output
checks, the one-line errors) and ``_model.py`` (the paper model's inputs of ``simulate`` and
``pde``).

Errors are reported as one line on stderr with exit status 2 (no traceback); an error in a
TOML file names the file, the line and the key. A ``drillstring drill`` run that reached its end
with a headline metric that is not finite says so on its first line and in a warning, and writes
``"metrics_finite": false`` to metrics.json (not a result).
Ctrl-C stops a run within a fraction of a second with "drillstring: interrupted" and exit status
130; output files are written atomically, so an interrupted run leaves none half-written.

Every output destination is checked before any work is done (``_common.check_outputs``,
:func:`drillstring.io.output.check_destination`); a command never writes over its own input file;
``-`` writes a file output to standard output (the messages then go to stderr); a closed or
failing standard output is an error (exit status 2), never silently lost output.
"""

from __future__ import annotations

import argparse
import importlib
from collections.abc import Sequence
from typing import Optional

from .._core import __version__
from ._common import Parser, run_command

__all__ = ["VERBS", "build_parser", "main"]

#: The verb modules of ``drillstring``, in the order of ``drillstring --help``.
VERBS = (
    "simulate",
    "pde",
    "convergence",
    "table2",
    "paper",
    "sweep",
    "drill",
    "torque_drag",
    "drill_map",
    "lumped",
    "tune",
    "fit",
    "rig_log",
    "live",
)


def build_parser() -> argparse.ArgumentParser:
    """The parser of ``drillstring``: each verb of :data:`VERBS` adds its subcommand."""
    parser = Parser(
        prog="drillstring",
        description="Nonlinear torsional dynamics of rotating drill strings.",
    )
    parser.add_argument("--version", action="version", version=f"drillstring {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in VERBS:
        importlib.import_module(f"{__name__}.{name}").add_parser(sub)
    return parser


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``drillstring`` command; returns the exit status."""
    args = build_parser().parse_args(argv)
    return run_command(args)

