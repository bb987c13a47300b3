"""One schema of the drilling configuration, the core's: the Python dataclasses against the core's
fields and defaults, and dotted-path overrides set by the core for ``with_overrides``, ``--set``
and the axes of a stick-slip map alike."""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import pytest

from drillstring import _core
from drillstring.drilling import DrillConfig, drill, drill_map
from drillstring.drilling.config import (
    Bit,
    Controller,
    Friction,
    MetricsConfig,
    Numerics,
    StringSection,
    TopDrive,
    Well,
)
from drillstring.errors import ValidationError

REQUIRED = {"length", "outer_diameter", "inner_diameter"}  # a section's required fields


def _tables(defaults: dict[str, Any]) -> list[tuple[type, dict[str, Any]]]:
    top = {k: v for k, v in defaults.items()}
    return [
        (DrillConfig, top),
        (StringSection, defaults["sections"][0]),
        (Well, defaults["well"]),
        (Friction, defaults["friction"]),
        (TopDrive, defaults["top_drive"]),
        (Controller, defaults["top_drive"]["controller"]),
        (Bit, defaults["bit"]),
        (Numerics, defaults["numerics"]),
        (MetricsConfig, defaults["metrics"]),
    ]


def _frozen(value: Any) -> Any:
    return tuple(_frozen(v) for v in value) if isinstance(value, list) else value


def test_every_dataclass_field_and_default_is_the_cores() -> None:
    defaults = _core.drill_defaults()
    for cls, core in _tables(defaults):
        fields = {f.name: f for f in dataclasses.fields(cls)}
        assert set(fields) == set(core), cls.__name__
        for name, f in fields.items():
            if isinstance(core[name], dict) or name == "sections":
                continue  # a sub-table: checked as its own dataclass
            if cls is StringSection and name in REQUIRED:
                assert f.default is dataclasses.MISSING, name
                continue
            assert f.default == _frozen(core[name]), (cls.__name__, name)
    # the published setup (Aarsnes & Shor 2018, MAIN.m and parameters_WellB.m): an oracle of the values
    assert (Controller().type, Controller().kp, Controller().ki) == ("pi", 38e3, 100e3)
    assert (Friction().static, Friction().kinetic_ratio, Friction().stick_speed) == (0.3, 0.65, 1.5)
    assert Well().md == (0.0, 500.0, 1600.0, 4000.0) and Well().inclination_deg == (0.0, 0.0, 60.0, 60.0)
    assert (TopDrive().inertia, TopDrive().rpm, TopDrive().control_interval) == (2900.0, 40.0, 0.01)
    assert (Numerics().cells, Numerics().duration) == (1000, 60.0)


def test_the_dataclasses_take_units_from_the_schema_only() -> None:
    """A field's unit is the core's schema's, read by the unit conversions; the dataclasses
    declare none of their own (a second declaration could disagree with the core's)."""
    from drillstring.drilling import config as config_module
    from drillstring.drilling.units import _unit_of

    schema = _core.drill_config_schema()
    classes = [c for c in vars(config_module).values()
               if isinstance(c, type) and dataclasses.is_dataclass(c) and c.__module__ == config_module.__name__]
    assert len(classes) >= 10
    for cls in classes:
        for f in dataclasses.fields(cls):
            assert set(f.metadata) <= {"kind"}, (cls.__name__, f.name, dict(f.metadata))
    # every number of the schema has its unit there, and the conversions read that unit
    numbers = [key for key, entry in schema.items() if entry["type"] == "number"]
    assert len(numbers) > 50
    for key in numbers:
        assert isinstance(schema[key]["unit"], str) and _unit_of(key) == schema[key]["unit"], key


def _base() -> DrillConfig:
    return DrillConfig.from_dict({
        "sections": [{"length": 800.0, "outer_diameter": 0.127, "inner_diameter": 0.108},
                     {"length": 100.0, "outer_diameter": 0.17, "inner_diameter": 0.07, "density": 7800.0}],
        "numerics": {"cells": 40, "duration": 2.0, "field_interval": 0.0},
    })


@pytest.mark.parametrize(("key", "value", "check"), [
    ("top_drive.rpm", 70.0, lambda c: c.top_drive.rpm == 70.0),  # scalar
    ("sections[1].length", 150.0, lambda c: c.sections[1].length == 150.0 and c.sections[0].length == 800.0),
    ("top_drive.controller.type", "soft_torque", lambda c: c.top_drive.controller.type == "soft_torque"),
    ("well.inclination_deg", 25.0, lambda c: c.well.md is None and c.well.inclination_deg == 25.0),
])
def test_an_override_gives_the_same_run_from_python_and_from_a_map_axis(key: str, value: Any, check: Any) -> None:
    base = _base()
    changed = base.with_overrides({key: value})
    assert check(changed) and changed != base
    assert base.with_overrides([f"{key}={json.dumps(value)}"]) == changed  # the --set form
    row = drill_map(base, {key: [value]}, threads=1).iloc[0]
    single = drill(changed)
    assert row["status"] == single.status == "success", row["message"]
    assert row["steps"] == single.stats["steps"] and row["dt"] == single.stats["dt"]
    assert row["bit_rpm_min"] == single.metrics.to_dict()["bit_rpm_min"]


def test_a_table_override_is_merged_into_the_table() -> None:
    base = _base().with_overrides({"top_drive.controller.type": "soft_torque"})
    merged = base.with_overrides({"top_drive.controller": {"kp": 1.0}})
    assert merged.top_drive.controller.type == "soft_torque" and merged.top_drive.controller.kp == 1.0
    assert base.with_overrides(['top_drive.controller={kp = 1.0}']) == merged
    raw = _core.drill_config_override(base.to_json(), json.dumps([["top_drive.controller", {"kp": 1.0}]]))
    assert raw["top_drive"]["controller"] == {**dataclasses.asdict(merged.top_drive.controller), "kp": 1.0}


@pytest.mark.parametrize(("key", "value", "field", "allowed"), [
    ("top_drive.rpmm", 1.0, "top_drive.rpmm", "one of inertia, torque_limit, rpm, ramp_time"),  # unknown key
    ("sections[2].length", 1.0, "sections[2]", "an index 0..1 of sections"),  # index out of range
    ("sections.length", 1.0, "sections.length", "an index first: sections is a list of 2 (sections[0].length)"),
    ("top_drive.rpm.x", 1.0, "top_drive.rpm.x", "a key of a table: top_drive.rpm is 40.0, not a table"),
])
def test_a_bad_path_gives_the_same_message_from_python_and_from_a_map_axis(
        key: str, value: Any, field: str, allowed: str) -> None:
    with pytest.raises(ValidationError) as python:
        _base().with_overrides({key: value})
    with pytest.raises(ValidationError) as axis:
        drill_map(_base(), {key: [value]}, threads=1)
    assert python.value.field == axis.value.field == field
    assert python.value.allowed == axis.value.allowed and python.value.allowed.startswith(allowed)


@pytest.mark.parametrize(("key", "value", "allowed"), [
    ("top_drive.rpm", "fast", "a number"),
    ("bit.on_bottom", 1, "true or false"),
    ("numerics.cells", 2.5, "an integer >= 0"),
    ("top_drive.controller.type", "fuzzy", "one of speed, pi, soft_torque, z_torque"),
    ("well.inclination_deg", "steep", "a number or an array of numbers (degrees)"),
    ("metrics.window", [1.0, 2.0, 3.0], "an array of 2 numbers"),
])
def test_a_bad_type_gives_the_same_message_from_python_and_from_a_map_axis(key: str, value: Any,
                                                                           allowed: str) -> None:
    with pytest.raises(ValidationError) as python:
        _base().with_overrides({key: value})
    assert python.value.field == key and python.value.allowed == allowed, str(python.value)
    with pytest.raises(ValidationError) as axis:
        drill_map(_base(), {key: [value]}, threads=1)
    assert axis.value.field == f"axes[{key!r}]" and axis.value.allowed == f"a value of {key}: {allowed}"


@pytest.mark.parametrize(("key", "value"), [
    ("numerics.cells", 0), ("top_drive.inertia", -1.0), ("sections[0].inner_diameter", 0.5),
    ("friction.kinetic_ratio", 1.5),
])
def test_a_value_out_of_range_gives_the_same_message_from_python_and_from_a_map_row(key: str, value: Any) -> None:
    with pytest.raises(ValidationError) as python:
        _base().with_overrides({key: value})
    assert python.value.field == key
    row = drill_map(_base(), {key: [value]}, threads=1).iloc[0]
    assert row["status"] == "invalid"
    assert row["message"] == f"invalid {key}: got {python.value.value}, expected {python.value.allowed}"


def test_a_malformed_path_names_the_caller_field() -> None:
    with pytest.raises(ValidationError) as err:
        _base().with_overrides({"top_drive..rpm": 1.0})
    assert err.value.field == "--set" and "dotted key" in err.value.allowed
    with pytest.raises(ValidationError) as err:
        _core.drill_config_override(_base().to_json(), '[["a[x]", 1]]', "axis")
    assert err.value.field == "axis"


def test_the_constant_inclination_rule_is_the_cores() -> None:
    # one number without depths: no survey, from JSON, from an override and from the dataclass
    cfg = _base()
    assert cfg.well.md == (0.0, 500.0, 1600.0, 4000.0)
    for flat in (DrillConfig.from_dict({**cfg.to_dict(), "well": {"inclination_deg": 10.0}}),
                 cfg.with_overrides({"well.inclination_deg": 10.0}),
                 DrillConfig(sections=cfg.sections, well=Well(md=None, inclination_deg=10.0))):
        assert flat.well.md is None and flat.well.inclination_deg == 10.0
    # with depths given too, one number is refused
    with pytest.raises(ValidationError) as err:
        cfg.with_overrides({"well.inclination_deg": 10.0, "well.md": [0.0, 100.0]})
    assert err.value.field == "well.inclination_deg"
    # null depths with a table: refused, naming well.md
    with pytest.raises(ValidationError) as err:
        cfg.with_overrides(["well.md=null"])
    assert err.value.field == "well.md"


def test_non_finite_and_foreign_values_name_the_field() -> None:
    for value, allowed in ((math.nan, "a finite number"), (-math.inf, "a finite number"), (object(), "a number")):
        with pytest.raises(ValidationError) as err:
            _base().with_overrides({"top_drive.rpm": value})
        assert err.value.field == "top_drive.rpm" and err.value.allowed == allowed
