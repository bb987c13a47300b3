"""Linear stability of a coupled run's regenerative bit: Aarsnes & van de Wouw's (2019) loop gains.

Their criterion (``Coupled - nondim/MAIN_Torsional_FreqStabMap.m``: the open loop ``G(j w)`` of the
string's bit response times the regenerative bit law, unstable when the largest gain ``|G|`` where
``G`` crosses the negative real axis exceeds 1, their ``M_T = max |G_t(j w_180)|``) on the
dimensional loops of their ``Coupled/freqPlots.m`` (lines 17-36), for a uniform string whose top
turns and moves at imposed speeds (their boundary) and with the distributed velocity damping at the
rate the configuration applies (``damping_rate``)::

    g_t(s) = -tanh(L s / c_t sqrt(1 + k / s)) / sqrt(1 + k / s)
    G_t(s) = g_t(s) K_t / s (1 - exp(-s t_N)),    K_t = (V0 / Omega0) a^2 eps n / (2 J sqrt(G rho))
    G_a(s) = -g_a(s) K_a / s (1 - exp(-s t_N)),   K_a = a zeta eps n / (A sqrt(E rho))

with ``t_N = 2 pi / (n Omega0)`` the blade-pass delay, ``V0`` the hoist's speed and ``Omega0`` the top
drive's. ``tests/test_avdw_stability.py`` checks it against their loops run in GNU Octave
(``tests/reference/aarsnes-van-de-wouw-2019``) and compares the torsional onset with the simulations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from drillstring import _core
from drillstring.drilling.config import DrillConfig

__all__ = ["LoopGains", "negative_real_axis_gains", "regenerative_loop_gains", "torsional_gain_nondim"]

#: Their frequency grid (``freqPlots.m``: ``linspace(3e-3, 10 * 2 pi, nw)``), rad/s, at 10 times their
#: ``nw = 2e3`` points (as the stored Octave run).
FREQUENCIES = np.linspace(3e-3, 10 * 2 * math.pi, 20_000)


def negative_real_axis_gains(g: NDArray[np.complex128], w: NDArray[np.float64]) -> tuple[NDArray[np.float64],
                                                                                          NDArray[np.float64]]:
    """``|G(j w)|`` and ``w`` at every crossing of the negative real axis on the grid ``w`` (sign
    changes of ``Im G``, linear interpolation between grid points, ``Re G < 0``), largest gain first:
    the criterion of their ``nyqStab`` (the loop is unstable when the first exceeds 1)."""
    g, w = np.asarray(g).ravel(), np.asarray(w, dtype=np.float64).ravel()
    im = g.imag
    i = np.nonzero((im[:-1] * im[1:] <= 0) & (im[:-1] != im[1:]))[0]
    frac = im[i] / (im[i] - im[i + 1])
    gc = g[i] + frac * (g[i + 1] - g[i])
    wc = w[i] + frac * (w[i + 1] - w[i])
    keep = gc.real < 0
    gains, freqs = np.abs(gc[keep]), wc[keep]
    order = np.argsort(-gains, kind="stable")
    return gains[order], freqs[order]


@dataclass(frozen=True)
class LoopGains:
    """The largest negative-real-axis gains of the regenerative loops and their frequencies (rad/s;
    NaN without a crossing, the gain then 0): torsional ``G_t``, axial ``G_a``, both ``G_a + G_t``."""

    torsional: float
    torsional_frequency: float
    axial: float
    axial_frequency: float
    combined: float
    combined_frequency: float

    @property
    def torsionally_unstable(self) -> bool:
        """``M_T > 1``: their linear torsional instability."""
        return self.torsional > 1.0


def _largest(g: NDArray[np.complex128], w: NDArray[np.float64]) -> tuple[float, float]:
    gains, freqs = negative_real_axis_gains(g, w)
    return (float(gains[0]), float(freqs[0])) if len(gains) else (0.0, math.nan)


def regenerative_loop_gains(cfg: DrillConfig, w: NDArray[np.float64] | None = None) -> LoopGains:
    """The loop gains of a coupled run ``cfg`` (one string section, ``bit.law`` ``"rgd"``, a hoist in
    ``velocity`` mode; the BHA inertia and the top drive's controller are not in the loop, as in their
    ``freqPlots.m``) on the frequency grid ``w`` (rad/s, default :data:`FREQUENCIES`)."""
    if len(cfg.sections) != 1:
        raise ValueError(f"sections: one uniform section (the loop of a uniform string), not {len(cfg.sections)}")
    if cfg.hoist is None or cfg.hoist.mode != "velocity":
        raise ValueError("hoist.mode: 'velocity' (the loop is linearised about the hoist's speed)")
    if cfg.top_drive.rpm <= 0.0:
        raise ValueError(f"top_drive.rpm: > 0 (the delay 2 pi / (n Omega0)), not {cfg.top_drive.rpm}")
    sec, bit, law = cfg.sections[0], cfg.bit, cfg.bit.detournay
    props = _core.section(sec.outer_diameter, sec.inner_diameter)
    area = sec.area if sec.area is not None else props["area"]
    polar = sec.polar_moment if sec.polar_moment is not None else props["polar_moment"]
    shear, rho = sec.shear_modulus, sec.density
    youngs = shear / _core.shear_modulus(1.0, sec.poisson_ratio)  # E = 2 G (1 + nu), the core's relation
    omega0 = cfg.top_drive.rpm * 2 * math.pi / 60
    v0 = cfg.hoist.speed
    n, a, eps = float(law.blades), bit.radius, law.intrinsic_specific_energy
    t_n = 2 * math.pi / (n * omega0)
    k_t = v0 / omega0 * a**2 * eps * n / (2 * polar * math.sqrt(shear * rho))
    k_a = a * law.cutting_ratio * eps * n / (area * math.sqrt(youngs * rho))
    w = FREQUENCIES if w is None else np.asarray(w, dtype=np.float64)
    s = 1j * w
    root = np.sqrt(1 + cfg.damping_rate / s)
    length = sec.length
    g_t = -np.tanh(length * s / math.sqrt(shear / rho) * root) / root
    g_a = -np.tanh(length * s / math.sqrt(youngs / rho) * root) / root
    delay = 1 - np.exp(-s * t_n)
    big_t = g_t * k_t / s * delay
    big_a = -g_a * k_a / s * delay
    mt, wt = _largest(big_t, w)
    ma, wa = _largest(big_a, w)
    mg, wg = _largest(big_a + big_t, w)
    return LoopGains(mt, wt, ma, wa, mg, wg)


def torsional_gain_nondim(v0: float, om: float, eta: float = 0.7, w: NDArray[np.float64] | None = None) -> float:
    """``M_T`` of their non-dimensional map (``MAIN_Torsional_FreqStabMap.m``, lines 29-45) at the
    speeds ``V0``, ``Om`` (their scales) and the top's reflection ``eta``:
    ``G_t = -g_t / s V0 / Om (1 - exp(-s / Om))``, ``g_t = (1 + Z tanh s) / (Z + tanh s)``,
    ``Z = (1 + eta) / (1 - eta)``, on their grid ``linspace(3e-3, 20 pi, 3000)`` by default."""
    w = np.linspace(3e-3, 10 * 2 * math.pi, 3000) if w is None else np.asarray(w, dtype=np.float64)
    s = 1j * w
    z = (1 + eta) / (1 - eta)
    g = (1 + z * np.tanh(s)) / (z + np.tanh(s))
    return _largest(-g / s * v0 / om * (1 - np.exp(-s / om)), w)[0]
