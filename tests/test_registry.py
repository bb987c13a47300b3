"""The registry of a run's outputs (``drillstring_core::outputs``, ``_core.drill_outputs()``):
every metric and series channel declared once, read by ``metrics.json``, a map's columns, the
units, the grid check's tolerances and the documentation's table; each metric's name in few
source files."""

from __future__ import annotations

import importlib.util
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from drillstring import _core
from drillstring.drilling import map_table, result
from drillstring.drilling.metrics import OUTPUTS, stick_slip_metrics

ROOT = Path(__file__).resolve().parents[1]


def _metric_reference() -> Any:
    spec = importlib.util.spec_from_file_location("metric_reference", ROOT / "docs" / "_ext" / "metric_reference.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_python_lists_are_the_registrys() -> None:
    entries = list(_core.drill_outputs())
    names = [e["name"] for e in entries]
    assert len(set(names)) == len(names) and list(OUTPUTS) == names
    columns = [e["name"] for e in entries if e["map_column"] and "torsional" in e["runs"]]
    assert list(result.METRICS) == columns == list(map_table.METRIC_COLUMNS)
    assert list(result.COUPLED_METRICS) == [e["name"] for e in entries if e["map_column"] and "coupled" in e["runs"]]
    assert {k: v for k, v in result.METRIC_UNITS.items()} == {
        e["name"]: e["unit"] for e in entries if e["name"] in columns and e["kind"] == "number"}
    assert result.SERIES == ("surface_rpm", "bit_rpm", "motor_torque", "bit_torque")
    assert result.UNITS["motor_torque"] == "N m" and result.UNITS["rop"] == "m/h"
    # the tolerances of the grid check are the registry's, in its order
    tolerances = [(e["name"], *e["tolerance"]) for e in entries if e["tolerance"] is not None]
    assert [tuple(t) for t in _core.drill_compare_tolerances()] == tolerances


def test_a_metric_named_by_a_unit_ends_in_it() -> None:
    suffix = {"s": "_s", "N": "_N", "N*m": "_Nm", "Pa": "_Pa", "Hz": "_Hz", "m/h": "_m_per_h"}
    for o in OUTPUTS.values():
        if o.kind != "number":
            continue
        if o.unit == "rpm":
            assert "rpm" in o.name, o.name
        elif o.unit in suffix and not o.name.startswith("window_"):
            assert o.name.endswith(suffix[o.unit]), o.name
        else:
            assert o.unit in ("", "s"), o.name


def test_the_metrics_of_a_series_are_every_stick_slip_entry() -> None:
    t = np.linspace(0.0, 8.0, 8001)
    omega = np.maximum(0.0, 5.0 * (1.0 + 1.5 * np.sin(2 * np.pi * 0.5 * t)))
    raw = _core.stick_slip_metrics(t, omega, 900.0 + 300.0 * np.sin(2 * np.pi * 0.5 * t))
    assert set(raw) - {"warnings"} == {n for n, o in OUTPUTS.items() if o.stick_slip}
    m = stick_slip_metrics(t, omega, 900.0 + 300.0 * np.sin(2 * np.pi * 0.5 * t))
    for name, o in OUTPUTS.items():
        if o.stick_slip:
            value = m[name]
            assert value == raw[name] or (isinstance(value, float) and math.isnan(value) and math.isnan(raw[name]))


def test_the_docs_table_lists_every_output() -> None:
    table = _metric_reference().table()
    rows = [line for line in table.splitlines() if line.startswith("| `")]
    assert [re.match(r"\| `([^`]+)`", row).group(1) for row in rows] == [  # type: ignore[union-attr]
        *(n for n, o in OUTPUTS.items() if o.kind != "series"), *(n for n, o in OUTPUTS.items() if o.kind == "series")]
    for row, o in zip(rows, [*(o for o in OUTPUTS.values() if o.kind != "series"),
                             *(o for o in OUTPUTS.values() if o.kind == "series")]):
        assert o.definition.replace("|", "\\|") in row
    assert "```{include} ../_generated/metrics.md" in (ROOT / "docs" / "guide" / "metrics.md").read_text()
    assert '"metric_reference"' in (ROOT / "docs" / "conf.py").read_text()


# Each metric's name in at most 3 source files under rust/ and python/ (the tests, the
# benchmarks and Rust test modules aside): where it is declared or used as a key, a quoted
# name ("ssi") or a field or attribute declared by it (`pub ssi: f64`, `ssi: float`). Reading a
# field (`m.ssi`) or a sentence that names it does not count.
MAX_FILES = 3

#: Names still over the limit: the package's typed fields and the console's and plots' keys of
#: the coupled metrics, each of which a later change moves to the registry. The list only shrinks:
#: a name that comes within the limit must leave it.
OVER_THE_LIMIT = {
    "ssi", "stuck_fraction", "period_s", "bit_rpm_min", "bit_rpm_max", "bit_rpm_mean", "stick_slip", "settled",
    "stick_slip_verdict", "stick_slip_reason", "rop_mean_m_per_h", "wob_mean_N", "tob_mean_Nm", "bounce_fraction",
    "hook_load_mean_N", "mse_mean_Pa", "regime",
}


def _source_files() -> list[Path]:
    rust = [p for p in (ROOT / "rust").rglob("*.rs")
            if "target" not in p.parts and "benches" not in p.parts and not p.name.endswith("tests.rs")
            and p.name != "tests.rs"]
    python = [*(ROOT / "python").rglob("*.py"), *(ROOT / "python").rglob("*.pyi")]
    return sorted(rust + python)


def _code(path: Path) -> str:
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".rs":
        text = text.split("#[cfg(test)]\nmod tests")[0]
        text = re.sub(r"//[^\n]*", "", text)
    return text


def files_naming(name: str, sources: dict[Path, str]) -> list[str]:
    """The source files that declare ``name`` or use it as a key."""
    n = re.escape(name)
    pattern = re.compile(rf"[\"']{n}[\"']|^\s*(pub\s+)?{n}\s*:", re.M)
    return [str(p.relative_to(ROOT)) for p, text in sources.items() if pattern.search(text)]


def test_files_naming_counts_keys_and_declarations_only() -> None:
    sources = {ROOT / "a.rs": 'pub struct S {\n    pub ssi: f64,\n}\n', ROOT / "b.py": 'x = m.ssi\n',
               ROOT / "c.py": 'names = ("ssi",)\n', ROOT / "d.py": "class M:\n    ssi: float\n",
               ROOT / "e.py": "text = 'the ssi of a run'\n"}
    assert files_naming("ssi", sources) == ["a.rs", "c.py", "d.py"]


def test_each_metric_name_is_in_at_most_three_source_files() -> None:
    sources = {p: _code(p) for p in _source_files()}
    over = {}
    for name, o in OUTPUTS.items():
        if o.kind == "series":
            continue
        files = files_naming(name, sources)
        assert files, f"{name} is in no source file"
        if len(files) > MAX_FILES:
            over[name] = files
    assert set(over) <= OVER_THE_LIMIT, {k: v for k, v in over.items() if k not in OVER_THE_LIMIT}
    assert OVER_THE_LIMIT <= set(over), f"within the limit now, remove from OVER_THE_LIMIT: {OVER_THE_LIMIT - set(over)}"


@pytest.mark.parametrize("name", ["period_cycles", "periodicity", "slip_period_s", "min_cycle_torque_Nm"])
def test_a_registry_metric_is_declared_once_in_rust(name: str) -> None:
    sources = {p: _code(p) for p in _source_files() if p.suffix == ".rs"}
    assert len(files_naming(name, sources)) <= 2, files_naming(name, sources)
