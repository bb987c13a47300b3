"""``drillstring tune``: the controller presets' settings for a string."""

from __future__ import annotations

import argparse
from typing import Any

from ._common import drilling_config


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring tune`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
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
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring tune``; returns its exit status."""
    from ..drilling import recommend_controllers

    config = drilling_config(args)
    for line in recommend_controllers(config).lines(args.units or config.units):
        print(line)
    return 0
