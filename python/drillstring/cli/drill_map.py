"""``drillstring drill-map``: the stick-slip map of a drilling configuration over its axes."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

from .. import _core
from ..errors import ValidationError
from ..io.output import check_destination
from ..limits import INT64_MAX
from ._common import add_progress, add_units, dask_client, drilling_config, int_in, map_axis, say, show_progress


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring drill-map`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
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
    p.add_argument("--threads", type=int_in(1, _core.MAX_THREADS), default=None,
                   help=f"threads, 1..{_core.MAX_THREADS} (default: every core)")
    p.add_argument("--chunk-size", type=int_in(1, INT64_MAX), default=None,
                   help="runs per stored chunk (default 100)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="solve the chunks on this Dask distributed scheduler, e.g. tcp://head-node:8786")
    p.add_argument("--no-plots", action="store_true", help="skip the figures")
    add_units(p)
    add_progress(p)
    p.set_defaults(func=run)


#: The files ``drill-map --out DIR`` may write (``drillstring.drilling.maps.MAP_FILES`` and the manifest).
DRILL_MAP_FILES = ("map.parquet", "map.csv", "config.toml", "ssi_map.png", "regime_map.png", "controllers.png",
                   "ssi_lines.png", "manifest.json")


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring drill-map``; returns its exit status."""
    import time

    from ..drilling.maps import _map_config, check_axis, drill_map
    from ..drilling.metrics import MSE_MEAN, OUTPUTS, REGIME, ROP_MEAN, SETTLED, SSI, STICK_SLIP_VERDICT
    from ..io.output import refuse_foreign_folder

    config = drilling_config(args, _map_config, ["numerics.field_interval=0"])  # a map keeps no snapshots
    system = args.units or config.units
    axes: dict[str, list[Any]] = {}
    for text in args.axes:
        key, values = map_axis(text)
        if key in axes:
            raise ValidationError("--axis", text, f"each key once ({key} is given twice)")
        axes[key] = check_axis(key, values, "--axis", config)
    check_destination(args.out, field="--out", directory=True, files=DRILL_MAP_FILES)
    refuse_foreign_folder(args.out, "drill-map", field="--out")
    client = dask_client(args.scheduler)
    start = time.perf_counter()
    written: list[Any] = []

    def also_write(table: Any, directory: str) -> None:  # swapped in with map.parquet and map.csv
        from ..io.output import write_text

        write_text(os.path.join(directory, "config.toml"), config.to_toml())
        written[:] = [os.path.join(args.out, name) for name in ("map.parquet", "map.csv", "config.toml")]
        if not args.no_plots:
            from ..drilling.map_plots import map_figures
            from ..io.figures import save

            for name, fig in map_figures(table, system).items():
                save(fig, os.path.join(directory, name))
                written.append(os.path.join(args.out, name))

    try:
        # the axes are SI now (check_axis read them in the configuration's units)
        frame = drill_map(config.with_units("si"), axes, threads=args.threads, progress=show_progress(args),
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
    say(f"drill-map: {len(frame)} runs ({', '.join(f'{n} {s}' for s, n in counts.items())}) in {seconds:.3g} s "
         f"({len(frame) / seconds:.3g} runs/s){f', {redone} stored chunk(s) recomputed' if redone else ''}")
    if len(ok):
        verdicts = ok[STICK_SLIP_VERDICT].value_counts()
        say(f"SSI {ok[SSI].min():.3g}..{ok[SSI].max():.3g}; stick-slip: yes in {int(verdicts.get('yes', 0))} "
             f"runs (the bit stops during part of the window), no in {int(verdicts.get('no', 0))}, undetermined in "
             f"{int(verdicts.get('undetermined', 0))}; settled in {int((ok[SETTLED] == 1).sum())} of {len(ok)}")
        if REGIME in ok.columns:  # a coupled map ([hoist])
            from ..drilling.units import reported_unit

            regimes = ok[REGIME].value_counts()
            ranges = []
            for name in (ROP_MEAN, MSE_MEAN):
                scale, unit = reported_unit(str(OUTPUTS[name].unit), system)
                low, high = ok[name].min() * scale, ok[name].max() * scale
                ranges.append(f"{OUTPUTS[name].label} {low:.3g}..{high:.3g} {unit}")
            say("regimes: " + ", ".join(f"{r} in {n} runs" for r, n in regimes.items()) + "; " + ", ".join(ranges))
    from ..drilling.map_table import controller_recommendation

    ranking = controller_recommendation(frame)
    if ranking:
        say(f"controller recommendation: {ranking[0].controller} (" + "; ".join(s.line() for s in ranking)
             + f"); set it with --set top_drive.controller.type={ranking[0].controller}; the presets' settings: "
             f"drillstring tune {os.fsdecode(args.config)}")
    say(f"wrote {len(written)} files to {args.out} (and the resumable store: manifest.json, chunks/)")
    return 0
