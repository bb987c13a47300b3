"""The lumped two-inertia stick-slip model of Navarro-Lopez & Cortes (2007), solved in the core.

E. M. Navarro-Lopez, R. Cortes, "Avoiding harmful oscillations in a drillstring through
dynamical analysis", J. Sound Vib. 307 (2007) 152-171: the rotary table (``jr``) and the bit
(``jb``) joined by a torsional spring ``kt`` and damper ``ct``, viscous damping ``cr`` at the
top and ``cb`` at the bit, a constant motor torque ``tm`` and the velocity-weakening bit torque
``wob rb (mu_cb + (mu_sb - mu_cb) exp(-gamma_b |wb| / v_f)) sign(wb)`` with a true stick phase
(the bit stays at rest while the torque applied to it is within ``wob rb mu_sb``). The same
bit-torque function as the distributed string's bit (its ``decay`` is ``gamma_b / v_f``).

* :func:`lumped` runs it (``drillstring_core::drilling::lumped::solve_lumped``: fourth-order
  Runge-Kutta with the stick and slip switches located within the step) and returns the speeds,
  the spring and bit torques, the stick-slip metrics (the same core function as every other
  run, with the spring torque as the torque series) and the energy balance;
* :func:`lumped_equilibria` the steady rotations (roots of ``tm = (cr + cb) w + wob rb mu(w)``),
  their linear stability (eigenvalues of the 3x3 Jacobian in ``(wr, phi, wb)``) and the regime:
  ``"stable_rotation"``, ``"unstable"`` (stick-slip or a growing oscillation) or ``"stuck"``
  (no steady rotation; the bit at rest, ``wr = 0`` and ``kt phi = tm``, is an equilibrium whenever
  ``tm <= wob rb mu_sb``);
* :func:`lumped_defaults`: the published parameters (``tm = 6000 N m``, ``wob = 50 kN``).

>>> from drillstring.drilling import lumped, lumped_equilibria
>>> lumped_equilibria({"wob": 30e3}).regime
'stable_rotation'
>>> res = lumped({"wob": 55e3}, duration=100.0)
>>> res.metrics.stuck_fraction > 0
True
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Callable, Optional, cast

import numpy as np
from numpy.typing import NDArray

from .. import _core
from ..analysis import StickSlipMetrics
from ..errors import SolveError, ValidationError

__all__ = ["LumpedEquilibria", "LumpedResult", "LumpedRotation", "lumped", "lumped_defaults", "lumped_equilibria"]


def lumped_defaults() -> dict[str, float]:
    """The default parameters (Navarro-Lopez & Cortes 2007, ``tm = 6000`` N m, ``wob = 50e3`` N),
    as the core defines them: ``jr``, ``jb`` kg m^2; ``kt`` N m/rad; ``ct``, ``cr``, ``cb``
    N m s/rad; ``rb`` m; ``mu_cb``, ``mu_sb``; ``gamma_b`` s/rad; ``v_f``, ``d_v`` rad/s;
    ``tm`` N m; ``wob`` N."""
    params: dict[str, float] = json.loads(_core.lumped_defaults()[0])
    return params


def _params_json(params: Optional[Mapping[str, Any]]) -> str:
    known = lumped_defaults()
    out: dict[str, float] = {}
    for key, value in (params or {}).items():
        if key not in known:
            raise ValidationError(key, value, f"a parameter name, one of {', '.join(known)}")
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
            raise ValidationError(key, value, "a number")
        number = float(value)
        if not math.isfinite(number):
            raise ValidationError(key, value, "a finite number")
        out[key] = number
    return json.dumps(out)


@dataclass(frozen=True)
class LumpedResult:
    """One run of the lumped model (:func:`lumped`); everything computed by the core."""

    params: dict[str, float]
    """The parameters solved (all of them, defaults filled in)."""
    t: NDArray[np.float64]
    """Sample times, s."""
    top_speed: NDArray[np.float64]
    """Rotary-table speed ``wr``, rad/s."""
    bit_speed: NDArray[np.float64]
    """Bit speed ``wb``, rad/s (exactly 0 while stuck)."""
    spring_torque: NDArray[np.float64]
    """``kt (phr - phb)``, N m."""
    bit_torque: NDArray[np.float64]
    """The bit-rock torque: the slip law while slipping, the holding torque while stuck, N m."""
    metrics: StickSlipMetrics
    """Over ``window``, of the bit speed with the spring torque as the torque series
    (``torque_min``, ``torque_max``, ``cycle_period`` are the spring torque's)."""
    window: tuple[float, float]
    energy: dict[str, float]
    """``motor_work``, ``initial``, ``kinetic_top``, ``kinetic_bit``, ``spring`` (at the end),
    ``viscous_loss``, ``friction_loss``, J; ``balance_error`` (relative residual of
    ``motor_work = change + losses``)."""
    stats: dict[str, int]
    """``steps``, ``sticks``, ``slips``."""
    status: str
    message: str


@dataclass(frozen=True)
class LumpedRotation:
    """A steady rotation ``wr = wb = speed`` and its linear stability."""

    speed: float
    """rad/s."""
    twist: float
    """``phr - phb``, rad."""
    eigenvalues: NDArray[np.complex128]
    """Of the Jacobian in ``(wr, phi, wb)``, by increasing real part."""
    stable: bool


@dataclass(frozen=True)
class LumpedEquilibria:
    """What :func:`lumped_equilibria` returns."""

    rotations: tuple[LumpedRotation, ...]
    """By increasing speed (0, 1 or 2)."""
    stuck_possible: bool
    """``tm <= wob rb mu_sb``: the bit at rest (``wr = 0``, ``kt phi = tm``) is an equilibrium (started
    there it stays; from rest untwisted the wind-up can overshoot and break it free)."""
    regime: str
    """``"stable_rotation"`` (a stable root), ``"unstable"`` (roots, none stable) or ``"stuck"``."""
    static_limit: float
    """``wob rb mu_sb``, N m."""


def lumped_equilibria(params: Optional[Mapping[str, Any]] = None) -> LumpedEquilibria:
    """The steady rotations of the lumped model with ``params`` (over :func:`lumped_defaults`),
    their stability and the regime (computed by the core).

    >>> eq = lumped_equilibria({"wob": 50e3})
    >>> [round(r.speed, 3) for r in eq.rotations], eq.stuck_possible
    ([0.15, 4.345], True)
    """
    raw = _core.lumped_equilibria(_params_json(params))
    rotations = tuple(
        LumpedRotation(speed=float(r["speed"]), twist=float(r["twist"]),
                       eigenvalues=np.array([complex(re, im) for re, im in r["eigenvalues"]]),
                       stable=bool(r["stable"]))
        for r in raw["rotations"])
    return LumpedEquilibria(rotations=rotations, stuck_possible=bool(raw["stuck_possible"]),
                            regime=str(raw["regime"]), static_limit=float(raw["static_limit"]))


def lumped(
    params: Optional[Mapping[str, Any]] = None,
    *,
    duration: float = 200.0,
    dt: float = 1e-3,
    output_interval: float = 0.01,
    initial: Sequence[float] = (0.0, 0.0, 0.0),
    window: Optional[tuple[float, float]] = None,
    stick_speed: Optional[float] = None,
    progress: Optional[Callable[[float], object]] = None,
    check: bool = True,
) -> LumpedResult:
    """Runs the lumped two-inertia model in the core.

    Parameters
    ----------
    params : mapping, optional
        Parameters over :func:`lumped_defaults` (e.g. ``{"wob": 40e3, "tm": 6000}``).
    duration, dt, output_interval : float
        Simulated time, Runge-Kutta step and sample interval, s.
    initial : (wr, phi, wb)
        Initial rotary-table speed rad/s, twist rad and bit speed rad/s (default: at rest).
    window : (t_start, t_end), optional
        The metrics window (default: the last half of the run).
    stick_speed : float, optional
        The stuck threshold of the metrics, rad/s (default the metrics' ``STICK_SPEED``).
    progress : callable, optional
        Called with the fraction done: at the start (0), about every 20 ms while the core steps,
        and at the end (1); an exception it raises stops the run and is raised here.
    check : bool
        Raise :class:`~drillstring.errors.SolveError` when the run stops early (default).

    Raises
    ------
    ValidationError
        A parameter or numerical setting out of range, naming it.

    Examples
    --------
    >>> res = lumped({"wob": 30e3}, duration=300.0)
    >>> round(float(res.bit_speed[-1]), 4), res.metrics.stuck_fraction
    (7.7158, 0.0)
    """
    numerics: dict[str, Any] = {"duration": float(duration), "dt": float(dt),
                                "output_interval": float(output_interval),
                                "initial": [float(x) for x in initial]}
    if len(numerics["initial"]) != 3:
        raise ValidationError("initial", initial, "three numbers (wr rad/s, phi rad, wb rad/s)")
    if window is not None:
        numerics["window"] = [float(window[0]), float(window[1])]
    if stick_speed is not None:
        numerics["stick_speed"] = float(stick_speed)
    for key in ("duration", "dt", "output_interval"):
        if not math.isfinite(numerics[key]):
            raise ValidationError(key, numerics[key], "a finite number > 0")
    params_json = _params_json(params)
    if progress is not None:
        progress(0.0)
    raw = _core.lumped_solve(params_json, json.dumps(numerics), progress)
    if progress is not None and raw["status"] == "success":
        progress(1.0)
    full = json.loads(_core.lumped_defaults()[0])
    full.update(json.loads(params_json))
    result = LumpedResult(
        params=full,
        t=raw["t"], top_speed=raw["top_speed"], bit_speed=raw["bit_speed"],
        spring_torque=raw["spring_torque"], bit_torque=raw["bit_torque"],
        metrics=StickSlipMetrics(**raw["metrics"]), window=(float(raw["window"][0]), float(raw["window"][1])),
        energy=dict(cast("dict[str, float]", raw["energy"])),
        stats=dict(raw["stats"]),
        status=str(raw["status"]), message=str(raw["message"]),
    )
    if check and result.status != "success":
        raise SolveError(result.status, result.message, result=result)
    return result
