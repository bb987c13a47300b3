"""The coupled axial-torsional run from Python: the ``[hoist]`` table and ``bit.law`` keys, the
axial series and the coupled metrics against the Detournay law's steady state worked by hand."""

from __future__ import annotations

import math

import pytest

from drillstring.drilling import DrillConfig, drill
from drillstring.drilling.config import Hoist
from drillstring.drilling.result import COUPLED_REGIME_CRITERION
from drillstring.errors import ValidationError

PIPE = {"length": 200.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
        "shear_modulus": 200e9 / 2.6, "density": 8000.0, "poisson_ratio": 0.3}


def _config(law: str = "detournay", **hoist: object) -> DrillConfig:
    return DrillConfig.from_dict({
        "sections": [PIPE], "well": {"inclination_deg": 0.0}, "friction": {"static": 0.0},
        "damping_rate": 10.0,
        "top_drive": {"rpm": 120.0, "ramp_time": 2.0, "controller": {"type": "speed"}},
        "bit": {"radius": 0.108, "law": law}, "hoist": {"speed": 30.0 / 3600.0, "ramp_time": 2.0, **hoist},
        "numerics": {"cells": 100, "duration": 60.0, "output_interval": 0.01}, "metrics": {"window": [50.0, 60.0]},
    })


def test_the_coupled_run_settles_to_the_bit_law_steady_state() -> None:
    result = drill(_config())
    assert result.success, result.message
    # d = 2 pi V / Omega; W = a zeta eps d + a l sigma; T = a^2 eps d / 2 + mu a (a l sigma) / 2
    a, eps, zeta, sigma, wear, mu = 0.108, 60e6, 0.6, 60e6, 0.011, 0.6
    d = 2 * math.pi * (30 / 3600) / (120 * 2 * math.pi / 60)
    w = a * zeta * eps * d + a * wear * sigma
    t = a * a * eps * d / 2 + mu * a * (a * wear * sigma) / 2
    m = result.coupled_metrics
    assert m is not None
    assert m["wob_mean_N"] == pytest.approx(w, rel=1e-9)
    assert m["tob_mean_Nm"] == pytest.approx(t, rel=1e-9)
    assert m["rop_mean_m_per_h"] == pytest.approx(30.0, rel=1e-6)
    assert m["bounce_fraction"] == 0.0
    area = math.pi * a * a
    assert m["mse_mean_Pa"] == pytest.approx(w / area + 4 * math.pi * t / (area * 30 / 3600), rel=1e-6)
    assert set(result.axial) == {"bit_axial_speed", "rop", "weight_on_bit", "hook_load", "bit_depth", "depth_of_cut",
                                "block_position"}
    assert result.axial["depth_of_cut"][-1] == pytest.approx(d, rel=1e-9)
    # hook load: the string's weight (no mud) at rest; drilling, the weight less the weight on
    # bit and the viscous damping force rho A c V L of the string moving at V, approached from
    # above at first order in the cell size (the end forces are the end cells'; at 100 cells
    # 176 N above, at 400 cells 53 N; without gravity within 2 N)
    mass = 8000.0 * math.pi / 4 * (0.127**2 - 0.108**2) * 200.0
    assert result.axial["hook_load"][0] == pytest.approx(mass * 9.81, rel=1e-12)
    assert mass * 9.81 - w - 1.001 * mass * 10.0 * 30 / 3600 < result.axial["hook_load"][-1] < mass * 9.81 - w
    assert abs(result.energy["balance_error"]) < 1e-12
    assert result.coupled_regime == "smooth drilling"
    assert result.summary()["coupled"] == {**m, "regime": "smooth drilling",
                                           "regime_criterion": COUPLED_REGIME_CRITERION}


def test_without_a_hoist_a_run_is_torsion_only() -> None:
    cfg = DrillConfig.from_dict({"sections": [PIPE], "numerics": {"cells": 50, "duration": 1.0}})
    result = drill(cfg)
    assert cfg.hoist is None and cfg.bit.law == "velocity_weakening"
    assert result.axial == {} and result.coupled_metrics is None and "coupled" not in result.summary()


def test_the_coupled_keys_are_checked_by_the_core() -> None:
    with pytest.raises(ValidationError, match="bit.law"):
        DrillConfig.from_dict({"sections": [PIPE], "bit": {"law": "rgd"}})
    with pytest.raises(ValidationError, match="hoist"):
        DrillConfig.from_dict({"sections": [PIPE], "hoist": {"speed": 0.01}})
    with pytest.raises(ValidationError, match="hoist.ramp_time"):
        _config(ramp_time=-1.0)
    with pytest.raises(ValidationError, match="hoist.mode"):
        _config(mode="manual")
    with pytest.raises(ValidationError, match="hoist.autodriller.kp"):  # an autodriller without gains
        _config(mode="autodriller")
    assert Hoist().mode == "velocity" and Hoist().speed == pytest.approx(30 / 3600)
    assert _config().to_toml().count("[hoist]") == 1
    assert DrillConfig.from_dict(_config().to_dict()) == _config()


def _pulled_out(coupling: str, rpm: float) -> DrillConfig:
    """500 m of the pipe in a horizontal hole (contact force ``g rho A``, no mud), pulled out at
    0.01 m/s while turning at ``rpm``."""
    return DrillConfig.from_dict({
        "sections": [dict(PIPE, length=500.0)], "well": {"inclination_deg": 90.0, "mud_density": 0.0},
        "friction": {"static": 0.3, "kinetic_ratio": 0.65, "contact": "weight", "stick_speed": 0.0,
                     "coupling": coupling},
        "damping_rate": 0.5,
        "top_drive": {"rpm": rpm, "ramp_time": 0.5, "controller": {"type": "speed"}},
        "bit": {"radius": 0.108, "law": "detournay"}, "hoist": {"speed": -0.01, "ramp_time": 0.5},
        "numerics": {"cells": 100, "duration": 20.0, "output_interval": 0.01}, "metrics": {"window": [15.0, 20.0]},
    })


def test_the_coupled_wall_friction_drags_against_the_sliding_velocity() -> None:
    # the hook load of a string pulled out at v: the drag mu_k N L v / sqrt(v^2 + (r omega)^2)
    # plus the damping rho A d v L; with torsion_only the damping alone (no axial wall friction)
    rho_a = 8000.0 * math.pi / 4 * (0.127**2 - 0.108**2)
    n, v, length, r = 9.81 * rho_a, 0.01, 500.0, 0.0635
    damping = rho_a * 0.5 * v * length
    for coupling, rpm in (("axial_torsional", 60.0), ("axial_torsional", 0.0), ("torsion_only", 60.0)):
        # one factor (static = kinetic): with a static factor above the kinetic one the slow
        # non-rotating pull sticks and slips
        one_factor = {"friction.static": 0.195, "friction.kinetic_ratio": 1.0}
        result = drill(_pulled_out(coupling, rpm).with_overrides(one_factor))
        assert result.success, result.message
        t = result.t
        hook = result.axial["hook_load"][(t >= 15.0)].mean()
        rw = r * rpm * math.pi / 30
        drag = 0.195 * n * length * v / math.hypot(v, rw) if coupling == "axial_torsional" else 0.0
        assert hook == pytest.approx(drag + damping, rel=1e-3), (coupling, rpm)
        friction = result.energy["axial_friction_loss"]
        assert (friction > 0.0) == (coupling == "axial_torsional")
        assert abs(result.energy["balance_error"]) < 1e-12


def test_the_coupled_friction_and_bha_keys_are_validated() -> None:
    assert _config().friction.coupling == "axial_torsional" and _config().bit.bha_mass == 0.0
    with pytest.raises(ValidationError, match="friction.coupling"):
        DrillConfig.from_dict({"sections": [PIPE], "friction": {"coupling": "both"}})
    with pytest.raises(ValidationError, match="bit.bha_mass"):
        DrillConfig.from_dict({"sections": [PIPE], "bit": {"bha_mass": -1.0}})
