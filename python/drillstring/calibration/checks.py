"""When a fit is not a result: the checks of a fitted point, each a warning naming the parameter
or the column (``FitResult.warnings``: the console, ``fit.json``'s ``warnings``, ``report.md``).

* a value at or near a bound of its search (within :data:`BOUND_SHARE` of the box): the best fit
  may lie beyond it;
* a residual far above the data's noise: the RMS of the fitted series' residual more than
  :data:`NOISE_RATIO` times the noise level estimated from the data alone (the differences of
  successive samples, :func:`~drillstring.calibration.features.noise_level`), above a floor of
  :data:`NOISE_FLOOR` of the series' spread (noise-free data); with ``misfit="features"`` the
  features' chi-square per degree of freedom above :data:`CHI2_RATIO`;
* residuals correlated from sample to sample (lag-one autocorrelation above
  :data:`AUTOCORRELATION_LIMIT`) in a sample-by-sample fit: the model misses structure of the
  data (a drift, a period, a phase), and the intervals rest on fewer independent samples than
  the count;
* data whose size is implausible for the quantity: the mean magnitude of a series more than
  :data:`UNIT_RATIO` times smaller or larger than the fitted model's (torque in kN m read as
  N m gives a factor of a thousand);
* two parameters whose estimates are correlated beyond :data:`RIDGE_CORRELATION`: a ridge, the
  data fix a combination of them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .features import noise_level

__all__ = ["AUTOCORRELATION_LIMIT", "BOUND_SHARE", "CHI2_RATIO", "NOISE_FLOOR", "NOISE_RATIO", "RIDGE_CORRELATION",
           "SERIES_UNITS", "UNIT_RATIO", "SeriesCheck", "far_above_noise", "model_error", "series_check"]

#: A value within this share of its box from a bound is "at its bound".
BOUND_SHARE = 0.01
#: The residual's RMS above this multiple of the data's noise level is a model that misses the data.
NOISE_RATIO = 3.0
#: ... unless below this share of the series' standard deviation (noise-free data).
NOISE_FLOOR = 0.02
#: With ``misfit="features"``: the chi-square per degree of freedom above this is a model that misses.
CHI2_RATIO = 4.0
#: Lag-one autocorrelation of the residual above this: the model misses structure.
AUTOCORRELATION_LIMIT = 0.5
#: Data this many times smaller or larger than the model's: a unit mistake.
UNIT_RATIO = 20.0
#: Estimates correlated beyond this: a ridge.
RIDGE_CORRELATION = 0.95

#: The SI unit of each fitted series, as messages name it.
SERIES_UNITS = {"motor_torque": "N m", "bit_torque": "N m", "surface_rpm": "rpm", "bit_rpm": "rpm", "hook_load": "N",
          "weight_on_bit": "N"}
_LARGER_UNITS = {"N m": "kN m", "N": "kN", "rpm": "rad/s"}


@dataclass(frozen=True)
class SeriesCheck:
    """One event's fitted series against its data, sample by sample over the windows."""

    event: int
    series: str
    rms: float
    """RMS of the residual (model - data), in the series' SI unit."""
    noise: float
    """The data's noise level from successive differences."""
    autocorrelation: float
    """Lag-one autocorrelation of the residual."""
    data_scale: float
    """Mean magnitude of the data."""
    model_scale: float
    """Mean magnitude of the fitted model's series."""
    spread: float
    """Standard deviation of the data."""

    def to_dict(self) -> dict[str, Any]:
        return {"event": self.event, "series": self.series, "rms": self.rms, "noise": self.noise,
                "autocorrelation": self.autocorrelation, "data_scale": self.data_scale,
                "model_scale": self.model_scale}


def _lag_one(r: NDArray[np.float64]) -> float:
    if r.size < 4 or not np.std(r) > 0:
        return 0.0
    rho = float(np.corrcoef(r[:-1], r[1:])[0, 1])
    return rho if math.isfinite(rho) else 0.0


def series_check(event: int, series: str, model: NDArray[np.float64], data: NDArray[np.float64]) -> SeriesCheck:
    """The check of one fitted series ``model`` against ``data`` at the same times."""
    r = np.asarray(model, dtype=np.float64) - np.asarray(data, dtype=np.float64)
    return SeriesCheck(event, series, float(np.sqrt(np.mean(r ** 2))), noise_level(data), _lag_one(r),
                       float(np.mean(np.abs(data))), float(np.mean(np.abs(model))), float(np.std(data)))


def far_above_noise(c: SeriesCheck) -> bool:
    """The residual's RMS more than :data:`NOISE_RATIO` times the data's noise level (at least
    :data:`NOISE_FLOOR` of the data's spread)."""
    return c.rms > NOISE_RATIO * max(c.noise, NOISE_FLOOR * c.spread)


def model_error(c: SeriesCheck) -> bool:
    """A sample-by-sample residual that is not the data's noise: far above it
    (:func:`far_above_noise`) or correlated beyond :data:`AUTOCORRELATION_LIMIT`."""
    return far_above_noise(c) or c.autocorrelation > AUTOCORRELATION_LIMIT


def bound_warnings(estimates: Mapping[str, Any]) -> list[str]:
    """A value within :data:`BOUND_SHARE` of its box from a bound."""
    out = []
    for est in estimates.values():
        share = BOUND_SHARE * (est.upper - est.lower)
        for bound, side in ((est.lower, "lower"), (est.upper, "upper")):
            if abs(est.value - bound) <= share:
                out.append(f"{est.key} = {est.value:.5g} is at its {side} bound {bound:g}: the best fit may lie "
                           f"beyond it (or the data do not fit the model); widen the bounds of {est.key} or check "
                           "the data, and do not use this value")
    return out


def residual_warnings(checks: Sequence[SeriesCheck], misfit: str) -> list[str]:
    """The residual far above the noise, correlated residuals and implausible units, per series."""
    out = []
    for c in checks:
        unit = SERIES_UNITS.get(c.series, "")
        name = f"{c.series} (event {c.event})" if any(k.event for k in checks) else c.series
        if c.model_scale > 0 and c.data_scale > 0:
            ratio = c.data_scale / c.model_scale
            if not 1 / UNIT_RATIO <= ratio <= UNIT_RATIO:
                hint = (f"; values in {_LARGER_UNITS[unit]} read as {unit}? give the column's unit (--unit "
                        f"'{c.series}={_LARGER_UNITS[unit]}', a header suffix or a units row)"
                        if ratio < 1 / UNIT_RATIO and unit in _LARGER_UNITS else "; check the column's unit")
                out.append(f"column {name}: the data's mean magnitude {c.data_scale:.4g} {unit} is {ratio:.3g} times "
                           f"the fitted model's {c.model_scale:.4g} {unit}, implausible for the quantity{hint}")
                continue
        if misfit == "least_squares" and far_above_noise(c):
            out.append(f"column {name}: the residual's RMS {c.rms:.4g} {unit} is {c.rms / max(c.noise, 1e-300):.3g} "
                       f"times the data's noise level {c.noise:.4g} {unit} (from successive differences): the model "
                       "misses what the data hold; the values and intervals are not a calibration")
        if misfit == "least_squares" and c.autocorrelation > AUTOCORRELATION_LIMIT:
            out.append(f"column {name}: the residuals are correlated from sample to sample (lag-one autocorrelation "
                       f"{c.autocorrelation:.3g}): the model misses structure of the data (a drift, a period or a "
                       "phase); misfit='features' compares what does not depend on the phase")
    return out


def chi2_warnings(ssr: float, points: int, parameters: int, worst: str) -> list[str]:
    """With ``misfit="features"``: the features' chi-square per degree of freedom above :data:`CHI2_RATIO`."""
    dof = max(points - parameters, 1)
    if ssr / dof <= CHI2_RATIO:
        return []
    return [f"column {worst}: its features miss the data's by {math.sqrt(ssr / dof):.3g} standard deviations on "
            f"average (chi-square {ssr:.4g} over {dof} degrees of freedom): the model misses what the data hold; "
            "the intervals are widened by that factor"]


def correlation(cov: NDArray[np.floating[Any]]) -> NDArray[np.float64]:
    """The correlation matrix of a covariance (0 where a variance is 0)."""
    d = np.sqrt(np.maximum(np.diag(cov), 0.0))
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.asarray(cov, dtype=np.float64) / np.outer(d, d)
    return np.nan_to_num(c, nan=0.0)


def ridge_warnings(corr: NDArray[np.float64], names: Sequence[str]) -> list[str]:
    """Pairs of parameters correlated beyond :data:`RIDGE_CORRELATION`."""
    out = []
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            if abs(corr[i, j]) > RIDGE_CORRELATION:
                out.append(f"{names[i]} and {names[j]} are correlated ({corr[i, j]:+.3f}): a ridge, the data fix a "
                           "combination of the two better than each (see the landscape)")
    return out
