"""The output folder of a drilling-system run (``drillstring drill --out DIR``,
:meth:`DrillResult.save`). Every file goes through :mod:`drillstring.io.output`: written to a
temporary file and renamed into place, never over an input of the command.

The folder is written as a whole (:func:`output_folder`):

* **one writer**: the folder is locked (:func:`drillstring.io.output.lock_directory`, the lock of
  the sweep and map stores) while a run writes it (``drillstring drill`` takes it before solving);
  a second run into it is refused, naming the process that holds it;
* **all or nothing**: the run's complete set is written into a hidden folder beside it and
  swapped in at the end (:func:`drillstring.io.output.replaced_folder`): ``kill -9``, Ctrl-C or
  a full disk at any moment leave the complete old set or the complete new one, never a mix (the
  files of :data:`FILES` this run does not write, the figures with ``plots=False``, go with the
  old set; other files the user keeps in the folder stay). Where the folder cannot be swapped
  (a mount point) it is written in place: :data:`MARKER` first and removed last, so a folder
  whose writing was interrupted says so;
* **its own folder**: a folder holding another command's output (a ``drill-map`` or ``sweep``
  store) is refused (:func:`drillstring.io.output.refuse_foreign_folder`).
"""

from __future__ import annotations

import json
import math
import os
import unicodedata
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np

from ..io.output import (
    FolderWrite,
    atomic_write,
    check_destination,
    check_directory_name,
    recover_folder,
    write_bytes,
    write_text,
    writing_folder,
)
from ..io.table import csv_text, write_parquet
from .metrics import STICK_SLIP_CRITERION

if TYPE_CHECKING:  # pragma: no cover
    from .result import DrillResult

__all__ = ["COUPLED_PLOT_FILES", "DATA_FILES", "FILES", "MARKER", "PLOT_FILES", "output_folder", "output_names",
           "report_markdown", "write_outputs"]

#: The data files of an output folder, in the order they are written.
DATA_FILES: tuple[str, ...] = ("series.parquet", "series.csv", "metrics.json", "fields.npz", "config.toml")
#: The figures (skipped with ``--no-plots``).
PLOT_FILES: tuple[str, ...] = ("time_histories.png", "space_time.png", "torque_depth.png")
#: The figures of a coupled run (``[hoist]``) besides :data:`PLOT_FILES` (skipped with
#: ``--no-plots``; a torsion-only run removes an earlier run's).
COUPLED_PLOT_FILES: tuple[str, ...] = ("axial_time.png", "axial_space_time.png")
#: Every file an output folder gets (``report.md`` last).
FILES: tuple[str, ...] = (*DATA_FILES, *PLOT_FILES, "report.md")
#: Written first and removed last: a folder that still has it was not written to the end (its
#: files may be of different runs).
MARKER = "INCOMPLETE"


def _json_ready(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {str(k): _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, np.generic):
        return _json_ready(value.item())
    return value


def output_names(plots: bool = True) -> tuple[str, ...]:
    """The files an output folder gets (:data:`FILES`, without the figures with ``plots=False``)."""
    return FILES if plots else tuple(name for name in FILES if name not in PLOT_FILES)


def owned(name: str) -> bool:
    """Whether ``name`` is a file of a ``drill`` folder (:data:`FILES`, :data:`COUPLED_PLOT_FILES`,
    :data:`MARKER`): replaced by each run; the folder's other entries are kept."""
    return name in FILES or name in COUPLED_PLOT_FILES or name == MARKER


@contextmanager
def output_folder(out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
                  field: str = "out_dir", command: str = "drill",
                  names: Optional[tuple[str, ...]] = None,
                  owns: Optional[Callable[[str], bool]] = None) -> Iterator[FolderWrite]:
    """Holds the output folder ``out_dir`` of a run for the ``with`` block: checks it
    (:func:`~drillstring.io.output.check_destination`, not another command's output), creates it
    and takes its lock (see the module docstring), removes what an interrupted run left beside
    it; yields a :class:`~drillstring.io.output.FolderWrite`: write the new set into its
    ``directory`` (:func:`_write_files`), name the files by its ``shown``. A normal exit swaps the
    new set in; an exception drops it (the folder keeps its old set). At the end the lock is
    released and its file removed, as is the folder if it was created here and is still empty
    (a run interrupted before writing leaves nothing). Refusals raise
    :class:`~drillstring.errors.ValidationError` naming ``field``; so does a folder held by
    anyone else, also another ``with`` block of this process; a failed write an
    :class:`~drillstring.io.output.OutputError` naming the user's path. ``command`` names the
    command whose folder it is (another command's is refused), ``names`` the files it writes
    (default: :func:`output_names`) and ``owns`` which names are its own (default :func:`owned`;
    the others are kept)."""
    display = os.fsdecode(os.fspath(out_dir))
    check_directory_name(display, field)
    recover_folder(display)  # an old set moved aside by an interrupted swap goes back first
    files = (*output_names(plots), *COUPLED_PLOT_FILES) if names is None else names
    check_destination(display, field=field, directory=True, files=(*files, MARKER))
    with writing_folder(display, field=field, owned=owned if owns is None else owns, command=command) as folder:
        yield folder


def write_outputs(result: DrillResult, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
                  field: str = "out_dir", output_units: str = "si") -> list[Path]:
    """Writes the run's files into ``out_dir`` (created if needed; see :data:`FILES`) and
    returns their paths. The folder and every file destination in it are checked first
    (:func:`~drillstring.io.output.check_destination`): a refused one raises
    :class:`~drillstring.errors.ValidationError` naming ``field`` before anything is written.
    The folder is held (:func:`output_folder`) while it is written and replaced as a whole (see
    the module docstring). ``output_units`` adds a converted copy of the metrics to ``metrics.json``
    (:meth:`DrillResult.summary`) and is the unit system of the figures (their ``units``) and of
    ``report.md`` (:func:`report_markdown`); the data files stay SI."""
    from .units import system_of

    output_units = system_of(output_units, "output_units")  # refused before anything is written
    with output_folder(out_dir, plots=plots, field=field) as folder:
        written = _write_files(result, folder.directory, plots, output_units)
    return [folder.shown(path) for path in written]


def _write_files(result: DrillResult, directory: Path, plots: bool, output_units: str = "si", *,
                 workers: int = 0) -> list[Path]:
    """The files of :func:`write_outputs` into ``directory`` (the ``directory`` of
    :func:`output_folder`); returns their paths there. ``workers`` forked processes draw the
    figures while this one writes the data files (:class:`~drillstring.io.figures.FigureJobs`;
    the command line's choice, 0: all here, in turn)."""
    written: list[Path] = []

    def path(name: str) -> str:
        return os.path.join(os.fspath(directory), name)

    marker = path(MARKER)
    write_text(marker, f"drillstring drill (process {os.getpid()}) is writing this folder. If this file is still "
               "here, that run did not finish: the files beside it may be missing or of an earlier run.\n")
    names = output_names(plots)
    coupled = bool(result.axial)
    for name in (*FILES, *COUPLED_PLOT_FILES):
        if (name not in names or (name in COUPLED_PLOT_FILES and not (plots and coupled))) \
                and os.path.lexists(path(name)) and not os.path.isdir(path(name)):
            os.unlink(path(name))  # a file of an earlier run (a figure, with plots=False now)
    figures = _figure_jobs(result, path, coupled, output_units, workers) if plots else None
    try:
        # the frame of DrillResult.to_pandas without its attrs (the config and metrics have their own
        # files), written without pandas, whose import alone would cost a command line 0.3 s
        index, columns = ("t", result.t), result.series_columns()
        written.append(atomic_write(path("series.parquet"), lambda tmp: write_parquet(tmp, index, columns),
                                    suffix=".parquet"))
        written.append(write_text(path("series.csv"), csv_text(index, columns)))
        text = json.dumps(_json_ready(result.summary(output_units)), indent=2, allow_nan=False) + "\n"
        written.append(write_text(path("metrics.json"), text))
        profile = result.profile

        axial: dict[str, Any] = ({"axial_z": result.axial_z, "axial_speed_m_s": result.axial_speed_field,
                                  "axial_force_N": result.axial_force_field} if coupled else {})

        def save_fields(tmp: str) -> None:
            with open(tmp, "wb") as handle:
                np.savez_compressed(
                    handle, t=result.field_t, z=result.z, omega_rpm=result.omega_field, torque_Nm=result.torque_field,
                    profile_z=profile.z, limit_per_m=profile.limit_per_m, cumulative_Nm=profile.cumulative,
                    breakoff_torque_Nm=np.float64(profile.breakoff_torque), inclination_deg=profile.inclination_deg,
                    azimuth_deg=profile.azimuth_deg, tvd_m=profile.tvd, dls_deg_per_30m=profile.dls_deg_per_30m,
                    friction_factor=profile.friction_factor, **axial,
                )

        written.append(atomic_write(path("fields.npz"), save_fields, suffix=".npz"))
        written.append(write_text(path("config.toml"), result.config.to_toml()))
    except BaseException:
        if figures is not None:
            figures.cancel()
        raise
    if figures is not None:
        written += [Path(os.fsdecode(os.fspath(p))) for p in figures.finish()]
    report = report_markdown(result, plots=plots, units=output_units)
    written.append(write_bytes(path("report.md"), report.encode("utf-8")))
    os.unlink(marker)
    return written


def _figure_jobs(result: DrillResult, path: Callable[[str], str], coupled: bool, output_units: str,
                 workers: int) -> Any:
    """The run's figures (a coupled run's too) as :class:`~drillstring.io.figures.FigureJobs`,
    started."""
    from functools import partial

    from ..io.figures import FigureJobs
    from .plots import space_time_maps, time_histories, torque_depth

    makers: list[Any] = [time_histories, space_time_maps, torque_depth]
    if coupled:
        from .plots import axial_histories, axial_space_time

        makers += [axial_histories, axial_space_time]
    jobs = [(partial(make, result, units=output_units), path(name))
            for name, make in zip((*PLOT_FILES, *COUPLED_PLOT_FILES), makers)]
    return FigureJobs(jobs, workers)


_MD_SPECIAL = frozenset("\\`*_[]<>|!~&$")


def _md(text: str) -> str:
    """``text`` (a name or message from the configuration or the core) as literal Markdown on
    one line: the characters Markdown acts on mid-line backslash-escaped (no emphasis, code,
    links, HTML, entities or table cells), control, format and line/paragraph-separator
    characters shown as ``U+XXXX``."""
    out = []
    for ch in str(text):
        if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp", "Cs"):
            out.append(f"U+{ord(ch):04X}")
        elif ch in _MD_SPECIAL:
            out.append("\\" + ch)
        else:
            out.append(ch)
    return "".join(out)


def _fmt(value: float, digits: int = 4) -> str:
    return "–" if not math.isfinite(value) else f"{value:.{digits}g}"


def _metric_rows(values: Mapping[str, Any], names: Iterable[str], system: str) -> list[str]:
    """``| label, unit | value |`` of each metric of ``names`` in ``values`` (SI, by the registry's
    names) with the registry's label, in ``system``'s :func:`~drillstring.drilling.units.reported_unit`
    (4 significant digits; a dimensionless number 3)."""
    from .metrics import OUTPUTS
    from .units import reported_unit

    rows = []
    for name in names:
        o = OUTPUTS[name]
        scale, unit = reported_unit(o.unit, system) if o.unit else (1.0, "")
        value = math.nan if values[name] is None else values[name]  # (None: undefined, as metrics.json writes it)
        rows.append(f"| {o.label}{', ' + unit if unit else ''} | {_fmt(value * scale, 4 if unit else 3)} |")
    return rows


def report_markdown(result: DrillResult, *, plots: bool = True, units: str = "si") -> str:
    """A short Markdown report of the run: the system, how the solve ended, the metrics, the
    energy balance and the files. ``units`` (``"si"`` or ``"field"``) is the unit system of its
    numbers (field: ft, in, klbf, kft-lbf, ppg, psi, ft/h; :mod:`drillstring.drilling.units`); the
    data files it lists are SI either way."""
    from .result import METRIC_UNITS
    from .units import annotate, convert, shown_unit, system_of

    system = system_of(units, "units")
    cfg = result.config
    m = result.metrics
    td = cfg.top_drive
    bit = cfg.bit

    def unit(si: str, key: str = "", kilo: bool = False) -> str:  # the unit a column writes
        if system == "field" and key:
            return convert(1.0, si, system, key=key)[1]
        return shown_unit(si, system, kilo=kilo)

    def num(value: float, si: str, key: str = "", kilo: bool = False, digits: int = 4) -> str:
        number = convert(value, si, system, key=key or None)[0]
        number = float("nan") if number is None else number
        return _fmt(number / 1e3 if kilo and not unit(si, key).startswith("k") else number, digits)

    def kilo(si: str) -> bool:  # a thousand of the unit: kN m, kN; klbf is one already
        return not unit(si).startswith("k")

    pressure = "GPa" if system == "si" else unit("Pa")
    lines = [
        "# Drilling-system run",
        "",
        f"Status: **{result.status}**" + (f" ({_md(result.message)})" if result.message else ""),
        "",
        *([f"Units: field ({', '.join(('ft', 'in', 'klbf', 'ft-lbf', 'ppg', 'psi', 'ft/h'))}); "
           "the data files are SI.", ""] if system == "field" else []),
        "## System",
        "",
        f"| section | length, {unit('m')} | OD, {unit('m', 'sections[].outer_diameter')} | "
        f"ID, {unit('m', 'sections[].inner_diameter')} | G, {pressure} | density, "
        f"{'kg/m³' if system == 'si' else unit('kg/m^3')} |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for s in cfg.sections:
        modulus = _fmt(s.shear_modulus / 1e9, 4) if system == "si" else num(s.shear_modulus, "Pa", digits=4)
        lines.append(f"| {_md(s.name)} | {num(s.length, 'm', digits=6)} | "
                     f"{num(s.outer_diameter, 'm', 'sections[].outer_diameter', digits=6)} | "
                     f"{num(s.inner_diameter, 'm', 'sections[].inner_diameter', digits=6)} | "
                     f"{modulus} | {num(s.density, 'kg/m^3', digits=6)} |")
    inclination = cfg.well.inclination_deg
    if cfg.well.survey is not None:
        survey = f"survey file {_md(cfg.well.survey)} (minimum curvature)"
    elif cfg.well.plan is not None:
        survey = f"a plan of {len(cfg.well.plan)} segments (minimum curvature)"
    else:
        survey = (f"{inclination:g}° constant" if isinstance(inclination, float) else
                  ", ".join(f"{i:g}° at {num(md, 'm', digits=6)} {unit('m')}"
                            for md, i in zip(cfg.well.md or (), inclination)))
    contact = ("the soft-string normal force (buoyed weight and tension times curvature)"
               if cfg.friction.contact == "soft_string" else "the buoyed weight times sin(inclination)")
    on_bottom = (f"on bottom, WOB {num(bit.weight_on_bit, 'N', kilo=kilo('N'))} {unit('N', kilo=kilo('N'))}, "
                 f"r {num(bit.radius, 'm', 'bit.radius', digits=6)} {unit('m', 'bit.radius')}, "
                 f"mu_s {bit.mu_static:g}, mu_k {bit.mu_kinetic:g}" if bit.on_bottom else "off bottom")
    torque_unit = unit("N*m", kilo=True)
    lines += [
        "",
        f"- Well: {survey}; wall friction mu {cfg.friction.static:g}"
        + (f" (and {len(cfg.friction.intervals)} depth interval(s) of their own)" if cfg.friction.intervals else "")
        + f" (kinetic x{cfg.friction.kinetic_ratio:g}, {cfg.friction.model}) on the contact force "
        f"`{cfg.friction.contact}`: {contact}",
        f"- Top drive: {td.rpm:g} rpm, {td.controller.type} controller, inertia "
        f"{num(td.inertia, 'kg*m^2', digits=6)} {unit('kg*m^2').replace('^2', '²')}",
        f"- Bit: {on_bottom}",
        f"- Numerics: {cfg.numerics.cells} cells asked"
        + (f" ({result.stats['cells']} used), {cfg.numerics.duration:g} s in {result.stats['steps']} steps of "
           f"{_fmt(float(result.stats['dt']))} s" if {"cells", "steps", "dt"} <= set(result.stats)
           else f", {cfg.numerics.duration:g} s"),
        "",
        f"## Stick-slip (window {_fmt(m.window_start)}–{_fmt(m.window_end)} s)",
        "",
        f"**Stick-slip: {m.stick_slip_verdict}** ({_md(m.stick_slip_reason)}); the window is "
        f"{'' if m.settled else '**not** '}settled{'' if m.settled else ' (a transient)'}.",
        "",
        f"Criterion: {_md(STICK_SLIP_CRITERION)}.",
        "",
        *[f"- warning: {_md(annotate(w, system))}" for w in result.warnings],
        *([""] if result.warnings else []),
        "| metric | value |",
        "|---|---:|",
        # every numeric metric of metrics.json but the window's bounds, by the registry's labels, in its order
        *_metric_rows(m.to_dict(), [n for n in METRIC_UNITS if not n.startswith("window_")], system),
        *([f"| static torque to break free (wall + bit {num(result.profile.bit_static_torque, 'N*m', kilo=True)}), "
           f"{torque_unit} | {num(result.profile.static_torque, 'N*m', kilo=True)} |"]
          if result.profile.bit_static_torque > 0 else []),
    ]
    if result.coupled_metrics is not None:  # a coupled axial-torsional run ([hoist])
        from .result import COUPLED_METRIC_UNITS, COUPLED_REGIME_CRITERION

        rows = _metric_rows(result.coupled_metrics, COUPLED_METRIC_UNITS, system)
        lines += ["", f"## Coupled axial-torsional run (window {_fmt(m.window_start)}–{_fmt(m.window_end)} s)", "",
                  f"**Regime: {result.coupled_regime}**.", "",
                  f"Criterion: {_md(COUPLED_REGIME_CRITERION)}.", "",
                  "| metric (over the window) | value |", "|---|---:|", *rows]
    if result.energy and all(math.isnan(v) for v in result.energy.values()):
        lines += ["", "## Energy balance", "", "Not kept (`numerics.energy_balance = false`)."]
    elif result.energy:
        energy = "J" if system == "si" else unit("N*m")
        lines += ["", f"## Energy balance, {energy}", "",
                  "Motor work and losses from the start; kinetic, elastic, top-drive and BHA energies at the end.",
                  "", "| term | value |", "|---|---:|"]
        lines += [f"| {name.replace('_', ' ')} | {num(value, 'N*m', digits=6)} |"
                  for name, value in result.energy.items()]
    lines += ["", "## Files", "",
              "- `series.parquet`, `series.csv`: t, surface_rpm, bit_rpm, motor_torque, bit_torque"
              + (" and the coupled run's bit_axial_speed (m/s), rop (m/h), weight_on_bit, hook_load (N), bit_depth, "
                 "depth_of_cut, block_position (m)" if result.axial else ""),
              "- `metrics.json`: the metrics above, window, status, energy balance",
              "- `fields.npz`: t, z, omega_rpm[t, z], torque_Nm[t, z] and the friction profile (with the well at "
              "the cells: inclination, azimuth, TVD, dogleg severity, friction factor)"
              + (" and the axial field: axial_z, axial_speed_m_s[t, z], axial_force_N[t, z] (compression +)"
                 if result.axial else ""),
              "- `config.toml`: the configuration solved (normalised: every default filled)"]
    if plots:
        lines += ["", "## Figures", ""]
        lines += [f"![{name[:-4].replace('_', ' ')}]({name})"
                  for name in (*PLOT_FILES, *(COUPLED_PLOT_FILES if result.axial else ()))]
    return "\n".join(lines) + "\n"
