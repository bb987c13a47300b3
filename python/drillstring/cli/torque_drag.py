"""``drillstring torque-drag``: the static soft-string torque and drag of a configuration."""

from __future__ import annotations

import argparse
from typing import Any

from ._common import add_drilling_config_arguments, add_units, drilling_config, say


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring torque-drag`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "torque-drag",
        help="static soft-string torque and drag: hook loads, surface torques, profiles, broomstick plot",
        description="Solve the static soft-string torque and drag (Johancsik et al. 1984) of the configuration's "
        "string in its well (minimum-curvature survey) for pick-up, slack-off, rotating off bottom and on bottom, "
        "and the hook loads over bit depth for the friction factors of torque_drag.friction_factors; write "
        "torque_drag.json, profiles.csv, broomstick.csv, survey.csv, config.toml and the figures into DIR.",
        epilog="example: drillstring torque-drag examples/s-well-3d.toml --out s-well-td",
    )
    add_drilling_config_arguments(p)
    add_units(p)
    p.add_argument("--measured", metavar="FILE", default=None,
                   help="measured points (CSV: depth, operation, hook_load and/or surface_torque, units in the "
                   "header as 'hook_load [klbf]'): drawn on the broomstick figures, each with the friction factor "
                   "that reproduces it in measured.csv")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring torque-drag``; returns its exit status."""
    import time

    from ..drilling.torque_drag import torque_drag, write_torque_drag
    from ..drilling.units import axis_unit

    config = drilling_config(args)
    points = None
    if args.measured is not None:
        from ..calibration.td_measured import read_td_measured

        points = read_td_measured(args.measured)
    start = time.perf_counter()
    result = torque_drag(config)
    seconds = time.perf_counter() - start
    s = result.summary
    units = args.units or config.units
    force, force_unit = axis_unit("N", units, kilo=True)  # kN or klbf
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    normal, normal_unit = axis_unit("N/m", units)
    depth, depth_unit = axis_unit("m", units)
    say(f"torque-drag: {config.length * depth:.6g} {depth_unit} string, solved in {seconds:.2g} s (with the "
         "broomstick sweep)")
    say(f"hook load: pick-up {s['hook_load_pickup_N'] * force:.1f} {force_unit}, slack-off "
         f"{s['hook_load_slackoff_N'] * force:.1f} {force_unit}, rotating {s['hook_load_rotating_N'] * force:.1f} "
         f"{force_unit}, rotating on bottom {s['hook_load_rotating_on_bottom_N'] * force:.1f} {force_unit} (with the "
         "block weight; effective tension)")
    say(f"sliding (lowering, not rotating, the weight on bit on the bit): hook load "
        f"{s['hook_load_sliding_N'] * force:.1f} {force_unit}")
    say(f"surface torque: off bottom {s['surface_torque_off_bottom_Nm'] * torque:.2f} {torque_unit}, on bottom "
         f"{s['surface_torque_on_bottom_Nm'] * torque:.2f} {torque_unit}; largest normal force "
         f"{s['max_normal_force_N_per_m'] * normal:.0f} {normal_unit} at {s['max_normal_force_md'] * depth:.0f} "
         f"{depth_unit} ({s['max_normal_force_operation']})")
    for line in result.report_lines(units):
        say(line)
    measured = None
    if points is not None:
        from ..calibration.td_measured import implied_friction

        measured = implied_friction(config, points)
        found = int(measured["friction_factor"].notna().sum())
        say(f"measured: {len(measured)} points, {found} with an implied friction factor, {points.skipped} rows "
            "skipped (no known operation)")
    written = write_torque_drag(result, args.out, plots=not args.no_plots, field="--out", units=units,
                                measured=measured)
    say(f"wrote {len(written)} files to {args.out}")
    return 0
