"""Coefficients ``k1..k6`` of the torsional PDE (paper eqs. 17, 18) for each model.

The compact form of the equation of motion (eq. 18, with ``theta(z, t)`` the twist angle)::

    k1 theta_tt = k2 theta_zz - k3 theta^3 + k4 (theta^2 theta_zz + theta theta_z^2)
                  + k5 d/dz (theta_z^3) + k6 theta,          0 < z < l,

with ``theta_z = 0`` at ``z = 0`` and ``z = l`` (eq. 14). ``Parameters.model`` selects the
coefficients:

``"paper"`` (eq. 17 as printed)

* ``k1 = rho I_p``
* ``k2 = 4 G I_p``
* ``k3 = 2 A G / (1 - 2 nu)``
* ``k4 = G I_p (5 - 6 nu) / (4 (1 - 2 nu))``
* ``k5 = G (I_r -+ I_{x^2y^2} (5 - 6 nu)) / (8 (1 - 2 nu))`` (``-``: ``k5_variant="paper"``, as
  printed; ``+``: ``"energy"``, re-derived from eqs. 5-7, model notes erratum 2)
* ``k6 = rho I_p Omega^2``

``"consistent"`` (finite-strain torsion of rigidly rotating circular sections, Green-Lagrange
strain, St Venant-Kirchhoff energy, kinetic energy ``rho I_p (Omega + theta_t)^2 / 2``)

* ``k1 = rho I_p``, ``k2 = G I_p``, ``k3 = k4 = k6 = 0``, ``k5 = M J4 / 2`` with
  ``M = lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu))`` and ``J4 = int r^4 dA``.

where ``G = E / (2 (1 + nu))`` and ``A, I_p, I_r, I_{x^2y^2}, J4`` are the section properties
(:class:`~drillstring.model.cross_section.CrossSection`). The formulas are evaluated in the Rust core
(``drillstring_core::model``). Eq. 18 is the Euler-Lagrange equation of the energy
``H = int_0^l [k1/2 theta_t^2 + k2/2 theta_z^2 + k3/4 theta^4
+ k4/2 theta^2 theta_z^2 + k5/4 theta_z^4 - k6/2 theta^2] dz``, which it conserves.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from ..errors import ValidationError
from ..limits import as_float

if TYPE_CHECKING:
    from .parameters import Parameters

__all__ = ["PDECoefficients", "shear_modulus"]

FloatOrArray = Union[float, NDArray[np.float64]]


def shear_modulus(youngs_modulus: float, poisson_ratio: float) -> float:
    """Shear modulus ``G = E / (2 (1 + nu))`` in Pa (isotropic Hooke's law)."""
    return float(_core.shear_modulus(youngs_modulus, poisson_ratio))


def _finite(name: str, value: Any) -> float:
    return as_float(name, value, "a finite real number")


def _mode_numbers(indices: ArrayLike) -> NDArray[np.float64]:
    values = np.asarray(indices, dtype=float)
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ValidationError("indices", indices, "finite mode numbers i >= 0")
    return values


def _shaped(flat: NDArray[np.float64], like: NDArray[Any]) -> FloatOrArray:
    """The core's values ``flat`` of the flattened ``like`` in its shape: a float for a 0-d
    ``like``, else an array."""
    result = np.asarray(flat, dtype=float).reshape(like.shape)
    return float(result) if result.ndim == 0 else result


@dataclass(frozen=True)
class PDECoefficients:
    """The constants of eq. 18 for one parameter set (module docstring: both models).

    Attributes
    ----------
    k1:
        ``rho I_p`` (kg m): torsional inertia per unit length.
    k2:
        ``4 G I_p`` (paper) or ``G I_p`` (consistent) (N m^2): linear torsional stiffness.
    k3:
        ``2 A G / (1 - 2 nu)`` (paper) or 0 (N): coefficient of ``theta^3``.
    k4:
        ``G I_p (5 - 6 nu) / (4 (1 - 2 nu))`` (paper) or 0 (N m^2): coefficient of
        ``theta^2 theta_zz + theta theta_z^2``.
    k5:
        ``G (I_r -+ I_{x^2y^2} (5 - 6 nu)) / (8 (1 - 2 nu))`` (paper; may be negative for the
        ``"paper"`` variant) or ``M J4 / 2`` (consistent) (N m^4): coefficient of
        ``(theta_z^3)_z``.
    k6:
        ``rho I_p Omega^2`` (paper) or 0 (N): rotation (softening) term.
    length:
        ``l`` (m).
    k6_per_omega_squared:
        ``k6 / Omega^2`` of the model (kg m): ``rho I_p`` (paper), 0 (consistent: no rotation
        softening, no critical speed). ``None`` for coefficients given directly, which the
        critical speeds then take to be ``k1`` (``k6 = k1 Omega^2``, as in eq. 17).
    """

    k1: float
    k2: float
    k3: float
    k4: float
    k5: float
    k6: float
    length: float
    k6_per_omega_squared: Optional[float] = None

    def __post_init__(self) -> None:
        for name in ("k1", "k2", "k3", "k4", "k5", "k6", "length"):
            object.__setattr__(self, name, _finite(name, getattr(self, name)))
        rate = self.k6_per_omega_squared
        if rate is not None:
            rate = _finite("k6_per_omega_squared", rate)
            if rate < 0.0:
                raise ValidationError("k6_per_omega_squared", rate, "None or 0 <= k6_per_omega_squared < inf")
            object.__setattr__(self, "k6_per_omega_squared", rate)
        if self.k1 <= 0.0:
            raise ValidationError("k1", self.k1, "0 < k1 < inf")
        if self.length <= 0.0:
            raise ValidationError("length", self.length, "0 < length < inf")

    @classmethod
    def from_parameters(cls, params: Parameters) -> PDECoefficients:
        """The coefficients of ``params.model`` (with ``params.k5_variant`` for the sign in
        ``k5`` of the paper model), evaluated in the Rust core.

        Raises
        ------
        ValidationError
            ``field="parameters"``: valid fields whose magnitudes make a coefficient overflow
            (or ``k1`` underflow to 0), e.g. ``omega=1e200``; the message names the coefficient.
        """
        try:
            k = _core.coefficients(
                params.youngs_modulus,
                params.density,
                params.poisson_ratio,
                params.outer_diameter,
                params.inner_diameter,
                params.omega,
                params.k5_variant,
                params.model,
            )
            return cls(**k, length=params.length)
        except ValidationError as exc:
            raise ValidationError(
                "parameters",
                params,
                f"magnitudes whose PDE coefficients k1..k6 (eq. 17) are finite with k1 > 0 ({exc})",
            ) from exc

    def as_tuple(self) -> tuple[float, float, float, float, float, float]:
        """``(k1, k2, k3, k4, k5, k6)``."""
        return (self.k1, self.k2, self.k3, self.k4, self.k5, self.k6)

    def frequency_squared(self, indices: ArrayLike) -> FloatOrArray:
        """Linearised ``w_i^2 = (k2 (i pi / l)^2 - k6) / k1`` (rad^2/s^2) of ``cos(i pi z/l)``
        (the core's ``stability::frequency_squared``).

        Negative for ``i = 0`` (rotation softening) and for any mode above its critical speed.
        Returns a float for a scalar ``i``, else an array of the same shape.
        """
        i = _mode_numbers(indices)
        flat = _core.frequency_squared(self.k1, self.k2, self.k6, self.length, i.ravel())
        return _shaped(flat, i)

    def linear_frequencies(self, indices: ArrayLike) -> FloatOrArray:
        """``w_i = sqrt(w_i^2)`` (rad/s) where ``w_i^2 >= 0``, ``nan`` where it is negative."""
        w2 = np.asarray(self.frequency_squared(indices), dtype=float)
        return _shaped(_core.linear_frequencies(w2.ravel()), w2)

    @property
    def wave_speed(self) -> float:
        """Linear torsional wave speed ``c = sqrt(k2 / k1)`` (m/s): ``2 sqrt(G / rho)`` in the
        paper model, ``sqrt(G / rho)`` in the consistent one; ``nan`` if ``k2 < 0`` (the core's
        ``stability::wave_speed``)."""
        return float(_core.wave_speed(self.k1, self.k2))

    def critical_speed(self, indices: ArrayLike) -> FloatOrArray:
        """``Omega_i = (i pi / l) sqrt(k2 / (k6 / Omega^2))`` (rad/s); paper model:
        ``(i pi / l) sqrt(k2 / k1) = (i pi / l) sqrt(4 G / rho)``.

        The rotation speed at which ``w_i^2`` changes sign, i.e. mode ``i`` loses linear
        stability (``k6 = k1 Omega^2`` in the paper model, independent of the section). ``inf``
        for every mode when the model has no rotation softening (``k6_per_omega_squared == 0``,
        the consistent model); ``nan`` if ``k2 < 0``.
        """
        i = _mode_numbers(indices)
        rate = self.k1 if self.k6_per_omega_squared is None else self.k6_per_omega_squared
        return _shaped(_core.critical_speeds(self.k2, rate, self.length, i.ravel()), i)
