"""Controller presets (``top_drive.controller.preset``) and the tuning helper
(``ds.recommend_controllers``, ``drillstring tune``): the gains against closed forms computed
here from the pipe's dimensions, the presets on the on-bottom example, and the plausibility
warnings and the flag of metrics that are not finite.

Before: ``kp``, ``ki``, ``tuning_frequency``, ``z_factor``, ``torque_highpass_time`` had no
unit or meaning anywhere, "stiff PI" was not said, and a run whose SSI was NaN (a bit that never
turned) reported ``success`` with exit status 0.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from _cli import run_cli
from scipy.optimize import brentq

import drillstring as ds

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ON_BOTTOM = EXAMPLES / "on-bottom-3000m.toml"


def _impedance(od: float, idia: float, g: float, rho: float) -> float:
    return math.pi / 32 * (od**4 - idia**4) * math.sqrt(g * rho)


def _first_mode_hz(sections: list[tuple[float, float, float, float, float]], bha: float) -> float:
    """The first root of the fixed-top frequency equation of sections (L, OD, ID, G, rho) with
    a tip inertia, by transfer matrices of (twist, torque) and a bracketing root finder."""

    def residual(w: float) -> float:
        theta, q = 0.0, 1.0
        for length, od, idia, g, rho in sections:
            z = _impedance(od, idia, g, rho)
            k = w * length / math.sqrt(g / rho)
            theta, q = theta * math.cos(k) + q * math.sin(k) / (z * w), -z * w * theta * math.sin(k) + q * math.cos(k)
        return q - bha * w * w * theta

    grid = np.linspace(1e-3, 20.0, 20001)
    values = [residual(w) for w in grid]
    i = next(i for i in range(len(grid) - 1) if values[i] * values[i + 1] < 0)
    return brentq(residual, grid[i], grid[i + 1], xtol=1e-14) / (2 * math.pi)


def test_the_recommended_gains_match_the_closed_forms() -> None:
    rec = ds.recommend_controllers(ON_BOTTOM)
    z = _impedance(0.127, 0.1086, 79.3e9, 7850.0)
    f1 = _first_mode_hz([(3000.0, 0.127, 0.1086, 79.3e9, 7850.0), (200.0, 0.1651, 0.0714, 79.3e9, 7850.0)], 100.0)
    assert rec.string.impedance == pytest.approx(z, rel=1e-13)
    assert rec.string.first_mode_hz == pytest.approx(f1, rel=1e-9)
    assert f1 == pytest.approx(0.16, abs=0.001)
    stiff, soft, zt = rec["stiff"], rec["soft_torque"], rec["z_torque"]
    assert stiff.controller["type"] == "pi" and stiff.controller["preset"] == "stiff"
    assert stiff.controller["kp"] == pytest.approx(50 * z, rel=1e-13)
    assert stiff.controller["ki"] == pytest.approx(5 * 2900.0, rel=1e-13)
    assert stiff.speed_bandwidth_hz == pytest.approx(50 * z / (2 * math.pi * 2900.0), rel=1e-13)
    assert stiff.reflection == pytest.approx(49 / 51, rel=1e-13)
    assert soft.controller["type"] == "soft_torque" and soft.controller["z_factor"] == 4.0
    assert soft.controller["kp"] == pytest.approx(4 * z, rel=1e-13)
    assert soft.controller["ki"] == pytest.approx((2 * math.pi * f1) ** 2 * 2900.0, rel=1e-8)
    assert soft.reflection == pytest.approx(3 / 5, rel=1e-13)
    assert zt.controller["type"] == "z_torque"
    assert zt.controller["torque_highpass_time"] == pytest.approx(1 / (math.pi * f1), rel=1e-8)
    k = 1 / (3000 / (79.3e9 * math.pi / 32 * (0.127**4 - 0.1086**4))
             + 200 / (79.3e9 * math.pi / 32 * (0.1651**4 - 0.0714**4)))
    assert rec.string.stiffness == pytest.approx(k, rel=1e-12)
    assert zt.windup_speed_ratio == pytest.approx(1 / (1 + k / (math.pi * f1) / (4 * z)), rel=1e-8)
    assert math.isnan(zt.speed_bandwidth_hz) and math.isnan(stiff.windup_speed_ratio)


def test_a_uniform_string_gets_the_quarter_wave_tuning() -> None:
    # f1 = c / (4 L) of a free-ended uniform string: ki = (2 pi f1)^2 I, T = 4 L / (pi c)
    cfg = {"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086,
                         "shear_modulus": 80e9, "density": 8000.0}],
           "top_drive": {"inertia": 1000.0}}
    c = math.sqrt(80e9 / 8000.0)
    rec = ds.recommend_controllers(cfg)
    assert rec.string.first_mode_hz == pytest.approx(c / 8000.0, rel=1e-9)
    assert rec["soft_torque"].controller["ki"] == pytest.approx((2 * math.pi * c / 8000.0) ** 2 * 1000.0, rel=1e-8)
    assert rec["z_torque"].controller["torque_highpass_time"] == pytest.approx(8000.0 / (math.pi * c), rel=1e-8)


def test_a_preset_fills_in_type_and_gains_and_explicit_keys_win() -> None:
    base = {"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}]}
    z = ds.recommend_controllers(base).string.impedance
    cfg = ds.DrillConfig.from_dict({**base, "top_drive": {"controller": {"preset": "stiff", "ki": 7.0}}})
    c = cfg.top_drive.controller
    assert (c.preset, c.type, c.ki) == ("stiff", "pi", 7.0)
    assert c.kp == pytest.approx(50 * z, rel=1e-13)
    # the example sets type = "pi", kp, ki and z_factor = 5: a preset set over it replaces them
    ex = ds.load_drill_config(ON_BOTTOM)
    soft = ex.with_overrides(["top_drive.controller.preset=soft_torque"]).top_drive.controller
    assert (soft.type, soft.z_factor) == ("soft_torque", 4.0)
    later = ex.with_overrides(["top_drive.controller.preset=soft_torque", "top_drive.controller.z_factor=2"])
    assert later.top_drive.controller.z_factor == 2.0
    with pytest.raises(ds.ValidationError, match="top_drive.controller.preset"):
        ds.DrillConfig.from_dict({**base, "top_drive": {"controller": {"preset": "gentle"}}})


def test_soft_and_z_torque_presets_remove_the_stick_slip_the_stiff_one_leaves() -> None:
    cfg = ds.load_drill_config(ON_BOTTOM)
    assert cfg.top_drive.rpm == 40.0
    m = {p: ds.drill(cfg.with_overrides([f"top_drive.controller.preset={p}"]), progress=False).metrics
         for p in ("stiff", "soft_torque", "z_torque")}
    # measured (300 cells): SSI stiff 1.13 (stuck 25 %), soft_torque 0.21, z_torque 0.032
    assert m["stiff"].stick_slip and m["stiff"].ssi > 1.0
    for p in ("soft_torque", "z_torque"):
        assert not m[p].stick_slip and m[p].ssi < 0.3 * m["stiff"].ssi, (p, m[p].ssi, m["stiff"].ssi)


def test_the_z_torque_preset_winds_the_string_up_faster_than_the_fixed_high_pass() -> None:
    # 60 rpm: the fixed 20 / (2 pi) s high-pass holds the top near 33 rpm while the string winds up
    cfg = ds.load_drill_config(ON_BOTTOM).with_overrides(["top_drive.rpm=60", "numerics.duration=12"])
    fixed = ds.drill(cfg.with_overrides(["top_drive.controller.type=z_torque", "top_drive.controller.z_factor=4"]),
                     progress=False)
    tuned = ds.drill(cfg.with_overrides(["top_drive.controller.preset=z_torque"]), progress=False)
    at = (fixed.t >= 4.0) & (fixed.t <= 8.0)
    ratio = ds.recommend_controllers(cfg)["z_torque"].windup_speed_ratio
    assert fixed.surface_rpm[at].mean() < 36.0
    assert tuned.surface_rpm[at].mean() > 38.0
    assert tuned.surface_rpm[at].mean() == pytest.approx(60 * ratio, rel=0.1)


def test_tune_prints_one_line_per_preset_with_units(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(capsys, "tune", str(ON_BOTTOM))
    assert code == 0
    lines = out.strip().splitlines()
    assert len(lines) == 4 and lines[0].startswith("string: Z = 296.5 N m s")
    assert lines[1].startswith("stiff: top_drive.controller.type = pi; kp = 50 Z = 14825 N m s/rad, "
                               "ki = 5 1/s^2 x I_TD = 14500 N m/rad")
    assert lines[2].startswith("soft_torque:") and "kp = z_factor Z = 4 Z = 1186 N m s/rad" in lines[2]
    assert "at f1 = 0.1600 Hz" in lines[2]
    assert lines[3].startswith("z_torque:") and "torque_highpass_time = 1 / (pi f1) = 1.990 s" in lines[3]


def test_a_nan_metric_is_not_a_success(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = ds.load_drill_config(ON_BOTTOM).with_overrides(["top_drive.rpm=0", "numerics.duration=4"])
    r = ds.drill(cfg, progress=False)
    assert math.isnan(r.metrics.ssi) and r.status == "success"
    assert not r.metrics_finite
    assert any(w.startswith("not a result: ssi = nan") for w in r.warnings), r.warnings
    # at 40 rpm the bit breaks free after about 10 s: a full run is a result
    assert ds.drill(cfg.with_overrides(["top_drive.rpm=40", "numerics.duration=60"]), progress=False).metrics_finite
    code, out, err = run_cli(capsys, "drill", str(ON_BOTTOM), "--no-plots", "--out", str(tmp_path / "o"),
                             "--set", "top_drive.rpm=0", "--set", "numerics.duration=4")
    assert code == 0  # the files are written; the first line and metrics.json say it is not a result
    assert "(success, but metrics not finite: not a result)" in out + err
    assert json.loads((tmp_path / "o" / "metrics.json").read_text())["metrics_finite"] is False


def test_plausibility_warnings_name_the_value_and_the_likely_mistake() -> None:
    cfg = ds.load_drill_config(ON_BOTTOM).with_overrides(["numerics.duration=4"])
    r = ds.drill(cfg.with_overrides(["top_drive.torque_limit=20"]), progress=False)  # meant 20 kN m
    assert any("top_drive.torque_limit = 20 N m" in w and "a limit in kN m?" in w for w in r.warnings), r.warnings
    # soft torque at its default gain on the example: the oscillation decays through the window
    r = ds.drill(ds.load_drill_config(ON_BOTTOM).with_overrides(["top_drive.controller.type=soft_torque",
                                                                 "top_drive.controller.z_factor=4"]), progress=False)
    assert any(w.startswith("a transient is still decaying in the metrics window [30, 60] s") for w in r.warnings)
    # the stiff PI's steady stick-slip cycle is none
    r = ds.drill(ds.load_drill_config(ON_BOTTOM), progress=False)
    assert not any("transient" in w for w in r.warnings), r.warnings
