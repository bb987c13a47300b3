"""Wells and torque and drag: the core's minimum curvature and soft-string torque and drag
against welleng 0.30.0 (numbers computed by tests/reference/welleng/welleng_reference.py, with
welleng's two defects corrected there, and an independent numpy implementation of the same
conventions in that script), closed forms, the dynamic model's use of the contact force, and
the CLI's contracts (``drillstring torque-drag``, ``torque_drag.json``, bad surveys)."""

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
from drillstring.errors import ValidationError

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "s-well-3d.toml"
REFERENCE = Path(__file__).resolve().parent / "reference" / "welleng"


@pytest.fixture(scope="module")
def td() -> ds.TorqueDragResult:
    # The references' friction factors (0.2 cased, 0.3 open) are the sliding factors torque and
    # drag use, friction.static x friction.kinetic_ratio: one factor here.
    cfg = ds.drilling.load_drill_config(EXAMPLE).with_overrides(["friction.kinetic_ratio=1"])
    return ds.torque_drag(cfg)


def test_minimum_curvature_matches_welleng(td: ds.TorqueDragResult) -> None:
    ref = json.loads((REFERENCE / "welleng_s_well_3d_survey.json").read_text())
    t = td.trajectory
    np.testing.assert_array_equal(t["md"], ref["md"])
    for ours, theirs in (("north", "north"), ("east", "east"), ("tvd", "tvd")):
        np.testing.assert_allclose(t[ours], ref[theirs], rtol=0, atol=1e-9)
    np.testing.assert_allclose(t["dls_deg_per_30m"], ref["dls_deg_per_30m"], rtol=0, atol=1e-9)
    # the bit: 261.9 m north, 1314.8 m east, 3625.2 m TVD
    assert (t["north"][-1], t["east"][-1], t["tvd"][-1]) == pytest.approx((261.908, 1314.847, 3625.159), abs=1e-3)


SUMMARY = ("hook_load_pickup_N", "hook_load_slackoff_N", "hook_load_rotating_N", "hook_load_rotating_on_bottom_N",
           "surface_torque_off_bottom_Nm", "surface_torque_on_bottom_Nm")


def test_torque_and_drag_match_the_independent_implementations(td: ds.TorqueDragResult) -> None:
    ref = json.loads((REFERENCE / "welleng_s_well_3d_torque_drag.json").read_text())
    for key in SUMMARY:
        # the same conventions written independently in numpy: to rounding of the node grid
        assert td.summary[key] == pytest.approx(ref["direct"][key], rel=2e-6), key
        # welleng with its build/drop sign and radius-walk defects corrected: within its kick-off
        # element's false azimuth change (28 N of 1.7 MN, 1.7 N m of 26 kN m)
        assert td.summary[key] == pytest.approx(ref["welleng_corrected"][key], rel=1e-4), key
    # welleng as published differs by more than that: the defects are real
    assert abs(td.hook_load_pickup_N / ref["welleng_as_is"]["hook_load_pickup_N"] - 1) > 5e-3
    # the profiles every 100 m
    p = ref["direct_profiles_every_100m"]
    md = np.asarray(td.profiles["pickup"]["md"])
    for op, key in (("pickup", "tension_pickup_N"), ("rotating", "torque_rotating_off_bottom_Nm"),
                    ("rotating_on_bottom", "tension_rotating_on_bottom_N")):
        column = "tension_N" if "tension" in key else "torque_Nm"
        ours = np.interp(p["md"], md, np.asarray(td.profiles[op][column]))
        np.testing.assert_allclose(ours, p[key], rtol=2e-6, atol=1e-3 * max(1.0, abs(float(np.max(p[key])))))


def test_rotating_hook_load_is_the_buoyed_weight_along_the_vertical(td: ds.TorqueDragResult) -> None:
    """Rotating, no axial friction: the surface tension is the buoyed weight projected on the
    vertical, sum of w_i times the TVD each section spans (independent of friction)."""
    cfg = td.config
    g = cfg.well.gravity
    t = td.trajectory
    tvd_at = lambda d: float(np.interp(d, t["md"], t["tvd"]))  # noqa: E731 (stations dense; arcs ~ chords)
    top = 0.0
    total = 0.0
    for s in cfg.sections:
        area = math.pi / 4 * (s.outer_diameter**2 - s.inner_diameter**2)
        total += (s.density - cfg.well.mud_density) * g * area * (tvd_at(top + s.length) - tvd_at(top))
        top += s.length
    assert td.hook_load_rotating_N - cfg.torque_drag.block_weight == pytest.approx(total, rel=1e-4)
    # on bottom, the weight on bit comes off the hook
    assert td.hook_load_rotating_N - td.hook_load_rotating_on_bottom_N == pytest.approx(cfg.bit.weight_on_bit, rel=1e-9)


def test_straight_inclined_hole_closed_form() -> None:
    """T = w L (cos i + mu sin i) picking up, (cos i - mu sin i) slacking off; M = mu r w L sin i,
    with mu the sliding factor friction.static x friction.kinetic_ratio (0.25 x 0.8 = 0.2)."""
    cfg = ds.DrillConfig(sections=[{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                         well={"inclination_deg": 40.0}, friction={"static": 0.25, "kinetic_ratio": 0.8})
    r = ds.torque_drag(cfg)
    area = math.pi / 4 * (0.127**2 - 0.1086**2)
    w = 7850.0 * 9.81 * area
    i = math.radians(40.0)
    mu = 0.25 * 0.8
    assert r.hook_load_pickup_N == pytest.approx(w * 2000 * (math.cos(i) + mu * math.sin(i)), rel=1e-12)
    assert r.hook_load_slackoff_N == pytest.approx(w * 2000 * (math.cos(i) - mu * math.sin(i)), rel=1e-12)
    assert r.surface_torque_off_bottom_Nm == pytest.approx(mu * 0.127 / 2 * w * 2000 * math.sin(i), rel=1e-12)
    # the static factor is the break-off torque's
    static = ds.drilling.friction_profile(cfg.with_overrides(["friction.contact=weight"]))
    assert static.breakoff_torque == pytest.approx(0.25 * 0.127 / 2 * w * 2000 * math.sin(i), rel=1e-9)


def test_a_plan_in_three_lines_and_its_doglegs() -> None:
    cfg = ds.DrillConfig(sections=[{"length": 3000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                         well={"plan": [{"hold": 500}, {"build": 3, "inclination": 60}, {"hold": 2000}]})
    t = ds.torque_drag(cfg).trajectory
    np.testing.assert_array_equal(t["md"], [0.0, 500.0, 1100.0, 3100.0])
    assert t["dls_deg_per_30m"][2] == pytest.approx(3.0, rel=1e-12)
    # the build is a circular arc of radius 30 / (3 deg): TVD gained R sin 60
    radius = 30.0 / math.radians(3.0)
    assert t["tvd"][2] - t["tvd"][1] == pytest.approx(radius * math.sin(math.radians(60)), rel=1e-12)


def test_soft_string_contact_sets_the_wall_limit_and_the_break_off_torque() -> None:
    cfg = ds.load_drill_config(EXAMPLE)
    profile = ds.drilling.friction_profile(cfg)
    r = ds.torque_drag(cfg)
    # the break-off torque is the rotating torque without the bit's (on bottom: with the WOB) at
    # the static factors; torque and drag's at the sliding ones (x friction.kinetic_ratio)
    on_bottom = r.surface_torque_on_bottom_Nm - cfg.torque_drag.bit_torque
    assert profile.breakoff_torque * cfg.friction.kinetic_ratio == pytest.approx(on_bottom, rel=1e-9)
    weight = ds.drilling.friction_profile(cfg.with_overrides(["friction.contact=weight"]))
    assert weight.breakoff_torque != pytest.approx(profile.breakoff_torque, rel=0.05)


def test_the_weight_contact_keeps_published_aarsnes_shor_numbers() -> None:
    cfg = ds.load_drill_config(ROOT / "examples" / "aarsnes-shor-well-b.toml")
    assert cfg.friction.contact == "weight"


def test_cli_writes_the_contract_files(tmp_path: Path) -> None:
    out = tmp_path / "td"
    proc = subprocess.run([sys.executable, "-m", "drillstring", "torque-drag", str(EXAMPLE), "--out", str(out),
                           "--no-plots"], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((out / "torque_drag.json").read_text())
    for key in (*SUMMARY, "max_normal_force_N_per_m", "max_normal_force_md"):
        assert math.isfinite(doc[key]), key
    assert doc["hook_load_pickup_N"] > doc["hook_load_rotating_N"] > doc["hook_load_slackoff_N"]
    import pandas as pd

    profiles = pd.read_csv(out / "profiles.csv")
    assert profiles["md_m"].iloc[-1] == 4000.0
    assert profiles["pickup_tension_N"].iloc[0] + 300e3 == pytest.approx(doc["hook_load_pickup_N"], rel=1e-9)
    assert sorted(os.listdir(out)) == sorted(["torque_drag.json", "profiles.csv", "broomstick.csv", "survey.csv",
                                              "config.toml", "report.md"])


@pytest.mark.parametrize("text, where", [
    ("md_m,inc_deg,azi_deg\n0,0,0\n30,x,0\n", "row 3, column inc_deg"),
    ("md_m,inc_deg,azi_deg\n0,0,0\n30,1,0\n20,2,0\n", "row 4, column md_m"),
    ("md_m,inc_deg,azi_deg\n0,0,0\n30,181,0\n", "row 3, column inc_deg"),
    ("md_m,inc_deg,azi_deg\n0,0,0\n30,1,400\n", "row 3, column azi_deg"),
    ("md,inc\n0,0\n", "a column named azi"),
])
def test_bad_surveys_get_one_line_errors_naming_file_row_and_column(tmp_path: Path, text: str, where: str) -> None:
    survey = tmp_path / "bad.csv"
    survey.write_text(text)
    config = tmp_path / "well.toml"
    config.write_text('[[sections]]\nlength = 100.0\nouter_diameter = 0.127\ninner_diameter = 0.1\n\n'
                      '[well]\nsurvey = "bad.csv"\n')
    proc = subprocess.run([sys.executable, "-m", "drillstring", "torque-drag", str(config), "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "bad.csv" in lines[0] and where in lines[0], proc.stderr


def test_a_survey_shorter_than_the_string_is_refused_unless_extended(tmp_path: Path) -> None:
    survey = tmp_path / "short.csv"
    survey.write_text("md_m,inc_deg,azi_deg\n0,0,0\n500,10,0\n")
    base = {"sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.1}],
            "well": {"survey": str(survey)}}
    with pytest.raises(ValidationError, match="well.survey"):
        ds.DrillConfig.from_dict(base)
    extended = ds.DrillConfig.from_dict({**base, "well": {"survey": str(survey), "extend": True}})
    assert ds.torque_drag(extended).trajectory["md"][-1] == 500.0


def test_drill_says_which_contact_it_uses(tmp_path: Path) -> None:
    proc = subprocess.run([sys.executable, "-m", "drillstring", "drill", str(EXAMPLE), "--out", str(tmp_path / "d"),
                           "--no-plots", "--set", "numerics.duration=5"], capture_output=True, text=True,
                          cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "wall contact: soft_string" in proc.stdout
    assert "`soft_string`" in (tmp_path / "d" / "report.md").read_text()
    fields = np.load(tmp_path / "d" / "fields.npz")
    assert fields["dls_deg_per_30m"].max() == pytest.approx(2.56, abs=0.01)  # the survey's largest dogleg
    assert set(np.unique(fields["friction_factor"])) == {0.2, 0.3}  # cased above 1800 m, open below
