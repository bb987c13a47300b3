"""Signal metrics of simulated responses: spectral peaks, accumulated phase, boundedness.

Used by the paper report (:mod:`drillstring.report`) and by parameter sweeps. Every function
takes a uniformly sampled record ``x(t)`` (numpy arrays; no scipy needed) and calls the core.

* :func:`spectral_peaks` / :func:`dominant_frequencies`: Hann-windowed real FFT (zero-padded),
  local maxima of the magnitude, each refined by a parabola through the logarithms of the three
  bins around it (Gaussian interpolation, exact for a Gaussian peak and accurate to well below
  1e-3 bin for the Hann main lobe once zero-padded). Computed by the core
  (``drillstring_core::metrics``), the same function that gives a sweep's
  ``dominant_frequency_hz``.
* :func:`phase_shift`: accumulated phase of one oscillation relative to another, from their
  zero-crossing times (see the function for why zero crossings rather than the analytic signal).
  This and every function below are computed by the core (``drillstring_core::metrics::signal``
  and ``::stickslip``); this module checks the records and converts them.
* :func:`amplitude_growth` / :func:`is_bounded`: finite, and the largest ``|x|`` over the last
  half of the record is not much larger than over the first half.
* :func:`modulation_depth`: how much the half-cycle peaks ``|x|`` vary; :func:`hull_area`: the
  area of the convex hull of a phase-plane trajectory (how wide a region it occupies);
  :func:`phase_fill`: the fraction of that region the trajectory actually passes through (a
  closed curve fills little of it, a precessing multi-mode orbit much more).
* :func:`stick_slip_metrics` (:class:`StickSlipMetrics`), :func:`break_off_torque`: stick-slip
  metrics of any bit-speed and motor-torque series (uniformly or non-uniformly sampled) and the
  static break-off torque of a well, computed by the core
  (``drillstring_core::metrics::stickslip``).
* :func:`duffing_amplitude`, :func:`duffing_frequency`: exact reference values of the one-mode
  model ``x'' + w2 x + beta x^3 = 0`` (complete elliptic integral by the arithmetic-geometric
  mean, no scipy).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..limits import as_float

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import ArrayLike, NDArray

__all__ = [
    "SpectralPeak",
    "spectral_peaks",
    "dominant_frequencies",
    "crossing_phase",
    "phase_shift",
    "amplitude_growth",
    "is_bounded",
    "BOUNDED_GROWTH",
    "modulation_depth",
    "hull_area",
    "phase_fill",
    "PHASE_FILL_BINS",
    "ellipk",
    "duffing_amplitude",
    "duffing_frequency",
]

#: Default zero-padding factor of the FFT (the bin spacing is ``1 / (pad * duration)``).
DEFAULT_PAD: int = _core.SPECTRAL_PAD

#: Default relative threshold of :func:`spectral_peaks`.
DEFAULT_THRESHOLD: float = _core.PEAK_THRESHOLD


class SpectralPeak(NamedTuple):
    """One peak of the windowed spectrum."""

    frequency: float
    """Interpolated peak frequency, Hz."""
    amplitude: float
    """Amplitude of the sine it corresponds to (window-gain corrected), in the units of ``x``."""


def _record(t: ArrayLike, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    ta = np.asarray(t, dtype=float)
    xa = np.asarray(x, dtype=float)
    if ta.ndim != 1 or xa.shape != ta.shape or ta.size < 4:
        raise ValidationError(
            "x", f"arrays of shapes {ta.shape} and {xa.shape}", "1-D t and x of equal length >= 4"
        )
    steps = np.diff(ta)
    dt = float(steps.mean())
    # 1e-3 of a step: times read back from a file (10 significant digits, 186 616 samples over
    # 100 s jitter by 2e-6 of a step) pass; the jitter shifts a phase by 2 pi f dt 1e-3 at most
    if not dt > 0 or np.max(np.abs(steps - dt)) > 1e-3 * dt:
        raise ValidationError("t", "non-uniform sample times", "uniformly increasing times")
    if not np.all(np.isfinite(xa)):
        raise ValidationError("x", "non-finite samples", "finite samples")
    return ta, xa, dt


def _peaks(
    t: ArrayLike, x: ArrayLike, count: int, pad: int, threshold: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    _, xa, dt = _record(t, x)
    return _core.spectral_peaks(xa, dt, count, pad, threshold)


def spectral_peaks(
    t: ArrayLike,
    x: ArrayLike,
    count: int = 3,
    *,
    pad: int = DEFAULT_PAD,
    threshold: float = DEFAULT_THRESHOLD,
) -> list[SpectralPeak]:
    """The ``count`` strongest peaks of the Hann-windowed spectrum of ``x(t)``, strongest first.

    Parameters
    ----------
    t, x : array_like
        Uniform sample times (s) and the signal; its (window-weighted) mean is removed first.
    count : int
        How many peaks to return at most.
    pad : int
        Zero-padding factor (>= 1).
    threshold : float
        Peaks weaker than ``threshold`` times the strongest are ignored. Side lobes of the
        Hann window (0.027 of their peak and below) are recognised from their distance to the
        stronger peaks and skipped.

    Returns
    -------
    list of SpectralPeak
        ``(frequency in Hz, sine amplitude)``; fewer than ``count`` if the spectrum has fewer
        peaks; empty for a constant signal. Peaks closer than two unpadded bins
        (``2 / duration``) to a stronger one are not resolved from it and are dropped.
    """
    frequencies, amplitudes = _peaks(t, x, count, pad, threshold)
    return [SpectralPeak(f, a) for f, a in zip(frequencies.tolist(), amplitudes.tolist())]


def dominant_frequencies(
    t: ArrayLike, x: ArrayLike, count: int = 3, *, pad: int = DEFAULT_PAD, threshold: float = DEFAULT_THRESHOLD
) -> NDArray[np.float64]:
    """Frequencies (Hz) of the ``count`` strongest spectral peaks of ``x(t)``, strongest first.

    See :func:`spectral_peaks` (Hann window, zero padding ``pad``, log-parabolic interpolation).
    The error for a pure sine of ``N`` cycles is far below 0.1 % once ``N >= 10``; two components
    are resolved when they are more than ``2 / duration`` Hz apart.

    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 4001)
    >>> round(float(dominant_frequencies(t, np.sin(2 * np.pi * 31.3 * t), 1)[0]), 3)
    31.3
    """
    return _peaks(t, x, count, pad, threshold)[0]


def _flat(x: ArrayLike) -> NDArray[np.float64]:
    """``x`` as a contiguous 1-D float array (a 2-D record is flattened, as numpy's ``ravel``)."""
    return np.ascontiguousarray(np.asarray(x, dtype=float).ravel())


def crossing_phase(t: ArrayLike, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Zero-crossing times of ``x(t)`` and the phase (rad) the oscillation has there.

    The phase is ``k pi`` at the ``k``-th crossing (linear interpolation between the samples
    around it) plus the phase at ``t[0]``, extrapolated from the first half period:
    ``pi (1 - (t_1 - t[0]) / (t_2 - t_1))``. A record starting at ``x = 0`` (rest position)
    therefore starts at phase 0, one starting at an extreme at ``pi/2``.

    Returns ``(times, phases)``, each of length (number of crossings + 1), the first entry
    being ``t[0]``. Fewer than two crossings raise :class:`~drillstring.errors.ValidationError`.
    Computed by the core (``drillstring_core::metrics::signal``).
    """
    ta, xa, _ = _record(t, x)
    return _core.crossing_phase(ta, xa)


def phase_shift(
    t: ArrayLike,
    x_ref: ArrayLike,
    x: ArrayLike,
    at: Optional[Union[float, ArrayLike]] = None,
) -> Union[float, NDArray[np.float64]]:
    """Accumulated phase (rad) of ``x`` minus that of ``x_ref`` at time(s) ``at``.

    Positive when ``x`` runs ahead (higher frequency). ``at`` defaults to ``t[-1]``; a scalar
    gives a float, an array an array. Both records share the times ``t``.

    Method: the phase of each signal is ``k pi`` at its ``k``-th zero crossing (crossing
    times interpolated linearly between samples, see :func:`crossing_phase`) and linear in time
    between crossings (extrapolated with the last half period beyond the last crossing). For the
    symmetric oscillations of this model (``theta -> -theta`` symmetry) the crossings are
    exactly half a period apart, so the phase is exact at every crossing and the accumulated
    difference needs no unwrapping. The analytic signal (Hilbert transform) was not used: its
    phase is biased near the record ends by the FFT's periodic extension, exactly where the
    accumulated shift is read. Computed by the core.

    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 40001)
    >>> shift = phase_shift(t, np.sin(2 * np.pi * 31.0 * t), np.sin(2 * np.pi * 31.5 * t))
    >>> round(float(np.degrees(shift)))
    1800
    """
    ta, ref, _ = _record(t, x_ref)
    _, xa, _ = _record(t, x)
    when = np.atleast_1d(np.asarray(ta[-1] if at is None else at, dtype=float))
    shift = _core.phase_shift(ta, ref, xa, _flat(when)).reshape(when.shape)
    return float(shift[0]) if np.ndim(ta[-1] if at is None else at) == 0 else shift


def amplitude_growth(x: ArrayLike) -> float:
    """``max |x|`` over the last half of the record divided by ``max |x|`` over the first half.

    ``inf`` if the record has non-finite samples (a blown-up solution); ``nan`` if both halves
    are identically zero, ``inf`` if only the first is. Computed by the core.
    """
    return _core.amplitude_growth(_flat(x))


#: Default largest :func:`amplitude_growth` that :func:`is_bounded` accepts.
BOUNDED_GROWTH: float = _core.BOUNDED_GROWTH


def is_bounded(x: ArrayLike, factor: float = BOUNDED_GROWTH, *, limit: Optional[float] = None) -> bool:
    """Whether the record looks bounded: finite, :func:`amplitude_growth` ``<= factor``, and
    ``max |x| <= limit`` when a limit is given.

    A conservative oscillation has growth close to 1 (1 exactly for a pure sine over whole
    periods); a linearly unstable mode grows exponentially and exceeds any fixed factor once
    the record is a few e-folding times long. Computed by the core.
    """
    return _core.is_bounded(_flat(x), float(factor), None if limit is None else float(limit))


def modulation_depth(x: ArrayLike) -> float:
    """Depth ``1 - min/max`` of the envelope of the half-cycle peaks: 0 for a constant envelope.

    A half-cycle peak is the extreme of ``x`` between two successive zero crossings (the partial
    half cycles at both ends of the record are left out). Positive and negative half cycles are
    taken separately, so that a steady but asymmetric waveform is not counted as modulated; the
    larger of the two depths is returned. ``nan`` with fewer than two complete half cycles of
    each sign. Computed by the core.
    """
    return _core.modulation_depth(_flat(x))


def hull_area(x: ArrayLike, y: ArrayLike) -> float:
    """Area of the convex hull of the points ``(x_k, y_k)`` (monotone chain), in units x*y.
    Computed by the core."""
    return _core.hull_area(_flat(x), _flat(y))


#: Default cells per axis of the grid of :func:`phase_fill`.
PHASE_FILL_BINS: int = _core.PHASE_FILL_BINS


def phase_fill(x: ArrayLike, y: ArrayLike, bins: int = PHASE_FILL_BINS) -> float:
    """Fraction of the cells of a ``bins x bins`` grid over the trajectory's convex hull that
    the trajectory passes through (samples joined by straight segments).

    Scale-free (each axis normalised to the bounding box). About ``2.5/bins`` for one closed
    curve such as an ellipse, approaching 1 for an orbit that sweeps its whole region.
    Computed by the core.
    """
    return _core.phase_fill(_flat(x), _flat(y), bins)


def ellipk(m: float) -> float:
    """Complete elliptic integral of the first kind ``K(m) = int_0^{pi/2} (1 - m sin^2)^(-1/2)``
    (parameter ``m = k^2 < 1``), by the arithmetic-geometric mean: ``pi / (2 agm(1, sqrt(1-m)))``.
    Computed by the core.
    """
    return _core.ellipk(as_float("m", m, "m < 1"))


def duffing_amplitude(omega2: float, beta: float, velocity: float) -> float:
    """Turning point ``A`` of ``x'' + omega2 x + beta x^3 = 0`` started at ``x = 0``, ``x' = v``.

    From the energy ``v^2/2 = omega2 A^2/2 + beta A^4/4``. Computed by the core.
    """
    return _core.duffing_amplitude(float(omega2), float(beta), float(velocity))


def duffing_frequency(omega2: float, beta: float, amplitude: float) -> float:
    """Exact frequency (Hz) of ``x'' + omega2 x + beta x^3 = 0`` oscillating with amplitude ``A``.

    ``T = 4 K(m) / sqrt(omega2 + beta A^2)`` with ``m = beta A^2 / (2 (omega2 + beta A^2))``.
    Computed by the core.
    """
    return _core.duffing_frequency(float(omega2), float(beta), float(amplitude))


