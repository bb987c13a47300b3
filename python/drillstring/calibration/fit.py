"""``fit``: configuration values estimated from measured data by weighted least squares.

The model of each event (a start-up) is its configuration with the parameters set by dotted
path (the core's overrides, as ``DrillConfig.with_overrides`` and the axes of a map), solved by
the core (``_core.drill_solve``, which runs without the GIL) over the span of the windows. The
top boundary is, with ``top="controller"`` (default), the configuration's: the top drive with
its controller, setpoint and ramp (``top_drive.*``), and the measured surface speed may be
compared; with ``top="measured"`` the data's ``surface_rpm`` is imposed
(``top_drive.mode = "measured_speed"``, the series as ``top_drive.speed_series``, held after
its last sample), so that the controller and its gains need not be known, and the model's
motor torque is the torque that imposes it. With ``offset=`` a sensor offset of each target
(constant or linear in time) is fitted by linear least squares at every evaluation and profiled
out of the residuals.

Residuals: for each event, each target series ``s`` and each model output time ``t_k`` nearest
a measured sample inside a window, ``sqrt(w_s) (model_s(t_k) - measured_s(t_k)) / scale_s``, the
measured series linearly interpolated at ``t_k`` and ``scale_s`` its standard deviation over the
windows (so that series of different units combine). The misfit is the sum of their squares
(``ssr``). A run that fails or is refused gets residuals :data:`FAILED_RESIDUAL`. With
``misfit="features"`` the residuals are instead the cycle features of each target series
(:mod:`~drillstring.calibration.features`) against the data's, in their standard deviations,
over the whole windows at once (no horizons: the features do not depend on the cycles' phase).

Stages:

1. **global**: a scrambled Sobol sample of the parameter box (``samples`` points, default 64 per
   parameter, at least 128, rounded up to a power of two) solved as one batch on ``threads``
   threads, over the first ``horizon`` seconds (or more) of the windows;
2. **refinement**: :func:`scipy.optimize.least_squares` (trust-region reflective, in the box
   scaled to ``[0, 1]``) from the ``starts`` best distinct samples, over that horizon and its
   doubles up to the whole windows in turn (before each longer horizon, the best of a small
   Sobol sample within :data:`ZOOM` of the point), its forward-difference Jacobian (step ``diff_step``
   of the box) solved as one batch of runs per iteration;
3. **uncertainty**: the covariance ``s^2 (J^T J)^-1`` at the optimum (``J`` by central
   differences of ``diff_step``; ``s^2 = ssr / (n - p)``, inflated by ``(1 + rho) / (1 - rho)``
   for a lag-one autocorrelation ``rho > 0`` of the residuals: correlated residuals carry less
   information than their count) gives, per parameter, the point of the confidence ellipsoid
   that reaches furthest in it; the misfit is solved along that path (multiples
   :data:`PATH_MULTIPLES`), and the interval reaches the furthest point whose excess misfit stays
   within ``s^2 chi2_1(level)``, never less far than the quadratic reach of the covariance (a
   jump of the misfit inside it is the set-valued friction's roughness at small scales), widened
   to every point solved during the fit within that threshold (where the misfit is flatter than
   quadratic, the quadratic model alone is too optimistic). Where the Jacobian is near-singular (condition
   number of the box-scaled Jacobian above :data:`CONDITION_LIMIT`; ``profile="auto"``) or with
   ``profile=True``, the parameter's **profile likelihood** (the misfit minimised over the others
   at each of ``profile_points`` values) gives the interval instead. A parameter whose interval
   spans its whole box is reported not identifiable (a warning), and a near-singular Jacobian
   names the parameters of its weakest direction (a ridge). Where the sample-by-sample
   residuals show a model error (``interval="auto"``), each interval is joined with a block
   bootstrap over the stick-slip cycles (:func:`_bootstrap_intervals`);
4. **checks** (:mod:`~drillstring.calibration.checks`): warnings for a value at its bound, a
   residual far above the data's noise or correlated, implausible units, a ridge;
5. **landscape**: the misfit over a ``landscape_points`` x ``landscape_points`` grid of each pair
   of parameters, the others at the optimum (a ridge of equally good fits shows there).

Several events (start-ups, each its data and optionally its own configuration) are fitted
jointly: the parameters are shared, except those in ``per_event``, which get one value per
event (named ``events[i].key``).
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Callable, Optional, Union

import numpy as np
from numpy.typing import NDArray

from .. import _core
from ..drilling.config import DrillConfig
from ..drilling.solve import ConfigLike, _config
from ..drilling.units import override_to_si
from ..errors import ValidationError
from . import checks
from .data import AXIAL_SERIES, MODEL_SERIES, MeasuredData, read_measured
from .features import features as cycle_features
from .features import noise_level, uncertainties

__all__ = ["CONDITION_LIMIT", "INTERVALS", "MISFITS", "OFFSETS", "Event", "FitResult", "Landscape", "ParameterEstimate",
           "Profile", "fit"]

#: Condition number of the box-scaled Jacobian above which the intervals come from profiles.
CONDITION_LIMIT = 1e3
#: The residual of a run that failed (normalised units), so that the optimiser moves away from it.
FAILED_RESIDUAL = 1e2
#: The misfits a fit can minimise (``misfit=``): the sample-by-sample least squares, or the cycle
#: features with their uncertainties (:mod:`drillstring.calibration.features`).
MISFITS = ("least_squares", "features")
#: The residual of a feature the data have and the model's run has not (standard deviations).
MISSING_FEATURE = 10.0
#: The coarse grid of the features' discretisation error has at least this many cells.
MIN_GRID_CELLS = 50
#: Starts of the refinement are the best points of the global stage at least this far apart
#: (largest coordinate difference in the box scaled to [0, 1]).
START_SEPARATION = 0.2
#: Before the refinement over a longer horizon: the best of 2**ZOOM_LOG2 points within ZOOM (of
#: the box) of the point, since the later cycles move the misfit's valleys.
ZOOM = 0.1
ZOOM_LOG2 = 5
#: ``top="measured"``: a measured speed whose noise level exceeds this share of its range is smoothed.
SPEED_NOISE = 1e-3
#: ... over this long, s.
SPEED_SMOOTH_TIME = 0.5
#: The sandwich covariance's bandwidth: the lag at which the residuals' autocorrelation falls below this.
HAC_CUTOFF = 0.05
#: ... times this many.
HAC_LENGTHS = 3
#: The offsets a fit can estimate per event and target series (``offset=``): none, a constant, or a
#: constant plus a rate (linear in time), each profiled out in closed form at every evaluation.
OFFSETS = ("none", "constant", "linear")
#: The intervals a fit can give (``interval=``): the block bootstrap's over the stick-slip cycles
#: joined to the Jacobian's where sample-by-sample residuals show a model error (``"auto"``), the
#: Jacobian's alone, or the bootstrap's always.
INTERVALS = ("auto", "jacobian", "bootstrap")
#: The block bootstrap: points per parameter scattered around the optimum ...
BOOTSTRAP_POINTS = 64
#: ... over the larger of this many standard errors of the Jacobian ...
BOOTSTRAP_SE = 4.0
#: ... and this share of each value;
BOOTSTRAP_SHARE = 0.03
#: the resamplings of the cycles;
BOOTSTRAP_REPLICATES = 2000
#: the fewest and the most cycles (groups) the windows are cut into.
BOOTSTRAP_CYCLES = (6, 40)
#: Multiples of the Jacobian interval's end scanned along its path (see :func:`fit`).
PATH_MULTIPLES = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0)

DataLike = Union[MeasuredData, str, "os.PathLike[str]", Any]


@dataclass(frozen=True)
class Event:
    """One start-up to fit: its configuration, its data and its windows (model times, s)."""

    config: DrillConfig
    data: MeasuredData
    windows: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class ParameterEstimate:
    """A fitted value with its interval at the fit's level (``fit.json``'s entry of the key)."""

    key: str
    """The dotted configuration key (``events[i].key`` for a per-event parameter)."""
    value: float
    """The fitted value, in the key's SI unit."""
    ci_low: float
    """Lower end of the interval at the fit's level (95 % by default)."""
    ci_high: float
    """Upper end of the interval."""
    lower: float
    """Lower bound of the search."""
    upper: float
    """Upper bound of the search."""
    std_error: float
    """Standard error from the Jacobian at the optimum."""
    #: ``"jacobian"`` or ``"profile"``: where the interval comes from.
    method: str
    identifiable: bool
    """False when the interval spans the bounds (a flat misfit: the data do not fix the value)."""

    def to_dict(self) -> dict[str, Any]:
        return {"value": self.value, "ci_low": self.ci_low, "ci_high": self.ci_high, "lower": self.lower,
                "upper": self.upper, "std_error": self.std_error, "ci_method": self.method,
                "identifiable": self.identifiable}


@dataclass(frozen=True)
class Landscape:
    """The misfit (``ssr``, shape ``(len(y), len(x))``) over a grid of two parameters, the others
    at the optimum."""

    x_key: str
    y_key: str
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    ssr: NDArray[np.float64]


@dataclass(frozen=True)
class Profile:
    """The profile likelihood of one parameter: the misfit minimised over the others at each value."""

    key: str
    values: NDArray[np.float64]
    ssr: NDArray[np.float64]
    threshold: float


@dataclass
class FitResult:
    """What :func:`fit` returns."""

    parameters: dict[str, ParameterEstimate]
    #: The fitted configuration of each event (the first is :attr:`config`).
    configs: list[DrillConfig]
    events: list[Event]
    targets: dict[str, float]
    ssr: float
    #: Residual points (n) and parameters (p).
    points: int
    level: float
    evaluations: int
    seconds: float
    condition: float
    residual_autocorrelation: float
    global_stage: dict[str, Any]
    refinement: dict[str, Any]
    #: Per event and target: the RMS error in the series' unit over the windows.
    rms: list[dict[str, float]]
    #: Per event: the fitted run's ``t`` and series (whole span) for figures.
    fitted: list[dict[str, NDArray[np.float64]]]
    landscapes: list[Landscape] = field(default_factory=list)
    profiles: dict[str, Profile] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    #: The model's top boundary: ``"controller"`` or ``"measured"`` (the data's surface speed imposed).
    top: str = "controller"
    #: What was minimised (the ``misfit`` option): ``"least_squares"`` or ``"features"``.
    objective: str = "least_squares"
    #: Per event and target: the fitted series against the data (residual RMS, noise, autocorrelation).
    series_checks: list[checks.SeriesCheck] = field(default_factory=list)
    #: The correlation matrix of the estimates (the parameters' order).
    correlation: list[list[float]] = field(default_factory=list)
    #: With ``misfit="features"``: per event, target and feature the data's value, its standard
    #: deviation and the fitted model's value.
    features: list[dict[str, Any]] = field(default_factory=list)
    #: Where the block bootstrap applied (``interval=``): the cycles, the points and per parameter
    #: the Jacobian's and the bootstrap's intervals, the smoothed estimate, the grid shift and the
    #: reported interval.
    intervals: dict[str, Any] = field(default_factory=dict)
    #: The ``offset`` option: ``"none"``, ``"constant"`` or ``"linear"``.
    offset: str = "none"
    #: Per event and target the estimated offset ``measured - model`` (:meth:`_Problem.offsets`:
    #: ``constant`` at ``t_ref``, ``rate_per_s``); the fitted series include it.
    offsets: list[dict[str, dict[str, float]]] = field(default_factory=list)

    @property
    def config(self) -> DrillConfig:
        """The fitted configuration (of the first event)."""
        return self.configs[0]

    @property
    def misfit(self) -> float:
        """The mean square of the normalised residuals, ``ssr / n``."""
        return self.ssr / self.points

    def to_dict(self) -> dict[str, Any]:
        """The content of ``fit.json``."""
        return {
            "parameters": {k: p.to_dict() for k, p in self.parameters.items()},
            "misfit": {"ssr": self.ssr, "mean_square": self.misfit, "points": self.points,
                       "rms": self.rms, "targets": self.targets},
            "evaluations": self.evaluations,
            "time_s": self.seconds,
            "level": self.level,
            "jacobian_condition": self.condition,
            "residual_autocorrelation": self.residual_autocorrelation,
            "global": self.global_stage,
            "refinement": self.refinement,
            "events": [{"source": e.data.source, "windows": [list(w) for w in e.windows]} for e in self.events],
            "warnings": list(self.warnings),
            "top": self.top,
            "objective": self.objective,
            "series_checks": [c.to_dict() for c in self.series_checks],
            "correlation": self.correlation,
            "features": self.features,
            "intervals": self.intervals,
            "offset": self.offset,
            "offsets": self.offsets,
        }

    def save(self, out_dir: Union[str, os.PathLike[str]], *, plots: bool = True) -> list[Any]:
        """Writes the fit's folder (see :mod:`drillstring.calibration.output`)."""
        from .output import write_fit

        return write_fit(self, out_dir, plots=plots)


# --------------------------------------------------------------------------- the problem


@dataclass(frozen=True)
class _Column:
    """One coordinate of the parameter vector."""

    name: str
    key: str
    event: Optional[int]  # None: shared by every event
    lower: float
    upper: float


class _Problem:
    """The residuals of the events as a function of the parameter vector scaled to ``[0, 1]``."""

    def __init__(self, events: list[Event], columns: list[_Column], targets: dict[str, float],
                 threads: int, fraction: float = 1.0, top: str = "controller", misfit: str = "least_squares",
                 offset: str = "none") -> None:
        self.events = events
        self.misfit = misfit
        #: ``offset=``: the sensor offset profiled out of each event's and target's residuals.
        self.offset = offset
        self.columns = columns
        self.targets = targets
        self.threads = threads
        #: The share of the windows' span compared (the horizon).
        self.fraction = fraction
        self.evaluations = 0
        #: Every point solved (scaled) with its misfit: the likelihood-ratio set of the intervals.
        self.history: list[tuple[NDArray[np.float64], float]] = []
        self.lower = np.array([c.lower for c in columns])
        self.upper = np.array([c.upper for c in columns])
        self.bases: list[str] = []
        self.index: list[NDArray[np.int64]] = []
        self.measured: list[dict[str, NDArray[np.float64]]] = []
        self.scale: list[dict[str, float]] = []
        self.times: list[NDArray[np.float64]] = []
        #: ``misfit="features"``: per event and target the data's features, values and standard deviations.
        self.reference: list[dict[str, tuple[list[str], NDArray[np.float64], NDArray[np.float64]]]] = []
        for ev in events:
            dt = ev.config.numerics.output_interval
            first = min(a for a, _ in ev.windows)
            end = first + fraction * (max(b for _, b in ev.windows) - first)
            ev = Event(ev.config, ev.data, tuple((a, min(b, end)) for a, b in ev.windows if a < end or a == first))
            # the output times nearest the measured samples (every output time when the data are finer)
            k = np.unique(np.rint(ev.data.t[(ev.data.t >= 0) & (ev.data.t <= end + 1e-9)] / dt).astype(np.int64))
            k = k[k * dt <= end + 1e-9]
            t = k * dt
            inside = np.zeros(t.size, dtype=bool)
            for a, b in ev.windows:
                inside |= (t >= a - 1e-9) & (t <= b + 1e-9)
            idx = k[inside]
            if idx.size == 0:
                raise ValidationError("windows", ev.windows, f"windows holding model output times (every {dt:g} s)")
            times = (idx * dt).astype(np.float64)
            meas = {s: ev.data.resample(s, times) for s in targets}
            scales = {}
            for s, v in meas.items():
                sd = float(np.std(v))
                scales[s] = sd if sd > 0 else (float(np.mean(np.abs(v))) or 1.0)
            duration = float(idx[-1] * dt + dt)
            # (the metrics window, which the fit does not read, as the default: the last half of the
            # shortened run, so that a window set in the configuration cannot fall outside it)
            overrides: dict[str, Any] = {"numerics.duration": duration, "numerics.field_interval": 0.0,
                                         "metrics.window": None}
            if top == "measured":
                overrides.update({"top_drive.mode": "measured_speed",
                                  "top_drive.speed_series": _speed_series(ev.data, duration)})
            cfg = ev.config.with_overrides(overrides, units="si")
            self.bases.append(cfg.to_json())
            self.index.append(idx)
            self.measured.append(meas)
            self.scale.append(scales)
            self.times.append(times)
            self.reference.append({s: _reference(times, v) for s, v in meas.items()} if misfit == "features" else {})
        if misfit == "features":
            self.points = sum(len(ref[s][0]) for ref in self.reference for s in targets)
        else:
            self.points = sum(i.size * len(targets) for i in self.index)
        #: The offsets' coefficients profiled out (degrees of freedom the residuals lose).
        self.profiled = OFFSETS.index(offset) * len(targets) * len(events)

    def values(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.lower + np.clip(u, 0.0, 1.0) * (self.upper - self.lower)

    def pairs(self, u: NDArray[np.float64], event: int) -> list[list[Any]]:
        x = self.values(u)
        return [[c.key, float(v)] for c, v in zip(self.columns, x) if c.event is None or c.event == event]

    def _solve(self, job: tuple[NDArray[np.float64], int, bool]) -> Any:
        u, e, whole = job
        try:
            cfg = _core.drill_config_override(self.bases[e], json.dumps(self.pairs(u, e)), "parameters")
        except ValidationError as exc:
            return f"refused: {exc}"
        out = _core.drill_solve(json.dumps(cfg))
        if out["status"] != "success":
            return f"{out['status']}: {out['message']}"
        series: dict[str, Any] = dict(out)
        if whole:
            return {name: np.asarray(series[name]) for name in ("t", *MODEL_SERIES, *AXIAL_SERIES) if name in series}
        return {s: np.asarray(series[s])[self.index[e]] for s in self.targets}

    def run(self, points: Sequence[NDArray[np.float64]], whole: bool = False) -> list[list[Any]]:
        """Solves every event at every point (one batch on the threads): per point, per event,
        the series at the windows' times (``whole``: the whole run) or the failure message."""
        jobs = [(np.asarray(u, dtype=np.float64), e, whole) for u in points for e in range(len(self.events))]
        self.evaluations += len(jobs)
        if self.threads == 1 or len(jobs) == 1:
            flat = [self._solve(j) for j in jobs]
        else:
            with ThreadPoolExecutor(max_workers=min(self.threads, len(jobs))) as pool:
                flat = list(pool.map(self._solve, jobs))
        n = len(self.events)
        return [flat[i * n:(i + 1) * n] for i in range(len(points))]

    def residual_of(self, runs: list[Any]) -> NDArray[np.float64]:
        parts = []
        for e, run in enumerate(runs):
            for s, w in self.targets.items():
                if self.misfit == "features":
                    parts.append(self._feature_residual(run, e, s, w))
                elif isinstance(run, str):
                    parts.append(np.full(self.index[e].size, FAILED_RESIDUAL))
                else:
                    difference = run[s] - self.measured[e][s]
                    if self.offset != "none":
                        basis = self.offset_basis(e)
                        difference = difference - basis @ np.linalg.lstsq(basis, difference, rcond=None)[0]
                    parts.append(math.sqrt(w) * difference / self.scale[e][s])
        return np.concatenate(parts)

    def offset_basis(self, e: int) -> NDArray[np.float64]:
        """The offset's basis over event ``e``'s compared times: a constant, and with
        ``offset="linear"`` the time from the times' mean (the two columns orthogonal)."""
        t = self.times[e]
        columns = [np.ones(t.size)] + ([t - t.mean()] if self.offset == "linear" else [])
        return np.column_stack(columns)

    def offsets(self, runs: list[Any]) -> list[dict[str, dict[str, float]]]:
        """Per event and target the offset ``measured - model`` profiled out at a point's runs:
        its value at the compared times' mean ``t_ref`` (``constant``, the series' unit) and its
        ``rate`` per second (0 with ``offset="constant"``); empty without an offset."""
        out: list[dict[str, dict[str, float]]] = []
        for e, run in enumerate(runs):
            out.append({})
            if self.offset == "none" or isinstance(run, str):
                continue
            basis = self.offset_basis(e)
            for s in self.targets:
                c = np.linalg.lstsq(basis, self.measured[e][s] - run[s], rcond=None)[0]
                out[e][s] = {"constant": float(c[0]), "rate_per_s": float(c[1]) if c.size > 1 else 0.0,
                             "t_ref": float(self.times[e].mean())}
        return out

    def coarse_features(self, u: NDArray[np.float64]) -> list[dict[str, dict[str, float]]]:
        """``misfit="features"``: per event and target the features of the run at ``u`` on half
        the configuration's cells (at least :data:`MIN_GRID_CELLS`), or an empty dict where the
        run fails."""
        out: list[dict[str, dict[str, float]]] = []
        for e, base in enumerate(self.bases):
            cells = max(int(json.loads(base)["numerics"]["cells"]) // 2, MIN_GRID_CELLS)
            self.evaluations += 1
            try:
                cfg = _core.drill_config_override(base, json.dumps([*self.pairs(u, e), ["numerics.cells", cells]]),
                                                  "parameters")
                run: dict[str, Any] = dict(_core.drill_solve(json.dumps(cfg)))
            except ValidationError:
                out.append({})
                continue
            ok = run["status"] == "success"
            out.append({s: cycle_features(self.times[e], np.asarray(run[s])[self.index[e]]).values
                        for s in self.targets} if ok else {})
        return out

    def _feature_residual(self, run: Any, e: int, s: str, w: float) -> NDArray[np.float64]:
        """The features of the model's series ``s`` of event ``e`` against the data's, in their
        standard deviations (a feature the model's run lacks: :data:`MISSING_FEATURE`)."""
        names, ref, sd = self.reference[e][s]
        if isinstance(run, str):
            return np.full(len(names), FAILED_RESIDUAL)
        got = cycle_features(self.times[e], run[s]).values
        r = math.sqrt(w) * (np.array([got.get(n, math.nan) for n in names]) - ref) / sd
        return np.where(np.isfinite(r), r, MISSING_FEATURE)

    def residuals(self, points: Sequence[NDArray[np.float64]], record: bool = True) -> list[NDArray[np.float64]]:
        """The residuals at each point, their misfits recorded in :attr:`history` unless
        ``record`` is false (the bootstrap's points, on other grids too)."""
        out = [self.residual_of(r) for r in self.run(points)]
        if not record:
            return out
        self.history += [(np.asarray(u, dtype=np.float64), float(r @ r)) for u, r in zip(points, out)]
        return out

    def coarser(self) -> _Problem:
        """The same problem on half the configuration's cells (at least :data:`MIN_GRID_CELLS`),
        with its own history and count of runs: the model's discretisation error at a point."""
        import copy

        out = copy.copy(self)
        out.history, out.evaluations = [], 0
        bases = []
        for base in self.bases:
            cfg = json.loads(base)
            cfg["numerics"]["cells"] = max(int(cfg["numerics"]["cells"]) // 2, MIN_GRID_CELLS)
            bases.append(json.dumps(cfg))
        out.bases = bases
        return out

    def groups(self, count: int) -> NDArray[np.int64]:
        """The bootstrap's group of each sample-by-sample residual: the windows' span (from the
        first window's start, the same for every event) cut into ``count`` contiguous parts of
        equal time."""
        labels = []
        for e, times in enumerate(self.times):
            first = min(a for a, _ in self.events[e].windows)
            span = max(float(times[-1] - first), 1e-300)
            g = np.minimum(np.floor((times - first) / span * count), count - 1).astype(np.int64)
            labels += [g] * len(self.targets)
        return np.concatenate(labels)


def _reference(times: NDArray[np.float64], values: NDArray[np.float64]
               ) -> tuple[list[str], NDArray[np.float64], NDArray[np.float64]]:
    """The features of a measured series with their standard deviations."""
    found = cycle_features(times, values)
    sd = uncertainties(times, values, found)
    names = list(found.values)
    return names, np.array([found.values[n] for n in names]), np.array([max(sd[n], 1e-300) for n in names])


def _speed_series(data: MeasuredData, duration: float) -> list[list[float]]:
    """``top="measured"``: the data's ``surface_rpm`` as ``top_drive.speed_series`` over ``0 ..
    duration`` (from the last sample at or before 0 to the first at or after ``duration``, the
    last value held to ``duration`` when the data end before it), refused naming the column and
    the time when the data start after 0 or hold a non-finite speed there."""
    t, rpm = data.t, data.series["surface_rpm"]
    if t[0] > 0:
        raise ValidationError(f"{data.source}: column surface_rpm", f"first sample at t = {t[0]:g} s",
                              "data from the start-up (t <= 0) to drive the model with top='measured'")
    a = int(np.searchsorted(t, 0.0, side="right")) - 1
    b = min(int(np.searchsorted(t, duration, side="left")), t.size - 1)
    t, rpm = t[a:b + 1], rpm[a:b + 1]
    bad = ~np.isfinite(rpm)
    if bad.any():
        raise ValidationError(f"{data.source}: column surface_rpm", f"NaN or infinite at t = {t[np.argmax(bad)]:g} s",
                              "finite speeds over the run to drive the model with top='measured'")
    rpm = _denoised_speed(t, rpm)
    pairs = [[float(x), float(y)] for x, y in zip(t, rpm)]
    if pairs[-1][0] < duration:
        pairs.append([duration, pairs[-1][1]])
    return pairs


def _denoised_speed(t: NDArray[np.float64], rpm: NDArray[np.float64]) -> NDArray[np.float64]:
    """The measured speed the model imposes: smoothed over the data's own samples when it carries
    noise (a noise level, from successive differences, above :data:`SPEED_NOISE` of its range),
    since the torque that imposes a speed is the top drive's inertia times its derivative, which
    amplifies noise by the sampling rate. The smoothing is a cubic Savitzky-Golay filter over
    :data:`SPEED_SMOOTH_TIME` (an odd number of samples, at least five), which passes a cubic's
    worth of the speed's own motion unchanged (a moving average as long flattens the speed's
    turns at a slip and biases the torque). Measured on Well B (250 cells, 0.3 rpm of noise at
    100 Hz, the true friction): the imposing torque's error is 12.8 kN m RMS unsmoothed,
    1.3 kN m smoothed, with a mean error below 0.1 kN m."""
    from scipy.signal import savgol_filter

    dt = float(np.median(np.diff(t))) if t.size > 1 else 1.0
    width = max(int(round(SPEED_SMOOTH_TIME / dt)) // 2 * 2 + 1, 5)
    span = float(np.max(rpm) - np.min(rpm))
    if rpm.size < width or not noise_level(rpm) > SPEED_NOISE * span:
        return rpm
    return np.asarray(savgol_filter(rpm, width, 3), dtype=np.float64)


class _Cached:
    """The residual function and its batched forward-difference Jacobian for least_squares, over
    the coordinates ``free`` of the scaled vector (the others fixed at ``fixed``)."""

    def __init__(self, problem: _Problem, fixed: NDArray[np.float64], free: list[int], step: float) -> None:
        self.problem = problem
        self.fixed = fixed
        self.free = free
        self.step = step
        self.cache: dict[bytes, NDArray[np.float64]] = {}

    def full(self, v: NDArray[np.float64]) -> NDArray[np.float64]:
        u = self.fixed.copy()
        u[self.free] = v
        return u

    def fun(self, v: NDArray[np.float64]) -> NDArray[np.float64]:
        key = np.asarray(v, dtype=np.float64).tobytes()
        if key not in self.cache:
            self.cache[key] = self.problem.residuals([self.full(v)])[0]
        return self.cache[key]

    def jac(self, v: NDArray[np.float64]) -> NDArray[np.float64]:
        v = np.asarray(v, dtype=np.float64)
        r0 = self.fun(v)
        steps = []
        points = []
        for i in range(v.size):
            h = self.step if v[i] + self.step <= 1.0 else -self.step
            w = v.copy()
            w[i] += h
            steps.append(h)
            points.append(self.full(w))
        cols = self.problem.residuals(points)
        return np.column_stack([(c - r0) / h for c, h in zip(cols, steps)])


def _refine(problem: _Problem, u0: NDArray[np.float64], free: list[int], step: float,
            max_iterations: int) -> tuple[NDArray[np.float64], float, dict[str, Any]]:
    """:func:`scipy.optimize.least_squares` from ``u0`` over the coordinates ``free`` (forward
    differences of ``step`` in the scaled box, as one batch per Jacobian: larger than the scale at
    which the set-valued friction makes the misfit jump); never worse than ``u0``."""
    from scipy.optimize import least_squares

    cached = _Cached(problem, u0.copy(), free, step)
    r0 = cached.fun(u0[free])
    # the features' chi-square needs its minimum to a hundredth of a standard deviation, no finer
    tol = {"ftol": 1e-3, "xtol": 1e-4} if problem.misfit == "features" else {}
    res = least_squares(cached.fun, u0[free], jac=cached.jac, bounds=(0.0, 1.0), method="trf",
                        max_nfev=max_iterations, x_scale=1.0, **tol)
    u, ssr = (cached.full(res.x), float(res.fun @ res.fun)) if res.fun @ res.fun < r0 @ r0 else (u0, float(r0 @ r0))
    return u, ssr, {"status": int(res.status), "message": str(res.message), "evaluations": int(res.nfev)}


def _jacobian(problem: _Problem, u: NDArray[np.float64], step: float) -> NDArray[np.float64]:
    """Central differences of the residuals at ``u`` (one-sided at a bound), step ``step`` in the
    scaled box, as one batch."""
    points = []
    spans = []
    for i in range(u.size):
        hi, lo = min(u[i] + step, 1.0), max(u[i] - step, 0.0)
        for v in (hi, lo):
            w = u.copy()
            w[i] = v
            points.append(w)
        spans.append(hi - lo)
    res = problem.residuals(points)
    return np.column_stack([(res[2 * i] - res[2 * i + 1]) / spans[i] for i in range(u.size)])


# --------------------------------------------------------------------------- inputs


def _targets(targets: Union[str, Sequence[str], Mapping[str, float]]) -> dict[str, float]:
    if isinstance(targets, str):
        targets = [targets]
    items = dict(targets) if isinstance(targets, Mapping) else {t: 1.0 for t in targets}
    known = (*MODEL_SERIES, *AXIAL_SERIES)
    if not items:
        raise ValidationError("targets", targets, f"at least one series of {', '.join(known)}")
    out = {}
    for name, weight in items.items():
        if name not in known:
            raise ValidationError("targets", name, f"series the model computes: {', '.join(known)} (the last "
                                  f"{len(AXIAL_SERIES)} in coupled runs)")
        w = float(weight)
        if not (math.isfinite(w) and w > 0):
            raise ValidationError(f"targets[{name}]", weight, "a finite weight > 0")
        out[name] = w
    return out


def _number_at(config: DrillConfig, key: str) -> Any:
    """The value at dotted path ``key`` of the configuration's dict (``None`` if absent)."""
    node: Any = config.to_dict()
    for part in key.replace("]", "").split("."):
        name, _, index = part.partition("[")
        if not isinstance(node, Mapping) or name not in node:
            return None
        node = node[name]
        if index:
            if not isinstance(node, list) or not index.isdigit() or int(index) >= len(node):
                return None
            node = node[int(index)]
    return node


def _bounds(parameters: Mapping[str, Any], config: DrillConfig) -> dict[str, tuple[float, float]]:
    if not isinstance(parameters, Mapping) or not parameters:
        raise ValidationError("parameters", parameters, "a mapping of dotted keys to (low, high) bounds")
    out = {}
    chosen = config.chosen_units()
    for key, bounds in parameters.items():
        try:
            # plain numbers in the configuration's unit system, strings with units converted
            lo, hi = (float(override_to_si(str(key), b, config.units, chosen)) for b in bounds)
        except ValidationError as exc:
            raise ValidationError(f"parameters[{key}]", bounds, f"(low, high): two values of {key}: {exc.allowed}") \
                from None
        except (TypeError, ValueError):
            raise ValidationError(f"parameters[{key}]", bounds, "(low, high): two numbers") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ValidationError(f"parameters[{key}]", bounds, "finite bounds low < high")
        for value in (lo, hi):  # the key exists, takes numbers and the core accepts both bounds
            config.with_overrides({key: value}, units="si")
        current = _number_at(config, key)
        if isinstance(current, bool) or not isinstance(current, float):
            raise ValidationError(f"parameters[{key}]", current, "a key of a real number (not an integer, a flag, "
                                  "a string or a list)")
        out[str(key)] = (lo, hi)
    return out


def _windows(windows: Any, data: MeasuredData, config: DrillConfig) -> tuple[tuple[float, float], ...]:
    if windows is None:
        return ((0.0, min(data.span[1], config.numerics.duration)),)
    out = []
    for w in windows:
        try:
            a, b = (float(x) for x in w)
        except (TypeError, ValueError):
            raise ValidationError("windows", w, "(start, end) pairs of times, s") from None
        if not (math.isfinite(a) and math.isfinite(b) and 0 <= a < b):
            raise ValidationError("windows", w, "0 <= start < end, finite, s from the start-up")
        out.append((a, b))
    if not out:
        raise ValidationError("windows", windows, "at least one (start, end) window")
    return tuple(out)


def _as_list(value: Any) -> list[Any]:
    return list(value) if isinstance(value, (list, tuple)) else [value]


# --------------------------------------------------------------------------- the fit


def fit(
    config: Union[ConfigLike, Sequence[ConfigLike]],
    data: Union[DataLike, Sequence[DataLike]],
    parameters: Mapping[str, tuple[Any, Any]],
    *,
    targets: Union[str, Sequence[str], Mapping[str, float]] = ("motor_torque",),
    windows: Optional[Sequence[tuple[float, float]]] = None,
    per_event: Sequence[str] = (),
    samples: Optional[int] = None,
    threads: Optional[int] = None,
    seed: int = 0,
    level: float = 0.95,
    starts: Optional[int] = None,
    horizon: float = 5.0,
    max_iterations: int = 50,
    diff_step: float = 1e-2,
    profile: Union[bool, str] = "auto",
    profile_points: int = 9,
    landscape: bool = True,
    landscape_points: int = 9,
    max_gap: Optional[float] = None,
    progress: Optional[Callable[[str], Any]] = None,
    top: str = "controller",
    carry: Optional[int] = None,
    misfit: str = "least_squares",
    interval: str = "auto",
    offset: str = "none",
) -> FitResult:
    """Fits configuration values to measured data (see the module docstring).

    Parameters
    ----------
    config : DrillConfig, mapping or TOML path, or one per event
        The model; one configuration serves every event unless a list (one per event) is given.
    data : MeasuredData, path, DataFrame, or a list of them (one per event)
        The measurements (:func:`~drillstring.calibration.data.read_measured` reads paths and
        frames with the column names of ``drill``'s ``series.csv``), times from the start-up.
    parameters : mapping
        Dotted key -> ``(low, high)``: any real configuration value (``friction.static``,
        ``friction.kinetic_ratio``, ``friction.stick_speed``, ``damping_rate``,
        ``sections[1].density``, ...). Plain numbers are in the configuration's unit system
        (:attr:`DrillConfig.units <drillstring.drilling.config.DrillConfig.units>`: klbf for
        ``bit.weight_on_bit`` of a field file), strings with units (``"10 klbf"``) in their own;
        the result's values are SI.
    targets : str, sequence of str, or mapping of str to float
        The series compared (of ``surface_rpm``, ``motor_torque``, ``bit_rpm``, ``bit_torque``,
        and in a coupled run, a ``[hoist]`` table, ``hook_load`` and ``weight_on_bit``), with their
        weights when a mapping (default weight 1).
    windows : list of (start, end), optional
        Model times compared, s (default: from 0 to the end of the data or of the configuration's
        duration); the same for every event.
    per_event : keys
        Parameters with one value per event (the others are shared).
    samples : int, optional
        Points of the global stage (a power of two; default 64 per parameter, at least 128,
        rounded up; with ``misfit="features"`` 32 per parameter, at least 64).
    starts : int, optional
        Refinements, from the best points of the global stage at least
        :data:`START_SEPARATION` apart (default 4; 2 with ``misfit="features"``, whose misfit
        has one valley where the sample-by-sample one has many).
    horizon : float
        The global stage compares the first ``horizon`` seconds or more of the windows (the
        span halved until it is shorter than twice ``horizon``) and each start is refined over
        that, twice that, ... and the whole span in turn: the later cycles of a stick-slip
        record shift in phase with the parameters and make the whole record's misfit
        many-valleyed. Choose it to hold the break-off and the first slip.
    threads : int, optional
        Runs solved at once (default: every core).
    profile : ``"auto"``, True or False
        Profile likelihood for the intervals: where the Jacobian is ill-conditioned or an
        interval leaves the box (``"auto"``), for every parameter, or never.
    landscape, landscape_points
        The misfit over a grid of each pair of parameters.
    top : ``"controller"`` or ``"measured"``
        The model's top boundary: the configuration's top drive with its controller and setpoint
        (default), or the data's ``surface_rpm`` imposed as the top speed
        (``top_drive.mode = "measured_speed"``; the data must start at the start-up, and
        ``surface_rpm`` cannot then be a target). See the guide's section "The measured top".
    carry : int, optional
        Early stopping: the number of starts carried on to the longer horizons, the best after
        the first horizon's refinement (default: every start).
    misfit : ``"least_squares"`` or ``"features"``
        What is minimised: the normalised residuals sample by sample over the horizons (default),
        or the cycle features of each target (break-off torque, each cycle's maximum and minimum,
        period, mean; :mod:`~drillstring.calibration.features`) against the data's, in their
        standard deviations (noise, cycle scatter, model error), over the whole windows: a
        model whose period differs slightly from the well's, a phase shift or a sensor's lag
        leave it unchanged. See the guide's section "Data a model did not make".
    interval : ``"auto"``, ``"jacobian"`` or ``"bootstrap"``
        A sample-by-sample fit's intervals: the Jacobian's, joined with the block bootstrap's
        over the stick-slip cycles (:func:`_bootstrap_intervals`) where the residuals show a
        model error (``"auto"``), never (``"jacobian"``) or always (``"bootstrap"``).
    offset : ``"none"``, ``"constant"`` or ``"linear"``
        A sensor offset per event and target, ``measured = model + a + b (t - t_ref)``, by linear
        least squares at every run, profiled out of the residuals (``"constant"``: ``b = 0``);
        in :attr:`FitResult.offsets` and the fitted series. Sample-by-sample misfit only.

    Returns
    -------
    FitResult

    Raises
    ------
    ValidationError
        Bad data (naming the column and the time), a key that is not a real configuration value,
        bounds the core refuses, windows outside the data.
    """
    start_time = time.perf_counter()
    configs, datasets = _read_inputs(config, data)
    target_map = _targets(targets)
    bounds = _bounds(parameters, configs[0])
    opts = _Options.checked(
        target_map, bounds, per_event=per_event, samples=samples, threads=threads, seed=seed, level=level,
        starts=starts if starts is not None else (2 if misfit == "features" else 4),
        horizon=horizon, max_iterations=max_iterations, diff_step=diff_step, profile=profile,
        profile_points=profile_points, landscape=landscape, landscape_points=landscape_points, max_gap=max_gap,
        say=progress or (lambda _msg: None), top=top, carry=carry, misfit=misfit, interval=interval,
        offset=offset,
    )
    events = _events(configs, datasets, windows, opts)
    columns = _columns(bounds, events, opts.per_event)
    problems = _problems(events, columns, opts)
    sobol, global_ssr, global_stage = _global_stage(problems, columns, opts)
    u_opt, ssr, refinement = _refinement(problems, sobol, global_ssr, opts)
    problem = problems[-1]
    grid_error = _grid_error(problem, u_opt) if opts.misfit == "features" else []
    r = problem.residuals([u_opt])[0]
    ssr = float(r @ r) if opts.misfit == "features" else ssr
    spread = _Spread.at(problem, u_opt, ssr, r, opts)
    estimates = _jacobian_intervals(problem, u_opt, ssr, spread, columns)
    warnings_ = _ridge_warnings(spread, columns)
    profiles = _profiles(problem, u_opt, ssr, spread, columns, estimates, opts)
    intervals = _bootstrap_intervals(problem, u_opt, r, spread, columns, estimates, opts)
    warnings_ += _identifiability_warnings(estimates, opts.level)
    landscapes = _landscapes(problem, u_opt, columns, opts)
    fitted_configs, fitted, failures, offsets = _fitted_runs(problem, events, u_opt)
    series_checks, feature_rows = _checks(problem, fitted, grid_error)
    corr = checks.correlation(spread.cov)
    warnings_ += _result_warnings(estimates, series_checks, feature_rows, corr, ssr, r.size, opts)
    return FitResult(
        parameters=estimates, configs=fitted_configs, events=events, targets=target_map, ssr=ssr, points=r.size,
        level=opts.level, evaluations=sum(q.evaluations for q in problems), seconds=time.perf_counter() - start_time,
        condition=spread.condition, residual_autocorrelation=_autocorrelation(series_checks, spread),
        global_stage=global_stage, refinement=refinement, rms=_rms(problem, series_checks), fitted=fitted,
        landscapes=landscapes, profiles=profiles, warnings=warnings_ + failures, top=opts.top, objective=opts.misfit,
        series_checks=series_checks, correlation=corr.tolist(), features=feature_rows, intervals=intervals,
        offset=opts.offset, offsets=offsets,
    )


# --------------------------------------------------------------------------- the fit's steps


@dataclass(frozen=True)
class _Options:
    """The settings of :func:`fit` (its keywords), checked; ``say`` reports progress."""

    targets: dict[str, float]
    per_event: list[str]
    samples: Optional[int]
    threads: int
    seed: int
    level: float
    starts: int
    horizon: float
    max_iterations: int
    diff_step: float
    profile: Union[bool, str]
    profile_points: int
    landscape: bool
    landscape_points: int
    max_gap: Optional[float]
    say: Callable[[str], Any]
    top: str
    carry: Optional[int]
    misfit: str
    interval: str
    offset: str

    @classmethod
    def checked(cls, targets: dict[str, float], bounds: Mapping[str, tuple[float, float]], *, per_event: Sequence[str],
                threads: Optional[int], **kw: Any) -> _Options:
        """The options, each refused naming its keyword and what it takes."""
        per = [str(k) for k in per_event]
        for key in per:
            if key not in bounds:
                raise ValidationError("per_event", key, f"a key of parameters: {', '.join(bounds)}")
        for name in ("level", "diff_step"):
            value = kw[name]
            if not (isinstance(value, (int, float)) and 0.0 < value < 1):
                raise ValidationError(name, value, "a number in (0, 1)")
        for name, least in (("profile_points", 3), ("landscape_points", 2), ("max_iterations", 1), ("starts", 1)):
            count = kw[name]
            if isinstance(count, bool) or not isinstance(count, int) or count < least:
                raise ValidationError(name, count, f"an integer >= {least}")
        if kw["profile"] not in ("auto", True, False):
            raise ValidationError("profile", kw["profile"], "'auto', True or False")
        top, carry = kw["top"], kw["carry"]
        if top not in ("controller", "measured"):
            raise ValidationError("top", top, "'controller' or 'measured'")
        if top == "measured" and "surface_rpm" in targets:
            raise ValidationError("targets", ", ".join(targets),
                                  "targets other than surface_rpm with top='measured' (the model's top speed is the "
                                  "data's)")
        if kw["misfit"] not in MISFITS:
            raise ValidationError("misfit", kw["misfit"], " or ".join(repr(m) for m in MISFITS))
        if kw["offset"] not in OFFSETS:
            raise ValidationError("offset", kw["offset"], ", ".join(repr(m) for m in OFFSETS))
        if kw["offset"] != "none" and kw["misfit"] != "least_squares":
            raise ValidationError("offset", kw["offset"], "'none' with misfit='features' (the offset is estimated "
                                  "sample by sample: misfit='least_squares')")
        if kw["interval"] not in INTERVALS:
            raise ValidationError("interval", kw["interval"], ", ".join(repr(m) for m in INTERVALS))
        if carry is not None and (isinstance(carry, bool) or not isinstance(carry, int) or carry < 1):
            raise ValidationError("carry", carry, "an integer >= 1, or None for every start")
        if threads is None:
            threads = os.cpu_count() or 1
        if isinstance(threads, bool) or not isinstance(threads, int) or not 1 <= threads <= _core.MAX_THREADS:
            raise ValidationError("threads", threads, f"an integer 1..{_core.MAX_THREADS}")
        return cls(targets=targets, per_event=per, threads=threads, **kw)


def _read_inputs(config: Union[ConfigLike, Sequence[ConfigLike]], data: Union[DataLike, Sequence[DataLike]]
                 ) -> tuple[list[DrillConfig], list[MeasuredData]]:
    """The configuration and the data of each event (one configuration serves every event)."""
    configs = [_config(c) for c in _as_list(config)] if isinstance(config, (list, tuple)) else [_config(config)]
    datasets = [d if isinstance(d, MeasuredData) else read_measured(d) for d in _as_list(data)] \
        if isinstance(data, (list, tuple)) else [data if isinstance(data, MeasuredData) else read_measured(data)]
    if len(configs) == 1 and len(datasets) > 1:
        configs = configs * len(datasets)
    if len(configs) != len(datasets):
        raise ValidationError("config", f"{len(configs)} configurations",
                              f"one configuration, or one per event ({len(datasets)} data sets)")
    return configs, datasets


def _events(configs: list[DrillConfig], datasets: list[MeasuredData], windows: Any, opts: _Options) -> list[Event]:
    """The events, their data checked for the targets over their windows."""
    events = []
    for cfg, ds_ in zip(configs, datasets):
        axial = [name for name in opts.targets if name in AXIAL_SERIES]
        if axial and cfg.hoist is None:
            raise ValidationError("targets", axial[0], "a series of a torsion-only run (surface_rpm, motor_torque, "
                                  "bit_rpm, bit_torque): hook_load and weight_on_bit need a coupled run, a [hoist] "
                                  "table with bit.law = rgd or detournay")
        ds_.require(list(opts.targets) + (["surface_rpm"] if opts.top == "measured" else []))
        wins = _windows(windows, ds_, cfg)
        ds_.check_windows(wins, list(opts.targets), opts.max_gap)
        events.append(Event(cfg, ds_, wins))
    return events


def _columns(bounds: Mapping[str, tuple[float, float]], events: list[Event], per: list[str]) -> list[_Column]:
    """The coordinates of the parameter vector: a shared key once, a per-event key once per event."""
    columns = []
    for key, (lo, hi) in bounds.items():
        if key in per and len(events) > 1:
            columns += [_Column(f"events[{e}].{key}", key, e, lo, hi) for e in range(len(events))]
        else:
            columns.append(_Column(key, key, None, lo, hi))
    return columns


def _problems(events: list[Event], columns: list[_Column], opts: _Options) -> list[_Problem]:
    """The problem of each horizon, the shortest first and the whole windows last: the span of
    the windows halved until it is shorter than twice ``horizon``."""
    horizon = opts.horizon
    if isinstance(horizon, bool) or not isinstance(horizon, (int, float)) or not horizon > 0:
        raise ValidationError("horizon", horizon, "a time > 0, s")
    longest = max(max(b for _, b in e.windows) - min(a for a, _ in e.windows) for e in events)
    fractions = [1.0]
    # the features do not depend on the cycles' phase: the whole windows at once
    while opts.misfit == "least_squares" and fractions[0] * longest / 2 >= horizon * (1 - 1e-9):
        fractions.insert(0, fractions[0] / 2)
    problems = [_Problem(events, columns, opts.targets, opts.threads, f, opts.top, opts.misfit, opts.offset)
                for f in fractions]
    if min(q.points for q in problems) <= len(columns):
        raise ValidationError("windows", [e.windows for e in events],
                              f"more compared samples ({min(q.points for q in problems)}, in the shortest horizon) "
                              f"than parameters ({len(columns)})")
    return problems


def _global_stage(problems: list[_Problem], columns: list[_Column], opts: _Options
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64], dict[str, Any]]:
    """Stage 1: the scrambled Sobol sample of the box solved over the shortest horizon; the
    points, their misfits and ``fit.json``'s ``global``."""
    from scipy.stats import qmc

    p = len(columns)
    n = opts.samples if opts.samples is not None else \
        (max(32 * p, 64) if opts.misfit == "features" else max(64 * p, 128))
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValidationError("samples", opts.samples, "an integer >= 1")
    m = max(int(math.ceil(math.log2(n))), 1)
    sobol = qmc.Sobol(d=p, scramble=True, seed=opts.seed).random_base2(m)
    first = problems[0]
    opts.say(f"global stage: {sobol.shape[0]} points x {len(first.events)} event(s) on {opts.threads} thread(s), "
             f"over {first.fraction:.3g} of the windows' span")
    global_ssr = np.array([float(r @ r) for r in first.residuals(list(sobol))])
    best = int(np.argmin(global_ssr))
    stage = {"points": int(sobol.shape[0]), "best_ssr": float(global_ssr[best]), "horizon": first.fraction,
             "best": {c.name: float(v) for c, v in zip(columns, problems[-1].values(sobol[best].copy()))},
             "failed": int(np.sum(global_ssr >= FAILED_RESIDUAL ** 2))}
    return sobol, global_ssr, stage


def _through(problems: list[_Problem], u: NDArray[np.float64], stages: range, opts: _Options
             ) -> tuple[NDArray[np.float64], float, dict[str, Any]]:
    """A start refined through the horizons ``stages``, the shortest first; before a longer
    horizon, the best of a small Sobol sample within :data:`ZOOM` of the point."""
    from scipy.stats import qmc

    p = u.size
    ssr = math.inf
    info: dict[str, Any] = {}
    for stage in stages:
        q = problems[stage]
        if stage:  # a longer horizon: the best of a small sample around the point first
            near = np.clip(u + (qmc.Sobol(d=p, scramble=True, seed=opts.seed + stage).random_base2(ZOOM_LOG2)
                                - 0.5) * 2 * ZOOM, 0.0, 1.0)
            candidates = [u, *near]
            misfits = [float(r @ r) for r in q.residuals(candidates)]
            u = candidates[int(np.argmin(misfits))].copy()
        u, ssr, info = _refine(q, u, list(range(p)), opts.diff_step, opts.max_iterations)
    return u, ssr, info


def _refinement(problems: list[_Problem], sobol: NDArray[np.float64], global_ssr: NDArray[np.float64],
                opts: _Options) -> tuple[NDArray[np.float64], float, dict[str, Any]]:
    """Stage 2: least squares from the best ``starts`` distinct points of the global stage
    through the horizons (with ``carry``, only the best after the first horizon go on); the
    best point, its misfit and ``fit.json``'s ``refinement``."""
    order: list[int] = []
    for k in np.argsort(global_ssr):
        if len(order) < opts.starts and all(np.max(np.abs(sobol[k] - sobol[j])) >= START_SEPARATION for j in order):
            order.append(int(k))
    opts.say(f"refinement from the best {len(order)} point(s) (ssr {global_ssr.min():.4g})")
    carry = opts.carry
    if carry is None or carry >= len(order) or len(problems) == 1:
        runs = [_through(problems, sobol[k].copy(), range(len(problems)), opts) for k in order]
        dropped: list[float] = []
    else:  # early stopping: every start over the first horizon, the best `carry` on
        first = sorted((_through(problems, sobol[k].copy(), range(1), opts) for k in order), key=lambda run: run[1])
        runs = [_through(problems, u.copy(), range(1, len(problems)), opts) for u, _, _ in first[:carry]]
        dropped = [run[1] for run in first[carry:]]
        opts.say(f"carried the best {carry} of {len(first)} start(s) on (misfits over the first horizon "
                 f"{[round(run[1], 4) for run in first]})")
    u_opt, ssr, info = min(runs, key=lambda run: run[1])
    refinement = {**info, "starts": len(order), "ssr": ssr, "ssr_of_starts": [run[1] for run in runs],
                  "horizons": [q.fraction for q in problems]}
    if dropped:
        refinement["dropped_first_horizon_ssr"] = dropped
    return u_opt, ssr, refinement


@dataclass(frozen=True)
class _Spread:
    """Stage 3's linearisation at the optimum (in the box scaled to ``[0, 1]``): the Jacobian,
    its condition number, the covariance ``s^2 (J^T J)^-1``, the standard errors (SI) and the
    misfit threshold ``s^2 chi2_1(level)`` of the intervals."""

    jacobian: NDArray[np.float64]
    condition: float
    rho: float
    s2: float
    cov: NDArray[np.floating[Any]]
    se: NDArray[np.float64]
    span: NDArray[np.float64]
    threshold: float
    profile: list[int]

    @classmethod
    def at(cls, problem: _Problem, u_opt: NDArray[np.float64], ssr: float, r: NDArray[np.float64],
           opts: _Options) -> _Spread:
        """The linearisation at ``u_opt`` (residuals ``r``, misfit ``ssr``); ``profile`` the
        parameters whose intervals come from profiles (``opts.profile``)."""
        from scipy import stats

        p = u_opt.size
        dof = max(r.size - p - problem.profiled, 1)
        if problem.misfit == "features":
            # residuals in their standard deviations, nearly independent (one per feature): the
            # chi-square's scale is 1, widened by its excess (a model error beyond the assumed)
            rho = 0.0
            s2 = max(1.0, ssr / dof)
        else:
            rho = float(np.corrcoef(r[:-1], r[1:])[0, 1]) if r.size > 3 and np.std(r) > 0 else 0.0
            rho = rho if math.isfinite(rho) else 0.0
            inflation = (1 + rho) / (1 - rho) if 0 < rho < 0.999 else (1e3 if rho >= 0.999 else 1.0)
        J = _jacobian(problem, u_opt, opts.diff_step)
        if problem.misfit != "features":
            if rho > checks.AUTOCORRELATION_LIMIT:
                inflation = max(inflation, _hac_inflation(J, r, dof))
            s2 = ssr / dof * inflation
        span = problem.upper - problem.lower
        sing = np.linalg.svd(J, compute_uv=False)
        condition = float(sing[0] / sing[-1]) if sing[-1] > 0 else math.inf
        cov = s2 * np.linalg.pinv(J.T @ J)
        se = np.sqrt(np.maximum(np.diag(cov), 0.0)) * span
        profile = opts.profile is True or (opts.profile == "auto" and condition > CONDITION_LIMIT)
        return cls(J, condition, rho, s2, cov, se, span, s2 * float(stats.chi2.ppf(opts.level, 1)),
                   list(range(p)) if profile else [])


def _hac_inflation(J: NDArray[np.float64], r: NDArray[np.float64], dof: int) -> float:
    """Residuals correlated beyond :data:`~drillstring.calibration.checks.AUTOCORRELATION_LIMIT`
    (a model error with structure, not sensor noise): the factor by which the Newey-West
    (heteroscedasticity and autocorrelation consistent, Bartlett weights) sandwich covariance
    ``B S B`` (``B = (J^T J)^-1``, ``S`` the long-run covariance of the scores ``J_t r_t``) exceeds
    the independent-residual covariance ``ssr / dof B``, the largest over the parameters. Its
    bandwidth is :data:`HAC_LENGTHS` times the residuals' correlation length, the first lag at
    which their autocorrelation falls below :data:`HAC_CUTOFF` (at most half the samples). The AR(1) factor
    ``(1 + rho) / (1 - rho)`` assumes one exponential decay; a stick-slip misfit's residual
    correlation follows the cycles instead."""
    n = r.size
    if n < 8 or not np.any(r):
        return 1.0
    centred = r - r.mean()
    spectrum = np.fft.rfft(centred, 2 * n)
    acf = np.fft.irfft(spectrum * np.conj(spectrum))[:n]
    acf = acf / acf[0]
    below = np.flatnonzero(acf < HAC_CUTOFF)
    # three correlation lengths: the Bartlett weights' taper then loses a tenth of an AR(1)'s
    # long-run variance instead of a third
    bandwidth = int(min(HAC_LENGTHS * below[0] if below.size else n // 2, n // 2))
    g = J * r[:, None]
    S = g.T @ g
    for lag in range(1, bandwidth + 1):
        c = g[lag:].T @ g[:-lag]
        S += (1.0 - lag / (bandwidth + 1)) * (c + c.T)
    B = np.linalg.pinv(J.T @ J)
    hac = np.diag(B @ S @ B)
    plain = float(r @ r) / dof * np.diag(B)
    ratios = [h / q for h, q in zip(hac, plain) if q > 0 and math.isfinite(h)]
    return max([1.0, *ratios])


def _jacobian_intervals(problem: _Problem, u_opt: NDArray[np.float64], ssr: float, spread: _Spread,
                        columns: list[_Column]) -> dict[str, ParameterEstimate]:
    """The Jacobian's interval of each parameter, checked along its own path: the points of the
    confidence ellipsoid that reach furthest in each parameter, and multiples of them, solved as
    one batch; widened to every point solved so far within the threshold."""
    p = u_opt.size
    path_points = []
    for i in range(p):
        direction = spread.cov[:, i] / math.sqrt(spread.cov[i, i]) * math.sqrt(spread.threshold / spread.s2) \
            if spread.cov[i, i] > 0 else np.eye(p)[i] * 0.0
        for sign in (1.0, -1.0):
            path_points += [np.clip(u_opt + sign * m * direction, 0.0, 1.0) for m in PATH_MULTIPLES]
    path_ssr = np.array([float(v @ v) for v in problem.residuals(path_points)]) - ssr
    x_opt = problem.values(u_opt)
    count = len(PATH_MULTIPLES)
    estimates: dict[str, ParameterEstimate] = {}
    for i, c in enumerate(columns):
        ends = []
        for side in range(2):
            part = slice((2 * i + side) * count, (2 * i + side + 1) * count)
            xs = np.array([problem.values(w)[i] for w in path_points[part]])
            ends.append(_path_end(xs, path_ssr[part], side, float(x_opt[i]), float(spread.se[i]), spread))
        estimates[c.name] = _jacobian_estimate(problem, c, i, float(x_opt[i]), ends, ssr, spread)
    return estimates


def _path_end(xs: NDArray[np.float64], excess: NDArray[np.float64], side: int, best: float, se: float,
              spread: _Spread) -> float:
    """One end of a Jacobian interval (``side`` 0 up, 1 down): the furthest point of its path
    inside the threshold, never nearer than the Jacobian's (quadratic) reach: a jump of the misfit
    inside it is the set-valued friction's roughness at small scales, not information."""
    inside = excess <= spread.threshold
    reach = best + (1 if side == 0 else -1) * math.sqrt(spread.threshold / spread.s2) * se
    if not inside[0] or not math.isfinite(se):
        return reach
    far = float(xs[np.flatnonzero(inside)[-1]])  # the furthest point inside
    return max(far, reach) if side == 0 else min(far, reach)


def _jacobian_estimate(problem: _Problem, c: _Column, i: int, best: float, ends: list[float], ssr: float,
                       spread: _Spread) -> ParameterEstimate:
    """The estimate of parameter ``i`` from its path's ``ends`` (up, down), widened to every
    point solved so far within the threshold and reported up to the box."""
    hi_ci, lo_ci = max(ends[0], best), min(ends[1], best)
    # every point solved so far whose misfit is within the threshold belongs to the set too
    # (the set-valued friction makes the misfit jump at the scale of the intervals)
    near = [problem.values(u)[i] for u, v in problem.history if v - ssr <= spread.threshold]
    if near:
        lo_ci, hi_ci = min(lo_ci, min(near)), max(hi_ci, max(near))
    span = spread.span[i]
    at_bounds = lo_ci <= c.lower + 1e-12 * span and hi_ci >= c.upper - 1e-12 * span
    wide = not math.isfinite(spread.se[i]) or at_bounds
    # the fit searches the box only: an interval reaching past a bound is reported up to it
    lo_ci, hi_ci = max(lo_ci, c.lower), min(hi_ci, c.upper)
    return ParameterEstimate(c.name, best, float(lo_ci), float(hi_ci), c.lower, c.upper, float(spread.se[i]),
                             "jacobian", not wide)


def _bootstrap_intervals(problem: _Problem, u_opt: NDArray[np.float64], r: NDArray[np.float64], spread: _Spread,
                         columns: list[_Column], estimates: dict[str, ParameterEstimate], opts: _Options
                         ) -> dict[str, Any]:
    """The block bootstrap over stick-slip cycles of a sample-by-sample fit (with
    ``interval="auto"`` where its residuals show a model error, :func:`_model_error`; see the
    guide's "The measured top" for the coverage it gives), joined to the Jacobian's interval in ``estimates`` (never
    narrower than it):

    1. the misfit of each **cycle** (the windows cut into groups one period of the data's first
       target long, :meth:`_Problem.groups`, :func:`_cycle_count`) at :data:`BOOTSTRAP_POINTS`
       per parameter scattered (scrambled Sobol) around the optimum, over the larger of
       :data:`BOOTSTRAP_SE` standard errors and :data:`BOOTSTRAP_SHARE` of each value;
    2. :data:`BOOTSTRAP_REPLICATES` resamplings of the cycles with replacement, each replicate's
       estimate the minimum of the quadratic fitted to its misfit summed over its cycles
       (:func:`_quadratic_minima`); the interval from the lesser of the value and the quadratic's
       minimum over all cycles (the **smoothed** estimate: the value is a minimum of the
       staircase, which the optimiser may meet a stair away from the smooth one) to the greater,
       extended on each side by the replicates' standard deviation times Student's t of the
       cycles' ``G - 1`` degrees of freedom (and ``sqrt(G / (G - 1))``, the jackknife's divisor:
       few cycles, a wide quantile);
    3. widened on each side by the model's **discretisation error** at the optimum: the shift of
       the fitted quadratic's minimum when the same points are solved on half the cells (as the
       features' deviations carry it, :func:`_grid_error`).

    Why: a model error leaves residuals correlated over whole cycles, and the set-valued friction
    makes the misfit a staircase in the parameters (the stick and slip instants move by whole
    steps), so the estimate jumps between the stairs from one noise draw to the next by more than
    any covariance of the Jacobian says, however its scale is corrected. The cycles are nearly
    independent, and each replicate meets the staircase itself. Returns ``fit.json``'s
    ``intervals`` (``method``, ``cycles``, ``points``, and per parameter the ``jacobian``,
    ``bootstrap`` and reported ``ci_low``, ``ci_high``, the ``smoothed`` estimate, the grid shift),
    empty where it does not apply."""
    from scipy import stats
    from scipy.stats import qmc

    if problem.misfit != "least_squares" or opts.interval == "jacobian" or \
            (opts.interval == "auto" and not _model_error(problem, r)):
        return {}
    p = u_opt.size
    cycles = _cycle_count(problem)
    labels = problem.groups(cycles)
    x_opt = problem.values(u_opt)
    half = np.maximum(BOOTSTRAP_SE * spread.se, BOOTSTRAP_SHARE * np.abs(x_opt)) / spread.span
    m = max(int(math.ceil(math.log2(BOOTSTRAP_POINTS * p))), 1)
    unit = qmc.Sobol(d=p, scramble=True, seed=opts.seed).random_base2(m)
    points = [np.clip(u_opt + (2 * q - 1) * half, 0.0, 1.0) for q in unit]
    opts.say(f"bootstrap: {len(points)} points around the optimum by {cycles} cycles, and on half the cells")
    per_cycle = np.array([np.bincount(labels, weights=r * r, minlength=cycles)
                          for r in problem.residuals(points, record=False)])
    coarse = problem.coarser()
    coarse_ssr = np.array([float(r @ r) for r in coarse.residuals(points, record=False)])
    problem.evaluations += coarse.evaluations
    xs = np.array([problem.values(u) for u in points])
    replicates = _block_bootstrap(per_cycle, xs, BOOTSTRAP_REPLICATES, np.random.default_rng(opts.seed))
    # Student's t of the cycles' degrees of freedom, the bootstrap's spread of G groups scaled to
    # the jackknife's (G - 1) divisor
    quantile = float(stats.t.ppf(0.5 + opts.level / 2, cycles - 1)) * math.sqrt(cycles / (cycles - 1))
    spread_x = np.std(replicates, axis=0)
    smooth, smooth_coarse = _quadratic_minima(np.vstack([per_cycle.sum(axis=1), coarse_ssr]), xs)
    low = np.minimum(x_opt, smooth) - quantile * spread_x
    high = np.maximum(x_opt, smooth) + quantile * spread_x
    shift = np.abs(smooth_coarse - smooth)
    out: dict[str, Any] = {"method": "bootstrap", "cycles": cycles, "points": len(points),
                           "replicates": BOOTSTRAP_REPLICATES, "parameters": {}}
    for i, c in enumerate(columns):
        est = estimates[c.name]
        lo = max(min(est.ci_low, low[i] - shift[i]), c.lower)
        hi = min(max(est.ci_high, high[i] + shift[i]), c.upper)
        out["parameters"][c.name] = {
            "jacobian": [est.ci_low, est.ci_high], "bootstrap": [float(low[i]), float(high[i])],
            "smoothed": float(smooth[i]),
            "grid_shift": float(shift[i]), "ci_low": float(lo), "ci_high": float(hi),
            "std_error": float(spread_x[i])}
        if (lo, hi) != (est.ci_low, est.ci_high):
            span = c.upper - c.lower
            spans_box = lo <= c.lower + 1e-12 * span and hi >= c.upper - 1e-12 * span
            estimates[c.name] = ParameterEstimate(c.name, est.value, float(lo), float(hi), c.lower, c.upper,
                                                  est.std_error, "bootstrap", est.identifiable and not spans_box)
    return out


def _model_error(problem: _Problem, r: NDArray[np.float64]) -> bool:
    """Whether the residuals ``r`` (the order of :meth:`_Problem.residual_of`) of any event and
    target show a model error: far above the data's noise or correlated
    (:func:`~drillstring.calibration.checks.model_error`, the checks' own thresholds)."""
    k = 0
    for e, index in enumerate(problem.index):
        for s, w in problem.targets.items():
            data = problem.measured[e][s]
            model = data + r[k:k + index.size] * problem.scale[e][s] / math.sqrt(w)
            k += index.size
            if checks.model_error(checks.series_check(e, s, model, data)):
                return True
    return False


def _cycle_count(problem: _Problem) -> int:
    """The bootstrap's groups: the windows' span over the stick-slip period of the first event's
    first target's data (its cycle features, :mod:`~drillstring.calibration.features`), within
    :data:`BOOTSTRAP_CYCLES`; the range's lower end without a period."""
    times = problem.times[0]
    data = problem.measured[0][next(iter(problem.targets))]
    period = cycle_features(times, data).values.get("period", math.nan)
    lo, hi = BOOTSTRAP_CYCLES
    if not (math.isfinite(period) and period > 0):
        return lo
    span = float(times[-1] - min(a for a, _ in problem.events[0].windows))
    return int(min(max(round(span / period), lo), hi))


def _block_bootstrap(per_group: NDArray[np.float64], xs: NDArray[np.float64], replicates: int,
                     rng: np.random.Generator) -> NDArray[np.float64]:
    """The block bootstrap's estimates: ``per_group[k, g]`` the misfit of group ``g`` at point
    ``xs[k]``; each replicate draws the groups with replacement (multinomial counts) and takes the
    minimum of the quadratic fitted to its misfit summed over its draws (:func:`_quadratic_minima`).
    Returns ``(replicates, p)``."""
    groups = per_group.shape[1]
    counts = rng.multinomial(groups, np.full(groups, 1.0 / groups), size=replicates)
    return _quadratic_minima(counts @ per_group.T, xs)


def _quadratic_minima(misfits: NDArray[np.float64], xs: NDArray[np.float64]) -> NDArray[np.float64]:
    """Per row of ``misfits`` (its values at the points ``xs``, ``(N, p)``), the minimum of the
    quadratic in ``p`` variables fitted to it by least squares, within the points' box; the
    point of least misfit where the quadratic has no minimum. The quadratic averages the steps of
    a staircase misfit (the set-valued friction) where the point of least misfit would jump
    between them."""
    n, p = xs.shape
    centre, scale = xs.mean(axis=0), np.maximum(np.ptp(xs, axis=0) / 2, 1e-300)
    z = (xs - centre) / scale
    pairs = [(i, j) for i in range(p) for j in range(i, p)]
    design = np.column_stack([np.ones(n), z] + [z[:, i] * z[:, j] for i, j in pairs])
    coef = np.linalg.lstsq(design, misfits.T, rcond=None)[0]  # (1 + p + pairs, rows)
    out = np.empty((misfits.shape[0], p))
    for k in range(misfits.shape[0]):
        g = coef[1:1 + p, k]
        H = np.zeros((p, p))
        for (i, j), c in zip(pairs, coef[1 + p:, k]):
            H[i, j] += c if i != j else 2 * c
            H[j, i] = H[i, j]
        eig = np.linalg.eigvalsh(H)
        if eig[0] > 0:
            out[k] = np.clip(np.linalg.solve(H, -g), -1.0, 1.0)
        else:
            out[k] = z[int(np.argmin(misfits[k]))]
    return np.asarray(centre + out * scale)


def _ridge_warnings(spread: _Spread, columns: list[_Column]) -> list[str]:
    """A near-singular Jacobian's warning, naming the parameters of its weakest direction."""
    if not spread.condition > CONDITION_LIMIT:
        return []
    _, _, vt = np.linalg.svd(spread.jacobian)
    weak = [columns[i].name for i in np.argsort(-np.abs(vt[-1])) if abs(vt[-1][i]) > 0.3]
    return [f"near-singular Jacobian (condition number {spread.condition:.3g}): the data fix a combination of "
            f"{', '.join(weak)} better than each (a ridge of equally good fits; see the landscape)"]


def _profiles(problem: _Problem, u_opt: NDArray[np.float64], ssr: float, spread: _Spread, columns: list[_Column],
              estimates: dict[str, ParameterEstimate], opts: _Options) -> dict[str, Profile]:
    """The profile likelihood of each parameter of ``spread.profile`` (the misfit minimised over
    the others at each of ``profile_points`` values), whose interval replaces the Jacobian's in
    ``estimates``."""
    profiles: dict[str, Profile] = {}
    p = u_opt.size
    for i in spread.profile:
        c = columns[i]
        opts.say(f"profile likelihood of {c.name}")
        grid = np.linspace(0.0, 1.0, opts.profile_points)
        points = []
        for g in grid:
            u = u_opt.copy()
            u[i] = g
            points.append(u)
        others = [j for j in range(p) if j != i]
        if not others:
            prof = np.array([float(v @ v) for v in problem.residuals(points)])
        else:
            iterations = max(opts.max_iterations // 2, 5)
            prof = np.array([_refine(problem, u, others, opts.diff_step, iterations)[1] for u in points])
        values = c.lower + grid * (c.upper - c.lower)
        profiles[c.name] = Profile(c.name, values, prof, spread.threshold)
        best = float(problem.values(u_opt)[i])
        lo_ci, hi_ci, flat = _profile_interval(values, prof - ssr, spread.threshold, best)
        estimates[c.name] = ParameterEstimate(c.name, best, lo_ci, hi_ci, c.lower, c.upper,
                                              estimates[c.name].std_error, "profile", not flat)
    return profiles


def _identifiability_warnings(estimates: Mapping[str, ParameterEstimate], level: float) -> list[str]:
    return [f"{est.key} is not identifiable from these data: its {level:.0%} interval "
            f"({est.ci_low:.4g}..{est.ci_high:.4g}) spans its bounds {est.lower:g}..{est.upper:g} "
            "(flat misfit); fix it, narrow its bounds or add data that excite it"
            for est in estimates.values() if not est.identifiable]


def _landscapes(problem: _Problem, u_opt: NDArray[np.float64], columns: list[_Column], opts: _Options
                ) -> list[Landscape]:
    """Stage 4: the misfit over a grid of each pair of parameters, the others at the optimum."""
    p = u_opt.size
    if not opts.landscape or p < 2:
        return []
    grid = np.linspace(0.0, 1.0, opts.landscape_points)
    pairs = [(i, j) for i in range(p) for j in range(i + 1, p)]
    opts.say(f"landscape: {len(pairs)} pair(s) x {grid.size ** 2} points")
    points = []
    for i, j in pairs:
        for gy in grid:
            for gx in grid:
                u = u_opt.copy()
                u[i], u[j] = gx, gy
                points.append(u)
    flat_ssr = np.array([float(v @ v) for v in problem.residuals(points)])
    size = grid.size ** 2
    span = problem.upper - problem.lower
    landscapes = []
    for n_pair, (i, j) in enumerate(pairs):
        block = flat_ssr[n_pair * size:(n_pair + 1) * size].reshape(grid.size, grid.size)
        landscapes.append(Landscape(columns[i].name, columns[j].name,
                                    columns[i].lower + grid * span[i], columns[j].lower + grid * span[j], block))
    return landscapes


def _fitted_runs(problem: _Problem, events: list[Event], u_opt: NDArray[np.float64]
                 ) -> tuple[list[DrillConfig], list[dict[str, NDArray[np.float64]]], list[str],
                            list[dict[str, dict[str, float]]]]:
    """The fitted configuration of each event, its run over the whole span (each target with its
    estimated offset added), the warnings of the runs that failed and the offsets."""
    configs = [events[e].config.with_overrides(dict(problem.pairs(u_opt, e)), units="si")
               for e in range(len(events))]
    whole = problem.run([u_opt], whole=True)[0]
    fitted = [w if isinstance(w, dict) else {} for w in whole]
    failures = [f"the fitted configuration's run failed: {w}" for w in whole if isinstance(w, str)]
    offsets = problem.offsets([{s: w[s][problem.index[e]] for s in problem.targets} if w else "failed"
                               for e, w in enumerate(fitted)])
    for run, found in zip(fitted, offsets):
        for s, o in found.items():
            run[s] = run[s] + o["constant"] + o["rate_per_s"] * (run["t"] - o["t_ref"])
    return configs, fitted, failures, offsets


def _rms(problem: _Problem, series_checks: list[checks.SeriesCheck]) -> list[dict[str, float]]:
    """Per event and target: the RMS error in the series' unit over the windows."""
    rms: list[dict[str, float]] = [{} for _ in problem.events]
    for c in series_checks:
        rms[c.event][c.series] = c.rms
    return rms


def _grid_error(problem: _Problem, u_opt: NDArray[np.float64]) -> list[dict[str, dict[str, float]]]:
    """``misfit="features"``: the model's discretisation error of each feature at the optimum,
    the difference of its features on half the cells (for the first-order scheme, about the
    error of the configuration's grid), added to each feature's standard deviation in
    quadrature (the data come from a well, or another code, not from this grid); the points
    solved before, whose misfits used the smaller deviations, are forgotten."""
    coarse = problem.coarse_features(u_opt)
    fine = problem.run([u_opt])[0]
    errors: list[dict[str, dict[str, float]]] = []
    for e, run in enumerate(fine):
        errors.append({})
        for s in problem.targets:
            names, ref, sd = problem.reference[e][s]
            here = cycle_features(problem.times[e], run[s]).values if isinstance(run, dict) else {}
            there = coarse[e].get(s, {})
            delta = {n: abs(here[n] - there[n]) if n in here and n in there else 0.0 for n in names}
            errors[e][s] = delta
            problem.reference[e][s] = (names, ref, np.sqrt(sd ** 2 + np.array([delta[n] for n in names]) ** 2))
    problem.history.clear()
    return errors


def _checks(problem: _Problem, fitted: list[dict[str, NDArray[np.float64]]],
            grid_error: list[dict[str, dict[str, float]]]) -> tuple[list[checks.SeriesCheck], list[dict[str, Any]]]:
    """The fitted series against the data, per event and target (sample by sample), and with
    ``misfit="features"`` the features' table of ``fit.json`` (with each feature's
    discretisation error, ``grid_error``)."""
    found, rows = [], []
    for e, run in enumerate(fitted):
        for s in problem.targets:
            data = problem.measured[e][s]
            model = np.asarray(run[s])[problem.index[e]] if s in run else np.full(data.size, np.nan)
            found.append(checks.series_check(e, s, model, data))
            if problem.misfit != "features":
                continue
            names, ref, sd = problem.reference[e][s]
            got = cycle_features(problem.times[e], model).values if s in run else {}
            rows += [{"event": e, "series": s, "feature": n, "data": float(v), "std": float(d),
                      "fitted": got.get(n, math.nan), "grid_error": grid_error[e][s].get(n, 0.0)}
                     for n, v, d in zip(names, ref, sd)]
    return found, rows


def _autocorrelation(series_checks: list[checks.SeriesCheck], spread: _Spread) -> float:
    """The residuals' lag-one autocorrelation: the largest of the series' sample-by-sample."""
    values = [c.autocorrelation for c in series_checks if math.isfinite(c.autocorrelation)]
    return max(values) if values else spread.rho


def _result_warnings(estimates: Mapping[str, ParameterEstimate], series_checks: list[checks.SeriesCheck],
                     feature_rows: list[dict[str, Any]], corr: NDArray[np.float64], ssr: float, points: int,
                     opts: _Options) -> list[str]:
    """When the fit is not a result (:mod:`~drillstring.calibration.checks`): values at bounds,
    residuals far above the noise or correlated, implausible units, a ridge."""
    out = checks.bound_warnings(estimates)
    out += checks.residual_warnings(series_checks, opts.misfit)
    if opts.misfit == "features" and feature_rows:
        worst = max(feature_rows, key=lambda row: abs(row["fitted"] - row["data"]) / row["std"]
                    if math.isfinite(row["fitted"]) else math.inf)
        out += checks.chi2_warnings(ssr, points, len(estimates), worst["series"])
    out += checks.ridge_warnings(corr, list(estimates))
    return out


def _profile_interval(values: NDArray[np.float64], excess: NDArray[np.float64], threshold: float,
                      best: float) -> tuple[float, float, bool]:
    """The interval where the profile's excess misfit stays below ``threshold`` around ``best``
    and whether the profile is flat (below the threshold everywhere). On each side, the first
    grid value beyond the threshold ``v`` (excess ``e``) ends it at ``best + (v - best)
    sqrt(threshold / e)`` (a quadratic profile from the optimum), never nearer than the grid
    values inside before it; a side that never crosses ends at the bound."""
    flat = bool(np.all(excess <= threshold))
    ends = []
    for side in (-1.0, 1.0):
        order = np.argsort(side * (values - best))
        end = best
        reached = False
        for k in order:
            d = side * (values[k] - best)
            if d <= 0:
                continue
            if excess[k] > threshold:
                end = side * max(side * end, side * (best + (values[k] - best) * math.sqrt(threshold / excess[k])))
                reached = True
                break
            end = float(values[k])
        if not reached:
            end = float(values[-1] if side > 0 else values[0])
        ends.append(float(end))
    return ends[0], ends[1], flat
