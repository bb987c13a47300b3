"""The drilling-system configuration (``drillstring.drilling``): defaults from the core, round trips
TOML <-> dataclass <-> JSON, ``--set`` overrides, and every bad input named by its dotted field."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path
from typing import Any

import pytest

import drillstring as ds
from drillstring import _core
from drillstring.drilling import (
    Bit,
    Controller,
    DrillConfig,
    Numerics,
    StringSection,
    TopDrive,
    Well,
    friction_profile,
    load_drill_config,
)
from drillstring.errors import ValidationError

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
DRILL_EXAMPLES = ("aarsnes-shor-well-b.toml", "aarsnes-shor-well-b-corrected.toml", "on-bottom-3000m.toml")

PIPE = {"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}


def rich() -> DrillConfig:
    """A configuration that sets something in every table."""
    return DrillConfig(
        sections=(StringSection(name="pipe", **PIPE),
                  StringSection(150.0, 0.1651, 0.0714, name="collars", density=7800.0, contact_diameter=0.17)),
        well=Well(md=(0.0, 300.0, 1200.0), inclination_deg=(0.0, 0.0, 45.0), mud_density=1200.0),
        damping_rate=0.05,
        top_drive=TopDrive(rpm=80.0, steps=((5.0, 100.0), (8.0, 60.0)), torque_limit=4.0e4,
                           controller=Controller(type="soft_torque", tuning_frequency=0.3)),
        bit=Bit(on_bottom=True, weight_on_bit=5.0e4, radius=0.108),
        numerics=Numerics(cells=120, duration=3.0, field_interval=0.25),
    )


def test_defaults_are_the_cores() -> None:
    core = _core.drill_defaults()
    cfg = DrillConfig(sections=[StringSection(**PIPE)])
    for table, values in core.items():
        if table == "sections":
            for key, value in values[0].items():
                if key not in PIPE:
                    assert getattr(cfg.sections[0], key) == value, key
        elif isinstance(values, dict):
            for key, value in values.items():
                ours = getattr(getattr(cfg, table), key)
                if isinstance(value, dict):
                    assert dataclasses.asdict(ours) == value, key
                else:
                    assert json.loads(json.dumps(ours)) == value, (table, key)
        else:
            assert json.loads(json.dumps(getattr(cfg, table))) == values, table
    # and the dataclass defaults are those values too
    assert TopDrive().rpm == core["top_drive"]["rpm"] and Numerics().cells == core["numerics"]["cells"]
    assert ds.drilling.defaults() == core


def test_the_config_holds_what_the_core_normalises() -> None:
    cfg = rich()
    assert cfg.to_dict() == _core.drill_validate(cfg.to_json())
    assert cfg.length == 1150.0 and cfg.sections[1].shear_modulus == StringSection(**PIPE).shear_modulus


def test_toml_json_and_dict_round_trips(tmp_path: Path) -> None:
    cfg = rich()
    path = cfg.save(tmp_path / "cfg.toml")
    again = load_drill_config(path)
    assert again == cfg
    assert again.to_toml() == cfg.to_toml()
    assert DrillConfig.from_dict(json.loads(cfg.to_json())) == cfg
    assert DrillConfig.from_dict(cfg.to_dict()) == cfg
    # floats survive bit for bit
    odd = cfg.with_overrides({"sections[0].outer_diameter": 0.1 + 0.2, "top_drive.rpm": 1 / 3})
    assert load_drill_config(odd.save(tmp_path / "odd.toml")) == odd
    assert odd.top_drive.rpm == 1 / 3


def test_mappings_and_integers_are_accepted_and_converted() -> None:
    cfg = DrillConfig(sections=[{"length": 1000, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
                      top_drive={"rpm": 60, "controller": {"type": "pi", "kp": 10}})
    assert isinstance(cfg.sections, tuple) and isinstance(cfg.sections[0], StringSection)
    assert cfg.sections[0].length == 1000.0 and isinstance(cfg.sections[0].length, float)
    assert cfg.top_drive.rpm == 60.0 and cfg.top_drive.controller.kp == 10.0
    assert cfg.top_drive.controller.ki == Controller().ki
    with pytest.raises(dataclasses.FrozenInstanceError):
        cfg.damping_rate = 1.0  # type: ignore[misc]


def test_overrides() -> None:
    cfg = rich()
    new = cfg.with_overrides(["top_drive.rpm=60", "sections[0].length=3000", "bit.on_bottom=false",
                              "top_drive.controller.type=z_torque", 'sections[1].name="BHA"',
                              "well.md=[0, 4000]", "well.inclination_deg = [0, 30]", "numerics.cells=200",
                              "top_drive.steps=[]", "metrics.window=[1.0, 3.0]"])
    assert new.top_drive.rpm == 60.0 and new.sections[0].length == 3000.0 and new.bit.on_bottom is False
    assert new.top_drive.controller.type == "z_torque" and new.sections[1].name == "BHA"
    assert new.well.md == (0.0, 4000.0) and new.well.inclination_deg == (0.0, 30.0)
    assert new.numerics.cells == 200 and new.top_drive.steps == () and new.metrics.window == (1.0, 3.0)
    assert cfg == rich()  # the original is unchanged
    assert cfg.with_overrides({"top_drive.controller": {"kp": 1.0}}).top_drive.controller.type == "soft_torque"
    assert cfg.with_overrides([]) == cfg
    # null unsets an optional field; one inclination number replaces the survey
    assert cfg.top_drive.torque_limit == 4.0e4
    # a number (default 60 kN m, every controller); a very large value for no limit
    assert cfg.with_overrides(["top_drive.torque_limit=1e12"]).top_drive.torque_limit == 1e12
    with pytest.raises(ValidationError, match="top_drive.torque_limit"):
        cfg.with_overrides(["top_drive.torque_limit=null"])
    flat = cfg.with_overrides(["well.inclination_deg=20"])
    assert flat.well.md is None and flat.well.inclination_deg == 20.0
    assert fails(lambda: cfg.with_overrides(["top_drive.rpm=null"])).field == "top_drive.rpm"


def test_a_constant_inclination_in_toml(tmp_path: Path) -> None:
    cfg = load_drill_config(write(tmp_path, GOOD + "\n[well]\ninclination_deg = 30.0\n"))
    assert cfg.well.md is None and cfg.well.inclination_deg == 30.0
    assert load_drill_config(cfg.save(tmp_path / "again.toml")) == cfg
    survey = "\n[well]\nmd = [0.0, 100.0]\ninclination_deg = 30.0\n"
    error = fails(lambda: load_drill_config(write(tmp_path, GOOD + survey)))
    assert error.field == "well.inclination_deg" and error.line == 26


def fails(call: Any) -> ValidationError:
    with pytest.raises(ValidationError) as err:
        call()
    assert "expected" in str(err.value) and "\n" not in str(err.value)
    return err.value


@pytest.mark.parametrize(
    ("assignment", "field", "needle"),
    [
        ("top_drive.rpmm=1", "top_drive.rpmm", "rpm, ramp_time"),
        ("sections[2].length=1", "sections[2]", "0..1"),
        ("nosuch=1", "nosuch", "sections, well"),
        ("nosuch.deeper=1", "nosuch", "top_drive"),
        ("sections.length=1", "sections.length", "sections[0].length"),
        ("top_drive.rpm.x=1", "top_drive.rpm.x", "not a table"),
        ("top_drive.rpm=fast", "top_drive.rpm", "a number"),
        ("top_drive.rpm", "--set", "key=value"),
        ("top_drive.rpm=", "--set", "empty"),
        ("top_drive.rpm=[1,", "--set", "TOML value"),
        ("=3", "--set", "dotted key"),
        ("bit.on_bottom=1", "bit.on_bottom", "true or false"),
        ("numerics.cells=10.5", "numerics.cells", "integer"),
        ("numerics.cells=0", "numerics.cells", "1..="),
        ("top_drive.inertia=-1", "top_drive.inertia", "> 0"),
        ("sections[0].inner_diameter=0.5", "sections[0].inner_diameter", "outer_diameter"),
        ("well.md=[0, 1000, 500]", "well.md", ""),
        ("top_drive.controller.type=fuzzy", "top_drive.controller.type", "soft_torque"),
        ("friction.model=smooth", "friction.model", "regularised"),
        ("top_drive.steps=[[1, 2, 3]]", "top_drive.steps[0]", ""),
        ("sections[1].polar_moment=-1e-4", "sections[1].polar_moment", "> 0"),
        ("numerics.duration=1e400", "numerics.duration", ""),
        ("nonlinearity=cubic", "nonlinearity", "linear, consistent"),
        ("sections[0].poisson_ratio=0.5", "sections[0].poisson_ratio", "-1 < poisson_ratio < 0.5"),
        ("numerics.max_shear_strain=0", "numerics.max_shear_strain", "(0, 1]"),
    ],
)
def test_bad_overrides_name_the_field(assignment: str, field: str, needle: str) -> None:
    error = fails(lambda: rich().with_overrides([assignment]))
    assert error.field == field or error.field.startswith(field), (error.field, str(error))
    assert needle in str(error), str(error)


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "cfg.toml"
    path.write_text(text, encoding="utf-8")
    return path


GOOD = """\
damping_rate = 0.0

[[sections]]
name = "pipe"
length = 1000.0
outer_diameter = 0.127
inner_diameter = 0.1086

[[sections]]
name = "collars"
length = 100.0
outer_diameter = 0.17
inner_diameter = 0.07

[top_drive]
rpm = 40.0

[top_drive.controller]
type = "pi"

[numerics]
cells = 100
"""


@pytest.mark.parametrize(
    ("old", "new", "field", "line", "needle"),
    [
        ("rpm = 40.0", "rmp = 40.0", "top_drive.rmp", 16, "rpm"),  # unknown key: the allowed ones listed
        ('type = "pi"', 'type = "pi"\ngain = 3', "top_drive.controller.gain", 20, "kp"),
        ("length = 100.0", "length = 100.0\nlenght = 1.0", "sections[1].lenght", 12, "outer_diameter"),
        ("damping_rate = 0.0", "damping_rate = 0.0\n[weather]\nwind = 3", "weather", 2, "numerics"),
        ("cells = 100", 'cells = "many"', "numerics.cells", 22, "integer"),  # wrong type
        ("length = 100.0", "length = -100.0", "sections[1].length", 11, "> 0"),  # the core's range
        ("inner_diameter = 0.07", "inner_diameter = 0.2", "sections[1].inner_diameter", 13, "outer_diameter"),
        ("length = 100.0\n", "", "sections[1].length", 9, "required"),  # required, at the table's line
        ("rpm = 40.0", "rpm = true", "top_drive.rpm", 16, "a number"),
    ],
)
def test_bad_toml_names_the_file_the_line_and_the_field(
    tmp_path: Path, old: str, new: str, field: str, line: int, needle: str
) -> None:
    assert old in GOOD
    path = write(tmp_path, GOOD.replace(old, new, 1))
    error = fails(lambda: load_drill_config(path))
    assert error.field == field and error.source == str(path) and error.line == line, (str(error), error.line)
    assert needle in str(error) and str(error).startswith(f"{path}, line {line}: invalid {field}")


def test_a_file_without_sections_or_not_toml(tmp_path: Path) -> None:
    assert load_drill_config(write(tmp_path, GOOD)).numerics.cells == 100
    assert fails(lambda: load_drill_config(write(tmp_path, "[top_drive]\nrpm = 40.0\n"))).field == "sections"
    assert fails(lambda: load_drill_config(write(tmp_path, "sections = 3\n"))).field == "sections"
    error = fails(lambda: load_drill_config(write(tmp_path, "[[sections]\nlength = 1\n")))
    assert error.field == "toml" and error.line == 1
    assert fails(lambda: load_drill_config(tmp_path / "missing.toml")).field == "toml"


def test_python_values_of_the_wrong_type() -> None:
    assert fails(lambda: DrillConfig(sections=[StringSection(length="long", outer_diameter=0.1,  # type: ignore[arg-type]
                                                       inner_diameter=0.05)])).field == "sections[0].length"
    assert fails(lambda: DrillConfig(sections=[StringSection(**PIPE)], damping_rate=math.nan)).field == "damping_rate"
    assert fails(lambda: DrillConfig(sections=[StringSection(**PIPE)], numerics=3)).field == "numerics"  # type: ignore[arg-type]
    assert fails(lambda: DrillConfig(sections=[])).field == "sections"
    assert fails(lambda: DrillConfig(sections=StringSection(**PIPE))).field == "sections"  # type: ignore[arg-type]
    assert fails(lambda: DrillConfig(sections=[StringSection(**PIPE)], well=Well(md=(0.0,), inclination_deg="steep"))
                 ).field == "well.inclination_deg"  # type: ignore[arg-type]
    assert fails(lambda: DrillConfig.from_dict([1, 2])).field == "config"  # type: ignore[arg-type]


@pytest.mark.parametrize("name", DRILL_EXAMPLES)
def test_examples_load_validate_and_round_trip(name: str, tmp_path: Path) -> None:
    cfg = load_drill_config(EXAMPLES / name)
    assert load_drill_config(cfg.save(tmp_path / name)) == cfg
    profile = friction_profile(cfg)
    assert profile.breakoff_torque > 0 and profile.z.size == profile.limit_per_m.size == profile.cumulative.size
    assert ds.drill is ds.drilling.drill


def test_well_b_example_is_the_published_setup() -> None:
    """The numbers of parameters_WellB.m and MAIN.m (MD 2500 m, mu 0.3, fRat 0.65, oThres 1.5, 40 rpm)."""
    lengths = [48.700, 114.800, 56.700, 38.880]
    od = [0.150473, 0.187322, 0.209550, 0.247280]
    inner = [0.096207, 0.098912, 0.071438, 0.123391]
    total = sum(lengths)
    area = sum(L * math.pi * ((o / 2) ** 2 - (i / 2) ** 2) for L, o, i in zip(lengths, od, inner)) / total
    polar = sum(L * math.pi * (o**4 - i**4) / 32 for L, o, i in zip(lengths, od, inner)) / total
    radius = sum(L * o / 2 for L, o in zip(lengths, od)) / total
    # as their code: Jc with the extra pi, Gc, and the density that gives their collar the pipe's
    # wave speed c_t (so that its friction, from the weight, is theirs times Gc / Gp); their
    # survey depths mapped onto the cell centres and their setpoint ramp; corrected: the averaged
    # J, Gc and the steel's density
    published, corrected = (load_drill_config(EXAMPLES / name)
                            for name in ("aarsnes-shor-well-b.toml", "aarsnes-shor-well-b-corrected.toml"))
    cases = ((published, math.pi * polar, 67e9, 7850.0 * 67 / 61), (corrected, polar, 67e9, 7850.0))
    for cfg, collar_j, collar_g, collar_rho in cases:
        pipe, collars = cfg.sections
        assert (pipe.length, collars.length) == (2270.0, 230.0)
        assert (pipe.outer_diameter, pipe.inner_diameter) == (0.146529, 0.123024)
        assert collars.polar_moment == pytest.approx(collar_j, rel=1e-12)
        assert collars.area == pytest.approx(area, rel=1e-12)
        contact = collars.contact_diameter if collars.contact_diameter is not None else collars.outer_diameter
        assert contact == pytest.approx(2 * radius, rel=1e-12)
        assert pipe.density == 7850.0 and collars.density == pytest.approx(collar_rho, rel=1e-15)
        assert (pipe.shear_modulus, collars.shear_modulus) == (61e9, collar_g)
        assert cfg.damping_rate == pytest.approx(2 * 50 * 0.01 / 12, rel=1e-15)  # 2 kt dt
        assert cfg.well.inclination_deg == (0.0, 0.0, 60.0, 60.0)
        assert (cfg.friction.static, cfg.friction.kinetic_ratio, cfg.friction.stick_speed) == (0.3, 0.65, 1.5)
        td = cfg.top_drive
        assert (td.inertia, td.rpm, td.control_interval) == (2900.0, 40.0, 0.01)
        assert (td.controller.type, td.controller.kp, td.controller.ki) == ("pi", 38e3, 100e3)
        assert (cfg.numerics.cells, cfg.numerics.duration) == (1000, 60.0)
        assert cfg.bit.on_bottom is False
