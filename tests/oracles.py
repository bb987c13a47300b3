"""Numpy implementations of numbers the core computes, kept only as test oracles.

The package calls the core (``drillstring._core``) for each of these; the tests check that the
core gives the same numbers to rounding.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

#: Hann main-lobe half width in unpadded bins (the core's ``HANN_HALF_WIDTH``).
HANN_HALF_WIDTH = 2


def _hann_leakage(distance: float) -> float:
    """Envelope of the Hann window's side lobes relative to its peak, ``distance`` in bins."""
    with np.errstate(divide="ignore"):
        return float(np.float64(1.0) / (math.pi * distance * abs(distance * distance - 1.0)))


def spectral_peaks(x: NDArray[np.float64], dt: float, count: int, pad: int = 8,
                   threshold: float = 1e-3) -> list[tuple[float, float]]:
    """``(frequency Hz, sine amplitude)`` of the ``count`` strongest peaks of the Hann-windowed,
    zero-padded spectrum, strongest first (side lobes and unresolved peaks dropped)."""
    xa = np.asarray(x, dtype=float)
    n = xa.size
    window = np.hanning(n)
    signal = (xa - np.dot(window, xa) / window.sum()) * window
    nfft = 1 << int(math.ceil(math.log2(n * pad)))
    magnitude = np.abs(np.fft.rfft(signal, nfft))
    top = float(magnitude.max()) if magnitude.size else 0.0
    if top <= 0.0:
        return []
    inner = magnitude[1:-1]
    is_peak = (inner > magnitude[:-2]) & (inner >= magnitude[2:]) & (inner >= threshold * top)
    candidates = np.nonzero(is_peak)[0] + 1
    candidates = candidates[np.argsort(magnitude[candidates])[::-1]]
    bin_hz = 1.0 / (nfft * dt)
    gain = window.sum() / 2.0
    chosen: list[int] = []
    peaks: list[tuple[float, float]] = []
    for k in candidates.tolist():
        distances = [abs(k - j) / (nfft / n) for j in chosen]
        if any(d < HANN_HALF_WIDTH for d in distances):
            continue
        leakage = sum(
            magnitude[j] * (_hann_leakage(d) + _hann_leakage((k + j) / (nfft / n)))
            for j, d in zip(chosen, distances)
        )
        if magnitude[k] <= 2.0 * leakage:
            continue
        chosen.append(k)
        a, b, c = (math.log(max(v, 1e-300)) for v in magnitude[k - 1 : k + 2])
        denom = a - 2.0 * b + c
        delta = 0.5 * (a - c) / denom if denom < 0 else 0.0
        log_peak = b - 0.25 * (a - c) * delta
        peaks.append(((k + delta) * bin_hz, math.exp(log_peak) / gain))
        if len(peaks) == count:
            break
    return peaks


def energy_drift(energy: NDArray[np.float64], dissipated: NDArray[np.float64] | None = None) -> float:
    """``max |H + D - H(0)| / |H(0)|`` (0 when ``H(0) = 0`` or without samples)."""
    h = np.asarray(energy, dtype=float)
    if dissipated is not None:
        h = h + dissipated
    if h.size == 0 or h[0] == 0:
        return 0.0
    return float(np.max(np.abs(h - h[0])) / abs(h[0]))


def modal_energies(mass: NDArray[np.float64], stiffness: NDArray[np.float64], q: NDArray[np.float64],
                   qdot: NDArray[np.float64]) -> NDArray[np.float64]:
    """``E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`` of each mode (rows) at each sample (columns)."""
    return 0.5 * (mass[:, None] * qdot**2 + stiffness[:, None] * q**2)


def max_modal_shares(mass: NDArray[np.float64], stiffness: NDArray[np.float64], q: NDArray[np.float64],
                     qdot: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest ``E_i / sum_j E_j`` of each mode over the samples with a positive total."""
    e = modal_energies(mass, stiffness, q, qdot)
    total = e.sum(axis=0)
    keep = total > 0
    if not keep.any():
        return np.full(mass.size, math.nan)
    return np.max(e[:, keep] / total[keep], axis=1)
