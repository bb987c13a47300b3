"""Cycle features of a series: what a fit with ``misfit="features"`` compares.

A stick-slip record of many cycles cannot be compared sample by sample: a model whose period
differs by a fraction of a percent from the well's drifts out of phase after a few cycles, and
the sample-by-sample misfit then has many valleys and residuals correlated over whole cycles.
The features below do not depend on the phase of the cycles, on a constant lag of the sensor or
on small differences of the period; each comes with its uncertainty, so that the misfit is a
chi-square of nearly independent terms.

The series (measured and model alike, at the same sample times) is smoothed by a centred moving
average over :data:`SMOOTH_TIME` (at least three samples); its cycles are the peaks of the
smoothed series whose prominence is at least :data:`PROMINENCE` of its range and at least
:data:`MIN_SEPARATION` apart. The features:

=================  ==============================================================
``first_peak``     the first peak's height: the break-off of a start-up
``peak_mean``      the mean height of the later peaks (each cycle's maximum)
``trough_mean``    the mean of the minima between successive peaks (the first: the
                   first slip's)
``period``         the mean time between successive peaks
``cycle_mean``     the mean of the series from the first to the last peak
``level``          the mean of the series (a record without cycles: its only feature
                   besides its maximum, ``first_peak``)
=================  ==============================================================

Uncertainty of each measured feature (standard deviation): the sensor noise (``noise_level``:
from the differences of successive samples taken twice, by the median absolute deviation, so
that the signal's own slope does not count) through the smoothing and the number of cycles
averaged, the scatter of the cycles (a mean over few cycles of a record whose cycles differ is
uncertain by their spread), the sampling interval for times, and the model error: a share
:data:`MODEL_ERROR` of the feature (the spread of these features measured between the numpy port
of Aarsnes & Shor's scheme on 700 and 1500 cells and this solver on 700 to 2000 cells at the same
friction; the coverage this gives is measured by ``benchmarks/fit_coverage.py``, see the
calibration guide).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

__all__ = ["FEATURES", "MODEL_ERROR", "SMOOTH_TIME", "Features", "features", "noise_level", "smoothed", "uncertainties"]

#: The moving average's length, s.
SMOOTH_TIME = 0.25
#: A cycle's peak rises above its neighbouring minima by at least this share of the series' range.
PROMINENCE = 0.3
#: Peaks at least this far apart, s.
MIN_SEPARATION = 1.0
#: The model error of each feature, as a share of the feature (times: of the period).
MODEL_ERROR: Mapping[str, float] = {"first_peak": 0.015, "peak_mean": 0.03, "trough_mean": 0.05,
                                    "period": 0.01, "cycle_mean": 0.02, "level": 0.02}
#: The features in the order of the residual vector.
FEATURES: tuple[str, ...] = ("first_peak", "peak_mean", "trough_mean", "period", "cycle_mean", "level")


def noise_level(values: NDArray[np.float64]) -> float:
    """The standard deviation of the series' noise from the differences of successive samples,
    taken twice (independent noise of standard deviation ``s`` gives second differences of
    ``s sqrt 6``; a signal's slope gives none and its curvature between samples little), by the
    median absolute deviation scaled to a normal distribution's (a stick-slip cycle's corners,
    a few samples each, do not count)."""
    d = np.diff(np.asarray(values, dtype=np.float64), n=2)
    if d.size < 2:
        return 0.0
    mad = float(np.median(np.abs(d - np.median(d))))
    return mad / 0.6744897501960817 / math.sqrt(6.0)


def smoothed(values: NDArray[np.float64], width: int) -> NDArray[np.float64]:
    """The centred moving average over ``width`` samples (shorter at the ends)."""
    if width <= 1 or values.size < 2:
        return values.astype(np.float64)
    kernel = np.ones(width)
    total = np.convolve(values, kernel, mode="same")
    count = np.convolve(np.ones(values.size), kernel, mode="same")
    return np.asarray(total / count, dtype=np.float64)


@dataclass(frozen=True)
class Features:
    """The features of one series: name -> value, and the cycles they come from."""

    values: dict[str, float]
    peaks: int
    width: int
    #: The standard error of a mean over cycles from their spread (name -> value).
    scatter: Mapping[str, float] = field(default_factory=dict)


def features(t: NDArray[np.float64], values: NDArray[np.float64]) -> Features:
    """The features of ``values`` sampled at ``t`` (see the module docstring); a feature the
    series does not have (``period`` with fewer than two peaks) is absent."""
    from scipy.signal import find_peaks

    t = np.asarray(t, dtype=np.float64)
    x = np.asarray(values, dtype=np.float64)
    dt = float(np.median(np.diff(t))) if t.size > 1 else 1.0
    width = max(int(round(SMOOTH_TIME / dt)), 3)
    s = smoothed(x, width)
    out: dict[str, float] = {"level": float(np.mean(s)), "first_peak": float(np.max(s))}
    span = float(np.max(s) - np.min(s))
    if span <= 0:
        return Features(out, 0, width)
    peaks, _ = find_peaks(s, prominence=PROMINENCE * span, distance=max(int(round(MIN_SEPARATION / dt)), 1))
    if peaks.size == 0:
        return Features(out, 0, width)
    out["first_peak"] = float(s[peaks[0]])
    if peaks.size >= 2:
        troughs = np.array([np.min(s[a:b]) for a, b in zip(peaks[:-1], peaks[1:])])
        periods = np.diff(t[peaks])
        out["peak_mean"] = float(np.mean(s[peaks[1:]]))
        out["trough_mean"] = float(np.mean(troughs))
        out["period"] = float(np.mean(periods))
        out["cycle_mean"] = float(np.mean(s[peaks[0]:peaks[-1]]))
        spread = {"peak_mean": s[peaks[1:]], "trough_mean": troughs, "period": periods}
        scatter = {k: float(np.std(v, ddof=1) / math.sqrt(v.size)) if v.size > 1 else 0.0 for k, v in spread.items()}
        return Features(out, int(peaks.size), width, scatter)
    return Features(out, int(peaks.size), width)


def uncertainties(t: NDArray[np.float64], values: NDArray[np.float64], found: Features) -> dict[str, float]:
    """The standard deviation of each feature of ``found`` (measured ``values`` at ``t``): noise
    through the smoothing and the cycles averaged, the sampling interval for the period, and the
    model error :data:`MODEL_ERROR`."""
    dt = float(np.median(np.diff(t))) if t.size > 1 else 1.0
    noise = noise_level(values)
    smooth = noise / math.sqrt(found.width)
    later = max(found.peaks - 1, 1)
    scale = max(float(np.max(values) - np.min(values)), abs(found.values["level"]), 1e-300)
    out = {}
    for name, value in found.values.items():
        if name == "period":
            # each peak's time to about the sampling interval (and the smoothing's flat top)
            timing = math.hypot(dt, smooth / max(scale, 1e-300) * found.width * dt)
            statistical = math.sqrt(2.0) * timing / later
        elif name in ("peak_mean", "trough_mean"):
            statistical = smooth / math.sqrt(later)
        elif name in ("cycle_mean", "level"):
            statistical = noise / math.sqrt(max(values.size, 1))
        else:
            statistical = smooth
        model = MODEL_ERROR[name] * abs(value) if name != "period" else MODEL_ERROR[name] * value
        # a feature near 0 (a torque crossing zero) keeps an error of the series' scale
        floor = MODEL_ERROR[name] * 0.1 * scale if name != "period" else dt
        out[name] = math.sqrt(statistical ** 2 + found.scatter.get(name, 0.0) ** 2 + max(model, floor) ** 2)
    return out
