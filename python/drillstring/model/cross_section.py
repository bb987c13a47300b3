"""Geometric properties of the drill-string cross-section (paper eq. 8).

For a hollow circular section (annulus) with outer radius ``R = D/2`` and inner radius
``r = d/2``:

* ``A = pi (R^2 - r^2)``                          cross-sectional area,
* ``I_p = int (x^2 + y^2) dA = pi (R^4 - r^4)/2``  polar moment of inertia,
* ``I_r = int (x^4 + y^4) dA = pi (R^6 - r^6)/4``,
* ``I_x2y2 = int x^2 y^2 dA = pi (R^6 - r^6)/24``,
* ``J4 = int (x^2 + y^2)^2 dA = pi (R^6 - r^6)/3`` (the ``"consistent"`` model's ``k5``).

The last three follow from ``int_0^{2 pi} cos^4 = 3 pi/4`` and
``int_0^{2 pi} cos^2 sin^2 = pi/4`` with ``int_r^R rho^5 d rho = (R^6 - r^6)/6``. The formulas
are evaluated in the Rust core (``drillstring_core::model::CrossSection``); this module validates
the diameters and holds the values.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

from .. import _core
from ..errors import ValidationError
from ..limits import as_float

__all__ = ["CrossSection"]


def _positive_finite(field: str, value: Any) -> float:
    number = as_float(field, value, f"a finite real number, 0 < {field} < inf")
    if number <= 0:
        raise ValidationError(field, value, f"0 < {field} < inf")
    return number


@dataclass(frozen=True)
class CrossSection:
    """Cross-section properties entering the coefficients ``k1..k6`` (eqs. 8, 17).

    Attributes
    ----------
    area:
        ``A`` in m^2.
    polar_moment:
        ``I_p = int (x^2 + y^2) dA`` in m^4.
    i_r:
        ``I_r = int (x^4 + y^4) dA`` in m^6.
    i_x2y2:
        ``I_{x^2 y^2} = int x^2 y^2 dA`` in m^6.
    j4:
        ``J4 = int (x^2 + y^2)^2 dA`` in m^6 (``None`` when not given).
    """

    area: float
    polar_moment: float
    i_r: float
    i_x2y2: float
    j4: Optional[float] = None

    def __post_init__(self) -> None:
        for name in ("area", "polar_moment", "i_r", "i_x2y2"):
            object.__setattr__(self, name, _positive_finite(name, getattr(self, name)))
        if self.j4 is not None:
            object.__setattr__(self, "j4", _positive_finite("j4", self.j4))

    @property
    def axial_moment(self) -> float:
        """``I_x = I_y = I_p / 2`` (m^4), the axial moments of eq. 10."""
        return self.polar_moment / 2.0

    @classmethod
    def annulus(cls, outer_diameter: float, inner_diameter: float) -> CrossSection:
        """Properties of a hollow circular section.

        Parameters
        ----------
        outer_diameter:
            ``D`` in m, ``D > 0``.
        inner_diameter:
            ``d`` in m, ``0 <= d < D`` (``d = 0`` is a solid shaft).

        Returns
        -------
        CrossSection
            ``A``, ``I_p``, ``I_r`` and ``I_{x^2 y^2}`` of eq. 8, and ``J4``.

        Raises
        ------
        ValidationError
            If a diameter is not a finite real number or ``0 <= d < D`` fails, or (naming the
            diameter) the section properties overflow or underflow to 0.
        """
        big = _positive_finite("outer_diameter", outer_diameter)
        allowed = f"0 <= inner_diameter < outer_diameter = {big!r}"
        small = as_float("inner_diameter", inner_diameter, allowed)
        if not 0.0 <= small < big:
            raise ValidationError("inner_diameter", inner_diameter, allowed)
        return cls(**_core.section(big, small))

