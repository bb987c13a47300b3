"""``drillstring drill``: one run of the drilling system and its folder."""

from __future__ import annotations

import argparse
import os
from typing import Any, Optional

from ._common import (
    add_drilling_config_arguments,
    add_progress,
    add_units,
    drilling_config,
    figure_workers,
    say,
    show_progress,
)


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring drill`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "drill",
        help="stick-slip of the drilling system: a string in a well, top drive, wall friction, bit",
        description="Solve the torsional waves of a drill string in a deviated well (sections from the top, "
        "Coulomb wall friction, a top drive with its speed controller, the bit off or on bottom) and write the "
        "time series (series.parquet, series.csv), the stick-slip metrics (metrics.json), the space-time fields "
        "(fields.npz), figures, the configuration solved (config.toml) and report.md into DIR.",
        epilog="example: drillstring drill examples/on-bottom-3000m.toml --out drill-run --set top_drive.rpm=120",
    )
    add_drilling_config_arguments(p)
    p.add_argument("--check-grid", action="store_true",
                   help="also solve on twice the cells and report how much every metric moves (about four "
                   "times the work); metrics.json gets grid_check, a move beyond its tolerance a warning (a "
                   "coupled run's ROP, weight and torque on bit, hook load, MSE and regime too)")
    p.add_argument("--check-start", action="store_true",
                   help="a coupled run ([hoist]): also solve it from the other start, numerics.initial_state = rest "
                   "or steady (the bit law's steady drilling), and warn where the regimes or metrics disagree (more "
                   "than one attractor); metrics.json gets start_check")
    add_units(p)
    add_progress(p)
    p.set_defaults(func=run)


def _change(kind: str, change: Optional[float]) -> str:
    """A grid check's change as the console shows it."""
    if change is None:
        return "n/a"
    return f"{100 * change:+.2g} %" if kind == "rel" else f"{change:+.3g}"


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring drill``; returns its exit status."""
    import time

    from ..drilling import drill
    from ..drilling.metrics import HOOK_LOAD_MEAN, OUTPUTS, REGIME
    from ..drilling.output import _write_files, output_folder
    from ..drilling.units import annotate, metric_texts, shown

    config = drilling_config(args)
    plots = not args.no_plots
    # the folder is checked, created and locked before solving: a second run into it is refused now
    with output_folder(args.out, plots=plots, field="--out") as folder:
        start = time.perf_counter()
        result = drill(config, progress=show_progress(args), check_grid=args.check_grid,
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

        say(f"drill: {shown(config.length, 'm', system, digits=6)} string, {config.numerics.cells} cells, "
             f"{config.numerics.duration:g} s simulated in {seconds:.2g} s ({status})")
        say(f"wall contact: {config.friction.contact} ("
             + ("soft-string normal force: buoyed weight and tension times curvature"
                if config.friction.contact == "soft_string" else "buoyed weight times sin(inclination)")
             + f"), break-off torque {torque(result.metrics.breakoff_torque_Nm)}")
        # the registry's console metrics, by their labels, in its order
        shown_here = [n for n, o in OUTPUTS.items() if o.console and "torsional" in o.runs]
        say(f"window {m.window_start:g}-{m.window_end:g} s: {', '.join(metric_texts(m.values, shown_here, system))}")
        say(f"stick-slip: {m.stick_slip_verdict} ({m.stick_slip_reason}); {'' if m.settled else 'not '}settled")
        if result.coupled_metrics is not None:  # a coupled axial-torsional run ([hoist])
            regime = f"{OUTPUTS[REGIME].label}: {result.coupled_regime}"
            if result.coupled_regime == "off bottom":  # a pick-up or slack-off: the hook load is the number
                say(f"off bottom: {metric_texts(result.coupled_metrics, (HOOK_LOAD_MEAN,), system)[0]} (mean over "
                     f"the window); {regime}")
            else:
                on_bottom = [n for n, o in OUTPUTS.items() if o.console and "coupled" in o.runs]
                say(f"on bottom: {', '.join(metric_texts(result.coupled_metrics, on_bottom, system))}; {regime}")
        if result.profile.bit_static_torque > 0:
            p = result.profile
            say(f"static torque to break free {torque(p.static_torque)} (wall {torque(p.breakoff_torque)} "
                 f"+ bit {torque(p.bit_static_torque)})")
        if result.grid_check is not None:
            g = result.grid_check
            moves = ", ".join(f"{r.metric} {_change(r.kind, r.change)}" for r in g.rows if r.kind != "equal")
            say(f"grid check, {g.cells} -> {g.refined_cells} cells: "
                 f"{'converged' if g.converged else 'NOT converged'} ({moves})")
        if result.start_check is not None:
            s = result.start_check
            moved = [r for r in s.rows if not r.within]
            say("start check, rest -> steady: " + ("the same answer" if s.agree else "DISAGREE (" + ", ".join(
                f"{r.metric} {r.rest!r} -> {r.steady!r}" if r.change is None or r.kind == "equal"
                else f"{r.metric} {_change(r.kind, r.change)}" for r in moved) + ")"))
        for warning in result.warnings:
            say(f"warning: {annotate(warning, system)}")
        written = _write_files(result, folder.directory, plots, system, workers=figure_workers())
    say(f"wrote {len(written)} files to {args.out} (report: {os.path.join(args.out, 'report.md')})")
    return 0
