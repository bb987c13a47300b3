"""Linear stability of the equilibrium ``q = qdot = 0`` of a Galerkin model (paper sec. 3.6).

Writing the modal system ``M q'' + K q + grad V(q) = 0`` in first order, ``x = (q, qdot)``,
the quartic potential contributes nothing at the equilibrium, so the Jacobian there is::

    J = [[0, I], [-M^-1 K, 0]],

(eq. 28 for one mode). Its eigenvalues are ``lambda = +-sqrt(-mu)`` for every eigenvalue
``mu`` of ``M^-1 K``; ``M`` and ``K`` are diagonal, so ``mu_i = K_ii / M_ii = w_i^2`` and the
eigenvalues are ``+-i w_i`` (eq. 29: ``+-i sqrt(a2/a1)``) while ``K_ii > 0``.

Classification of the equilibrium:

* ``"centre"``: every ``mu_i > 0``, all eigenvalues purely imaginary (Lyapunov stable in the
  linear approximation, not asymptotically stable; the conserved energy with a positive
  definite quadratic part makes it a nonlinear centre too).
* ``"saddle"``: some ``mu_i < 0``, a real positive eigenvalue ``sqrt(-mu_i)`` (unstable).
* ``"degenerate"``: no ``mu_i < 0`` but some ``mu_i = 0`` (a double zero eigenvalue, exactly at
  a critical speed); the linearisation does not decide.

Since ``K_ii / M_ii = (k2/k1) (i pi / l)^2 - Omega^2``, mode ``i`` loses linear stability when
the rotation speed exceeds the critical speed ``Omega_crit,i = (i pi / l) sqrt(k2 / k1) =
(i pi / l) sqrt(4 G / rho)``, which does not depend on the cross-section. The rigid mode
``i = 0`` has ``Omega_crit,0 = 0``: it is a saddle for any ``Omega != 0``.

With viscous damping (:attr:`Parameters.damping_rate` ``c > 0``, force ``-c M qdot``) the
Jacobian is ``J = [[0, I], [-M^-1 K, -c I]]`` and mode ``i`` has the eigenvalues
``lambda = -c/2 +- sqrt(c^2/4 - mu_i)``: a centre becomes a ``"stable focus"`` (``mu_i > c^2/4``,
decaying oscillation ``exp(-c t / 2)``) or, overdamped (``0 < mu_i <= c^2/4``), a
``"stable node"``; ``mu_i < 0`` stays a saddle and ``mu_i = 0`` degenerate (a zero eigenvalue).
The whole equilibrium is a ``"stable focus"`` when every mode is stable and some mode
oscillates, a ``"stable node"`` when none does.

The ``"consistent"`` model (:attr:`Parameters.model`) has no rotation softening (``k6 = 0``):
``K_ii / M_ii = (k2/k1) (i pi / l)^2`` for every ``Omega``, no mode has a critical speed
(``inf``), and the rigid mode is neutral (``K_00 = 0``: ``"degenerate"``).

The Rust core computes all of it (``drillstring_core::stability``: the Jacobian, the
eigenvalues of each mode in closed form, the classification with a rate within ``1e-12`` of the
largest ``|K_ii / M_ii|`` counted as zero, the same rule by which sweeps count unstable modes,
and the critical speeds); this module arranges its answers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..model.coefficients import PDECoefficients
from ..model.galerkin import ModalCoefficients, project
from ..model.parameters import Parameters, check_damping_rate

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import NDArray

__all__ = ["CLASSIFICATIONS", "Stability", "jacobian", "analyse"]

#: Possible values of :attr:`Stability.classification`.
CLASSIFICATIONS = ("centre", "stable focus", "stable node", "saddle", "degenerate")


def jacobian(coefficients: ModalCoefficients, damping_rate: float = 0.0) -> NDArray[np.float64]:
    """``J = [[0, I], [-M^-1 K, -c I]]`` (2m, 2m) of the first-order system at ``q = qdot = 0``
    (``c`` = ``damping_rate``, 1/s; the damping force ``-c M qdot`` gives ``-c I``)."""
    c = check_damping_rate(damping_rate)
    return _core.modal_jacobian(coefficients.mass, coefficients.stiffness, c)


def _complex(real: NDArray[np.float64], imag: NDArray[np.float64]) -> NDArray[np.complex128]:
    out = np.empty(real.size, dtype=complex)
    out.real, out.imag = real, imag
    return out


@dataclass(frozen=True, eq=False)
class Stability:
    """Linear stability of the equilibrium of one Galerkin model; see :func:`analyse`."""

    indices: NDArray[np.int64]
    """Mode numbers ``i`` of the retained basis (rigid mode ``0`` first when included)."""
    jacobian: NDArray[np.float64]
    """``(2m, 2m)`` Jacobian at the equilibrium."""
    eigenvalues: NDArray[np.complex128]
    """``(2m,)`` eigenvalues of :attr:`jacobian` (both roots of every mode, in closed form),
    sorted by imaginary then real part."""
    mode_eigenvalues: NDArray[np.complex128]
    """``(m,)`` per mode the eigenvalue ``-c/2 + sqrt(c^2/4 - K_ii / M_ii)`` (principal root,
    ``Im >= 0``); without damping the mode contributes the pair ``+-`` it (``i w_i`` for a
    stable mode, ``+-s_i`` real for an unstable one), with damping ``c`` the pair
    ``-c/2 +- sqrt(c^2/4 - K_ii / M_ii)``."""
    mode_classification: tuple[str, ...]
    """Per mode ``"centre"``, ``"stable focus"``, ``"stable node"``, ``"saddle"`` or
    ``"degenerate"`` (from the sign of ``K_ii`` and the damping)."""
    classification: str
    """Of the whole equilibrium: ``"saddle"`` if any mode is, else ``"degenerate"`` if any mode
    is, else ``"centre"`` without damping and ``"stable focus"`` (some mode oscillates) or
    ``"stable node"`` with it."""
    omega: Optional[float]
    """Rotation speed ``Omega`` (rad/s) the model was built for, when known."""
    critical_speeds: Optional[NDArray[np.float64]]
    """``(m,)`` ``Omega_crit,i = (i pi / l) sqrt(k2 / k1)`` (rad/s,
    :meth:`PDECoefficients.critical_speed`), when ``omega`` is known; ``inf`` for a model
    without rotation softening (``"consistent"``)."""
    damping_rate: float = 0.0
    """The viscous damping rate ``c`` (1/s) of the linearisation."""

    @property
    def linear_frequencies_hz(self) -> NDArray[np.float64]:
        """``w_i / (2 pi)`` (Hz) of the oscillating stable modes (with damping the damped
        frequency ``sqrt(w_i^2 - c^2/4)``), ``nan`` for unstable, degenerate or overdamped ones."""
        lam = self.mode_eigenvalues
        stable = (lam.real == -0.5 * self.damping_rate) & (lam.imag > 0)
        return np.where(stable, lam.imag / (2 * math.pi), np.nan)

    @property
    def stable(self) -> bool:
        """True for a centre or (with damping) a stable focus or node."""
        return self.classification in ("centre", "stable focus", "stable node")


def analyse(
    source: Union[ModalCoefficients, Parameters],
    modes: int = 3,
    rigid_mode: bool = False,
    *,
    omega: Optional[float] = None,
    damping_rate: Optional[float] = None,
) -> Stability:
    """Jacobian, eigenvalues, classification and critical speeds of a Galerkin model.

    Parameters
    ----------
    source : ModalCoefficients or Parameters
        A projected model (any modes, rigid or not), or parameters to project with ``modes``
        and ``rigid_mode`` (then ``omega`` is ``source.omega``).
    modes, rigid_mode :
        Basis of the projection when ``source`` is a :class:`Parameters`.
    omega : float, optional
        Rotation speed of a :class:`ModalCoefficients` source. Needed only for the critical
        speeds: ``K_ii / M_ii + Omega^2 = (k2/k1) (i pi/l)^2`` gives ``k2/k1`` and
        ``Omega_crit,i = (i pi / l) sqrt(k2/k1)`` (exactly 0 for the rigid mode); that is, a
        :class:`ModalCoefficients` source is taken to have the paper model's ``k6 = k1 Omega^2``.
        For a :class:`Parameters` source whose model has no rotation softening
        (``"consistent"``) every critical speed is ``inf``.
    damping_rate : float, optional
        Viscous damping rate ``c`` (1/s, ``>= 0``) of a :class:`ModalCoefficients` source
        (default 0); a :class:`Parameters` source uses ``source.damping_rate``.

    Examples
    --------
    >>> import drillstring as ds
    >>> s = analyse(ds.preset("aluminum"), modes=1)
    >>> s.classification, round(float(s.mode_eigenvalues[0].imag), 2)
    ('centre', 195.4)
    """
    pde: Optional[PDECoefficients] = None
    if isinstance(source, Parameters):
        if omega is not None and float(omega) != source.omega:
            raise ValidationError("omega", omega, f"omitted or equal to params.omega = {source.omega}")
        omega = source.omega
        if damping_rate is not None and check_damping_rate(damping_rate) != source.damping_rate:
            raise ValidationError(
                "damping_rate", damping_rate, f"omitted or equal to params.damping_rate = {source.damping_rate}"
            )
        damping_rate = source.damping_rate
        coefficients = project(source, modes=modes, rigid_mode=rigid_mode)
        pde = PDECoefficients.from_parameters(source)
    elif isinstance(source, ModalCoefficients):
        coefficients = source
    else:
        raise ValidationError(
            "source", type(source).__name__, "a drillstring.ModalCoefficients or Parameters"
        )
    if omega is not None and not math.isfinite(float(omega)):
        raise ValidationError("omega", omega, "a finite rotation speed, rad/s")
    c = check_damping_rate(0.0 if damping_rate is None else damping_rate)
    raw = _core.modal_stability(coefficients.mass, coefficients.stiffness, c)
    indices = coefficients.indices.copy()
    critical = None
    if pde is not None:
        critical = np.asarray(pde.critical_speed(indices), dtype=float)
    elif omega is not None:
        # a model known by its arrays is taken to be of the paper's family, k6 = k1 Omega^2:
        # k2 / k1 from its rates and Omega, then the critical speeds of that wave speed
        speed2 = _core.wave_speed_squared_of_rates(raw["rates"], indices, coefficients.length, float(omega))
        critical = _core.critical_speeds(speed2, 1.0, coefficients.length, indices.astype(float))
    return Stability(
        indices=indices,
        jacobian=jacobian(coefficients, c),
        eigenvalues=_complex(raw["eigenvalues_real"], raw["eigenvalues_imag"]),
        mode_eigenvalues=_complex(raw["mode_eigenvalues_real"], raw["mode_eigenvalues_imag"]),
        mode_classification=tuple(raw["mode_classification"]),
        classification=raw["classification"],
        omega=None if omega is None else float(omega),
        critical_speeds=critical,
        damping_rate=c,
    )
