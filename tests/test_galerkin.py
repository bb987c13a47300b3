"""Tests of drillstring.model.galerkin: the Bubnov-Galerkin projection of eq. 18.

Every number here comes from the core; the tests compare it with a closed form, SymPy, a
quadrature or the numpy oracles of ``tests/oracles.py``, never with another path of the core.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import pickle
from typing import Any

import numpy as np
import oracles
import pytest
import sympy as sp

import drillstring as ds
from drillstring.errors import ValidationError
from drillstring.model import galerkin
from drillstring.model.coefficients import PDECoefficients
from drillstring.model.galerkin import ModalCoefficients, dimensionless_integrals, mode_numbers, project
from drillstring.model.parameters import Parameters, preset

RNG_SEED = 20240611


def _random_coefficients(rng: np.random.Generator) -> PDECoefficients:
    """Arbitrary k1..k6 and l of order one (k5 of either sign), to exercise every term."""
    k = rng.uniform(0.5, 2.0, size=6)
    k[4] *= rng.choice([-1.0, 1.0])
    return PDECoefficients(*k, length=float(rng.uniform(0.5, 3.0)))


# ------------------------------------------------------------------------ eq. 19, 20


@pytest.mark.parametrize("variant", ["paper", "energy"])
@pytest.mark.parametrize("length", [1.0, 100.0, 250.0, 500.0])
def test_one_mode_duffing_is_corrected_eq_20(variant: str, length: float) -> None:
    params = preset("steel" if length == 250.0 else "aluminum").replace(
        length=length, k5_variant=variant
    )
    k = PDECoefficients.from_parameters(params)
    a1, a2, a3 = project(params, modes=1).duffing()
    l2 = length**2
    assert a1 == pytest.approx(k.k1, rel=1e-12)
    assert a2 == pytest.approx(k.k2 * math.pi**2 / l2 - k.k6, rel=1e-12)
    assert a3 == pytest.approx(
        3 * k.k3 / 4 + k.k4 * math.pi**2 / (2 * l2) + 3 * k.k5 * math.pi**4 / (4 * l2**2),
        rel=1e-12,
    )


def test_duffing_with_random_coefficients() -> None:
    rng = np.random.default_rng(RNG_SEED)
    for _ in range(5):
        k = _random_coefficients(rng)
        a = ModalCoefficients.from_coefficients(k, modes=1).duffing()
        lp = math.pi / k.length
        expected = (
            k.k1,
            k.k2 * lp**2 - k.k6,
            0.75 * k.k3 + k.k4 * lp**2 / 2 + 0.75 * k.k5 * lp**4,
        )
        np.testing.assert_allclose(a, expected, rtol=1e-12)


@pytest.mark.parametrize(("modes", "rigid"), [(2, False), (1, True), (3, True)])
def test_duffing_needs_single_mode(modes: int, rigid: bool) -> None:
    with pytest.raises(ValidationError, match="modes"):
        project(Parameters(), modes=modes, rigid_mode=rigid).duffing()


# ------------------------------------------------------------------------ SymPy projection

SYM_MODES = (0, 1, 2, 3)


@pytest.fixture(scope="module")
def symbolic() -> dict[str, Any]:
    """Symbolic Galerkin projection of eq. 18 on cos(i pi z/l), i = 0..3, and its energy.

    Smaller bases are obtained by setting the absent q_i to zero (the projection of the
    truncated field onto a retained phi_j is the same integral). The z-derivatives are taken
    by SymPy on the cosines; for the integrals the trigonometric polynomial is written in
    X = exp(i pi z/l) (z = l s) and each power X^k is integrated by SymPy over s in [0, 1].
    """
    z, l, s = sp.symbols("z l s", positive=True)
    x = sp.Symbol("X")
    ks = sp.symbols("k1:7", real=True)
    k1, k2, k3, k4, k5, k6 = ks
    q = sp.symbols(f"q0:{len(SYM_MODES)}", real=True)
    v = sp.symbols(f"v0:{len(SYM_MODES)}", real=True)
    phi = [sp.cos(i * sp.pi * z / l) for i in SYM_MODES]
    th = sum(qi * p for qi, p in zip(q, phi))
    th_t = sum(vi * p for vi, p in zip(v, phi))
    th_z = sp.diff(th, z)
    th_zz = sp.diff(th, z, 2)
    # eq. 18: k1 theta_tt = RHS
    rhs = (
        k2 * th_zz
        - k3 * th**3
        + k4 * (th**2 * th_zz + th * th_z**2)
        + k5 * sp.diff(th_z**3, z)
        + k6 * th
    )
    density = (
        k1 / 2 * th_t**2
        + k2 / 2 * th_z**2
        + k3 / 4 * th**4
        + k4 / 2 * th**2 * th_z**2
        + k5 / 4 * th_z**4
        - k6 / 2 * th**2
    )

    def laurent(expr: Any) -> Any:
        """Substitute z = l s and exp(i pi k s) -> X^k."""
        expo = expr.subs(z, l * s).rewrite(sp.exp)
        return expo.replace(
            lambda a: isinstance(a, sp.exp),
            lambda a: x ** sp.cancel(a.args[0] / (sp.I * sp.pi * s)),
        )

    gens = (x, 1 / x, *q, *v, *ks, l, 1 / l, sp.pi)
    cache: dict[int, Any] = {}

    def to_poly(expr: Any) -> sp.Poly:
        """Build the polynomial structurally (much faster than expanding the expression)."""
        if expr in gens or expr.is_Number or expr == sp.I:
            return sp.Poly(expr, *gens, domain="QQ_I")
        if expr.is_Add or expr.is_Mul:
            parts = [to_poly(a) for a in expr.args]
            result = parts[0]
            for part in parts[1:]:
                result = result + part if expr.is_Add else result * part
            return result
        if expr.is_Pow and expr.exp.is_Integer:
            if expr.exp < 0:
                return sp.Poly(1 / expr.base, *gens, domain="QQ_I") ** int(-expr.exp)
            return to_poly(expr.base) ** int(expr.exp)
        raise AssertionError(f"not a polynomial term: {expr}")

    def integrate(expr: Any) -> Any:
        """int_0^l expr dz = l int_0^1 (...) ds, for a Laurent polynomial in X."""
        poly = to_poly(expr)
        total = []
        for powers, coef in poly.terms():
            k = powers[0] - powers[1]
            if k not in cache:
                cos_part = sp.integrate(sp.cos(k * sp.pi * s), (s, 0, 1))
                sin_part = sp.integrate(sp.sin(k * sp.pi * s), (s, 0, 1))
                cache[k] = l * (cos_part + sp.I * sin_part)
            total.append(cache[k] * coef * sp.Mul(*(g**e for g, e in zip(gens[2:], powers[2:]))))
        result = sp.expand(sp.Add(*total))
        assert sp.im(result) == 0
        return result

    rhs_x = laurent(rhs)
    phi_x = [laurent(p) for p in phi]
    projected = [integrate(rhs_x * p) for p in phi_x]
    gram = [[integrate(pi * pj) for pj in phi_x] for pi in phi_x]
    energy = integrate(laurent(density))
    args = (*ks, l, *q)
    jacobian = sp.Matrix(projected).jacobian(q).subs(dict.fromkeys(q, 0))
    return {
        "projected": sp.lambdify(args, projected, "math"),
        "jacobian": sp.lambdify(args, jacobian),
        "gram": sp.lambdify((l,), gram),
        "energy": sp.lambdify((*ks, l, *q, *v), energy, "math"),
    }


BASES = [(n, rigid) for rigid in (False, True) for n in (1, 2, 3)]


@pytest.mark.slow
@pytest.mark.parametrize(("n", "rigid"), BASES)
def test_projection_matches_sympy(symbolic: dict[str, Any], n: int, rigid: bool) -> None:
    rng = np.random.default_rng([RNG_SEED, n, rigid])
    modes = mode_numbers(n, rigid)
    keep = [SYM_MODES.index(i) for i in modes]
    for _ in range(3):
        k = _random_coefficients(rng)
        model = ModalCoefficients.from_coefficients(k, modes=n, rigid_mode=rigid)
        np.testing.assert_array_equal(model.indices, modes)
        full_q = np.zeros(len(SYM_MODES))
        full_q[keep] = rng.normal(scale=0.7, size=len(keep))
        q = full_q[keep]
        args = (*k.as_tuple(), k.length, *full_q)

        # mass: M_ij = k1 int phi_i phi_j (off-diagonal zeros included)
        gram = np.array(symbolic["gram"](k.length), dtype=float)[np.ix_(keep, keep)]
        np.testing.assert_allclose(model.mass_matrix, k.k1 * gram, rtol=1e-12, atol=1e-14)
        # stiffness: -d(projection)/dq at q = 0
        jac = np.array(symbolic["jacobian"](*args), dtype=float)[np.ix_(keep, keep)]
        np.testing.assert_allclose(model.stiffness_matrix, -jac, rtol=1e-12, atol=1e-12)
        # full projection: int RHS phi_j dz = -(K q + grad V)_j
        proj = np.array(symbolic["projected"](*args), dtype=float)[keep]
        linear = jac @ q
        np.testing.assert_allclose(-(model.stiffness * q + model.cubic_force(q)), proj, rtol=1e-10)
        np.testing.assert_allclose(
            -model.cubic_force(q), proj - linear, rtol=1e-10, atol=1e-12 * np.abs(proj).max()
        )


@pytest.mark.slow
@pytest.mark.parametrize(("n", "rigid"), BASES)
def test_energy_matches_sympy(symbolic: dict[str, Any], n: int, rigid: bool) -> None:
    rng = np.random.default_rng([RNG_SEED, 7, n, rigid])
    keep = [SYM_MODES.index(i) for i in mode_numbers(n, rigid)]
    k = _random_coefficients(rng)
    model = ModalCoefficients.from_coefficients(k, modes=n, rigid_mode=rigid)
    q = np.zeros(len(SYM_MODES))
    v = np.zeros(len(SYM_MODES))
    q[keep] = rng.normal(size=len(keep))
    v[keep] = rng.normal(size=len(keep))
    expected = symbolic["energy"](*k.as_tuple(), k.length, *q, *v)
    assert model.energy(q[keep], v[keep]) == pytest.approx(expected, rel=1e-11)


# ------------------------------------------------------------------------ internal consistency


def test_core_force_and_potential_are_the_dense_tensor_contractions() -> None:
    """The numpy oracle's dense tensor of the compact terms, contracted, gives the core's force
    and potential."""
    rng = np.random.default_rng(RNG_SEED)
    model = ModalCoefficients.from_coefficients(_random_coefficients(rng), 4, rigid_mode=True)
    m = model.n_modes
    t = oracles.cubic_tensor(model.quartic_index, model.quartic_coef, m)
    assert t.shape == (m, m, m, m)
    for perm in itertools.permutations(range(4)):
        np.testing.assert_array_equal(t, t.transpose(perm))
    # each compact term is the sum of the tensor entries over its orderings, / 4
    seen = np.zeros(t.shape, dtype=bool)
    for idx, coef in zip(model.quartic_index, model.quartic_coef):
        orderings = set(itertools.permutations(idx.tolist()))
        assert sum(t[o] for o in orderings) / 4 == pytest.approx(coef, rel=1e-13)
        for o in orderings:
            seen[o] = True
    assert np.all(t[~seen] == 0.0)
    for _ in range(3):
        q = rng.normal(size=m)
        force = np.einsum("jbcd,b,c,d->j", t, q, q, q)
        np.testing.assert_allclose(model.cubic_force(q), force, rtol=1e-12)
        assert model.potential(q) == pytest.approx(np.einsum("abcd,a,b,c,d", t, q, q, q, q) / 4)


def test_gradient_matches_finite_differences() -> None:
    rng = np.random.default_rng(RNG_SEED + 1)
    model = ModalCoefficients.from_coefficients(_random_coefficients(rng), 5, rigid_mode=True)
    q = rng.normal(size=model.n_modes)
    h = 1e-5
    fd = np.array(
        [
            (model.potential(q + h * e) - model.potential(q - h * e)) / (2 * h)
            for e in np.eye(model.n_modes)
        ]
    )
    np.testing.assert_allclose(model.cubic_force(q), fd, rtol=1e-8)


@pytest.mark.parametrize(("modes", "rigid"), [(1, False), (3, False), (4, True), (9, True)])
def test_force_and_acceleration_match_the_numpy_oracle(modes: int, rigid: bool) -> None:
    """The core's force and acceleration (term sum below the spectral crossover, spectral from
    it) against the former numpy evaluation, for one state and for columns of states."""
    model = project(preset("aluminum").replace(length=2.0), modes=modes, rigid_mode=rigid)
    rng = np.random.default_rng(3 + modes)
    q = rng.normal(scale=0.3, size=(model.n_modes, 7))
    args = (model.quartic_index, model.quartic_coef)
    force = oracles.cubic_force(*args, q)
    acc = oracles.modal_acceleration(model.mass, model.stiffness, *args, q)
    scale = oracles.cubic_force(model.quartic_index, np.abs(model.quartic_coef), np.abs(q))
    linear = np.abs(model.stiffness[:, None] * q)
    got_force, got_acc = model.cubic_force(q), model.acceleration(q)
    assert got_force.shape == q.shape and got_acc.shape == q.shape
    assert np.all(np.abs(got_force - force) <= 1e-13 * scale)
    assert np.all(np.abs(got_acc - acc) <= 1e-13 * (scale + linear) / model.mass[:, None])
    one = model.cubic_force(q[:, 0])
    assert one.shape == (model.n_modes,)
    assert np.all(np.abs(one - force[:, 0]) <= 1e-13 * scale[:, 0])


def test_bad_state_shapes() -> None:
    model = project(Parameters(), modes=3)
    with pytest.raises(ValidationError, match="q"):
        model.cubic_force(np.zeros(4))
    with pytest.raises(ValidationError, match="qdot"):
        model.energy(np.zeros(3), np.zeros((3, 2)))
    with pytest.raises(ValidationError, match="z"):
        model.basis(np.zeros((2, 2)))


def test_selection_rule_odd_modes_stay_odd() -> None:
    rng = np.random.default_rng(5)
    model = ModalCoefficients.from_coefficients(_random_coefficients(rng), 7, rigid_mode=True)
    odd = model.indices % 2 == 1
    q = np.where(odd, rng.normal(size=model.n_modes), 0.0)
    terms = model.core_system(evaluation="terms")
    force = terms.quartic_gradient(q)
    assert np.all(force[~odd] == 0.0)
    assert np.all(np.abs(force[odd]) > 0.0)
    # the spectral evaluation (8 retained modes) forces the even modes only by round-off
    spectral = model.cubic_force(q)
    assert model.core_system().evaluation == "spectral"
    assert np.all(np.abs(spectral[~odd]) <= 1e-13 * np.abs(force).max())
    # with an even mode moving, the rigid mode and the other even modes are forced
    q_even = q.copy()
    q_even[model.indices == 2] = 0.3
    force_even = terms.quartic_gradient(q_even)
    assert np.all(np.abs(force_even[~odd]) > 0.0)
    # theta -> -theta symmetry
    np.testing.assert_array_equal(terms.quartic_gradient(-q_even), -force_even)
    # every stored term obeys i_a + i_b + i_c + i_d even
    assert np.all(model.indices[model.quartic_index].sum(axis=1) % 2 == 0)


def _gauss_legendre(points: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(points)
    return (x + 1) / 2, w / 2  # on [0, 1]


def test_integrals_match_quadrature() -> None:
    integrals = dimensionless_integrals(6, rigid_mode=True)
    s, w = _gauss_legendre(64)
    i = integrals.indices
    c = np.cos(np.pi * np.outer(i, s))  # (m, points)
    sn = np.sin(np.pi * np.outer(i, s))
    stored = {tuple(t): k for k, t in enumerate(integrals.quartic_index.tolist())}
    m = len(i)
    for quad in itertools.combinations_with_replacement(range(m), 4):
        orderings = set(itertools.permutations(quad))
        cos4 = sum(np.sum(w * c[a] * c[b] * c[cc] * c[d]) for a, b, cc, d in orderings)
        mixed = sum(
            i[cc] * i[d] * np.sum(w * c[a] * c[b] * sn[cc] * sn[d]) for a, b, cc, d in orderings
        )
        sin4 = sum(
            i[a] * i[b] * i[cc] * i[d] * np.sum(w * sn[a] * sn[b] * sn[cc] * sn[d])
            for a, b, cc, d in orderings
        )
        if quad in stored:
            k = stored[quad]
            assert integrals.cos4[k] == pytest.approx(cos4, abs=1e-12)
            assert integrals.mixed[k] == pytest.approx(mixed, abs=1e-11)
            assert integrals.sin4[k] == pytest.approx(sin4, abs=1e-9)
            assert integrals.cos4[k] > 0
        else:
            assert abs(cos4) < 1e-12 and abs(mixed) < 1e-11 and abs(sin4) < 1e-9


def test_potential_matches_quadrature_of_energy_density() -> None:
    rng = np.random.default_rng(11)
    k = _random_coefficients(rng)
    model = ModalCoefficients.from_coefficients(k, 6, rigid_mode=True)
    s, w = _gauss_legendre(80)
    z = s * k.length
    for _ in range(3):
        q = rng.normal(size=model.n_modes)
        th = model.twist(q, z)
        th_z = model.basis_derivative(z) @ q
        density = k.k3 / 4 * th**4 + k.k4 / 2 * th**2 * th_z**2 + k.k5 / 4 * th_z**4
        assert model.potential(q) == pytest.approx(k.length * np.sum(w * density), rel=1e-12)


def test_large_basis_is_cached_and_read_only() -> None:
    galerkin._cached_integrals.cache_clear()
    integrals = dimensionless_integrals(40, rigid_mode=True)
    assert dimensionless_integrals(40, True) is integrals
    assert integrals.indices.tolist() == list(range(41))
    assert integrals.rigid_mode
    for array in (integrals.quartic_index, integrals.cos4, integrals.mixed, integrals.sin4):
        assert not array.flags.writeable
        with pytest.raises(ValueError):
            array[0] = 1
    qi = integrals.quartic_index
    assert qi.dtype == np.int64 and qi.shape == (integrals.n_terms, 4)
    assert np.all(np.diff(qi, axis=1) >= 0)
    keys = [tuple(row) for row in qi.tolist()]
    assert keys == sorted(set(keys))
    model = project(Parameters(), modes=40, rigid_mode=True)
    assert not model.quartic_coef.flags.writeable


def test_linear_frequencies() -> None:
    params = preset("steel").replace(length=250.0)
    model = project(params, modes=5, rigid_mode=True)
    # closed form of the material: w_i^2 = (i pi c / l)^2 - Omega^2, c = 2 sqrt(G / rho)
    g = params.youngs_modulus / (2 * (1 + params.poisson_ratio))
    c = 2 * math.sqrt(g / params.density)
    i = np.arange(0, 6)
    w2 = (i * math.pi * c / 250.0) ** 2 - params.omega**2
    w = model.linear_frequencies
    assert math.isnan(w[0])
    np.testing.assert_allclose(w[1:], np.sqrt(w2[1:]), rtol=1e-13)
    # without rotation the free-free string: w_i = i pi c / l, the rigid mode at rest
    still = project(params.replace(omega=0.0), modes=2, rigid_mode=True)
    np.testing.assert_allclose(still.linear_frequencies, np.arange(3) * math.pi * c / 250.0, rtol=1e-13)
    assert still.linear_frequencies[0] == 0.0
    # the numpy oracle of the diagonals: sqrt(K / M) where K >= 0, bit for bit
    w2_model = model.stiffness / model.mass
    assert np.array_equal(w, np.sqrt(np.where(w2_model >= 0, w2_model, np.nan)), equal_nan=True)


def test_duffing_frequency_of_the_one_mode_solve() -> None:
    """The one-mode core solve oscillates at the exact frequency of the Duffing equation with eq.
    20's coefficients: ``w = pi sqrt(w0^2 + beta A^2) / (2 K(m))``, ``m = beta A^2 / (2 (w0^2 +
    beta A^2))``, the amplitude ``A`` from the energy ``w0^2 A^2 / 2 + beta A^4 / 4 = v0^2 / 2``."""
    from scipy.special import ellipk

    params = preset("aluminum")
    a1, a2, a3 = project(params, modes=1).duffing()
    w0sq, beta, v0 = a2 / a1, a3 / a1, params.initial_velocities[0]
    a_sq = (-w0sq / 2 + math.sqrt(w0sq**2 / 4 + beta * v0**2 / 2)) / (beta / 2)
    stiff = w0sq + beta * a_sq
    expected = math.pi * math.sqrt(stiff) / (2 * float(ellipk(beta * a_sq / (2 * stiff))))
    res = ds.simulate(params, modes=1, t_end=0.5, rtol=1e-12, atol=1e-15, samples=20001)
    q = res.q[0]
    down = np.nonzero((q[:-1] > 0) & (q[1:] <= 0))[0]  # crossings from + to -: one per period
    t = res.t[down] - q[down] * (res.t[down + 1] - res.t[down]) / (q[down + 1] - q[down])
    frequency = 2 * math.pi / float(np.mean(np.diff(t)))
    assert frequency == pytest.approx(expected, rel=1e-7)
    assert abs(expected / math.sqrt(w0sq) - 1) > 1e-5  # the nonlinear shift is resolved


def test_mass_and_stiffness_closed_forms() -> None:
    params = Parameters()
    k = PDECoefficients.from_parameters(params)
    model = project(params, modes=3, rigid_mode=True)
    l = params.length
    np.testing.assert_allclose(model.mass, k.k1 * np.array([l, l / 2, l / 2, l / 2]), rtol=1e-15)
    i = np.arange(1, 4)
    np.testing.assert_allclose(
        model.stiffness,
        np.concatenate([[-k.k6 * l], k.k2 * (i * np.pi) ** 2 / (2 * l) - k.k6 * l / 2]),
        rtol=1e-13,
    )


def test_basis_and_derivative() -> None:
    model = project(Parameters(length=3.0), modes=3, rigid_mode=True)
    z = np.linspace(0.0, 3.0, 11)
    phi = model.basis(z)
    # the core's mode shapes are the former numpy evaluation, bit for bit
    shapes, slopes = oracles.mode_shapes(model.indices, 3.0, z)
    assert np.array_equal(phi, shapes) and np.array_equal(model.basis_derivative(z), slopes)
    assert phi.shape == (11, 4)
    np.testing.assert_allclose(phi[:, 0], 1.0)
    np.testing.assert_allclose(phi[:, 2], np.cos(2 * np.pi * z / 3.0), atol=1e-15)
    dphi = model.basis_derivative(z)
    np.testing.assert_allclose(dphi[[0, -1]], 0.0, atol=1e-14)  # eq. 14
    h = 1e-6
    np.testing.assert_allclose(dphi, (model.basis(z + h) - model.basis(z - h)) / (2 * h), atol=1e-8)
    assert model.basis(1.5).shape == (1, 4)
    q = np.array([0.1, 0.2, -0.3, 0.05])
    np.testing.assert_allclose(model.twist(q, z), phi @ q)


@pytest.mark.parametrize(
    ("modes", "rigid", "expected"),
    [
        (1, False, [0.1]),
        (2, True, [0.0, 0.1, 0.05]),
        (3, False, [0.1, 0.05, 0.02]),
        (5, True, [0.0, 0.1, 0.05, 0.02, 0.0, 0.0]),
    ],
)
def test_initial_state_projects_eq_13(modes: int, rigid: bool, expected: list[float]) -> None:
    params = preset("aluminum")
    model = project(params, modes=modes, rigid_mode=rigid)
    q0, v0 = model.initial_state(params)
    np.testing.assert_array_equal(q0, np.zeros(len(expected)))
    np.testing.assert_array_equal(v0, expected)
    # the modal velocities are the L2 projection of sum C_i cos(i pi z/l) onto the basis
    s, w = _gauss_legendre(60)
    z = s * params.length
    field = sum(
        c * np.cos((i + 1) * np.pi * z / params.length) for i, c in enumerate([0.1, 0.05, 0.02])
    )
    phi = model.basis(z)
    projection = (phi.T @ (w * field)) / (phi.T**2 @ w)
    np.testing.assert_allclose(v0, projection, atol=1e-14)


@pytest.mark.parametrize("modes", [0, -1, 257, True, 2.0, "3", None])
def test_bad_modes(modes: Any) -> None:
    with pytest.raises(ValidationError) as info:
        project(Parameters(), modes=modes)
    assert info.value.field == "modes" and "modes" in str(info.value)


@pytest.mark.parametrize("rigid", [1, 0, "yes", None])
def test_bad_rigid_mode(rigid: Any) -> None:
    with pytest.raises(ValidationError) as info:
        dimensionless_integrals(2, rigid_mode=rigid)
    assert info.value.field == "rigid_mode"


def test_from_parameters_equals_project() -> None:
    params = preset("steel")
    a = ModalCoefficients.from_parameters(params, modes=2, rigid_mode=True)
    b = project(PDECoefficients.from_parameters(params), modes=2, rigid_mode=True)
    for name in ("indices", "mass", "stiffness", "quartic_index", "quartic_coef"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.length == b.length == 100.0


def test_model_without_quartic_terms_is_linear() -> None:
    """A copy with no quartic terms (the linearised model) gives float zeros, not ints."""
    model = project(preset("aluminum"), modes=3, rigid_mode=True)
    linear = dataclasses.replace(
        model, quartic_index=np.zeros((0, 4), dtype=np.int64), quartic_coef=np.zeros(0)
    )
    q = np.array([0.1, -0.2, 0.3, 0.05])
    for state in (q, np.stack([q, 2 * q], axis=1)):
        force = linear.cubic_force(state)
        assert force.dtype == np.float64 and force.shape == state.shape
        assert np.all(force == 0.0)
    assert linear.potential(q) == 0.0
    assert linear.energy(q, q) == pytest.approx(0.5 * np.sum((model.mass + model.stiffness) * q**2))
    assert linear.energy(q, q) != model.energy(q, q)


# ------------------------------------------------------------------------ the core's numbers


@pytest.mark.parametrize(("modes", "rigid"), [(1, False), (3, False), (4, True), (9, False)])
def test_energy_and_potential_match_numpy_oracle(modes: int, rigid: bool) -> None:
    rng = np.random.default_rng(RNG_SEED + modes)
    model = project(_random_coefficients(rng), modes, rigid)
    m = model.n_modes
    q, v = rng.normal(size=(m, 11)), rng.normal(size=(m, 11))
    args = (model.quartic_index, model.quartic_coef)
    scale = oracles.modal_potential(model.quartic_index, np.abs(model.quartic_coef), np.abs(q))
    assert np.all(np.abs(model.potential(q) - oracles.modal_potential(*args, q)) <= 1e-14 * scale)
    h = oracles.modal_energy(model.mass, model.stiffness, *args, q, v)
    quadratic = oracles.modal_energies(np.abs(model.mass), np.abs(model.stiffness), q, v).sum(axis=0)
    assert np.all(np.abs(model.energy(q, v) - h) <= 1e-14 * (quadratic + scale))
    for s in (0, 10):  # one state -> float
        assert isinstance(model.potential(q[:, s]), float)
        assert model.energy(q[:, s], v[:, s]) == model.energy(q, v)[s]
        assert model.potential(q[:, s]) == model.potential(q)[s]
    # non-contiguous views give the same numbers
    assert np.array_equal(model.energy(q[:, ::2], v[:, ::2]), model.energy(q, v)[::2])
    # the model stays a plain value
    assert np.array_equal(pickle.loads(pickle.dumps(model)).energy(q, v), model.energy(q, v))


@pytest.mark.parametrize(("modes", "rigid"), [(3, False), (9, True)])
def test_energy_is_conserved_along_a_solution(modes: int, rigid: bool) -> None:
    """H of the modal model stays constant along an undamped solve (to the tolerance), and its
    quartic part is a visible share of it (the test would see a wrong V)."""
    params = preset("steel").replace(initial_velocities=(2.0, 1.0, 0.5))
    model = project(params, modes, rigid)
    res = ds.simulate(params, modes=modes, rigid_mode=rigid, t_end=0.2, rtol=1e-12, atol=1e-14, samples=200)
    h = np.asarray(model.energy(res.q, res.qdot))
    assert np.max(np.abs(h - h[0])) <= 1e-9 * abs(h[0])
    assert np.max(np.abs(model.potential(res.q))) > 1e-6 * abs(h[0])
    with pytest.raises(ValidationError) as info:
        model.core_system().potential(np.zeros((2, 5)))
    assert info.value.field == "q"


@pytest.mark.parametrize("name", ["aluminum", "steel"])
@pytest.mark.parametrize("model_name", ["paper", "consistent"])
@pytest.mark.parametrize(("modes", "rigid"), [(1, False), (3, False), (6, True)])
def test_projection_scaling_of_presets_is_the_numpy_one(name: str, model_name: str, modes: int, rigid: bool) -> None:
    """The core's scaling of the integrals (the one a sweep uses) gives the numpy numbers,
    bit for bit at the presets' lengths."""
    params = preset(name).replace(model=model_name)
    k = PDECoefficients.from_parameters(params)
    g = dimensionless_integrals(modes, rigid)
    expected = oracles.galerkin_scaling(k.as_tuple(), k.length, g.indices, g.cos4, g.mixed, g.sin4)
    model = project(params, modes, rigid)
    for got, want in zip((model.mass, model.stiffness, model.quartic_coef), expected):
        assert np.array_equal(got, want)


@pytest.mark.parametrize(
    ("modes", "rigid"), [(1, False), (1, True), (2, False), (3, True), (7, False), (16, True), (33, False)]
)
def test_core_integrals_equal_the_numpy_generator(modes: int, rigid: bool) -> None:
    """The core's integrals are the former numpy generator's, exactly (same terms, same order)."""
    g = dimensionless_integrals(modes, rigid)
    indices, quartic_index, cos4, mixed, sin4 = oracles.galerkin_integrals(modes, rigid)
    assert g.indices.dtype == np.int64 and g.quartic_index.dtype == np.int64
    assert np.array_equal(g.indices, indices) and np.array_equal(g.quartic_index, quartic_index)
    for got, want in zip((g.cos4, g.mixed, g.sin4), (cos4, mixed, sin4)):
        assert got.dtype == np.float64 and np.array_equal(got, want)


def test_projection_of_random_coefficients_matches_numpy_oracle() -> None:
    """Equal to rounding: the core takes ``l^3`` as ``l * l * l``, numpy as ``pow(l, 3)``."""
    rng = np.random.default_rng(RNG_SEED)
    eps = np.finfo(float).eps
    for _ in range(200):
        k = _random_coefficients(rng)
        k = dataclasses.replace(k, length=float(10 ** rng.uniform(-1.0, 4.0)))
        modes, rigid = int(rng.integers(1, 9)), bool(rng.random() < 0.5)
        g = dimensionless_integrals(modes, rigid)
        mass, stiffness, coef = oracles.galerkin_scaling(k.as_tuple(), k.length, g.indices, g.cos4, g.mixed, g.sin4)
        *_, scale = oracles.galerkin_scaling(
            tuple(abs(x) for x in k.as_tuple()), k.length, g.indices, g.cos4, np.abs(g.mixed), np.abs(g.sin4)
        )
        model = project(k, modes, rigid)
        assert np.array_equal(model.mass, mass) and np.array_equal(model.stiffness, stiffness)
        assert np.all(np.abs(model.quartic_coef - coef) <= 8 * eps * scale)


@pytest.mark.parametrize(
    "change",
    [{"k1": 1e308, "length": 1e10}, {"k2": 1e300, "length": 1e-10}, {"k3": 1e300, "length": 1e300},
     {"k5": 1.0, "length": 1e-120}],
)
def test_projection_that_overflows_names_the_coefficients(change: dict[str, float]) -> None:
    k = dataclasses.replace(PDECoefficients(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, length=1.0), **change)
    with pytest.raises(ValidationError) as info:
        project(k, 2)
    assert info.value.field == "coefficients"
    assert "Galerkin projection is finite" in str(info.value)
