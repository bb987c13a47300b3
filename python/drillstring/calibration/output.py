"""The folder of a fit (``drillstring fit --out DIR``, :meth:`FitResult.save`).

Written as ``drill`` writes its folder (:func:`drillstring.drilling.output.output_folder`): one
writer (locked), refused if it holds another command's output, the complete set written beside
it and swapped in at the end (an interrupted fit leaves the earlier fit's complete set, never a
mix of two fits; the files of :data:`FILES` this fit does not write go with the earlier set):

* ``config.toml``: the fitted configuration (of the first event; ``config-event-N.toml`` for the
  others), ready for ``drill`` and ``drill-map``;
* ``fit.json``: ``parameters`` (per dotted key ``value``, ``ci_low``, ``ci_high``, bounds,
  standard error, interval method, identifiable), the misfit, evaluations, time, stages, warnings;
* ``fit_series.csv``: per event the compared times, measured and fitted series;
* ``fit_series.png`` (measured against fitted), ``landscape.png`` (the misfit over each pair),
  ``profiles.png`` (when profiles were computed);
* ``report.md``: the parameters, the intervals, the warnings, the next commands.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from ..drilling.output import MARKER, _json_ready, _md, output_folder
from ..drilling.units import annotate, field_value
from ..io.output import atomic_write, write_text
from .data import AXIAL_SERIES

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from .fit import FitResult

__all__ = ["FILES", "PLOT_FILES", "next_commands", "owned", "report_markdown", "write_fit"]

DATA_FILES: tuple[str, ...] = ("config.toml", "fit.json", "fit_series.csv")
PLOT_FILES: tuple[str, ...] = ("fit_series.png", "landscape.png", "profiles.png")
FILES: tuple[str, ...] = (*DATA_FILES, *PLOT_FILES, "report.md")


def owned(name: str) -> bool:
    """Whether ``name`` is a file of a fit's folder (:data:`FILES`, ``config-event-N.toml``, the
    marker): replaced by each fit; the folder's other entries are kept."""
    return name in FILES or name == MARKER or (name.startswith("config-event-") and name.endswith(".toml"))


def write_fit(result: FitResult, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
              field: str = "out_dir") -> list[Path]:
    """Writes the fit's files into ``out_dir`` (see the module docstring); returns their paths."""
    extra = tuple(f"config-event-{e}.toml" for e in range(1, len(result.configs)))
    names = (*DATA_FILES, *extra, *(PLOT_FILES if plots else ()), "report.md")
    with output_folder(out_dir, plots=plots, field=field, command="fit", names=names, owns=owned) as folder:
        written = write_files(result, folder.directory, plots, shown=folder.path)
    return [folder.shown(path) for path in written]


def write_files(result: FitResult, directory: Path, plots: bool,
                shown: Optional[Union[str, os.PathLike[str]]] = None) -> list[Path]:
    """The files of :func:`write_fit` into ``directory`` (the ``directory`` of ``output_folder``);
    ``shown`` is the folder as the user named it (default ``directory``), which the report's
    next commands name. Returns the paths written in ``directory``."""
    def path(name: str) -> str:
        return os.path.join(os.fspath(directory), name)

    marker = path(MARKER)
    write_text(marker, f"drillstring fit (process {os.getpid()}) is writing this folder. If this file is still "
               "here, that fit did not finish: the files beside it may be missing or of an earlier fit.\n")
    for name in os.listdir(directory):  # files of an earlier fit
        if (name in FILES or (name.startswith("config-event-") and name.endswith(".toml"))) \
                and not os.path.isdir(path(name)):
            os.unlink(path(name))
    written = [write_text(path("config.toml"), result.configs[0].to_toml())]
    for e, cfg in enumerate(result.configs[1:], start=1):
        written.append(write_text(path(f"config-event-{e}.toml"), cfg.to_toml()))
    text = json.dumps(_json_ready(result.to_dict()), indent=2, allow_nan=False) + "\n"
    written.append(write_text(path("fit.json"), text))
    frame = series_frame(result)
    written.append(atomic_write(path("fit_series.csv"), lambda tmp: frame.to_csv(tmp, index=False,
                                                                                 float_format="%.10g"), suffix=".csv"))
    figures: list[str] = []
    if plots:
        from ..io.figures import save

        made = {"fit_series.png": series_figure(result)}
        if result.landscapes:
            made["landscape.png"] = landscape_figure(result)
        if result.profiles:
            made["profiles.png"] = profile_figure(result)
        for name, fig in made.items():
            written.append(Path(os.fsdecode(os.fspath(save(fig, path(name))))))
            figures.append(name)
            import matplotlib.pyplot as plt

            plt.close(fig)
    folder = os.fspath(directory if shown is None else shown)
    written.append(write_text(path("report.md"), report_markdown(result, folder, figures)))
    os.unlink(marker)
    return written


def series_frame(result: FitResult) -> Any:
    """The compared samples: event, t, and per target the measured and fitted values."""
    import pandas as pd

    frames = []
    for e, (event, fitted) in enumerate(zip(result.events, result.fitted)):
        dt = event.config.numerics.output_interval
        t = np.asarray(fitted.get("t", np.empty(0)))
        inside = np.zeros(t.size, dtype=bool)
        for a, b in event.windows:
            inside |= (t >= a - 1e-9) & (t <= b + 1e-9)
        t = t[inside & (t >= event.data.t[0]) & (t <= event.data.t[-1])]
        cols: dict[str, Any] = {"event": np.full(t.size, e), "t": t}
        for s in result.targets:
            cols[f"{s}_measured"] = event.data.resample(s, t)
            cols[f"{s}_fitted"] = np.asarray(fitted[s])[np.rint(t / dt).astype(np.int64)] if s in fitted else np.nan
        frames.append(pd.DataFrame(cols))
    return pd.concat(frames, ignore_index=True)


def series_figure(result: FitResult) -> Figure:
    """Measured against fitted, one row per event, one column per target; windows shaded."""
    import matplotlib.pyplot as plt

    rows, cols = len(result.events), len(result.targets)
    fig, axes = plt.subplots(rows, cols, figsize=(6.5 * cols, 3.0 * rows), squeeze=False)
    units = {"motor_torque": "N m", "bit_torque": "N m", "surface_rpm": "rpm", "bit_rpm": "rpm", "hook_load": "N",
             "weight_on_bit": "N"}
    for e, (event, fitted) in enumerate(zip(result.events, result.fitted)):
        for j, s in enumerate(result.targets):
            ax = axes[e][j]
            ax.plot(event.data.t, event.data.series[s], color="0.6", lw=0.8, label="measured")
            if s in fitted:
                ax.plot(fitted["t"], fitted[s], color="C3", lw=1.2, label="fitted")
            for a, b in event.windows:
                ax.axvspan(a, b, color="C0", alpha=0.06)
            ax.set_xlabel("t, s")
            ax.set_ylabel(f"{s}, {units[s]}")
            ax.set_title(f"event {e}: {os.path.basename(event.data.source)}", fontsize=9)
            ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    return fig


def landscape_figure(result: FitResult) -> Figure:
    """log10 of the misfit over the minimum on each pair's grid (lower triangle), the optimum and
    the threshold contour of the intervals."""
    import matplotlib.pyplot as plt

    names = list(result.parameters)
    p = len(names)
    fig, axes = plt.subplots(p - 1, p - 1, figsize=(3.6 * (p - 1) + 1.2, 3.2 * (p - 1) + 0.4), squeeze=False,
                             constrained_layout=True)
    for ax in axes.flat:
        ax.set_visible(False)
    floor = max(result.ssr, 1e-300)
    mesh = None
    for land in result.landscapes:
        i, j = names.index(land.x_key), names.index(land.y_key)
        ax = axes[j - 1][i]
        ax.set_visible(True)
        z = np.log10(np.maximum(land.ssr, floor) / floor)
        mesh = ax.pcolormesh(land.x, land.y, z, shading="nearest", cmap="viridis_r")
        if z.max() > 0:
            ax.contour(land.x, land.y, z, levels=np.linspace(0, z.max(), 8)[1:], colors="w", linewidths=0.4)
        ax.plot(result.parameters[land.x_key].value, result.parameters[land.y_key].value, "r+", ms=10)
        ax.set_xlabel(land.x_key, fontsize=8)
        ax.set_ylabel(land.y_key, fontsize=8)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes, label="log10(misfit / minimum)")
    fig.suptitle("misfit landscape (other parameters at the optimum)", fontsize=10)
    return fig


def profile_figure(result: FitResult) -> Figure:
    """Each profiled parameter's excess misfit with the threshold of its interval."""
    import matplotlib.pyplot as plt

    profs = list(result.profiles.values())
    fig, axes = plt.subplots(1, len(profs), figsize=(4.0 * len(profs), 3.2), squeeze=False)
    for ax, prof in zip(axes[0], profs):
        ax.plot(prof.values, prof.ssr - result.ssr, "o-", ms=3)
        ax.axhline(prof.threshold, color="C3", lw=0.8, label=f"{result.level:.0%} threshold")
        ax.set_xlabel(prof.key, fontsize=8)
        ax.set_ylabel("misfit - minimum")
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _axial_fit(result: FitResult) -> bool:
    """Whether the fit compared only a coupled run's axial series (a pick-up's hook load)."""
    return all(name in AXIAL_SERIES for name in result.targets)


def next_heading(result: FitResult) -> str:
    """What :func:`next_commands` gives, as the command line announces it."""
    if _axial_fit(result):
        return "next, the torque and drag of the calibrated well (pick-up, slack-off, rotating loads, the broomstick):"
    return "next, the stick-slip map of the calibrated well and the controller recommendation:"


def next_commands(out_dir: str, result: FitResult) -> list[str]:
    """The commands that follow a fit: the stick-slip map of the calibrated well over the
    setpoint and the controllers (the controller recommendation), with the fitted static
    friction's interval as an axis when it was fitted; after a fit of axial series only (a
    pick-up's hook load), the torque and drag of the calibrated well."""
    config = os.path.join(out_dir, "config.toml")
    if _axial_fit(result):
        return [f"drillstring torque-drag {config} --out {out_dir.rstrip('/')}-td"]
    rpm = result.config.top_drive.rpm
    axes = [f"--axis top_drive.rpm={max(rpm / 2, 10):.3g}:{max(4 * rpm, 120):.3g}:9"]
    est = result.parameters.get("friction.static")
    if est is not None and est.ci_high > est.ci_low:
        axes.append(f"--axis friction.static={est.ci_low:.4g}:{est.ci_high:.4g}:3")
    elif result.config.bit.on_bottom:
        w = result.config.bit.weight_on_bit
        axes.append(f"--axis bit.weight_on_bit={w / 2:.4g}:{2 * w:.4g}:5")
    axes.append("--axis top_drive.controller.type=pi,soft_torque,z_torque")
    return [f"drillstring drill-map {config} {' '.join(axes)} --out {out_dir.rstrip('/')}-map"]


def _fmt(value: float) -> str:
    return "–" if not math.isfinite(value) else f"{value:.5g}"


def _field(key: str, system: str, low: float, high: Optional[float] = None) -> str:
    """`` (20 klbf)`` or `` (18 .. 22 klbf)``: the SI value(s) of ``key`` in field units, for a
    field configuration (``system``); empty in SI or for a key whose unit is the same in both."""
    first = field_value(key, low, system, 5)
    if first is None:
        return ""
    if high is None:
        return f" ({first})"
    second = field_value(key, high, system, 5)
    if second is None:
        return ""
    return f" ({first.split(' ', 1)[0]} .. {second})"


def report_markdown(result: FitResult, out_dir: str, figures: list[str]) -> str:
    """A short Markdown report of the fit; for a field configuration (``units = "field"``) the
    parameters in field units too, beside the SI values the fitted ``config.toml`` holds."""
    lines = [
        "# Calibration from measured data",
        "",
        f"{len(result.events)} event(s), targets "
        f"{', '.join(f'{k} (weight {v:g})' for k, v in result.targets.items())}; "
        f"{result.points} compared samples; {result.evaluations} model runs in {result.seconds:.3g} s.",
        "",
        f"## Parameters ({result.level:.0%} intervals)",
        "",
        "| parameter | value | interval | bounds | from | identifiable |",
        "|---|---:|---|---|---|---|",
    ]
    system = result.config.units  # a field configuration's values in field units too
    for key, p in result.parameters.items():
        lines.append(f"| `{_md(key)}` | {_fmt(p.value)}{_field(key, system, p.value)} | {_fmt(p.ci_low)} .. "
                     f"{_fmt(p.ci_high)}{_field(key, system, p.ci_low, p.ci_high)} | {p.lower:g} .. {p.upper:g}"
                     f"{_field(key, system, p.lower, p.upper)} | {p.method} | "
                     f"{'yes' if p.identifiable else '**no**'} |")
    lines += ["", "## Misfit", "",
              f"- sum of squared normalised residuals {result.ssr:.5g} (mean square {result.misfit:.4g}); "
              f"global stage best {result.global_stage['best_ssr']:.5g} over {result.global_stage['points']} points",
              f"- condition number of the box-scaled Jacobian {result.condition:.3g}; residual lag-one "
              f"autocorrelation {result.residual_autocorrelation:.3g}",
              f"- misfit: {'cycle features' if result.objective == 'features' else 'least squares, sample by sample'}"]
    for e, found in enumerate(result.offsets):
        for series, o in found.items():
            lines.append(f"- event {e}: offset of {series} (measured - model) {o['constant']:.5g} at t = "
                         f"{o['t_ref']:.4g} s" + (f", drifting {o['rate_per_s']:.4g} per s"
                                                  if result.offset == "linear" else "")
                         + " (estimated with the values; the fitted series include it)")
    for e, row in enumerate(result.rms):
        lines.append(f"- event {e} ({_md(os.path.basename(result.events[e].data.source))}): RMS error "
                     + ", ".join(f"{k} {v:.4g}" for k, v in row.items()))
    for c in result.series_checks:
        lines.append(f"- event {c.event}, {c.series}: the data's noise level {c.noise:.4g} (from successive "
                     f"differences), residual autocorrelation {c.autocorrelation:.3g}")
    if len(result.parameters) > 1 and result.correlation:
        names = list(result.parameters)
        pairs = [f"`{_md(names[i])}` / `{_md(names[j])}` {result.correlation[i][j]:+.3f}"
                 for i in range(len(names)) for j in range(i + 1, len(names))]
        lines.append("- correlation of the estimates: " + ", ".join(pairs))
    if result.features:
        lines += ["", "## Features", "", "| event | series | feature | data | std | fitted | (fitted - data) / std |",
                  "|---:|---|---|---:|---:|---:|---:|"]
        for row in result.features:
            z = (row["fitted"] - row["data"]) / row["std"] if math.isfinite(row["fitted"]) else math.nan
            lines.append(f"| {row['event']} | {row['series']} | {row['feature']} | {_fmt(row['data'])} | "
                         f"{_fmt(row['std'])} | {_fmt(row['fitted'])} | {_fmt(z)} |")
    if result.warnings:
        lines += ["", "## Warnings", ""] + [f"- {_md(annotate(w, system))}" for w in result.warnings]
    lines += ["", "## What the data must contain", "",
              "- static friction: a break-off (a start-up from rest, the torque peak before the string turns);",
              "- kinetic ratio: the torque while the string slips, after break-off;",
              "- stick speed and damping: the stick-slip cycles or the decay after the start-up;",
              "- with the kinetic torque alone (steady rotation) only static x kinetic ratio is fixed: a ridge.",
              "", "## Next", "", "The stick-slip map of the calibrated well and the controller recommendation:", ""]
    lines += [f"    {c}" for c in next_commands(out_dir, result)]
    lines += ["", "## Files", "", "- `config.toml`: the fitted configuration", "- `fit.json`: parameters, "
              "intervals, misfit, evaluations, time", "- `fit_series.csv`: measured and fitted samples"]
    if figures:
        lines += ["", "## Figures", ""] + [f"![{n[:-4].replace('_', ' ')}]({n})" for n in figures]
    return "\n".join(lines) + "\n"
