"""The folder of a rig log (``drillstring rig-log FILE --out DIR``, :meth:`RigLogResult.write`).

Written as ``drill`` writes its folder (:func:`drillstring.drilling.output.output_folder`: one
writer, locked, another command's folder refused, the complete set swapped in at the end):

* ``states.csv``: one row per row of the log kept: ``t`` (s), ``rig_state`` (WITS0 code),
  ``bit_depth_m``, ``hole_depth_m``, ``rop_m_per_h``, ``in_slips`` (0/1) and the channels in SI
  (``hook_load_N``, ``surface_torque_Nm``, ...);
* ``events.csv``: one row per calibration event (``event``, ``t_start``, ``t_end``,
  ``operation``, ``depth [m]``, ``hook_load [N]``, ``surface_torque [N m]``, ...), the table a
  torque-and-drag comparison reads (rows with an operation);
* ``intervals.csv``: per drilled interval its depths, rate of penetration and stick-slip severity;
* ``start_up_NN.csv``: each start-up's series (``t [s]`` from its last sample at rest,
  ``surface_rpm [rpm]``, ``motor_torque [N m]``, ``hook_load [N]``), as ``drillstring fit --data``
  reads it;
* ``summary.json``: rows, duration, gaps, time per state, depth range, events by kind, the rules;
* ``rig_log.png`` (depths, hook load, speed and torque over time with the states as coloured
  bands), ``events.png`` (hook load and torque over depth with the events marked);
* ``report.md``: the summary, the intervals, the events and the next commands.
"""

from __future__ import annotations

import json
import os
import re
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

import numpy as np

from ..drilling.metrics import ROP_MEAN
from ..drilling.output import MARKER, _json_ready, _md, output_folder
from ..io.output import atomic_write, write_text
from .rig_log import STATES, RigStateRules

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from .rig_log import RigLogResult

__all__ = ["DATA_FILES", "PLOT_FILES", "next_commands", "owned", "report_markdown", "write_rig_log"]

DATA_FILES: tuple[str, ...] = ("states.csv", "events.csv", "intervals.csv", "summary.json")
PLOT_FILES: tuple[str, ...] = ("rig_log.png", "events.png")
_SERIES = re.compile(r"^start_up_\d+\.csv$")

#: The colour of each state's band in the figures.
STATE_COLOURS: dict[int, str] = {0: "#d9d9d9", 2: "#2ca02c", 3: "#ff7f0e", 4: "#9467bd", 7: "#17becf",
                                 8: "#1f77b4", 9: "#d62728"}
_EVENT_MARKERS: dict[str, tuple[str, str]] = {"start_up": ("*", "black"), "pick_up": ("^", "tab:red"),
                                              "slack_off": ("v", "tab:blue"),
                                              "rotating_off_bottom": ("o", "tab:green")}


def owned(name: str) -> bool:
    """Whether ``name`` is a file of a rig-log folder (replaced by each run; other entries kept)."""
    return name in DATA_FILES or name in PLOT_FILES or name in ("report.md", MARKER) or bool(_SERIES.match(name))


def _csv(frame: Any, tmp: str) -> None:
    frame.to_csv(tmp, index=False, float_format="%.10g")


def write_rig_log(result: RigLogResult, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
                  field: str = "out_dir") -> list[Path]:
    """Writes the folder (see the module docstring) into ``out_dir``; returns the paths written."""
    names = (*DATA_FILES, *result.series, *(PLOT_FILES if plots else ()), "report.md")
    with output_folder(out_dir, field=field, command="rig-log", names=names, owns=owned) as folder:
        def path(name: str) -> str:
            return os.path.join(os.fspath(folder.directory), name)

        marker = path(MARKER)
        write_text(marker, f"drillstring rig-log (process {os.getpid()}) is writing this folder. If this file is "
                   "still here, that run did not finish.\n")
        written = []
        for name, frame in (("states.csv", result.states), ("events.csv", result.events),
                            ("intervals.csv", result.intervals), *result.series.items()):
            written.append(atomic_write(path(name), partial(_csv, frame), suffix=".csv"))
        written.append(write_text(path("summary.json"), json.dumps(_json_ready(result.summary), indent=2) + "\n"))
        if plots:
            from ..io.figures import save

            for name, make in zip(PLOT_FILES, (log_figure, events_figure)):
                written.append(Path(os.fsdecode(os.fspath(save(make(result), path(name))))))
        shown = os.fsdecode(os.fspath(out_dir))
        written.append(write_text(path("report.md"), report_markdown(result, shown, plots=plots)))
        os.unlink(marker)
    return [folder.shown(p) for p in written]


def next_commands(out_dir: str, result: RigLogResult, config: str = "CONFIG.toml") -> list[str]:
    """The commands that follow: the fit of the start-ups' series (one ``--data`` per start-up,
    the surface speed imposed), and the torque and drag of the well against the events."""
    out = out_dir.rstrip("/") or "."
    commands = []
    if result.series:
        data = " ".join(f"--data {os.path.join(out, name)}" for name in result.series)
        commands.append(f"drillstring fit {config} {data} --top measured --param friction.static=0.1:0.6 "
                        f"--out {out}-fit")
    if (result.events["operation"] != "").any():
        commands.append(f"drillstring torque-drag {config} --measured {os.path.join(out, 'events.csv')} "
                        f"--out {out}-td")
    return commands


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def _bands(ax: Any, t: np.ndarray, state: np.ndarray) -> None:
    for code, colour in STATE_COLOURS.items():
        ax.fill_between(t, 0, 1, where=state == code, step="post", color=colour, alpha=0.3, linewidth=0,
                        transform=ax.get_xaxis_transform())


def log_figure(result: RigLogResult) -> Figure:
    """The time-depth log: bit and hole depth (down), hook load, surface speed and torque over
    time (h), the rig states as coloured bands behind every panel."""
    from matplotlib.patches import Patch

    s = result.states
    t = (s["t"].to_numpy() - s["t"].iloc[0]) / 3600.0
    state = s["rig_state"].to_numpy()
    panels = [("bit_depth_m", "depth (m)")]
    panels += [(c, label) for c, label in (("hook_load_N", "hook load (kN)"), ("surface_rpm", "surface speed (rpm)"),
                                           ("surface_torque_Nm", "surface torque (kN m)")) if c in s]
    fig = _figure(12, 2.2 * len(panels) + 1)
    axes = np.atleast_1d(fig.subplots(len(panels), 1, sharex=True))
    for ax, (column, label) in zip(axes, panels):
        _bands(ax, t, state)
        if column == "bit_depth_m":
            ax.plot(t, s["hole_depth_m"], color="black", lw=1.0, label="hole depth")
            ax.plot(t, s["bit_depth_m"], color="tab:blue", lw=0.8, label="bit depth")
            ax.invert_yaxis()
            ax.legend(loc="lower left", fontsize=8)
        else:
            scale = 1e-3 if column in ("hook_load_N", "surface_torque_Nm") else 1.0
            ax.plot(t, s[column] * scale, color="black", lw=0.4)
        ax.set_ylabel(label)
    axes[-1].set_xlabel("time from the first row (h)")
    handles = [Patch(color=c, alpha=0.5, label=f"{code} {STATES[code].replace('_', ' ')}")
               for code, c in STATE_COLOURS.items()]
    fig.legend(handles=handles, loc="outside upper center", ncol=len(handles), fontsize=8)
    return fig


def events_figure(result: RigLogResult) -> Figure:
    """Hook load (kN) and surface torque (kN m) against bit depth (m, down), every row out of
    slips as a faint point and the events marked by kind (the broomstick's measured points)."""
    s = result.states
    off = s[s["in_slips"] == 0]
    fig = _figure(11, 6)
    axes = fig.subplots(1, 2, sharey=True)
    for ax, (column, event_column, label) in zip(axes, (("hook_load_N", "hook_load [N]", "hook load (kN)"),
                                                         ("surface_torque_Nm", "surface_torque [N m]",
                                                          "surface torque (kN m)"))):
        if column in off:
            ax.plot(off[column] * 1e-3, off["bit_depth_m"], ",", color="0.7")
        for kind, (marker, colour) in _EVENT_MARKERS.items():
            e = result.events[result.events["event"] == kind]
            ax.plot(e[event_column] * 1e-3, e["depth [m]"], marker, color=colour, ls="none", ms=7,
                    label=f"{kind.replace('_', ' ')} ({len(e)})")
        ax.set_xlabel(label)
    axes[0].set_ylabel("bit depth (m)")
    axes[0].invert_yaxis()
    axes[0].legend(fontsize=8)
    return fig


def _f(value: Any, digits: int = 4) -> str:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return "–"
    return "–" if not np.isfinite(number) else f"{number:.{digits}g}"


def report_markdown(result: RigLogResult, out_dir: str, *, plots: bool = True) -> str:
    """``report.md``: what was read, the gaps, time per state, depths, intervals, events and the
    next commands."""
    s = result.summary
    lines = [f"# Rig log: {_md(os.path.basename(s['source']))}", "",
             f"{s['rows']} rows over {s['duration_s'] / 3600:.3g} h (sampling {s['sampling_interval_s']:.3g} s); "
             f"{s['rows_dropped_time_backwards']} rows dropped for a time before the one before, "
             f"{s['rows_repeated_time']} rows with the time of the one before kept; "
             f"{s['gap_count']['time_jump']} time jumps and {s['gap_count']['missing_values']} runs of missing values.",
             "", "| channel | header | unit read |", "|---|---|---|"]
    lines += [f"| {name} | {_md(c['header'])} | {_md(c['unit'])} |" for name, c in s["channels"].items()]
    if s["gaps"]:
        lines += ["", "| gap | from t (s) | to t (s) | duration (s) | rows |", "|---|---|---|---|---|"]
        lines += [f"| {g['kind'].replace('_', ' ')} | {g['t_start']:.6g} | {g['t_end']:.6g} | {g['duration_s']:.4g} | "
                  f"{g['rows']} |" for g in s["gaps"]]
    lines += ["", "## Rig states", "", "| code | state | time (h) | share |", "|---|---|---|---|"]
    total = max(sum(s["time_per_state_s"].values()), 1e-300)
    for code, name in STATES.items():
        seconds = s["time_per_state_s"][name]
        lines.append(f"| {code} | {name.replace('_', ' ')} | {seconds / 3600:.3g} | {seconds / total:.1%} |")
    d = s["depth_range_m"]
    rop = s[ROP_MEAN]
    lines += ["", f"Hole depth {d['hole_start']:.2f} m to {d['hole_end']:.2f} m ({d['drilled']:.2f} m drilled"
              + (f", {rop:.3g} m/h mean rate of penetration" if rop is not None else "") + f"); bit depth "
              f"{d['bit_min']:.2f} m to {d['bit_max']:.2f} m. Block weight "
              f"{s['rules']['thresholds']['block_weight'] / 1e3:.4g} kN ({s['rules']['block_weight']}).", ""]
    if plots:
        lines += ["![rig log](rig_log.png)", ""]
    lines += ["## Drilled intervals", "", "| from (m) | to (m) | drilled (m) | ROP (m/h) | surface speed (rpm) | "
              "surface torque (kN m) | stick-slip severity |", "|---|---|---|---|---|---|---|"]
    for _, r in result.intervals.iterrows():
        lines.append(f"| {r['depth_from [m]']:.2f} | {r['depth_to [m]']:.2f} | {r['drilled [m]']:.2f} | "
                     f"{_f(r['rop [m/h]'], 3)} | {_f(r['surface_rpm [rpm]'], 3)} | "
                     f"{_f(r['surface_torque [N m]'] / 1e3, 3)} | {_f(r['stick_slip_severity [1]'], 2)} |")
    lines += ["", "## Calibration events", "", ", ".join(f"{n} {k.replace('_', ' ')}" for k, n in s["events"].items())
              + " (events.csv; start-ups' series in start_up_NN.csv).", ""]
    if plots:
        lines += ["![events](events.png)", ""]
    lines += ["| event | t start (s) | depth (m) | hook load (kN) | surface torque (kN m) | surface speed (rpm) |",
              "|---|---|---|---|---|---|"]
    for _, e in result.events.iterrows():
        lines.append(f"| {e['event']} | {e['t_start']:.0f} | {e['depth [m]']:.2f} | {_f(e['hook_load [N]'] / 1e3)} | "
                     f"{_f(e['surface_torque [N m]'] / 1e3, 3)} | {_f(e['surface_rpm [rpm]'], 3)} |")
    lines += ["", "## Next", "", "The string and survey are not in a surface log: write them in a configuration "
              "(CONFIG.toml, see the drilling guide), then:", ""]
    lines += [f"    {c}" for c in next_commands(out_dir, result)]
    lines += ["", "## Rules", "", "| rule | value | unit |", "|---|---|---|"]
    lines += [f"| {k} | {_f(v, 6)} | {RigStateRules.UNITS.get(k) or '1'} |"
              for k, v in s["rules"]["thresholds"].items()]
    lines += [""] + [f"- {k}: {_md(v)}" for k, v in s["rules"].items() if isinstance(v, str)] + [""]
    return "\n".join(lines)
