"""Impossible loads, undefined holes and unbounded work in a drilling configuration: each is
refused by the core's validation (a ValidationError naming the key and the allowed range; on the
command line one line and exit status 2) or warned about with the number, never an abort."""

from __future__ import annotations

from pathlib import Path

import pytest

from drillstring.cli import main
from drillstring.drilling import drill, drill_map, load_drill_config
from drillstring.errors import ValidationError

#: 1000 m of 5-in pipe (28.06 kg/m, 275 kN hanging), vertical, with a hoist holding a weight on
#: bit and the regenerative Detournay bit.
COUPLED = """
[[sections]]
length = 1000.0
outer_diameter = 0.127
inner_diameter = 0.108
density = 8000.0

[well]
inclination_deg = 0.0

[bit]
law = "rgd"
radius = 0.108

[hoist]
mode = "weight_on_bit"
weight_on_bit = 50e3

[numerics]
cells = 100
duration = 2.0
"""


def _config(tmp_path: Path) -> Path:
    path = tmp_path / "coupled.toml"
    path.write_text(COUPLED)
    return path


def _cli(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    return code, capsys.readouterr().err


CASES = [
    ("negative-hook-load-step", ["hoist.mode='hook_load'", "hoist.hook_load=200e3", "hoist.steps=[[1.0,-50e3]]"],
     "hoist.steps[0][1]", ">= 0"),
    ("negative-wob-step", ["hoist.steps=[[1.0,-50e3]]"], "hoist.steps[0][1]", ">= 0"),
    ("wob-above-the-buoyed-weight", ["bit.weight_on_bit=10e6"], "bit.weight_on_bit", "at most 275200 N"),
    ("dogleg-of-180-deg", ["well.md=[0,100,400,500,1200]", "well.inclination_deg=[0,0,90,90,90]",
                           "well.azimuth_deg=[0,0,0,0,180]"], "well.md[4]", "a dogleg below 179 deg"),
    ("horizontal-reversing", ["well.md=[0,600,1200]", "well.inclination_deg=[90,90,90]",
                              "well.azimuth_deg=[0,0,180]"], "well.md[2]", "a dogleg below 179 deg"),
    ("hole-above-the-rig-floor", ["well.md=[0,30,60,1100]", "well.inclination_deg=[0,0,150,150]"],
     "well.md[3]", "below the rig floor"),
    ("inclination-180", ["well.inclination_deg=180.0"], "well.inclination_deg", "[0, 180)"),
    ("empty-plan", ["well.plan=[]"], "well.plan", "at least one segment"),
    ("plan-turn-1e-9", ["well.plan=[{hold=100},{build=3,inclination=60},{turn=1e-9,azimuth=90}]",
                        "well.extend=true"], "well.plan[2].turn", "deg/30 m"),
    ("torque-drag-step-1e-9", ["torque_drag.step=1e-9"], "torque_drag.step", "at least 0.001 m"),
    ("cut-surface-cells-1e6", ["bit.detournay.cut_surface='upwind'", "bit.detournay.cut_surface_cells=1000000",
                               "numerics.duration=60"], "bit.detournay.cut_surface_cells", "an integer in 1..="),
    ("no-friction-factors", ["torque_drag.friction_factors=[]"], "torque_drag.friction_factors", "1 to 100"),
]


@pytest.mark.parametrize("sets, field, allowed", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_refused_in_validation_naming_the_key(tmp_path: Path, sets: list[str], field: str, allowed: str) -> None:
    cfg = load_drill_config(_config(tmp_path))
    with pytest.raises(ValidationError) as info:
        cfg.with_overrides(sets)
    assert info.value.field == field and allowed in str(info.value), str(info.value)


@pytest.mark.parametrize("command", ["drill", "torque-drag"])
@pytest.mark.parametrize("sets, field, allowed", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_cli_one_line_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str, sets: list[str],
                             field: str, allowed: str) -> None:
    argv = [command, str(_config(tmp_path)), "--out", str(tmp_path / "out")]
    for s in sets:
        argv += ["--set", s]
    code, err = _cli(capsys, *argv)
    assert code == 2, err
    assert err.count("\n") == 1 and f"invalid {field}" in err and allowed in err, err
    assert "Traceback" not in err and not (tmp_path / "out" / "INCOMPLETE").exists()


MEASURED = """
[[sections]]
length = 1000.0
outer_diameter = 0.127
inner_diameter = 0.108

[well]
inclination_deg = 30.0

[top_drive]
mode = "measured_speed"
speed_series = [[0.0, 40.0], [4.0, 60.0]]

[numerics]
cells = 40
duration = 4.0
"""


def test_a_map_axis_without_effect_is_refused_naming_it(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "measured.toml"
    path.write_text(MEASURED)
    cfg = load_drill_config(path)
    with pytest.raises(ValidationError) as info:
        drill_map(cfg, {"top_drive.rpm": [40.0, 80.0]})
    assert info.value.field == "axis top_drive.rpm" and "measured_speed" in str(info.value)
    # a controller gain under measured_speed, a hoist key of a torsion-only run
    for key, values in (("top_drive.controller.kp", [1e3, 2e3]), ("hoist.speed", [0.01, 0.02])):
        with pytest.raises(ValidationError, match=f"axis {key}"):
            drill_map(cfg, {key: values})
    # the chunked map is checked whole: the rpm changes the controller's runs
    frame = drill_map(cfg, {"top_drive.mode": ["controller", "measured_speed"],
                            "top_drive.speed_series": [[]], "top_drive.rpm": [40.0, 80.0]}, chunk_size=2,
                      out=tmp_path / "map")
    assert list(frame["status"]) == ["success", "success", "invalid", "invalid"]
    code, err = _cli(capsys, "drill-map", str(path), "--axis", "top_drive.rpm=40,80", "--out", str(tmp_path / "m"))
    assert code == 2 and err.count("\n") == 1 and "invalid axis top_drive.rpm" in err, err


def test_loads_the_hoist_cannot_hold_or_the_bit_cannot_drill_are_warned(tmp_path: Path) -> None:
    cfg = load_drill_config(_config(tmp_path)).with_overrides(
        ["hoist.steps=[[0.5,100e6]]", "top_drive.controller.type='pi'", "numerics.duration=1.0"])
    warnings = drill(cfg).warnings
    above = [w for w in warnings if w.startswith("hoist.steps[0][1] = 100000000 N is above the string's buoyed weight "
                                                  "along the hole, 275200 N")]
    stalled = [w for w in warnings if w.startswith("hoist.steps[0][1] = 100000000 N: the bit cannot drill it")]
    assert above and stalled, warnings
    # block and top-drive speeds far outside practice
    fast = load_drill_config(_config(tmp_path)).with_overrides(
        ["hoist.mode='velocity'", "hoist.speed=-30", "numerics.duration=0.2"])
    assert any(w.startswith("hoist.speed = -30 m/s is over the 3 m/s") for w in drill(fast).warnings)
