"""The package layout: the import direction between the subpackages, nothing taken from
``drillstring/__init__`` inside the package, the report loaded lazily, and the old module paths
and names that warn for one release and give the same objects."""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
import warnings
from functools import partial
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pandas as pd
import pytest

import drillstring as ds
from drillstring.drilling import DrillMetrics, StringSection
from drillstring.drilling import config as drill_config
from drillstring.drilling import metrics as metrics_module
from drillstring.drilling.result import METRICS
from drillstring.model import cross_section
from drillstring.model.cross_section import CrossSection
from drillstring.studies import sweep_axes

PACKAGE = Path(ds.__file__).parent

#: The layers of the package, bottom first: a module may import from its own layer and below.
#: The drilling system stands beside the paper's model: it uses the bottom, ``io`` and itself.
LAYERS = {
    "_core": 0, "_deprecated": 0, "errors": 0, "limits": 0,
    "io": 1, "model": 2, "solvers": 3, "studies": 4, "plots": 5, "report": 6,
    "cli": 7, "__main__": 8, "": 9,
}
DRILLING_MAY_USE = {"_core", "_deprecated", "errors", "limits", "io", "drilling"}
#: Calibration from measured data fits the drilling system: it uses what the drilling system may, and it.
CALIBRATION_MAY_USE = DRILLING_MAY_USE | {"calibration"}


def _is_shim(path: Path) -> bool:
    return "from drillstring._deprecated import forward" in path.read_text(encoding="utf-8")


def _module(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _sources() -> list[Path]:
    return [p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts and not _is_shim(p)]


def _imports(path: Path) -> list[tuple[int, str, str]]:
    """``(line, module, name)`` of every import of the package in ``path`` (relative ones
    resolved; ``name`` is ``""`` for ``import drillstring.x``), at any depth (lazy imports too)."""
    module = _module(path)
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target == "drillstring" or target.startswith("drillstring."):
                out += [(node.lineno, target, alias.name) for alias in node.names]
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name, "") for a in node.names if a.name.split(".")[0] == "drillstring"]
    return out


def _top(dotted: str) -> str:
    """The subpackage or top-level module of ``drillstring.x.y`` (``""`` for the package)."""
    parts = dotted.split(".")
    return parts[1] if len(parts) > 1 else ""


def test_no_module_takes_a_name_from_the_package_init() -> None:
    bad = []
    for path in _sources():
        for line, target, name in _imports(path):
            if target == "drillstring" and name:
                is_module = (PACKAGE / f"{name}.py").exists() or (PACKAGE / name / "__init__.py").exists() \
                    or name == "_core"
                if not is_module:
                    bad.append(f"{path.relative_to(PACKAGE)}:{line}: from drillstring import {name}")
    assert bad == []


def test_imports_run_down_the_layers_only() -> None:
    bad = []
    for path in _sources():
        source = _module(path)
        layer = _top(source)
        for line, target, name in _imports(path):
            if target == "drillstring" and name:
                target = f"drillstring.{name}"
            used = _top(target)
            where = f"{path.relative_to(PACKAGE)}:{line}: imports {target}"
            if layer == "drilling":
                if used not in DRILLING_MAY_USE:
                    bad.append(where)
            elif layer == "calibration":
                if used not in CALIBRATION_MAY_USE:
                    bad.append(where)
            elif used in ("drilling", "calibration"):
                if layer not in ("cli", ""):
                    bad.append(where)
            elif LAYERS[used] > LAYERS[layer]:
                bad.append(where)
    assert bad == []


def test_the_layer_table_knows_every_module() -> None:
    tops = {_top(_module(p)) for p in _sources()} - {"drilling", "calibration"}
    assert tops <= set(LAYERS), tops - set(LAYERS)


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()


def test_import_drillstring_loads_neither_the_report_nor_jinja2() -> None:
    code = ("import sys, drillstring as ds\n"
            "print('drillstring.report' in sys.modules, 'jinja2' in sys.modules)\n"
            "ds.report\n"
            "print('drillstring.report' in sys.modules)")
    assert _run(code).split() == ["False", "False", "True"]


def test_no_module_of_the_package_goes_through_an_old_path() -> None:
    names = sorted(_module(p) for p in _sources() if p.name != "__main__.py")
    code = ("import importlib, warnings\n"
            "warnings.filterwarnings('error', message='.*is deprecated: use drillstring',\n"
            "                        category=DeprecationWarning)\n"
            f"for name in {names!r}:\n"
            "    importlib.import_module(name)\n"
            "print('ok')")
    assert _run(code) == "ok"


# --------------------------------------------------------------------------- old paths and names


def _one_warning(get: Callable[[], Any]) -> tuple[Any, warnings.WarningMessage]:
    """``get()`` and the single DeprecationWarning it issued (at this file's line)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = get()
    deprecations = [w for w in caught if issubclass(w.category, DeprecationWarning)]
    assert len(deprecations) == 1, [str(w.message) for w in deprecations]
    assert deprecations[0].filename == __file__
    return value, deprecations[0]


SHIMS = sorted(_module(p) for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts and _is_shim(p))


def test_the_old_module_paths_are_the_moved_modules() -> None:
    assert set(SHIMS) == {
        "drillstring._atomic", "drillstring._output", "drillstring._progress", "drillstring.analysis",
        "drillstring.coefficients", "drillstring.convergence", "drillstring.galerkin", "drillstring.grid",
        "drillstring.paper", "drillstring.paper.checks", "drillstring.paper.document", "drillstring.paper.fmt",
        "drillstring.paper.measure", "drillstring.paper.render", "drillstring.paper.run", "drillstring.paper.specs",
        "drillstring.paper.table2", "drillstring.parameters", "drillstring.pde", "drillstring.result",
        "drillstring.section", "drillstring.simulate", "drillstring.stability", "drillstring.sweep_store",
        "drillstring.sweeps",
    }


@pytest.mark.parametrize("old", SHIMS)
def test_each_name_of_an_old_path_warns_once_and_is_the_new_object(old: str) -> None:
    shim = importlib.import_module(old)
    targets = [importlib.import_module(t) for t in shim._TARGETS]
    names = dir(shim)
    assert names and set(names) == {n for t in targets for n in dir(t) if not n.startswith("_")}
    for name in names:
        if name in vars(shim):  # the shim's own imports (``Any``), the same objects
            continue
        value, caught = _one_warning(partial(getattr, shim, name))
        owner = next(t for t in targets if name in vars(t))
        assert value is vars(owner)[name], (old, name)
        assert f"use {owner.__name__}.{name}" in str(caught.message)


def test_old_paths_by_example() -> None:
    import drillstring.io.cluster
    import drillstring.studies.table2

    cases: list[tuple[Callable[[], Any], Any]] = [
        (lambda: importlib.import_module("drillstring.analysis").stick_slip_metrics,
         metrics_module.stick_slip_metrics),
        (lambda: importlib.import_module("drillstring.analysis").phase_shift,
         importlib.import_module("drillstring.studies.analysis").phase_shift),
        (lambda: importlib.import_module("drillstring.sweeps").sweep, ds.sweep),
        (lambda: importlib.import_module("drillstring.sweeps").check_client, drillstring.io.cluster.check_client),
        (lambda: importlib.import_module("drillstring.paper.table2").table2, ds.table2),
        (lambda: importlib.import_module("drillstring.paper.table2").table2, drillstring.studies.table2.table2),
        (lambda: importlib.import_module("drillstring.simulate").simulate, ds.simulate),
        (lambda: importlib.import_module("drillstring.parameters").load_toml, ds.io.toml.load_toml),
    ]
    for get, expected in cases:
        assert _one_warning(get)[0] is expected
    # importing the old module path does not turn the function ``ds.simulate`` into that module
    import drillstring.simulate

    assert callable(ds.simulate) and ds.simulate is ds.solvers.modal.simulate
    with pytest.warns(DeprecationWarning, match="drillstring.studies.analysis.ellipk"):
        from drillstring.analysis import ellipk
    assert ellipk is importlib.import_module("drillstring.studies.analysis").ellipk


def test_from_import_of_an_old_path_warns_at_the_import_line() -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        from drillstring.galerkin import project
    assert project is ds.project
    assert [(w.category, w.filename) for w in caught] == [(DeprecationWarning, __file__)]


def test_the_old_module_attributes_of_the_package_warn_and_give_the_new_modules() -> None:
    # in a fresh interpreter: an old path imported once is an attribute of the package from then on
    code = """
import sys, types, warnings
import drillstring as ds
for old, new in ds._MOVED_MODULES.items():
    if old in vars(ds):  # a function of the same name (ds.simulate) stays the function
        assert not isinstance(vars(ds)[old], types.ModuleType), old
        continue
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = getattr(ds, old)
    assert [w.category for w in caught] == [DeprecationWarning], (old, caught)
    assert caught[0].filename == "<string>" and f"drillstring.{new}" in str(caught[0].message)
    expected = f"drillstring.{old}" if old in ("analysis", "sweeps") else f"drillstring.{new}"
    assert value is sys.modules[expected], old
    print(old, new)
try:
    ds.no_such_thing
except AttributeError:
    print("AttributeError")
"""
    lines = _run(code).splitlines()
    assert lines[-1] == "AttributeError"
    assert {line.split()[0] for line in lines[:-1]} == set(ds._MOVED_MODULES) - {"simulate"}  # type: ignore[attr-defined]


def test_the_renamed_classes_warn_and_give_the_same_class() -> None:
    for module, old, new in [
        (cross_section, "Section", CrossSection),
        (importlib.import_module("drillstring.drilling"), "Section", StringSection),
        (drill_config, "Section", StringSection),
        (sweep_axes, "expand_grid", sweep_axes.expand_axes),
        (sweep_axes, "Grid", sweep_axes.Axes),
    ]:
        value, caught = _one_warning(partial(getattr, module, old))
        assert value is new, (module, old)
        assert "deprecated" in str(caught.message)
    # the old name through the old path: one warning, naming the new name
    value, caught = _one_warning(lambda: importlib.import_module("drillstring.section").Section)
    assert value is CrossSection and "cross_section.CrossSection" in str(caught.message)
    assert CrossSection.annulus(0.2, 0.1).area == pytest.approx(np.pi * (0.1**2 - 0.05**2), rel=1e-15)
    assert StringSection.__name__ == "StringSection" and CrossSection.__name__ == "CrossSection"


# the stick-slip metrics: one name per metric (``metrics.json``'s), the old ones warn

OLD_METRIC_NAMES = {
    "t_start": "window_start", "t_end": "window_end", "severity": "ssi", "rpm_min": "bit_rpm_min",
    "rpm_max": "bit_rpm_max", "rpm_mean": "bit_rpm_mean", "torque_min": "motor_torque_min_Nm",
    "torque_max": "motor_torque_max_Nm", "cycle_period": "period_s", "slip_period": "slip_period_s",
}


def test_the_old_metric_names_warn_and_give_the_same_values() -> None:
    t = np.linspace(0.0, 8.0, 8001)
    omega = np.maximum(0.0, 5.0 * (1.0 + 1.5 * np.sin(2 * np.pi * 0.5 * t)))
    torque = 900.0 + 300.0 * np.sin(2 * np.pi * 0.5 * t)
    m = metrics_module.stick_slip_metrics(t, omega, torque)
    assert (m.window_start, m.window_end) == (0.0, 8.0) and m.period_s == pytest.approx(2.0, rel=1e-3)
    for old, new in OLD_METRIC_NAMES.items():
        value, caught = _one_warning(partial(getattr, m, old))
        assert value is getattr(m, new), old
        assert f".{new}" in str(caught.message)


def test_metrics_from_the_cores_dict() -> None:
    core = {"window_start": 1.0, "window_end": 9.0, "ssi": 0.5, "stuck_fraction": 0.25, "bit_rpm_min": 0.0,
            "bit_rpm_max": 120.0, "bit_rpm_mean": 60.0, "motor_torque_min_Nm": 5.0e3, "motor_torque_max_Nm": 9.0e3,
            "period_s": 4.0, "period_cycles": 2.0, "periodicity": 0.99, "slip_period_s": None, "slip_onsets": 2,
            "stick_slip": True, "settled": False, "warnings": ["w"]}
    m = metrics_module.StickSlipMetrics.from_core(core)
    assert (m.window_start, m.window_end, m.ssi, m.bit_rpm_max, m.motor_torque_min_Nm, m.period_s) == (
        1.0, 9.0, 0.5, 120.0, 5.0e3, 4.0)
    assert np.isnan(m.slip_period_s) and m.slip_onsets == 2 and m.warnings == ("w",)
    assert m["ssi"] == 0.5 and m["stick_slip"] is True
    # a drill run's dict: the window asked for, and the static torques
    drill = DrillMetrics.from_core({**core, "window_start": 0.5, "window_end": 10.0, "breakoff_torque_Nm": 7.0e3,
                                    "min_cycle_torque_Nm": 4.0e3})
    assert isinstance(drill, metrics_module.StickSlipMetrics)
    assert (drill.window_start, drill.window_end, drill.breakoff_torque_Nm, drill.min_cycle_torque_Nm) == (
        0.5, 10.0, 7.0e3, 4.0e3)
    with pytest.raises(KeyError, match="not a metric"):
        drill["severity"]


def test_metrics_json_and_map_columns_keep_their_names_and_order() -> None:
    contract = ["window_start", "window_end", "ssi", "stuck_fraction", "period_s", "bit_rpm_min", "bit_rpm_max",
                "bit_rpm_mean", "motor_torque_min_Nm", "motor_torque_max_Nm", "breakoff_torque_Nm", "period_cycles",
                "periodicity", "slip_period_s", "stick_slip", "settled", "min_cycle_torque_Nm", "stick_slip_verdict"]
    from drillstring.drilling.map_table import METRIC_COLUMNS

    assert list(METRICS) == contract and list(METRIC_COLUMNS) == contract
    fields: dict[str, Any] = {**{f: 1.0 for f in contract}, "stick_slip": True, "settled": True, "slip_onsets": 3,
                              "stick_slip_verdict": "yes"}
    m = DrillMetrics(**fields)
    assert list(m.to_dict()) == contract


def test_sweep_grid_keyword_warns_and_gives_the_same_table() -> None:
    axes = {"length": [100.0, 150.0]}
    table = ds.sweep("aluminum", axes=axes, modes=1, t_end=0.05, progress=False)
    old, caught = _one_warning(lambda: ds.sweep("aluminum", grid=axes, modes=1, t_end=0.05, progress=False))
    assert "axes" in str(caught.message)
    pd.testing.assert_frame_equal(old, table)
    assert table.attrs["axes"] == {"length": [100.0, 150.0]}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ds.ValidationError, match="grid"):
            ds.sweep("aluminum", axes, grid=axes, modes=1, t_end=0.05)
