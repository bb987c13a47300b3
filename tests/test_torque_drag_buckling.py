"""Torque and drag as a drilling engineer checks it: buckling and lock-up, sliding, the pipe's
limits, the side force per joint and measured points on the broomstick.

Independent references: the closed forms of Dawson & Paslay (1984) and Chen, Lin & Cheatham
(1990) for the critical loads, Mitchell's helical contact `r_c F^2 / (4 E I)` in a scipy ODE of
the sliding string's compression, a scipy root of the curved-hole convention, von Mises by hand
at the surface, and measured points made by the model at known friction factors."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.drilling.config import DrillConfig

INCH = 0.0254
OD, ID, HOLE = 5.0 * INCH, 4.276 * INCH, 8.5 * INCH
MUD, G, NU, SHEAR, RHO = 1200.0, 9.81, 0.3, 79.3e9, 7850.0
E = 2.0 * SHEAR * (1.0 + NU)
AREA = math.pi / 4.0 * (OD**2 - ID**2)
EI = E * math.pi / 64.0 * (OD**4 - ID**4)
W = (RHO - MUD) * G * AREA
RC = (HOLE - OD) / 2.0
S135 = 135e3 * 6894.757293168361


def _config(**well: Any) -> dict[str, Any]:
    return {
        "sections": [{"length": 3000.0, "outer_diameter": OD, "inner_diameter": ID, "grade": "S-135",
                      "makeup_torque": 40e3}],
        "well": {"inclination_deg": 20.0, "mud_density": MUD, "hole_diameter": HOLE, **well},
        "friction": {"static": 0.3, "kinetic_ratio": 1.0},
        "bit": {"weight_on_bit": 150e3},
        "torque_drag": {"bit_torque": 5e3},
    }


def _run(tmp_path: Path, data: dict[str, Any], *extra: str) -> tuple[dict[str, Any], Any, str]:
    import pandas as pd

    cfg = DrillConfig.from_dict(data)
    tmp_path.mkdir(parents=True, exist_ok=True)
    path = tmp_path / "td.toml"
    path.write_text(cfg.to_toml())
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "drillstring", "torque-drag", str(path), "--out", str(out), *extra],
                          capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((out / "torque_drag.json").read_text())
    return doc, pd.read_csv(out / "profiles.csv"), proc.stdout


@pytest.fixture(scope="module")
def straight(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, Any], Any, str]:
    return _run(tmp_path_factory.mktemp("straight"), _config(), "--no-plots")


def test_critical_loads_are_the_closed_forms(straight: tuple[dict[str, Any], Any, str]) -> None:
    _, p, _ = straight
    sin_i = math.sin(math.radians(20.0))
    fs = 2.0 * math.sqrt(EI * W * sin_i / RC)
    fh = 2.0 * math.sqrt(2.0) * math.sqrt(EI * W * sin_i / RC)
    np.testing.assert_allclose(p["sinusoidal_buckling_load_N"], fs, rtol=5e-3)
    np.testing.assert_allclose(p["helical_buckling_load_N"], fh, rtol=5e-3)


def test_sliding_marks_the_helically_buckled_length(straight: tuple[dict[str, Any], Any, str]) -> None:
    """Mitchell's contact in an independent ODE of the compression going up from the bit,
    `dF/du = -w cos i + mu (w sin i + r_c F^2 / (4 E I))` while helical: the helical length the
    core marks is the ODE's to the element length."""
    from scipy.integrate import solve_ivp

    doc, p, out = straight
    md = p["md_m"].to_numpy()
    helical = md[(p["sliding_buckling"] == "helical").to_numpy()]
    assert len(helical) and helical.max() == md[-1]
    compression = -p["sliding_tension_N"].to_numpy()
    # the marks are the compression against the critical loads, node by node
    expect = np.where(compression >= p["helical_buckling_load_N"], "helical",
                      np.where(compression >= p["sinusoidal_buckling_load_N"], "sinusoidal", "none"))
    assert (p["sliding_buckling"].to_numpy() == expect).all()
    inc, mu = math.radians(20.0), 0.3
    fh = 2.0 * math.sqrt(2.0) * math.sqrt(EI * W * math.sin(inc) / RC)

    def rhs(_u: float, f: np.ndarray) -> np.ndarray:
        return -W * math.cos(inc) + mu * (W * math.sin(inc) + RC * f**2 / (4.0 * EI))

    event = lambda _u, f: f[0] - fh  # noqa: E731
    event.terminal = True  # type: ignore[attr-defined]
    sol = solve_ivp(rhs, (0.0, 3000.0), [150e3], events=event, rtol=1e-10, atol=1e-6)
    length = float(sol.t_events[0][0])
    assert md[-1] - helical.min() == pytest.approx(length, abs=2.0)
    assert doc["first_buckling"]["sliding"]["helical_md"] == pytest.approx(helical.min())
    assert doc["hook_load_sliding_N"] < doc["hook_load_slackoff_N"]
    assert not doc["lockup"]["sliding"] and "helical from" in out


def test_utilisation_is_von_mises_by_hand(straight: tuple[dict[str, Any], Any, str]) -> None:
    doc, p, out = straight
    j = math.pi / 32.0 * (OD**4 - ID**4)
    # pick-up: tension only at the surface (no pressure there)
    t = p["pickup_tension_N"].iloc[0]
    assert p["pickup_utilisation"].iloc[0] == pytest.approx(t / AREA / S135, rel=1e-8)
    # rotating on bottom: tension and the full torque
    t, m = p["rotating_on_bottom_tension_N"].iloc[0], p["rotating_on_bottom_torque_Nm"].iloc[0]
    vm = math.sqrt((t / AREA) ** 2 + 3.0 * (m * OD / 2.0 / j) ** 2)
    assert p["rotating_on_bottom_utilisation"].iloc[0] == pytest.approx(vm / S135, rel=1e-8)
    # below the surface the true force is the effective one less the pressure on the body
    k = len(p) // 2
    tvd = p["md_m"].iloc[k] * math.cos(math.radians(20.0))
    true = p["pickup_tension_N"].iloc[k] - MUD * G * tvd * AREA
    assert p["pickup_utilisation"].iloc[k] == pytest.approx(abs(true) / AREA / S135, rel=1e-9)
    columns = [c for c in p.columns if c.endswith("_utilisation")]
    assert doc["max_utilisation"] == pytest.approx(float(np.nanmax(p[columns].to_numpy())), rel=1e-8)
    assert doc["overpull_margin_N"] == pytest.approx(S135 * AREA - p["pickup_tension_N"].iloc[0], rel=1e-8)
    assert doc["closest_limit"] in ("utilisation", "makeup_torque", "overpull") and "closest limit" in out
    # the side force of a joint (9.144 m by default) is the normal force times it
    np.testing.assert_allclose(p["pickup_side_force_per_joint_N"], p["pickup_normal_force_N_per_m"] * 9.144,
                               rtol=1e-8)


def test_a_long_horizontal_slack_off_locks_up(tmp_path: Path) -> None:
    """5 in pipe pushed along 3000 m of horizontal hole at a friction factor of 0.5: the
    compression grows by `mu w` per metre past the helical load and the helical contact makes it
    diverge; the vertical 500 m cannot push it. A short horizontal does not lock up, and the
    largest weight on bit the core reports is the one that leaves the surface tension at 0."""
    plan = [{"hold": 500.0}, {"build": 6.0, "inclination": 90.0}, {"hold": 3000.0}]
    data = _config(plan=plan, inclination_deg=0.0)
    data["sections"][0]["length"] = 3900.0
    data["friction"]["static"] = 0.5
    doc, p, out = _run(tmp_path, data, "--no-plots")
    assert doc["lockup"]["slackoff"] and doc["lockup"]["sliding"]
    assert doc["hook_load_slackoff_N"] is None and doc["max_set_down_N"] == 0.0
    assert "lock-up: slackoff, sliding" in out
    # the limits' maxima leave the locked-up operations out: the largest utilisation is the
    # others' (their compression below the lock-up is no load the string reaches)
    feasible = [f"{op}_utilisation" for op in ("pickup", "rotating", "rotating_on_bottom")
                if f"{op}_utilisation" in p.columns]
    assert feasible and doc["max_utilisation_operation"] not in ("slackoff", "sliding")
    assert doc["max_utilisation"] == pytest.approx(float(np.nanmax(p[feasible].to_numpy())), rel=1e-8)
    assert doc["max_utilisation"] < 1.0
    short = _config(plan=[{"hold": 1500.0}, {"build": 6.0, "inclination": 90.0}, {"hold": 400.0}],
                    inclination_deg=0.0)
    short["sections"][0]["length"] = 2300.0
    short["bit"]["weight_on_bit"] = 20e3
    doc, p, _ = _run(tmp_path / "short", short, "--no-plots")
    assert not doc["lockup"]["slackoff"] and not doc["lockup"]["sliding"]
    wob = doc["max_weight_on_bit_N"]
    assert wob > 20e3 and doc["max_set_down_N"] == pytest.approx(doc["hook_load_slackoff_N"], rel=1e-8)
    short["bit"]["weight_on_bit"] = wob
    at_limit = ds.torque_drag(DrillConfig.from_dict(short))
    assert abs(at_limit.hook_load_sliding_N) < 1e-6 * wob


def test_sliding_in_a_horizontal_hole_locks_up_where_the_closed_form_diverges(tmp_path: Path) -> None:
    """Helically buckled pipe slid along a horizontal hole: the compression going up from the bit
    obeys `dF/du = mu (w + r_c F^2 / (4 E I))` (Mitchell's contact), whose solution is
    `F(u) = a tan(mu w u / a + atan(F_0 / a))` with `a = 2 sqrt(E I w / r_c)`: it diverges, and the
    string locks up, a finite `u* = (pi/2 - atan(F_0 / a)) a / (mu w)` above the bit (the
    horizontal-hole lock-up analysis of coiled tubing, e.g. He & Kyllingstad 1995). 250 kN on the bit, above the
    helical load 2 sqrt(2) sqrt(E I w / r_c) = 221 kN from the bit up: u* = 1313 m."""
    plan = [{"hold": 1000.0}, {"build": 6.0, "inclination": 90.0}, {"hold": 2000.0}]
    data = _config(plan=plan, inclination_deg=0.0)
    data["sections"][0]["length"] = 3450.0
    f0, mu = 250e3, 0.3
    data["bit"]["weight_on_bit"] = f0
    doc, p, out = _run(tmp_path, data, "--no-plots")
    a = 2.0 * math.sqrt(EI * W / RC)
    assert f0 > math.sqrt(2.0) * a  # helical from the bit
    u_star = (math.pi / 2.0 - math.atan(f0 / a)) * a / (mu * W)
    assert u_star == pytest.approx(1313.0, abs=1.0)
    md = p["md_m"].to_numpy()
    u = md[-1] - md
    compression = -p["sliding_tension_N"].to_numpy()
    closed = a * np.tan(mu * W * np.minimum(u, 0.99 * u_star) / a + math.atan(f0 / a))
    early = closed < 2.0 * f0  # a doubled compression, 1 m elements: to 0.1 %
    assert early.sum() > 300
    np.testing.assert_allclose(compression[early], closed[early], rtol=1e-3)
    assert (p["sliding_buckling"].to_numpy()[u < 1000.0] == "helical").all()
    # where the closed form diverges, the core's compression does, within 1 % of u*
    diverged = u[~(compression < 1e3 * f0)]
    assert diverged.size and diverged.min() == pytest.approx(u_star, rel=1e-2)
    assert doc["lockup"]["sliding"] and doc["hook_load_sliding_N"] is None and "lock-up: sliding" in out


def test_curved_hole_critical_load_is_the_lateral_balance_root(tmp_path: Path) -> None:
    """In a build the critical load solves `F = 2 sqrt(E I (w sin i + F / R) / r_c)` (the
    convention of the docs): a scipy root of it against the core's profile in the build."""
    from scipy.optimize import brentq

    dls = 3.0  # deg/30 m
    data = _config(plan=[{"hold": 300.0}, {"build": dls, "inclination": 60.0}, {"hold": 2100.0}], inclination_deg=0.0)
    _, p, _ = _run(tmp_path, data, "--no-plots")
    radius = 30.0 / math.radians(dls)
    k = int(np.searchsorted(p["md_m"], 300.0 + 0.5 * 60.0 * 10.0))
    md_mid = 0.5 * (p["md_m"].iloc[k] + p["md_m"].iloc[k + 1])
    inc = math.radians((md_mid - 300.0) / radius * 180.0 / math.pi)
    root = brentq(lambda f: f - 2.0 * math.sqrt(EI * (W * math.sin(inc) + f / radius) / RC), 1.0, 1e8, xtol=1e-6)
    assert p["sinusoidal_buckling_load_N"].iloc[k] == pytest.approx(root, rel=1e-4)
    straight = 2.0 * math.sqrt(EI * W * math.sin(inc) / RC)
    assert root > straight


def test_no_hole_diameter_changes_nothing(tmp_path: Path) -> None:
    data = _config()
    del data["well"]["hole_diameter"]
    doc, p, out = _run(tmp_path, data, "--no-plots")
    assert doc["buckling_note"] == "no hole diameter: buckling not evaluated" and "buckling not evaluated" in out
    assert "sinusoidal_buckling_load_N" not in p.columns and "sliding_buckling" not in p.columns
    assert doc["first_buckling"]["sliding"] == {"sinusoidal_md": None, "helical_md": None}


def test_measured_points_get_the_factor_that_made_them(tmp_path: Path) -> None:
    """Points made by the model at known factors (the broomstick's lines), written in field units,
    come back with their factors; an impossible point and an unknown operation are reported."""
    import pandas as pd

    data = _config()
    data["torque_drag"]["friction_factors"] = [0.15, 0.35]
    data["torque_drag"]["broomstick_points"] = 10
    _run(tmp_path / "made", data, "--no-plots")
    b = pd.read_csv(tmp_path / "made" / "out" / "broomstick.csv")
    ft, klbf, ftlbf = 0.3048, 4448.2216152605, 0.3048 * 4.4482216152605
    rows = ["depth [ft],operation,hook_load [klbf],surface_torque [ft lbf]"]
    expect = []
    for mu in (0.15, 0.35):
        r = b[(b["friction_factor"] == mu)].iloc[6]
        d = float(r["bit_depth_m"]) / ft
        rows.append(f"{d!r},pick_up,{float(r['pickup_N']) / klbf!r},")
        rows.append(f"{d!r},slack_off,{float(r['slackoff_N']) / klbf!r},")
        rows.append(f"{d!r},rotating_off_bottom,,{float(r['torque_rotating_Nm']) / ftlbf!r}")
        expect += [mu, mu, mu]
    rows.append(f"{2000 / ft},pick_up,{1e4},")
    rows.append(f"{2000 / ft},tripping,{100},")
    rows.append(f"{2000 / ft},,{100},")
    measured = tmp_path / "points.csv"
    measured.write_text("\n".join(rows) + "\n")
    _, _, out = _run(tmp_path / "check", data, "--measured", str(measured))
    m = pd.read_csv(tmp_path / "check" / "out" / "measured.csv")
    assert "7 points, 6 with an implied friction factor, 2 rows skipped" in out
    np.testing.assert_allclose(m["friction_factor"].iloc[:6], expect, atol=1e-9)
    assert math.isnan(m["friction_factor"].iloc[6]) and "no friction factor in [0, 1]" in m["reason"].iloc[6]
    assert m["depth_m"].iloc[-1] == pytest.approx(2000.0)
    assert (tmp_path / "check" / "out" / "broomstick.png").exists()
    assert (tmp_path / "check" / "out" / "utilisation.png").exists()


def test_field_units_hole_and_pipe_keys() -> None:
    from drillstring.drilling.units import to_si

    si = to_si({"units": "field", "sections": [{"length": 1000, "tool_joint_outer_diameter": 6.625,
                                                "nominal_weight": 22.6, "makeup_torque": 30000}],
                "well": {"hole_diameter": 8.5, "hole_sections": [{"bottom_md": 5000, "diameter": 8.835}]}})
    assert si["well"]["hole_diameter"] == pytest.approx(8.5 * INCH)
    assert si["well"]["hole_sections"][0]["diameter"] == pytest.approx(8.835 * INCH)
    assert si["well"]["hole_sections"][0]["bottom_md"] == pytest.approx(5000 * 0.3048)
    s = si["sections"][0]
    assert s["tool_joint_outer_diameter"] == pytest.approx(6.625 * INCH)
    assert s["nominal_weight"] == pytest.approx(22.6 * 4.4482216152605 / 0.3048)
    assert s["makeup_torque"] == pytest.approx(30000 * 0.3048 * 4.4482216152605)


def test_a_hole_smaller_than_the_tool_joints_is_refused() -> None:
    from drillstring.errors import ValidationError

    data = _config()
    data["sections"][0].update(tool_joint_outer_diameter=0.22, tool_joint_inner_diameter=0.07,
                               tool_joint_length=0.5)
    with pytest.raises(ValidationError, match="tool_joint_outer_diameter") as err:
        ds.torque_drag(DrillConfig.from_dict(data))
    assert err.value.field == "well.hole_diameter"


@settings(max_examples=8, deadline=None)
@given(inc_deg=st.floats(5.0, 85.0), tool_joint_in=st.floats(5.0, 8.0), mu=st.floats(0.05, 0.6))
def test_the_tool_joints_are_the_friction_lever_arm(inc_deg: float, tool_joint_in: float, mu: float) -> None:
    """On a straight inclined hole the rotating off-bottom surface torque is the closed form
    `mu w L sin(i) r`, `r` half the tool joints' outer diameter where a section has tool joints
    (they touch the wall): `TJ OD / OD` times the torque of the same string (the same weight,
    `nominal_weight`) without them; a `contact_diameter` overrides the tool joints."""
    length, weight = 3000.0, 22.6 * 4.4482216152605 / 0.3048  # m, N/m in air
    data = _config(inclination_deg=inc_deg, hole_diameter=None)
    data["sections"][0].update(nominal_weight=weight)
    data["friction"]["static"] = mu
    data["bit"]["weight_on_bit"] = 10e3
    data["torque_drag"].update(broomstick_points=2, friction_factors=[mu])
    joints = {"tool_joint_outer_diameter": tool_joint_in * INCH, "tool_joint_inner_diameter": 2.75 * INCH,
              "tool_joint_length": 21.0 * INCH}

    def torque(**section: Any) -> float:
        d = json.loads(json.dumps(data))
        d["sections"][0].update(section)
        return float(ds.torque_drag(DrillConfig.from_dict(d)).summary["surface_torque_off_bottom_Nm"])

    w_buoyed = weight * (1.0 - MUD / RHO)
    normal = w_buoyed * length * math.sin(math.radians(inc_deg))
    plain, jointed = torque(), torque(**joints)
    assert plain == pytest.approx(mu * normal * OD / 2.0, rel=1e-9)
    assert jointed == pytest.approx(mu * normal * tool_joint_in * INCH / 2.0, rel=1e-9)
    assert jointed / plain == pytest.approx(tool_joint_in / 5.0, rel=1e-12)
    assert torque(**joints, contact_diameter=OD) == pytest.approx(plain, rel=1e-12)
    assert torque(**joints, contact_diameter=6.0 * INCH) == pytest.approx(mu * normal * 3.0 * INCH, rel=1e-9)


def test_the_example_measured_points_give_back_their_factors(tmp_path: Path) -> None:
    """`examples/directional-10000ft-measured.csv` was read off the model's broomstick at the
    factors below (hook loads to 0.1 klbf, torques to 1 ft-lbf): each point's implied friction
    factor is its own within 0.002; the row of an unknown operation is skipped."""
    import pandas as pd

    examples = Path(__file__).resolve().parents[1] / "examples"
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "drillstring", "torque-drag",
                           str(examples / "directional-10000ft-td-field.toml"), "--out", str(out), "--no-plots",
                           "--measured", str(examples / "directional-10000ft-measured.csv")],
                          capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert "12 points, 12 with an implied friction factor, 1 rows skipped" in proc.stdout
    m = pd.read_csv(out / "measured.csv")
    made = [0.3, 0.2, 0.2, 0.3, 0.2, 0.3, 0.3, 0.3, 0.3, 0.4, 0.3, 0.3]
    np.testing.assert_allclose(m["friction_factor"], made, atol=0.002)
