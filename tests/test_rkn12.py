"""The RKN12(10) integrator and method="auto" through the Python API and the CLI."""

from __future__ import annotations

import numpy as np
import pytest
from _cli import one_line_error, run_cli
from test_simulate import crossings, duffing_period

import drillstring as ds
from drillstring import _core
from drillstring.errors import ValidationError

REF = ds.preset("aluminum")


def test_rkn12_agrees_with_dop853_to_tolerance():
    kw = dict(modes=3, t_end=0.5, rtol=1e-12, atol=1e-17, samples=5001)
    rkn = ds.simulate(REF, method="rkn12", **kw)
    dop = ds.simulate(REF, method="dop853", **kw)
    assert rkn.method == "rkn12" and rkn.success
    np.testing.assert_array_equal(rkn.t, dop.t)
    scale = np.abs(dop.q).max()
    assert np.abs(rkn.q - dop.q).max() < 1e-9 * scale
    assert np.abs(rkn.qdot - dop.qdot).max() < 1e-9 * np.abs(dop.qdot).max()
    # several times fewer evaluations than DOP853 at this tolerance
    assert rkn.stats.nfev * 2 < dop.stats.nfev
    assert rkn.energy_drift() < 1e-10


@pytest.mark.parametrize("t_end", [0.3, 0.6, 0.9])
def test_rkn12_dense_output_as_accurate_at_both_ends_of_the_span(t_end):
    """The samples of the first and last intervals are no less accurate than the others:
    their interpolants take two steps before t0 and two beyond t_end (without them the last
    interval was up to 40 times less accurate here, the first 200 times)."""
    t = np.linspace(0.0, t_end, 20001)
    kw = dict(modes=3, t_end=t_end, t_eval=t)
    ref = ds.simulate(REF, method="rkn12", rtol=3e-14, atol=1e-20, **kw)
    res = ds.simulate(REF, method="rkn12", rtol=3e-11, atol=3e-11, **kw)
    err = np.abs(res.qdot - ref.qdot).max(axis=0) / np.abs(ref.qdot).max()
    edge = (t < 0.005) | (t > t_end - 0.005)
    assert err[edge].max() <= err[~edge].max(), (err[edge].max(), err[~edge].max())
    assert err.max() < 1e-8


@pytest.mark.parametrize("c1", [0.1, 3.0])
def test_rkn12_one_mode_period_equals_exact_duffing_period(c1):
    params = REF.replace(initial_velocities=(c1,))
    a1, a2, a3 = ds.model.galerkin.project(params, modes=1).duffing()
    exact = duffing_period(a1, a2, a3, c1)
    res = ds.simulate(params, modes=1, t_end=0.5, method="rkn12", rtol=1e-12, atol=1e-15, samples=50001)
    measured = np.diff(crossings(res.t, res.q[0])).mean()
    assert measured == pytest.approx(exact, rel=1e-7)


def test_auto_picks_rkn12_when_undamped_and_tight():
    tight = ds.simulate(REF, modes=3, t_end=0.1, method="auto", rtol=1e-12, samples=101)
    loose = ds.simulate(REF, modes=3, t_end=0.1, method="auto", rtol=1e-6, samples=101)
    damped = ds.simulate(REF.replace(damping_rate=2.0), modes=3, t_end=0.1, method="auto", rtol=1e-12, samples=101)
    assert (tight.method, loose.method, damped.method) == ("rkn12", "dop853", "dop853")
    # the rule is the core's: the result is the named method's, bit for bit
    named = ds.simulate(REF, modes=3, t_end=0.1, method="rkn12", rtol=1e-12, samples=101)
    np.testing.assert_array_equal(tight.q, named.q)
    assert _core.resolve_method("auto", False, _core.AUTO_RKN12_MAX_RTOL) == "rkn12"
    assert _core.resolve_method("auto", False, 2 * _core.AUTO_RKN12_MAX_RTOL) == "dop853"


def test_rkn12_refuses_damping_naming_method():
    with pytest.raises(ValidationError) as info:
        ds.simulate(REF.replace(damping_rate=1.0), modes=3, t_end=0.01, method="rkn12")
    assert info.value.field == "method"
    assert "rkn12" in str(info.value)


def test_rkn12_in_the_pde_solver():
    res = ds.solve_pde(REF, nodes=41, t_end=0.02, method="rkn12", rtol=1e-10, atol=1e-14, samples=201)
    ref = ds.solve_pde(REF, nodes=41, t_end=0.02, method="dop853", rtol=1e-12, atol=1e-16, samples=201)
    assert res.method == "rkn12"
    assert np.abs(res.theta(50.0) - ref.theta(50.0)).max() < 1e-7 * np.abs(ref.theta(50.0)).max()


def test_sweeps_take_rkn12_but_not_auto():
    rows = [{"initial_velocities": (1.0, 0.5, 0.2)}]
    kw = dict(runs=rows, modes=3, t_end=0.05, samples=64, rtol=1e-11, atol=1e-16)
    table, ref = ds.sweep(REF, method="rkn12", **kw), ds.sweep(REF, method="dop853", **kw)
    assert table["status"].iloc[0] == "success"
    assert table["energy_drift"].iloc[0] < 1e-9
    assert table["max_theta"].iloc[0] == pytest.approx(ref["max_theta"].iloc[0], rel=1e-9)
    assert table["rms_theta"].iloc[0] == pytest.approx(ref["rms_theta"].iloc[0], rel=1e-9)
    assert table["nfev"].iloc[0] < ref["nfev"].iloc[0]
    with pytest.raises(ValidationError) as info:
        ds.sweep(REF, runs=rows, modes=3, t_end=0.05, samples=64, method="auto")
    assert info.value.field == "method"


def test_cli_method_rkn12(capsys):
    code, out, _ = run_cli(capsys, "simulate", "--modes", "2", "--t-end", "0.01", "--method", "rkn12")
    assert code == 0 and out.startswith("rkn12:")
    code, _, err = run_cli(
        capsys, "simulate", "--damping-rate", "1", "--method", "rkn12", "--t-end", "0.01"
    )
    assert code != 0
    one_line_error(err, "method")
