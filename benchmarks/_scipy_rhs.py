"""The right-hand side scipy's ``solve_ivp`` gets in the benchmarks: the fastest numpy version of
a Galerkin modal model we found.

The quartic potential's gradient is a sum over its terms (``quartic_index``, ``quartic_coef``). A
term-by-term numpy version needs four ``np.add.at`` scatters per call (about 10-15 us at 3 modes).
Here the terms are folded once into a dense matrix over the cubic monomials ``q_i q_j q_k``
(i <= j <= k), so one call is three gathers, two products and one small matrix-vector product
(about 4 us at 3 modes; the monomial count grows like n^3 / 6, which is fine for the few modes the
benchmarks give scipy). A plain-Python-float version was about as fast at 3 modes, within the machine's noise.
``modal_rhs`` checks the folded form (unless told not to) against the term-by-term sum at a random state before
returning it.
"""

from __future__ import annotations

import itertools
from typing import Any, Callable

import numpy as np


def _termwise(coeff: Any) -> Callable[[float, np.ndarray], np.ndarray]:
    m = len(coeff.mass)
    inv_mass = 1.0 / coeff.mass
    k_over_m = coeff.stiffness * inv_mass
    a, b, c, d = (coeff.quartic_index[:, j] for j in range(4))
    cm = coeff.quartic_coef

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:m], y[m:]
        qa, qb, qc, qd = q[a], q[b], q[c], q[d]
        force = np.zeros(m)
        np.add.at(force, a, cm * qb * qc * qd)
        np.add.at(force, b, cm * qa * qc * qd)
        np.add.at(force, c, cm * qa * qb * qd)
        np.add.at(force, d, cm * qa * qb * qc)
        return np.concatenate([v, -k_over_m * q - force * inv_mass])

    return rhs


def modal_rhs(coeff: Any, check: bool = True) -> Callable[[float, np.ndarray], np.ndarray]:
    """``rhs(t, y)`` with ``y = (q, qdot)`` for ``solve_ivp``, for a ``GalerkinCoefficients``;
    ``check=False`` skips the comparison with the term-by-term sum (for timed loops)."""
    m = len(coeff.mass)
    monomials = list(itertools.combinations_with_replacement(range(m), 3))
    column = {mono: p for p, mono in enumerate(monomials)}
    dense = np.zeros((m, len(monomials)))
    for row, value in zip(coeff.quartic_index.tolist(), coeff.quartic_coef.tolist()):
        for k in range(4):  # d/dq_row[k] of value * q_a q_b q_c q_d
            dense[row[k], column[tuple(sorted(row[:k] + row[k + 1:]))]] += value
    dense_t = np.ascontiguousarray((-dense / coeff.mass[:, None]).T)
    i, j, k = (np.array([mono[p] for mono in monomials], dtype=np.intp) for p in range(3))
    minus_k_over_m = -coeff.stiffness / coeff.mass

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q = y[:m]
        return np.concatenate([y[m:], minus_k_over_m * q + (q[i] * q[j] * q[k]) @ dense_t])

    if not check:
        return rhs
    y = np.random.default_rng(0).normal(size=2 * m)
    expected, got = _termwise(coeff)(0.0, y), rhs(0.0, y)
    if not np.allclose(got, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max()):
        raise AssertionError(f"folded rhs differs from the term-by-term sum: {np.abs(got - expected).max()}")
    return rhs
