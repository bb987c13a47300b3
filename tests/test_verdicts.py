"""Verdicts that hold: a motor at its torque limit for a share of the metrics window says so
and leaves the stick-slip verdict undetermined; the controller presets that tune to the BHA's
mode are refused on a string without BHA inertia.

Before: the ``z_torque`` preset on a string with ``bit.bha_inertia = 0`` chattered between the
+-60 kN m torque limits and printed "stick-slip: yes; settled" without a warning.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _cli import one_line_error, run_cli

import drillstring as ds

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
STRING = {"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
          "numerics": {"cells": 100, "duration": 20.0}}


def test_a_motor_at_its_torque_limit_is_warned_about_and_leaves_the_verdict_undetermined() -> None:
    free = ds.drill(STRING, progress=False)
    assert free.metrics.stick_slip_verdict == "yes"
    assert not any("at its limit" in w for w in free.warnings)
    # 4.2 kN m, just over the 4.17 kN m break-off torque: the wind-up rests on the limit
    limited = ds.drill({**STRING, "top_drive": {"torque_limit": 4200.0}}, progress=False)
    m = limited.metrics
    assert m.stick_slip_verdict == "undetermined"
    assert m.stick_slip_reason.startswith("motor torque at its limit ") and m.stick_slip_reason.endswith(
        " % of the window")
    share = float(m.stick_slip_reason.split("limit ")[1].split(" %")[0])
    assert share > 5
    warning = next(w for w in limited.warnings if "top_drive.torque_limit = 4200 N m" in w)
    assert f"{share:.0f} % of the metrics window" in warning


@pytest.mark.parametrize("preset", ["soft_torque", "z_torque"])
def test_a_preset_tuned_to_the_bha_mode_is_refused_without_bha_inertia(preset: str) -> None:
    cfg = {**STRING, "top_drive": {"controller": {"preset": preset}}}
    with pytest.raises(ds.ValidationError, match="top_drive.controller.preset") as err:
        ds.DrillConfig.from_dict(cfg)
    assert "bit.bha_inertia" in str(err.value)
    ok = ds.DrillConfig.from_dict({**cfg, "bit": {"bha_inertia": 100.0}})
    assert ok.top_drive.controller.preset == preset
    # set later on the command line: the same refusal
    base = ds.DrillConfig.from_dict({**STRING, "bit": {"bha_inertia": 100.0}})
    with pytest.raises(ds.ValidationError, match="bit.bha_inertia"):
        base.with_overrides([f"top_drive.controller.preset={preset}", "bit.bha_inertia=0"])


def test_stiff_needs_no_bha_inertia() -> None:
    cfg = ds.DrillConfig.from_dict({**STRING, "top_drive": {"controller": {"preset": "stiff"}}})
    assert cfg.top_drive.controller.type == "pi"


def test_the_cli_refuses_the_preset_in_one_line(tmp_path: object, capsys: pytest.CaptureFixture[str]) -> None:
    import pathlib

    path = pathlib.Path(str(tmp_path)) / "bare.toml"
    path.write_text("[[sections]]\nlength = 2000.0\nouter_diameter = 0.127\ninner_diameter = 0.1086\n"
                    "[top_drive.controller]\npreset = \"z_torque\"\n")
    code, _, err = run_cli(capsys, "drill", str(path), "--out", str(pathlib.Path(str(tmp_path)) / "out"),
                           "--no-plots")
    assert code == 2
    one_line_error(err, "top_drive.controller.preset", "bit.bha_inertia")


# A short coupled string (the van de Wouw pipe, 500 m, no gravity, no wall friction): the rate law
# at 120 rpm and 10 m/h; 4 s of a string that takes tens of seconds to compress onto the bit.
COUPLED = {"sections": [{"length": 500.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
                         "shear_modulus": 77e9, "density": 8000.0, "poisson_ratio": 0.2987012987012987}],
           "well": {"inclination_deg": 0.0, "gravity": 0.0}, "friction": {"static": 0.0}, "damping_rate": 2.0,
           "top_drive": {"rpm": 120.0, "torque_limit": 1e12, "controller": {"type": "speed"},
                         "motor_bandwidth": 1000.0},
           "bit": {"radius": 0.108, "law": "detournay"},
           "hoist": {"mode": "velocity", "speed": 10.0 / 3600.0},
           "numerics": {"cells": 200, "duration": 4.0}}


def _coupled(**numerics: object) -> dict[str, object]:
    return {**COUPLED, "numerics": {**COUPLED["numerics"], **numerics}}  # type: ignore[dict-item]


def test_the_initial_state_defaults_to_rest_and_steady_drills_at_the_steady_state_from_the_start() -> None:
    assert ds.DrillConfig.from_dict(COUPLED).numerics.initial_state == "rest"
    rest = ds.drill(COUPLED, progress=False)
    steady = ds.drill(_coupled(initial_state="steady"), progress=False)
    again = ds.drill(_coupled(initial_state="rest"), progress=False)
    assert np.array_equal(rest.motor_torque, again.motor_torque)  # "rest" is the default, bit for bit
    # from the steady state: the hoist's 10 m/h from the first second; from rest the string is
    # still compressing (the bit far below it)
    assert steady.coupled_metrics is not None and rest.coupled_metrics is not None
    assert steady.coupled_metrics["rop_mean_m_per_h"] == pytest.approx(10.0, abs=0.02)
    assert rest.coupled_metrics["rop_mean_m_per_h"] < 5.0
    assert steady.coupled_regime == "smooth drilling"


def test_a_window_inside_the_axial_transient_is_no_smooth_drilling() -> None:
    # before: "smooth drilling" while the string was still compressing onto the bit
    rest = ds.drill(COUPLED, progress=False)
    assert rest.metrics.stick_slip_verdict == "no"
    assert rest.coupled_regime == "undetermined"
    warning = next(w for w in rest.warnings if w.startswith("regime undetermined, not smooth drilling"))
    assert "weight on bit" in warning and "numerics.initial_state" in warning
    assert "still changing between its halves" in ds.drilling.result.COUPLED_REGIME_CRITERION


def test_a_steady_start_is_refused_without_a_hoist() -> None:
    with pytest.raises(ds.ValidationError, match="numerics.initial_state"):
        ds.drill({**STRING, "numerics": {**STRING["numerics"], "initial_state": "steady"}}, progress=False)
    with pytest.raises(ds.ValidationError, match="numerics.initial_state"):
        ds.DrillConfig.from_dict(_coupled(initial_state="moving"))
    with pytest.raises(ds.ValidationError, match="check_start"):
        ds.drill(STRING, check_start=True, progress=False)


def test_check_start_compares_the_runs_from_rest_and_from_the_steady_state() -> None:
    r = ds.drill(COUPLED, check_start=True, progress=False)
    s = r.start_check
    assert s is not None and not s.agree
    rows = {row.metric: row for row in s.rows}
    assert rows["rop_mean_m_per_h"].rest == r.coupled_metrics["rop_mean_m_per_h"]  # type: ignore[index]
    assert rows["rop_mean_m_per_h"].steady == pytest.approx(10.0, abs=0.02)
    assert (rows["regime"].rest, rows["regime"].steady) == ("undetermined", "smooth drilling")
    warning = next(w for w in r.warnings if w.startswith("start check:"))
    assert "wob_mean_N moves by +857 %" in warning and "regime is 'undetermined' from rest" in warning
    assert r.summary()["start_check"]["agree"] is False


def test_check_grid_compares_the_coupled_metrics_too() -> None:
    # before: only the torsional metrics were compared
    r = ds.drill(_coupled(initial_state="steady", duration=2.0), check_grid=True, progress=False)
    g = r.grid_check
    assert g is not None
    rows = {row.metric: row for row in g.rows}
    for name in ("rop_mean_m_per_h", "wob_mean_N", "tob_mean_Nm", "hook_load_mean_N", "bounce_fraction",
                 "mse_mean_Pa", "regime"):
        assert name in rows, name
    assert rows["regime"].value == rows["regime"].refined == "smooth drilling" and rows["regime"].within
    assert rows["rop_mean_m_per_h"].within
    # the tolerances are the core's
    assert ds.drilling.result.GRID_TOLERANCES["regime"] == ("equal", 0.0)
    assert ds.drilling.result.GRID_FLOORS["ssi"] == 0.01


def test_the_cli_checks_the_start(tmp_path: object, capsys: pytest.CaptureFixture[str]) -> None:
    import pathlib

    folder = pathlib.Path(str(tmp_path))
    (folder / "short.toml").write_text(ds.DrillConfig.from_dict(COUPLED).to_toml())
    code, out, _ = run_cli(capsys, "drill", str(folder / "short.toml"), "--check-start", "--out",
                           str(folder / "out"), "--no-plots")
    assert code == 0
    assert "start check, rest -> steady: DISAGREE (" in out and "regime 'undetermined' -> 'smooth drilling'" in out


def test_z_torque_without_bha_inertia_chatters_at_the_limits_and_says_so() -> None:
    # examples/s-well-3d.toml without its BHA inertia, with what the z_torque rule gave it
    # (torque_highpass_time = 1 / (pi f1) of the bare string): before, "stick-slip: yes" for a
    # motor chattering between its +-60 kN m limits with a 0.18 s period
    cfg = ds.load_drill_config(EXAMPLES / "s-well-3d.toml").with_overrides([
        "top_drive.rpm=40", "bit.bha_inertia=0", "top_drive.controller.type='z_torque'",
        "top_drive.controller.z_factor=4", "top_drive.controller.torque_highpass_time=2.108418168067379"])
    r = ds.drill(cfg, progress=False)
    m = r.metrics
    assert (m.motor_torque_min_Nm, m.motor_torque_max_Nm) == (-60e3, 60e3) and m.period_s < 0.2
    assert m.stick_slip_verdict == "undetermined"
    assert m.stick_slip_reason == "motor torque at its limit 12 % of the window"
    assert any("top_drive.torque_limit = 60000 N m, 12 % of the metrics window" in w for w in r.warnings)
    # the preset itself is refused on this string
    with pytest.raises(ds.ValidationError, match="bit.bha_inertia"):
        cfg.with_overrides(["top_drive.controller.preset='z_torque'"])


def test_the_cli_refuses_a_start_check_or_a_steady_start_without_a_hoist(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    on_bottom = str(EXAMPLES / "on-bottom-3000m.toml")
    code, _, err = run_cli(capsys, "drill", on_bottom, "--check-start", "--out", str(tmp_path / "a"), "--no-plots")
    assert code == 2
    one_line_error(err, "check_start", "[hoist]")
    code, _, err = run_cli(capsys, "drill", on_bottom, "--set", "numerics.initial_state='steady'", "--out",
                           str(tmp_path / "b"), "--no-plots")
    assert code == 2
    one_line_error(err, "numerics.initial_state", "[hoist]")
