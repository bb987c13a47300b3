"""Coefficients ``k1..k6`` of the torsional PDE (paper eqs. 17, 18).

The compact form of the equation of motion (eq. 18, with ``theta(z, t)`` the twist angle)::

    k1 theta_tt = k2 theta_zz - k3 theta^3 + k4 (theta^2 theta_zz + theta theta_z^2)
                  + k5 d/dz (theta_z^3) + k6 theta,          0 < z < l,

with ``theta_z = 0`` at ``z = 0`` and ``z = l`` (eq. 14), and

* ``k1 = rho I_p``
* ``k2 = 4 G I_p``
* ``k3 = 2 A G / (1 - 2 nu)``
* ``k4 = G I_p (5 - 6 nu) / (4 (1 - 2 nu))``
* ``k5 = G (I_r -+ I_{x^2y^2} (5 - 6 nu)) / (8 (1 - 2 nu))`` (``-``: ``"paper"``, eq. 17 as
  printed; ``+``: ``"energy"``, re-derived from eqs. 5-7, model notes erratum 2)
* ``k6 = rho I_p Omega^2``

where ``G = E / (2 (1 + nu))`` and ``A, I_p, I_r, I_{x^2y^2}`` are the section properties of
eq. 8 (:class:`~drillstring.section.Section`). Eq. 18 is the Euler-Lagrange equation of the
energy ``H = int_0^l [k1/2 theta_t^2 + k2/2 theta_z^2 + k3/4 theta^4
+ k4/2 theta^2 theta_z^2 + k5/4 theta_z^4 - k6/2 theta^2] dz``, which it conserves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import ValidationError
from .limits import as_float
from .section import Section

if TYPE_CHECKING:
    from .parameters import Parameters

__all__ = ["PDECoefficients", "shear_modulus"]

FloatOrArray = Union[float, NDArray[np.float64]]


def shear_modulus(youngs_modulus: float, poisson_ratio: float) -> float:
    """Shear modulus ``G = E / (2 (1 + nu))`` in Pa (isotropic Hooke's law)."""
    return youngs_modulus / (2.0 * (1.0 + poisson_ratio))


def _finite(name: str, value: Any) -> float:
    return as_float(name, value, "a finite real number")


def _mode_numbers(indices: ArrayLike) -> NDArray[np.float64]:
    values = np.asarray(indices, dtype=float)
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ValidationError("indices", indices, "finite mode numbers i >= 0")
    return values


@dataclass(frozen=True)
class PDECoefficients:
    """The constants of eq. 18 for one parameter set.

    Attributes
    ----------
    k1:
        ``rho I_p`` (kg m): torsional inertia per unit length.
    k2:
        ``4 G I_p`` (N m^2): linear torsional stiffness.
    k3:
        ``2 A G / (1 - 2 nu)`` (N): coefficient of ``theta^3``.
    k4:
        ``G I_p (5 - 6 nu) / (4 (1 - 2 nu))`` (N m^2): coefficient of
        ``theta^2 theta_zz + theta theta_z^2``.
    k5:
        ``G (I_r -+ I_{x^2y^2} (5 - 6 nu)) / (8 (1 - 2 nu))`` (N m^4): coefficient of
        ``(theta_z^3)_z``; may be negative for the ``"paper"`` variant.
    k6:
        ``rho I_p Omega^2`` (N): rotation (softening) term.
    length:
        ``l`` (m).
    """

    k1: float
    k2: float
    k3: float
    k4: float
    k5: float
    k6: float
    length: float

    def __post_init__(self) -> None:
        for name in ("k1", "k2", "k3", "k4", "k5", "k6", "length"):
            object.__setattr__(self, name, _finite(name, getattr(self, name)))
        if self.k1 <= 0.0:
            raise ValidationError("k1", self.k1, "0 < k1 < inf")
        if self.length <= 0.0:
            raise ValidationError("length", self.length, "0 < length < inf")

    @classmethod
    def from_parameters(cls, params: Parameters) -> PDECoefficients:
        """Evaluate eq. 17 (with ``params.k5_variant`` for the sign in ``k5``).

        Raises
        ------
        ValidationError
            ``field="parameters"``: valid fields whose magnitudes make a coefficient overflow
            (or ``k1`` underflow to 0), e.g. ``omega=1e200``; the message names the coefficient.
        """
        try:
            section = Section.annulus(params.outer_diameter, params.inner_diameter)
            nu = params.poisson_ratio
            g = shear_modulus(params.youngs_modulus, nu)
            ip = section.polar_moment
            sign = -1.0 if params.k5_variant == "paper" else 1.0
            return cls(
                k1=params.density * ip,
                k2=4.0 * g * ip,
                k3=2.0 * section.area * g / (1.0 - 2.0 * nu),
                k4=g * ip * (5.0 - 6.0 * nu) / (4.0 * (1.0 - 2.0 * nu)),
                k5=g
                * (section.i_r + sign * section.i_x2y2 * (5.0 - 6.0 * nu))
                / (8.0 * (1.0 - 2.0 * nu)),
                k6=params.density * ip * params.omega**2,
                length=params.length,
            )
        except (OverflowError, ZeroDivisionError, ValidationError) as exc:
            raise ValidationError(
                "parameters",
                params,
                f"magnitudes whose PDE coefficients k1..k6 (eq. 17) are finite with k1 > 0 ({exc})",
            ) from exc

    def as_tuple(self) -> tuple[float, float, float, float, float, float]:
        """``(k1, k2, k3, k4, k5, k6)``."""
        return (self.k1, self.k2, self.k3, self.k4, self.k5, self.k6)

    def frequency_squared(self, indices: ArrayLike) -> FloatOrArray:
        """Linearised ``w_i^2 = (k2 (i pi / l)^2 - k6) / k1`` (rad^2/s^2) of ``cos(i pi z/l)``.

        Negative for ``i = 0`` (rotation softening) and for any mode above its critical speed.
        Returns a float for a scalar ``i``, else an array of the same shape.
        """
        i = _mode_numbers(indices)
        result = (self.k2 * (i * math.pi / self.length) ** 2 - self.k6) / self.k1
        return float(result) if result.ndim == 0 else result

    def linear_frequencies(self, indices: ArrayLike) -> FloatOrArray:
        """``w_i = sqrt(w_i^2)`` (rad/s) where ``w_i^2 >= 0``, ``nan`` where it is negative."""
        w2 = np.asarray(self.frequency_squared(indices), dtype=float)
        result = np.sqrt(np.where(w2 >= 0.0, w2, np.nan))
        return float(result) if result.ndim == 0 else result

    def critical_speed(self, indices: ArrayLike) -> FloatOrArray:
        """``Omega_i = (i pi / l) sqrt(k2 / k1) = (i pi / l) sqrt(4 G / rho)`` (rad/s).

        The rotation speed at which ``w_i^2`` changes sign, i.e. mode ``i`` loses linear
        stability (``k6 = k1 Omega^2``, independent of the section). ``nan`` if ``k2 < 0``.
        """
        i = _mode_numbers(indices)
        speed = math.sqrt(self.k2 / self.k1) if self.k2 >= 0.0 else math.nan
        result = i * math.pi / self.length * speed
        return float(result) if result.ndim == 0 else result
