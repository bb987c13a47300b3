"""Tests of drillstring.model.parameters: defaults, presets, validation, dict and TOML I/O."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path
from typing import Any

import _docs
import numpy as np
import pytest

from drillstring.errors import ValidationError
from drillstring.io.toml import load_toml
from drillstring.model.parameters import PRESETS, Parameters, load, preset

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"


def test_defaults_are_table_1() -> None:
    p = Parameters()
    assert p.length == 100.0
    assert p.youngs_modulus == 0.7e11
    assert p.density == 2.7e3
    assert p.poisson_ratio == 0.34
    assert p.outer_diameter == 0.20
    assert p.inner_diameter == 0.12
    assert p.omega == pytest.approx(math.pi, rel=1e-15)
    assert p.initial_velocities == (0.1, 0.05, 0.02)
    assert p.k5_variant == "paper"
    assert p.model == "paper"


def test_defaults_are_the_aluminium_preset_and_the_readme_table() -> None:
    assert Parameters() == preset("aluminum") == preset("aluminium")
    docs = _docs.text()  # the table is on the page of the paper's model in Python
    table = re.split(r"\n##? ", docs.split("<!-- DEFAULTS -->")[1])[0]
    rows = dict(line.split("|")[1:3] for line in table.splitlines() if line.startswith("| `"))
    shown = {key.strip().strip("`"): value.strip() for key, value in rows.items()}
    p = Parameters()
    assert set(shown) == set(Parameters.field_names())  # every field has its row
    assert shown["length"] == f"{p.length:g}" and shown["youngs_modulus"] == f"{p.youngs_modulus:g}"
    assert shown["density"] == f"{p.density:g}" and shown["poisson_ratio"] == f"{p.poisson_ratio:g}"
    assert shown["outer_diameter"] == f"{p.outer_diameter:g}" and shown["inner_diameter"] == f"{p.inner_diameter:g}"
    assert shown["omega"].startswith(f"{p.omega:.6g}") and "2π · 0.5" in shown["omega"]
    assert shown["initial_velocities"] == str(p.initial_velocities)
    assert shown["k5_variant"] == f'"{p.k5_variant}"' and shown["model"] == f'"{p.model}"'


def test_field_names_are_exactly_the_specified_ones() -> None:
    assert [f.name for f in dataclasses.fields(Parameters)] == [
        "length",
        "youngs_modulus",
        "density",
        "poisson_ratio",
        "outer_diameter",
        "inner_diameter",
        "omega",
        "initial_velocities",
        "k5_variant",
        "model",
        "damping_rate",
    ]


def test_frozen() -> None:
    p = Parameters()
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.length = 3.0  # type: ignore[misc]


def test_presets() -> None:
    assert PRESETS == ("aluminum", "steel")
    al = preset("aluminum")
    assert al == Parameters(initial_velocities=(0.1, 0.05, 0.02))
    assert preset("aluminium") == al
    steel = preset("steel")
    assert (steel.youngs_modulus, steel.density, steel.poisson_ratio) == (2.1e11, 7.8e3, 0.28)
    for name in ("length", "outer_diameter", "inner_diameter", "omega", "initial_velocities"):
        assert getattr(steel, name) == getattr(al, name)
    assert steel.k5_variant == "paper"


def test_unknown_preset_lists_names() -> None:
    with pytest.raises(ValidationError) as info:
        preset("titanium")
    message = str(info.value)
    assert "preset" in message and "titanium" in message
    assert "aluminum" in message and "steel" in message


def test_coercion() -> None:
    p = Parameters(length=250, initial_velocities=[1, 0.5], omega=np.float64(-2.0))
    assert isinstance(p.length, float) and p.length == 250.0
    assert p.initial_velocities == (1.0, 0.5)
    assert all(type(v) is float for v in p.initial_velocities)
    assert p.omega == -2.0 and type(p.omega) is float
    assert Parameters(initial_velocities=()).initial_velocities == ()
    assert Parameters(inner_diameter=0).inner_diameter == 0.0  # solid shaft allowed
    assert Parameters(k5_variant="energy").k5_variant == "energy"


def test_replace() -> None:
    p = Parameters()
    q = p.replace(length=500.0, initial_velocities=[0.2])
    assert q.length == 500.0 and q.initial_velocities == (0.2,)
    assert p.length == 100.0
    assert q.replace(length=100.0, initial_velocities=(0.1, 0.05, 0.02)) == p
    with pytest.raises(ValidationError, match="length"):
        p.replace(length=-1.0)


def test_replace_unknown_field_lists_valid_ones() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters().replace(lenght=3.0)
    message = str(info.value)
    assert info.value.field == "lenght"
    assert "lenght" in message and "length" in message and "k5_variant" in message


def test_dict_round_trip() -> None:
    p = preset("steel").replace(k5_variant="energy", omega=-1.25)
    d = p.to_dict()
    assert d["initial_velocities"] == [0.1, 0.05, 0.02]
    assert d["youngs_modulus"] == 2.1e11
    assert Parameters.from_dict(d) == p
    assert Parameters.from_dict({"preset": "steel", "length": 250.0}) == preset("steel").replace(
        length=250.0
    )
    assert Parameters.from_dict({}) == Parameters()


def test_from_dict_unknown_key_names_source() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters.from_dict({"length": 1.0, "colour": "red"}, source="cfg.toml")
    assert info.value.field == "colour"
    assert "cfg.toml" in str(info.value) and "colour" in str(info.value)


def test_from_dict_bad_value_names_source() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters.from_dict({"density": -1.0}, source="cfg.toml")
    assert info.value.field == "density"
    assert str(info.value).startswith("cfg.toml: invalid density")


# ------------------------------------------------------------------------ bad values

BAD_VALUES: list[tuple[str, Any]] = []
for _name in ("length", "youngs_modulus", "density", "outer_diameter"):
    BAD_VALUES += [
        (_name, 0.0),
        (_name, -1.0),
        (_name, math.inf),
        (_name, math.nan),
        (_name, True),
        (_name, "1.0"),
        (_name, None),
    ]
BAD_VALUES += [
    ("inner_diameter", -0.01),
    ("inner_diameter", 0.20),  # == outer
    ("inner_diameter", 0.25),  # > outer
    ("inner_diameter", math.nan),
    ("inner_diameter", math.inf),
    ("inner_diameter", False),
    ("inner_diameter", "0.1"),
    ("poisson_ratio", 0.5),
    ("poisson_ratio", -1.0),
    ("poisson_ratio", 0.7),
    ("poisson_ratio", -1.5),
    ("poisson_ratio", math.nan),
    ("poisson_ratio", None),
    ("poisson_ratio", True),
    ("omega", math.inf),
    ("omega", -math.inf),
    ("omega", math.nan),
    ("omega", "fast"),
    ("omega", True),
    ("omega", None),
    ("initial_velocities", 0.1),
    ("initial_velocities", "0.1"),
    ("initial_velocities", None),
    ("initial_velocities", (0.1, math.nan)),
    ("initial_velocities", [math.inf]),
    ("initial_velocities", [True]),
    ("initial_velocities", ["0.1"]),
    ("initial_velocities", {"C1": 0.1}),
    ("k5_variant", "Paper"),
    ("k5_variant", "minus"),
    ("k5_variant", ""),
    ("k5_variant", None),
    ("k5_variant", 1),
    ("model", "Paper"),
    ("model", "classical"),
    ("model", ""),
    ("model", None),
    ("model", 0),
]


@pytest.mark.parametrize(("name", "value"), BAD_VALUES)
def test_bad_value_raises_naming_field(name: str, value: Any) -> None:
    with pytest.raises(ValidationError) as info:
        Parameters(**{name: value})
    assert isinstance(info.value, ValueError)
    assert name in str(info.value)
    assert info.value.field.startswith(name)
    with pytest.raises(ValidationError, match=name):
        Parameters().replace(**{name: value})


def test_inner_diameter_message_names_range() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters(inner_diameter=0.25)
    assert str(info.value) == (
        "invalid inner_diameter: got 0.25, expected 0 <= inner_diameter < outer_diameter = 0.2"
    )


def test_poisson_message_names_range() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters(poisson_ratio=0.5)
    assert "-1 < poisson_ratio < 0.5" in str(info.value)
    assert info.value.value == 0.5


def test_bad_velocity_names_its_index() -> None:
    with pytest.raises(ValidationError) as info:
        Parameters(initial_velocities=(0.1, 0.2, math.inf))
    assert info.value.field == "initial_velocities[2]"


# ------------------------------------------------------------------------ TOML


def test_reference_example_is_aluminum_preset() -> None:
    assert load(EXAMPLES / "reference.toml") == preset("aluminum")
    solver = load_toml(EXAMPLES / "reference.toml")["solver"]
    assert solver == {
        "modes": 3,
        "rigid_mode": False,
        "t_end": 1.0,
        "method": "dop853",
        "rtol": 1e-10,
        "atol": 1e-12,
        "samples": 2001,
    }


def test_steel_example_is_steel_preset() -> None:
    assert load(EXAMPLES / "steel.toml") == preset("steel")


@pytest.mark.parametrize(
    "params",
    [
        Parameters(),
        preset("steel"),
        Parameters(
            length=1.0 / 3.0,
            youngs_modulus=2.0e11 + 0.1,
            density=7.85e3,
            poisson_ratio=-0.999999,
            outer_diameter=0.1 + 0.2,
            inner_diameter=0.0,
            omega=-2 * math.pi * 6,
            initial_velocities=(1e-300, -5e-7, 1.0 / 7.0, 12345678901234567890.0),
            k5_variant="energy",
            model="consistent",
        ),
        Parameters(initial_velocities=()),
    ],
)
def test_toml_round_trip_is_exact(tmp_path: Path, params: Parameters) -> None:
    path = tmp_path / "p.toml"
    params.save(path)
    loaded = load(path)
    assert loaded == params
    for name in Parameters.field_names():
        assert repr(getattr(loaded, name)) == repr(getattr(params, name))
    assert path.read_text(encoding="utf-8") == params.to_toml()
    assert params.to_toml().splitlines()[1] == "[parameters]"


def test_load_ignores_other_tables(tmp_path: Path) -> None:
    path = tmp_path / "p.toml"
    path.write_text(
        '[solver]\nmodes = 2\n\n[parameters]\npreset = "steel"\nlength = 500\n', encoding="utf-8"
    )
    assert load(path) == preset("steel").replace(length=500.0)
    assert load_toml(path)["solver"] == {"modes": 2}


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_malformed_toml_names_file_and_line(tmp_path: Path) -> None:
    path = _write(tmp_path, "[parameters]\nlength = 100.0\ndensity = = 3\n")
    for reader in (load, load_toml):
        with pytest.raises(ValidationError) as info:
            reader(path)
        assert info.value.field == "toml"
        message = str(info.value)
        assert str(path) in message
        assert "line 3" in message


def test_toml_nesting_and_big_integers_within_the_parser_s_limits_still_load(tmp_path: Path) -> None:
    """load_toml refuses only what the parser cannot represent (nesting beyond its recursion,
    integers beyond 4300 digits, see test_bad_input): moderate nesting and long integers load."""
    big = 10**400
    path = _write(tmp_path, "[parameters]\nlength = 250\n[other]\na = " + "[" * 50 + "1" + "]" * 50
                  + f"\nb = {big}\n")
    document = load_toml(path)
    inner = document["other"]["a"]
    for _ in range(50):
        inner = inner[0]
    assert inner == 1 and document["other"]["b"] == big
    assert load(path).length == 250.0  # the other tables do not matter to load()
    # an integer too large for a float as a parameter is refused like 1e400, naming file and line
    path = _write(tmp_path, f"[parameters]\nlength = {big}\n")
    with pytest.raises(ValidationError) as info:
        load(path)
    assert (info.value.field, info.value.source, info.value.line) == ("length", str(path), 2)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ValidationError) as info:
        load(tmp_path / "nope.toml")
    assert info.value.field == "toml" and "nope.toml" in str(info.value)


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ('[parameters]\ncolour = "red"\n', "colour"),
        ('[parameters]\nlength = "100"\n', "length"),
        ("[parameters]\nlength = -100.0\n", "length"),
        ("[parameters]\npoisson_ratio = true\n", "poisson_ratio"),
        ("[parameters]\ninitial_velocities = 0.1\n", "initial_velocities"),
        ('[parameters]\ninitial_velocities = [0.1, "x"]\n', "initial_velocities"),
        ("[parameters]\nomega = nan\n", "omega"),
        ("[parameters]\nk5_variant = 2\n", "k5_variant"),
        ('[parameters]\nmodel = "exact"\n', "model"),
        ('[parameters]\npreset = "copper"\n', "preset"),
        ("[parameters]\ninner_diameter = 0.3\n", "inner_diameter"),
        ("[solver]\nmodes = 3\n", "parameters"),
        ("parameters = 3\n", "parameters"),
    ],
)
def test_bad_toml_values_name_file_and_key(tmp_path: Path, text: str, field: str) -> None:
    path = _write(tmp_path, text)
    with pytest.raises(ValidationError) as info:
        load(path)
    message = str(info.value)
    assert field in message
    assert str(path) in message
    assert info.value.source == str(path)


def test_model_field(tmp_path: Path) -> None:
    p = preset("steel").replace(model="consistent")
    assert p.model == "consistent" and p.youngs_modulus == 2.1e11
    assert p.to_dict()["model"] == "consistent"
    assert Parameters.from_dict(p.to_dict()) == p
    assert 'model = "consistent"' in p.to_toml().splitlines()
    path = _write(tmp_path, '[parameters]\npreset = "steel"\nmodel = "consistent"\n')
    assert load(path) == p
    with pytest.raises(ValidationError) as info:
        Parameters(model="exact")
    assert info.value.field == "model" and "'paper', 'consistent'" in str(info.value)
