"""Tests of drillstring.model.cross_section (eq. 8) and drillstring.model.coefficients (eq. 17)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy.integrate import dblquad

from drillstring.errors import ValidationError
from drillstring.model.coefficients import PDECoefficients, shear_modulus
from drillstring.model.cross_section import CrossSection
from drillstring.model.parameters import Parameters, preset


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
    section = CrossSection.annulus(big, small)
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
    s = CrossSection.annulus(0.20, 0.12)
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
        CrossSection.annulus(outer, inner)
    assert info.value.field == field and field in str(info.value)


def test_section_rejects_nonpositive() -> None:
    with pytest.raises(ValidationError, match="i_r"):
        CrossSection(area=1.0, polar_moment=1.0, i_r=0.0, i_x2y2=1.0)


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
    s = CrossSection.annulus(0.2, 0.12)
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
    two = c.linear_frequencies(2)
    assert isinstance(two, float) and two == pytest.approx(math.sqrt(expected_w2[2]), rel=1e-13)

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


# ------------------------------------------------------------------ Rust vs the paper's formulas

def _paper_oracle(p: Parameters) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Eqs. 8 and 17 in Python, operation for operation as the package evaluated them before the
    formulas moved to the Rust core (``x**n`` is the C library's ``pow``, like Rust's ``powf``):
    the Rust values must equal these bit for bit, so that every paper result is unchanged."""
    r_out, r_in = p.outer_diameter / 2.0, p.inner_diameter / 2.0
    r6 = r_out**6 - r_in**6
    area = math.pi * (r_out**2 - r_in**2)
    ip = math.pi * (r_out**4 - r_in**4) / 2.0
    i_r, i_x2y2 = math.pi * r6 / 4.0, math.pi * r6 / 24.0
    nu = p.poisson_ratio
    g = p.youngs_modulus / (2.0 * (1.0 + nu))
    sign = -1.0 if p.k5_variant == "paper" else 1.0
    k = (
        p.density * ip,
        4.0 * g * ip,
        2.0 * area * g / (1.0 - 2.0 * nu),
        g * ip * (5.0 - 6.0 * nu) / (4.0 * (1.0 - 2.0 * nu)),
        g * (i_r + sign * i_x2y2 * (5.0 - 6.0 * nu)) / (8.0 * (1.0 - 2.0 * nu)),
        p.density * ip * p.omega**2,
    )
    return (area, ip, i_r, i_x2y2), k


def _random_parameters(count: int) -> list[Parameters]:
    rng = np.random.default_rng(12)
    sets = [preset("aluminum"), preset("steel"), Parameters(length=250.0, omega=2 * math.pi * 6),
            Parameters(inner_diameter=0.0, k5_variant="energy")]
    for _ in range(count):
        outer = float(rng.uniform(0.01, 3.0))
        sets.append(Parameters(
            youngs_modulus=float(10 ** rng.uniform(8, 12)),
            density=float(rng.uniform(500, 20000)),
            poisson_ratio=float(rng.uniform(-0.99, 0.499)),
            outer_diameter=outer,
            inner_diameter=float(outer * rng.uniform(0.0, 0.99)),
            omega=float(rng.normal() * 100),
            k5_variant=str(rng.choice(["paper", "energy"])),
        ))
    return sets


def test_rust_paper_coefficients_equal_the_formulas_bit_for_bit() -> None:
    for p in _random_parameters(300):
        section, k = _paper_oracle(p)
        s = CrossSection.annulus(p.outer_diameter, p.inner_diameter)
        assert (s.area, s.polar_moment, s.i_r, s.i_x2y2) == section, p
        c = PDECoefficients.from_parameters(p)
        assert c.as_tuple() == k, p
        assert c.k6_per_omega_squared == c.k1  # k6 = k1 Omega^2
        g = p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio))
        assert shear_modulus(p.youngs_modulus, p.poisson_ratio) == g
        # the critical speed as before: (i pi / l) sqrt(k2 / k1)
        assert c.critical_speed(2) == 2 * math.pi / p.length * math.sqrt(k[1] / k[0])


def test_j4_is_the_fourth_polar_moment() -> None:
    for big, small in [(0.20, 0.12), (0.3, 0.0), (2.5, 1.0)]:
        s = CrossSection.annulus(big, small)
        assert s.j4 is not None
        r_out, r_in = big / 2, small / 2
        assert s.j4 == pytest.approx(_polar_integral(lambda x, y: (x**2 + y**2) ** 2, r_in, r_out), rel=1e-10)
        assert s.j4 == pytest.approx(s.i_r + 2 * s.i_x2y2, rel=1e-15)


def test_consistent_coefficients_closed_form() -> None:
    """k1 = rho I_p, k2 = G I_p, k3 = k4 = k6 = 0, k5 = M J4 / 2 with M = lambda + 2 mu."""
    for p in _random_parameters(20):
        c = PDECoefficients.from_parameters(p.replace(model="consistent"))
        e, nu = p.youngs_modulus, p.poisson_ratio
        g = e / (2 * (1 + nu))
        lam = e * nu / ((1 + nu) * (1 - 2 * nu))
        r6 = (p.outer_diameter / 2) ** 6 - (p.inner_diameter / 2) ** 6
        ip = math.pi * ((p.outer_diameter / 2) ** 4 - (p.inner_diameter / 2) ** 4) / 2
        assert c.k1 == pytest.approx(p.density * ip, rel=1e-14)
        assert c.k2 == pytest.approx(g * ip, rel=1e-14)
        assert (c.k3, c.k4, c.k6, c.k6_per_omega_squared) == (0.0, 0.0, 0.0, 0.0)
        assert c.k5 == pytest.approx((lam + 2 * g) * (math.pi * r6 / 3) / 2, rel=1e-13)
        assert c.wave_speed == pytest.approx(math.sqrt(g / p.density), rel=1e-14)
        paper = PDECoefficients.from_parameters(p)
        assert paper.wave_speed == pytest.approx(2 * c.wave_speed, rel=1e-14)
        # no rotation softening: no critical speed for any mode
        assert np.all(np.isinf(c.critical_speed([0, 1, 5])))
        assert math.isinf(c.critical_speed(1))


def test_coefficients_given_directly_keep_the_paper_critical_speed() -> None:
    c = PDECoefficients(k1=2.0, k2=8.0, k3=0.0, k4=0.0, k5=0.0, k6=1.0, length=math.pi)
    assert c.k6_per_omega_squared is None
    assert c.critical_speed(3) == pytest.approx(3 * 2.0)
    with pytest.raises(ValidationError, match="k6_per_omega_squared"):
        PDECoefficients(k1=1.0, k2=1.0, k3=0.0, k4=0.0, k5=0.0, k6=0.0, length=1.0, k6_per_omega_squared=-1.0)


def test_overflowing_diameter_is_named() -> None:
    with pytest.raises(ValidationError) as info:
        CrossSection.annulus(1e100, 0.0)
    assert info.value.field == "outer_diameter"
    with pytest.raises(ValidationError) as info:
        PDECoefficients.from_parameters(Parameters(outer_diameter=1e100, inner_diameter=0.0))
    assert info.value.field == "parameters" and "outer_diameter" in str(info.value)
