"""The registry of a run's outputs (``drillstring_core::outputs``, ``_core.drill_outputs()``):
every metric and series channel declared once, read by ``metrics.json``, a map's columns, the
units, the grid check's tolerances and the documentation's table; each metric's name in few
source files."""

from __future__ import annotations

import importlib.util
import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

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
    assert set(raw) - {"warnings"} == {n for n, o in OUTPUTS.items() if o.of_any_series}
    m = stick_slip_metrics(t, omega, 900.0 + 300.0 * np.sin(2 * np.pi * 0.5 * t))
    for name, o in OUTPUTS.items():
        if o.of_any_series:
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
    assert not over, over


@pytest.mark.parametrize("name", ["period_cycles", "periodicity", "slip_period_s", "min_cycle_torque_Nm"])
def test_a_registry_metric_is_declared_once_in_rust(name: str) -> None:
    sources = {p: _code(p) for p in _source_files() if p.suffix == ".rs"}
    assert len(files_naming(name, sources)) <= 2, files_naming(name, sources)


# The mean stick duration, a metric added as one registry entry and its computation in the core.

STRING = {"sections": [{"length": 2000.0, "outer_diameter": 0.127, "inner_diameter": 0.1086}],
          "numerics": {"cells": 100, "duration": 20.0}}


def test_stick_durations_of_a_clipped_sine_are_the_arccos_closed_form() -> None:
    # omega = max(0, w0 (1 + a sin(2 pi f t))): stuck while sin < -1/a, each phase lasting
    # (pi - 2 arcsin(1/a)) / (2 pi f); the samples from 0 to 9 s hold 4 whole ones
    w0, a, f = 10.0, 2.0, 0.5
    t = np.linspace(0.0, 9.0, 180001)
    omega = np.maximum(0.0, w0 * (1.0 + a * np.sin(2 * np.pi * f * t)))
    m = stick_slip_metrics(t, omega, stick_speed=0.0)
    expected = (np.pi - 2.0 * np.arcsin(1.0 / a)) / (2.0 * np.pi * f)
    # the clipped samples are 0 from the first sample past the crossing: within a sample at each end
    dt = t[1] - t[0]
    assert abs(m["stick_duration_mean_s"] - expected) <= 2.0 * dt
    # never stuck: NaN
    assert math.isnan(stick_slip_metrics(t, np.full_like(t, 3.0))["stick_duration_mean_s"])


def test_stick_duration_is_in_every_output_of_a_run(tmp_path: Path) -> None:
    import drillstring as ds

    res = ds.drill(STRING, progress=False)
    m = res.metrics
    assert m.stick_slip_verdict == "yes"
    duration = m["stick_duration_mean_s"]
    # one stick phase per cycle: its mean duration is the stuck share of a period
    assert duration == pytest.approx(m.stuck_fraction * m.period_s, rel=0.05)
    summary = res.summary()
    assert summary["stick_duration_mean_s"] == duration and "stick_duration_mean_s" in summary["definitions"]
    assert "stick_duration_mean_s" in result.METRICS and "stick_duration_mean_s" in map_table.METRIC_COLUMNS
    assert result.METRIC_UNITS["stick_duration_mean_s"] == "s"
    assert "`stick_duration_mean_s`" in _metric_reference().table()
    raw = _core.drill_map(json.dumps(res.config.to_dict()), json.dumps([[]]), threads=1)
    assert raw["metrics"]["stick_duration_mean_s"][0] == duration


def test_the_mean_stick_duration_converges_with_the_grid_and_the_window() -> None:
    """On finer grids the bit chatters around the stick speed inside a stick phase; a partial
    slip does not split the phase, so the metric stays the stuck share of a period on every grid
    (it once halved from 200 cells on: 1.238 s on 100 cells, 0.745 s on 200) and does not move
    with the window's start (whole phases only), where the stuck fraction of a window of no whole
    number of cycles does (1.313 s against 1.234 s as stuck fraction x period)."""
    import drillstring as ds

    durations = []
    for cells, window in ((100, [10.0, 20.0]), (200, [10.0, 20.0]), (400, [10.0, 20.0]), (400, [12.0, 20.0])):
        cfg = ds.DrillConfig.from_dict(STRING).with_overrides({"numerics.cells": cells, "metrics.window": window})
        m = ds.drill(cfg, progress=False).metrics
        if window[0] == 10.0:  # (about four whole cycles)
            assert m["stick_duration_mean_s"] == pytest.approx(m.stuck_fraction * m.period_s, rel=0.02), cells
        durations.append(m["stick_duration_mean_s"])
    assert max(durations) / min(durations) - 1.0 < 0.01, durations


@settings(max_examples=40, deadline=None)
@given(knots=st.lists(st.one_of(st.just(0.0), st.floats(1.0, 10.0)), min_size=3, max_size=12),
       extra=st.lists(st.tuples(st.integers(0, 10), st.floats(0.05, 0.95)), max_size=8))
def test_stick_duration_does_not_depend_on_samples_on_a_line(knots: list[float],
                                                             extra: list[tuple[int, float]]) -> None:
    # the series is linear between samples: a sample added on a segment changes nothing
    t = np.arange(len(knots), dtype=float)
    x = np.asarray(knots)
    # (a full slip is a speed above the time mean: a knot at the mean itself, to rounding, is on
    # the metric's threshold, where the rounding of the mean over other samples decides; drawn
    # once as knots [0, 2.5, 0, 10 - 2e-15], whose mean is 2.5 within 1 ulp)
    mean = float(np.sum(np.diff(t) * (x[1:] + x[:-1]) / 2.0) / (t[-1] - t[0]))
    assume(bool(np.all(np.abs(x - mean) > 1e-9 * max(1.0, float(np.max(np.abs(x)))))))
    base = stick_slip_metrics(t, x)["stick_duration_mean_s"]
    samples = dict(zip(t.tolist(), x.tolist()))
    for k, frac in extra:
        k = k % (len(knots) - 1)
        samples[k + frac] = x[k] + frac * (x[k + 1] - x[k])
    tt = np.asarray(sorted(samples))
    denser = stick_slip_metrics(tt, np.asarray([samples[v] for v in tt]))["stick_duration_mean_s"]
    if math.isnan(base):
        assert math.isnan(denser)
    else:
        assert denser == pytest.approx(base, rel=1e-9)
