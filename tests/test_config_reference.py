"""The configuration reference of the core (``config_schema()``): one entry per key the
configuration accepts, each with exactly type, unit, label, default and description, the unit
one that pint parses with the dimension of the quantity."""

from __future__ import annotations

from typing import Any

import pytest

from drillstring.drilling import DrillConfig
from drillstring.drilling.config import config_schema, defaults
from drillstring.errors import ValidationError

ENTRY = {"type", "unit", "label", "default", "description"}
TYPES = {"number", "integer", "string", "boolean", "array", "table"}


def _keys(value: Any, path: str = "") -> set[str]:
    """The dotted keys of a configuration's JSON (``[]`` for the items of a list of tables,
    ``[][i]`` for the entries of a list of pairs)."""
    out: set[str] = set()
    if isinstance(value, dict):
        for k, v in value.items():
            full = f"{path}.{k}" if path else k
            out |= {full} | _keys(v, full)
    elif isinstance(value, list) and value:
        if isinstance(value[0], dict):
            out |= _keys(value[0], f"{path}[]")
        elif isinstance(value[0], list):
            out |= {f"{path}[][{i}]" for i in range(len(value[0]))}
    return out


def test_every_key_of_the_configuration_has_one_entry_and_no_other() -> None:
    config = defaults()
    # the lists that are empty by default, with one item of every key
    config["well"]["plan"] = [{k: 1.0 for k in ("hold", "build", "drop", "turn", "inclination", "azimuth")}]
    config["friction"]["intervals"] = [{"top_md": 0.0, "bottom_md": 1.0, "static": 0.2}]
    config["well"]["hole_sections"] = [{"bottom_md": 1.0, "diameter": 0.2, "friction": 0.2}]
    config["top_drive"]["steps"] = [[10.0, 60.0]]
    config["top_drive"]["speed_series"] = [[0.0, 0.0]]
    config["hoist"] = {k: 0.0 for k in ("mode", "speed", "hook_load", "weight_on_bit", "ramp_time")}  # null by default
    config["hoist"].update(steps=[[10.0, 0.01]], autodriller={k: 0.0 for k in (
        "target", "setpoint", "kp", "ki", "min_speed", "max_speed")})
    config["changes"] = [{"time": 1.0, "key": "top_drive.rpm", "value": 60.0}]
    schema = config_schema()
    assert set(schema) == _keys(config) | {"units"}  # units: read by the Python edge
    assert list(schema) == sorted(schema)


def test_each_entry_has_the_documented_fields() -> None:
    for key, entry in config_schema().items():
        assert set(entry) == ENTRY, key
        assert entry["type"] in TYPES, key
        assert entry["label"] and entry["description"].endswith("."), key
        if entry["type"] in ("number", "integer"):
            assert isinstance(entry["unit"], str), f"{key} has no unit"
        elif entry["type"] in ("string", "boolean", "table"):
            assert entry["unit"] is None, key


@pytest.mark.parametrize(
    ("key", "dimension"),
    [
        ("sections[].outer_diameter", "[length]"),
        ("sections[].shear_modulus", "[mass] / [length] / [time] ** 2"),
        ("well.mud_density", "[mass] / [length] ** 3"),
        ("bit.weight_on_bit", "[length] * [mass] / [time] ** 2"),
        ("top_drive.torque_limit", "[length] ** 2 * [mass] / [time] ** 2"),
        ("top_drive.inertia", "[length] ** 2 * [mass]"),
        ("top_drive.rpm", "1 / [time]"),
        ("well.plan[].build", "1 / [length]"),
        ("damping_rate", "1 / [time]"),
        ("friction.static", "dimensionless"),
    ],
)
def test_units_have_the_dimension_of_the_quantity(key: str, dimension: str) -> None:
    pint = pytest.importorskip("pint")
    registry = pint.UnitRegistry()
    unit = config_schema()[key]["unit"]
    expected = registry.get_dimensionality(dimension) if dimension != "dimensionless" else {}
    assert registry.parse_expression(unit or "1").dimensionality == expected


def test_defaults_are_the_configurations_and_required_keys_have_none() -> None:
    schema = config_schema()
    core = defaults()
    assert schema["top_drive.rpm"]["default"] == core["top_drive"]["rpm"]
    assert schema["bit.radius"]["default"] == core["bit"]["radius"]
    assert schema["well.md"]["default"] == core["well"]["md"]
    for key in ("sections", "sections[].length", "sections[].outer_diameter", "sections[].inner_diameter"):
        assert schema[key]["default"] is None


PIPE = {"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.1}


def test_the_bit_by_its_diameter_is_half_of_it_as_radius() -> None:
    cfg = DrillConfig.from_dict({"sections": [PIPE], "bit": {"diameter": 0.2159}})
    assert cfg.bit.radius == 0.2159 / 2 and cfg.bit.diameter is None
    assert cfg.with_overrides(["bit.diameter=0.3"]).bit.radius == 0.15
    assert cfg.with_overrides({"bit": {"diameter": 0.25}}).bit.radius == 0.125
    assert cfg.with_overrides(["bit.radius=0.2"]).bit.radius == 0.2


def test_a_bit_by_radius_and_diameter_is_refused_naming_both() -> None:
    with pytest.raises(ValidationError, match=r"bit\.diameter.*both bit\.radius and bit\.diameter") as info:
        DrillConfig.from_dict({"sections": [PIPE], "bit": {"radius": 0.1, "diameter": 0.2}})
    assert info.value.field == "bit.diameter"
    cfg = DrillConfig.from_dict({"sections": [PIPE]})
    with pytest.raises(ValidationError, match="both bit.radius and bit.diameter"):
        cfg.with_overrides(["bit.radius=0.1", "bit.diameter=0.2"])
    with pytest.raises(ValidationError, match=r"bit\.diameter"):
        DrillConfig.from_dict({"sections": [PIPE], "bit": {"diameter": -0.2}})
