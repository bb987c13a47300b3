"""The ``consistent`` (finite-strain) torque-twist law of the drilling solver from Python: the
option through the configuration, TOML and ``--set``; the linear default unchanged; the elastic
energy of a run against its definition evaluated here from the returned torque field."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from _cli import run_cli

import drillstring as ds
from drillstring.drilling import DrillConfig, load_drill_config

ROOT = Path(__file__).resolve().parents[1]
ON_BOTTOM = ROOT / "examples" / "on-bottom-3000m.toml"
SHORT = ["numerics.duration=8", "numerics.cells=120", "numerics.field_interval=0.5"]


def test_the_option_defaults_to_linear_and_round_trips(tmp_path: Path) -> None:
    cfg = load_drill_config(ON_BOTTOM)
    assert cfg.nonlinearity == "linear"
    assert cfg.sections[0].poisson_ratio == pytest.approx(0.3)
    assert cfg.numerics.max_shear_strain == pytest.approx(0.005)
    consistent = cfg.with_overrides(["nonlinearity=consistent", "sections[1].poisson_ratio=0.29"])
    assert consistent.nonlinearity == "consistent" and consistent.sections[1].poisson_ratio == 0.29
    path = consistent.save(tmp_path / "c.toml")
    assert 'nonlinearity = "consistent"' in path.read_text()
    assert load_drill_config(path) == consistent


def test_linear_is_the_default_scheme_bit_for_bit() -> None:
    base = load_drill_config(ON_BOTTOM).with_overrides(SHORT)
    implicit = ds.drill(base)
    explicit = ds.drill(base.with_overrides(["nonlinearity=linear", "numerics.max_shear_strain=0.5",
                                             "sections[0].poisson_ratio=0.45"]))
    for name in ("bit_rpm", "motor_torque", "torque_field"):
        np.testing.assert_array_equal(getattr(implicit, name), getattr(explicit, name))
    assert implicit.stats["courant_peak"] == implicit.stats["courant_max"]


def test_consistent_run_is_close_to_linear_with_its_energy_closing() -> None:
    base = load_drill_config(ON_BOTTOM).with_overrides(SHORT)
    linear = ds.drill(base)
    res = ds.drill(base.with_overrides(["nonlinearity=consistent"]))
    assert res.success and res.message == ""
    assert res.stats["courant_peak"] <= res.stats["courant_max"] <= 1.0
    assert abs(res.energy["balance_error"]) < 1e-11
    assert 0.0 < res.energy["upwind_loss"] < 0.05 * res.energy["motor_work"]
    # shear strains ~1e-3: the runs differ, but by far less than the torques themselves
    difference = np.max(np.abs(res.motor_torque - linear.motor_torque)) / np.max(np.abs(linear.motor_torque))
    assert 0.0 < difference < 0.02, difference


def test_elastic_energy_is_the_integral_of_the_quartic_law() -> None:
    """One uniform section, driven until the last snapshot (t = duration): the core's elastic
    energy against sum h (k2 eps^2 / 2 + k5 eps^4 / 4), eps solved here from each cell's torque
    with k2 = G J, k5 = M J4 / 2 of the annulus, M = 2 G (1 - nu) / (1 - 2 nu)."""
    od, id_, g, nu, length = 0.1, 0.0, 79.3e9, 0.499, 800.0
    cfg = DrillConfig.from_dict({
        "sections": [{"length": length, "outer_diameter": od, "inner_diameter": id_, "poisson_ratio": nu}],
        "nonlinearity": "consistent",
        "well": {"md": None, "inclination_deg": 0.0},
        # an ideal speed step (no motor lag, no torque limit) for strains of a few 1e-2
        "top_drive": {"rpm": 3000.0, "ramp_time": 0.0, "controller": {"type": "speed"}, "motor_bandwidth": 1e12,
                      "torque_limit": 1e12},
        "bit": {"bha_inertia": 5.0},
        "numerics": {"cells": 200, "duration": 0.01, "field_interval": 0.0, "max_shear_strain": 0.05},
    })
    # a duration of a whole number of steps, so that the last snapshot is the final state
    duration = 300 * ds.drill(cfg).stats["dt"]
    res = ds.drill(cfg.with_overrides([f"numerics.duration={duration!r}", f"numerics.field_interval={duration!r}"]))
    assert res.success, res.message
    assert res.stats["steps"] == 300 and res.field_t[-1] == duration
    r_out, r_in = od / 2, id_ / 2
    k2 = g * math.pi / 2 * (r_out**4 - r_in**4)
    m = 2 * g * (1 - nu) / (1 - 2 * nu)
    k5 = m * math.pi / 3 * (r_out**6 - r_in**6) / 2
    tau = res.torque_field[-1]
    eps = np.array([np.real(next(r for r in np.roots([k5, 0.0, k2, -t]) if abs(r.imag) < 1e-9)) for t in tau])
    h = length / res.z.size
    elastic = float(np.sum(h * (k2 * eps**2 / 2 + k5 * eps**4 / 4)))
    linear_elastic = float(np.sum(h * tau**2 / (2 * k2)))
    assert res.energy["elastic"] == pytest.approx(elastic, rel=1e-9)
    # the quartic term matters here (strains of a few 1e-2): the linear formula is off
    assert abs(linear_elastic / elastic - 1) > 1e-3
    kinetic = float(np.sum(h * 7850.0 * k2 / g * (res.omega_field[-1] * 2 * math.pi / 60) ** 2 / 2))
    assert res.energy["kinetic"] == pytest.approx(kinetic, rel=1e-9)


def test_cli_runs_the_consistent_law(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    code, _, err = run_cli(capsys, "drill", str(ON_BOTTOM), "--out", str(out), "--no-plots", "--no-progress",
                           *[arg for s in SHORT for arg in ("--set", s)], "--set", "nonlinearity=consistent")
    assert code == 0, err
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["status"] == "success" and metrics["stats"]["courant_peak"] <= 1.0
    assert load_drill_config(out / "config.toml").nonlinearity == "consistent"
    code, _, err = run_cli(capsys, "drill", str(ON_BOTTOM), "--out", str(tmp_path / "bad"), "--no-progress",
                           "--set", "nonlinearity=cubic")
    assert code == 2 and "nonlinearity" in err and "consistent" in err


def test_maps_report_the_courant_peak() -> None:
    """A map row carries its run's largest Courant number: at most 1 for the linear law, above 1
    when the consistent law is driven past ``numerics.max_shear_strain``."""
    # one uniform section: Courant number 1 on the grid, so any strain above the 1e-6 the grid
    # was built for pushes the consistent law past 1
    base = DrillConfig.from_dict({
        "sections": [{"length": 1000.0, "outer_diameter": 0.14, "inner_diameter": 0.1}],
        "top_drive": {"rpm": 60.0},
        "numerics": {"cells": 200, "duration": 1.0, "field_interval": 0.5, "max_shear_strain": 1e-6},
    })
    frame = ds.drill_map(base, {"nonlinearity": ["linear", "consistent"]}, threads=1)
    assert list(frame["status"]) == ["success", "success"]
    for _, row in frame.iterrows():
        single = ds.drill(base.with_overrides([f"nonlinearity={row['nonlinearity']}"]))
        assert row["courant_peak"] == single.stats["courant_peak"]
    linear, consistent = frame["courant_peak"]
    assert linear == 1.0 < consistent
    assert "numerics.max_shear_strain" in frame["message"][1]


def test_quartic_moment_sets_the_cubic_torque() -> None:
    """``sections[i].quartic_moment`` (J4) unset is the annulus's pi/192 (OD^6 - ID^6): giving that
    value changes nothing, bit for bit; a larger one stiffens the string; a bad one names the field."""
    base = load_drill_config(ON_BOTTOM).with_overrides([*SHORT, "nonlinearity=consistent"])
    section = base.sections[0]
    annulus = math.pi / 192 * (section.outer_diameter ** 6 - section.inner_diameter ** 6)
    implicit = ds.drill(base)
    explicit = ds.drill(base.with_overrides([f"sections[0].quartic_moment={annulus!r}"]))
    np.testing.assert_array_equal(implicit.motor_torque, explicit.motor_torque)
    stiffer = ds.drill(base.with_overrides([f"sections[0].quartic_moment={1e4 * annulus!r}"]))
    assert not np.array_equal(stiffer.motor_torque, implicit.motor_torque)
    with pytest.raises(ds.errors.ValidationError, match=r"sections\[0\]\.quartic_moment"):
        ds.drill(base.with_overrides(["sections[0].quartic_moment=-1"]))
