"""Viscous damping (``Parameters.damping_rate``): decay of linear modes at ``c / 2`` against the
exact damped oscillator, the energy balance ``H(t) + dissipated(t) = H(0)``, the undamped model
unchanged, the methods that refuse velocity-dependent forces, and the damped linearisation."""

from __future__ import annotations

import math

import numpy as np
import oracles
import pytest

import drillstring as ds
from drillstring import _core
from drillstring.errors import ValidationError
from drillstring.studies.stability import analyse, jacobian

C = 4.0  # 1/s
ONE_MODE = ds.Parameters(initial_velocities=(0.01,))


def _damped(w: float, c: float, v0: float, t: np.ndarray) -> np.ndarray:
    """``x(t) = v0 / wd e^{-c t / 2} sin(wd t)``, ``wd = sqrt(w^2 - c^2 / 4)``: the solution of
    ``x'' + c x' + w^2 x = 0``, ``x(0) = 0``, ``x'(0) = v0``."""
    wd = math.sqrt(w * w - 0.25 * c * c)
    return v0 / wd * np.exp(-0.5 * c * t) * np.sin(wd * t)


@pytest.mark.parametrize("method, dt, tol", [("dop853", None, 1e-8), ("dopri5", None, 1e-6), ("rk4", 1e-4, 1e-6)])
def test_damped_linear_mode_is_the_damped_oscillator(method: str, dt: float, tol: float) -> None:
    params = ONE_MODE.replace(damping_rate=C)
    res = ds.simulate(params, modes=1, t_end=1.0, method=method, dt=dt, nonlinear=False, samples=701,
                      rtol=1e-11, atol=1e-14)
    w = math.sqrt(res.coefficients.stiffness[0] / res.coefficients.mass[0])
    exact = _damped(w, C, 0.01, res.t)
    amplitude = 0.01 / w
    assert np.max(np.abs(res.q[0] - exact)) < tol * amplitude
    # the envelope: the energy of a linear mode decays as exp(-c t) on average over a period
    assert res.energy[-1] / res.energy[0] == pytest.approx(math.exp(-C * 1.0), rel=0.05)


def test_damped_pde_mode_decays_at_half_the_damping_rate() -> None:
    """The linear PDE (cubic terms negligible at this amplitude) from theta_t = C cos(pi z / l):
    the first mode's amplitude follows the damped oscillator of the grid's own frequency."""
    params = ds.Parameters(initial_velocities=(1e-6,), damping_rate=C, omega=0.0)
    nodes = 121
    system = ds.solvers.pde.pde_system(params, nodes)
    w = math.sqrt(system.linear_frequencies_squared(2)[1])
    sol = ds.solve_pde(params, nodes=nodes, t_end=0.5, samples=1001, rtol=1e-11, atol=1e-20)
    exact = _damped(w, C, 1e-6, sol.t)
    # theta at z = 0 is the mode amplitude (cos 0 = 1)
    assert np.max(np.abs(sol.q[0] - exact)) < 1e-6 * 1e-6 / w
    ratio = np.max(np.abs(sol.q[0][sol.t > 0.45])) / np.max(np.abs(sol.q[0][sol.t < 0.05]))
    assert ratio == pytest.approx(math.exp(-0.5 * C * 0.45), rel=0.05)


@pytest.mark.parametrize("rtol, bound", [(1e-7, 1e-5), (1e-10, 1e-8)])
def test_energy_balance_closes_to_the_tolerance_for_a_nonlinear_run(rtol: float, bound: float) -> None:
    params = ds.preset("aluminum").replace(damping_rate=3.0)
    res = ds.simulate(params, modes=3, rigid_mode=True, t_end=1.0, rtol=rtol, atol=rtol * 1e-3)
    assert res.dissipated is not None and res.dissipated[0] == 0.0
    assert np.all(np.diff(res.dissipated) >= 0)
    assert res.dissipated[-1] > 0.9 * res.energy[0]  # most of the energy has gone
    balance = res.energy + res.dissipated - res.energy[0]
    assert res.energy_drift() == pytest.approx(np.max(np.abs(balance)) / res.energy[0])
    assert res.energy_drift() < bound
    # the energy alone is far from conserved: the balance is what closes
    assert abs(res.energy[-1] - res.energy[0]) / res.energy[0] > 0.9


def test_energy_balance_of_the_damped_pde() -> None:
    params = ds.preset("aluminum").replace(damping_rate=2.0)
    sol = ds.solve_pde(params, nodes=60, t_end=0.2, samples=401, rtol=1e-10, atol=1e-14)
    assert sol.dissipated is not None
    assert sol.energy_drift() < 1e-8
    assert sol.dissipated[-1] > 0.2 * sol.energy[0]


def test_zero_damping_is_the_undamped_model_bit_for_bit() -> None:
    params = ds.preset("aluminum")
    assert params.damping_rate == 0.0
    t = np.linspace(0.0, 0.2, 401)
    for method, dt in (("dop853", None), ("rk4", 1e-4), ("central", 1e-4), ("verlet", 1e-4)):
        res = ds.simulate(params, modes=3, t_end=0.2, t_eval=t, method=method, dt=dt)
        assert res.dissipated is None
        coefficients = res.coefficients
        system = _core.ModalSystem(
            coefficients.mass, coefficients.stiffness,
            np.ascontiguousarray(coefficients.quartic_index, dtype=np.int64), coefficients.quartic_coef,
        )
        q0, v0 = coefficients.initial_state(params)
        raw = _core.solve_modal(system, q0, v0, 0.2, t, method, 1e-9, 1e-12, dt=dt)
        assert raw["dissipated"] is None
        assert np.array_equal(np.asarray(raw["y"]).T[:3], res.q)


def test_every_method_with_zero_damping_and_refusals_with_damping() -> None:
    damped = ds.preset("aluminum").replace(damping_rate=0.5)
    for method in ("central", "verlet"):
        with pytest.raises(ValidationError) as info:
            ds.simulate(damped, modes=2, t_end=0.01, method=method)
        assert info.value.field == "method" and "dop853" in str(info.value)
        with pytest.raises(ValidationError) as info:
            ds.solve_pde(damped, nodes=20, t_end=0.01, method=method)
        assert info.value.field == "method"
    for method in ("dop853", "dopri5", "rk4"):
        assert ds.simulate(damped, modes=2, t_end=0.01, method=method).success


def test_damping_rate_field_round_trips(tmp_path) -> None:
    p = ds.Parameters(damping_rate=2.5)
    assert p.to_dict()["damping_rate"] == 2.5
    assert ds.Parameters.from_dict(p.to_dict()) == p
    path = p.save(tmp_path / "damped.toml")
    assert ds.load(path) == p
    assert p.replace(damping_rate=0).damping_rate == 0.0
    assert ds.solvers.pde.pde_system(p, 10).damping_rate == 2.5


def test_cli_damping_rate(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    from drillstring.cli import main

    out = tmp_path / "run.csv"
    code = main(["simulate", "--modes", "1", "--t-end", "0.05", "--samples", "101", "--damping-rate", "3",
                 "--out", str(out)])
    assert code == 0
    theta = np.loadtxt(out, delimiter=",", skiprows=1)[:, 1]
    params = ds.Parameters()
    damped = ds.simulate(params.replace(damping_rate=3.0), modes=1, t_end=0.05, samples=101)
    undamped = ds.simulate(params, modes=1, t_end=0.05, samples=101)
    z = 2 * params.length / 3
    # the option reaches the model: the CSV is the damped run, not the undamped one
    np.testing.assert_allclose(theta, damped.theta(z), rtol=1e-9, atol=1e-16)
    assert np.max(np.abs(theta - undamped.theta(z))) > 1e-3 * np.max(np.abs(theta))


def test_sweep_energy_drift_is_the_balance_error() -> None:
    table = ds.sweep(ds.preset("aluminum"), {"damping_rate": [0.0, 5.0]}, modes=2, t_end=0.3, samples=512,
                     rtol=1e-10, threads=1)
    assert (table["status"] == "success").all()
    assert table["damping_rate"].tolist() == [0.0, 5.0]
    assert (table["energy_drift"] < 1e-7).all()
    # the same number as the single solve at the sweep's output times
    res = ds.simulate(ds.preset("aluminum").replace(damping_rate=5.0), modes=2, t_end=0.3,
                      t_eval=np.linspace(0.0, 0.3, 512), rtol=1e-10, atol=1e-12)
    assert table["energy_drift"].iloc[1] == pytest.approx(res.energy_drift(), rel=1e-6, abs=1e-12)
    assert table["max_theta"].iloc[1] < table["max_theta"].iloc[0]


def test_stability_of_a_damped_mode_is_a_stable_focus() -> None:
    params = ds.preset("aluminum")
    undamped = analyse(params, modes=2)
    assert undamped.classification == "centre"
    damped = analyse(params.replace(damping_rate=C), modes=2)
    assert damped.classification == "stable focus" and damped.stable
    assert oracles.classify_eigenvalues(damped.eigenvalues) == "stable focus"
    # every eigenvalue -c/2 +- i sqrt(w^2 - c^2/4)
    assert np.allclose(damped.eigenvalues.real, -C / 2, rtol=1e-9)
    w2 = undamped.mode_eigenvalues.imag**2
    assert np.allclose(damped.mode_eigenvalues.imag, np.sqrt(w2 - C * C / 4), rtol=1e-12)
    assert np.allclose(damped.linear_frequencies_hz, np.sqrt(w2 - C * C / 4) / (2 * math.pi))
    # the Jacobian's damping block
    coefficients = ds.project(params, modes=2)
    jac = jacobian(coefficients, C)
    assert np.array_equal(jac[2:, 2:], -C * np.eye(2))
    assert np.array_equal(jacobian(coefficients)[2:, 2:], np.zeros((2, 2)))
    # overdamped: c^2 / 4 > w^2 gives a stable node
    w_max = float(np.max(np.sqrt(w2)))
    node = analyse(coefficients, damping_rate=2.5 * w_max)
    assert node.classification == "stable node" and oracles.classify_eigenvalues(node.eigenvalues) == "stable node"
    assert np.all(np.isnan(node.linear_frequencies_hz))
    # a mode above its critical speed stays a saddle with damping
    fast = analyse(params.replace(omega=250.0, damping_rate=C), modes=1)
    assert fast.classification == "saddle"


def test_xarray_export_holds_the_dissipated_energy() -> None:
    res = ds.simulate(ds.preset("aluminum").replace(damping_rate=1.0), modes=2, t_end=0.05)
    data = res.to_xarray()
    assert np.array_equal(data["dissipated"].values, res.dissipated)
    assert data["dissipated"].attrs["units"] == "J"
    assert "dissipated" not in ds.simulate(ds.preset("aluminum"), modes=2, t_end=0.05).to_xarray()
