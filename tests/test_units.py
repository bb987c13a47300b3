"""Field units at the edge (``drillstring.drilling.units``): quantities with units in a
configuration and in overrides, ``units = "field"``, clear errors, and the outputs converted on
request. Conversions are checked against the exact definitions of the units (1 ft = 0.3048 m,
1 in = 0.0254 m, 1 lbf = 4.4482216152605 N, 1 lb = 0.45359237 kg, 1 US gal = 3.785411784 L)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from _cli import one_line_error, run_cli

from drillstring.drilling import DrillConfig, drill, load_drill_config
from drillstring.drilling.config import config_schema
from drillstring.drilling.units import FIELD_UNITS, FIELD_UNITS_BY_KEY, convert, quantity, to_si
from drillstring.errors import ValidationError

pytest.importorskip("pint")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FT, INCH, LBF, LB, GAL = 0.3048, 0.0254, 4.4482216152605, 0.45359237, 3.785411784e-3
PIPE = {"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.1}


def _close(a: float, b: float, rel: float = 4e-16) -> bool:
    return abs(a - b) <= rel * abs(b)


@pytest.mark.parametrize(
    ("path", "text", "si"),
    [
        ("sections[1].outer_diameter", "5 in", 5 * INCH),
        ("sections[0].length", "9842.5 ft", 9842.5 * FT),
        ("sections[0].length", "1000 ft", 1000 * FT),
        ("bit.weight_on_bit", "18 klbf", 18e3 * LBF),
        ("bit.weight_on_bit", "80 kN", 80e3),
        ("well.mud_density", "10.8 ppg", 10.8 * LB / GAL),
        ("well.mud_density", "1.2 g/cm^3", 1200.0),
        ("well.plan[2].build", "3 deg/100ft", 3 * 30 / (100 * FT)),
        ("well.plan[2].build", "3 deg/100 ft", 3 * 30 / (100 * FT)),
        ("top_drive.torque_limit", "44000 ft-lbf", 44e3 * FT * LBF),
        ("top_drive.inertia", "68818 lb*ft^2", 68818 * LB * FT**2),
        ("sections[0].shear_modulus", "11.5e6 psi", 11.5e6 * LBF / INCH**2),
        ("top_drive.steps[1][0]", "2 min", 120.0),
        ("top_drive.steps[1][1]", "1 rps", 60.0),
        ("top_drive.rpm", "120", 120.0),
        ("friction.static", "25 %", 0.25),
        ("metrics.window[0]", "0.5 min", 30.0),
    ],
)
def test_a_quantity_is_converted_to_the_si_unit_of_its_key(path: str, text: str, si: float) -> None:
    assert _close(quantity(path, text), si)


def test_exact_conversions_are_exact() -> None:
    # decimal factors: the correctly rounded float of the exact product
    assert quantity("sections[0].outer_diameter", "5 in") == 0.127
    assert quantity("sections[0].length", "1000 ft") == 304.8
    assert quantity("sections[0].outer_diameter", 6.5, "field") == 0.1651


def test_plain_numbers_in_field_units_take_the_field_unit_of_their_key() -> None:
    config = to_si({
        "units": "field",
        "sections": [{"length": 1000, "outer_diameter": 5, "inner_diameter": "0.1 m", "density": 65.5}],
        "bit": {"weight_on_bit": 18, "diameter": 8.5},
        "top_drive": {"rpm": 60, "steps": [[10, 80]], "controller": {"kp": 1000, "type": "pi"}},
        "well": {"md": [0, 1000], "inclination_deg": [0, 30], "plan": None},
    })
    section = config["sections"][0]
    assert "units" not in config
    assert section["length"] == 304.8 and section["outer_diameter"] == 0.127 and section["inner_diameter"] == 0.1
    assert _close(section["density"], 65.5 * LB / GAL)
    assert _close(config["bit"]["weight_on_bit"], 18e3 * LBF) and _close(config["bit"]["diameter"], 8.5 * INCH)
    assert config["top_drive"]["rpm"] == 60 and config["top_drive"]["steps"] == [[10, 80]]  # rpm, s as in SI
    assert _close(config["top_drive"]["controller"]["kp"], 1000 * FT * LBF)
    assert config["well"]["md"] == [0, 304.8] and config["well"]["inclination_deg"] == [0, 30]


def test_si_numbers_pass_untouched() -> None:
    document = {"sections": [{"length": 2500.123456789, "outer_diameter": 0.1465, "inner_diameter": 0.12}],
                "bit": {"weight_on_bit": 1e5 / 3}}
    converted = to_si({**document, "units": "si"})
    assert converted == document
    assert converted["bit"]["weight_on_bit"] is document["bit"]["weight_on_bit"]


def test_every_field_unit_has_the_dimension_of_its_si_unit() -> None:
    import pint

    registry = pint.UnitRegistry()
    registry.define("ppg = pound / gallon")
    schema = config_schema()
    for si, field in FIELD_UNITS.items():
        assert registry.parse_expression(si).dimensionality == registry.parse_expression(field).dimensionality
    for key, field in FIELD_UNITS_BY_KEY.items():
        unit = schema[key]["unit"]
        assert registry.parse_expression(unit).dimensionality == registry.parse_expression(field).dimensionality


def test_the_field_example_gives_the_metrics_of_its_si_twin() -> None:
    si = load_drill_config(EXAMPLES / "on-bottom-3000m.toml")
    field = load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml")
    # the same configuration to the last bit: a plain number is converted as written (its
    # shortest decimal), and the example's 16-17 digit field numbers are the SI values rounded,
    # so some arrive one ulp off
    flat_si, flat_field = _numbers(si.to_dict()), _numbers(field.to_dict())
    assert flat_si.keys() == flat_field.keys()
    off = {k for k in flat_si if flat_si[k] != flat_field[k]}
    assert off == {"sections[0].inner_diameter", "sections[0].density", "sections[1].density", "well.md[1]",
                   "bit.radius", "sections[1].length", "sections[0].shear_modulus", "sections[1].shear_modulus"}
    assert all(_close(flat_field[k], flat_si[k], 3e-16) for k in off)
    a, b = drill(si).metrics.to_dict(), drill(field).metrics.to_dict()
    for name, value in a.items():
        other = b[name]
        if isinstance(value, float):
            assert isinstance(other, float) and abs(other - value) <= 1e-12 * abs(value), name
        else:
            assert other == value, name


def _numbers(value: object, path: str = "") -> dict[str, float]:
    if isinstance(value, dict):
        out: dict[str, float] = {}
        for k, v in value.items():
            out.update(_numbers(v, f"{path}.{k}" if path else k))
        return out
    if isinstance(value, list):
        out = {}
        for i, v in enumerate(value):
            out.update(_numbers(v, f"{path}[{i}]"))
        return out
    return {path: value} if isinstance(value, (int, float)) and not isinstance(value, bool) else {}


def test_overrides_take_quantities() -> None:
    cfg = DrillConfig.from_dict({"sections": [PIPE, PIPE]})
    changed = cfg.with_overrides(["sections[1].outer_diameter=6.5 in", 'bit.diameter="8.5 in"',
                                  "top_drive.steps=[[0, 40], [\"1 min\", 80]]"])
    assert changed.sections[1].outer_diameter == 0.1651
    assert _close(changed.bit.radius, 8.5 * INCH / 2)
    assert changed.top_drive.steps == ((0.0, 40.0), (60.0, 80.0))
    mapped = cfg.with_overrides({"well": {"mud_density": "10 ppg"}, "sections[0].length": "3280.84 ft"})
    assert _close(mapped.well.mud_density, 10 * LB / GAL) and _close(mapped.sections[0].length, 3280.84 * FT)


@pytest.mark.parametrize(
    ("path", "text", "words"),
    [
        ("sections[1].outer_diameter", "5 psi", "a quantity of length"),
        ("sections[1].outer_diameter", "5 furlongs of pipe", "a quantity pint reads"),
        ("bit.weight_on_bit", "18 klbf/m", "a quantity of force"),
        ("friction.static", "3 m", "dimensionless"),
        ("top_drive.rpm", "12 knots", "a quantity of angular speed"),
    ],
)
def test_a_bad_quantity_names_the_field_the_value_and_the_dimension(path: str, text: str, words: str) -> None:
    with pytest.raises(ValidationError) as info:
        quantity(path, text)
    assert info.value.field == path and info.value.value == text
    assert words in info.value.allowed


def test_a_string_that_is_no_quantity_is_left_to_the_core() -> None:
    assert quantity("top_drive.rpm", "fast") == "fast"
    with pytest.raises(ValidationError, match="top_drive.rpm: got .*fast.*, expected a number"):
        DrillConfig.from_dict({"sections": [PIPE], "top_drive": {"rpm": "fast"}})


def test_an_unknown_unit_system_is_refused() -> None:
    with pytest.raises(ValidationError, match="one of si .* field") as info:
        DrillConfig.from_dict({"units": "imperial", "sections": [PIPE]})
    assert info.value.field == "units"


def test_a_bad_unit_in_a_file_is_one_line_with_file_and_line(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "bad.toml"
    path.write_text('units = "field"\n\n[[sections]]\nlength = 1000\nouter_diameter = "5 psi"\ninner_diameter = 4\n')
    code, _, err = run_cli(capsys, "drill", str(path), "--out", str(tmp_path / "out"))
    assert code == 2
    one_line_error(err, "line 5", "sections[0].outer_diameter", "'5 psi'", "length")
    code, _, err = run_cli(capsys, "drill", str(EXAMPLES / "on-bottom-3000m.toml"), "--out", str(tmp_path / "o"),
                           "--set", "bit.weight_on_bit=18 klbf/s")
    assert code == 2
    one_line_error(err, "bit.weight_on_bit", "force")


def test_metrics_in_field_units_are_a_copy_beside_the_si_ones(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    config = str(EXAMPLES / "on-bottom-3000m-field.toml")
    # a field file's console and metrics copy are in field units without --units; --units si is SI
    code, out, _ = run_cli(capsys, "drill", config, "--out", str(tmp_path / "field"), "--no-plots")
    assert code == 0
    assert "10498.7 ft string" in out and "kft-lbf" in out and "kN m" not in out
    code, out_si, _ = run_cli(capsys, "drill", config, "--out", str(tmp_path / "si"), "--no-plots", "--units", "si")
    assert code == 0 and "3200 m string" in out_si and "kN m" in out_si
    field = json.loads((tmp_path / "field" / "metrics.json").read_text())
    si = json.loads((tmp_path / "si" / "metrics.json").read_text())
    copy = field.pop("output_units")
    assert field == si  # every SI entry unchanged
    assert copy["system"] == "field"
    # a key naming a unit holds that unit: the field values under field-named keys
    assert copy["units"]["motor_torque_max_ftlbf"] == "ft*lbf" and copy["units"]["bit_rpm_mean"] == "rpm"
    assert not any(k.endswith("_Nm") for k in (*copy["units"], *copy["metrics"]))
    ft_lbf = FT * LBF
    for name in ("motor_torque_min_Nm", "motor_torque_max_Nm", "breakoff_torque_Nm", "min_cycle_torque_Nm"):
        assert _close(copy["metrics"][name[:-2] + "ftlbf"], si[name] / ft_lbf, 1e-15), name
    for name in ("ssi", "period_s", "bit_rpm_mean", "window_start"):
        assert copy["metrics"][name] == si[name], name


def test_a_non_finite_field_number_is_left_to_the_core() -> None:
    assert math.isnan(quantity("sections[0].length", math.nan, "field"))
    with pytest.raises(ValidationError, match=r"sections\[0\]\.length"):
        DrillConfig.from_dict({"units": "field", "sections": [{**PIPE, "length": math.inf}]})


def test_convert_leaves_nan_and_same_units() -> None:
    assert convert(3.0, "rpm", "field") == (3.0, "rpm")
    value, unit = convert(math.nan, "N*m", "field")
    assert math.isnan(value) and unit == "N*m"
    assert convert(1.0, "N*m", "si") == (1.0, "N*m")


def test_the_reference_lists_the_units_key() -> None:
    entry = config_schema()["units"]
    assert entry["type"] == "string" and entry["default"] == "si" and entry["unit"] is None


def test_map_axes_take_quantities(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from drillstring.drilling.maps import check_axis

    assert check_axis("bit.weight_on_bit", ["80 kN", 40e3], "--axis") == [80e3, 40e3]
    assert check_axis("sections[0].outer_diameter", ["5 in", "6.5 in"], "--axis") == [0.127, 0.1651]
    with pytest.raises(ValidationError, match="a value of bit.weight_on_bit: a quantity of force") as info:
        check_axis("bit.weight_on_bit", ["80 kN", "3 m"], "--axis")
    assert info.value.field == "--axis"
