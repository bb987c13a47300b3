"""Stick-slip metrics of bit-speed and motor-torque series (computed by the core's
``metrics::stickslip``), for drilling runs, the lumped model and field data."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .. import _core
from ..errors import ValidationError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray


__all__ = ["STICK_SPEED", "StickSlipMetrics", "stick_slip_metrics", "break_off_torque"]


#: Default stick threshold speed of :func:`stick_slip_metrics`, rad/s (about 0.1 rpm).
STICK_SPEED: float = _core.STICK_SPEED


@dataclass(frozen=True)
class StickSlipMetrics:
    """Stick-slip metrics of one window (see :func:`stick_slip_metrics`)."""

    t_start: float
    """First sample time in the window, s."""
    t_end: float
    """Last sample time in the window, s."""
    severity: float
    """``(max - min) / (2 |mean|)`` of the bit speed (NaN when the mean is 0)."""
    stuck_fraction: float
    """Fraction of the window's time with ``|omega_bit| <= stick_speed``."""
    rpm_min: float
    rpm_max: float
    rpm_mean: float
    """Time-weighted (trapezoidal) mean bit speed, rpm."""
    torque_min: float
    """Motor torque minimum (NaN without a torque series)."""
    torque_max: float
    cycle_period: float
    """The motor torque's period from its autocorrelation (the similarity of the series with
    itself shifted, searched up to half the window), s (NaN with fewer than two cycles in the
    window or without a torque series)."""
    period_cycles: float
    """The window's length in periods (NaN without one)."""
    periodicity: float
    """Similarity of the motor torque with itself one period later (1: exactly periodic)."""
    slip_period: float
    """Mean interval between the bit's slip onsets (its speed rising through ``stick_speed`` in
    the direction of its mean, for a slip that carries it above its mean speed), s (NaN with
    fewer than three)."""
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
        Severity ``SSI = (max - min) / (2 |mean|)`` of the bit speed, stuck fraction, bit rpm
        min / max / mean, motor torque min / max and its cycle period (the mean interval
        between upward crossings of its mean, one per cycle).

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
    return stick_slip_from_core(d)


def stick_slip_from_core(d: Any) -> StickSlipMetrics:
    """:class:`StickSlipMetrics` from the core's dict (its ``warnings`` list as a tuple)."""
    return StickSlipMetrics(**{**d, "warnings": tuple(d.get("warnings", ()))})


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
