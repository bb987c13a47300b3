"""Tests of drillstring.section (eq. 8) and drillstring.coefficients (eq. 17)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy.integrate import dblquad

from drillstring.coefficients import PDECoefficients, shear_modulus
from drillstring.errors import ValidationError
from drillstring.parameters import Parameters, preset
from drillstring.section import Section


def _polar_integral(f: Any, r_in: float, r_out: float) -> float:
    """int over the annulus of f(x, y) dA, in polar coordinates (rho d rho d phi)."""
    value, _ = dblquad(
        lambda rho, phi: f(rho * math.cos(phi), rho * math.sin(phi)) * rho,
        0.0,
        2.0 * math.pi,
        r_in,
        r_out,
        epsabs=0.0,
        epsrel=1e-12,
    )
    return value


@pytest.mark.parametrize(("big", "small"), [(0.20, 0.12), (0.3, 0.0), (1.0, 0.9), (2.5, 1.0)])
def test_annulus_matches_numerical_integration(big: float, small: float) -> None:
    section = Section.annulus(big, small)
    r_out, r_in = big / 2, small / 2
    assert section.area == pytest.approx(_polar_integral(lambda x, y: 1.0, r_in, r_out), rel=1e-10)
    assert section.polar_moment == pytest.approx(
        _polar_integral(lambda x, y: x**2 + y**2, r_in, r_out), rel=1e-10
    )
    assert section.i_r == pytest.approx(
        _polar_integral(lambda x, y: x**4 + y**4, r_in, r_out), rel=1e-10
    )
    assert section.i_x2y2 == pytest.approx(
        _polar_integral(lambda x, y: x**2 * y**2, r_in, r_out), rel=1e-10
    )
    assert section.axial_moment == pytest.approx(
        _polar_integral(lambda x, y: y**2, r_in, r_out), rel=1e-10
    )


def test_table_1_section_values() -> None:
    s = Section.annulus(0.20, 0.12)
    assert s.area == pytest.approx(math.pi * (0.01 - 0.0036), rel=1e-14)
    assert s.polar_moment == pytest.approx(math.pi * 8.704e-5 / 2, rel=1e-13)
    assert s.i_r == pytest.approx(math.pi * (1e-6 - 4.6656e-8) / 4, rel=1e-13)
    assert s.i_r == pytest.approx(6 * s.i_x2y2, rel=1e-15)


@pytest.mark.parametrize(
    ("outer", "inner", "field"),
    [
        (0.0, 0.0, "outer_diameter"),
        (-0.2, 0.1, "outer_diameter"),
        (math.nan, 0.1, "outer_diameter"),
        ("0.2", 0.1, "outer_diameter"),
        (0.2, 0.2, "inner_diameter"),
        (0.2, -0.1, "inner_diameter"),
        (0.2, math.inf, "inner_diameter"),
        (0.2, True, "inner_diameter"),
    ],
)
def test_annulus_rejects_bad_diameters(outer: Any, inner: Any, field: str) -> None:
    with pytest.raises(ValidationError) as info:
        Section.annulus(outer, inner)
    assert info.value.field == field and field in str(info.value)


def test_section_rejects_nonpositive() -> None:
    with pytest.raises(ValidationError, match="i_r"):
        Section(area=1.0, polar_moment=1.0, i_r=0.0, i_x2y2=1.0)


def test_shear_modulus() -> None:
    assert shear_modulus(0.7e11, 0.34) == pytest.approx(0.7e11 / 2.68, rel=1e-15)
    assert shear_modulus(2.1e11, 0.28) == pytest.approx(2.1e11 / 2.56, rel=1e-15)


def test_table_1_coefficients() -> None:
    """Eq. 17 with Table 1, evaluated by hand from the closed forms."""
    c = PDECoefficients.from_parameters(Parameters())
    g = 0.7e11 / 2.68
    area = math.pi * 0.0064
    ip = math.pi * 8.704e-5 / 2
    ir = math.pi * (1e-6 - 4.6656e-8) / 4
    ixy = ir / 6
    assert c.k1 == pytest.approx(2700 * ip, rel=1e-13)
    assert c.k1 == pytest.approx(0.36914970316741513, rel=1e-12)
    assert c.k2 == pytest.approx(4 * g * ip, rel=1e-13)
    assert c.k3 == pytest.approx(2 * area * g / 0.32, rel=1e-13)
    assert c.k4 == pytest.approx(g * ip * 2.96 / (4 * 0.32), rel=1e-13)
    assert c.k5 == pytest.approx(g * (ir - ixy * 2.96) / (8 * 0.32), rel=1e-13)
    assert c.k6 == pytest.approx(2700 * ip * math.pi**2, rel=1e-13)
    assert c.length == 100.0
    assert c.as_tuple() == (c.k1, c.k2, c.k3, c.k4, c.k5, c.k6)


def test_k5_variants_differ_by_sign_only() -> None:
    params = preset("steel")
    paper = PDECoefficients.from_parameters(params)
    energy = PDECoefficients.from_parameters(params.replace(k5_variant="energy"))
    s = Section.annulus(0.2, 0.12)
    g = shear_modulus(2.1e11, 0.28)
    factor = g / (8 * (1 - 2 * 0.28))
    assert paper.k5 == pytest.approx(factor * (s.i_r - s.i_x2y2 * (5 - 6 * 0.28)), rel=1e-13)
    assert energy.k5 == pytest.approx(factor * (s.i_r + s.i_x2y2 * (5 - 6 * 0.28)), rel=1e-13)
    assert paper.k5 < energy.k5
    for name in ("k1", "k2", "k3", "k4", "k6", "length"):
        assert getattr(paper, name) == getattr(energy, name)


def test_linear_frequencies_and_critical_speed() -> None:
    params = Parameters(length=250.0)
    c = PDECoefficients.from_parameters(params)
    i = np.arange(0, 6)
    expected_w2 = (c.k2 * (i * math.pi / 250.0) ** 2 - c.k6) / c.k1
    np.testing.assert_allclose(c.frequency_squared(i), expected_w2, rtol=1e-13)
    assert c.frequency_squared(0) == pytest.approx(-(params.omega**2), rel=1e-13)
    w = c.linear_frequencies(i)
    assert math.isnan(w[0])
    np.testing.assert_allclose(w[1:], np.sqrt(expected_w2[1:]), rtol=1e-13)
    assert isinstance(c.linear_frequencies(2), float)

    g = shear_modulus(params.youngs_modulus, params.poisson_ratio)
    for mode in (1, 2, 3):
        speed = c.critical_speed(mode)
        assert speed == pytest.approx(mode * math.pi / 250.0 * math.sqrt(4 * g / params.density))
        # at Omega = critical speed the mode is exactly neutral, just above it is unstable
        at = PDECoefficients.from_parameters(params.replace(omega=speed))
        assert abs(at.frequency_squared(mode)) < 1e-9 * c.frequency_squared(mode)
        above = PDECoefficients.from_parameters(params.replace(omega=speed * 1.01))
        assert above.frequency_squared(mode) < 0 < above.frequency_squared(mode + 1)
        assert math.isnan(above.linear_frequencies(mode))


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"k1": 0.0}, "k1"),
        ({"k1": -1.0}, "k1"),
        ({"length": 0.0}, "length"),
        ({"k3": math.nan}, "k3"),
        ({"k5": math.inf}, "k5"),
        ({"k2": "1"}, "k2"),
        ({"k6": True}, "k6"),
    ],
)
def test_pde_coefficients_validation(changes: dict[str, Any], field: str) -> None:
    base = {"k1": 1.0, "k2": 1.0, "k3": 1.0, "k4": 1.0, "k5": 1.0, "k6": 1.0, "length": 1.0}
    base.update(changes)
    with pytest.raises(ValidationError) as info:
        PDECoefficients(**base)
    assert info.value.field == field and field in str(info.value)


def test_bad_mode_numbers() -> None:
    c = PDECoefficients.from_parameters(Parameters())
    with pytest.raises(ValidationError, match="indices"):
        c.frequency_squared(-1)
    with pytest.raises(ValidationError, match="indices"):
        c.critical_speed([1, math.nan])
