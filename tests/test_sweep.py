"""Parameter sweeps: Rust-scaled coefficients, metrics on known cases, fault isolation, grids."""

from __future__ import annotations

import math

import numpy as np
import pytest

pd = pytest.importorskip("pandas")

import drillstring as ds  # noqa: E402
from drillstring import _core  # noqa: E402
from drillstring.model.coefficients import PDECoefficients  # noqa: E402
from drillstring.model.galerkin import dimensionless_integrals  # noqa: E402
from drillstring.studies.analysis import dominant_frequencies  # noqa: E402
from drillstring.studies.sweep_axes import expand_axes  # noqa: E402

ALUMINUM = ds.preset("aluminum")
FAST = {"t_end": 0.2, "samples": 256}


def critical_speed(params: ds.Parameters, i: int = 1) -> float:
    g = params.youngs_modulus / (2 * (1 + params.poisson_ratio))
    return i * math.pi / params.length * math.sqrt(4 * g / params.density)


# --------------------------------------------------------------------------- coefficients


@pytest.mark.parametrize(
    ("params", "modes", "rigid"),
    [
        (ALUMINUM, 1, False),
        (ALUMINUM.replace(length=250.0, omega=40.0), 3, True),
        (ds.preset("steel").replace(k5_variant="energy", outer_diameter=0.3, inner_diameter=0.0), 5, False),
        (ALUMINUM.replace(length=37.5, omega=-300.0, poisson_ratio=0.1), 4, True),
    ],
)
def test_rust_scaled_coefficients_equal_projection(params, modes, rigid):
    g = dimensionless_integrals(modes, rigid)
    k = np.array(PDECoefficients.from_parameters(params).as_tuple())
    scaled = _core.scale_integrals(
        k, params.length, g.indices, np.ascontiguousarray(g.quartic_index), g.cos4, g.mixed, g.sin4
    )
    ref = ds.project(params, modes=modes, rigid_mode=rigid)
    np.testing.assert_array_equal(ref.quartic_index, g.quartic_index)
    for name, want in (("mass", ref.mass), ("stiffness", ref.stiffness), ("quartic_coef", ref.quartic_coef)):
        np.testing.assert_allclose(scaled[name], want, rtol=1e-13, atol=0, err_msg=name)


# --------------------------------------------------------------------------- metrics on known cases


def test_one_mode_dominant_frequency_is_the_exact_duffing_frequency():
    from scipy.special import ellipk

    runs = [ALUMINUM.replace(length=length, initial_velocities=(c,)) for length in (100.0, 300.0) for c in (0.1, 1.0)]
    table = ds.sweep(runs=runs, modes=1, t_end=1.0, rtol=1e-10, samples=2048)
    assert (table["status"] == "success").all()
    nonlinear_shift = []
    for params, got in zip(runs, table["dominant_frequency_hz"]):
        a1, a2, a3 = ds.project(params, modes=1).duffing()
        w2, beta, c = a2 / a1, a3 / a1, params.initial_velocities[0]
        amp2 = 2 * c * c / (w2 + math.sqrt(w2 * w2 + 2 * beta * c * c))  # from the energy
        stiff = w2 + beta * amp2
        exact = math.sqrt(stiff) / (4 * ellipk(beta * amp2 / (2 * stiff)))
        assert got == pytest.approx(exact, rel=5e-3)
        nonlinear_shift.append(abs(exact / (math.sqrt(w2) / (2 * math.pi)) - 1))
    assert max(nonlinear_shift) > 0.5  # the linear frequency would fail this test


def test_unstable_mode_count_flips_at_the_critical_speed():
    rows = []
    for length in (100.0, 250.0):
        crit = critical_speed(ALUMINUM.replace(length=length))
        rows += [{"length": length, "omega": crit * f} for f in (0.999, 1.001, 2.001, 3.001)]
    table = ds.sweep(ALUMINUM, runs=rows, modes=3, t_end=0.05, samples=64)
    assert table["unstable_modes"].tolist() == [0, 1, 2, 3] * 2
    rigid = ds.sweep(ALUMINUM, runs=rows[:2], modes=3, rigid_mode=True, t_end=0.05, samples=64)
    assert rigid["unstable_modes"].tolist() == [1, 2]  # K_00 = -k6 l < 0 whenever omega != 0


def test_metrics_agree_with_simulate():
    params = ALUMINUM.replace(length=180.0, omega=5.0)
    table, traj = ds.sweep(runs=[params], modes=3, rigid_mode=True, t_end=0.5, rtol=1e-10, samples=500,
                           trajectories=True)
    row = table.iloc[0]
    res = ds.simulate(params, modes=3, rigid_mode=True, t_end=0.5, rtol=1e-10, samples=500)
    theta = res.theta(2 * params.length / 3)
    assert row["max_theta"] == pytest.approx(np.abs(theta).max(), rel=1e-8)
    assert row["rms_theta"] == pytest.approx(np.sqrt(np.mean(theta**2)), rel=1e-8)
    assert row["dominant_frequency_hz"] == pytest.approx(dominant_frequencies(res.t, theta, 1)[0], rel=1e-8)
    assert row["energy_drift"] == pytest.approx(res.energy_drift(), rel=1e-3, abs=1e-12)
    assert row["nfev"] == res.stats.nfev
    energies = 0.5 * (res.coefficients.mass[:, None] * res.qdot**2 + res.coefficients.stiffness[:, None] * res.q**2)
    total = energies.sum(axis=0)
    shares = (energies[:, total > 0] / total[total > 0]).max(axis=1)
    got = row[[f"share_mode_{i}" for i in (0, 1, 2, 3)]].to_numpy(dtype=float)
    np.testing.assert_allclose(got, shares, rtol=1e-8)
    np.testing.assert_allclose(traj.theta[0], theta, rtol=1e-8, atol=1e-14)
    np.testing.assert_allclose(traj.q[0], res.q, rtol=1e-8, atol=1e-14)
    np.testing.assert_array_equal(traj.t, res.t)


# --------------------------------------------------------------------------- faults


def test_faults_are_rows_and_leave_other_runs_unaffected():
    good = [{"length": 100.0}, {"length": 150.0}, {"length": 200.0}]
    bad_geometry = {"inner_diameter": 0.3}  # > outer_diameter
    too_many_steps = {"length": 30.0}  # ~1900 steps for t_end = 0.5 > max_steps
    runs = [good[0], bad_geometry, good[1], too_many_steps, good[2], {"poisson_ratio": "x"}]
    options = {"modes": 3, "t_end": 0.5, "samples": 256, "max_steps": 1000, "chunk_size": 4}
    table = ds.sweep(ALUMINUM, runs=runs, **options)
    assert table["status"].tolist() == ["success", "invalid", "success", "max_steps", "success", "invalid"]
    assert "inner_diameter" in table.loc[1, "message"] and "outer_diameter" in table.loc[1, "message"]
    assert "max_steps = 1000" in table.loc[3, "message"]
    assert table.loc[1, "inner_diameter"] == 0.3  # the requested value is shown
    assert math.isnan(table.loc[5, "poisson_ratio"])
    assert table.loc[[1, 5], "unstable_modes"].isna().all()
    assert table.loc[[1, 3, 5], "max_theta"].isna().all()
    assert table.loc[3, "nfev"] > 0
    alone = ds.sweep(ALUMINUM, runs=good, **options)
    pd.testing.assert_frame_equal(table.loc[[0, 2, 4]].reset_index(drop=True), alone)


def test_shared_options_are_validated_up_front():
    with pytest.raises(ds.ValidationError, match="rtol"):
        ds.sweep(ALUMINUM, {"length": [100.0]}, rtol=-1.0)
    with pytest.raises(ds.ValidationError, match="samples"):
        ds.sweep(ALUMINUM, {"length": [100.0]}, samples=2)
    with pytest.raises(ds.ValidationError, match="grid"):
        ds.sweep(ALUMINUM, {"lenght": [100.0]})
    with pytest.raises(ds.ValidationError, match="modes"):
        ds.sweep(ALUMINUM, {"length": [100.0]}, modes=0)
    with pytest.raises(ds.ValidationError, match="either axes or"):
        ds.sweep(ALUMINUM, {"length": [100.0]}, runs=[{}])


# --------------------------------------------------------------------------- grids and table


def test_grid_axes_and_product_order():
    axes, runs = expand_axes({
        "length": ds.linspace(100.0, 300.0, 3),
        "omega": {"logspace": [0.1, 10.0, 3]},
        "c2": [0.0, 0.5],
    })
    assert axes["length"] == [100.0, 200.0, 300.0]
    np.testing.assert_allclose(axes["omega"], [0.1, 1.0, 10.0])
    assert len(runs) == 18 and runs[1] == {"length": 100.0, "omega": 0.1, "c2": 0.5}
    with pytest.raises(ds.ValidationError, match="not powers of ten"):
        expand_axes({"omega": ds.logspace(-1, 2, 4)})
    with pytest.raises(ds.ValidationError, match="linspace"):
        expand_axes({"omega": {"linspace": [0, 1]}})


def test_table_columns_and_velocity_keys():
    table = ds.sweep(ALUMINUM, {"c1": [0.05, 0.1], "k5_variant": ["paper", "energy"]}, modes=2, **FAST)
    assert list(table.columns) == [
        "length", "youngs_modulus", "density", "poisson_ratio", "outer_diameter", "inner_diameter", "omega",
        "c1", "c2", "c3", "k5_variant", "model", "damping_rate", "z", "status", "message", "max_theta", "rms_theta",
        "dominant_frequency_hz", "energy_drift", "unstable_modes", "nfev", "share_mode_1", "share_mode_2",
    ]
    assert table["c1"].tolist() == [0.05, 0.05, 0.1, 0.1]
    assert table["c2"].tolist() == [0.05] * 4 and table["k5_variant"].tolist() == ["paper", "energy"] * 2
    assert table["z"].tolist() == pytest.approx([200.0 / 3] * 4)
    assert (table["status"] == "success").all() and (table["message"] == "").all()
    assert table.attrs["axes"] == {"c1": [0.05, 0.1], "k5_variant": ["paper", "energy"]}
    # larger C1, larger response; the k5 variant barely matters at these amplitudes
    assert table["max_theta"].iloc[2] > 1.5 * table["max_theta"].iloc[0]
    assert table["max_theta"].iloc[1] == pytest.approx(table["max_theta"].iloc[0], rel=1e-3)


def test_thread_count_and_chunking_do_not_change_the_table():
    grid = {"length": ds.linspace(100.0, 200.0, 4), "omega": [0.0, 20.0, 40.0]}
    one = ds.sweep(ALUMINUM, grid, threads=1, chunk_size=5, **FAST)
    two = ds.sweep(ALUMINUM, grid, threads=2, chunk_size=100, **FAST)
    pd.testing.assert_frame_equal(one, two)


def test_progress_bar_on_request(capsys):
    ds.sweep(ALUMINUM, {"length": [100.0, 120.0]}, chunk_size=1, progress=True, **FAST)
    err = capsys.readouterr().err
    assert "2/2 runs" in err and "1/2 runs" in err and err.endswith("\n")
    ds.sweep(ALUMINUM, {"length": [100.0]}, progress=False, **FAST)
    assert capsys.readouterr().err == ""


def test_per_run_coefficients_are_those_of_the_parameters():
    import importlib

    sweep_module = importlib.import_module("drillstring.studies.sweeps")
    cache: dict = {}
    for params in (ALUMINUM, ALUMINUM.replace(omega=-7.3, length=3.0), ds.preset("steel").replace(k5_variant="energy"),
                   ALUMINUM.replace(omega=123.4, inner_diameter=0.0)):
        assert sweep_module._coefficients(params, cache) == PDECoefficients.from_parameters(params).as_tuple()
    assert len(cache) == 3  # k1..k5 shared by the runs of one material and section
