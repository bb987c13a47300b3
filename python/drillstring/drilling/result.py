"""What a drilling-system solve returns: time series, space-time fields, the friction profile,
stick-slip metrics and the energy balance, all computed by the core; exports."""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from .. import _core
from .config import DrillConfig
from .metrics import OUTPUTS, REGIME, STICK_SLIP_CRITERION, StickSlipMetrics

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

__all__ = ["SERIES", "UNITS", "METRICS", "DrillMetrics", "DrillProfile", "DrillResult"]

#: The time series of a run, in the order of the tables (``t`` is the index): the core's series
#: channels of a torsional run (:data:`~drillstring.drilling.metrics.OUTPUTS`).
SERIES: tuple[str, ...] = tuple(o.name for o in OUTPUTS.values() if o.kind == "series" and "torsional" in o.runs)
#: A coupled run's series (``DrillResult.axial``), by the core's names.
AXIAL_SERIES: tuple[str, ...] = tuple(o.name for o in OUTPUTS.values() if o.kind == "series" and "coupled" in o.runs)

#: Units of the series, fields, profile and metrics (the series' from the core's registry).
UNITS: dict[str, str] = {
    "t": "s",
    **{name: str(OUTPUTS[name].unit).replace("*", " ") for name in (*SERIES, *AXIAL_SERIES)},
    "z": "m",
    "field_t": "s",
    "omega_field": "rpm",
    "torque_field": "N m",
    "limit_per_m": "N m/m",
    "cumulative": "N m",
    "breakoff_torque": "N m",
    "min_cycle_torque": "N m",
    # a coupled run's axial fields, as the core gives them
    "axial_z": "m",
    "axial_speed_field": "m/s",
    "axial_force_field": "N",
}


#: The criterion of a coupled run's regime (:attr:`DrillResult.coupled_regime`; the core's
#: ``drilling::axial::regime::regime``), as ``metrics.json`` and ``report.md`` state it.
COUPLED_REGIME_CRITERION: str = _core.COUPLED_REGIME_CRITERION

#: The coupled regimes' names, in a map legend's order.
COUPLED_REGIMES: tuple[str, ...] = tuple(_core.COUPLED_REGIMES)

#: The coupled metrics of ``metrics.json``'s ``coupled`` block and a coupled map's columns, in order
#: (``regime`` the text one).
COUPLED_METRICS: tuple[str, ...] = tuple(o.name for o in OUTPUTS.values() if o.map_column and "coupled" in o.runs)

#: What each entry of ``metrics.json`` is (written beside the numbers): the core's definitions.
METRIC_DEFINITIONS: dict[str, str] = {
    o.name: o.definition for o in OUTPUTS.values() if o.map_column and "torsional" in o.runs}

#: The SI unit of each numeric metric of a coupled run (:data:`COUPLED_METRICS`), as
#: :data:`METRIC_UNITS`.
COUPLED_METRIC_UNITS: dict[str, str] = {
    name: str(OUTPUTS[name].unit) for name in COUPLED_METRICS if OUTPUTS[name].kind == "number"}

#: The metrics of :data:`METRICS` that are text (the others are numbers and verdicts as true/false).
TEXT_METRICS: tuple[str, ...] = tuple(name for name in METRIC_DEFINITIONS if OUTPUTS[name].kind == "text")


#: The SI unit of each numeric metric as pint parses it (``""`` dimensionless); a unit system's
#: copy in ``metrics.json`` (``output_units``) converts by it (:mod:`drillstring.drilling.units`).
METRIC_UNITS: dict[str, str] = {
    name: str(OUTPUTS[name].unit) for name in METRIC_DEFINITIONS if OUTPUTS[name].kind == "number"}


#: The metrics of ``metrics.json`` and a map's columns, in order (the keys of :data:`METRIC_DEFINITIONS`).
METRICS: tuple[str, ...] = tuple(METRIC_DEFINITIONS)


@dataclass(frozen=True)
class DrillMetrics(StickSlipMetrics):
    """Stick-slip metrics of a run over its window, as the core computes them
    (``drillstring_core::metrics::stickslip``, the function behind
    :func:`drillstring.drilling.metrics.stick_slip_metrics`: the metrics of
    :class:`~drillstring.drilling.metrics.StickSlipMetrics`, with ``window_start`` and
    ``window_end`` the window asked for, by default the last half of the run), and the static
    torques of the string in the well. NaN where a metric is undefined (no full cycle in the
    window: no period). ``metrics.json`` and a map hold :data:`METRICS`."""

    breakoff_torque_Nm: float = math.nan
    """Static break-off torque of the string in the well (the integral of the friction limit), N m."""
    min_cycle_torque_Nm: float = math.nan
    """The minimum motor torque of a stick-slip cycle that break-off implies, ``2 K - S`` (``S`` the
    static torque of the wall and, on bottom, the bit; ``K`` the same contacts at their kinetic
    torque): ``breakoff (1 - 2 (1 - kinetic_ratio))`` off bottom, as ``tauMin`` of Aarsnes & Shor's
    code (``drillstring_core::drilling::grid::min_cycle_torque``), N m."""

    def to_dict(self) -> dict[str, Any]:
        """``{name: value}`` of :data:`METRICS` with NaN as ``None`` (JSON-ready; the verdict a string)."""
        out: dict[str, Any] = {}
        for name in METRICS:
            value = self[name] if name in self.values or hasattr(self, name) else math.nan
            out[name] = None if name not in TEXT_METRICS and math.isnan(value) else value
        return out


#: How far each metric may move between the two runs of a check before it warns (the grid check,
#: :func:`drillstring.drill` with ``check_grid=True``, ``drillstring drill --check-grid``, and the
#: start check, ``check_start=True``, ``--check-start``): ``(kind, tolerance)`` with kind ``"rel"``
#: (relative change), ``"abs"`` (in the metric's unit) or ``"equal"`` (a verdict or regime that
#: must not change). The core's table (each metric's ``tolerance`` in its registry of outputs),
#: coupled metrics included; the core also holds each metric's floor, a change too small to count
#: whatever its relative size (the SSI's 0.01), in :data:`GRID_FLOORS`.
GRID_TOLERANCES: dict[str, tuple[str, float]] = {
    str(name): (str(kind), float(tol)) for name, kind, tol, _ in _core.drill_compare_tolerances()}
GRID_FLOORS: dict[str, float] = {str(name): float(floor) for name, _, _, floor in _core.drill_compare_tolerances()}

CheckValue = Union[float, str, None]


def _check_metrics(result: DrillResult) -> dict[str, CheckValue]:
    """A run's metrics as the core's comparison takes them (numbers, texts, None for undefined;
    verdicts as 0 / 1; a coupled run's ``coupled`` block with its regime)."""
    out: dict[str, CheckValue] = {}
    for name, value in result.metrics.to_dict().items():
        out[name] = float(value) if isinstance(value, bool) else value
    if result.coupled_metrics is not None:
        out.update(result.coupled_metrics)
        out[REGIME] = result.coupled_regime
    return out


def _compared(a: DrillResult, b: DrillResult) -> list[dict[str, Any]]:
    """The core's rows (``_core.drill_compare``) of two runs' metrics."""
    return list(_core.drill_compare(_check_metrics(a), _check_metrics(b)))


def _moved(r: Any, first: str, second: str) -> str:
    """How a row's metric moved between the runs ``first`` and ``second``, in words."""
    if r.change is None:
        return f"is {r.value} {first} and {r.other} {second}"
    if r.kind == "equal":
        return f"is {r.value!r} {first} and {r.other!r} {second}"
    if r.kind == "rel":
        return f"moves by {100 * r.change:+.3g} % from {r.value:.5g} {first} to {r.other:.5g} {second} " \
               f"(tolerance {100 * r.tolerance:g} %)"
    return f"moves by {r.change:+.4g} from {r.value:.5g} {first} to {r.other:.5g} {second} (tolerance {r.tolerance:g})"


@dataclass(frozen=True)
class GridCheckRow:
    """One metric of a grid check: its value on the run's grid and on twice the cells."""

    metric: str
    value: CheckValue
    refined: CheckValue
    change: Optional[float]
    """``refined - value`` (``"abs"``), ``refined / value - 1`` (``"rel"``; None when ``value``
    is 0), or 0 / 1 for a verdict or regime that kept / changed."""
    kind: str
    tolerance: float
    within: bool
    """The change is within the tolerance (a metric undefined on one grid only is not)."""

    @property
    def other(self) -> CheckValue:
        return self.refined


@dataclass(frozen=True)
class GridCheck:
    """A run repeated on twice the cells (:data:`GRID_TOLERANCES`): how much every metric moved,
    a coupled run's ROP, weight and torque on bit, hook load, bounce fraction, MSE and regime too."""

    cells: int
    refined_cells: int
    rows: tuple[GridCheckRow, ...]

    @classmethod
    def compare(cls, base: DrillResult, refined: DrillResult, cells: int, refined_cells: int) -> GridCheck:
        """The rows of :data:`GRID_TOLERANCES` both runs give, judged in the core."""
        rows = tuple(GridCheckRow(r["metric"], r["value"], r["other"], r["change"], r["kind"], r["tolerance"],
                                  r["within"]) for r in _compared(base, refined))
        return cls(cells, refined_cells, rows)

    @property
    def converged(self) -> bool:
        """Every metric within its tolerance."""
        return all(r.within for r in self.rows)

    def warnings(self) -> list[str]:
        """One sentence per metric that moved more than its tolerance."""
        first, second = f"on {self.cells} cells", f"on {self.refined_cells}"
        return [f"grid check: {r.metric} {_moved(r, first, second)}: not converged, refine numerics.cells"
                for r in self.rows if not r.within]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (``metrics.json``'s ``grid_check``)."""
        return {"cells": self.cells, "refined_cells": self.refined_cells, "converged": self.converged,
                "rows": [dataclasses.asdict(r) for r in self.rows]}


@dataclass(frozen=True)
class StartCheckRow:
    """One metric of a start check: its value in the run from rest and from the steady state."""

    metric: str
    rest: CheckValue
    steady: CheckValue
    change: Optional[float]
    """``steady - rest`` (``"abs"``), ``steady / rest - 1`` (``"rel"``), 0 / 1 (``"equal"``)."""
    kind: str
    tolerance: float
    within: bool

    @property
    def value(self) -> CheckValue:
        return self.rest

    @property
    def other(self) -> CheckValue:
        return self.steady


@dataclass(frozen=True)
class StartCheck:
    """A coupled run repeated from both starts, ``numerics.initial_state = "rest"`` and
    ``"steady"`` (:data:`GRID_TOLERANCES`, judged in the core): where they disagree, the case has
    more than one attractor (or the window is still in a transient) and each start's answer is one
    of them."""

    rows: tuple[StartCheckRow, ...]

    @classmethod
    def compare(cls, rest: DrillResult, steady: DrillResult) -> StartCheck:
        """The rows both runs give."""
        return cls(tuple(StartCheckRow(r["metric"], r["value"], r["other"], r["change"], r["kind"], r["tolerance"],
                                       r["within"]) for r in _compared(rest, steady)))

    @property
    def agree(self) -> bool:
        """Every metric within its tolerance: one answer whatever the start."""
        return all(r.within for r in self.rows)

    def warnings(self) -> list[str]:
        """One sentence for the disagreeing metrics (none when they agree)."""
        moved = [f"{r.metric} {_moved(r, 'from rest', 'from the steady state')}" for r in self.rows if not r.within]
        if not moved:
            return []
        return ["start check: the runs from rest and from the steady state disagree (more than one attractor, or a "
                "window still in a transient; each start's answer is one of them): " + "; ".join(moved)]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (``metrics.json``'s ``start_check``)."""
        return {"agree": self.agree, "rows": [dataclasses.asdict(r) for r in self.rows]}


def _no_cells() -> NDArray[np.float64]:
    return np.zeros(0)


@dataclass(frozen=True)
class DrillProfile:
    """The static friction profile of the string in the well (``_core.drill_profile``)."""

    z: NDArray[np.float64]
    """Measured depth of the cell centres, m."""
    limit_per_m: NDArray[np.float64]
    """Static friction torque limit per metre, N m/m."""
    cumulative: NDArray[np.float64]
    """Static friction torque from the bit up to ``z`` (the torque the string must carry at ``z``
    to turn everything below it from rest), N m."""
    breakoff_torque: float
    """Its value at the surface: the wall's break-off torque, N m."""
    bit_static_torque: float = 0.0
    """The bit's static torque ``W r mu_s`` with the bit on bottom (0 off bottom), N m."""
    static_torque: float = math.nan
    """The static torque the motor must exceed to break the string free: :attr:`breakoff_torque` plus
    :attr:`bit_static_torque`, N m."""
    holding: NDArray[np.float64] = field(default_factory=_no_cells)
    """The static torque the string holds at ``z`` at break-off: :attr:`cumulative` plus
    :attr:`bit_static_torque` (the bit's torque is carried along the whole string), N m."""
    inclination_deg: NDArray[np.float64] = field(default_factory=_no_cells)
    """The well at the cell centres (minimum curvature): inclination, degrees."""
    azimuth_deg: NDArray[np.float64] = field(default_factory=_no_cells)
    """Azimuth at the cell centres, degrees clockwise from north."""
    tvd: NDArray[np.float64] = field(default_factory=_no_cells)
    """True vertical depth of the cell centres, m."""
    dls_deg_per_30m: NDArray[np.float64] = field(default_factory=_no_cells)
    """Curvature of the well at the cell centres as a dogleg severity, degrees per 30 m."""
    friction_factor: NDArray[np.float64] = field(default_factory=_no_cells)
    """Static friction factor at the cell centres (``friction.static`` or an interval's)."""

    @classmethod
    def from_core(cls, raw: Mapping[str, Any]) -> DrillProfile:
        arrays = {k: np.asarray(raw[k], dtype=np.float64) for k in (
            "z", "limit_per_m", "cumulative", "holding", "inclination_deg", "azimuth_deg", "tvd", "dls_deg_per_30m",
            "friction_factor")}
        return cls(breakoff_torque=float(raw["breakoff_torque"]), bit_static_torque=float(raw["bit_static_torque"]),
                   static_torque=float(raw["static_torque"]), **arrays)


class DrillResult:
    """One run of the drilling system.

    Attributes
    ----------
    config : DrillConfig
        The normalised configuration that was solved.
    t : ndarray
        Sample times of the series, s.
    surface_rpm, bit_rpm : ndarray
        Top-drive and bit speed, rpm.
    motor_torque, bit_torque : ndarray
        Motor torque and bit-rock torque, N m.
    z : ndarray
        Measured depth of the grid cells, m.
    field_t : ndarray
        Times of the space-time snapshots, s (empty with ``numerics.field_interval = 0``).
    omega_field, torque_field : ndarray
        Speed (rpm) and torque (N m) along the string, shape ``(field_t.size, z.size)``.
    profile : DrillProfile
        The static friction profile and break-off torque.
    metrics : DrillMetrics
        Stick-slip metrics over the window.
    energy : dict
        The energy balance, J: ``motor_work, initial, kinetic, elastic, top_drive, bha,
        friction_loss`` (both fields in a coupled run; ``axial_friction_loss`` its axial part)
        ``damping_loss, bit_loss, numerical_loss`` (``upwind_loss`` of the transport
        plus ``inertia_loss`` of the implicit top-drive and BHA steps and of the coupled wall
        friction's implicit step with the gravity kick) and ``balance_error``. Every value NaN
        with ``numerics.energy_balance = False`` (the ledger not kept; ``warnings`` says so).
    stats : dict
        ``cells``, ``steps``, ``dt`` of the solve, the Courant numbers ``courant_min``,
        ``courant_max`` of the sections (at the speed the step is made for) and ``courant_peak``
        (the largest of the local wave speed met: above 1 only when a ``"consistent"`` run
        exceeded ``numerics.max_shear_strain``), the controller gains ``kp``, ``ki`` and
        ``first_mode_hz``.
    status, message : str
        How the solve ended (``"success"`` or a failure status, see :class:`~drillstring.errors.SolveError`).
    metrics_finite : bool
        False when a headline metric (``ssi``, ``stuck_fraction``, the bit speed's and motor
        torque's extremes and mean) is not finite: not a result even with ``status`` success
        (``warnings`` says which; ``drillstring drill`` says so on its first line).
    grid_check : GridCheck or None
        With ``drill(..., check_grid=True)``: every metric against the same run on twice the
        cells (its moves beyond :data:`GRID_TOLERANCES` are in ``warnings``).
    warnings : tuple of str
        What makes the run or its metrics doubtful: a torque limit below the string's static
        torque, a value that is likely a unit mistake, a transient still decaying in the metrics
        window, a headline metric that is not finite, a window that is not settled, an undefined
        severity or period, a period its cross-check disagrees with; empty when nothing does.
    """

    def __init__(self, config: DrillConfig, raw: Mapping[str, Any], profile: DrillProfile) -> None:
        self.config = config
        self.t: NDArray[np.float64] = np.asarray(raw["t"], dtype=np.float64)
        self.surface_rpm: NDArray[np.float64] = np.asarray(raw["surface_rpm"], dtype=np.float64)
        self.bit_rpm: NDArray[np.float64] = np.asarray(raw["bit_rpm"], dtype=np.float64)
        self.motor_torque: NDArray[np.float64] = np.asarray(raw["motor_torque"], dtype=np.float64)
        self.bit_torque: NDArray[np.float64] = np.asarray(raw["bit_torque"], dtype=np.float64)
        self.z: NDArray[np.float64] = np.asarray(raw["z"], dtype=np.float64)
        self.field_t: NDArray[np.float64] = np.asarray(raw["field_t"], dtype=np.float64)
        self.omega_field: NDArray[np.float64] = np.asarray(raw["omega_field"], dtype=np.float64).reshape(
            self.field_t.size, self.z.size)
        self.torque_field: NDArray[np.float64] = np.asarray(raw["torque_field"], dtype=np.float64).reshape(
            self.field_t.size, self.z.size)
        self.profile = profile
        self.metrics = DrillMetrics.from_core(raw["metrics"])
        self.warnings: tuple[str, ...] = tuple(
            str(w) for w in (*raw.get("warnings", ()), *raw["metrics"].get("warnings", ())))
        self.energy: dict[str, float] = {str(k): float(v) for k, v in dict(raw.get("energy") or {}).items()}
        self.stats: dict[str, Any] = dict(raw.get("stats") or {})
        self.axial: dict[str, NDArray[np.float64]] = {
            k: np.asarray(raw[k], dtype=np.float64) for k in AXIAL_SERIES if k in raw}
        """A coupled run's series at the times ``t`` (empty without a hoist): ``bit_axial_speed`` m/s
        (down positive), ``rop`` m/h (the rate the deepest bit position advances), ``weight_on_bit``
        N, ``hook_load`` N, ``bit_depth`` m (below the start), ``depth_of_cut`` m per revolution
        (0 while the rate form's bit does not turn), ``block_position`` m (the top of the string's
        position from the start, down positive: a rig's block travel); the torque on bit is ``bit_torque``."""
        coupled = dict(raw.get("coupled") or {})
        self.axial_z: NDArray[np.float64] = np.asarray(raw.get("axial_z", ()), dtype=np.float64)
        """A coupled run's axial cell centres, m (empty without a hoist)."""
        self.axial_speed_field: NDArray[np.float64] = np.asarray(
            raw.get("axial_speed_field", ()), dtype=np.float64).reshape(
            self.field_t.size if self.axial_z.size else 0, self.axial_z.size)
        """A coupled run's axial speed along the string at ``field_t``, m/s, down positive, shape
        ``(field_t.size, axial_z.size)`` (the speed at the middle of the step's gravity kick)."""
        self.axial_force_field: NDArray[np.float64] = np.asarray(
            raw.get("axial_force_field", ()), dtype=np.float64).reshape(
            self.field_t.size if self.axial_z.size else 0, self.axial_z.size)
        """A coupled run's axial force along the string at ``field_t``, N, compression positive
        (tension negative), shape ``(field_t.size, axial_z.size)``."""
        self.coupled_metrics: Optional[dict[str, float]] = (
            {str(k): float(v) for k, v in coupled.items() if k != REGIME} if coupled else None)
        """A coupled run's metrics over the window (None without a hoist): ``rop_mean_m_per_h``,
        ``wob_mean_N``, ``tob_mean_Nm``, ``bounce_fraction`` (share of samples with no weight on
        bit), ``hook_load_mean_N`` and ``mse_mean_Pa`` (Teale's mechanical specific energy of the
        means)."""
        self.coupled_regime: Optional[str] = str(coupled[REGIME]) if REGIME in coupled else None
        """A coupled run's regime over the window (None without a hoist): ``"smooth drilling"``,
        ``"stick-slip"``, ``"bit bounce"``, ``"stick-slip and bit bounce"``, ``"off bottom"`` or
        ``"undetermined"``, decided in the core (``drilling::axial::regime``) by
        :data:`~drillstring.drilling.result.COUPLED_REGIME_CRITERION` from the stick-slip verdict
        and ``bounce_fraction``."""
        self.grid_check: Optional[GridCheck] = None
        self.start_check: Optional[StartCheck] = None
        """With ``drill(..., check_start=True)``: the run from rest against the run from the steady
        state (its disagreements are in ``warnings``)."""
        self.status: str = str(raw["status"])
        self.message: str = str(raw["message"])
        self.name: Optional[str] = None
        """The well's name in figure titles (the configuration file's stem when :func:`drill` read one)."""
        self.metrics_finite: bool = bool(raw.get("metrics_finite", True))
        self.rotating: bool = bool(raw.get("rotating", True))
        """Whether the top drive was asked to turn (a setpoint, step or measured speed other than
        0): a coupled pick-up or slack-off without rotation has no torsional metrics by design."""

    @property
    def success(self) -> bool:
        """True when the solve reached ``numerics.duration``."""
        return self.status == "success"

    def __repr__(self) -> str:
        m = self.metrics
        return (f"<DrillResult {self.status}: {self.t.size} samples to t = {self.t[-1] if self.t.size else 0:g} s, "
                f"SSI {m.ssi:.3g}, stuck {m.stuck_fraction:.3g}, period {m.period_s:.3g} s>")

    def series(self) -> dict[str, NDArray[np.float64]]:
        """``{"t": ..., "surface_rpm": ..., ...}``: the time series by name."""
        return {"t": self.t, **{name: getattr(self, name) for name in SERIES}}

    def series_columns(self) -> dict[str, NDArray[np.float64]]:
        """The columns of :meth:`to_pandas` (and of ``series.csv``), each a series over :attr:`t`:
        :data:`SERIES`, then a coupled run's :attr:`axial` series."""
        columns = {name: getattr(self, name) for name in SERIES}
        columns.update(self.axial)
        return columns

    def to_pandas(self) -> pd.DataFrame:
        """The time series as a :class:`pandas.DataFrame` indexed by ``t`` (s), with the columns
        ``surface_rpm``, ``bit_rpm`` (rpm), ``motor_torque``, ``bit_torque`` (N m) and, for a
        coupled run, the series of :attr:`axial` by the core's names (``bit_axial_speed`` m/s,
        ``rop`` m/h, ``weight_on_bit`` N, ``hook_load`` N, ``bit_depth`` m, ``depth_of_cut`` m,
        ``block_position`` m;
        the torque on bit is ``bit_torque``); ``df.attrs`` holds ``units``, ``status``,
        ``metrics`` and the ``config`` (:meth:`DrillConfig.to_dict`)."""
        import pandas as pd

        columns = self.series_columns()
        frame = pd.DataFrame(columns, index=pd.Index(self.t, name="t"))
        frame.attrs.update(
            units={key: UNITS[key] for key in ("t", *columns)}, status=self.status,
            metrics=self.metrics.to_dict(), config=self.config.to_dict(),
        )
        return frame

    def summary(self, output_units: Optional[str] = None) -> dict[str, Any]:
        """What ``metrics.json`` holds: the metrics, the window, the status and message, the
        energy balance and the solver counters (NaN as ``None``), and for a coupled run its
        metrics under ``coupled`` (:attr:`coupled_metrics`). Every number is SI; with
        ``output_units="field"`` the summary also holds ``output_units``: ``{"system": "field",
        "units": {name: unit}, "metrics": {name: value}}``, the numeric metrics (and a coupled
        run's) converted (torques to ft-lbf, forces to klbf, ROP to ft/h, MSE to psi; rpm, s and
        ratios stay; :mod:`drillstring.drilling.units`), each under its name with the SI unit
        suffix replaced by the field unit's (``motor_torque_max_ftlbf``, ``rop_mean_ft_per_h``;
        :func:`~drillstring.drilling.units.unit_key`): a key naming a unit holds that unit. The
        default (None) is the configuration's ``units`` (:attr:`DrillConfig.units`)."""
        from .units import convert, system_of, unit_key

        system = system_of(self.config.units if output_units is None else output_units, "output_units")
        out: dict[str, Any] = {"status": self.status, "message": self.message, "metrics_finite": self.metrics_finite,
                               "rotating": self.rotating}
        out.update(self.metrics.to_dict())
        # the texts beside the verdicts that a map has no column for (the verdict's reason)
        out.update({o.name: self.metrics[o.name] for o in OUTPUTS.values()
                    if o.kind == "text" and not o.map_column and "torsional" in o.runs})
        out["stick_slip_criterion"] = STICK_SLIP_CRITERION
        out["warnings"] = list(self.warnings)
        if self.grid_check is not None:
            out["grid_check"] = self.grid_check.to_dict()
        if self.start_check is not None:
            out["start_check"] = self.start_check.to_dict()
        out["definitions"] = dict(METRIC_DEFINITIONS)
        out["window"] = [self.metrics.window_start, self.metrics.window_end]
        out["energy"] = {k: (None if math.isnan(v) else v) for k, v in self.energy.items()}
        out["stats"] = self.stats
        if self.coupled_metrics is not None:
            out["coupled"] = dict(self.coupled_metrics)
            if self.coupled_regime is not None:
                out["coupled"][REGIME] = self.coupled_regime
                out["coupled"]["regime_criterion"] = COUPLED_REGIME_CRITERION
        if system != "si":
            values = dict(out)
            units = dict(METRIC_UNITS)
            if self.coupled_metrics is not None:
                values.update(self.coupled_metrics)
                units.update(COUPLED_METRIC_UNITS)
            converted = {unit_key(name, unit, convert(1.0, unit, system)[1]): convert(values[name], unit, system)
                         for name, unit in units.items()}
            out["output_units"] = {"system": system, "units": {k: u for k, (_, u) in converted.items()},
                                   "metrics": {k: v for k, (v, _) in converted.items()}}
        return out

    def plot(self, kind: str = "time", *, fig: Any = None, path: Any = None, title: Optional[str] = None,
             units: Optional[str] = None) -> Figure:
        """A figure of the run.

        Parameters
        ----------
        kind : {"time", "space_time", "torque_depth", "axial", "axial_space_time"}
            ``"time"``: surface and bit speed, motor and bit torque against time with the
            break-off torque and the metrics window
            (:func:`~drillstring.drilling.plots.time_histories`); ``"space_time"``: speed and
            torque along the string against time
            (:func:`~drillstring.drilling.plots.space_time_maps`); ``"torque_depth"``: torque
            against depth inside the break-off envelope
            (:func:`~drillstring.drilling.plots.torque_depth`); a coupled run's ``"axial"``:
            weight and torque on bit, ROP and depth of cut against time
            (:func:`~drillstring.drilling.plots.axial_histories`) and ``"axial_space_time"``:
            axial speed and force along the string against time
            (:func:`~drillstring.drilling.plots.axial_space_time`).
        fig : Figure or SubFigure, optional
            Draw into this (empty) figure instead of a new one.
        path : str or path-like, optional
            Also save the figure there (:func:`drillstring.io.figures.save`: the format from the
            extension, atomic replacement).
        title : str, optional
            The figure's title instead of the default.
        units : {"si", "field"}, optional
            The unit system of the axes and the title: ``"si"`` or ``"field"`` (depths in ft,
            torques in kft-lbf; :mod:`drillstring.drilling.units`); by default the
            configuration's ``units``. The data stay SI.

        Returns
        -------
        matplotlib.figure.Figure

        Raises
        ------
        ValidationError
            An unknown ``kind`` (naming the allowed ones), an unknown ``units`` (naming the
            systems), or a ``path`` whose extension is no image format.

        Examples
        --------
        >>> import drillstring as ds
        >>> result = ds.drill("examples/on-bottom-3000m.toml")  # doctest: +SKIP
        >>> fig = result.plot("torque_depth", path="torque_depth.png")  # doctest: +SKIP
        >>> fig = result.plot("time", units="field")  # doctest: +SKIP
        """
        from ..errors import ValidationError
        from .plots import KINDS
        from .units import system_of

        make = KINDS.get(kind) if isinstance(kind, str) else None
        if make is None:
            raise ValidationError("kind", kind, "one of " + ", ".join(KINDS))
        units = system_of(self.config.units if units is None else units, "units")
        if path is not None:
            from ..io.figures import plot_path

            plot_path(path, "path")  # an unknown extension is refused before drawing
        figure = make(self, title, fig=fig, units=units)
        if path is not None:
            from ..io.figures import save

            save(figure, path)
        return figure

    def save(self, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True,
             output_units: Optional[str] = None) -> list[Path]:
        """Writes the run into the folder ``out_dir`` (created if needed) and returns the paths
        written: ``series.parquet``, ``series.csv``, ``metrics.json``, ``fields.npz``,
        ``config.toml`` (the normalised configuration), the figures (unless ``plots=False``) and
        ``report.md``. The destinations are checked before anything is written; every file is
        written atomically (see :mod:`drillstring.io.output`). ``output_units="field"`` adds the
        metrics in field units to ``metrics.json`` (:meth:`summary`) and draws the figures in
        field units (:meth:`plot`'s ``units``); the data files stay SI. The default (None) is the
        configuration's ``units``, as on the command line."""
        from .output import write_outputs

        system = self.config.units if output_units is None else output_units
        return write_outputs(self, out_dir, plots=plots, output_units=system)
