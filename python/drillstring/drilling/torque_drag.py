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
radius (``contact_diameter / 2``, default the outer diameter's half). Validated against closed
forms (a straight inclined hole, the capstan on a weightless arc) and against welleng 0.30.0 on
``examples/s-well-3d.toml`` with its two defects corrected (``tests/reference/welleng``).
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

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

__all__ = ["OPERATIONS", "SUMMARY_KEYS", "TD_DATA_FILES", "TD_FILES", "TD_PLOT_FILES", "TorqueDragResult",
           "broomstick_figure", "profiles_figure", "torque_drag", "well_path_figure", "write_torque_drag"]

#: The operations, in the order of the profiles: pick-up, slack-off, rotating off bottom,
#: rotating on bottom.
OPERATIONS: tuple[str, ...] = ("pickup", "slackoff", "rotating", "rotating_on_bottom")
#: The summary numbers of ``torque_drag.json``.
SUMMARY_KEYS: tuple[str, ...] = (
    "hook_load_pickup_N", "hook_load_slackoff_N", "hook_load_rotating_N", "hook_load_rotating_on_bottom_N",
    "surface_torque_off_bottom_Nm", "surface_torque_on_bottom_Nm", "max_normal_force_N_per_m",
    "max_normal_force_md", "max_normal_force_operation",
)
#: The data files of a ``torque-drag`` output folder.
TD_DATA_FILES: tuple[str, ...] = ("torque_drag.json", "profiles.csv", "broomstick.csv", "survey.csv", "config.toml")
#: Its figures (skipped with ``--no-plots``).
TD_PLOT_FILES: tuple[str, ...] = ("torque_drag.png", "broomstick.png", "well_path.png")
TD_FILES: tuple[str, ...] = (*TD_DATA_FILES, *TD_PLOT_FILES)


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
        """The profiles as one table (``profiles.csv``): ``md_m`` and, per operation,
        ``{op}_tension_N``, ``{op}_torque_Nm``, ``{op}_normal_force_N_per_m``."""
        import pandas as pd

        columns: dict[str, np.ndarray] = {"md_m": self.profiles[OPERATIONS[0]]["md"]}
        for op in OPERATIONS:
            p = self.profiles[op]
            columns[f"{op}_tension_N"] = p["tension_N"]
            columns[f"{op}_torque_Nm"] = p["torque_Nm"]
            columns[f"{op}_normal_force_N_per_m"] = p["normal_force_N_per_m"]
        return pd.DataFrame(columns)

    def broomstick_frame(self) -> pd.DataFrame:
        """The broomstick hook loads as a long table (``broomstick.csv``): ``friction_factor``,
        ``bit_depth_m``, ``pickup_N``, ``slackoff_N``, ``rotating_N``."""
        import pandas as pd

        b = self.broomstick
        depth = np.asarray(b["depth_m"])
        rows = []
        for k, mu in enumerate(np.asarray(b["friction_factors"])):
            rows.append(pd.DataFrame({"friction_factor": np.full(depth.size, mu), "bit_depth_m": depth,
                                      "pickup_N": b["pickup"][k], "slackoff_N": b["slackoff"][k],
                                      "rotating_N": b["rotating"][k]}))
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
        return {
            **{k: self.summary[k] for k in SUMMARY_KEYS},
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
            },
        }


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
    summary = {k: raw[k] for k in SUMMARY_KEYS}
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
                      field: str = "out_dir", units: str = "si") -> list[Path]:
    """Writes ``torque_drag.json``, ``profiles.csv``, ``broomstick.csv``, ``survey.csv``,
    ``config.toml`` and (with ``plots``) ``torque_drag.png``, ``broomstick.png`` and
    ``well_path.png`` into ``out_dir``, with the folder rules of ``drillstring drill`` (checked
    first, locked while written, the complete set swapped in at the end so that an interrupted
    run leaves the old set, stale figures dropped, another command's folder refused). ``units``
    is the unit system of the figures (``"si"`` or ``"field"``); the data files are SI either way.
    Returns the paths written."""
    units = system_of(units, "units")
    names = TD_FILES if plots else TD_DATA_FILES
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
        if plots:
            from ..io.figures import save

            for name, make in zip(TD_PLOT_FILES, (profiles_figure, broomstick_figure, well_path_figure)):
                written.append(Path(os.fsdecode(os.fspath(save(make(result, units=units), path(name))))))
        os.unlink(marker)
    return [folder.shown(p) for p in written]


# --- figures -------------------------------------------------------------------------------------------------

_LABELS: Mapping[str, str] = {"pickup": "pick-up (tripping out)", "slackoff": "slack-off (tripping in)",
                              "rotating": "rotating off bottom", "rotating_on_bottom": "rotating on bottom"}
_COLOURS: Mapping[str, str] = {"pickup": "tab:red", "slackoff": "tab:blue", "rotating": "tab:green",
                               "rotating_on_bottom": "tab:purple"}


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def profiles_figure(result: TorqueDragResult, *, units: str = "si") -> Figure:
    """Effective tension (kN; klbf with ``units="field"``), torque (kN m; kft-lbf) and normal
    force per metre (N/m; lbf/ft) against measured depth (m; ft; down) for the four operations."""
    force, force_unit = axis_unit("N", units, kilo=True)
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    normal, normal_unit = axis_unit("N/m", units)
    depth, depth_unit = axis_unit("m", units)
    fig = _figure(12, 6.5)
    axes = fig.subplots(1, 3, sharey=True)
    for op in OPERATIONS:
        p = result.profiles[op]
        md = np.asarray(p["md"]) * depth
        kw = {"color": _COLOURS[op], "lw": 1.2, "label": _LABELS[op]}
        axes[0].plot(np.asarray(p["tension_N"]) * force, md, **kw)
        if op in ("rotating", "rotating_on_bottom"):
            axes[1].plot(np.asarray(p["torque_Nm"]) * torque, md, **kw)
        axes[2].plot(np.asarray(p["normal_force_N_per_m"]) * normal, md, **kw)
    axes[0].axvline(0.0, color="0.5", lw=0.8)
    for ax, label in zip(axes, (f"effective tension, {force_unit}", f"torque, {torque_unit}",
                                f"normal force, {normal_unit}")):
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(f"measured depth, {depth_unit}")
    axes[0].invert_yaxis()
    axes[0].legend(fontsize=8, loc="lower left")
    s = result.summary
    fig.suptitle(f"soft-string torque and drag: hook load pick-up {s['hook_load_pickup_N'] * force:.0f} "
                 f"{force_unit}, slack-off {s['hook_load_slackoff_N'] * force:.0f} {force_unit}, rotating "
                 f"{s['hook_load_rotating_N'] * force:.0f} {force_unit}; surface torque "
                 f"{s['surface_torque_off_bottom_Nm'] * torque:.1f} (off) / "
                 f"{s['surface_torque_on_bottom_Nm'] * torque:.1f} (on bottom) {torque_unit}", fontsize=10)
    return fig


def broomstick_figure(result: TorqueDragResult, *, units: str = "si") -> Figure:
    """The broomstick plot: hook load (kN; klbf with ``units="field"``) against bit depth (m;
    ft; down) while tripping out (pick-up), in (slack-off) and rotating, one line per friction
    factor."""
    force, force_unit = axis_unit("N", units, kilo=True)
    scale, depth_unit = axis_unit("m", units)
    fig = _figure(7.5, 7.0)
    ax = fig.subplots()
    b = result.broomstick
    depth = np.asarray(b["depth_m"]) * scale
    ax.plot(np.asarray(b["rotating"][0]) * force, depth, color="k", lw=1.4, label="rotating")
    for k, mu in enumerate(np.asarray(b["friction_factors"])):
        alpha = 0.35 + 0.65 * (k + 1) / max(1, len(b["friction_factors"]))
        ax.plot(np.asarray(b["pickup"][k]) * force, depth, color="tab:red", alpha=alpha, lw=1.1,
                label=f"pick-up, mu {mu:g}")
        ax.plot(np.asarray(b["slackoff"][k]) * force, depth, color="tab:blue", alpha=alpha, lw=1.1, ls="--",
                label=f"slack-off, mu {mu:g}")
    ax.set_xlabel(f"hook load, {force_unit} (with the block weight)")
    ax.set_ylabel(f"bit depth, {depth_unit} (measured)")
    ax.invert_yaxis()
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="lower left")
    ax.set_title("broomstick plot: hook load while tripping")
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
