"""``drillstring rig-log``: a rig's surface log read into rig states, depths, rate of penetration
and calibration events."""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from typing import Any

from ..errors import ValidationError
from ._common import say


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring rig-log`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "rig-log",
        help="a rig's surface log: rig states, bit and hole depth, ROP, stick-slip severity, calibration events",
        description="Read a rig's surface log (CSV with 'name [unit]' headers or a units row, Parquet, or LAS 2.0 "
        "with the 'las' extra; the null -999.25 read as missing), find its channels by name or common mnemonic, "
        "derive the bit and hole depth from the block height and the slips, the rig state per row (WITS0 code), "
        "the rate of penetration, the stick-slip severity per drilled interval and the calibration events "
        "(start-ups, pick-ups, slack-offs, rotating off bottom); write states.csv, events.csv, intervals.csv, "
        "start_up_NN.csv, summary.json, figures and report.md into DIR and print the next commands.",
        epilog="example: drillstring rig-log rig.csv --start-depth '3000 ft' --out rig-states",
    )
    p.add_argument("file", metavar="FILE", help="the log: .csv, .parquet or .las")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created if needed)")
    p.add_argument("--column", action="append", default=[], metavar="NAME=HEADER", dest="columns",
                   help="the log's header of a channel (t, block_height, hook_load, surface_rpm, surface_torque, "
                   "flow_out, standpipe_pressure, weight_on_bit, bit_depth, hole_depth), e.g. hook_load=HKLD "
                   "(repeatable)")
    p.add_argument("--unit", action="append", default=[], metavar="NAME=UNIT", dest="units",
                   help="the unit of a channel in the log, e.g. hook_load=klbf, 'surface_torque=kft lbf' (repeatable)")
    p.add_argument("--start-depth", default="0", metavar="DEPTH",
                   help="the bit depth at the first row, m or a quantity ('3000 ft') (default 0)")
    p.add_argument("--hole-depth", default=None, metavar="DEPTH",
                   help="the hole depth at the first row, m or a quantity (default: the start depth)")
    p.add_argument("--rule", action="append", default=[], metavar="NAME=VALUE", dest="rules",
                   help="a threshold of the state rules, SI or a quantity, e.g. block_weight=32klbf, "
                   "'slips_margin=4 klbf', moving_speed=0.05 (see docs/guide/rig-logs.md) (repeatable)")
    p.add_argument("--config", default="CONFIG.toml", metavar="CONFIG.toml", dest="next_config",
                   help="the well's configuration named in the next commands printed (default CONFIG.toml)")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")
    p.set_defaults(func=run)


def _pairs(texts: Sequence[str], field: str, form: str, names: Sequence[str]) -> dict[str, str]:
    out = {}
    for text in texts:
        key, sep, value = text.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or not key or not value:
            raise ValidationError(field, text, form)
        if key not in names:
            raise ValidationError(field, key, f"a name: one of {', '.join(names)}")
        out[key] = value
    return out


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring rig-log``; returns its exit status."""
    from dataclasses import fields

    from ..calibration.rig_log import CHANNELS, RigStateRules, parse_quantity, rig_log
    from ..calibration.rig_log_output import next_commands
    from ..drilling.metrics import ROP_MEAN
    from ..io.output import command_inputs

    columns = _pairs(args.columns, "--column", "NAME=HEADER (e.g. hook_load=HKLD)", list(CHANNELS))
    units = _pairs(args.units, "--unit", "NAME=UNIT (e.g. hook_load=klbf)", list(CHANNELS))
    rules = _pairs(args.rules, "--rule", "NAME=VALUE (e.g. block_weight=32klbf)",
                   [f.name for f in fields(RigStateRules)])
    start = parse_quantity(args.start_depth, "m", "--start-depth")
    hole = None if args.hole_depth is None else parse_quantity(args.hole_depth, "m", "--hole-depth")
    if hole is not None and hole < start:
        raise ValidationError("--hole-depth", args.hole_depth, f"at least the start depth ({start:g} m)")
    rule_values = RigStateRules.from_pairs(rules, "--rule")
    with command_inputs(args.file):
        result = rig_log(args.file, columns=columns, units=units, start_depth=start, start_hole_depth=hole,
                         rules=rule_values)
        written = result.write(args.out, plots=not args.no_plots, field="--out")
    s = result.summary
    say(f"rig-log: {s['rows']} rows, {s['duration_s'] / 3600:.3g} h, read and analysed in {result.seconds:.2g} s; "
        f"{len(s['gaps'])} gaps ({s['gap_count']['time_jump']} time jumps, {s['gap_count']['missing_values']} runs "
        f"of missing values), {s['rows_repeated_time']} repeated time stamps kept, "
        f"{s['rows_dropped_time_backwards']} rows going back in time dropped")
    states = ", ".join(f"{name.replace('_', ' ')} {seconds / 3600:.2f} h"
                       for name, seconds in s["time_per_state_s"].items() if seconds > 0)
    say(f"states: {states}")
    d = s["depth_range_m"]
    rop = s[ROP_MEAN]
    say(f"hole depth {d['hole_start']:.1f} m -> {d['hole_end']:.1f} m ({d['drilled']:.1f} m in "
        f"{s['drilled_intervals']} intervals" + (f", mean ROP {rop:.3g} m/h" if rop is not None else "") + ")")
    say("events: " + ", ".join(f"{n} {kind.replace('_', ' ')}" for kind, n in s["events"].items()))
    say(f"wrote {len(written)} files to {args.out} (report: {os.path.join(args.out, 'report.md')})")
    commands = next_commands(os.fspath(args.out), result, args.next_config)
    if commands:
        say(f"next (with the well's string and survey in {args.next_config}):")
        for command in commands:
            say(f"  {command}")
    return 0
