"""Stick-slip metrics of bit-speed and motor-torque series (computed by the core's
``metrics::stickslip``), for drilling runs, the lumped model and field data."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional, TypeVar

import numpy as np

from .. import _core
from ..errors import ValidationError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray


__all__ = ["STICK_SPEED", "STICK_SLIP_CRITERION", "OUTPUTS", "Output", "StickSlipMetrics", "stick_slip_metrics",
           "break_off_torque"]


#: Default stick threshold speed of :func:`stick_slip_metrics`, rad/s (about 0.1 rpm).
STICK_SPEED: float = _core.STICK_SPEED


@dataclass(frozen=True)
class Output:
    """One output of a run as the core's registry declares it (``drillstring_core::outputs``)."""

    name: str
    label: str
    """The few words the console, ``report.md`` and the figures name it by (``"ROP"``), without its unit."""
    unit: Optional[str]
    """SI unit as pint parses it (``""`` dimensionless); None for a verdict, a count or a text."""
    definition: str
    runs: tuple[str, ...]
    """The runs that report it: of ``"torsional"``, ``"coupled"``, ``"lumped"``."""
    map_column: bool
    """A column of a stick-slip map and an entry of ``metrics.json``."""
    kind: str
    """``"number"``, ``"verdict"``, ``"count"``, ``"text"`` or ``"series"``."""
    tolerance: Optional[tuple[str, float, float]]
    """``(kind, tolerance, floor)`` of the grid and start checks, or None."""
    headline: bool
    """Finite in every run that has metrics, or the run is not a result."""
    console: bool
    """On the console's summary of a run (``drillstring drill``), by its label, in the registry's order."""
    of_any_series: bool
    """A metric of :func:`stick_slip_metrics` (of any series)."""

    def value(self, raw: Any) -> Any:
        """A value of the core as this output's kind: a float (None read as NaN), a bool, an int or a str."""
        if self.kind == "verdict":
            return bool(raw)
        if self.kind == "count":
            return 0 if raw is None else int(raw)
        if self.kind == "text":
            return "" if raw is None else str(raw)
        return math.nan if raw is None else float(raw)


#: Every output of a run by name, in the core's order (``_core.drill_outputs()``): the one list of
#: the metrics and series channels that ``metrics.json``, a map's columns, the units and the
#: documentation read.
OUTPUTS: dict[str, Output] = {
    str(d["name"]): Output(name=str(d["name"]), label=str(d["label"]), unit=d["unit"], definition=str(d["definition"]),
                           runs=tuple(d["runs"]), map_column=bool(d["map_column"]), kind=str(d["kind"]),
                           tolerance=None if d["tolerance"] is None else (
                               str(d["tolerance"][0]), float(d["tolerance"][1]), float(d["tolerance"][2])),
                           headline=bool(d["headline"]), console=bool(d["console"]),
                           of_any_series=bool(d["of_any_series"]))
    for d in _core.drill_outputs()}

#: The metrics the package reads in particular (a map's figures and console summary, the lumped
#: model's table, the rig log's summary), each name spelled here once; every list of metrics is
#: :data:`OUTPUTS`'s. The stick-slip severity, the stuck fraction, the period, the bit speed's
#: range and mean, the verdicts; a coupled run's mean ROP, mean hook load, MSE and regime.
SSI, STUCK_FRACTION, PERIOD = "ssi", "stuck_fraction", "period_s"
BIT_RPM_MIN, BIT_RPM_MAX, BIT_RPM_MEAN = "bit_rpm_min", "bit_rpm_max", "bit_rpm_mean"
STICK_SLIP_VERDICT, SETTLED = "stick_slip_verdict", "settled"
ROP_MEAN, HOOK_LOAD_MEAN, MSE_MEAN, REGIME = "rop_mean_m_per_h", "hook_load_mean_N", "mse_mean_Pa", "regime"
assert {SSI, STUCK_FRACTION, PERIOD, BIT_RPM_MIN, BIT_RPM_MAX, BIT_RPM_MEAN, STICK_SLIP_VERDICT, SETTLED, ROP_MEAN,
        HOOK_LOAD_MEAN, MSE_MEAN, REGIME} <= set(OUTPUTS), "a metric the package reads is not in the core's registry"

#: The criterion of the three-way verdict ``stick_slip_verdict`` (the core's
#: ``metrics::stickslip::verdict``), as ``metrics.json`` and ``report.md`` state it.
STICK_SLIP_CRITERION: str = _core.STICK_SLIP_CRITERION


_M = TypeVar("_M", bound="StickSlipMetrics")


@dataclass(frozen=True)
class StickSlipMetrics:
    """Stick-slip metrics of one window (see :func:`stick_slip_metrics`), by the names of
    ``metrics.json``. NaN where a metric is undefined (no torque series, no full cycle)."""

    window_start: float
    """Start of the window the metrics cover, s: its first sample (a drill run's
    :class:`~drillstring.drilling.DrillMetrics`: the window asked for)."""
    window_end: float
    """End of the window, s: its last sample (a drill run's: the window asked for)."""
    ssi: float
    """Stick-slip severity ``(max - min) / (2 |mean|)`` of the bit speed (NaN when the mean is 0)."""
    stuck_fraction: float
    """Fraction of the window's time with ``|omega_bit| <= stick_speed``."""
    bit_rpm_min: float
    bit_rpm_max: float
    bit_rpm_mean: float
    """Time-weighted (trapezoidal) mean bit speed, rpm."""
    motor_torque_min_Nm: float
    """Motor torque minimum (NaN without a torque series; the lumped model's spring torque)."""
    motor_torque_max_Nm: float
    period_s: float
    """Stick-slip period, s: the motor torque's period from its autocorrelation (the similarity of
    the series with itself shifted, searched up to half the window); NaN with fewer than two cycles
    in the window or without a torque series. It does not depend on where the window starts."""
    period_cycles: float
    """The window's length in periods (NaN without one)."""
    periodicity: float
    """Similarity of the motor torque with itself one period later (1: exactly periodic)."""
    slip_period_s: float
    """Cross-check of ``period_s``: the mean interval between the bit's slip onsets (its speed
    rising through ``stick_speed`` in the direction of its mean, for a slip that carries it above
    its mean speed; a partial slip is no cycle), s (NaN with fewer than three)."""
    slip_onsets: int
    """Slip onsets of the bit in the window."""
    stick_slip: bool
    """The verdict: the bit stops during part of the window (``0 < stuck_fraction < 1``)."""
    settled: bool
    """The first and the last whole periods of the window (as many as half of it holds; its
    halves without a period) agree in the
    means and ranges of the bit speed and the motor torque, to 5 % of the ranges plus 1 % of the
    means: not a transient."""
    warnings: tuple[str, ...] = ()
    """What in these metrics cannot be trusted as it stands (empty when all can)."""
    stick_slip_verdict: str = "undetermined"
    """The three-way verdict, ``"yes"``, ``"no"`` or ``"undetermined"`` (:data:`STICK_SLIP_CRITERION`):
    ``"yes"`` exactly when :attr:`stick_slip`; ``"no"`` only for a bit that never stops in a settled
    window with ``ssi < 1``."""
    stick_slip_reason: str = ""
    """Why the verdict is what it is, in a few words (the core's)."""
    values: Mapping[str, Any] = dataclasses.field(default_factory=dict, hash=False)
    """Every metric the core gave, by its name in :data:`OUTPUTS` (also ``metrics[name]``)."""

    @classmethod
    def from_core(cls: type[_M], d: Mapping[str, Any]) -> _M:
        """From a metrics dict of the core (the names of :data:`OUTPUTS`; ``None`` read as NaN, the
        ``warnings`` list as a tuple)."""
        values = {name: o.value(d[name]) for name, o in OUTPUTS.items() if name in d and o.kind != "series"}
        fields: dict[str, Any] = {}
        for f in dataclasses.fields(cls):
            if f.name == "warnings":
                fields[f.name] = tuple(str(w) for w in (d.get("warnings") or ()))
            elif f.name == "values":
                fields[f.name] = values
            elif f.name in values:
                fields[f.name] = values[f.name]
            elif f.default is not dataclasses.MISSING:
                fields[f.name] = f.default
            else:
                fields[f.name] = OUTPUTS[f.name].value(None)
        return cls(**fields)

    def __getitem__(self, name: str) -> Any:
        """The metric ``name`` of :data:`OUTPUTS` (KeyError naming the metrics there are)."""
        if name in self.values:
            return self.values[name]
        if name in OUTPUTS and any(f.name == name for f in dataclasses.fields(self)):
            return getattr(self, name)
        raise KeyError(f"{name!r}: not a metric of this run (metrics: {', '.join(self.values)})")

    @property
    def window(self) -> tuple[float, float]:
        """``(window_start, window_end)``, s."""
        return (self.window_start, self.window_end)



def _series(name: str, x: ArrayLike) -> NDArray[np.float64]:
    xa = np.ascontiguousarray(x, dtype=float)
    if xa.ndim != 1:
        raise ValidationError(name, f"an array of shape {xa.shape}", "a 1-D array")
    return xa


def stick_slip_metrics(
    t: ArrayLike,
    omega_bit: ArrayLike,
    motor_torque: Optional[ArrayLike] = None,
    *,
    window: Optional[tuple[float, float]] = None,
    stick_speed: float = STICK_SPEED,
) -> StickSlipMetrics:
    """Stick-slip metrics of a bit-speed series (and optionally the motor torque).

    Works on any series, uniformly or non-uniformly sampled (a simulation, another simulator,
    field data); the series is taken as linear between samples and means are time-weighted
    (trapezoidal rule). Computed by the core; nothing is recomputed here.

    Parameters
    ----------
    t : array_like
        Sample times, s, finite and strictly increasing.
    omega_bit : array_like
        Bit angular speed, rad/s, one per time.
    motor_torque : array_like, optional
        Motor torque (any unit), one per time.
    window : (t_start, t_end), optional
        Only the samples with ``t_start <= t <= t_end`` (at least 2); None: all.
    stick_speed : float
        The bit counts as stuck while ``|omega_bit| <= stick_speed`` (rad/s, >= 0).

    Returns
    -------
    StickSlipMetrics
        Every metric of :data:`OUTPUTS` with ``stick_slip`` (``metrics[name]``): severity
        ``ssi = (max - min) / (2 |mean|)`` of the bit speed, stuck fraction, bit rpm
        min / max / mean, motor torque min / max and its period ``period_s``.

    Raises
    ------
    ValidationError
        Naming the argument: ``t`` not strictly increasing, series of other lengths or not
        finite, a window holding fewer than 2 samples, a negative ``stick_speed``.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 10001)
    >>> omega = np.maximum(0.0, 10.0 * (1.0 + 2.0 * np.sin(2 * np.pi * 0.5 * t)))
    >>> m = stick_slip_metrics(t, omega, window=(2.0, 10.0))
    >>> round(m.stuck_fraction, 3)  # arccos(1/2) / pi
    0.333
    """
    ta = _series("t", t)
    torque = None if motor_torque is None else _series("motor_torque", motor_torque)
    span = None if window is None else (float(window[0]), float(window[1]))
    d = _core.stick_slip_metrics(
        ta, _series("omega_bit", omega_bit), torque, window=span, stick_speed=float(stick_speed)
    )
    return StickSlipMetrics.from_core(d)


def break_off_torque(depth: ArrayLike, limit: ArrayLike) -> float:
    """The static break-off torque of a well, N m: the integral over measured depth of the
    friction limit per metre (trapezoidal rule).

    Parameters
    ----------
    depth : array_like
        Measured depths, m, strictly increasing.
    limit : array_like
        Friction limit per metre at each depth, N m/m (>= 0).

    Examples
    --------
    >>> break_off_torque([0.0, 1000.0, 2500.0], [4.0, 4.0, 4.0])
    10000.0
    """
    return _core.break_off_torque(_series("depth", depth), _series("limit", limit))
