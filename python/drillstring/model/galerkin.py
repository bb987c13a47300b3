r"""Bubnov-Galerkin reduction of eq. 18 onto the cosine modes of the free-free string.

Basis and ansatz (eqs. 15, 16)
------------------------------
``theta(z, t) = sum_k q_k(t) phi_k(z)`` with ``phi_k(z) = cos(i_k pi z / l)``, where the mode
numbers are ``i_k = 1..n`` (the paper's basis, default) or ``i_k = 0, 1..n`` with the rigid
(uniform-twist) mode ``i = 0`` placed first (``rigid_mode=True``). Every ``phi_k`` satisfies the
boundary conditions ``phi_k'(0) = phi_k'(l) = 0`` (eq. 14).

Reduced equations
-----------------
Eq. 18 is the Euler-Lagrange equation of ``H`` (see :mod:`drillstring.model.coefficients`). Projecting
it onto ``phi_j``, ``int_0^l (k1 theta_tt - RHS) phi_j dz = 0``, and integrating the
``d/dz (...)`` terms by parts (the boundary terms carry ``theta_z = 0`` at both ends and vanish)
gives the Ritz equations of the modal energy::

    M q'' + K q + grad V(q) = 0,
    M_jj = k1 int_0^l phi_j^2 dz,   K_jj = k2 int_0^l phi_j'^2 dz - k6 int_0^l phi_j^2 dz,
    V(q) = int_0^l [k3/4 theta^4 + k4/2 theta^2 theta_z^2 + k5/4 theta_z^4] dz,

with ``int_0^l phi^2 = l/2`` (``i >= 1``) or ``l`` (``i = 0``), ``int_0^l phi'^2 = (i pi)^2/(2 l)``;
``M`` and ``K`` are diagonal. The modal energy ``1/2 q'^T M q' + 1/2 q^T K q + V(q)`` equals
``H`` of the Galerkin field and is conserved by the reduced equations. The core builds ``M``,
``K`` and the ``C_t`` below from the integrals of this module, and evaluates ``H`` and ``V``.

Quartic potential
-----------------
With ``s = z/l`` and ``c_k = cos(i_k pi s)``, ``s_k = sin(i_k pi s)``::

    V(q) = sum_t C_t q_a q_b q_c q_d        over sorted positions a <= b <= c <= d,
    C_t  = k3 l / 4 * cos4_t  +  k4 pi^2 / (2 l) * mixed_t  +  k5 pi^4 / (4 l^3) * sin4_t,

    cos4_t  = mult_t * int_0^1 c_a c_b c_c c_d ds,
    mixed_t = sum over the mult_t distinct orderings (p1, p2, p3, p4) of (a, b, c, d) of
              i_p3 i_p4 int_0^1 c_p1 c_p2 s_p3 s_p4 ds,
    sin4_t  = mult_t * i_a i_b i_c i_d * int_0^1 s_a s_b s_c s_d ds,

where ``mult_t = 24 / prod(r!)`` is the number of distinct orderings of ``t`` (``r`` = how often
each position repeats). The integrals are exact: writing ``cos x = (e^{ix} + e^{-ix})/2`` and
``sin x = (e^{ix} - e^{-ix})/(2i)`` and using that the integrand is even in ``s``,
``int_0^1 cos(k pi s) ds = [k = 0]`` for integer ``k`` gives, with ``e_a = +1``,
``e = (e_a, e_b, e_c, e_d) in {+-1}^4`` and ``N(e) = [e_a i_a + e_b i_b + e_c i_c + e_d i_d = 0]``::

    int c_a c_b c_c c_d = 1/8 sum_e N(e),
    int c_a c_b s_c s_d = 1/8 sum_e (-e_c e_d) N(e),
    int s_a s_b s_c s_d = 1/8 sum_e e_b e_c e_d N(e).

All three sets are integer multiples of 1/8 (computed in ``int64``, exact in ``float64``). A term
is nonzero only if ``i_d = +-i_a +- i_b +- i_c`` (then ``cos4_t > 0``); only those are stored.
They are generated in the Rust core (``drillstring_core::galerkin``, ``_core.galerkin_integrals``),
which discretises each term of the model with them (``K`` from the terms with ``p + r = 2``, ``C_t``
from those with ``p + r = 4``: ``cos4``, ``mixed``, ``sin4`` are the integrals of ``theta^4``,
``theta^2 theta_z^2``, ``theta_z^4``); ``tests/oracles.py`` keeps the former numpy generator.
Consequences: ``theta -> -theta`` symmetry (only quartic terms) and the selection rule
``i_a + i_b + i_c + i_d`` even, so that odd modes alone never force even modes.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, NamedTuple, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from ..errors import ValidationError
from ..limits import as_float, as_int
from .coefficients import PDECoefficients

if TYPE_CHECKING:
    from .parameters import Parameters

__all__ = [
    "MAX_MODES",
    "Evaluation",
    "DuffingCoefficients",
    "GalerkinIntegrals",
    "ModalCoefficients",
    "dimensionless_integrals",
    "mode_numbers",
    "project",
]

#: How the core evaluates the quartic force and potential (:meth:`ModalCoefficients.core_system`).
Evaluation = Literal["auto", "terms", "spectral"]

#: Largest accepted number of elastic modes ``n`` (the core's limit).
MAX_MODES: int = _core.GALERKIN_MAX_MODES

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
FloatOrArray = Union[float, FloatArray]


# --------------------------------------------------------------------------- validation


def _check_modes(modes: Any) -> int:
    return as_int("modes", modes, 1, MAX_MODES)


def _check_rigid_mode(rigid_mode: Any) -> bool:
    if not isinstance(rigid_mode, (bool, np.bool_)):
        raise ValidationError("rigid_mode", rigid_mode, "True or False")
    return bool(rigid_mode)


def _readonly(array: NDArray[Any]) -> NDArray[Any]:
    array.flags.writeable = False
    return array


def mode_numbers(modes: int, rigid_mode: bool = False) -> IntArray:
    """Mode numbers ``i`` of the retained basis: ``1..n``, or ``0, 1..n`` with the rigid mode."""
    n = _check_modes(modes)
    first = 0 if _check_rigid_mode(rigid_mode) else 1
    return np.arange(first, n + 1, dtype=np.int64)


# --------------------------------------------------------------------------- integrals


@dataclass(frozen=True, eq=False)
class GalerkinIntegrals:
    """Dimensionless quartic integrals on ``s = z/l in [0, 1]`` (see the module docstring).

    Attributes
    ----------
    indices:
        ``(m,)`` mode numbers ``i_k`` of the basis positions ``k = 0..m-1``.
    quartic_index:
        ``(T, 4)`` positions ``a <= b <= c <= d`` (into ``indices``) of the nonzero terms,
        in lexicographic order.
    cos4:
        ``(T,)`` ``mult_t * int c_a c_b c_c c_d ds`` (multiplies ``k3 l / 4``).
    mixed:
        ``(T,)`` ``sum_orderings i_p3 i_p4 int c_p1 c_p2 s_p3 s_p4 ds``
        (multiplies ``k4 pi^2 / (2 l)``).
    sin4:
        ``(T,)`` ``mult_t i_a i_b i_c i_d int s_a s_b s_c s_d ds``
        (multiplies ``k5 pi^4 / (4 l^3)``).

    All arrays are read-only (instances are cached and shared).
    """

    indices: IntArray
    quartic_index: IntArray
    cos4: FloatArray
    mixed: FloatArray
    sin4: FloatArray

    @property
    def rigid_mode(self) -> bool:
        """Whether the rigid mode ``i = 0`` is included (as position 0)."""
        return bool(self.indices[0] == 0)

    @property
    def n_terms(self) -> int:
        """Number ``T`` of stored (nonzero) quartic terms."""
        return int(self.quartic_index.shape[0])


@functools.lru_cache(maxsize=64)
def _cached_integrals(modes: int, rigid_mode: bool) -> GalerkinIntegrals:
    arrays = _core.galerkin_integrals(modes, rigid_mode)
    return GalerkinIntegrals(
        indices=_readonly(arrays["indices"]),
        quartic_index=_readonly(arrays["quartic_index"]),
        cos4=_readonly(arrays["cos4"]),
        mixed=_readonly(arrays["mixed"]),
        sin4=_readonly(arrays["sin4"]),
    )


def dimensionless_integrals(modes: int, rigid_mode: bool = False) -> GalerkinIntegrals:
    """Exact dimensionless quartic integrals of the ``cos(i pi s)`` basis (cached, read-only).

    Parameters
    ----------
    modes:
        Number ``n`` of elastic modes ``i = 1..n``, ``1 <= n <= 256``.
    rigid_mode:
        Include the rigid mode ``i = 0`` (as position 0).

    Raises
    ------
    ValidationError
        For a bad ``modes`` or ``rigid_mode``.
    """
    return _cached_integrals(_check_modes(modes), _check_rigid_mode(rigid_mode))


# --------------------------------------------------------------------------- modal model


class DuffingCoefficients(NamedTuple):
    """One-mode Duffing equation ``a1 q'' + a2 q + a3 q^3 = 0`` (eq. 19, corrected eq. 20)."""

    a1: float
    a2: float
    a3: float


def _as_state(name: str, value: ArrayLike, m: int) -> FloatArray:
    array = np.asarray(value, dtype=float)
    if array.ndim not in (1, 2) or array.shape[0] != m:
        raise ValidationError(
            name, f"array of shape {array.shape}", f"shape ({m},) or ({m}, samples)"
        )
    return array


def _as_positions(name: str, value: ArrayLike) -> FloatArray:
    array = np.atleast_1d(np.asarray(value, dtype=float))
    if array.ndim != 1:
        raise ValidationError(name, f"array of shape {array.shape}", "a scalar or a 1-D array")
    return array


@dataclass(frozen=True, eq=False)
class ModalCoefficients:
    """Galerkin model ``M q'' + K q + grad V(q) = 0`` of eq. 18 (see the module docstring).

    All arrays are read-only. Build with :func:`project`,
    :meth:`from_parameters` or :meth:`from_coefficients`.

    Attributes
    ----------
    indices:
        ``(m,)`` mode numbers ``i`` of the basis ``cos(i pi z / l)``.
    length:
        ``l`` in m.
    mass:
        ``(m,)`` diagonal of ``M``: ``k1 l/2`` (``i >= 1``), ``k1 l`` (``i = 0``).
    stiffness:
        ``(m,)`` diagonal of ``K``: ``k2 (i pi)^2/(2 l) - k6 l/2`` (``i >= 1``), ``-k6 l``
        (``i = 0``).
    quartic_index:
        ``(T, 4)`` positions ``a <= b <= c <= d`` of the quartic terms.
    quartic_coef:
        ``(T,)`` coefficients ``C_t`` with ``V(q) = sum_t C_t q_a q_b q_c q_d``.
    coefficients:
        The ``k1..k6`` and ``l`` projected (set by :meth:`from_coefficients`), or ``None``
        for a model given by its arrays. With them :meth:`core_system` may evaluate the quartic
        force pseudo-spectrally.
    """

    indices: IntArray
    length: float
    mass: FloatArray
    stiffness: FloatArray
    quartic_index: IntArray
    quartic_coef: FloatArray
    coefficients: PDECoefficients | None = None

    def __post_init__(self) -> None:
        indices = np.array(self.indices, dtype=np.int64)
        m = indices.size
        if indices.ndim != 1 or m == 0:
            raise ValidationError("indices", self.indices, "a non-empty 1-D array of modes")
        set_ = functools.partial(object.__setattr__, self)
        set_("indices", _readonly(indices))
        length = as_float("length", self.length, "0 < length < inf")
        if not length > 0.0:
            raise ValidationError("length", self.length, "0 < length < inf")
        set_("length", length)
        for name in ("mass", "stiffness"):
            array = np.array(getattr(self, name), dtype=float)
            if array.shape != (m,):
                raise ValidationError(name, f"array of shape {array.shape}", f"shape ({m},)")
            set_(name, _readonly(array))
        quad = np.array(self.quartic_index, dtype=np.int64).reshape(-1, 4)
        if quad.size and (quad.min() < 0 or quad.max() >= m):
            raise ValidationError("quartic_index", "out-of-range position", f"0 <= k < {m}")
        coef = np.array(self.quartic_coef, dtype=float)
        if coef.shape != (quad.shape[0],):
            raise ValidationError(
                "quartic_coef", f"array of shape {coef.shape}", f"shape ({quad.shape[0]},)"
            )
        set_("quartic_index", _readonly(quad))
        set_("quartic_coef", _readonly(coef))

    # ------------------------------------------------------------------ construction

    @classmethod
    def from_coefficients(
        cls, coefficients: PDECoefficients, modes: int = 3, rigid_mode: bool = False
    ) -> ModalCoefficients:
        """Project eq. 18 with the given ``k1..k6`` and ``l`` onto ``modes`` cosine modes.

        The dimensionless integrals (:func:`dimensionless_integrals`) are scaled to ``M``,
        ``K`` and ``C_t`` in the core (``_core.scale_integrals``), as for every run of a sweep.

        Raises
        ------
        ValidationError
            For a bad ``modes`` or ``rigid_mode``, or (``field="coefficients"``) coefficients
            whose projection overflows (a mass, stiffness or quartic coefficient not finite).
        """
        integrals = dimensionless_integrals(modes, rigid_mode)
        try:
            scaled = _core.scale_integrals(
                np.array(coefficients.as_tuple(), dtype=float),
                coefficients.length,
                integrals.indices,
                integrals.quartic_index,
                integrals.cos4,
                integrals.mixed,
                integrals.sin4,
            )
        except ValidationError as exc:
            raise ValidationError(
                "coefficients",
                coefficients,
                "magnitudes whose Galerkin projection is finite with masses > 0"
                f" ({exc.field} is {exc.value})",
            ) from exc
        return cls(
            indices=integrals.indices,
            length=coefficients.length,
            mass=scaled["mass"],
            stiffness=scaled["stiffness"],
            quartic_index=integrals.quartic_index,
            quartic_coef=scaled["quartic_coef"],
            coefficients=coefficients,
        )

    @classmethod
    def from_parameters(
        cls, params: Parameters, modes: int = 3, rigid_mode: bool = False
    ) -> ModalCoefficients:
        """Project eq. 18 with ``k1..k6`` of eq. 17 evaluated for ``params``.

        Raises
        ------
        ValidationError
            For a bad ``modes`` or ``rigid_mode``, or (``field="parameters"``) valid fields whose
            magnitudes make a coefficient overflow.
        """
        coefficients = PDECoefficients.from_parameters(params)
        try:
            return cls.from_coefficients(coefficients, modes, rigid_mode)
        except ValidationError as exc:
            if exc.field != "coefficients":
                raise
            raise ValidationError("parameters", params, exc.allowed) from exc

    # ------------------------------------------------------------------ basic properties

    @property
    def n_modes(self) -> int:
        """Number ``m`` of retained basis functions (including the rigid mode)."""
        return int(self.indices.size)

    @property
    def rigid_mode(self) -> bool:
        """Whether the rigid mode ``i = 0`` is included (as position 0)."""
        return bool(self.indices[0] == 0)

    @property
    def mass_matrix(self) -> FloatArray:
        """Full ``(m, m)`` mass matrix ``M`` (diagonal)."""
        return np.diag(self.mass)

    @property
    def stiffness_matrix(self) -> FloatArray:
        """Full ``(m, m)`` linear stiffness matrix ``K`` (diagonal)."""
        return np.diag(self.stiffness)

    @property
    def linear_frequencies(self) -> FloatArray:
        """``(m,)`` ``w_i = sqrt(K_ii / M_ii)`` in rad/s; ``nan`` where ``K_ii < 0`` (the core's
        ``_core.modal_rates`` and ``_core.linear_frequencies``)."""
        return _core.linear_frequencies(_core.modal_rates(self.mass, self.stiffness))

    # ------------------------------------------------------------------ potential and forces

    def core_system(self, damping_rate: float = 0.0, evaluation: Evaluation = "auto") -> _core.ModalSystem:
        """This model as the core's modal system, with the viscous damping rate ``c`` (1/s).

        ``evaluation`` is how the core evaluates the quartic force and potential: ``"terms"``
        (the merged monomials of :attr:`quartic_coef`), ``"spectral"`` (the exact quadrature of
        the quartic density of :attr:`coefficients`, ``O(n log n)``; equal to ``"terms"`` to
        rounding) or ``"auto"``: spectral from ``_core.SPECTRAL_MIN_MODES`` retained modes on
        when :attr:`coefficients` is set, else terms.

        Raises
        ------
        ValidationError
            For a model the core refuses (a mass not finite and > 0, a stiffness or quartic
            coefficient not finite), a bad ``damping_rate`` or ``evaluation``, or
            ``"spectral"`` without :attr:`coefficients`.
        """
        resolved = _core.resolve_evaluation(str(evaluation), self.n_modes)  # names "evaluation" if bad
        if evaluation == "spectral" and self.coefficients is None:
            raise ValidationError(
                "evaluation", evaluation, '"terms" or "auto" for a model without coefficients'
            )
        source = self.coefficients
        if source is not None and resolved == "spectral":
            return _core.ModalSystem.spectral(
                np.array(source.as_tuple(), dtype=float),
                source.length,
                np.ascontiguousarray(self.indices, dtype=np.int64),
                damping_rate=damping_rate,
            )
        return _core.ModalSystem(
            self.mass,
            self.stiffness,
            np.ascontiguousarray(self.quartic_index, dtype=np.int64),
            self.quartic_coef,
            damping_rate=damping_rate,
        )

    def potential(self, q: ArrayLike) -> FloatOrArray:
        """Quartic potential ``V(q)``; ``q`` of shape ``(m,)`` -> float, ``(m, S)`` -> ``(S,)``.

        Evaluated by the core (:meth:`core_system`), as :meth:`energy` is.
        """
        qa = _as_state("q", q, self.n_modes)
        value = self.core_system().potential(qa.reshape(self.n_modes, -1))
        return float(value[0]) if qa.ndim == 1 else value

    def _per_state(self, q: FloatArray, evaluate: Any) -> FloatArray:
        """``evaluate`` (a method of the core system taking one state) at ``q`` of shape
        ``(m,)``, or at each column of ``q`` of shape ``(m, S)``."""
        if q.ndim == 1:
            return np.asarray(evaluate(np.ascontiguousarray(q)), dtype=float)
        out = np.empty_like(q)
        for s in range(q.shape[1]):
            out[:, s] = evaluate(np.ascontiguousarray(q[:, s]))
        return out

    def cubic_force(self, q: ArrayLike) -> FloatArray:
        """``grad V(q)``, the cubic generalised force; same shape as ``q``.

        Evaluated by the core (:meth:`core_system`), as :meth:`potential` is.
        """
        qa = _as_state("q", q, self.n_modes)
        return self._per_state(qa, self.core_system().quartic_gradient)

    def acceleration(self, q: ArrayLike) -> FloatArray:
        """``q'' = -M^{-1} (K q + grad V(q))`` (undamped); same shape as ``q``. Evaluated by the
        core (:meth:`core_system`)."""
        qa = _as_state("q", q, self.n_modes)
        return self._per_state(qa, self.core_system().acceleration)

    def energy(self, q: ArrayLike, qdot: ArrayLike) -> FloatOrArray:
        """``H = 1/2 q'^T M q' + 1/2 q^T K q + V(q)`` (J), the PDE energy of the Galerkin field.

        ``q`` and ``qdot`` of shape ``(m,)`` -> float, ``(m, S)`` -> ``(S,)``.
        """
        qa = _as_state("q", q, self.n_modes)
        va = _as_state("qdot", qdot, self.n_modes)
        if qa.shape != va.shape:
            raise ValidationError("qdot", f"array of shape {va.shape}", f"shape {qa.shape}")
        total = self.core_system().energy(qa.reshape(self.n_modes, -1), va.reshape(self.n_modes, -1))
        return float(total[0]) if qa.ndim == 1 else total

    def duffing(self) -> DuffingCoefficients:
        """``a1, a2, a3`` of eq. 19 for a one-mode model (divided by ``int phi_1^2 = l/2``).

        Equal to the corrected eq. 20: ``a1 = k1``, ``a2 = k2 pi^2/l^2 - k6``,
        ``a3 = 3 k3/4 + k4 pi^2/(2 l^2) + 3 k5 pi^4/(4 l^4)``.

        Computed by the core (``_core.duffing``).

        Raises
        ------
        ValidationError
            Unless the model is the single mode ``i = 1`` (``modes=1, rigid_mode=False``).
        """
        a1, a2, a3 = _core.duffing(
            self.indices, self.mass, self.stiffness, self.quartic_coef, self.length
        )
        return DuffingCoefficients(a1=a1, a2=a2, a3=a3)

    # ------------------------------------------------------------------ fields

    def basis(self, z: ArrayLike) -> FloatArray:
        """``phi_k(z) = cos(i_k pi z / l)`` as a ``(len(z), m)`` array (the core's mode shapes,
        which sweeps evaluate too)."""
        za = _as_positions("z", z)
        return _core.mode_shapes(self.indices, self.length, za)

    def basis_derivative(self, z: ArrayLike) -> FloatArray:
        """``phi_k'(z) = -(i_k pi / l) sin(i_k pi z / l)`` as a ``(len(z), m)`` array."""
        za = _as_positions("z", z)
        return _core.mode_shapes(self.indices, self.length, za, slope=True)

    def twist(self, q: ArrayLike, z: ArrayLike) -> FloatArray:
        """``theta(z) = sum_k q_k phi_k(z)``: ``(len(z),)`` for ``q (m,)``, else ``(len(z), S)``."""
        qa = _as_state("q", q, self.n_modes)
        return self.basis(z) @ qa

    def initial_state(self, params: Parameters) -> tuple[FloatArray, FloatArray]:
        """Initial ``(q(0), q'(0))`` from eq. 13 (eq. 21 for one mode).

        ``theta(z, 0) = 0`` gives ``q(0) = 0``. ``theta_t(z, 0) = sum_i C_i cos(i pi z / l)``
        projected onto the retained basis (orthogonality) gives ``q_k'(0) = C_{i_k}`` for
        ``1 <= i_k <= len(C)`` and ``0`` otherwise, in particular ``0`` for the rigid mode.
        Velocities ``C_i`` with ``i > n`` are not representable in the basis and are dropped
        (this *is* their Galerkin projection, not an error).
        """
        velocities = params.initial_velocities
        q0 = np.zeros(self.n_modes)
        v0 = np.zeros(self.n_modes)
        for k, i in enumerate(self.indices.tolist()):
            if 1 <= i <= len(velocities):
                v0[k] = velocities[i - 1]
        return q0, v0


def project(
    source: Parameters | PDECoefficients, modes: int = 3, rigid_mode: bool = False
) -> ModalCoefficients:
    """Bubnov-Galerkin model of eq. 18 on ``modes`` cosine modes (plus ``i = 0`` if asked).

    Parameters
    ----------
    source:
        A :class:`~drillstring.model.parameters.Parameters` (``k1..k6`` from eq. 17) or explicit
        :class:`~drillstring.model.coefficients.PDECoefficients`.
    modes:
        Number ``n`` of elastic modes ``i = 1..n``, ``1 <= n <= 256``.
    rigid_mode:
        Also include the rigid mode ``i = 0`` (first position).

    Raises
    ------
    ValidationError
        For a bad ``modes`` or ``rigid_mode``.
    """
    if isinstance(source, PDECoefficients):
        return ModalCoefficients.from_coefficients(source, modes, rigid_mode)
    return ModalCoefficients.from_parameters(source, modes, rigid_mode)
