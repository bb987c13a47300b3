"""simulate(): analytic solutions, conservation, agreement with scipy, statuses, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core
from drillstring.errors import SolveError, ValidationError

REF = ds.preset("aluminum")


def crossings(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Upward zero crossings, located by linear interpolation between samples."""
    k = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    return t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])


def duffing_period(a1: float, a2: float, a3: float, c: float) -> float:
    """Exact period of a1 x'' + a2 x + a3 x^3 = 0 with x(0) = 0, x'(0) = c."""
    from scipy.special import ellipk

    w2, beta = a2 / a1, a3 / a1
    # amplitude from energy: c^2/2 = w2 A^2/2 + beta A^4/4
    amp2 = (-w2 + math.sqrt(w2 * w2 + 2 * beta * c * c)) / beta
    m = beta * amp2 / (2 * (w2 + beta * amp2))  # parameter m = k^2
    return 4 * float(ellipk(m)) / math.sqrt(w2 + beta * amp2)


def test_linear_frequencies_at_small_amplitude():
    # C = 1e-6 rad/s: amplitudes ~5e-9 rad, the cubic terms shift frequencies by ~1e-12
    params = REF
    coeff = ds.model.galerkin.project(params, modes=3)
    for i, mode in enumerate([1, 2, 3]):
        c = [0.0, 0.0, 0.0]
        c[i] = 1e-6
        res = ds.simulate(params.replace(initial_velocities=tuple(c)), modes=3, t_end=0.2, samples=20001,
                          rtol=1e-12, atol=1e-20)
        period = np.diff(crossings(res.t, res.q[i])).mean()
        k1, k2, k6 = coeff_k(params)
        expected = 2 * math.pi / math.sqrt((k2 * (mode * math.pi / params.length) ** 2 - k6) / k1)
        assert period == pytest.approx(expected, rel=1e-7)
        assert period == pytest.approx(2 * math.pi / coeff.linear_frequencies[i], rel=1e-7)


def coeff_k(params: ds.Parameters) -> tuple[float, float, float]:
    k = ds.model.coefficients.PDECoefficients.from_parameters(params)
    return k.k1, k.k2, k.k6


@pytest.mark.parametrize("c1", [0.1, 3.0])
@pytest.mark.parametrize("method", ["dop853", "dopri5"])
def test_one_mode_period_equals_exact_duffing_period(c1, method):
    params = REF.replace(initial_velocities=(c1,))
    a1, a2, a3 = ds.model.galerkin.project(params, modes=1).duffing()
    exact = duffing_period(a1, a2, a3, c1)
    res = ds.simulate(params, modes=1, t_end=0.5, method=method, rtol=1e-12, atol=1e-15, samples=50001)
    measured = np.diff(crossings(res.t, res.q[0])).mean()
    assert measured == pytest.approx(exact, rel=1e-7)
    if c1 == 3.0:  # the nonlinearity matters here: 10 % away from the linear period
        assert abs(exact * math.sqrt(a2 / a1) / (2 * math.pi) - 1) > 0.05


@pytest.mark.parametrize("rigid", [False, True])
def test_energy_drift_three_modes_dop853(rigid):
    res = ds.simulate(REF, modes=3, rigid_mode=rigid, t_end=10.0, rtol=1e-12, atol=1e-15, samples=2001)
    assert res.energy_drift() < 1e-9
    assert res.energy[0] == pytest.approx(0.5 * res.coefficients.mass @ res.qdot[:, 0] ** 2, rel=1e-14)


def test_agrees_with_scipy_dop853():
    from scipy.integrate import solve_ivp

    coeff = ds.model.galerkin.project(REF, modes=3)
    q0, v0 = coeff.initial_state(REF)

    def rhs(_t, y):
        q, v = y[:3], y[3:]
        return np.concatenate([v, -(coeff.stiffness * q + coeff.cubic_force(q)) / coeff.mass])

    t = np.linspace(0, 1, 501)
    ref = solve_ivp(rhs, (0, 1), np.concatenate([q0, v0]), method="DOP853", t_eval=t, rtol=1e-12, atol=1e-15)
    res = ds.simulate(REF, modes=3, t_eval=t, rtol=1e-12, atol=1e-15)
    scale = np.abs(ref.y[:3]).max()
    assert np.abs(res.q - ref.y[:3]).max() < 1e-9 * scale


def test_output_sampling_does_not_change_steps():
    a = ds.simulate(REF, modes=3, samples=11, rtol=1e-10)
    b = ds.simulate(REF, modes=3, samples=10001, rtol=1e-10)
    assert a.stats.naccept == b.stats.naccept
    np.testing.assert_allclose(a.q[:, -1], b.q[:, -1], rtol=0, atol=1e-14)


def test_fixed_step_methods_converge_to_adaptive():
    ref = ds.simulate(REF, modes=3, t_eval=[0.0, 0.5, 1.0], rtol=1e-13, atol=1e-16)
    errors = {}
    for method in ("rk4", "central"):
        for dt in (2e-4, 1e-4):
            res = ds.simulate(REF, modes=3, method=method, dt=dt, t_eval=[0.0, 0.5, 1.0])
            errors[method, dt] = np.abs(res.q[:, -1] - ref.q[:, -1]).max()
    assert errors["rk4", 2e-4] / errors["rk4", 1e-4] == pytest.approx(16, rel=0.25)
    assert errors["central", 2e-4] / errors["central", 1e-4] == pytest.approx(4, rel=0.15)


def test_theta_reconstruction_and_symmetry():
    res = ds.simulate(REF, modes=3, t_end=0.2)
    np.testing.assert_allclose(res.theta(0.0), res.q.sum(axis=0), rtol=1e-12, atol=1e-18)
    z = 2 * REF.length / 3
    basis = np.cos(np.array([1, 2, 3]) * math.pi * z / REF.length)
    np.testing.assert_allclose(res.theta(z), basis @ res.q, rtol=1e-12, atol=1e-18)
    assert res.theta([0.0, z]).shape == (2, res.t.size)
    # odd modes alone stay odd: mode 2 and the rigid mode are never excited (model notes)
    odd = ds.simulate(REF.replace(initial_velocities=(0.1, 0.0, 0.05)), modes=3, rigid_mode=True, t_end=0.5)
    assert np.abs(odd.q[0]).max() == 0.0 and np.abs(odd.q[2]).max() == 0.0
    # ... while an even mode drives the rigid mode through the cubic coupling
    even = ds.simulate(REF, modes=3, rigid_mode=True, t_end=0.5)
    assert np.abs(even.q[0]).max() > 1e-9


def test_status_max_steps_raises_and_reports():
    with pytest.raises(SolveError) as err:
        ds.simulate(REF, modes=3, max_steps=5)
    assert err.value.status == "max_steps"
    res = ds.simulate(REF, modes=3, max_steps=5, check=False)
    assert res.status == "max_steps" and not res.success and "5" in res.message
    assert res.t.size < 1001 and np.all(np.isfinite(res.q))


@pytest.mark.parametrize("method", ["dop853", "dopri5", "rk4", "central"])
def test_divergent_system_ends_with_status(method):
    # q'' = +q^3, q(0) = 0, q'(0) = 1 blows up at t* = int_0^inf dq / sqrt(1 + q^4/2) = 2.2049...
    system = _core.ModalSystem(np.ones(1), np.zeros(1), np.zeros((1, 4), dtype=np.int64), np.array([-0.25]))
    out = _core.solve_modal(system, np.zeros(1), np.ones(1), 10.0, None, method, 1e-8, 1e-8, dt=1e-3)
    assert out["status"] in ("step_size_underflow", "non_finite")
    assert out["message"]
    assert np.all(np.isfinite(out["y"]))
    from scipy.integrate import quad

    t_star = quad(lambda q: 1 / math.sqrt(1 + q**4 / 2), 0, math.inf)[0]
    assert out["t"][-1] <= t_star + (1e-3 if method.startswith("dop") else 5e-3)  # fixed steps: a few dt
    assert out["t"][-1] > t_star - 0.05


BAD_OPTIONS = [
    ({"modes": 0}, "modes"),
    ({"modes": 2.5}, "modes"),
    ({"modes": True}, "modes"),
    ({"rigid_mode": "yes"}, "rigid_mode"),
    ({"t_end": 0.0}, "t_end"),
    ({"t_end": -1.0}, "t_end"),
    ({"t_end": math.inf}, "t_end"),
    ({"method": "euler"}, "method"),
    ({"rtol": 0.0}, "rtol"),
    ({"rtol": 1e-20}, "rtol"),
    ({"rtol": math.nan}, "rtol"),
    ({"atol": -1e-9}, "atol"),
    ({"dt": 0.0, "method": "rk4"}, "dt"),
    ({"dt": 2.0, "method": "rk4"}, "dt"),
    ({"t_eval": [0.0, 0.5, 0.2]}, "t_eval"),
    ({"t_eval": [0.0, 2.0]}, "t_eval"),
    ({"t_eval": [[0.0, 1.0]]}, "t_eval"),
    ({"t_eval": ["a"]}, "t_eval"),
    ({"t_eval": [math.nan]}, "t_eval"),
    ({"samples": 1}, "samples"),
    ({"max_steps": 0}, "max_steps"),
]


@pytest.mark.parametrize(("kwargs", "field"), BAD_OPTIONS)
def test_bad_solver_options(kwargs, field):
    with pytest.raises(ValidationError) as err:
        ds.simulate(REF, **kwargs)
    assert err.value.field == field
    assert field in str(err.value)


def test_bad_params_and_sections():
    with pytest.raises(ValidationError, match="params"):
        ds.simulate({"length": 100.0})  # type: ignore[arg-type]
    res = ds.simulate(REF, modes=1, t_end=0.01)
    for z in (-1.0, REF.length * 1.01, math.nan):
        with pytest.raises(ValidationError, match="z"):
            res.theta(z)


def test_core_rejects_bad_arrays():
    with pytest.raises(ValidationError, match="mass"):
        _core.ModalSystem(np.array([-1.0]), np.ones(1), np.zeros((0, 4), dtype=np.int64), np.zeros(0))
    with pytest.raises(ValidationError, match="quartic_index"):
        _core.ModalSystem(np.ones(1), np.ones(1), np.zeros((1, 3), dtype=np.int64), np.ones(1))
    with pytest.raises(ValidationError, match="quartic_index"):
        _core.ModalSystem(np.ones(1), np.ones(1), np.full((1, 4), 5, dtype=np.int64), np.ones(1))
    system = _core.ModalSystem(np.ones(2), np.ones(2), np.zeros((0, 4), dtype=np.int64), np.zeros(0))
    with pytest.raises(ValidationError, match="q0"):
        _core.solve_modal(system, np.zeros(3), np.zeros(2), 1.0, None, "dop853", 1e-6, 1e-9)
    with pytest.raises(ValidationError, match="q0"):
        _core.solve_modal(system, np.array([math.nan, 0.0]), np.zeros(2), 1.0, None, "dop853", 1e-6, 1e-9)


def test_linearised_model_is_harmonic():
    # nonlinear=False: q1(t) = (C1 / w1) sin(w1 t) exactly
    res = ds.simulate(REF, modes=1, nonlinear=False, t_end=1.0, rtol=1e-12, atol=1e-16)
    w1 = res.coefficients.linear_frequencies[0]
    np.testing.assert_allclose(res.q[0], 0.1 / w1 * np.sin(w1 * res.t), rtol=0, atol=1e-10 * 0.1 / w1)
    assert res.energy_drift() < 1e-10
    nonlinear = ds.simulate(REF, modes=1, t_end=1.0)
    assert np.abs(nonlinear.q[0] - res.q[0]).max() > 1e-5  # the cubic term shifts the phase visibly


def test_dense_output_evaluations_are_counted_apart():
    # the same steps with 2 or 1001 output times: nfev differs only by the dense-output stages
    sparse = ds.simulate(ds.preset("aluminum"), t_end=1.0, samples=2)
    dense = ds.simulate(ds.preset("aluminum"), t_end=1.0, samples=1001)
    assert sparse.stats.naccept == dense.stats.naccept and sparse.stats.nreject == dense.stats.nreject
    assert sparse.stats.ndense == 0  # output times only at step ends
    assert 0 < dense.stats.ndense <= 3 * dense.stats.naccept and dense.stats.ndense % 3 == 0
    assert dense.stats.nfev - dense.stats.ndense == sparse.stats.nfev - sparse.stats.ndense
    assert dense.stats.nfev == 2 + 12 * dense.stats.naccept + 11 * dense.stats.nreject + dense.stats.ndense
    assert ds.simulate(ds.preset("aluminum"), t_end=0.1, method="dopri5", samples=101).stats.ndense == 0
