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
  their linear stability (eigenvalues of the 3x3 Jacobian in ``(wr, phi, wb)``) and what they predict, ``equilibrium``:
  ``"stable_rotation"``, ``"unstable"`` (stick-slip or a growing oscillation) or ``"stuck"``
  (no steady rotation; the bit at rest, ``wr = 0`` and ``kt phi = tm``, is an equilibrium whenever
  ``tm <= wob rb mu_sb``);
* :func:`lumped_defaults`: the published parameters (``tm = 6000 N m``, ``wob = 50 kN``);
* :func:`lumped_figure` the time histories of a run;
* :func:`lumped_sweep` both over the values of one parameter (e.g. the weight on bit): the
  steady speeds and their stability next to what a run from rest does, one row per value, and
  :func:`lumped_sweep_figure` draws them (the onset of stick-slip against the equilibria).

>>> from drillstring.drilling import lumped, lumped_equilibria
>>> lumped_equilibria({"wob": 30e3}).equilibrium
'stable_rotation'
>>> res = lumped({"wob": 55e3}, duration=100.0)
>>> res.metrics.stuck_fraction > 0
True
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Optional, Union, cast

import numpy as np
from numpy.typing import NDArray

from .. import _core
from ..errors import SolveError, ValidationError
from ..limits import as_float, json_ready
from .metrics import BIT_RPM_MAX, BIT_RPM_MEAN, BIT_RPM_MIN, OUTPUTS, PERIOD, SSI, STUCK_FRACTION, StickSlipMetrics

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = ["LumpedEquilibria", "LumpedParams", "LumpedResult", "LumpedRotation", "lumped", "lumped_defaults",
           "lumped_equilibria", "lumped_figure", "lumped_sweep", "lumped_sweep_figure"]


def lumped_defaults() -> dict[str, float]:
    """The default parameters (Navarro-Lopez & Cortes 2007, ``tm = 6000`` N m, ``wob = 50e3`` N),
    as the core defines them: ``jr``, ``jb`` kg m^2; ``kt`` N m/rad; ``ct``, ``cr``, ``cb``
    N m s/rad; ``rb`` m; ``mu_cb``, ``mu_sb``; ``gamma_b`` s/rad; ``v_f``, ``d_v`` rad/s;
    ``tm`` N m; ``wob`` N."""
    params: dict[str, float] = _core.lumped_defaults()[0]
    return params


_CORE_DEFAULTS: dict[str, float] = _core.lumped_defaults()[0]


def _param(name: str, doc: str) -> Any:
    return field(default=_CORE_DEFAULTS[name], metadata={"doc": doc})


@dataclass(frozen=True)
class LumpedParams:
    """The parameters of the lumped two-inertia model (Navarro-Lopez & Cortes 2007), every
    default the core's (:func:`lumped_defaults`). Constructing one has the core validate it:
    a value out of range raises :class:`~drillstring.errors.ValidationError` naming the field.
    :func:`lumped`, :func:`lumped_equilibria` and :func:`lumped_sweep` take one, or a mapping
    of some of the names.

    >>> p = LumpedParams(wob=60e3)
    >>> p.tm, p.wob
    (6000.0, 60000.0)
    """

    jr: float = _param("jr", "rotary table (top) inertia, kg m^2")
    jb: float = _param("jb", "bit (bottom) inertia, kg m^2")
    kt: float = _param("kt", "torsional stiffness of the string, N m/rad")
    ct: float = _param("ct", "torsional damping of the string, N m s/rad")
    cr: float = _param("cr", "viscous damping at the top, N m s/rad")
    cb: float = _param("cb", "viscous damping at the bit, N m s/rad")
    rb: float = _param("rb", "bit radius, m")
    mu_cb: float = _param("mu_cb", "bit Coulomb (kinetic) friction coefficient")
    mu_sb: float = _param("mu_sb", "bit static friction coefficient")
    gamma_b: float = _param("gamma_b", "decay of the friction from static to kinetic, s/rad")
    v_f: float = _param("v_f", "velocity of the friction law's decay, rad/s")
    d_v: float = _param("d_v", "stick band of the bit speed, rad/s")
    tm: float = _param("tm", "motor torque at the top, N m")
    wob: float = _param("wob", "weight on bit, N")

    def __post_init__(self) -> None:
        _core.lumped_equilibria(_params_json(self.to_dict()))  # the core's validation, naming the field

    def to_dict(self) -> dict[str, float]:
        """The parameters as a plain dict of the core's names."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


def _numerics(duration: Any, dt: Any, output_interval: Any, initial: Any, window: Any = None,
              stick_speed: Any = None) -> dict[str, Any]:
    """The numerical settings of a run as the core takes them, each a finite number (or
    :class:`~drillstring.errors.ValidationError` naming it, before any work; ranges are the core's)."""
    numerics: dict[str, Any] = {key: as_float(key, value, "a finite number > 0") for key, value in
                                (("duration", duration), ("dt", dt), ("output_interval", output_interval))}
    allowed = "three finite numbers (wr rad/s, phi rad, wb rad/s)"
    if isinstance(initial, (str, bytes, Mapping)) or not isinstance(initial, (Sequence, np.ndarray)) or len(
            initial) != 3:
        raise ValidationError("initial", initial, allowed)
    numerics["initial"] = [as_float(f"initial[{i}]", x, allowed) for i, x in enumerate(initial)]
    if window is not None:
        if isinstance(window, (str, bytes)) or not isinstance(window, (Sequence, np.ndarray)) or len(window) != 2:
            raise ValidationError("window", window, "(t_start, t_end), s")
        numerics["window"] = [as_float(f"window[{i}]", x, "a finite number, s") for i, x in enumerate(window)]
    if stick_speed is not None:
        numerics["stick_speed"] = as_float("stick_speed", stick_speed, "a finite number >= 0, rad/s")
    return numerics


def _params_json(params: Optional[Any]) -> str:
    """``params`` (a :class:`LumpedParams` or a mapping of some of the names) as the JSON the core
    parses and validates (an unknown name, a value that is not a number or out of range:
    ValidationError naming the field)."""
    if isinstance(params, LumpedParams):
        params = params.to_dict()
    if params is not None and not isinstance(params, Mapping):
        raise ValidationError("params", params, "a mapping of parameter names to numbers")
    return json.dumps(json_ready(dict(params or {})))


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
    (``motor_torque_min_Nm``, ``motor_torque_max_Nm``, ``period_s`` are the spring torque's)."""
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
    equilibrium: str
    """What the equilibria predict: ``"stable_rotation"`` (a stable root), ``"unstable"`` (roots,
    none stable) or ``"stuck"``."""
    static_limit: float
    """``wob rb mu_sb``, N m."""


def lumped_equilibria(params: Union[LumpedParams, Mapping[str, Any], None] = None) -> LumpedEquilibria:
    """The steady rotations of the lumped model with ``params`` (over :func:`lumped_defaults`),
    their stability and what they predict, ``equilibrium`` (computed by the core).

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
                            equilibrium=str(raw["equilibrium"]), static_limit=float(raw["static_limit"]))


def lumped(
    params: Union[LumpedParams, Mapping[str, Any], None] = None,
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
    numerics = _numerics(duration, dt, output_interval, initial, window, stick_speed)
    params_json = _params_json(params)
    if progress is not None:
        progress(0.0)
    raw = _core.lumped_solve(params_json, json.dumps(numerics), progress)
    if progress is not None and raw["status"] == "success":
        progress(1.0)
    full = _core.lumped_defaults()[0]
    full.update(json.loads(params_json))
    result = LumpedResult(
        params=full,
        t=raw["t"], top_speed=raw["top_speed"], bit_speed=raw["bit_speed"],
        spring_torque=raw["spring_torque"], bit_torque=raw["bit_torque"],
        metrics=StickSlipMetrics.from_core(raw["metrics"]), window=(float(raw["window"][0]), float(raw["window"][1])),
        energy=dict(cast("dict[str, float]", raw["energy"])),
        stats=dict(raw["stats"]),
        status=str(raw["status"]), message=str(raw["message"]),
    )
    if check and result.status != "success":
        raise SolveError(result.status, result.message, result=result)
    return result


#: rpm per rad/s, for display (the core's speeds are rad/s; its metrics give rpm).
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def lumped_figure(result: LumpedResult, title: Optional[str] = None) -> Figure:
    """Time histories of a :func:`lumped` run: rotary-table and bit speed above, spring and bit
    torque below, the metrics window shaded."""
    from matplotlib.figure import Figure

    rpm = RPM_PER_RAD_S
    fig = Figure(figsize=(7.0, 5.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    for ax in (top, bottom):
        ax.axvspan(*result.window, color="0.92", zorder=0, lw=0)
    top.plot(result.t, result.top_speed * rpm, color="tab:blue", lw=1.0, label="rotary table")
    top.plot(result.t, result.bit_speed * rpm, color="tab:orange", lw=1.0, label="bit")
    top.set_ylabel("speed (rpm)")
    top.legend(fontsize="small")
    bottom.plot(result.t, result.spring_torque * 1e-3, color="tab:blue", lw=1.0, label="spring")
    bottom.plot(result.t, result.bit_torque * 1e-3, color="tab:orange", lw=1.0, label="bit")
    bottom.set_ylabel("torque (kN m)")
    bottom.set_xlabel("t (s)")
    bottom.legend(fontsize="small")
    m = result.metrics
    top.set_title(title or f"Lumped two-inertia model, wob = {result.params['wob'] * 1e-3:g} kN, "
                  f"tm = {result.params['tm']:g} N m: SSI {m.ssi:.3g}, stuck {m.stuck_fraction:.2f}")
    return fig


#: The run's stick-slip metrics in a :func:`lumped_sweep` row, by the registry's names.
SWEEP_METRICS: tuple[str, ...] = (SSI, STUCK_FRACTION, PERIOD, BIT_RPM_MIN, BIT_RPM_MAX, BIT_RPM_MEAN)

#: The columns of :func:`lumped_sweep` after the parameter's own.
SWEEP_COLUMNS: tuple[str, ...] = (
    "equilibrium", "stuck_possible", "static_limit_Nm", "rotation_1", "stable_1", "rotation_2", "stable_2",
    "status", *SWEEP_METRICS, "spring_torque_min_Nm", "spring_torque_max_Nm", "balance_error",
)


def lumped_sweep(
    name: str,
    values: Sequence[float],
    params: Union[LumpedParams, Mapping[str, Any], None] = None,
    *,
    duration: float = 200.0,
    dt: float = 1e-3,
    initial: Sequence[float] = (0.0, 0.0, 0.0),
    progress: Optional[Callable[[float], object]] = None,
) -> pd.DataFrame:
    """The lumped model at each of ``values`` of the parameter ``name`` (over ``params`` and
    :func:`lumped_defaults`): its equilibria (:func:`lumped_equilibria`) and a run from ``initial``
    (:func:`lumped`, metrics over the last half), one row per value.

    Columns: ``name``; ``equilibrium``, ``stuck_possible``, ``static_limit_Nm``; ``rotation_1``,
    ``rotation_2`` (the steady speeds by increasing value, rad/s, NaN where there are fewer) and
    ``stable_1``, ``stable_2`` (None where absent); the run's ``status``, ``ssi``,
    ``stuck_fraction``, ``period_s``, ``bit_rpm_min/max/mean``, ``spring_torque_min/max_Nm`` and
    ``balance_error`` (NaN where the run has no metrics). Every number comes from the core.

    Raises
    ------
    ValidationError
        ``name`` is not a parameter, a value is not a finite number or makes the parameters
        invalid (naming the field), or ``values`` is empty.

    Examples
    --------
    >>> frame = lumped_sweep("wob", [30e3, 55e3], duration=100.0)
    >>> list(frame.equilibrium), [bool(f > 0) for f in frame.stuck_fraction]
    (['stable_rotation', 'stable_rotation'], [False, True])
    """
    import pandas as pd

    if name not in lumped_defaults():
        raise ValidationError("name", name, f"a parameter name, one of {', '.join(lumped_defaults())}")
    try:
        values = [value for value in values]
    except TypeError:
        raise ValidationError("values", values, "a sequence of numbers") from None
    if not values:
        raise ValidationError("values", values, "at least one value")
    _numerics(duration, dt, 0.01, initial)  # refused before any run
    rows: list[dict[str, Any]] = []
    for k, value in enumerate(values):
        base = params.to_dict() if isinstance(params, LumpedParams) else dict(params or {})
        p = {**base, name: value}
        eq = lumped_equilibria(p)
        res = lumped(p, duration=duration, dt=dt, initial=initial, check=False)
        speeds = [r.speed for r in eq.rotations] + [math.nan] * (2 - len(eq.rotations))
        stable: list[Optional[bool]] = [r.stable for r in eq.rotations] + [None] * (2 - len(eq.rotations))
        m = res.metrics
        rows.append({
            name: float(value), "equilibrium": eq.equilibrium, "stuck_possible": eq.stuck_possible,
            "static_limit_Nm": eq.static_limit, "rotation_1": speeds[0], "stable_1": stable[0],
            "rotation_2": speeds[1], "stable_2": stable[1], "status": res.status,
            **{metric: m[metric] for metric in SWEEP_METRICS}, "spring_torque_min_Nm": m.motor_torque_min_Nm,
            "spring_torque_max_Nm": m.motor_torque_max_Nm, "balance_error": res.energy.get("balance_error", math.nan),
        })
        if progress is not None:
            progress((k + 1) / len(values))
    frame = pd.DataFrame(rows, columns=[name, *SWEEP_COLUMNS])
    frame.attrs.update(parameter=name, duration=float(duration), initial=[float(x) for x in initial])
    return frame


def lumped_sweep_figure(frame: pd.DataFrame, title: Optional[str] = None) -> Figure:
    """Two panels over the swept parameter of a :func:`lumped_sweep` frame: the steady speeds
    (filled: stable, open: unstable) with the band of bit speeds of the runs (min to max over
    the metrics window) and their mean; below, the stick-slip severity and the stuck fraction,
    with SSI = 1 marked."""
    from matplotlib.figure import Figure

    name = str(frame.attrs.get("parameter", frame.columns[0]))
    scale, unit = (1e-3, "kN") if name == "wob" else (1.0, "")
    x = frame[name].to_numpy(dtype=float) * scale
    rpm = RPM_PER_RAD_S
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.fill_between(x, frame[BIT_RPM_MIN], frame[BIT_RPM_MAX], color="tab:orange", alpha=0.25, lw=0,
                     label="bit speed of the run, min to max")
    top.plot(x, frame[BIT_RPM_MEAN], color="tab:orange", lw=1.2, label="bit speed of the run, mean")
    for k in (1, 2):
        speed = frame[f"rotation_{k}"].to_numpy(dtype=float) * rpm
        stable = frame[f"stable_{k}"].to_numpy(dtype=object)
        is_stable = np.array([s is True for s in stable])
        is_unstable = np.array([s is False for s in stable])
        top.plot(x[is_stable], speed[is_stable], "o", color="tab:blue", ms=4,
                 label="steady rotation, stable" if k == 1 else None)
        top.plot(x[is_unstable], speed[is_unstable], "o", mfc="none", color="tab:blue", ms=4,
                 label="steady rotation, unstable" if k == 1 else None)
    top.set_ylabel("speed (rpm)")
    top.legend(fontsize="small")
    bottom.plot(x, frame[SSI], color="tab:red", label=OUTPUTS[SSI].label)
    bottom.plot(x, frame[STUCK_FRACTION], color="tab:gray", label=OUTPUTS[STUCK_FRACTION].label)
    bottom.axhline(1.0, color="tab:red", lw=0.8, ls="--")
    bottom.set_ylabel("severity")
    bottom.set_xlabel(f"{name} ({unit})" if unit else name)
    bottom.legend(fontsize="small")
    top.set_title(title or f"Lumped two-inertia model against {name}: equilibria and runs from rest")
    return fig
