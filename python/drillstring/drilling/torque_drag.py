"""Static soft-string torque and drag of a drilling configuration (``ds.torque_drag``,
``drillstring torque-drag CONFIG.toml --out DIR``).

The core computes everything (``drillstring_core::well``): the minimum-curvature trajectory of
the well's survey, and Johancsik's soft-string model stepped from the bit up (Johancsik, Friesen
& Dawson 1984, SPE 11380) for four operations: pick-up (tripping out), slack-off (tripping in),
rotating off bottom and rotating on bottom (the bit carrying ``bit.weight_on_bit`` and
``torque_drag.bit_torque``). This module returns the result, writes it and draws it.

Conventions: tensions are **effective** tensions (the buoyed weight ``(rho - rho_mud) g A`` per
metre, mud inside and outside); hook loads are the surface tension plus
``torque_drag.block_weight`` and exclude sheave friction; while rotating all the wall friction
is torque (no axial drag); friction factors are ``friction.static``, or those of
``[[friction.intervals]]`` over their depths; the torque lever arm is each section's contact
radius (``contact_diameter / 2``; default half the tool joints' outer diameter when the section
has tool joints, which touch the wall, else half the outer diameter). Validated against closed
forms (a straight inclined hole, the capstan on a weightless arc) and against welleng 0.30.0 on
``examples/s-well-3d.toml`` with its two defects corrected (``tests/reference/welleng``).
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from .. import _core
from ..io.output import atomic_write, write_text
from .output import MARKER as _MARKER
from .output import output_folder
from .units import axis_unit, system_of

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from matplotlib.figure import Figure

    from .config import DrillConfig

__all__ = ["LIMIT_KEYS", "MEASURED_OPERATIONS", "NO_BUCKLING", "OPERATIONS", "SUMMARY_KEYS", "TD_DATA_FILES",
           "TD_FILES", "TD_MEASURED_FILE", "TD_PLOT_FILES", "TorqueDragResult", "broomstick_figure", "profiles_figure",
           "torque_drag", "utilisation_figure", "well_path_figure", "write_torque_drag"]

#: The operations, in the order of the profiles: pick-up, slack-off, rotating off bottom,
#: rotating on bottom, sliding (lowering without rotation, the bit carrying the weight on bit).
OPERATIONS: tuple[str, ...] = ("pickup", "slackoff", "rotating", "rotating_on_bottom", "sliding")
#: The names of the operations in a file of measured points (``--measured``), each mapped to
#: the name of :data:`OPERATIONS` (which a file may use too).
MEASURED_OPERATIONS: Mapping[str, str] = {
    "pick_up": "pickup", "slack_off": "slackoff", "rotating_off_bottom": "rotating",
    "rotating_on_bottom": "rotating_on_bottom", "sliding": "sliding",
    **{op: op for op in ("pickup", "slackoff", "rotating")},
}
#: The summary numbers of ``torque_drag.json``.
SUMMARY_KEYS: tuple[str, ...] = (
    "hook_load_pickup_N", "hook_load_slackoff_N", "hook_load_rotating_N", "hook_load_rotating_on_bottom_N",
    "hook_load_sliding_N", "surface_torque_off_bottom_Nm", "surface_torque_on_bottom_Nm", "max_normal_force_N_per_m",
    "max_normal_force_md", "max_normal_force_operation",
)
#: The buckling, lock-up and limits of ``torque_drag.json`` (``null`` where not evaluated: no
#: hole diameter, no grade, no make-up torque).
LIMIT_KEYS: tuple[str, ...] = (
    "buckling_evaluated", "first_buckling", "lockup", "max_set_down_N", "max_weight_on_bit_N", "max_utilisation",
    "max_utilisation_md", "max_utilisation_operation", "max_torque_over_makeup", "max_torque_over_makeup_md",
    "max_torque_over_makeup_operation", "overpull_margin_N", "closest_limit", "closest_limit_ratio",
)
#: What the console and ``torque_drag.json`` say without a hole diameter.
NO_BUCKLING = "no hole diameter: buckling not evaluated"
#: The limits' names in words.
LIMIT_WORDS: Mapping[str, str] = {"utilisation": "von Mises utilisation (stress over yield)",
                                  "makeup_torque": "torque over the tool joints' make-up torque",
                                  "overpull": "pick-up load over the top section's tensile yield"}
#: The data files of a ``torque-drag`` output folder.
TD_DATA_FILES: tuple[str, ...] = ("torque_drag.json", "profiles.csv", "broomstick.csv", "survey.csv", "config.toml",
                                  "report.md")
#: Its figures (skipped with ``--no-plots``).
TD_PLOT_FILES: tuple[str, ...] = ("torque_drag.png", "broomstick.png", "well_path.png", "utilisation.png")
#: The implied friction factors of ``--measured`` points (written only with them).
TD_MEASURED_FILE = "measured.csv"
TD_FILES: tuple[str, ...] = (*TD_DATA_FILES, TD_MEASURED_FILE, *TD_PLOT_FILES)


@dataclass(frozen=True)
class TorqueDragResult:
    """The torque and drag of a configuration.

    ``summary`` holds :data:`SUMMARY_KEYS` (N, N m, N/m, m); ``profiles[op]`` (``op`` in
    :data:`OPERATIONS`) the arrays ``md`` (m, surface to bit), ``tension_N`` (effective;
    negative is compression), ``torque_Nm`` and ``normal_force_N_per_m`` (of the element below
    each node); ``broomstick`` the bit depths ``depth_m``, the ``friction_factors`` and the hook
    loads ``pickup``, ``slackoff``, ``rotating`` (N, arrays ``[factor, depth]``); ``trajectory``
    the survey stations with ``north``, ``east``, ``tvd`` (m) and ``dls_deg_per_30m``."""

    config: DrillConfig
    summary: dict[str, Any]
    profiles: dict[str, dict[str, np.ndarray]]
    broomstick: dict[str, np.ndarray]
    trajectory: dict[str, np.ndarray]
    contact: str = field(default="soft_string")

    def __getattr__(self, name: str) -> Any:
        summary = self.__dict__.get("summary", {})
        if name in summary:
            return summary[name]
        raise AttributeError(name)

    def profiles_frame(self) -> pd.DataFrame:
        """The profiles as one table (``profiles.csv``): ``md_m``; with a hole diameter the
        critical loads ``sinusoidal_buckling_load_N`` and ``helical_buckling_load_N``
        (compressive, of the element below each depth); per operation ``{op}_tension_N``,
        ``{op}_torque_Nm``, ``{op}_normal_force_N_per_m``, ``{op}_side_force_per_joint_N``, with a
        hole diameter ``{op}_buckling`` (``none``, ``sinusoidal``, ``helical``) and with a grade
        ``{op}_utilisation``."""
        import pandas as pd

        first = self.profiles[OPERATIONS[0]]
        columns: dict[str, Any] = {"md_m": first["md"]}
        for key in ("sinusoidal_buckling_load_N", "helical_buckling_load_N"):
            if len(first[key]):
                columns[key] = first[key]
        for op in OPERATIONS:
            p = self.profiles[op]
            columns[f"{op}_tension_N"] = p["tension_N"]
            columns[f"{op}_torque_Nm"] = p["torque_Nm"]
            columns[f"{op}_normal_force_N_per_m"] = p["normal_force_N_per_m"]
            columns[f"{op}_side_force_per_joint_N"] = p["side_force_per_joint_N"]
            if len(p["buckling"]):
                columns[f"{op}_buckling"] = list(p["buckling"])
            if len(p["utilisation"]):
                columns[f"{op}_utilisation"] = p["utilisation"]
        return pd.DataFrame(columns)

    def broomstick_frame(self) -> pd.DataFrame:
        """The broomstick hook loads as a long table (``broomstick.csv``): ``friction_factor``,
        ``bit_depth_m``, ``pickup_N``, ``slackoff_N``, ``rotating_N`` and the rotating surface
        torque ``torque_rotating_Nm``."""
        import pandas as pd

        b = self.broomstick
        depth = np.asarray(b["depth_m"])
        rows = []
        for k, mu in enumerate(np.asarray(b["friction_factors"])):
            rows.append(pd.DataFrame({"friction_factor": np.full(depth.size, mu), "bit_depth_m": depth,
                                      "pickup_N": b["pickup"][k], "slackoff_N": b["slackoff"][k],
                                      "rotating_N": b["rotating"][k],
                                      "torque_rotating_Nm": b["torque_rotating"][k]}))
        return pd.concat(rows, ignore_index=True)

    def survey_frame(self) -> pd.DataFrame:
        """The stations and their positions (``survey.csv``)."""
        import pandas as pd

        t = self.trajectory
        return pd.DataFrame({"md_m": t["md"], "inc_deg": t["inc_deg"], "azi_deg": t["azi_deg"],
                             "north_m": t["north"], "east_m": t["east"], "tvd_m": t["tvd"],
                             "dls_deg_per_30m": t["dls_deg_per_30m"]})

    def to_json_dict(self) -> dict[str, Any]:
        """``torque_drag.json``: the summary, the conventions and the inputs that set them."""
        cfg = self.config
        limits = {k: _finite(self.summary[k]) for k in LIMIT_KEYS}
        if not self.summary["buckling_evaluated"]:
            limits["buckling_note"] = NO_BUCKLING
        return {
            **{k: _finite(self.summary[k]) for k in SUMMARY_KEYS},
            **limits,
            "bit_depth_m": float(self.profiles[OPERATIONS[0]]["md"][-1]),
            "weight_on_bit_N": cfg.bit.weight_on_bit,
            "bit_torque_Nm": cfg.torque_drag.bit_torque,
            "block_weight_N": cfg.torque_drag.block_weight,
            "conventions": {
                "model": "soft string, Johancsik et al. 1984 (SPE 11380), stepped from the bit up",
                "tension": "effective tension: buoyed weight (rho - rho_mud) g A per metre",
                "hook_load": "surface tension + block_weight; sheave friction excluded",
                "rotating": "all wall friction is torque (no axial drag)",
                "trajectory": "minimum curvature",
                "buckling": "critical loads Dawson & Paslay 1984 (sinusoidal), Chen, Lin & Cheatham 1990 (helical) "
                            "on the soft-string lateral load at the critical compression (curved hole), not below "
                            "the vertical string's 2.55 and 5.55 (E I w^2)^(1/3); helical contact Mitchell 1986 "
                            "r_c F^2 / (4 E I) added to the drag",
                "lockup": "the bit load needs the surface to push (surface effective tension below 0)",
                "utilisation": "von Mises of the true axial force and torque on the pipe body over the minimum "
                               "yield strength (API RP 7G, ISO 10407)",
            },
        }

    def report_lines(self, units: str = "si") -> list[str]:
        """The buckling, lock-up and limits in words (the console's lines and ``report.md``)."""
        s = self.summary
        force, force_unit = axis_unit("N", units, kilo=True)
        depth, depth_unit = axis_unit("m", units)
        lines = []
        if not s["buckling_evaluated"]:
            lines.append(NO_BUCKLING)
        else:
            for op in OPERATIONS:
                first = s["first_buckling"][op]
                kinds = [f"{kind} from {first[kind + '_md'] * depth:.0f} {depth_unit}"
                         for kind in ("sinusoidal", "helical") if first[kind + "_md"] is not None]
                lines.append(f"buckling {op}: {', '.join(kinds) if kinds else 'none'}")
        locked = [op for op, v in s["lockup"].items() if v]
        wob = s["max_weight_on_bit_N"]
        on_bit = f"{wob * force:.1f} {force_unit} on the bit" if wob is not None else "an unbounded load on the bit"
        lines.append(f"lock-up: {', '.join(locked) if locked else 'none'}; the largest set-down reaching the bit "
                     f"{s['max_set_down_N'] * force:.1f} {force_unit} puts {on_bit}")
        if s["closest_limit"] is None:
            lines.append("limits: no grade, yield strength or make-up torque given: not evaluated")
        else:
            if s["max_utilisation"] is not None:
                lines.append(f"utilisation: largest {s['max_utilisation']:.3f} at "
                             f"{s['max_utilisation_md'] * depth:.0f} {depth_unit} ({s['max_utilisation_operation']})")
            if s["max_torque_over_makeup"] is not None:
                lines.append(f"torque over make-up torque: largest {s['max_torque_over_makeup']:.3f} at "
                             f"{s['max_torque_over_makeup_md'] * depth:.0f} {depth_unit} "
                             f"({s['max_torque_over_makeup_operation']})")
            if s["overpull_margin_N"] is not None:
                lines.append(f"overpull margin at the surface: {s['overpull_margin_N'] * force:.1f} {force_unit}")
            lines.append(f"closest limit: {LIMIT_WORDS[s['closest_limit']]}, {s['closest_limit_ratio']:.3f} of it")
        return lines


def _finite(value: Any) -> Any:
    """``value`` with a non-finite number as None (JSON has no infinity: a locked-up hook load)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def torque_drag(config: Union[DrillConfig, str, os.PathLike[str]]) -> TorqueDragResult:
    """The static soft-string torque and drag of ``config`` (a :class:`DrillConfig` or the path
    of its TOML), for pick-up, slack-off, rotating off bottom and rotating on bottom, and the
    broomstick hook loads over bit depth for ``torque_drag.friction_factors``.

    >>> import drillstring as ds
    >>> td = ds.torque_drag("examples/s-well-3d.toml")             # doctest: +SKIP
    >>> round(td.hook_load_pickup_N / 1e3)                          # doctest: +SKIP
    1725
    """
    from .config import DrillConfig, load_drill_config

    cfg = config if isinstance(config, DrillConfig) else load_drill_config(config)
    text = cfg.to_json()
    raw = _core.well_torque_drag(text)
    trajectory = _core.well_trajectory(text)
    summary = {k: raw[k] for k in (*SUMMARY_KEYS, *LIMIT_KEYS)}
    return TorqueDragResult(config=cfg, summary=summary, profiles=dict(raw["profiles"]),
                            broomstick=dict(raw["broomstick"]), trajectory=dict(trajectory))


# --- output folder -------------------------------------------------------------------------------------------


def _csv(frame: pd.DataFrame, tmp: str) -> None:
    frame.to_csv(tmp, index=False, float_format="%.10g")


def owned(name: str) -> bool:
    """Whether ``name`` is a file of a ``torque-drag`` folder (:data:`TD_FILES`, the marker):
    replaced by each run; the folder's other entries are kept."""
    return name in TD_FILES or name == _MARKER


def write_torque_drag(result: TorqueDragResult, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
                      field: str = "out_dir", units: str = "si", measured: Optional[pd.DataFrame] = None) -> list[Path]:
    """Writes ``torque_drag.json``, ``profiles.csv``, ``broomstick.csv``, ``survey.csv``,
    ``config.toml`` and (with ``plots``) ``torque_drag.png``, ``broomstick.png`` and
    ``well_path.png`` into ``out_dir``, with the folder rules of ``drillstring drill`` (checked
    first, locked while written, the complete set swapped in at the end so that an interrupted
    run leaves the old set, stale figures dropped, another command's folder refused). ``units``
    is the unit system of the figures (``"si"`` or ``"field"``); the data files are SI either way.
    With ``measured`` (the table of
    :func:`drillstring.calibration.td_measured.implied_friction`) also ``measured.csv`` and the
    points on the broomstick figure. Returns the paths written."""
    units = system_of(units, "units")
    names = (*TD_DATA_FILES, *((TD_MEASURED_FILE,) if measured is not None else ()), *(TD_PLOT_FILES if plots else ()))
    with output_folder(out_dir, field=field, command="torque-drag", names=names, owns=owned) as folder:
        def path(name: str) -> str:
            return os.path.join(os.fspath(folder.directory), name)

        marker = path(_MARKER)
        write_text(marker, f"drillstring torque-drag (process {os.getpid()}) is writing this folder. If this file "
                   "is still here, that run did not finish.\n")
        for name in TD_FILES:
            if name not in names and os.path.lexists(path(name)) and not os.path.isdir(path(name)):
                os.unlink(path(name))
        written = [write_text(path("torque_drag.json"), json.dumps(result.to_json_dict(), indent=2) + "\n")]
        for name, frame in (("profiles.csv", result.profiles_frame()), ("broomstick.csv", result.broomstick_frame()),
                            ("survey.csv", result.survey_frame())):
            written.append(atomic_write(path(name), partial(_csv, frame), suffix=".csv"))
        written.append(write_text(path("config.toml"), result.config.to_toml()))
        written.append(write_text(path("report.md"), _report(result, units)))
        if measured is not None:
            written.append(atomic_write(path(TD_MEASURED_FILE), partial(_csv, measured), suffix=".csv"))
        if plots:
            from ..io.figures import save

            makers: tuple[Callable[..., Figure], ...] = (profiles_figure, partial(broomstick_figure, measured=measured),
                                                         well_path_figure, utilisation_figure)
            for name, make in zip(TD_PLOT_FILES, makers):
                written.append(Path(os.fsdecode(os.fspath(save(make(result, units=units), path(name))))))
        os.unlink(marker)
    return [folder.shown(p) for p in written]


def _report(result: TorqueDragResult, units: str) -> str:
    """``report.md``: the hook loads, torques, buckling, lock-up and the closest limit."""
    s = result.summary
    force, force_unit = axis_unit("N", units, kilo=True)
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    hook = ", ".join(f"{op} {s[f'hook_load_{op}_N'] * force:.1f} {force_unit}" if math.isfinite(s[f"hook_load_{op}_N"])
                     else f"{op} locked up" for op in OPERATIONS)
    lines = ["# Torque and drag", "", f"- hook load: {hook}",
             f"- surface torque: off bottom {s['surface_torque_off_bottom_Nm'] * torque:.2f} {torque_unit}, on bottom "
             f"{s['surface_torque_on_bottom_Nm'] * torque:.2f} {torque_unit}"]
    lines += [f"- {line}" for line in result.report_lines(units)]
    return "\n".join(lines) + "\n"


# --- figures -------------------------------------------------------------------------------------------------

_LABELS: Mapping[str, str] = {"pickup": "pick-up (tripping out)", "slackoff": "slack-off (tripping in)",
                              "rotating": "rotating off bottom", "rotating_on_bottom": "rotating on bottom",
                              "sliding": "sliding"}
_COLOURS: Mapping[str, str] = {"pickup": "tab:red", "slackoff": "tab:blue", "rotating": "tab:green",
                               "rotating_on_bottom": "tab:purple", "sliding": "tab:brown"}


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def profiles_figure(result: TorqueDragResult, *, units: str = "si") -> Figure:
    """Effective tension (kN; klbf with ``units="field"``) with the buckling bands (between the
    sinusoidal and the helical critical load, and beyond it, drawn as compression), torque (kN
    m; kft-lbf), normal force per metre (N/m; lbf/ft) and side force per joint (kN; klbf)
    against measured depth (m; ft; down) for the five operations."""
    force, force_unit = axis_unit("N", units, kilo=True)
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    normal, normal_unit = axis_unit("N/m", units)
    depth, depth_unit = axis_unit("m", units)
    fig = _figure(15, 6.5)
    axes = fig.subplots(1, 4, sharey=True)
    first = result.profiles[OPERATIONS[0]]
    if len(first["sinusoidal_buckling_load_N"]):
        md = np.asarray(first["md"]) * depth
        fs = -np.asarray(first["sinusoidal_buckling_load_N"]) * force
        fh = -np.asarray(first["helical_buckling_load_N"]) * force
        tensions = np.concatenate([np.asarray(result.profiles[op]["tension_N"]) for op in OPERATIONS]) * force
        tensions = tensions[np.isfinite(tensions)]
        left = min(1.1 * float(tensions.min()), -0.3 * float(tensions.max()))
        axes[0].fill_betweenx(md, fh, fs, color="tab:orange", alpha=0.25, lw=0, label="sinusoidal buckling")
        axes[0].fill_betweenx(md, np.minimum(fh, left), fh, color="tab:red", alpha=0.12, lw=0,
                              label="helical buckling")
        axes[0].set_xlim(left, 1.05 * float(tensions.max()))
    for op in OPERATIONS:
        p = result.profiles[op]
        md = np.asarray(p["md"]) * depth
        kw = {"color": _COLOURS[op], "lw": 1.2, "label": _LABELS[op]}
        axes[0].plot(np.asarray(p["tension_N"]) * force, md, **kw)
        if op in ("rotating", "rotating_on_bottom"):
            axes[1].plot(np.asarray(p["torque_Nm"]) * torque, md, **kw)
        axes[2].plot(np.asarray(p["normal_force_N_per_m"]) * normal, md, **kw)
        axes[3].plot(np.asarray(p["side_force_per_joint_N"]) * force, md, **kw)
    axes[0].axvline(0.0, color="0.5", lw=0.8)
    for ax, label in zip(axes, (f"effective tension, {force_unit}", f"torque, {torque_unit}",
                                f"normal force, {normal_unit}", f"side force per joint, {force_unit}")):
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(f"measured depth, {depth_unit}")
    axes[0].invert_yaxis()
    axes[0].legend(fontsize=7, loc="lower left")
    s = result.summary
    fig.suptitle(f"soft-string torque and drag: hook load pick-up {s['hook_load_pickup_N'] * force:.0f} "
                 f"{force_unit}, slack-off {s['hook_load_slackoff_N'] * force:.0f} {force_unit}, rotating "
                 f"{s['hook_load_rotating_N'] * force:.0f} {force_unit}; surface torque "
                 f"{s['surface_torque_off_bottom_Nm'] * torque:.1f} (off) / "
                 f"{s['surface_torque_on_bottom_Nm'] * torque:.1f} (on bottom) {torque_unit}", fontsize=10)
    return fig


def broomstick_figure(result: TorqueDragResult, *, units: str = "si", measured: Any = None) -> Figure:
    """The broomstick plots: hook load (kN; klbf with ``units="field"``) while tripping out
    (pick-up), in (slack-off) and rotating, and the rotating surface torque (kN m; kft-lbf),
    against bit depth (m; ft; down), one line per friction factor; ``measured`` points (a table
    of ``depth_m``, ``operation``, ``hook_load_N``, ``surface_torque_Nm``, ``friction_factor``)
    drawn on them with their implied factors."""
    force, force_unit = axis_unit("N", units, kilo=True)
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    scale, depth_unit = axis_unit("m", units)
    fig = _figure(12, 7.0)
    ax, ax_t = fig.subplots(1, 2, sharey=True)
    b = result.broomstick
    depth = np.asarray(b["depth_m"]) * scale
    ax.plot(np.asarray(b["rotating"][0]) * force, depth, color="k", lw=1.4, label="rotating")
    factors = np.asarray(b["friction_factors"])
    for k, mu in enumerate(factors):
        alpha = 0.35 + 0.65 * (k + 1) / max(1, len(factors))
        ax.plot(np.asarray(b["pickup"][k]) * force, depth, color="tab:red", alpha=alpha, lw=1.1,
                label=f"pick-up, mu {mu:g}")
        ax.plot(np.asarray(b["slackoff"][k]) * force, depth, color="tab:blue", alpha=alpha, lw=1.1, ls="--",
                label=f"slack-off, mu {mu:g}")
        ax_t.plot(np.asarray(b["torque_rotating"][k]) * torque, depth, color="tab:green", alpha=alpha, lw=1.1,
                  label=f"rotating off bottom, mu {mu:g}")
    if measured is not None and len(measured):
        for op, marker in zip(OPERATIONS, ("^", "v", "o", "s", "D")):
            rows = measured[measured["operation"] == op]
            if not len(rows):
                continue
            d = np.asarray(rows["depth_m"], dtype=float) * scale
            mu = np.asarray(rows["friction_factor"], dtype=float)
            target, values, unit_scale = ((ax_t, rows["surface_torque_Nm"], torque) if op.startswith("rotating")
                                          else (ax, rows["hook_load_N"], force))
            x = np.asarray(values, dtype=float) * unit_scale
            target.scatter(x, d, marker=marker, color=_COLOURS[op], edgecolor="k", zorder=5, s=30,
                           label=f"measured, {_LABELS[op]}")
            for xi, di, m in zip(x, d, mu):
                if np.isfinite(xi) and np.isfinite(m):
                    target.annotate(f"{m:.2f}", (xi, di), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel(f"hook load, {force_unit} (with the block weight)")
    ax_t.set_xlabel(f"surface torque, {torque_unit}")
    ax.set_ylabel(f"bit depth, {depth_unit} (measured)")
    ax.invert_yaxis()
    for a in (ax, ax_t):
        a.grid(alpha=0.3)
        a.legend(fontsize=7, ncol=2, loc="lower left")
    ax.set_title("broomstick plot: hook load while tripping")
    ax_t.set_title("broomstick plot: surface torque")
    return fig


def utilisation_figure(result: TorqueDragResult, *, units: str = "si") -> Figure:
    """The von Mises utilisation (stress over the yield strength) against measured depth (m; ft
    with ``units="field"``) for the five operations, with the limit at 1; without a grade a note
    that it is not evaluated."""
    depth, depth_unit = axis_unit("m", units)
    fig = _figure(6.5, 6.5)
    ax = fig.subplots()
    evaluated = False
    for op in OPERATIONS:
        p = result.profiles[op]
        if len(p["utilisation"]):
            evaluated = True
            ax.plot(np.asarray(p["utilisation"]), np.asarray(p["md"]) * depth, color=_COLOURS[op], lw=1.2,
                    label=_LABELS[op])
    ax.axvline(1.0, color="k", lw=1.2, ls="--", label="yield (utilisation 1)")
    if not evaluated:
        ax.text(0.5, 0.5, "no grade or yield strength:\nutilisation not evaluated", transform=ax.transAxes,
                ha="center", va="center")
    ax.set_xlabel("utilisation: von Mises stress / yield strength")
    ax.set_ylabel(f"measured depth, {depth_unit}")
    ax.invert_yaxis()
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title("pipe-body utilisation (API RP 7G, ISO 10407)")
    return fig


def well_path_figure(result: TorqueDragResult, *, units: str = "si") -> Figure:
    """The well path: plan view (east, north) and vertical section (horizontal departure,
    TVD), with the dogleg severity along measured depth (m and deg/30 m; ft and deg/100 ft with
    ``units="field"``)."""
    scale, length_unit = axis_unit("m", units)
    dls, dls_unit = axis_unit("deg/(30 m)", units)
    fig = _figure(12, 4.8)
    ax_plan, ax_section, ax_dls = fig.subplots(1, 3)
    t = result.trajectory
    north, east, tvd = (np.asarray(t[k]) * scale for k in ("north", "east", "tvd"))
    ax_plan.plot(east, north, color="tab:blue")
    ax_plan.set_xlabel(f"east, {length_unit}")
    ax_plan.set_ylabel(f"north, {length_unit}")
    ax_plan.set_aspect("equal", adjustable="datalim")
    ax_plan.set_title("plan view")
    ax_section.plot(np.hypot(north, east), tvd, color="tab:blue")
    ax_section.invert_yaxis()
    ax_section.set_xlabel(f"horizontal departure, {length_unit}")
    ax_section.set_ylabel(f"TVD, {length_unit}")
    ax_section.set_title("vertical section")
    ax_dls.step(np.asarray(t["md"]) * scale, np.asarray(t["dls_deg_per_30m"]) * dls, where="pre", color="tab:orange")
    ax_dls.set_xlabel(f"measured depth, {length_unit}")
    ax_dls.set_ylabel(f"dogleg severity, {dls_unit}")
    ax_dls.set_title("dogleg severity")
    for ax in (ax_plan, ax_section, ax_dls):
        ax.grid(alpha=0.3)
    return fig
