"""The configuration reference of the documentation (docs/_ext/config_reference.py): one table per
configuration table, a row per key with its unit, default and meaning, from the core's schema
(dotted key -> {type, unit, label, default, description})."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def reference():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("config_reference", ROOT / "docs" / "_ext" / "config_reference.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("config_reference", module)
    spec.loader.exec_module(module)
    return module


def _entry(unit: str, default: object, description: str, kind: str = "number") -> dict[str, object]:
    return {"type": kind, "unit": unit if kind in ("number", "integer") else None,
            "label": description.split(",")[0], "default": default,
            "description": description}


def test_a_table_per_configuration_table_and_a_row_per_key(reference) -> None:  # type: ignore[no-untyped-def]
    schema = {
        "sections[].length": _entry("m", None, "length of the section, from the top"),
        "sections[].outer_diameter": _entry("m", None, "outer diameter"),
        "damping_rate": _entry("1/s", 0.0, "viscous damping rate"),
        "top_drive.rpm": _entry("rpm", 40.0, "setpoint"),
        "top_drive.controller": _entry("", None, "The top drive's controller.", "table"),
        "top_drive.controller.type": _entry("", "pi", "controller: one of speed, pi, soft_torque, z_torque", "string"),
        "top_drive.controller.kp": _entry("N m s/rad", 38e3, "proportional gain"),
    }
    page = reference.markdown(schema, True)
    titles = [line for line in page.splitlines() if line.startswith("## ")]
    assert titles == ["## top level", "## `[[sections]]`", "## `[top_drive]`", "## `[top_drive.controller]`"]
    rows = [line for line in page.splitlines() if line.startswith("| `")]
    assert rows == [
        "| `damping_rate` | 1/s | `0.0` | viscous damping rate |",
        "| `length` | m | – | length of the section, from the top |",
        "| `outer_diameter` | m | – | outer diameter |",
        "| `rpm` | rpm | `40.0` | setpoint |",
        '| `type` |  | `"pi"` | controller: one of speed, pi, soft_torque, z_torque |',
        "| `kp` | N m s/rad | `38000.0` | proportional gain |",
    ]
    assert "The top drive's controller." in page  # a table's entry introduces its table
    assert "note" not in page  # the core's schema: no caveat


def test_indexed_keys_share_their_table(reference) -> None:  # type: ignore[no-untyped-def]
    schema = {"sections[0].length": _entry("m", 1.0, "a"), "sections[*].density": _entry("kg/m^3", 2.0, "b")}
    page = reference.markdown(schema, True)
    assert page.count("## `[[sections]]`") == 1 and "| `length` |" in page and "| `density` |" in page


def test_the_page_of_this_core_lists_every_key(reference) -> None:  # type: ignore[no-untyped-def]
    schema, complete = reference.schema()
    page = reference.markdown(schema, complete)
    assert {"sections[].length", "top_drive.controller.kp", "bit.weight_on_bit", "numerics.cells"} <= {
        reference._normal(key) for key in schema}
    for key, entry in schema.items():
        if entry["type"] != "table":
            assert f"| `{key.rpartition('.')[2]}` |" in page, key
