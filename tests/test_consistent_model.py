"""The ``"consistent"`` model: finite-strain torsion of rigidly rotating circular sections.

The coefficients computed by the Rust core are checked against a symbolic derivation from the
kinematics (deformation gradient, Green-Lagrange strain, St Venant-Kirchhoff energy, the
annulus integrated in polar coordinates, Euler-Lagrange equation); its consequences (classical
wave speed and free-free frequencies, no force from a rigid twist, no dependence on a constant
rotation speed) are checked on the modal and the PDE paths, with the paper model as contrast.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np
import pytest
import sympy as sp

import drillstring as ds
from drillstring import _core
from drillstring.model.coefficients import PDECoefficients
from drillstring.model.galerkin import project
from drillstring.solvers.pde import pde_system
from drillstring.studies.stability import analyse

ALUMINIUM = ds.Parameters(model="consistent")  # Table 1, 100 m
STEEL = ds.preset("steel").replace(model="consistent", length=2000.0)

PARAMETER_SETS = [
    ALUMINIUM,
    STEEL,
    ds.Parameters(model="consistent", youngs_modulus=1.3e9, density=950.0, poisson_ratio=-0.4,
                  outer_diameter=0.5, inner_diameter=0.0, omega=-7.0),
    ds.Parameters(model="consistent", poisson_ratio=0.49, outer_diameter=1.7, inner_diameter=1.6),
]


def _classical_wave_speed(p: ds.Parameters) -> float:
    """``c = sqrt(G / rho)`` from the material constants (Saint-Venant torsion)."""
    return math.sqrt(p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio)) / p.density)


# ------------------------------------------------------------------ symbolic derivation


@lru_cache(maxsize=1)
def _derivation() -> dict[str, Any]:
    """Energy density per unit length and Euler-Lagrange expression, derived from kinematics."""
    X, Y, z, t = sp.symbols("X Y z t", real=True)
    r, phi = sp.symbols("r phi", nonnegative=True)
    r_in, r_out, lam, mu, rho, omega = sp.symbols("r_in r_out lambda mu rho Omega", positive=True)
    th = sp.Function("theta")(z, t)
    # rigidly rotated section at angle Omega t + theta(z, t); axial displacement suppressed
    angle = omega * t + th
    x = sp.Matrix([X * sp.cos(angle) - Y * sp.sin(angle), X * sp.sin(angle) + Y * sp.cos(angle), z])
    F = x.jacobian(sp.Matrix([X, Y, z]))
    E = sp.simplify((F.T * F - sp.eye(3)) / 2)
    W = lam / 2 * E.trace() ** 2 + mu * (E * E).trace()  # St Venant-Kirchhoff
    polar = {X: r * sp.cos(phi), Y: r * sp.sin(phi)}
    speed2 = sp.simplify(x.diff(t).dot(x.diff(t)))

    def over_section(f: sp.Expr) -> sp.Expr:
        inner = sp.integrate(sp.expand(sp.simplify(f.subs(polar))) * r, (phi, 0, 2 * sp.pi))
        return sp.simplify(sp.integrate(inner, (r, r_in, r_out)))

    strain_energy = over_section(W)
    kinetic = over_section(rho * speed2 / 2)
    lagrangian = kinetic - strain_energy
    (euler_lagrange,) = sp.euler_equations(lagrangian, th, [z, t])
    return {
        "symbols": (r_in, r_out, lam, mu, rho, omega),
        "theta": th,
        "z": z,
        "t": t,
        "E": E,
        "X": X,
        "Y": Y,
        "strain_energy": strain_energy,
        "kinetic": kinetic,
        "euler_lagrange": euler_lagrange.lhs - euler_lagrange.rhs,
    }


def test_green_lagrange_strain_of_a_rigidly_rotating_section() -> None:
    d = _derivation()
    th, z, X, Y = d["theta"], d["z"], d["X"], d["Y"]
    thz = th.diff(z)
    expected = sp.Matrix([[0, 0, -thz * Y / 2], [0, 0, thz * X / 2],
                          [-thz * Y / 2, thz * X / 2, thz**2 * (X**2 + Y**2) / 2]])
    assert sp.simplify(d["E"] - expected) == sp.zeros(3, 3)


def test_energy_per_unit_length_is_shear_plus_quartic_and_ignores_a_rigid_twist() -> None:
    d = _derivation()
    r_in, r_out, lam, mu, rho, omega = d["symbols"]
    th, z, t = d["theta"], d["z"], d["t"]
    ip = sp.pi * (r_out**4 - r_in**4) / 2
    j4 = sp.pi * (r_out**6 - r_in**6) / 3
    thz = th.diff(z)
    assert sp.simplify(d["strain_energy"] - (mu * ip * thz**2 / 2 + (lam + 2 * mu) * j4 * thz**4 / 8)) == 0
    assert sp.simplify(d["kinetic"] - rho * ip * (omega + th.diff(t)) ** 2 / 2) == 0
    # a uniform twist theta = const costs nothing: the energy depends on theta_z only
    const = sp.Symbol("c")
    assert d["strain_energy"].subs(th, const).doit() == 0


@pytest.mark.parametrize("params", PARAMETER_SETS, ids=["aluminium", "steel-2000m", "auxetic-solid", "thin-wall"])
def test_rust_coefficients_match_the_symbolic_euler_lagrange_equation(params: ds.Parameters) -> None:
    """The Euler-Lagrange equation of the derived Lagrangian equals, term by term,
    ``k1 th_tt - k2 th_zz + k3 th^3 - k4 (th^2 th_zz + th th_z^2) - k5 (th_z^3)_z - k6 th`` with
    the coefficients the Rust core returns."""
    d = _derivation()
    r_in, r_out, lam, mu, rho, omega = d["symbols"]
    th, z, t = d["theta"], d["z"], d["t"]
    e, nu = params.youngs_modulus, params.poisson_ratio
    values = {
        r_in: sp.Rational(params.inner_diameter) / 2,
        r_out: sp.Rational(params.outer_diameter) / 2,
        lam: sp.Rational(e) * sp.Rational(nu) / ((1 + sp.Rational(nu)) * (1 - 2 * sp.Rational(nu))),
        mu: sp.Rational(e) / (2 * (1 + sp.Rational(nu))),
        rho: sp.Rational(params.density),
        omega: sp.Rational(params.omega),
    }
    derived = sp.expand(-d["euler_lagrange"].subs(values))  # sign: k1 th_tt + ... = 0
    k = PDECoefficients.from_parameters(params)
    a, az, azz, att = sp.symbols("a a_z a_zz a_tt")
    model = (k.k1 * th.diff(t, 2) - k.k2 * th.diff(z, 2) + k.k3 * th**3
             - k.k4 * (th**2 * th.diff(z, 2) + th * th.diff(z) ** 2)
             - k.k5 * (th.diff(z) ** 3).diff(z) - k.k6 * th)
    plain = {th.diff(t, 2): att, th.diff(z, 2): azz}

    def poly(expr: sp.Expr) -> sp.Poly:
        expr = sp.expand(expr).subs(plain).subs(th.diff(z), az).subs(th, a)
        return sp.Poly(expr, a, az, azz, att)

    want, got = poly(derived).as_dict(), poly(model).as_dict()
    assert set(want) <= {(0, 0, 0, 1), (0, 0, 1, 0), (0, 2, 1, 0)}  # th_tt, th_zz, th_z^2 th_zz only
    for monomial in set(want) | set(got):
        expected = float(want.get(monomial, 0))
        assert float(got.get(monomial, 0)) == pytest.approx(expected, rel=1e-13, abs=0.0), monomial
    # the constant rotation speed drops out of the equation of motion
    assert omega not in d["euler_lagrange"].free_symbols


# ------------------------------------------------------------------ frequencies


def test_linear_frequencies_are_the_classical_free_free_ones_on_the_modal_path() -> None:
    """Galerkin: ``w_i^2 = K_ii / M_ii``, equal to ``(i pi c / l)^2``: ``f_i = i c / (2 l)``."""
    for params in PARAMETER_SETS:
        c = _classical_wave_speed(params)
        stab = analyse(params, modes=5, rigid_mode=True)
        expected = np.arange(1, 6) * c / (2.0 * params.length)
        np.testing.assert_allclose(stab.linear_frequencies_hz[1:], expected, rtol=1e-13)
        assert PDECoefficients.from_parameters(params).wave_speed == pytest.approx(c, rel=1e-14)
    # the printed model doubles them
    paper = analyse(ALUMINIUM.replace(model="paper", omega=0.0), modes=3)
    consistent = analyse(ALUMINIUM, modes=3)
    np.testing.assert_allclose(paper.linear_frequencies_hz, 2 * consistent.linear_frequencies_hz, rtol=1e-13)


def _crossing_frequency(t: np.ndarray, y: np.ndarray) -> float:
    """Frequency (Hz) from the first and last zero crossings (linear interpolation)."""
    s = np.signbit(y[1:]) != np.signbit(y[:-1])
    idx = np.nonzero(s & (y[:-1] != 0.0))[0]
    roots = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    return (len(roots) - 1) / (2.0 * (roots[-1] - roots[0]))


def test_simulated_one_mode_response_oscillates_at_c_over_2l() -> None:
    params = ALUMINIUM.replace(initial_velocities=(1e-6,))
    f1 = _classical_wave_speed(params) / (2 * params.length)
    res = ds.simulate(params, modes=3, t_end=0.6, rtol=1e-12, atol=1e-20, samples=24001)
    assert _crossing_frequency(res.t, res.q[0]) == pytest.approx(f1, rel=1e-6)
    assert np.all(res.q[1] == 0.0)  # the even mode stays at rest (symmetry z -> l - z)
    assert np.max(np.abs(res.q[2])) < 1e-20 * np.max(np.abs(res.q[0]))  # mode 3: cubic coupling only


def test_pde_eigenfrequencies_converge_to_c_over_2l_at_second_order() -> None:
    c = _classical_wave_speed(ALUMINIUM)
    exact = np.arange(1, 4) * c / (2 * ALUMINIUM.length)
    errors = []
    for nodes in (61, 121, 241):
        w2 = np.asarray(pde_system(ALUMINIUM, nodes).linear_frequencies_squared(4))
        assert abs(w2[0]) <= 1e-9 * w2[1]  # the uniform twist: zero frequency (no k6)
        f = np.sqrt(w2[1:]) / (2 * math.pi)
        errors.append(np.abs(f / exact - 1.0))
        # discretisation error of the lumped linear elements, ~ (i pi h / l)^2 / 24 ... / 12
        h = ALUMINIUM.length / (nodes - 1)
        assert np.all(errors[-1] < (np.arange(1, 4) * math.pi * h / ALUMINIUM.length) ** 2 / 6)
    ratios = errors[0] / errors[1], errors[1] / errors[2]
    for ratio in ratios:
        np.testing.assert_allclose(ratio, 4.0, rtol=0.02)


def test_pde_solve_oscillates_at_c_over_2l() -> None:
    params = ALUMINIUM.replace(initial_velocities=(1e-6,))
    f1 = _classical_wave_speed(params) / (2 * params.length)
    res = ds.solve_pde(params, nodes=241, t_end=0.4, rtol=1e-11, atol=1e-20, samples=16001)
    theta_end = res.theta(0.0)
    h = params.length / 240
    assert _crossing_frequency(res.t, theta_end) == pytest.approx(f1, rel=(math.pi * h / params.length) ** 2 / 6)


# ------------------------------------------------------------------ rigid twist and rotation


def test_a_rigid_twist_exerts_no_force() -> None:
    consistent = project(ALUMINIUM, modes=4, rigid_mode=True)
    paper = project(ALUMINIUM.replace(model="paper"), modes=4, rigid_mode=True)
    for coefficients, zero in ((consistent, True), (paper, False)):
        system = _core.ModalSystem(coefficients.mass, coefficients.stiffness,
                                   np.ascontiguousarray(coefficients.quartic_index), coefficients.quartic_coef)
        for c0 in (1e-3, 0.7, 25.0):
            q = np.array([c0, 0.0, 0.0, 0.0, 0.0])
            acc = np.asarray(system.acceleration(q))
            energy = float(coefficients.energy(q, np.zeros(5)))
            assert bool(np.all(acc == 0.0) and energy == 0.0) is zero, (acc, energy)
    for params, zero in ((ALUMINIUM, True), (ALUMINIUM.replace(model="paper"), False)):
        pde = pde_system(params, 31)
        q = np.full(31, 0.3)
        assert bool(np.all(np.asarray(pde.acceleration(q)) == 0.0)) is zero


def test_rigid_mode_start_stays_theta_equals_c0_t() -> None:
    c0, t_end = 0.37, 2.0
    coefficients = project(ALUMINIUM, modes=3, rigid_mode=True)
    system = _core.ModalSystem(coefficients.mass, coefficients.stiffness,
                               np.ascontiguousarray(coefficients.quartic_index), coefficients.quartic_coef)
    times = np.linspace(0.0, t_end, 101)
    out = _core.solve_modal(system, np.zeros(4), np.array([c0, 0.0, 0.0, 0.0]), t_end, times, "dop853", 1e-9, 1e-12)
    y = out["y"]
    assert out["status"] == "success"
    np.testing.assert_allclose(y[:, 0], c0 * out["t"], rtol=1e-14, atol=1e-15)
    assert np.all(y[:, 1:4] == 0.0) and np.all(y[:, 4] == c0) and np.all(y[:, 5:] == 0.0)
    # the same start on the PDE: a uniform velocity field
    res = ds.solve_pde(ALUMINIUM, nodes=41, t_end=t_end, initial_velocity=lambda z: np.full_like(z, c0), samples=51)
    expected = c0 * res.t
    for z in (0.0, 37.0, 100.0):
        np.testing.assert_allclose(res.theta(z), expected, rtol=1e-14, atol=1e-15)
    # the paper model does not keep it: k6 and k3 act on a uniform twist
    paper = ds.solve_pde(ALUMINIUM.replace(model="paper"), nodes=41, t_end=t_end,
                         initial_velocity=lambda z: np.full_like(z, c0), samples=51)
    assert np.max(np.abs(paper.theta(0.0) - expected)) > 1e-3


def test_results_do_not_depend_on_a_constant_rotation_speed() -> None:
    slow, fast = ALUMINIUM.replace(omega=0.0), ALUMINIUM.replace(omega=2 * math.pi * 60)
    a = ds.simulate(slow.replace(initial_velocities=(0.1, 0.05, 0.02)), modes=4, rigid_mode=True, t_end=0.5)
    b = ds.simulate(fast.replace(initial_velocities=(0.1, 0.05, 0.02)), modes=4, rigid_mode=True, t_end=0.5)
    assert np.array_equal(a.q, b.q) and np.array_equal(a.qdot, b.qdot)
    pa = ds.solve_pde(slow, nodes=61, t_end=0.2)
    pb = ds.solve_pde(fast, nodes=61, t_end=0.2)
    assert np.array_equal(pa.theta(40.0), pb.theta(40.0))
    stab = analyse(fast, modes=3, rigid_mode=True)
    assert stab.critical_speeds is not None and np.all(np.isinf(stab.critical_speeds))
    assert stab.mode_classification == ("degenerate", "centre", "centre", "centre")
    # contrast: the paper model at the same speed is past mode 1's critical speed
    paper = analyse(fast.replace(model="paper"), modes=3)
    assert paper.mode_classification[0] == "saddle"


# ------------------------------------------------------------------ every path accepts the model


def test_the_paper_model_is_the_default_and_unchanged() -> None:
    assert ds.Parameters().model == "paper" and ds.preset("steel").model == "paper"
    k = PDECoefficients.from_parameters(ds.Parameters())
    assert k.k2 == pytest.approx(4 * PDECoefficients.from_parameters(ALUMINIUM).k2, rel=1e-15)
    assert k.critical_speed(1) == pytest.approx(math.pi / 100.0 * 2 * _classical_wave_speed(ALUMINIUM), rel=1e-14)


def test_sweep_over_the_model() -> None:
    pytest.importorskip("pandas")
    base = ds.Parameters(initial_velocities=(1e-4,))
    table = ds.sweep(base, {"model": ["paper", "consistent"], "omega": [0.0, 300.0]}, modes=2, t_end=0.5,
                     rtol=1e-10, progress=False)
    assert list(table["status"]) == ["success"] * 4
    rows = {(m, o): r for m, o, r in zip(table["model"], table["omega"], table.to_dict("records"))}
    consistent = [rows["consistent", 0.0], rows["consistent", 300.0]]
    f1 = _classical_wave_speed(base) / (2 * base.length)
    for row in consistent:
        assert row["dominant_frequency_hz"] == pytest.approx(f1, rel=0.02)
        assert row["unstable_modes"] == 0
    assert consistent[0]["max_theta"] == consistent[1]["max_theta"]
    assert rows["paper", 0.0]["dominant_frequency_hz"] == pytest.approx(2 * f1, rel=0.02)
    assert rows["paper", 300.0]["unstable_modes"] == 1  # Omega above mode 1's 195 rad/s


def test_sweep_plot_draws_no_critical_speed_for_the_consistent_model() -> None:
    pytest.importorskip("pandas")
    pytest.importorskip("matplotlib")
    from drillstring import plots

    omegas = [0.0, 100.0, 200.0, 300.0]
    for model, lines in (("paper", 1), ("consistent", 0)):
        table = ds.sweep(ds.Parameters(model=model), {"omega": omegas}, modes=1, t_end=0.05, progress=False)
        fig = plots.sweep_metric(table, "max_theta")
        assert sum(1 for line in fig.axes[0].lines if len(line.get_xdata()) == 2
                   and line.get_xdata()[0] == line.get_xdata()[1]) == lines


def test_cli_model_flag(tmp_path: Any, capsys: Any) -> None:
    from drillstring.cli import main

    out = tmp_path / "run.csv"
    assert main(["simulate", "--model", "consistent", "--modes", "2", "--t-end", "0.1", "--out", str(out)]) == 0
    data = np.genfromtxt(out, delimiter=",", names=True)
    expected = ds.simulate(ds.preset("aluminum").replace(model="consistent"), modes=2, t_end=0.1)
    np.testing.assert_allclose(data["theta"], expected.theta(2 * 100.0 / 3), rtol=1e-10, atol=1e-16)
    paper = ds.simulate(ds.preset("aluminum"), modes=2, t_end=0.1)
    assert np.max(np.abs(data["theta"] - paper.theta(2 * 100.0 / 3))) > 1e-5
    assert main(["pde", "--model", "consistent", "--nodes", "21", "--t-end", "0.05"]) == 0
    with pytest.raises(SystemExit) as info:
        main(["simulate", "--model", "exact"])
    assert info.value.code == 2
    assert "model" in capsys.readouterr().err
