"""Verdicts that hold: a motor at its torque limit for a share of the metrics window says so
and leaves the stick-slip verdict undetermined; the controller presets that tune to the BHA's
mode are refused on a string without BHA inertia.

Before: the ``z_torque`` preset on a string with ``bit.bha_inertia = 0`` chattered between the
+-60 kN m torque limits and printed "stick-slip: yes; settled" without a warning.
"""

from __future__ import annotations

import pytest
from _cli import one_line_error, run_cli

import drillstring as ds

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
