"""Measured hook loads and surface torques against the torque and drag (``drillstring
torque-drag CONFIG --measured FILE``): the points read in SI, and for each the uniform friction
factor that reproduces it, found by the core (``well_implied_friction``: bisection in [0, 1] of
the core's hook load or surface torque at the point's bit depth).

The file is a CSV with the columns ``depth`` (the bit's measured depth), ``operation`` (one of
``pick_up``, ``slack_off``, ``rotating_off_bottom``, ``rotating_on_bottom``, ``sliding``, or the
profiles' names ``pickup``, ``slackoff``, ``rotating``) and ``hook_load`` and/or
``surface_torque``, each with its unit in the header as ``name [unit]`` (``depth [ft]``,
``hook_load [klbf]``, ``surface_torque [ft lbf]``; default m, N, N m). A row with another or no
operation is skipped and counted. The implied factor of a tripping or sliding point is that of
its hook load, of a rotating point that of its surface torque.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Union

import numpy as np

from .. import _core
from ..drilling.torque_drag import MEASURED_OPERATIONS
from ..errors import ValidationError
from .data import _SUFFIX, unit_factor

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

    from ..drilling.config import DrillConfig

__all__ = ["MeasuredPoints", "implied_friction", "read_td_measured"]

#: The columns of a measured-points file and their dimension.
_COLUMNS = {"depth": "length", "hook_load": "force", "surface_torque": "torque"}


@dataclass(frozen=True)
class MeasuredPoints:
    """Measured points in SI: ``depth`` (m), ``operation`` (names of the profiles), ``hook_load``
    (N) and ``surface_torque`` (N m), NaN where not measured; ``skipped`` rows without a known
    operation."""

    depth: np.ndarray
    operation: tuple[str, ...]
    hook_load: np.ndarray
    surface_torque: np.ndarray
    skipped: int


def read_td_measured(path: Union[str, os.PathLike[str]], field: str = "--measured") -> MeasuredPoints:
    """Reads a measured-points file (the module's format) into SI."""
    name = os.fspath(path)
    try:
        with open(name, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(line for line in f if not line.lstrip().startswith("#")))
    except OSError as exc:
        raise ValidationError(field, name, f"a readable CSV file ({exc.strerror})") from None
    if not rows:
        raise ValidationError(field, name, "a CSV file with a header row")
    index: dict[str, int] = {}
    factor: dict[str, float] = {}
    for j, header in enumerate(rows[0]):
        match = _SUFFIX.match(header)
        bare, unit = (match.group("name"), match.group("unit")) if match else (header.strip(), "")
        bare = bare.strip().lower()
        if bare == "operation":
            index[bare] = j
        elif bare in _COLUMNS:
            index[bare] = j
            default = {"length": "m", "force": "n", "torque": "n m"}[_COLUMNS[bare]]
            factor[bare] = unit_factor(bare, unit or default, f"{field} ({name}), columns",
                                       dimension=_COLUMNS[bare])
    missing = [c for c in ("depth", "operation") if c not in index]
    if missing or not ({"hook_load", "surface_torque"} & set(index)):
        raise ValidationError(f"{field} ({name}), row 1", ", ".join(rows[0]),
                              "the columns depth, operation and hook_load and/or surface_torque")
    depth, ops, hook, torque, skipped = [], [], [], [], 0

    def number(row: list[str], key: str, r: int) -> float:
        if key not in index or index[key] >= len(row) or not row[index[key]].strip():
            return math.nan
        text = row[index[key]].strip()
        try:
            value = float(text)
        except ValueError:
            raise ValidationError(f"{field} ({name}), row {r}, column {key}", text, "a number") from None
        return value * factor[key]

    for r, row in enumerate(rows[1:], start=2):
        op = row[index["operation"]].strip().lower() if index["operation"] < len(row) else ""
        if op not in MEASURED_OPERATIONS:
            skipped += 1
            continue
        depth.append(number(row, "depth", r))
        ops.append(MEASURED_OPERATIONS[op])
        hook.append(number(row, "hook_load", r))
        torque.append(number(row, "surface_torque", r))
    return MeasuredPoints(np.asarray(depth, dtype=float), tuple(ops), np.asarray(hook, dtype=float),
                          np.asarray(torque, dtype=float), skipped)


def implied_friction(config: DrillConfig, points: MeasuredPoints) -> pd.DataFrame:
    """``measured.csv``: the points in SI (``depth_m``, ``operation``, ``hook_load_N``,
    ``surface_torque_Nm``) with ``friction_factor`` (empty where no factor in [0, 1] reproduces
    the point) and ``reason``."""
    import pandas as pd

    raw = _core.well_implied_friction(config.to_json(), [float(d) for d in points.depth], list(points.operation),
                                      [float(h) for h in points.hook_load], [float(t) for t in points.surface_torque])
    return pd.DataFrame({"depth_m": points.depth, "operation": list(points.operation), "hook_load_N": points.hook_load,
                         "surface_torque_Nm": points.surface_torque,
                         "friction_factor": np.asarray(raw["friction_factor"], dtype=float),
                         "reason": list(raw["reason"])})
