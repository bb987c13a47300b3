"""A field-units configuration end to end: plain numbers of ``--set``, ``with_overrides``, a map's
axes, a fit's bounds and every series, step and setpoint are read in the file's unit system;
speeds and the bit's small lengths have their oilfield units; a quantity of the wrong dimension
for the hoist's mode is refused. Exact factors: 1 ft = 0.3048 m, 1 in = 0.0254 m,
1 lbf = 4.4482216152605 N, 1 lb = 0.45359237 kg, 1 US gal = 3.785411784 L."""

from __future__ import annotations

import json
import math
import re
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from _cli import one_line_error, run_cli
from hypothesis import example, given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.drilling import DrillConfig, load_drill_config
from drillstring.drilling.maps import check_axis
from drillstring.drilling.units import FIELD_UNITS, FIELD_UNITS_BY_KEY, field_unit, to_si
from drillstring.errors import ValidationError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

pytest.importorskip("pint")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FT, INCH, LBF, LB, GAL = 0.3048, 0.0254, 4.4482216152605, 0.45359237, 3.785411784e-3
FT_PER_H = FT / 3600.0


def _close(a: float, b: float, rel: float = 4e-16) -> bool:
    return abs(a - b) <= rel * abs(b)


def _pickup(**changes: Any) -> dict[str, Any]:
    """examples/pickup-3200m.toml (a coupled configuration) as a document, tables updated."""
    document = tomllib.loads((EXAMPLES / "pickup-3200m.toml").read_text())
    for table, values in changes.items():
        if isinstance(values, dict) and isinstance(document.get(table), dict):
            document[table] = {**document[table], **values}
        else:
            document[table] = values
    return document


def _field_file(tmp_path: Path, text: str = "") -> Path:
    path = tmp_path / "field.toml"
    path.write_text((EXAMPLES / "on-bottom-3000m-field.toml").read_text() + text)
    return path


# ---------------------------------------------------------------- 1. plain numbers of overrides


def test_a_field_file_remembers_its_unit_system() -> None:
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    si = load_drill_config(EXAMPLES / "on-bottom-3000m.toml")
    assert field.units == "field" and si.units == "si"
    assert field.with_overrides({"top_drive.rpm": 60}).units == "field"
    assert field.with_units("si").units == "si" and field.with_units("si") == field
    with pytest.raises(ValidationError, match="units"):
        field.with_units("imperial")


def test_with_overrides_reads_plain_numbers_in_the_files_units() -> None:
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    changed = field.with_overrides(["sections[0].outer_diameter=5.5", "bit.weight_on_bit=20",
                                    "sections[1].length=700", "well.mud_density=11"])
    assert changed.sections[0].outer_diameter == 5.5 * INCH
    assert _close(changed.bit.weight_on_bit, 20e3 * LBF)
    assert _close(changed.sections[1].length, 700 * FT)
    assert _close(changed.well.mud_density, 11 * LB / GAL)
    # a string with a unit is read in its own unit, and units="si" reads plain numbers as SI
    assert field.with_overrides({"sections[0].outer_diameter": "0.14 m"}).sections[0].outer_diameter == 0.14
    assert field.with_overrides({"bit.weight_on_bit": 80e3}, units="si").bit.weight_on_bit == 80e3
    # an SI file's plain numbers stay SI
    si = load_drill_config(EXAMPLES / "on-bottom-3000m.toml")
    assert si.with_overrides({"bit.weight_on_bit": 80e3}).bit.weight_on_bit == 80e3


def test_set_in_a_field_file_gives_the_pickup_of_the_field_value(tmp_path: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    config = str(EXAMPLES / "on-bottom-3000m-field.toml")
    lines = []
    for n, value in enumerate(("5", "'5 in'")):
        code, out, _ = run_cli(capsys, "torque-drag", config, "--out", str(tmp_path / f"td{n}"), "--no-plots",
                               "--set", f"sections[0].outer_diameter={value}")
        assert code == 0
        lines.append(next(line for line in out.splitlines() if line.startswith("hook load")))
    assert lines[0] == lines[1] and "klbf" in lines[0]  # the same pick-up, in the file's units
    pickup = float(lines[0].split("pick-up ")[1].split()[0])
    assert 100 < pickup < 400  # not the 871,097 klbf of a 5 m pipe


def test_map_axes_of_a_field_file_are_field_units() -> None:
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    values = check_axis("bit.weight_on_bit", [10.0, 20.0, 30.0, 40.0], "--axis", field)
    assert all(_close(v, w * 1e3 * LBF) for v, w in zip(values, (10, 20, 30, 40)))
    assert check_axis("sections[0].outer_diameter", [5.0, "0.14 m"], "--axis", field) == [0.127, 0.14]
    si = load_drill_config(EXAMPLES / "on-bottom-3000m.toml")
    assert check_axis("bit.weight_on_bit", [10.0], "--axis", si) == [10.0]


def test_drill_map_axis_in_a_field_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import pandas as pd

    code, out, err = run_cli(capsys, "drill-map", str(EXAMPLES / "on-bottom-3000m-field.toml"),
                             "--axis", "bit.weight_on_bit=10:40:4", "--set", "numerics.duration=0.5",
                             "--set", "numerics.cells=40", "--out", str(tmp_path / "map"), "--no-plots",
                             "--threads", "1")
    assert code == 0, err
    frame = pd.read_parquet(tmp_path / "map" / "map.parquet")
    assert all(_close(v, w * 1e3 * LBF, 1e-15) for v, w in zip(frame["bit.weight_on_bit"], (10, 20, 30, 40)))


def test_an_invalid_map_row_of_a_field_file_speaks_field_units() -> None:
    """A run the core refuses keeps its row (``status = "invalid"``) with the core's message, the
    SI quantities in it followed by their field values."""
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml").with_overrides(
        {"numerics.duration": 0.2, "numerics.cells": 40})
    frame = ds.drilling.drill_map(field, {"bit.weight_on_bit": [10.0, 1e5]}, threads=1)
    assert list(frame["status"]) == ["success", "invalid"]
    message = frame["message"][1]
    assert "bit.weight_on_bit" in message
    limit = re.search(r"at most ([0-9.]+) N \(([0-9.]+) klbf\)", message)
    assert limit is not None, message
    assert math.isclose(float(limit.group(2)), float(limit.group(1)) / LBF / 1e3, rel_tol=1e-5)
    si = ds.drilling.drill_map(load_drill_config(EXAMPLES / "on-bottom-3000m.toml").with_overrides(
        {"numerics.duration": 0.2, "numerics.cells": 40}), {"bit.weight_on_bit": [1e9]}, threads=1)
    assert "klbf" not in si["message"][0] and "bit.weight_on_bit" in si["message"][0]


def test_fit_bounds_of_a_field_file_are_field_units() -> None:
    from drillstring.calibration.fit import _bounds

    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    bounds = _bounds({"bit.weight_on_bit": (10, 40), "friction.static": (0.05, 0.5),
                      "sections[1].outer_diameter": ("6 in", 7)}, field)
    assert _close(bounds["bit.weight_on_bit"][0], 10e3 * LBF) and _close(bounds["bit.weight_on_bit"][1], 40e3 * LBF)
    assert bounds["friction.static"] == (0.05, 0.5)
    assert bounds["sections[1].outer_diameter"] == (0.1524, 0.1778)  # exact decimal factors
    assert _bounds({"bit.weight_on_bit": (10e3, 40e3)}, field.with_units("si"))["bit.weight_on_bit"] == (10e3, 40e3)
    with pytest.raises(ValidationError, match=r"parameters\[bit.weight_on_bit\].*force"):
        _bounds({"bit.weight_on_bit": ("10 ft", 40)}, field)


def test_series_and_steps_of_a_field_file_are_field_units() -> None:
    document = _pickup(units="field", hoist={"mode": "velocity", "speed": -600, "steps": [[5, 100], [10, "1 ft/s"]]},
                       top_drive={"mode": "measured_speed", "speed_series": [[0, 0], [40, 60]],
                                  "steps": [[1, 30]]})
    document["sections"] = [{**s, "length": s["length"] / FT, "outer_diameter": s["outer_diameter"] / INCH,
                             "inner_diameter": s["inner_diameter"] / INCH, "shear_modulus": "79.3 GPa",
                             "density": "7850 kg/m^3"} for s in document["sections"]]
    document["well"] = {**document["well"], "mud_density": "1200 kg/m^3"}
    document["bit"] = {**document["bit"], "radius": "0.108 m"}
    hoist = to_si(document)["hoist"]
    assert _close(hoist["speed"], -600 * FT_PER_H)
    assert hoist["steps"][0][0] == 5 and _close(hoist["steps"][0][1], 100 * FT_PER_H)
    assert _close(hoist["steps"][1][1], FT)
    top = to_si(document)["top_drive"]
    assert top["speed_series"] == [[0, 0], [40, 60]] and top["steps"] == [[1, 30]]  # s and rpm in both systems
    # the hook load's steps of hook_load mode are forces: klbf
    hook = to_si({**document, "hoist": {"mode": "hook_load", "hook_load": 170, "steps": [[5, 180]]}})["hoist"]
    assert _close(hook["hook_load"], 170e3 * LBF) and _close(hook["steps"][0][1], 180e3 * LBF)
    # the autodriller's setpoint and gains by its target
    wob = {"mode": "autodriller", "autodriller": {"target": "weight_on_bit", "setpoint": 18, "kp": 2, "ki": 1,
                                                  "max_speed": 100}, "steps": [[5, 20]]}
    wob_si = to_si({**document, "hoist": wob})["hoist"]
    assert _close(wob_si["autodriller"]["setpoint"], 18e3 * LBF)
    assert _close(wob_si["steps"][0][1], 20e3 * LBF)
    assert _close(wob_si["autodriller"]["kp"], 2 * FT_PER_H / (1e3 * LBF))
    assert _close(wob_si["autodriller"]["ki"], FT_PER_H / (1e3 * LBF))
    assert _close(wob_si["autodriller"]["max_speed"], 100 * FT_PER_H)
    rop = {"mode": "autodriller", "autodriller": {"target": "rop", "setpoint": 60, "kp": 0.5, "ki": 0.1},
           "steps": [[5, 90]]}
    rop_si = to_si({**document, "hoist": rop})["hoist"]
    assert _close(rop_si["autodriller"]["setpoint"], 60 * FT_PER_H) and _close(rop_si["steps"][0][1], 90 * FT_PER_H)
    assert rop_si["autodriller"]["kp"] == 0.5 and rop_si["autodriller"]["ki"] == 0.1
    # with_overrides of a field configuration: the steps by the mode it sets
    field = DrillConfig.from_dict({**document, "hoist": {"mode": "velocity", "speed": 100}})
    changed = field.with_overrides(["hoist.mode=hook_load", "hoist.hook_load=170", "hoist.steps=[[5, 180]]"])
    assert _close(changed.hoist.steps[0][1], 180e3 * LBF)
    assert _close(field.with_overrides(["hoist.steps=[[5, 120]]"]).hoist.steps[0][1], 120 * FT_PER_H)


# ---------------------------------------------------------------- 2. speeds and the bit's lengths


def test_the_field_unit_of_a_speed_is_ft_per_hour() -> None:
    assert FIELD_UNITS["m/s"] == "ft/h" and FIELD_UNITS["m/h"] == "ft/h"
    for key in ("hoist.speed", "hoist.autodriller.min_speed", "hoist.autodriller.max_speed"):
        assert field_unit(key) == "ft/h"
    hoist = to_si(_pickup(units="field", hoist={"speed": 100}))["hoist"]
    assert _close(hoist["speed"], 100 * FT_PER_H)  # 100 ft/h, not 100 m/s


def test_the_bits_small_lengths_are_inches_and_every_other_length_feet() -> None:
    from drillstring.drilling.config import config_schema

    lengths = {k for k, v in config_schema().items() if v["unit"] == "m"}
    inches = {k for k in lengths if field_unit(k) == "in"}
    assert inches == {"sections[].outer_diameter", "sections[].inner_diameter", "sections[].contact_diameter",
                      "sections[].tool_joint_outer_diameter", "sections[].tool_joint_inner_diameter",
                      "sections[].tool_joint_length", "well.hole_diameter", "well.hole_sections[].diameter",
                      "bit.radius", "bit.diameter", "bit.detournay.wear_flat_length"}
    assert {field_unit(k) for k in lengths - inches} == {"ft"}
    assert all(k in lengths for k in FIELD_UNITS_BY_KEY)
    bit = to_si({"units": "field", "sections": [{"length": 1000}],
                 "bit": {"diameter": 8.5, "detournay": {"wear_flat_length": 0.5}}})["bit"]
    assert bit["detournay"]["wear_flat_length"] == 0.5 * INCH and _close(bit["diameter"], 8.5 * INCH)


# ---------------------------------------------------------------- 3. the dimension of a mode's value


@pytest.mark.parametrize(
    ("hoist", "path", "words"),
    [
        ({"mode": "velocity", "steps": [[5.0, "100 kN"]]}, "hoist.steps[0][1]", 'speed (hoist.mode = "velocity")'),
        ({"mode": "hook_load", "steps": [[5.0, "1 ft/min"]]}, "hoist.steps[0][1]", 'force (hoist.mode = "hook_load")'),
        ({"mode": "weight_on_bit", "steps": [[1.0, 10e3], [5.0, "3 m/h"]]}, "hoist.steps[1][1]", "force"),
        ({"mode": "autodriller", "autodriller": {"target": "rop", "setpoint": "18 klbf"}},
         "hoist.autodriller.setpoint", 'speed (hoist.autodriller.target = "rop")'),
        ({"mode": "autodriller", "autodriller": {"setpoint": "60 ft/h"}},
         "hoist.autodriller.setpoint", 'force (hoist.autodriller.target = "weight_on_bit")'),
        ({"mode": "autodriller", "autodriller": {"target": "rop"}, "steps": [[5.0, "10 kN"]]},
         "hoist.steps[0][1]", "speed"),
    ],
)
def test_a_quantity_of_another_dimension_than_the_modes_is_refused(hoist: dict[str, Any], path: str,
                                                                   words: str) -> None:
    for units in ("si", "field"):
        with pytest.raises(ValidationError) as info:
            DrillConfig.from_dict(_pickup(units=units, hoist=hoist))
        assert info.value.field == path and words in str(info.value), str(info.value)


def test_a_wrong_dimension_in_the_hoists_steps_is_one_line_exit_2(tmp_path: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "pickup.toml"
    config.write_text((EXAMPLES / "pickup-3200m.toml").read_text().replace(
        "ramp_time = 2.0", 'ramp_time = 2.0\nsteps = [[5.0, "100 kN"]]'))
    code, _, err = run_cli(capsys, "drill", str(config), "--out", str(tmp_path / "run"))
    assert code == 2
    one_line_error(err, "hoist.steps[0][1]", "100 kN", "speed", "velocity")
    assert not (tmp_path / "run").exists()
    # and by --set, with the mode the same overrides set
    code, _, err = run_cli(capsys, "drill", str(EXAMPLES / "pickup-3200m.toml"), "--out", str(tmp_path / "run"),
                           "--set", "hoist.mode=hook_load", "--set", "hoist.steps=[[5.0, '3 ft/min']]")
    assert code == 2
    one_line_error(err, "hoist.steps[0][1]", "force", "hook_load")


def test_a_right_dimension_is_converted_in_either_system() -> None:
    for units in ("si", "field"):
        hoist = DrillConfig.from_dict(_pickup(units=units, hoist={"mode": "velocity", "steps": [[5.0, "60 ft/min"]]}))
        assert math.isclose(hoist.hoist.steps[0][1], 60 * FT / 60, rel_tol=1e-15)


# ---------------------------------------------------------------- one configuration, however written


def _si(value: float, factor: Fraction) -> float:
    """The SI float of the field number ``value`` as written (its shortest repr), correctly rounded
    (with its sign: a Fraction has no -0.0, the conversion keeps it)."""
    return math.copysign(float(Fraction(repr(value)) * factor), value)


#: key -> (field unit, its exact SI factor, the values a user writes)
_KEYS = {
    "sections[0].outer_diameter": ("in", Fraction("0.0254"), st.floats(2.5, 12.0)),
    "sections[1].length": ("ft", Fraction("0.3048"), st.floats(10.0, 30000.0)),
    "bit.radius": ("in", Fraction("0.0254"), st.floats(2.0, 10.0)),
    "hoist.speed": ("ft/h", Fraction("0.3048") / 3600, st.floats(-3000.0, 3000.0)),
    "well.mud_density": ("ppg", Fraction("0.45359237") / Fraction("0.003785411784"), st.floats(0.0, 20.0)),
    "friction.static": ("", Fraction(1), st.floats(0.0, 1.0)),
    "top_drive.rpm": ("rpm", Fraction(1), st.floats(-300.0, 300.0)),
}
#: weight on bit of a torsion-only run (the hoist's own is checked above): klbf
_WOB = ("klbf", Fraction("4448.2216152605"), st.floats(0.0, 100.0))


def _document(units: str, values: dict[str, Any]) -> dict[str, Any]:
    """A coupled configuration: every value not in ``values`` a string with its SI unit (the same
    in either system), those of ``values`` at their dotted keys."""
    document: dict[str, Any] = {
        "units": units,
        "sections": [{"length": "3000 m", "outer_diameter": "0.127 m", "inner_diameter": "0.05 m",
                      "shear_modulus": "79.3 GPa", "density": "7850 kg/m^3"},
                     {"length": "200 m", "outer_diameter": "0.1651 m", "inner_diameter": "0.05 m",
                      "shear_modulus": "79.3 GPa", "density": "7850 kg/m^3"}],
        "well": {"inclination_deg": 30.0, "mud_density": "1200 kg/m^3"},
        "friction": {"static": 0.2, "kinetic_ratio": 1.0},
        "top_drive": {"rpm": 0.0, "controller": {"type": "speed"}},
        "bit": {"law": "rgd", "radius": "0.108 m"},
        "hoist": {"mode": "velocity", "speed": "-0.05 m/s", "ramp_time": 2.0},
        "numerics": {"duration": 30.0},
    }
    for path, value in values.items():
        node: Any = document
        parts = path.replace("]", "").replace("[", ".").split(".")
        for part in parts[:-1]:
            node = node[int(part)] if part.isdigit() else node[part]
        node[parts[-1]] = value
    return document


@settings(max_examples=40, deadline=None)
@given(st.fixed_dictionaries({key: strategy for key, (_, _, strategy) in _KEYS.items()}))
@example({**{key: 5.0 for key in _KEYS}, "friction.static": 0.3, "top_drive.rpm": -0.0, "hoist.speed": -0.0})
def test_one_configuration_however_its_numbers_are_written(values: dict[str, float]) -> None:
    # (a) plain numbers of a field file
    plain = DrillConfig.from_dict(_document("field", values))
    # (b) strings with their units (either system)
    text = {k: f"{v!r} {_KEYS[k][0]}".strip() for k, v in values.items()}
    written = DrillConfig.from_dict(_document("si", text))
    # (c) SI numbers in an SI file
    si = DrillConfig.from_dict(_document("si", {k: _si(v, _KEYS[k][1]) for k, v in values.items()}))
    # (d) overrides of a field configuration, plain numbers (a mapping, and --set's key=value text)
    base = DrillConfig.from_dict(_document("field", {}))
    overridden = base.with_overrides(values)
    assigned = base.with_overrides([f"{k}={v!r}" for k, v in values.items()])
    assert plain == written == si == overridden == assigned
    assert plain.to_json() == written.to_json() == si.to_json() == overridden.to_json() == assigned.to_json()
    assert plain.units == overridden.units == "field" and si.units == "si"


@settings(max_examples=30, deadline=None)
@given(_WOB[2], st.floats(0.0, 20.0))
def test_the_weight_on_bit_however_it_is_written(wob: float, diameter_in: float) -> None:
    field = {"units": "field", "sections": [{"length": "3000 m", "outer_diameter": "0.127 m",
                                             "inner_diameter": "0.1 m"}]}
    plain = DrillConfig.from_dict({**field, "bit": {"weight_on_bit": wob}})
    written = DrillConfig.from_dict({**field, "units": "si", "bit": {"weight_on_bit": f"{wob!r} klbf"}})
    si = DrillConfig.from_dict({**field, "units": "si", "bit": {"weight_on_bit": _si(wob, _WOB[1])}})
    overridden = DrillConfig.from_dict(field).with_overrides([f"bit.weight_on_bit={wob!r}"])
    assert plain == written == si == overridden
    assert plain.to_json() == si.to_json() == overridden.to_json()


# ---------------------------------------------------------------- 4. a key naming a unit holds that unit


def test_a_converted_value_is_written_under_its_field_named_key() -> None:
    from drillstring.drilling.units import unit_key

    assert unit_key("motor_torque_max_Nm", "N*m", "ft*lbf") == "motor_torque_max_ftlbf"
    assert unit_key("rop_mean_m_per_h", "m/h", "ft/h") == "rop_mean_ft_per_h"
    assert unit_key("hook_load_mean_N", "N", "klbf") == "hook_load_mean_klbf"
    assert unit_key("mse_mean_Pa", "Pa", "psi") == "mse_mean_psi"
    assert unit_key("bit_rpm_mean", "rpm", "rpm") == "bit_rpm_mean"
    assert unit_key("motor_torque_max_Nm", "N*m", "N*m") == "motor_torque_max_Nm"
    assert unit_key("window_start", "s", "s") == "window_start"


def test_a_coupled_runs_field_copy_has_field_named_keys() -> None:
    from drillstring.drilling import drill
    from drillstring.drilling.output import report_markdown

    config = load_drill_config(EXAMPLES / "pickup-3200m.toml").with_overrides(
        ["numerics.cells=60", "numerics.duration=4", "metrics.window=[2.0, 4.0]"])
    result = drill(config)
    summary = result.summary("field")
    report = report_markdown(result, units="field")  # and the report's coupled table in field units
    assert "| hook load, klbf |" in report and "| ROP, ft/h |" in report
    assert "| MSE, psi |" in report and "kN" not in report
    copy = summary["output_units"]
    coupled = summary["coupled"]
    assert copy["units"]["hook_load_mean_klbf"] == "klbf" and copy["units"]["rop_mean_ft_per_h"] == "ft/h"
    assert _close(copy["metrics"]["hook_load_mean_klbf"], coupled["hook_load_mean_N"] / (1e3 * LBF), 1e-15)
    assert _close(copy["metrics"]["wob_mean_klbf"] or 1.0, (coupled["wob_mean_N"] / (1e3 * LBF)) or 1.0, 1e-15)
    assert copy["metrics"]["bounce_fraction"] == coupled["bounce_fraction"]
    for key in copy["metrics"]:  # every name with a unit suffix names the field unit it holds
        assert not key.endswith(("_N", "_Nm", "_Pa", "_m_per_h")), key
    # the SI entries keep their names and values
    assert "hook_load_mean_N" in coupled and "motor_torque_max_Nm" in summary


# ---------------------------------------------------------------- 5. a field user reads field units


SHORT = ["--set", "numerics.duration=5", "--set", "numerics.cells=60", "--no-plots"]


def test_a_field_files_report_and_console_are_in_field_units(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(capsys, "drill", str(EXAMPLES / "on-bottom-3000m-field.toml"), "--out",
                           str(tmp_path / "field"), *SHORT)
    assert code == 0
    report = (tmp_path / "field" / "report.md").read_text()
    assert "| section | length, ft | OD, in | ID, in | G, psi | density, ppg |" in report
    assert "| drill pipe 5 in 19.5 lb/ft | 9842.52 | 5 | 4.27559 |" in report
    assert "WOB 17.98 klbf, r 4.25197 in" in report and "| highest motor torque, kft-lbf |" in report
    assert "kN" not in report and "| 3000 |" not in report
    # a warning's SI quantities are followed by their field values, on the console and in the report
    warned = [line for line in out.splitlines() if line.startswith("warning:") and " N m" in line]
    assert warned and all("ft-lbf" in line for line in warned)
    assert all("ft-lbf" in line for line in report.splitlines() if line.startswith("- warning") and " N m" in line)
    # the SI file's report is SI, and --units si gives it for a field file
    run_cli(capsys, "drill", str(EXAMPLES / "on-bottom-3000m.toml"), "--out", str(tmp_path / "si"), *SHORT)
    si = (tmp_path / "si" / "report.md").read_text()
    assert "| section | length, m | OD, m | ID, m | G, GPa | density, kg/m³ |" in si and "ft-lbf" not in si
    assert "| drill pipe 5 in 19.5 lb/ft | 3000 | 0.127 | 0.1086 | 79.3 | 7850 |" in si
    assert "WOB 80 kN, r 0.108 m" in si
    run_cli(capsys, "drill", str(EXAMPLES / "on-bottom-3000m-field.toml"), "--out", str(tmp_path / "si2"), *SHORT,
            "--units", "si")
    assert "length, m" in (tmp_path / "si2" / "report.md").read_text()


def test_tune_prints_the_gains_in_field_units_too(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(capsys, "tune", str(EXAMPLES / "on-bottom-3000m-field.toml"))
    assert code == 0
    assert "14825 N m s/rad (10934.4 ft-lbf s/rad)" in out and "2900 kg m^2 (68818 lb ft^2)" in out
    code, si, _ = run_cli(capsys, "tune", str(EXAMPLES / "on-bottom-3000m.toml"))
    assert code == 0 and "ft-lbf" not in si and "14825 N m s/rad" in si
    assert "ft-lbf" in run_cli(capsys, "tune", str(EXAMPLES / "on-bottom-3000m.toml"), "--units", "field")[1]


def test_a_value_error_of_a_field_file_gives_the_range_in_field_units(tmp_path: Path,
                                                                     capsys: pytest.CaptureFixture[str]) -> None:
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    with pytest.raises(ValidationError) as info:
        field.with_overrides(["sections[0].outer_diameter=500"])
    assert info.value.field == "sections[0].outer_diameter"
    assert "at most 10 m" in str(info.value)  # the core's range, and the field user's
    assert "(in field units: got 500 in; a finite number > 0 in, at most 393.701 in)" in str(info.value)
    with pytest.raises(ValidationError, match=r"in field units: got -1 klbf; a finite number >= 0 \(klbf\)"):
        field.with_overrides({"bit.weight_on_bit": -1})
    with pytest.raises(ValidationError, match=r"in field units: got 70 ppg; a finite number in \[0, 65.5114\) ppg"):
        field.with_overrides({"well.mud_density": 70})
    # from the file itself, with its line; an SI file's error is SI alone
    bad = tmp_path / "bad.toml"
    bad.write_text((EXAMPLES / "on-bottom-3000m-field.toml").read_text().replace(
        'outer_diameter = "5 in"', "outer_diameter = 500"))
    code, _, err = run_cli(capsys, "drill", str(bad), "--out", str(tmp_path / "run"))
    assert code == 2
    one_line_error(err, "line 17", "sections[0].outer_diameter", "at most 393.701 in")
    code, _, err = run_cli(capsys, "drill", str(EXAMPLES / "on-bottom-3000m.toml"), "--out", str(tmp_path / "run"),
                           "--set", "sections[0].outer_diameter=12.7")
    assert code == 2 and "field units" not in one_line_error(err, "at most 10 m")
    # an SI file with --units field: the range in field units too
    code, _, err = run_cli(capsys, "torque-drag", str(EXAMPLES / "on-bottom-3000m.toml"), "--out",
                           str(tmp_path / "run"), "--set", "sections[0].outer_diameter=12.7", "--units", "field")
    assert code == 2
    one_line_error(err, "at most 10 m", "(in field units: got 500 in;", "at most 393.701 in)")


def test_annotate_gives_each_si_quantity_its_field_value() -> None:
    from drillstring.drilling.units import annotate

    text = "went from 808.1 to 1378 N m (+71 %), 0.6431 rpm at 3000 m, 80 kN and 12 kN m; [2.5, 5] s"
    assert annotate(text, "si") == text
    assert annotate(text, "field") == ("went from 808.1 to 1378 N m (596.024 to 1016.36 ft-lbf) (+71 %), 0.6431 rpm "
                                       "at 3000 m (9842.52 ft), 80 kN (17.9847 klbf) and 12 kN m (8.85075 kft-lbf); "
                                       "[2.5, 5] s")


def test_a_coupled_maps_console_and_figure_in_field_units(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    import pandas as pd

    from drillstring.drilling.map_plots import regime_map

    args = ["drill-map", str(EXAMPLES / "coupled-rpm-wob-map.toml"), "--axis", "top_drive.rpm=200,400",
            "--axis", "hoist.weight_on_bit=120e3,200e3", "--set", "numerics.duration=4", "--set", "numerics.cells=60",
            "--set", "metrics.window=[2.0, 4.0]", "--threads", "1", "--no-plots"]
    code, si, _ = run_cli(capsys, *args, "--out", str(tmp_path / "si"))
    assert code == 0 and "m/h" in si and "MPa" in si
    code, field, _ = run_cli(capsys, *args, "--out", str(tmp_path / "field"), "--units", "field")
    regimes = next(line for line in field.splitlines() if line.startswith("regimes:"))
    assert code == 0 and "ft/h" in regimes and "psi" in regimes and "m/h" not in regimes
    frame = pd.read_parquet(tmp_path / "si" / "map.parquet")
    frame.attrs["axes"] = {"top_drive.rpm": [200.0, 400.0], "hoist.weight_on_bit": [120e3, 200e3]}
    fig = regime_map(frame, "top_drive.rpm", "hoist.weight_on_bit", units="field")
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert any("ft/h" in label for label in labels) and any("psi" in label for label in labels), labels


def test_fit_of_a_field_file_reads_and_reports_field_units(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    import pandas as pd

    from drillstring.drilling import drill

    config = tmp_path / "pickup-field.toml"
    config.write_text("units = \"field\"\n" + (EXAMPLES / "pickup-3200m.toml").read_text()
                      .replace("length = 3000.0", 'length = "3000 m"').replace("length = 200.0", 'length = "200 m"')
                      .replace("outer_diameter = 0.127", "outer_diameter = 5").replace("inner_diameter = 0.1086",
                                                                                      'inner_diameter = "0.1086 m"')
                      .replace("outer_diameter = 0.1651", "outer_diameter = 6.5")
                      .replace("inner_diameter = 0.0714", 'inner_diameter = "0.0714 m"')
                      .replace("shear_modulus = 79.3e9", 'shear_modulus = "79.3 GPa"')
                      .replace("density = 7850.0", 'density = "7850 kg/m^3"')
                      .replace("mud_density = 1200.0", "mud_density = 10.0")
                      .replace("radius = 0.108", "radius = 4.25").replace("speed = -0.05", "speed = -600")
                      .replace("cells = 300", "cells = 60").replace("duration = 30.0", "duration = 12.0")
                      .replace("window = [20.0, 30.0]", "window = [6.0, 12.0]"))
    run = drill(load_drill_config(config))
    assert _close(run.config.hoist.speed, -600 * FT_PER_H) and _close(run.config.well.mud_density, 10 * LB / GAL)
    pd.DataFrame({"t": run.t, "hook_load": run.axial["hook_load"]}).to_csv(tmp_path / "data.csv", index=False)
    code, out, err = run_cli(capsys, "fit", str(config), "--data", str(tmp_path / "data.csv"), "--target",
                             "hook_load", "--param", "well.mud_density=8:12", "--window", "4:12", "--samples", "8",
                             "--no-landscape", "--no-plots", "--threads", "1", "--out", str(tmp_path / "fit"))
    assert code == 0, err
    line = next(line for line in out.splitlines() if line.startswith("well.mud_density = "))
    assert "ppg" in line, line
    value = float(line.split("; ")[1].split()[0])
    assert abs(value - 10.0) < 0.05, line  # the fitted mud weight, in ppg, from bounds read in ppg
    report = (tmp_path / "fit" / "report.md").read_text()
    row = next(r for r in report.splitlines() if r.startswith("| `well.mud\\_density`"))
    assert "ppg" in row and "(8 .. 12 ppg)" in row, row


# ---------------------------------------------------------------- 6. the field example end to end


def test_the_field_example_is_its_si_twin_within_its_rounding() -> None:
    from drillstring.drilling.torque_drag import torque_drag

    field = load_drill_config(EXAMPLES / "s-well-3d-field.toml")
    si = load_drill_config(EXAMPLES / "s-well-3d.toml")
    assert field.units == "field" and si.units == "si"
    assert _close(field.bit.weight_on_bit, 22.5e3 * LBF) and field.sections[0].outer_diameter == 0.127
    a, b = torque_drag(field).summary, torque_drag(si).summary
    for name in ("hook_load_pickup_N", "hook_load_slackoff_N", "hook_load_rotating_N", "surface_torque_off_bottom_Nm"):
        assert math.isclose(a[name], b[name], rel_tol=2e-3), (name, a[name], b[name])


def test_a_survey_in_feet_is_the_survey_in_metres() -> None:
    import numpy as np
    import pandas as pd

    metres = pd.read_csv(EXAMPLES / "s-well-3d-survey.csv")
    feet = pd.read_csv(EXAMPLES / "s-well-3d-survey-ft.csv")
    assert list(feet.columns) == ["md_ft", "inc_deg", "azi_deg"]
    assert np.allclose(feet["md_ft"] * FT, metres["md_m"], atol=0.005 * FT)
    assert (feet[["inc_deg", "azi_deg"]].to_numpy() == metres[["inc_deg", "azi_deg"]].to_numpy()).all()


def test_a_map_of_a_file_with_a_survey_reads_it_beside_the_file(tmp_path: Path) -> None:
    from drillstring.drilling.maps import _map_config

    for name in ("s-well-3d.toml", "s-well-3d-field.toml"):
        config = _map_config(EXAMPLES / name)  # the survey path is relative to the file
        assert config.well.survey is not None and Path(config.well.survey).is_absolute()
    assert _map_config(EXAMPLES / "s-well-3d-field.toml").units == "field"


def test_the_field_workflows_documented_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The console lines the README and docs/units.md show for examples/s-well-3d-field.toml."""
    root = EXAMPLES.parent
    readme, units_md = (root / "README.md").read_text(), (root / "docs" / "units.md").read_text()
    config = str(EXAMPLES / "s-well-3d-field.toml")
    code, out, _ = run_cli(capsys, "torque-drag", config, "--out", str(tmp_path / "td"), "--no-plots")
    hook = next(line for line in out.splitlines() if line.startswith("hook load"))
    assert code == 0 and hook.split(" (with")[0] in readme and hook.split(" (with")[0] in units_md
    code, out, _ = run_cli(capsys, "drill", config, "--out", str(tmp_path / "run"), "--no-plots",
                           "--set", "bit.weight_on_bit=30")
    window = next(line for line in out.splitlines() if line.startswith("window"))
    shown = "lowest motor torque 16.25 kft-lbf, highest motor torque 21.71 kft-lbf, break-off torque 16 kft-lbf"
    assert code == 0 and "SSI 1.11," in window and shown in window and shown in readme
    code, out, _ = run_cli(capsys, "drill", config, "--out", str(tmp_path / "run80"), "--no-plots",
                           "--set", "bit.weight_on_bit=30", "--set", "top_drive.rpm=80")
    window = next(line for line in out.splitlines() if line.startswith("window"))
    assert code == 0 and f"# {window}" in units_md


def test_a_field_files_figures_are_field_figures(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = str(EXAMPLES / "on-bottom-3000m-field.toml")
    for name, extra in (("default", []), ("field", ["--units", "field"]), ("si", ["--units", "si"])):
        assert run_cli(capsys, "torque-drag", config, "--out", str(tmp_path / name), *extra)[0] == 0
    for figure in ("torque_drag.png", "broomstick.png", "well_path.png"):
        default, field, si = ((tmp_path / name / figure).read_bytes() for name in ("default", "field", "si"))
        assert default == field != si, figure


def test_the_python_api_speaks_a_field_files_units_by_default(tmp_path: Path) -> None:
    """``ds.drill`` of a field configuration: its warnings carry the field values beside the SI
    ones (once, however often annotated), and ``save``/``summary`` default to its units as the
    command line does; ``output_units="si"`` still gives the SI set alone."""
    from drillstring.drilling.units import annotate

    config = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml").with_overrides(
        {"numerics.duration": 5.0}, units="si")
    result = ds.drill(config)
    torque = [w for w in result.warnings if " N m" in w]
    assert torque and all("ft-lbf)" in w for w in torque), torque
    assert all(annotate(w, "field") == w for w in result.warnings)
    assert result.summary()["output_units"]["system"] == "field"
    assert "output_units" not in result.summary("si")
    result.save(tmp_path / "field", plots=False)
    result.save(tmp_path / "si", plots=False, output_units="si")
    assert json.loads((tmp_path / "field" / "metrics.json").read_text())["output_units"]["system"] == "field"
    assert "output_units" not in json.loads((tmp_path / "si" / "metrics.json").read_text())
    si = ds.drill(config.with_units("si"))
    assert si.warnings == tuple(w for w in si.warnings if "ft-lbf" not in w)
