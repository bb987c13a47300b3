"""``drillstring table2``: the paper's Table 2."""

from __future__ import annotations

import argparse
from typing import Any

from ..studies.table2 import format_table2, table2, table2_json
from ._common import say


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring table2`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "table2",
        help="reproduce the paper's Table 2",
        description="RK4 at dt = 1e-4 vs central differences at four steps: max |theta_1| over 0 <= t <= 1.",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring table2``; returns its exit status."""
    rows = table2()
    say(table2_json(rows) if args.json else format_table2(rows))
    return 0
