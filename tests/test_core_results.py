"""The forms in which ``drillstring._core`` returns results (``_core.pyi``): dicts, numpy arrays of
the documented dtypes and shapes, lists where the stub says list, tuples where it says tuple."""

import json
import math

import numpy as np

from drillstring import _core


def test_a_solve_returns_2d_samples_and_plain_counters() -> None:
    pde = _core.PdeSystem(1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 11)
    out = _core.solve_pde(pde, np.zeros(11), np.full(11, 0.1), 0.1, np.linspace(0.0, 0.1, 5), "dop853", 1e-8, 1e-10)
    assert out["t"].dtype == np.float64 and out["t"].shape == (5,)
    assert out["y"].dtype == np.float64 and out["y"].shape == (5, 22)
    assert out["status"] == "success" and out["message"] == ""
    assert all(type(out[k]) is int for k in ("nfev", "naccept", "nreject", "ndense"))
    assert out["dissipated"] is None
    damped = _core.PdeSystem(1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 11, damping_rate=0.5)
    out = _core.solve_pde(damped, np.zeros(11), np.full(11, 0.1), 0.1, None, "dop853", 1e-8, 1e-10)
    assert out["dissipated"].shape == out["t"].shape and out["dissipated"][-1] > 0.0


def test_integer_arrays_keep_their_dtypes() -> None:
    g = _core.galerkin_integrals(3, True)
    assert g["indices"].dtype == np.int64 and list(g["indices"]) == [0, 1, 2, 3]
    assert g["quartic_index"].dtype == np.int64 and g["quartic_index"].shape == (len(g["cos4"]), 4)
    assert all(g["quartic_index"][t][0] <= g["quartic_index"][t][3] for t in range(len(g["cos4"])))


def test_stick_slip_warnings_are_a_list_even_when_empty() -> None:
    t = np.linspace(0.0, 10.0, 2001)
    settled = _core.stick_slip_metrics(t, np.full_like(t, 2.0))
    assert settled["warnings"] == [] and type(settled["warnings"]) is list
    assert type(settled["slip_onsets"]) is int and type(settled["stick_slip"]) is bool
    assert math.isnan(settled["motor_torque_max_Nm"])  # no torque series


def test_lumped_forms() -> None:
    eq = _core.lumped_equilibria("{}")
    assert type(eq["rotations"]) is list and eq["equilibrium"] in ("stable_rotation", "unstable", "stuck")
    for r in eq["rotations"]:
        assert type(r["eigenvalues"]) is list and len(r["eigenvalues"]) == 3
        assert all(type(e) is tuple and len(e) == 2 for e in r["eigenvalues"])
    run = _core.lumped_solve("{}", json.dumps({"duration": 2.0}))
    assert type(run["window"]) is tuple and len(run["window"]) == 2
    assert set(run["stats"]) == {"steps", "sticks", "slips"} and all(type(v) is int for v in run["stats"].values())
    assert run["t"].dtype == np.float64 and run["bit_speed"].shape == run["t"].shape


def test_configuration_results_are_what_json_gives() -> None:
    params, numerics = _core.lumped_defaults()
    assert params["tm"] == 6000.0 and params["wob"] == 50e3
    # lists, not tuples or arrays, as json.loads gives them
    assert type(numerics["initial"]) is list and numerics["window"] is None
    defaults = _core.drill_defaults()
    assert type(defaults["sections"]) is list and json.loads(json.dumps(defaults)) == defaults
