"""The finite-difference PDE solver through the Python API: accuracy, conservation, agreement
with the Galerkin models, errors."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core
from drillstring.errors import ValidationError

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

REF = ds.preset("aluminum")
ZK = 2 * REF.length / 3


def test_small_amplitude_matches_linear_modal_solution_with_second_order_in_space():
    # C1 = 1e-6 rad/s: linear regime; exact solution (C1/w1) sin(w1 t) cos(pi z / l)
    params = REF.replace(initial_velocities=(1e-6,))
    k = ds.PDECoefficients.from_parameters(params)
    w1 = math.sqrt((k.k2 * (math.pi / params.length) ** 2 - k.k6) / k.k1)
    t = np.array([0.0, 0.02, 0.05])
    exact = 1e-6 / w1 * np.sin(w1 * t) * math.cos(math.pi * ZK / params.length)
    errors = []
    for cells in (40, 80, 160):
        sol = ds.solve_pde(params, nodes=cells + 1, t_end=0.05, t_eval=t, rtol=1e-11, atol=1e-20)
        errors.append(np.abs(sol.theta(ZK) - exact).max())
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(rates - 2.0) < 0.1), rates
    assert errors[-1] < 1e-3 * 1e-6 / w1


def test_discrete_energy_is_conserved():
    sol = ds.solve_pde(REF, nodes=120, t_end=1.0, rtol=1e-12, atol=1e-16, samples=201)
    assert sol.energy_drift() < 1e-9
    # H(0) is the kinetic energy of theta_t = sum C_i cos(i pi z / l) with trapezoid weights
    v0 = np.asarray(sol._system.initial_velocity_from_modes(np.array(REF.initial_velocities)))
    w = np.asarray(sol._system.weights)
    k1 = ds.PDECoefficients.from_parameters(REF).k1
    assert sol.energy[0] == pytest.approx(0.5 * k1 * np.sum(w * v0**2), rel=1e-13)


SIMD_PROBE = """
import json, drillstring as ds
p = ds.preset("aluminum")
sol = ds.solve_pde(p, nodes=81, t_end=0.2, rtol=1e-11, atol=1e-15, samples=21)
modal = ds.simulate(p, modes=3, t_end=0.2, rtol=1e-11, atol=1e-15, samples=21)
zk = 2 * p.length / 3
# Drilling: the on-bottom example (sections at Courant numbers below 1, friction with sticking,
# damping) and Well B (Courant number 1 in both sections): series and energy terms.
drill = {}
for name in ("on-bottom-3000m", "aarsnes-shor-well-b"):
    cfg = ds.load_drill_config(EXAMPLES / f"{name}.toml").with_overrides(
        ["numerics.cells=203", "numerics.duration=12", "numerics.field_interval=0"])
    res = ds.drill(cfg)
    drill[name] = [res.bit_rpm.tolist(), res.motor_torque.tolist(), list(res.energy.values())]
print(json.dumps({"path": ds.simd_path(), "pde": sol.theta(zk).tolist(), "modal": modal.theta(zk).tolist(),
                  "drill": drill}))
"""


def _probe(simd: str | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "DRILLSTRING_SIMD"}
    if simd is not None:
        env["DRILLSTRING_SIMD"] = simd
    probe = f"from pathlib import Path\nEXAMPLES = Path({str(EXAMPLES)!r})\n" + SIMD_PROBE
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_vector_and_baseline_kernels_agree():
    # The hot loops run as AVX-512 or AVX2 code with FMA where the processor has it and as
    # baseline code otherwise (or with DRILLSTRING_SIMD=baseline): same solutions to well below
    # rtol. The two vector paths do the same operations in the same order: bit-identical.
    default, avx2, baseline = _probe(None), _probe("avx2"), _probe("baseline")
    assert default["path"] == ds.simd_path() in ("avx512+fma", "avx2+fma", "baseline")
    assert avx2["path"] in ("avx2+fma", "baseline") and baseline["path"] == "baseline"
    if avx2["path"] == "avx2+fma" and default["path"] != "baseline":
        assert avx2["pde"] == default["pde"] and avx2["modal"] == default["modal"]
    for key in ("pde", "modal"):
        a, b = np.array(default[key]), np.array(baseline[key])
        assert np.abs(a).max() > 1e-4  # a real response (~3e-4 rad at z_k)
        assert np.abs(a - b).max() < 1e-10 * np.abs(a).max(), key
    # The drilling kernels use no fused multiply-adds: every path gives the same bits.
    assert default["drill"] == avx2["drill"] == baseline["drill"]
    assert min(np.ptp(series[0]) for series in default["drill"].values()) > 10.0  # stick-slip, rpm


def test_verlet_is_bounded_and_close_to_dop853():
    ref = ds.solve_pde(REF, nodes=121, t_end=1.0, rtol=1e-11, atol=1e-15, samples=501)
    ver = ds.solve_pde(REF, nodes=121, t_end=1.0, method="verlet", samples=501)
    assert ver.energy_drift() < 1e-3  # O(dt^2), no secular growth
    scale = np.abs(ref.theta(ZK)).max()
    assert np.abs(ver.theta(ZK) - ref.theta(ZK)).max() < 1e-2 * scale


def test_galerkin_with_rigid_mode_converges_to_pde():
    # with i = 0 the modal error falls with modes to the PDE's own grid error; without it, it stalls
    t = np.linspace(0.0, 0.5, 501)
    pde = ds.solve_pde(REF, nodes=481, t_end=0.5, t_eval=t, rtol=1e-10, atol=1e-14).theta(ZK)
    scale = np.abs(pde).max()
    err = {}
    for n in (3, 6, 12):
        for rigid in (False, True):
            res = ds.simulate(REF, modes=n, rigid_mode=rigid, t_end=0.5, t_eval=t, rtol=1e-12, atol=1e-16)
            err[n, rigid] = np.abs(res.theta(ZK) - pde).max() / scale
    assert err[3, True] < err[3, False] / 4
    assert err[12, True] < err[6, True] < err[3, True]
    assert err[12, True] < 2e-3  # the grid error of N = 481 at t <= 0.5
    assert min(err[n, False] for n in (3, 6, 12)) > 0.05  # the paper's basis stalls


def test_pde_frequencies_approach_modal_frequencies():
    system = ds.solvers.pde.pde_system(REF, 241)
    w2 = np.asarray(system.linear_frequencies_squared(4))
    k = ds.PDECoefficients.from_parameters(REF)
    exact = (k.k2 * (np.arange(4) * math.pi / REF.length) ** 2 - k.k6) / k.k1
    assert w2[0] == pytest.approx(exact[0], rel=1e-9)  # the rigid mode, -Omega^2
    np.testing.assert_allclose(w2[1:], exact[1:], rtol=2e-4)


def test_initial_fields_and_field_output(tmp_path):
    sol = ds.solve_pde(
        REF, nodes=61, t_end=0.01, samples=11, save_field_every=5,
        initial_twist=lambda z: 1e-5 * np.cos(math.pi * z / REF.length), initial_velocity=np.zeros(61),
    )
    assert sol.field.shape == (61, 3) and sol.field_t.tolist() == pytest.approx([0.0, 0.005, 0.01])
    np.testing.assert_allclose(sol.theta(0.0)[0], 1e-5)
    np.testing.assert_allclose(sol.theta(REF.length / 2)[0], 0.0, atol=1e-20)
    path = tmp_path / "field.npz"
    sol.save_field(path)
    data = np.load(path)
    assert data["theta"].shape == (61, 3) and data["z"][-1] == REF.length


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"nodes": 2}, "nodes"),
        ({"nodes": 10.5}, "nodes"),
        ({"method": "euler"}, "method"),
        ({"rtol": -1.0}, "rtol"),
        ({"t_end": 0.0}, "t_end"),
        ({"save_field_every": 0}, "save_field_every"),
        ({"initial_twist": np.zeros(5)}, "initial_twist"),
        ({"initial_velocity": np.full(240, np.nan)}, "initial_velocity"),
        ({"initial_velocity": "abc"}, "initial_velocity"),
        ({"t_eval": [0.5, 0.1]}, "t_eval"),
    ],
)
def test_bad_input(kwargs, field):
    with pytest.raises(ValidationError) as err:
        ds.solve_pde(REF, **kwargs)
    assert err.value.field == field


def test_core_pde_errors():
    with pytest.raises(ValidationError, match="nodes"):
        _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2)
    with pytest.raises(ValidationError, match="k2"):
        _core.PdeSystem(1.0, math.nan, 0.0, 0.0, 0.0, 0.0, 1.0, 5)
    system = _core.PdeSystem(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 5)
    with pytest.raises(ValidationError, match="q0"):
        _core.solve_pde(system, np.zeros(4), np.zeros(5), 1.0, None, "dop853", 1e-6, 1e-9)


def test_pde_cli(tmp_path):
    from drillstring.cli import main

    out, png, npz = tmp_path / "p.csv", tmp_path / "p.png", tmp_path / "f.npz"
    code = main(["pde", "--nodes", "61", "--t-end", "0.05", "--samples", "51", "--out", str(out),
                 "--plot", str(png), "--field", str(npz)])
    assert code == 0
    assert out.read_text().splitlines()[0] == "t,theta,theta_dot"
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    sol = ds.solve_pde(REF, nodes=61, t_end=0.05, samples=51)
    np.testing.assert_allclose(data[:, 1], sol.theta(ZK), rtol=1e-9, atol=1e-16)
    assert png.read_bytes()[:4] == b"\x89PNG" and np.load(npz)["theta"].shape == (61, 51)
    assert main(["pde", "--nodes", "2"]) == 2


def test_convergence_study_small():
    from drillstring.studies import convergence

    res = convergence.study(REF, t_end=0.2, samples=201, modes=(3, 8), cells=60, max_nodes=241, tol=1e-3)
    assert res.converged and res.grids[-1].nodes == 241
    diffs = [g.difference for g in res.grids if g.difference is not None]
    assert diffs[0] / diffs[1] == pytest.approx(4.0, rel=0.1)  # second order
    assert res.error(8, True) < res.error(3, True) < res.error(3, False)


def test_the_node_limit_is_the_cores() -> None:
    # one number: the Python check asks the core's limit
    assert ds.solvers.pde.MAX_NODES == _core.PDE_MAX_NODES == 10_000_000
    with pytest.raises(ds.ValidationError, match="nodes"):
        ds.solvers.pde.pde_system(ds.preset("aluminum"), nodes=_core.PDE_MAX_NODES + 1)
