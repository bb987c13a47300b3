"""Measured surface (and downhole) data: reading, units, checks, resampling.

A data file is CSV or Parquet with a time column and one column per measured series. The
column names of ``drillstring drill``'s ``series.csv`` are read as they are; other names are
mapped with ``columns={"motor_torque": "TQ_SURF", ...}`` (model name -> file name).

=================  ===========  ====================================================
name               unit (SI)    what
=================  ===========  ====================================================
``t``              s            time
``surface_rpm``    rpm          top-drive (surface) speed
``motor_torque``   N m          top-drive torque (the motor's: it includes the
                                top-drive inertia's acceleration torque)
``bit_rpm``        rpm          bit speed (downhole, optional)
``bit_torque``     N m          torque on bit (downhole, optional)
``hook_load``      N            hook load (modelled in coupled runs: a ``[hoist]``)
``weight_on_bit``  N            weight on bit (downhole or from the hook load,
                                optional; modelled in coupled runs)
``block_position`` m            block position (read and kept; not modelled)
=================  ===========  ====================================================

Units, in this order of precedence: the ``units`` option (``{"motor_torque": "kN m"}``), a
suffix in the header (``motor_torque [kN m]`` or ``motor_torque (kN m)``), a units row (the
first row under the header holding text, not numbers, in the time column), else the SI unit of
the table. Known units: time ``s, ms, min, h``; speed ``rpm, rad/s, Hz`` (revolutions per
second); torque ``N m, kN m, ft lbf, kft lbf``; force ``N, kN, lbf, klbf, kgf, tf``; length
``m, ft``.

Checks (each a :class:`~drillstring.errors.ValidationError` naming the column and the time):
time strictly increasing; no NaN in a used column (``nan="drop"`` drops those rows instead); no
gap in the time column longer than ``max_gap`` (default five times the median sampling
interval) inside the span used; the columns asked for present.

Resampling: linear interpolation of the measured series at the model's output times
``k * numerics.output_interval`` inside the fit's windows (the windows must lie inside the
measured span). ``start`` is the time in the file of the model's ``t = 0`` (the start-up).
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Optional, Union

import numpy as np
from numpy.typing import NDArray

from ..errors import ValidationError
from ..io.table import read_parquet_frame

__all__ = ["AXIAL_SERIES", "COLUMNS", "MODEL_SERIES", "UNITS", "Columns", "MeasuredData", "read_columns",
           "read_measured"]

#: The columns a data file may have, each with its dimension (the model's SI unit in :data:`UNITS`).
COLUMNS: dict[str, str] = {
    "t": "time",
    "surface_rpm": "speed",
    "motor_torque": "torque",
    "bit_rpm": "speed",
    "bit_torque": "torque",
    "hook_load": "force",
    "weight_on_bit": "force",
    "block_position": "length",
}

#: The series the model computes (``drill``'s series), which a fit can compare.
MODEL_SERIES: tuple[str, ...] = ("surface_rpm", "motor_torque", "bit_rpm", "bit_torque")
#: The series a coupled axial-torsional run (a ``[hoist]`` table) computes besides, which a fit of
#: a coupled configuration can compare.
AXIAL_SERIES: tuple[str, ...] = ("hook_load", "weight_on_bit")

_FT_LBF = 0.3048 * 4.4482216152605
#: Per dimension: the model's unit first, then every known unit with its factor to the model's.
UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0},
    "speed": {"rpm": 1.0, "rev/min": 1.0, "rad/s": 60.0 / (2.0 * math.pi), "hz": 60.0, "rev/s": 60.0},
    "torque": {"n m": 1.0, "kn m": 1e3, "ft lbf": _FT_LBF, "lbf ft": _FT_LBF, "kft lbf": 1e3 * _FT_LBF},
    "force": {"n": 1.0, "kn": 1e3, "lbf": 4.4482216152605, "klbf": 4448.2216152605, "kgf": 9.80665,
              "tf": 9806.65},
    "length": {"m": 1.0, "ft": 0.3048},
    "pressure": {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "bar": 1e5, "psi": 6894.757293168361},
    "percent": {"%": 1.0, "percent": 1.0, "pct": 1.0},
}
#: Each dimension's model unit as pint writes it, for units outside :data:`UNITS`.
_PINT_UNITS: dict[str, str] = {"time": "s", "speed": "rpm", "torque": "N*m", "force": "N", "length": "m",
                               "pressure": "Pa", "percent": "percent"}

_SUFFIX = re.compile(r"^\s*(?P<name>[^\[\(]*?)\s*[\[\(]\s*(?P<unit>[^\]\)]*?)\s*[\]\)]\s*$")


def _unit_key(unit: str) -> str:
    """A unit written as people write it (``kN.m``, ``kNm``, ``N·m``, ``ft-lbf``, ``RPM``) in
    the spelling of :data:`UNITS`."""
    text = unit.strip().lower().replace("·", " ").replace("*", " ").replace("-", " ").replace(".", " ")
    text = re.sub(r"\s+", " ", text)
    text = {"nm": "n m", "knm": "kn m", "ftlbf": "ft lbf", "kftlbf": "kft lbf", "lbfft": "lbf ft",
            "sec": "s", "seconds": "s", "rad/sec": "rad/s", "r/min": "rpm", "1/min": "rpm"}.get(text.replace(" ", ""),
                                                                                                 text)
    return text


def unit_factor(name: str, unit: str, field_name: str = "units", dimension: Optional[str] = None) -> float:
    """The factor that takes ``name``'s values in ``unit`` to the model's SI unit (the first of
    its dimension's in :data:`UNITS`): the table's factor, else pint's (through
    :func:`drillstring.drilling.units.factor`, so that ``daN``, ``MPa`` or ``kip`` read too); a
    unit of another dimension or unknown raises :class:`~drillstring.errors.ValidationError`
    listing the units known for the column. ``dimension``: the column's, default
    :data:`COLUMNS`'s."""
    dimension = COLUMNS[name] if dimension is None else dimension
    known = UNITS[dimension]
    key = _unit_key(unit)
    if key in known:
        return known[key]
    from ..drilling.units import factor

    value = factor(unit, _PINT_UNITS[dimension])
    if value is None:
        raise ValidationError(f"{field_name}[{name}]", unit, f"a {dimension} unit: one of {', '.join(known)}")
    return value


@dataclass(frozen=True)
class MeasuredData:
    """A measured time series in the model's units: ``t`` (s, from the start-up: the model's
    ``t = 0``) and ``series`` (name -> values, the names and SI units of :data:`COLUMNS`)."""

    t: NDArray[np.float64]
    series: Mapping[str, NDArray[np.float64]]
    source: str = "data"
    #: The unit each column was read in (name -> unit as given), for the report.
    units: Mapping[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        t = np.asarray(self.t, dtype=np.float64)
        series = {str(k): np.asarray(v, dtype=np.float64) for k, v in self.series.items()}
        for name, values in series.items():
            if name not in COLUMNS or name == "t":
                raise ValidationError(f"{self.source}: column", name,
                                      f"one of {', '.join(n for n in COLUMNS if n != 't')} (map other names with "
                                      "columns=)")
            if values.shape != t.shape:
                raise ValidationError(f"{self.source}: column {name}", f"{values.size} values",
                                      f"as many values as times ({t.size})")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "series", series)
        _check_time(t, self.source)

    @property
    def span(self) -> tuple[float, float]:
        """First and last time, s."""
        return float(self.t[0]), float(self.t[-1])

    def require(self, names: Sequence[str]) -> None:
        """Refuses data without one of the series ``names``."""
        missing = [n for n in names if n not in self.series]
        if missing:
            raise ValidationError(f"{self.source}: columns", ", ".join(sorted(self.series)) or "none",
                                  f"the series the fit compares: {', '.join(missing)} missing (map other names "
                                  "with columns=, e.g. --column motor_torque=TORQUE)")

    def check_windows(self, windows: Sequence[tuple[float, float]], names: Sequence[str],
                      max_gap: Optional[float] = None) -> None:
        """Refuses windows outside the measured span, a gap longer than ``max_gap`` (default
        five times the median sampling interval) or a NaN of ``names`` inside a window."""
        t0, t1 = self.span
        dt = np.diff(self.t)
        gap_limit = 5.0 * float(np.median(dt)) if max_gap is None else float(max_gap)
        for a, b in windows:
            if a < t0 - 1e-9 or b > t1 + 1e-9:
                raise ValidationError(f"{self.source}: window", (a, b),
                                      f"a window inside the measured span {t0:g}..{t1:g} s (times from the start-up)")
            inside = (self.t >= a) & (self.t <= b)
            lo = max(int(np.searchsorted(self.t, a, side="right")) - 1, 0)
            hi = min(int(np.searchsorted(self.t, b, side="left")), self.t.size - 1)
            if hi > lo:
                steps = dt[lo:hi]
                k = int(np.argmax(steps))
                if steps[k] > gap_limit * (1 + 1e-9):
                    raise ValidationError(
                        f"{self.source}: t", f"a gap of {steps[k]:g} s from t = {self.t[lo + k]:g} s",
                        f"samples no more than {gap_limit:g} s apart inside the window {a:g}..{b:g} s (max_gap; "
                        "choose windows around the gap)")
            for name in names:
                bad = inside & ~np.isfinite(self.series[name])
                if bad.any():
                    raise ValidationError(f"{self.source}: column {name}",
                                          f"NaN or infinite at t = {self.t[np.argmax(bad)]:g} s",
                                          "finite values inside the windows (nan='drop' drops such rows)")

    def resample(self, name: str, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """``name`` linearly interpolated at ``times`` (inside the measured span)."""
        return np.interp(times, self.t, self.series[name])

    def window(self, start: float, end: Optional[float] = None) -> MeasuredData:
        """The samples from ``start`` to ``end`` (file times), with ``start`` as the new ``t = 0``:
        one start-up out of a longer record."""
        keep = (self.t >= start - 1e-12) & (self.t <= (np.inf if end is None else end) + 1e-12)
        if keep.sum() < 2:
            raise ValidationError(f"{self.source}: window", (start, end), f"a span holding at least two samples "
                                  f"of {self.span[0]:g}..{self.span[1]:g} s")
        return MeasuredData(self.t[keep] - start, {k: v[keep] for k, v in self.series.items()},
                            source=self.source, units=self.units)


def _check_time(t: NDArray[np.float64], source: str) -> None:
    if t.ndim != 1 or t.size < 2:
        raise ValidationError(f"{source}: t", f"{t.size} samples", "at least two samples")
    finite = np.isfinite(t)
    if not finite.all():
        raise ValidationError(f"{source}: t", f"NaN or infinite at row {int(np.argmin(finite))}",
                              "finite times (drop those rows)")
    step = np.diff(t)
    if (step <= 0).any():
        k = int(np.argmax(step <= 0))
        raise ValidationError(f"{source}: t", f"{t[k + 1]:g} s at row {k + 1} after {t[k]:g} s",
                              "strictly increasing times (sort the file, remove repeated samples)")


PathLike = Union[str, "os.PathLike[str]"]


def read_measured(source: Any, *, columns: Optional[Mapping[str, str]] = None,
                  units: Optional[Mapping[str, str]] = None, start: float = 0.0, end: Optional[float] = None,
                  nan: str = "error") -> MeasuredData:
    """Reads measured data: a CSV or Parquet file (by its extension; ``.csv`` or ``.txt`` is
    CSV), a :class:`pandas.DataFrame` or a mapping of column name -> values.

    Parameters
    ----------
    columns : mapping, optional
        Model name -> the file's column name (``{"motor_torque": "TQ", "t": "TIME"}``); the
        other columns are taken by the names of :data:`COLUMNS`, unknown ones ignored.
    units : mapping, optional
        Model name -> the unit of its column in the file (see the module docstring); overrides
        a units row or a header suffix.
    start, end : float
        The file's time of the model's ``t = 0`` (the start-up) and of the last sample kept, s
        (in the file's time unit converted to s).
    nan : ``"error"`` or ``"drop"``
        A NaN in a column read: refused where a fit uses it (:meth:`MeasuredData.check_windows`),
        or its rows dropped here.
    """
    if nan not in ("error", "drop"):
        raise ValidationError("nan", nan, "'error' or 'drop'")
    table = read_columns(source, COLUMNS, columns=columns, units=units)
    values = dict(table.values)
    t = values.pop("t")
    if nan == "drop":
        keep = np.isfinite(t)
        for v in values.values():
            keep &= np.isfinite(v)
        t = t[keep]
        values = {k: v[keep] for k, v in values.items()}
    data = MeasuredData(t, values, source=table.source, units=table.units)
    if start != 0.0 or end is not None:
        data = data.window(float(start), end)
    return data


@dataclass(frozen=True)
class Columns:
    """The columns of a table read by :func:`read_columns`, in SI, not yet checked: ``values``
    (name -> values), ``units`` (name -> the unit each was read in), ``headers`` (name -> the
    file's column it came from), ``nulls`` (name -> how many values were the null value),
    ``origin`` (the date and time of ``t = 0`` when the time column holds dates)."""

    source: str
    values: Mapping[str, NDArray[np.float64]]
    units: Mapping[str, str]
    headers: Mapping[str, str]
    nulls: Mapping[str, int]
    #: The first time of a time column of dates and times (ISO 8601, UTC), whose rows are then
    #: seconds from it; None for a numeric time column.
    origin: Optional[str] = None


def _frame(source: Any) -> tuple[str, Any]:
    """``(label, DataFrame)`` of a CSV or Parquet path, a DataFrame or a mapping."""
    import pandas as pd

    if isinstance(source, pd.DataFrame):
        return "data", source.copy()
    if isinstance(source, Mapping):
        return "data", pd.DataFrame({k: np.asarray(v) for k, v in source.items()})
    if isinstance(source, (str, os.PathLike)):
        label = os.fsdecode(os.fspath(source))
        if not os.path.isfile(label):
            raise ValidationError("data", label, "an existing CSV or Parquet file")
        if label.lower().endswith((".parquet", ".pq")):
            return label, read_parquet_frame(label)
        return label, pd.read_csv(label, dtype=str, skipinitialspace=True)
    raise ValidationError("data", type(source).__name__, "a CSV or Parquet path, a pandas DataFrame or a mapping")


def _normal(text: str) -> str:
    """A column name compared without case, spaces or punctuation (``Hook Load`` is ``HOOKLOAD``)."""
    return re.sub(r"[^0-9a-z]", "", text.lower())


def read_columns(source: Any, known: Mapping[str, str], *, columns: Optional[Mapping[str, str]] = None,
                 units: Optional[Mapping[str, str]] = None,
                 aliases: Optional[Mapping[str, Sequence[str]]] = None, null: Optional[float] = None,
                 field: str = "columns", units_field: str = "units") -> Columns:
    """The columns ``known`` (name -> dimension of :data:`UNITS`) of a CSV or Parquet file, a
    :class:`pandas.DataFrame` or a mapping, converted to SI: by the names of ``known``, a
    mapping ``columns`` (name -> the file's column), else the first of the name's ``aliases``
    the file has (compared without case and punctuation); units as :func:`read_measured` reads
    them. ``null``: a value meaning "missing" (the LAS null ``-999.25``), read as NaN and counted.
    Unknown columns are ignored; a time column ``t`` is required: numbers (in its unit), or
    dates and times, read as seconds from the first (:attr:`Columns.origin`). ``field`` and
    ``units_field`` name the options in messages."""
    import pandas as pd

    mapping = dict(columns or {})
    for name in mapping:
        if name not in known:
            raise ValidationError(field, name, f"a channel name: one of {', '.join(known)}")
    label, frame = _frame(source)
    if "t" not in frame.columns and frame.index.name is not None:
        frame = frame.reset_index()  # drill's series.parquet: time as the index
    header_units: dict[str, str] = {}
    renamed: dict[str, str] = {}
    for col in frame.columns:
        text = str(col)
        match = _SUFFIX.match(text)
        bare = match.group("name") if match else text
        renamed[text] = bare
        if match:
            header_units[bare] = match.group("unit")
    frame.columns = [renamed[str(c)] for c in frame.columns]
    for name, col in mapping.items():
        if col not in frame.columns:
            raise ValidationError(f"{field}[{name}]", col, f"a column of {label}: {', '.join(map(str, frame.columns))}")
    wanted = {name: mapping.get(name, name) for name in known if mapping.get(name, name) in frame.columns}
    by_normal = {_normal(str(c)): str(c) for c in reversed(list(frame.columns))}
    taken = set(wanted.values())
    for name, names in (aliases or {}).items():
        if name in wanted or name not in known:
            continue
        found = next((by_normal[_normal(a)] for a in names if _normal(a) in by_normal), None)
        if found is not None and found not in taken:
            wanted[name] = found
            taken.add(found)
    if "t" not in wanted:
        raise ValidationError(f"{label}: columns", ", ".join(map(str, frame.columns)),
                              f"a time column 't' (s; map another name with {field}={{'t': NAME}}, --column t=NAME)")
    row_units: dict[str, str] = {}
    first = frame[wanted["t"]].iloc[0] if len(frame) else None
    if isinstance(first, str) and not _is_number(first) and _datetimes(pd.Series([first])) is None:  # a units row
        for name, col in wanted.items():
            value = frame[col].iloc[0]
            if isinstance(value, str) and value.strip():
                row_units[name] = value.strip()
        frame = frame.iloc[1:]
    given = {**row_units, **header_units_by_model(header_units, wanted), **dict(units or {})}
    for name in given:
        if name not in known:
            raise ValidationError(units_field, name, f"a channel name: one of {', '.join(known)}")
    values: dict[str, NDArray[np.float64]] = {}
    used_units: dict[str, str] = {}
    nulls: dict[str, int] = {}
    origin: Optional[str] = None
    for name, col in wanted.items():
        try:
            raw = pd.to_numeric(frame[col], errors="raise").to_numpy(dtype=np.float64)
        except (ValueError, TypeError) as exc:
            stamps = _datetimes(frame[col]) if name == "t" else None
            if stamps is None:
                raise ValidationError(f"{label}: column {col}", str(exc), "numbers") from None
            raw, origin = stamps
            given[name] = "s"
        if null is not None:
            missing = raw == null
            nulls[name] = int(missing.sum())
            raw = np.where(missing, np.nan, raw)
        unit = given.get(name)
        factor = 1.0 if unit is None else unit_factor(name, unit, units_field, dimension=known[name])
        used_units[name] = unit if unit is not None else next(iter(UNITS[known[name]]))
        values[name] = raw * factor
    return Columns(label, values, used_units, dict(wanted), nulls, origin)


def _datetimes(column: Any) -> Optional[tuple[NDArray[np.float64], str]]:
    """A time column of dates and times (``2016-03-01 12:00:00``, ISO 8601 with or without a
    zone) as seconds from its first, and that first time (ISO); None if it holds other text."""
    import pandas as pd

    stamps = None
    for form in ("mixed", None):  # "mixed": each stamp its own form (pandas >= 2)
        try:
            stamps = pd.to_datetime(column, errors="raise", utc=True, format=form)
            break
        except (ValueError, TypeError, OverflowError):
            continue
    if stamps is None:
        return None
    valid = stamps.notna().to_numpy()
    if not valid.any():
        return None
    first = stamps[valid].iloc[0]
    seconds = (stamps - first).dt.total_seconds().to_numpy(dtype=np.float64)
    return seconds, first.isoformat()


def header_units_by_model(header_units: Mapping[str, str], wanted: Mapping[str, str]) -> dict[str, str]:
    """The units of header suffixes (file column -> unit) by model name."""
    return {name: header_units[col] for name, col in wanted.items() if col in header_units}


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
