"""Linear stability of the equilibrium (paper sec. 3.6): drillstring.studies.stability."""

from __future__ import annotations

import math

import numpy as np
import oracles
import pytest

import drillstring as ds
from drillstring.errors import ValidationError
from drillstring.model.coefficients import PDECoefficients, shear_modulus
from drillstring.studies.stability import analyse, jacobian


def test_one_mode_eigenvalues_are_eq_29():
    params = ds.preset("aluminum")
    coefficients = ds.project(params, modes=1)
    a1, a2, _ = coefficients.duffing()
    np.testing.assert_allclose(jacobian(coefficients), [[0.0, 1.0], [-a2 / a1, 0.0]], rtol=1e-14)
    st = analyse(params, modes=1)
    w = math.sqrt(a2 / a1)
    np.testing.assert_allclose(st.eigenvalues, [-1j * w, 1j * w], rtol=1e-12)
    assert st.mode_eigenvalues[0] == pytest.approx(1j * w, rel=1e-14)
    assert st.classification == "centre" and st.stable
    assert st.linear_frequencies_hz[0] == pytest.approx(w / (2 * math.pi), rel=1e-14)


@pytest.mark.parametrize("damping", [0.0, 3.0, 900.0])
@pytest.mark.parametrize("rigid", [False, True])
def test_core_eigenvalues_are_lapacks(rigid, damping):
    """The core's closed-form eigenvalues (both roots of every mode) and Jacobian against the numpy
    oracle: the Jacobian by a linear solve, its eigenvalues by LAPACK, the classification from
    those eigenvalues."""
    st = analyse(ds.preset("steel").replace(length=250.0, damping_rate=damping), modes=3, rigid_mode=rigid)
    model = ds.project(ds.preset("steel").replace(length=250.0), modes=3, rigid_mode=rigid)
    jac = oracles.jacobian(model.mass, model.stiffness, damping)
    np.testing.assert_allclose(st.jacobian, jac, rtol=1e-15, atol=0)  # LAPACK divides by a reciprocal
    lapack = oracles.jacobian_eigenvalues(jac)
    scale = np.abs(lapack).max()
    key = lambda z: (round(z.imag, 6), round(z.real, 6))  # noqa: E731
    np.testing.assert_allclose(sorted(st.eigenvalues, key=key), sorted(lapack, key=key), rtol=0, atol=1e-12 * scale)
    if damping == 0.0:
        pairs = np.concatenate([st.mode_eigenvalues, -st.mode_eigenvalues])
        np.testing.assert_allclose(sorted(pairs, key=key), sorted(lapack, key=key), rtol=0, atol=1e-12 * scale)
    assert oracles.classify_eigenvalues(lapack) == st.classification


def test_critical_speeds_match_the_formula():
    params = ds.preset("aluminum").replace(length=500.0)
    st = analyse(params, modes=3)
    g = shear_modulus(params.youngs_modulus, params.poisson_ratio)
    expected = np.arange(1, 4) * math.pi / params.length * math.sqrt(4 * g / params.density)
    np.testing.assert_allclose(st.critical_speeds, expected, rtol=1e-12)
    pde = PDECoefficients.from_parameters(params)
    np.testing.assert_allclose(st.critical_speeds, pde.critical_speed([1, 2, 3]), rtol=1e-12)
    # the same from the projected model and its Omega
    st2 = analyse(ds.project(params, modes=3), omega=params.omega)
    np.testing.assert_allclose(st2.critical_speeds, expected, rtol=1e-12)
    assert analyse(ds.project(params, modes=3)).critical_speeds is None


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_classification_flips_at_the_critical_speed(mode):
    base = ds.preset("aluminum")
    critical = PDECoefficients.from_parameters(base).critical_speed(mode)
    below = analyse(base.replace(omega=critical * (1 - 1e-6)), modes=3)
    above = analyse(base.replace(omega=critical * (1 + 1e-6)), modes=3)
    k = mode - 1
    assert below.mode_classification[k] == "centre"
    assert above.mode_classification[k] == "saddle"
    assert above.mode_eigenvalues[k].real > 0 and above.mode_eigenvalues[k].imag == 0
    assert above.classification == "saddle"
    assert below.classification == ("centre" if mode == 1 else "saddle")  # lower modes already unstable
    assert oracles.classify_eigenvalues(above.eigenvalues) == "saddle"
    assert oracles.classify_eigenvalues(below.eigenvalues) == below.classification
    # modes above the flipping one stay centres
    assert all(c == "centre" for c in above.mode_classification[mode:])


@pytest.mark.parametrize("omega", [-2.0, 0.1, 2 * math.pi * 0.5, 2 * math.pi * 6])
def test_rigid_mode_is_a_saddle_for_any_rotation(omega):
    st = analyse(ds.preset("aluminum").replace(omega=omega), modes=2, rigid_mode=True)
    assert list(st.indices) == [0, 1, 2]
    assert st.mode_classification == ("saddle", "centre", "centre")
    assert st.classification == "saddle"
    assert st.mode_eigenvalues[0] == pytest.approx(abs(omega), rel=1e-12)  # +-Omega, real
    assert st.critical_speeds[0] == 0.0


def test_rigid_mode_without_rotation_is_degenerate():
    st = analyse(ds.preset("aluminum").replace(omega=0.0), modes=1, rigid_mode=True)
    assert st.mode_classification[0] == "degenerate"
    assert st.classification == "degenerate"


def test_bad_source():
    with pytest.raises(ValidationError):
        analyse("aluminum")  # type: ignore[arg-type]
    with pytest.raises(ValidationError):
        analyse(ds.preset("aluminum"), omega=5.0)
