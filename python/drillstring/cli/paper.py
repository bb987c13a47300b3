"""``drillstring paper``: every figure and table of the paper, and the report checking its claims."""

from __future__ import annotations

import argparse
from typing import Any

from ..io.output import check_destination
from ._common import add_progress, say, show_progress


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring paper`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
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
    add_progress(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring paper``; returns its exit status."""
    from .. import report as paper

    scale = args.t_end_scale if args.t_end_scale is not None else (
        paper.QUICK_T_END_SCALE if args.quick else 1.0)
    per_second = paper.QUICK_SAMPLES_PER_SECOND if args.quick else paper.SAMPLES_PER_SECOND
    command = f"drillstring paper --out {args.out}" + (" --quick" if args.quick else "") + (
        f" --t-end-scale {args.t_end_scale:g}" if args.t_end_scale is not None else "")
    check_destination(args.out, field="--out", directory=True, files=paper.output_names())
    report = paper.reproduce(args.out, t_end_scale=scale, samples_per_second=per_second, command=command,
                             progress=show_progress(args))
    verdicts = [f.verdict for f in report.figures]
    say(f"wrote {len(report.files)} files to {report.out_dir} in {report.total_seconds:.1f} s")
    say(f"figure claims: {verdicts.count('supported')} supported, "
         f"{verdicts.count('partly supported')} partly, {verdicts.count('contradicted')} contradicted")
    for number, finding in report.contradictions:
        say(f"  Fig. {number}: {finding}")
    say(f"report: {report.report_html}")
    return 0
