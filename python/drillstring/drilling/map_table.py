"""The table of a stick-slip map (:func:`~drillstring.drilling.maps.drill_map`): its columns
(the axes, ``status`` and ``message``, :data:`METRIC_COLUMNS`, for a coupled map
:data:`COUPLED_COLUMNS`, :data:`STAT_COLUMNS`), the frame of a chunk of runs from the core's
columns, its numeric axes, and what is counted from it: the controllers of a map with a
``top_drive.controller.type`` axis ranked (:func:`controller_recommendation`)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from .config import DrillConfig
from .metrics import OUTPUTS, SSI, STICK_SLIP_VERDICT
from .result import COUPLED_METRICS, METRICS, TEXT_METRICS
from .units import annotate

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["CONTROLLER_AXIS", "COUPLED_COLUMNS", "METRIC_COLUMNS", "STAT_COLUMNS", "ControllerScore",
           "controller_recommendation", "numeric_axes"]

#: The axis of the controller type (one panel per controller in
#: :func:`~drillstring.drilling.map_plots.controller_maps`).
CONTROLLER_AXIS = "top_drive.controller.type"

#: The metric columns of a map, in order (those of ``metrics.json``, :data:`~drillstring.drilling.result.METRICS`).
METRIC_COLUMNS: tuple[str, ...] = METRICS

#: The columns a coupled map (a base configuration with a ``[hoist]``) adds after the metrics: the
#: coupled metrics of ``metrics.json`` (:data:`~drillstring.drilling.result.COUPLED_METRICS`; NaN
#: unless the run succeeded) and the ``regime`` (``"undetermined"`` unless it succeeded).
COUPLED_COLUMNS: tuple[str, ...] = COUPLED_METRICS

#: Solver columns after the metrics.
STAT_COLUMNS: tuple[str, ...] = ("cells", "steps", "dt", "balance_error", "courant_peak")


def coupled_columns(cfg: DrillConfig) -> tuple[str, ...]:
    """The coupled columns of a map of ``cfg``: :data:`COUPLED_COLUMNS` for a coupled base
    configuration (a ``[hoist]``), none for a torsion-only one (its table as before)."""
    return COUPLED_COLUMNS if cfg.hoist is not None else ()


def _axis_columns(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]]) -> dict[str, Any]:
    import pandas as pd

    columns: dict[str, Any] = {}
    for i, key in enumerate(named):
        values = [combo[i] for combo in combos]
        columns[key] = values if any(isinstance(v, (list, dict)) for v in values) else pd.array(values).to_numpy()
    return columns


def axis_frame(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], start: int) -> pd.DataFrame:
    import pandas as pd

    return pd.DataFrame(_axis_columns(named, combos), index=pd.RangeIndex(start, start + len(combos)))


def map_frame(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], raw: Mapping[str, Any],
           cfg: DrillConfig) -> pd.DataFrame:
    import pandas as pd

    columns = _axis_columns(named, combos)
    columns["status"] = list(raw["status"])
    # a field-units map speaks its file's units in its messages too (the SI value first, as the core wrote it)
    columns["message"] = [annotate(m, cfg.units) if m else m for m in raw["message"]]
    metrics = raw["metrics"]
    for name in METRIC_COLUMNS:
        value = metrics.get(name)
        if name in TEXT_METRICS:
            columns[name] = np.asarray(list(value or ()), dtype=object)
        else:
            columns[name] = np.asarray([] if value is None else value, dtype=float)
    coupled = raw.get("coupled") or {}
    for name in coupled_columns(cfg):
        value = coupled.get(name, ())
        columns[name] = (np.asarray(list(value), dtype=object) if OUTPUTS[name].kind == "text"
                         else np.asarray(value, dtype=float))
    for name in STAT_COLUMNS:
        columns[name] = np.asarray(raw["stats"].get(name, []))
    frame = pd.DataFrame(columns)
    frame.attrs.update(axes={k: list(v) for k, v in named.items()}, config=cfg.to_dict())
    return frame


def is_numeric(frame: pd.DataFrame, key: str) -> bool:
    import pandas as pd

    return key in frame.columns and pd.api.types.is_numeric_dtype(frame[key]) and not pd.api.types.is_bool_dtype(
        frame[key])


def numeric_axes(frame: pd.DataFrame) -> list[str]:
    """The axes of a map (``frame.attrs["axes"]``) with numeric values."""
    return [k for k in frame.attrs.get("axes", {}) if is_numeric(frame, k)]


@dataclasses.dataclass(frozen=True)
class ControllerScore:
    """One controller of a map with a ``top_drive.controller.type`` axis, over all its runs
    (every combination of the other axes' values): :func:`controller_recommendation`."""

    controller: str
    runs: int
    #: Runs that did not give a result (invalid, failed, interrupted).
    failed: int
    #: Runs with the stick-slip verdict ``yes`` (the bit stops during part of the window).
    stick_slip_runs: int
    #: Largest and mean SSI over the runs that gave a result (NaN without any).
    worst_ssi: float
    mean_ssi: float

    def line(self) -> str:
        ok = self.runs - self.failed
        failed = f", {self.failed} failed" if self.failed else ""
        return (f"{self.controller}: stick-slip in {self.stick_slip_runs} of {ok} runs{failed}, "
                f"SSI up to {self.worst_ssi:.3g} (mean {self.mean_ssi:.3g})")


def controller_recommendation(frame: pd.DataFrame) -> list[ControllerScore]:
    """The controllers of a map with a ``top_drive.controller.type`` axis, best first: fewest runs
    in stick-slip or without a result, then the lowest mean SSI, then the lowest largest SSI (the
    verdicts and SSI are the core's metrics of each run, counted here). Empty without that axis."""
    if CONTROLLER_AXIS not in frame.columns:
        return []
    scores = []
    for name, part in frame.groupby(CONTROLLER_AXIS, sort=False):
        ok = part[part["status"] == "success"]
        ssi = ok[SSI].to_numpy(dtype=float)
        ssi = ssi[np.isfinite(ssi)]
        scores.append(ControllerScore(
            controller=str(name), runs=len(part), failed=len(part) - len(ok),
            stick_slip_runs=int((ok[STICK_SLIP_VERDICT] == "yes").sum()),
            worst_ssi=float(ssi.max()) if ssi.size else math.nan,
            mean_ssi=float(ssi.mean()) if ssi.size else math.nan))
    inf = math.inf
    return sorted(scores, key=lambda s: (s.stick_slip_runs + s.failed, s.mean_ssi if math.isfinite(s.mean_ssi) else inf,
                                         s.worst_ssi if math.isfinite(s.worst_ssi) else inf))
