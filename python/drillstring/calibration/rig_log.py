"""A rig's surface log read into rig states, depths, rate of penetration and calibration events
(``drillstring rig-log``, :func:`rig_log`).

The log is a CSV file (``name [unit]`` headers or a units row), a Parquet file or an LAS 2.0 file
(through lasio, the ``las`` extra) with one row per sample. Its channels are found by their
canonical names (:data:`CHANNELS`), a mapping ``columns`` (canonical name -> header), else the
common mnemonics of :data:`ALIASES` (WITS, Pason and plain-language names); units are read as
:func:`~drillstring.calibration.data.read_columns` reads them and everything is SI from there on.
The LAS null ``-999.25`` is a missing value wherever it is found.

Derived where the log does not carry them (the rules, each threshold a field of
:class:`RigStateRules`, written once here and in ``docs/guide/rig-logs.md``):

* **in slips**: the hook load at most ``slips_margin`` above the block weight (``block_weight``;
  by default the lowest hook-load cluster holding at least 5 % of the rows: the load of the
  travelling block and top drive alone, :func:`estimate_block_weight`);
* **bit depth**: ``start_depth`` at the first row, then moved by the block when the string hangs
  from it: a row and the one before both out of slips move the bit by the block's fall between
  them; in slips the block moves alone. Across missing values the bit depth is held (across a
  time jump between two rows out of slips it moves by the block's fall);
* **hole depth**: the largest bit depth reached (from ``start_hole_depth``, default the start
  depth);
* **bit speed**: the centred difference of the bit depth over ``speed_window``; **on bottom**: the
  bit within ``on_bottom`` of the hole depth; **rotating**: surface speed above ``rotating_rpm``;
  **pumps on**: flow out above ``flow_out_min`` or standpipe pressure above ``standpipe_min``
  (without either channel the pumps are taken as on).

The rig state per row is the WITS0 activity code, the first rule that holds:

====  ================  ==================================================================
code  state             rule
====  ================  ==================================================================
0     undefined         a channel missing in the row, or none of the rules below holds
3     connection        in slips (also the connections of a trip)
2     drilling          on bottom with the pumps on or the string rotating
4     reaming           off bottom, moving faster than ``moving_speed``, rotating, pumps on
8     tripping in       off bottom, moving down faster than ``moving_speed``
9     tripping out      off bottom, moving up faster than ``moving_speed``
7     circulating       off bottom, not moving, pumps on (conditioning, rotating or not)
====  ================  ==================================================================

The rate of penetration is the hole depth's advance per drilling time (the time in state 2),
over a window of ``rop_window`` of drilling time centred on each drilling row; 0 outside
drilling. The stick-slip severity of a drilled interval (the drilling of one stand, between two
connections) is the median over windows of ``severity_window`` of ``(max - min) / (2 mean)`` of
the surface torque. The package's :func:`~drillstring.drilling.metrics.stick_slip_metrics` is not
used: it needs the bit's speed (absent from a surface log) and a sampling much faster than the
stick-slip period (a log's 1 Hz resolves a 5 s period with five points).

Calibration events (at least ``event_min`` long; values are medians after ``settle``):

* ``start_up``: rotation from rest (surface speed below ``rest_rpm`` for ``startup_rest``) to
  above ``rotating_rpm`` for at least ``event_min`` with the string out of slips (a connection's
  make-up spin in slips is no start-up of the string); its series (``startup_length`` from the
  last sample at rest) is what ``drillstring fit --data`` reads;
* ``pick_up`` / ``slack_off``: tripping out / in without rotation;
* ``rotating_off_bottom``: off bottom and out of slips, rotating, not moving.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields
from typing import Any, Optional, Union

import numpy as np
from numpy.typing import NDArray

from ..drilling.metrics import ROP_MEAN
from ..errors import ValidationError
from .data import read_columns

__all__ = ["ALIASES", "BLOCK_WEIGHT_SHARE", "CHANNELS", "EVENTS", "NULL", "STATES", "STATE_COLUMNS", "RigLogResult",
           "RigStateRules", "estimate_block_weight", "parse_quantity", "rig_log"]

#: The canonical channels of a rig log, each with its dimension (SI unit in
#: :data:`~drillstring.calibration.data.UNITS`: s, m, N, rpm, N m, %, Pa).
CHANNELS: dict[str, str] = {
    "t": "time", "block_height": "length", "hook_load": "force", "surface_rpm": "speed",
    "surface_torque": "torque", "flow_out": "percent", "standpipe_pressure": "pressure",
    "weight_on_bit": "force", "bit_depth": "length", "hole_depth": "length",
}

#: Header names taken for each channel when the log does not use the canonical name (compared
#: without case, spaces and punctuation): WITS0 mnemonics, Pason's and plain-language names.
ALIASES: dict[str, tuple[str, ...]] = {
    "t": ("time", "elapsed_time", "etim", "tim", "time_s", "seconds"),
    "block_height": ("block_position", "bpos", "blkpos", "block_pos", "hkht", "hook_height", "bht", "block"),
    "hook_load": ("hkld", "hkla", "hkl", "hookload", "hook_weight", "hkldav", "wt_on_hook"),
    "surface_rpm": ("rpm", "rpma", "tdrpm", "srpm", "rotary_rpm", "top_drive_rpm", "td_speed", "rop_rpm",
                    "rotary_speed"),
    "surface_torque": ("motor_torque", "torque", "tqa", "trq", "tq", "stor", "tdtorque", "td_torque",
                       "rotary_torque", "top_drive_torque", "torqa"),
    "flow_out": ("flowout", "flow_out_pct", "mfop", "mfo", "flwout", "return_flow", "flow_paddle"),
    "standpipe_pressure": ("spp", "sppa", "standpipe", "pump_pressure", "stand_pipe_pressure"),
    "weight_on_bit": ("wob", "swob", "woba", "bit_weight"),
    "bit_depth": ("dbtm", "bitdepth", "bit_depth_md", "bdep", "bit_position", "dbtv"),
    "hole_depth": ("dmea", "holedepth", "hole_depth_md", "total_depth", "hdep", "dmhd"),
}

#: The LAS null value, read as missing in every format.
NULL = -999.25

#: The rig states: WITS0 activity code -> name.
STATES: dict[int, str] = {0: "undefined", 2: "drilling", 3: "connection", 4: "reaming", 7: "circulating",
                          8: "tripping_in", 9: "tripping_out"}

#: The calibration events, each with its torque-and-drag operation ("" for none).
EVENTS: dict[str, str] = {"start_up": "", "pick_up": "pick_up", "slack_off": "slack_off",
                          "rotating_off_bottom": "rotating_off_bottom"}

#: The column of each measured channel in ``states.csv`` (SI, the package's unit suffixes).
STATE_COLUMNS: dict[str, str] = {
    "block_height": "block_height_m", "hook_load": "hook_load_N", "surface_rpm": "surface_rpm",
    "surface_torque": "surface_torque_Nm", "flow_out": "flow_out_percent",
    "standpipe_pressure": "standpipe_pressure_Pa", "weight_on_bit": "weight_on_bit_N",
}

_KLBF = 4448.2216152605


@dataclass(frozen=True)
class RigStateRules:
    """The thresholds of the rig-state, depth, rate and event rules (SI; see the module
    docstring). ``block_weight`` None: estimated from the log."""

    #: Hook load of the block and top drive alone, N (None: estimated, :func:`estimate_block_weight`).
    block_weight: Optional[float] = None
    #: In slips: hook load at most this above the block weight, N (5 klbf).
    slips_margin: float = 5 * _KLBF
    #: On bottom: the bit within this of the hole depth, m.
    on_bottom: float = 0.3
    #: Moving: the bit faster than this, m/s (108 m/h).
    moving_speed: float = 0.03
    #: Rotating: surface speed above this, rpm.
    rotating_rpm: float = 5.0
    #: At rest: surface speed below this, rpm.
    rest_rpm: float = 1.0
    #: Pumps on: flow out above this, %.
    flow_out_min: float = 5.0
    #: Pumps on: standpipe pressure above this, Pa (100 psi).
    standpipe_min: float = 689475.7293168362
    #: The window of the bit speed's centred difference, s.
    speed_window: float = 5.0
    #: The window of drilling time of the rate of penetration, s.
    rop_window: float = 60.0
    #: The window of the surface torque's stick-slip severity, s.
    severity_window: float = 60.0
    #: A time jump: a step longer than this many median sampling intervals.
    gap_factor: float = 5.0
    #: The shortest calibration event, s.
    event_min: float = 15.0
    #: Dropped at the start of a pick-up, slack-off or rotating-off-bottom event, s.
    settle: float = 5.0
    #: At rest at least this long before a start-up, s.
    startup_rest: float = 10.0
    #: The series written per start-up, s from its last sample at rest.
    startup_length: float = 60.0

    #: Each rule's SI unit, as pint reads it (for ``--rule NAME=QUANTITY``).
    UNITS = {"block_weight": "N", "slips_margin": "N", "on_bottom": "m", "moving_speed": "m/s",
             "rotating_rpm": "rpm", "rest_rpm": "rpm", "flow_out_min": "percent", "standpipe_min": "Pa",
             "speed_window": "s", "rop_window": "s", "severity_window": "s", "gap_factor": "",
             "event_min": "s", "settle": "s", "startup_rest": "s", "startup_length": "s"}

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.name == "block_weight":
                continue
            if isinstance(value, str):
                value = parse_quantity(value, self.UNITS[f.name], f"rules.{f.name}")
                object.__setattr__(self, f.name, value)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
                    or value <= 0 or (f.name == "gap_factor" and value <= 1):
                raise ValidationError(f"rules.{f.name}", value, f"a positive number ({self.UNITS[f.name] or '1'})"
                                      + (" above 1" if f.name == "gap_factor" else ""))
            object.__setattr__(self, f.name, float(value))

    @classmethod
    def from_pairs(cls, pairs: Mapping[str, Any], field: str = "rules") -> RigStateRules:
        """Rules from ``name -> value`` (a number in SI or a quantity ``"5 klbf"``); an unknown
        name is refused naming ``field`` and the names."""
        names = [f.name for f in fields(cls)]
        for name in pairs:
            if name not in names:
                raise ValidationError(field, name, f"a rule name: one of {', '.join(names)}")
        return cls(**{k: parse_quantity(v, cls.UNITS[k], f"{field} {k}") for k, v in pairs.items()})


_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def parse_quantity(value: Any, unit: str, field: str) -> float:
    """``value`` in the SI ``unit``: a number (SI), or text ``"3000 ft"`` / ``"5 klbf"``
    converted with pint; else a :class:`~drillstring.errors.ValidationError` naming ``field``."""
    from ..drilling.units import factor

    if isinstance(value, (int, float)) and not isinstance(value, bool):
        number = float(value)
    else:
        match = _NUMBER.match(str(value))
        scale = None
        if match is not None:
            scale = 1.0 if not match.group(2) else factor(match.group(2), unit or "dimensionless")
        if match is None or scale is None:
            raise ValidationError(field, value, f"a number in {unit or '1'} or a quantity such as "
                                  f"{_EXAMPLES.get(unit, '1')!r}")
        number = float(match.group(1)) * scale
    if not math.isfinite(number):
        raise ValidationError(field, value, "a finite number")
    return number


_EXAMPLES = {"m": "3000 ft", "N": "5 klbf", "m/s": "300 ft/h", "rpm": "5 rpm", "s": "10 s", "Pa": "100 psi",
             "percent": "5 percent"}


@dataclass
class RigLogResult:
    """What :func:`rig_log` found: ``states`` (one row per kept row of the log: ``t``,
    ``rig_state``, ``bit_depth_m``, ``hole_depth_m``, ``rop_m_per_h``, ``in_slips`` and the
    channels in SI, :data:`STATE_COLUMNS`), ``events`` (one row per calibration event),
    ``intervals`` (per drilled interval: depths, rate, stick-slip severity), ``series`` (per
    start-up its file name -> its series for ``drillstring fit``), ``summary`` (the
    ``summary.json`` document)."""

    states: Any
    events: Any
    intervals: Any
    series: dict[str, Any]
    summary: dict[str, Any]
    rules: RigStateRules
    seconds: float = 0.0

    def write(self, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True, field: str = "out_dir") -> list[Any]:
        """Writes the folder (:func:`~drillstring.calibration.rig_log_output.write_rig_log`)."""
        from .rig_log_output import write_rig_log

        return write_rig_log(self, out_dir, plots=plots, field=field)


def _read_las(path: str) -> Any:
    """An LAS file as a DataFrame with ``MNEMONIC [unit]`` headers (lasio; its null read as NaN)."""
    from ..io.extras import require

    require("las", f"reading the LAS file {path}")
    import lasio
    import pandas as pd

    try:
        las = lasio.read(path)
    except Exception as exc:  # lasio raises many kinds on a malformed file
        raise ValidationError("data", path, f"an LAS 2.0 file ({exc})") from None
    frame = pd.DataFrame({(f"{c.mnemonic} [{c.unit}]" if c.unit else c.mnemonic): np.asarray(c.data, dtype=object)
                          for c in las.curves})
    return frame


def _read(source: Any, columns: Optional[Mapping[str, str]], units: Optional[Mapping[str, str]]) -> Any:
    if isinstance(source, (str, os.PathLike)) and os.fsdecode(os.fspath(source)).lower().endswith(".las"):
        label = os.fsdecode(os.fspath(source))
        if not os.path.isfile(label):
            raise ValidationError("data", label, "an existing CSV, Parquet or LAS file")
        table = read_columns(_read_las(label), CHANNELS, columns=columns, units=units, aliases=ALIASES, null=NULL)
        object.__setattr__(table, "source", label)
        return table
    return read_columns(source, CHANNELS, columns=columns, units=units, aliases=ALIASES, null=NULL)


def _runs(mask: NDArray[np.bool_]) -> list[tuple[int, int]]:
    """``(first, last + 1)`` of each run of True in ``mask``."""
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return list(zip(np.flatnonzero(edges == 1).tolist(), np.flatnonzero(edges == -1).tolist()))


def _clean_time(t: NDArray[np.float64], values: dict[str, NDArray[np.float64]]
                ) -> tuple[NDArray[np.float64], dict[str, NDArray[np.float64]], int, int]:
    """Rows kept: a finite time not before any time before it. A time equal to the one before
    (a repeated time stamp of a real sample) is kept and counted; an earlier time or a missing one
    is dropped and counted."""
    finite = np.isfinite(t)
    running = np.maximum.accumulate(np.where(finite, t, -np.inf))
    keep = finite.copy()
    keep[1:] &= t[1:] >= running[:-1]
    dropped = int((~keep).sum())
    if keep.sum() < 2 or t[keep][-1] <= t[keep][0]:
        raise ValidationError("data: t", f"{int(keep.sum())} rows with increasing times", "at least two rows over "
                              "a time span")
    kept = t[keep]
    repeated = int((np.diff(kept) == 0).sum())
    return kept, {k: v[keep] for k, v in values.items()}, dropped, repeated


def _gaps(t: NDArray[np.float64], missing: NDArray[np.bool_], factor: float) -> tuple[list[dict[str, Any]], float]:
    """The time jumps (a step above ``factor`` median steps) and the runs of rows with a
    missing value, and the median step."""
    dt = np.diff(t)
    median = float(np.median(dt[dt > 0]))
    out: list[dict[str, Any]] = []
    for k in np.flatnonzero(dt > factor * median).tolist():
        out.append({"kind": "time_jump", "t_start": float(t[k]), "t_end": float(t[k + 1]),
                    "duration_s": float(dt[k]), "rows": 0})
    for a, b in _runs(missing):
        t_end = float(t[b]) if b < t.size else float(t[-1])
        out.append({"kind": "missing_values", "t_start": float(t[a]), "t_end": t_end,
                    "duration_s": t_end - float(t[a]), "rows": b - a})
    out.sort(key=lambda g: g["t_start"])
    return out, median


#: The share of the rows a hook-load cluster must hold to be taken as the block weight.
BLOCK_WEIGHT_SHARE = 0.05


def estimate_block_weight(hook_load: NDArray[np.float64]) -> float:
    """The block weight, N: the lowest hook-load cluster holding at least
    :data:`BLOCK_WEIGHT_SHARE` of the rows (1 kN bins summed over 5 kN, the lowest local maximum
    of that sum over +-5 kN), as the median of the loads within 2.5 kN of it. The string in slips
    hangs the block and top drive alone: every connection adds rows at that load, the lowest
    frequent one."""
    finite = hook_load[np.isfinite(hook_load)]
    if finite.size == 0:
        raise ValidationError("hook_load", "no finite values", "hook loads to find the block weight (or give "
                              "rules block_weight)")
    bins = np.floor(finite / 1000.0).astype(np.int64)
    low = int(bins.min())
    counts = np.bincount(bins - low)
    summed = np.convolve(counts, np.ones(5), mode="same")
    padded = np.pad(summed, 5, constant_values=-1.0)
    local_max = summed >= np.max(np.lib.stride_tricks.sliding_window_view(padded, 11), axis=1)
    found = np.flatnonzero(local_max & (summed >= BLOCK_WEIGHT_SHARE * finite.size))
    centre = (int(found[0]) if found.size else int(np.argmax(summed))) + low + 0.5
    near = finite[np.abs(finite / 1000.0 - centre) <= 2.5]
    return float(np.median(near))


def _centred_rate(t: NDArray[np.float64], x: NDArray[np.float64], window: float) -> NDArray[np.float64]:
    """``dx/dt`` by the centred difference over ``window`` (clipped at the ends)."""
    lo = np.searchsorted(t, t - window / 2, side="left")
    hi = np.searchsorted(t, t + window / 2, side="right") - 1
    hi = np.maximum(hi, np.minimum(lo + 1, t.size - 1))
    lo = np.minimum(lo, hi - 1)
    span = t[hi] - t[lo]
    return (x[hi] - x[lo]) / np.where(span > 0, span, np.inf)


def _depths(t: NDArray[np.float64], v: Mapping[str, NDArray[np.float64]], slips: NDArray[np.bool_],
            valid: NDArray[np.bool_], start_depth: float, start_hole: float
            ) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """Bit depth and hole depth: the log's, else from the block height and the slips."""
    if "bit_depth" in v:
        bit = v["bit_depth"].copy()
        how = "from the log's bit_depth"
    else:
        block = v["block_height"]
        fall = -(block[1:] - block[:-1])
        hanging = ~slips[1:] & ~slips[:-1] & valid[1:] & valid[:-1]
        fall = np.where(hanging & np.isfinite(fall), fall, 0.0)
        bit = start_depth + np.concatenate(([0.0], np.cumsum(fall)))
        how = ("from the block height: the bit moves with the block when the rows before and after are both out "
               "of slips, held in slips and across missing values")
    if "hole_depth" in v:
        return bit, v["hole_depth"].copy(), how + "; hole depth from the log's hole_depth"
    filled = np.where(np.isfinite(bit), bit, -np.inf)
    hole = np.maximum.accumulate(np.maximum(filled, start_hole))
    return bit, hole, how + "; hole depth the largest bit depth reached"


def _states(v: Mapping[str, NDArray[np.float64]], valid: NDArray[np.bool_], slips: NDArray[np.bool_],
            on_bottom: NDArray[np.bool_], speed: NDArray[np.float64], rules: RigStateRules
            ) -> tuple[NDArray[np.int8], NDArray[np.bool_], NDArray[np.bool_]]:
    """The WITS0 code per row (the table of the module docstring), rotating and pumps-on."""
    n = slips.size
    rpm = v.get("surface_rpm")
    rotating = np.zeros(n, bool) if rpm is None else np.nan_to_num(rpm) > rules.rotating_rpm
    if "flow_out" in v or "standpipe_pressure" in v:
        pumps = np.zeros(n, bool)
        if "flow_out" in v:
            pumps |= np.nan_to_num(v["flow_out"]) > rules.flow_out_min
        if "standpipe_pressure" in v:
            pumps |= np.nan_to_num(v["standpipe_pressure"]) > rules.standpipe_min
    else:
        pumps = np.ones(n, bool)
    moving = np.abs(speed) > rules.moving_speed
    state = np.zeros(n, np.int8)
    off = valid & ~slips & ~on_bottom
    state[off & ~moving & pumps] = 7
    state[off & moving & (speed < 0)] = 9
    state[off & moving & (speed > 0)] = 8
    state[off & moving & rotating & pumps] = 4
    state[valid & ~slips & on_bottom & (pumps | rotating)] = 2
    state[valid & slips] = 3
    return state, rotating, pumps


def _rop(t: NDArray[np.float64], hole: NDArray[np.float64], drilling: NDArray[np.bool_],
         window: float) -> NDArray[np.float64]:
    """Rate of penetration, m/h: the hole depth's advance per drilling time over ``window`` of
    drilling time centred on each drilling row (clipped at the log's first and last drilling);
    0 outside drilling."""
    rop = np.zeros(t.size)
    rows = np.flatnonzero(drilling)
    if rows.size < 2:
        return rop
    dt = np.diff(t, prepend=t[0])
    tau = np.cumsum(np.where(drilling, dt, 0.0))  # drilling time
    tau_d, hole_d = tau[rows], hole[rows]
    a = np.maximum(tau_d - window / 2, tau_d[0])
    b = np.minimum(tau_d + window / 2, tau_d[-1])
    span = b - a
    rate = (np.interp(b, tau_d, hole_d) - np.interp(a, tau_d, hole_d)) / np.where(span > 0, span, np.inf)
    rop[rows] = 3600.0 * rate
    return rop


def _severity(t: NDArray[np.float64], torque: NDArray[np.float64], window: float) -> float:
    """Median over windows of ``window`` of ``(max - min) / (2 mean)`` of a torque series."""
    if torque.size < 3:
        return math.nan
    edges = np.arange(t[0], t[-1] + window, window)
    idx = np.searchsorted(t, edges)
    values = []
    for a, b in zip(idx[:-1], idx[1:]):
        seg = torque[a:b]
        seg = seg[np.isfinite(seg)]
        if seg.size >= 3 and seg.mean() > 0:
            values.append((seg.max() - seg.min()) / (2 * seg.mean()))
    return float(np.median(values)) if values else math.nan


def _intervals(t: NDArray[np.float64], state: NDArray[np.int8], bit: NDArray[np.float64],
               hole: NDArray[np.float64], v: Mapping[str, NDArray[np.float64]], rules: RigStateRules) -> Any:
    """Per drilled interval (the drilling rows between two connections): times, depths, drilled
    length and time, mean rate of penetration, mean surface speed and torque, stick-slip
    severity of the surface torque."""
    import pandas as pd

    drilling = state == 2
    stand = np.cumsum(np.diff(np.concatenate(([0], (state == 3).astype(np.int8)))) == 1)
    # the steps between two drilling rows: their time is drilling time, their advance drilled length
    both = np.r_[False, drilling[1:] & drilling[:-1]]
    dt = np.diff(t, prepend=t[0])
    advance = np.diff(hole, prepend=hole[0])
    rows = []
    for s in np.unique(stand[drilling]):
        sel = np.flatnonzero(drilling & (stand == s))
        steps = sel[both[sel]]
        drilled_time = float(dt[steps].sum())
        length = float(np.nansum(advance[steps]))
        if drilled_time <= 0:
            continue
        torque = v.get("surface_torque")
        rpm = v.get("surface_rpm")
        turning = sel if rpm is None else sel[np.nan_to_num(rpm[sel]) > rules.rotating_rpm]  # not sliding
        rows.append({
            "t_start": float(t[sel[0]]), "t_end": float(t[sel[-1]]), "depth_from [m]": float(hole[sel[0]]),
            "depth_to [m]": float(hole[sel[0]]) + length, "drilled [m]": length, "drilling_time [s]": drilled_time,
            "rop [m/h]": 3600.0 * length / drilled_time,
            "surface_rpm [rpm]": float(np.nanmean(rpm[sel])) if rpm is not None else math.nan,
            "surface_torque [N m]": float(np.nanmean(torque[sel])) if torque is not None else math.nan,
            "stick_slip_severity [1]": _severity(t[turning], torque[turning], rules.severity_window)
            if torque is not None and turning.size >= 3 else math.nan,
        })
    columns = ["t_start", "t_end", "depth_from [m]", "depth_to [m]", "drilled [m]", "drilling_time [s]", "rop [m/h]",
               "surface_rpm [rpm]", "surface_torque [N m]", "stick_slip_severity [1]"]
    return pd.DataFrame(rows, columns=columns)


def _event_row(kind: str, t: NDArray[np.float64], sel: NDArray[np.intp], bit: NDArray[np.float64],
               hole: NDArray[np.float64], v: Mapping[str, NDArray[np.float64]], peak: float = math.nan,
               series: str = "") -> dict[str, Any]:
    def median(name: str) -> float:
        x = v.get(name)
        return float(np.nanmedian(x[sel])) if x is not None and np.isfinite(x[sel]).any() else math.nan

    mid = sel[sel.size // 2]
    return {"event": kind, "t_start": float(t[sel[0]]), "t_end": float(t[sel[-1]]), "operation": EVENTS[kind],
            "depth [m]": float(bit[mid]), "hole_depth [m]": float(hole[mid]), "hook_load [N]": median("hook_load"),
            "surface_torque [N m]": median("surface_torque"), "surface_rpm [rpm]": median("surface_rpm"),
            "peak_torque [N m]": peak, "standpipe_pressure [Pa]": median("standpipe_pressure"), "series": series}


def _events(t: NDArray[np.float64], state: NDArray[np.int8], valid: NDArray[np.bool_], slips: NDArray[np.bool_],
            on_bottom: NDArray[np.bool_], speed: NDArray[np.float64], rotating: NDArray[np.bool_],
            bit: NDArray[np.float64], hole: NDArray[np.float64], v: Mapping[str, NDArray[np.float64]],
            rules: RigStateRules) -> tuple[Any, dict[str, Any]]:
    """The calibration events (module docstring) and each start-up's series for ``fit``."""
    import pandas as pd

    rows: list[dict[str, Any]] = []
    steady = {
        "pick_up": (state == 9) & ~rotating,
        "slack_off": (state == 8) & ~rotating,
        "rotating_off_bottom": valid & ~slips & ~on_bottom & rotating & (np.abs(speed) <= rules.moving_speed),
    }
    for kind, mask in steady.items():
        for a, b in _runs(mask):
            if t[b - 1] - t[a] < rules.event_min:
                continue
            sel = np.arange(a, b)
            sel = sel[t[sel] >= t[a] + rules.settle]
            if sel.size >= 2:
                rows.append(_event_row(kind, t, sel, bit, hole, v))
    series: dict[str, Any] = {}
    rpm = v.get("surface_rpm")
    if rpm is not None:
        finite = np.isfinite(rpm)
        rest = finite & (rpm < rules.rest_rpm)
        for a, b in _runs(valid & rotating & ~slips):  # the string hanging from the block: not a make-up spin
            if t[b - 1] - t[a] < rules.event_min or a == 0:
                continue
            k = a - 1  # the last sample before the rotation
            while k >= 0 and finite[k] and not rest[k] and t[a] - t[k] < rules.startup_rest:
                k -= 1  # the speed ramping up from rest below rotating_rpm
            if k < 0 or not rest[k]:
                continue
            first_rest = k
            while first_rest > 0 and rest[first_rest - 1]:
                first_rest -= 1
            if t[k] - t[first_rest] < rules.startup_rest:
                continue
            end = min(b, int(np.searchsorted(t, t[k] + rules.startup_length, side="right")))
            sel = np.arange(k, end)
            name = f"start_up_{len(series) + 1:02d}.csv"
            torque = v.get("surface_torque")
            peak = float(np.nanmax(torque[sel])) if torque is not None and np.isfinite(torque[sel]).any() \
                else math.nan
            rows.append(_event_row("start_up", t, sel, bit, hole, v, peak=peak, series=name))
            frame = {"t [s]": t[sel] - t[k], "surface_rpm [rpm]": rpm[sel]}
            if torque is not None:
                frame["motor_torque [N m]"] = torque[sel]
            if "hook_load" in v:
                frame["hook_load [N]"] = v["hook_load"][sel]
            series[name] = pd.DataFrame(frame)
    columns = ["event", "t_start", "t_end", "operation", "depth [m]", "hole_depth [m]", "hook_load [N]",
               "surface_torque [N m]", "surface_rpm [rpm]", "peak_torque [N m]", "standpipe_pressure [Pa]", "series"]
    events = pd.DataFrame(rows, columns=columns).sort_values("t_start", kind="stable").reset_index(drop=True)
    return events, series


def rig_log(source: Any, *, columns: Optional[Mapping[str, str]] = None, units: Optional[Mapping[str, str]] = None,
            start_depth: Any = 0.0, start_hole_depth: Any = None,
            rules: Union[RigStateRules, Mapping[str, Any], None] = None,
            out: Union[str, os.PathLike[str], None] = None, plots: bool = True) -> RigLogResult:
    """Reads a rig's surface log and derives its rig states, depths, rate of penetration,
    drilled intervals and calibration events (see the module docstring for every rule).

    Parameters
    ----------
    source : path, DataFrame or mapping
        CSV (``name [unit]`` headers or a units row), Parquet or LAS 2.0 (the ``las`` extra).
    columns : mapping, optional
        Canonical channel name (:data:`CHANNELS`) -> the log's header.
    units : mapping, optional
        Channel name -> its unit in the log (overrides a header suffix or units row).
    start_depth : float or str
        Bit depth at the first row: m, or a quantity (``"3000 ft"``). Default 0.
    start_hole_depth : float or str, optional
        Hole depth at the first row (default: the start depth, the bit on bottom).
    rules : RigStateRules or mapping, optional
        Thresholds of the rules (a mapping of name -> number in SI or quantity).
    out : path, optional
        Write the folder there (:meth:`RigLogResult.write`).
    """
    import time

    import pandas as pd

    started = time.perf_counter()
    rules = rules if isinstance(rules, RigStateRules) else RigStateRules.from_pairs(dict(rules or {}))
    depth0 = parse_quantity(start_depth, "m", "start_depth")
    hole0 = depth0 if start_hole_depth is None else parse_quantity(start_hole_depth, "m", "start_hole_depth")
    if hole0 < depth0:
        raise ValidationError("start_hole_depth", hole0, f"at least the start depth ({depth0:g} m)")
    table = _read(source, columns, units)
    values = dict(table.values)
    required = ["hook_load", "bit_depth" if "bit_depth" in values else "block_height"]
    missing_channels = [n for n in required if n not in values]
    if missing_channels:
        raise ValidationError(f"{table.source}: columns", ", ".join(table.headers.values()),
                              f"the channels {', '.join(missing_channels)} (hook_load, and block_height or bit_depth; "
                              "map a header with --column NAME=HEADER)")
    t, values, dropped, repeated = _clean_time(values.pop("t"), values)
    used = [n for n in ("hook_load", "block_height", "bit_depth", "surface_rpm") if n in values]
    missing = np.zeros(t.size, bool)
    for channel in used:
        missing |= ~np.isfinite(values[channel])
    gaps, step = _gaps(t, missing, rules.gap_factor)
    valid = ~missing
    block_weight = rules.block_weight if rules.block_weight is not None else estimate_block_weight(values["hook_load"])
    slips = valid & (values["hook_load"] <= block_weight + rules.slips_margin)
    bit, hole, how = _depths(t, values, slips, valid, depth0, hole0)
    speed = _centred_rate(t, bit, rules.speed_window)
    speed = np.where(np.isfinite(speed), speed, 0.0)
    on_bottom = bit >= hole - rules.on_bottom
    state, rotating, _ = _states(values, valid, slips, on_bottom, speed, rules)
    rop = _rop(t, hole, state == 2, rules.rop_window)
    states = pd.DataFrame({"t": t, "rig_state": state, "bit_depth_m": bit, "hole_depth_m": hole, "rop_m_per_h": rop,
                           "in_slips": slips.astype(np.int8)})
    for name, column in STATE_COLUMNS.items():
        if name in values:
            states[column] = values[name]
    intervals = _intervals(t, state, bit, hole, values, rules)
    events, series = _events(t, state, valid, slips, on_bottom, speed, rotating, bit, hole, values, rules)
    result = RigLogResult(states, events, intervals, series, {}, rules)
    result.summary = _summary(table, t, state, bit, hole, gaps, step, (dropped, repeated), block_weight, how,
                              events, intervals, rules, values)
    result.seconds = time.perf_counter() - started
    if out is not None:
        result.write(out, plots=plots)
    return result


def _summary(table: Any, t: NDArray[np.float64], state: NDArray[np.int8], bit: NDArray[np.float64],
             hole: NDArray[np.float64], gaps: list[dict[str, Any]], step: float, dropped: tuple[int, int],
             block_weight: float, how: str, events: Any, intervals: Any, rules: RigStateRules,
             values: Mapping[str, NDArray[np.float64]]) -> dict[str, Any]:
    """The ``summary.json`` document."""
    dt = np.diff(t, append=t[-1])
    per_state = {STATES[c]: float(dt[state == c].sum()) for c in STATES}
    drilling = state == 2
    rules_used = asdict(rules)
    rules_used["block_weight"] = block_weight
    return {
        "source": table.source,
        "rows": int(t.size),
        "duration_s": float(t[-1] - t[0]),
        "t_origin": table.origin,
        "sampling_interval_s": step,
        "rows_dropped_time_backwards": dropped[0],
        "rows_repeated_time": dropped[1],
        "gaps": gaps,
        "gap_count": {"time_jump": sum(g["kind"] == "time_jump" for g in gaps),
                      "missing_values": sum(g["kind"] == "missing_values" for g in gaps)},
        "null_values": dict(table.nulls),
        "missing_values": {name: int((~np.isfinite(x)).sum()) for name, x in values.items()},
        "channels": {name: {"header": table.headers[name], "unit": table.units[name]} for name in table.headers},
        "time_per_state_s": per_state,
        "states": {str(c): name for c, name in STATES.items()},
        "depth_range_m": {"bit_min": float(np.nanmin(bit)), "bit_max": float(np.nanmax(bit)),
                          "hole_start": float(hole[0]), "hole_end": float(hole[-1]),
                          "drilled": float(hole[-1] - hole[0])},
        ROP_MEAN: (float(3600.0 * (intervals["drilled [m]"].sum() / intervals["drilling_time [s]"].sum()))
                             if len(intervals) and intervals["drilling_time [s]"].sum() > 0 else None),
        "drilled_intervals": int(len(intervals)),
        "drilling_rows": int(drilling.sum()),
        "events": {kind: int((events["event"] == kind).sum()) for kind in EVENTS},
        "rules": {
            "thresholds": rules_used,
            "block_weight": "given" if rules.block_weight is not None else
            "estimated: the lowest hook-load cluster holding 5 % of the rows",
            "depth": how,
            "pumps": "flow_out or standpipe_pressure above its threshold" if "flow_out" in values
            or "standpipe_pressure" in values else "taken as on (no flow_out or standpipe_pressure in the log)",
            "rop": "hole depth advance per drilling time over rop_window of drilling time",
            "stick_slip_severity": "median over severity_window windows of (max - min) / (2 mean) of the surface "
                                   "torque of the rotating rows of a drilled interval",
        },
    }
