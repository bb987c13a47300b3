"""What the live page shows and how: the log tracks against time, the views along the string, the
controls, each with its label, the unit it is shown in and the factor from the SI value the
server sends (:func:`~drillstring.drilling.units.axis_unit`: the page multiplies, never
converts on its own); the decimation of the series to what the page draws; the verdict of a
window of the run."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from ..drilling.units import axis_unit

__all__ = ["PROFILES", "TRACKS", "Channel", "choices", "controls", "decimate", "describe", "verdict"]


@dataclass(frozen=True)
class Channel:
    """A quantity of the display: a series column (a track) or a field of ``state()`` (a view along
    the string), in the SI ``unit`` of the core, shown in thousands with ``kilo``; ``coupled``
    only in a coupled run (``[hoist]``)."""

    name: str
    label: str
    unit: str
    kilo: bool = False
    coupled: bool = False
    group: str = "surface"

    def shown(self, system: str) -> dict[str, Any]:
        """The channel as the page reads it in the unit ``system``: name, label, unit, factor."""
        factor, unit = axis_unit(self.unit, system, kilo=self.kilo)
        return {"name": self.name, "label": self.label, "unit": unit, "factor": factor, "group": self.group}


#: The log tracks against time, surface first, as on the rig floor; series columns by the core's names.
TRACKS: tuple[Channel, ...] = (
    Channel("surface_rpm", "surface rpm", "rpm"),
    Channel("motor_torque", "surface torque", "N*m", kilo=True),
    Channel("hook_load", "hook load", "N", kilo=True, coupled=True),
    Channel("block_position", "block position (down)", "m", coupled=True),
    Channel("bit_depth", "bit depth drilled", "m", coupled=True),
    Channel("weight_on_bit", "WOB", "N", kilo=True, coupled=True),
    Channel("rop", "ROP", "m/h", coupled=True),
    Channel("bit_rpm", "bit rpm", "rpm", group="downhole"),
    Channel("bit_torque", "torque on bit", "N*m", kilo=True, group="downhole"),
)

#: The views along the string (``state()``'s fields against ``z_m``, or ``axial_z_m`` for the axial ones).
PROFILES: tuple[Channel, ...] = (
    Channel("omega_rpm", "angular speed", "rpm", group="z_m"),
    Channel("torque_Nm", "torque", "N*m", kilo=True, group="z_m"),
    Channel("axial_force_N", "axial force (compression +)", "N", kilo=True, coupled=True, group="axial_z_m"),
    Channel("contact_N_per_m", "wall contact force", "N/m", group="z_m"),
)

#: The setpoints the page offers a slider for, with the slider's range in SI (the core checks the value).
SETPOINTS: dict[str, tuple[str, str, float, float, bool]] = {
    # key: (label, SI unit, low, high, kilo)
    "top_drive.rpm": ("rpm setpoint", "rpm", 0.0, 250.0, False),
    "bit.weight_on_bit": ("weight on bit", "N", 0.0, 300e3, True),
    "hoist.weight_on_bit": ("WOB setpoint", "N", 0.0, 300e3, True),
    "hoist.hook_load": ("hook load setpoint", "N", 0.0, 3e6, True),
    "hoist.speed": ("block speed", "m/s", -0.05, 0.05, False),
}

#: The keys offered as a choice among the names the configuration reference lists.
CHOICES: dict[str, str] = {"top_drive.controller.type": "controller type",
                           "top_drive.controller.preset": "controller preset (gains)"}
#: The controller keys a preset sets during a run (its type and gains).
PRESET_KEYS: tuple[str, ...] = ("type", "kp", "ki", "z_factor")


def choices(key: str) -> list[str]:
    """The names a text key takes, as the configuration reference lists them ("One of: a, b.")."""
    from ..drilling.config import config_schema

    description = str(config_schema()[key]["description"])
    _, sep, tail = description.rpartition("One of: ")
    return [name.strip() for name in tail.rstrip(".").split(",")] if sep else []


def _current(config: Any, key: str) -> Any:
    value: Any = config
    for part in key.split("."):
        value = getattr(value, part, None)
    return value


#: The hoist's setpoint key of each hoist mode.
HOIST_SETPOINT: dict[str, str] = {"velocity": "hoist.speed", "hook_load": "hoist.hook_load",
                                  "weight_on_bit": "hoist.weight_on_bit"}


def _relevant(key: str, config: Any) -> bool:
    """Whether the page offers ``key`` for ``config``: the hoist's setpoint of its mode in a
    coupled run, the velocity-weakening bit's weight in a torsion-only one."""
    hoist = getattr(config, "hoist", None)
    if key.startswith("hoist."):
        return hoist is not None and HOIST_SETPOINT.get(str(hoist.mode)) == key
    if key == "bit.weight_on_bit":
        return hoist is None
    return True


def controls(settable: Sequence[str], config: Any, system: str,
             values: Optional[Mapping[str, Any]] = None) -> list[dict[str, Any]]:
    """The page's controls of the keys the session can change (``settable``): a slider with a number
    field for each setpoint (range, value and unit shown in ``system``), a choice for the
    controller's type and, with its gains settable, of a preset (``kind = "preset"``, which the
    driver applies as the preset's gains for this string). ``values``: the keys changed so far
    (SI), shown in place of the configuration's."""
    values = values or {}
    out: list[dict[str, Any]] = []
    for key in settable:
        if not _relevant(key, config):
            continue
        if key in SETPOINTS:
            label, unit, low, high, kilo = SETPOINTS[key]
            factor, shown = axis_unit(unit, system, kilo=kilo)
            value = values[key] if key in values else _current(config, key)
            value = float(value) if isinstance(value, (int, float)) and math.isfinite(value) else low
            out.append({"key": key, "kind": "slider", "label": label, "unit": shown, "factor": factor,
                        "min": min(low, value), "max": max(high, value), "value": value})
        elif key in CHOICES:
            value = values[key] if key in values else _current(config, key)
            names = choices(key)
            out.append({"key": key, "kind": "choice", "label": CHOICES[key],
                        "choices": names, "value": None if value is None else str(value)})
    if {f"top_drive.controller.{k}" for k in PRESET_KEYS} <= set(settable):
        key = "top_drive.controller.preset"
        out.append({"key": key, "kind": "preset", "label": CHOICES[key], "choices": choices(key), "value": None})
    return out


def describe(coupled: bool, system: str) -> dict[str, Any]:
    """The tracks and the views of a run (a coupled run's too), in the unit ``system``, and the depth
    axis."""
    depth_factor, depth_unit = axis_unit("m", system)
    return {
        "tracks": [c.shown(system) for c in TRACKS if coupled or not c.coupled],
        "profiles": [c.shown(system) for c in PROFILES if coupled or not c.coupled],
        "depth": {"factor": depth_factor, "unit": depth_unit},
        "time": {"factor": 1.0, "unit": "s"},
    }


def decimate(t: np.ndarray, step: float, last: float) -> np.ndarray:
    """The indices of the rows at times ``t`` that the page draws at one point per ``step`` of
    time: the first row of each interval ``[k step, (k + 1) step)`` after the interval of the
    time ``last`` (the last row drawn; ``-inf`` before any)."""
    if t.size == 0:
        return np.zeros(0, dtype=np.int64)
    bucket = np.floor(t / step)
    before = np.floor(last / step) if math.isfinite(last) else -np.inf
    previous = np.concatenate(([before], bucket[:-1]))
    return np.nonzero(bucket > previous)[0]


def verdict(metrics: Mapping[str, Any], window: tuple[float, float], coupled: bool, system: str) -> dict[str, Any]:
    """What the page says of a window of the run, as ``drillstring drill`` says it on the console:
    the stick-slip verdict and the registry's console metrics by their labels in ``system``
    (:func:`~drillstring.drilling.units.metric_texts`), and a coupled run's on-bottom metrics and
    regime."""
    from ..drilling.metrics import OUTPUTS, REGIME, STICK_SLIP_VERDICT
    from ..drilling.units import metric_texts

    def texts(values: Mapping[str, Any], run: str) -> list[str]:
        names = [n for n, o in OUTPUTS.items() if o.console and run in o.runs and n in values]
        return metric_texts({n: math.nan if values[n] is None else values[n] for n in names}, names, system)

    out: dict[str, Any] = {
        "window": [float(window[0]), float(window[1])],
        "verdict": str(metrics.get(STICK_SLIP_VERDICT, "")),
        "texts": texts(metrics, "torsional"),
    }
    if coupled:
        on_bottom = metrics.get("coupled") or {}
        out["texts"] += texts(on_bottom, "coupled")
        out["coupled"] = f"{OUTPUTS[REGIME].label}: {on_bottom.get(REGIME, '')}"
    return out
