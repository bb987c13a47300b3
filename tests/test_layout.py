"""The package layout: the import direction between the subpackages, nothing taken from
``drillstring/__init__`` inside the package, the report loaded lazily, and the stick-slip metrics
under one name each."""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import drillstring as ds
from drillstring.drilling import DrillMetrics
from drillstring.drilling import metrics as metrics_module
from drillstring.drilling.result import METRICS

PACKAGE = Path(ds.__file__).parent

#: The layers of the package, bottom first: a module may import from its own layer and below.
#: The drilling system stands beside the paper's model: it uses the bottom, ``io`` and itself.
LAYERS = {
    "_core": 0, "errors": 0, "limits": 0,
    "io": 1, "model": 2, "solvers": 3, "studies": 4, "plots": 5, "report": 6,
    "cli": 7, "__main__": 8, "": 9,
}
DRILLING_MAY_USE = {"_core", "errors", "limits", "io", "drilling"}
#: Calibration from measured data fits the drilling system: it uses what the drilling system may, and it.
CALIBRATION_MAY_USE = DRILLING_MAY_USE | {"calibration"}
#: The live display steps a drilling session: it uses what the drilling system may, and it.
LIVE_MAY_USE = DRILLING_MAY_USE | {"live"}


def _module(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _sources() -> list[Path]:
    return [p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts]


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
            elif layer == "live":
                if used not in LIVE_MAY_USE:
                    bad.append(where)
            elif used in ("drilling", "calibration", "live"):
                if layer not in ("cli", ""):
                    bad.append(where)
            elif LAYERS[used] > LAYERS[layer]:
                bad.append(where)
    assert bad == []


def test_the_layer_table_knows_every_module() -> None:
    tops = {_top(_module(p)) for p in _sources()} - {"drilling", "calibration", "live"}
    assert tops <= set(LAYERS), tops - set(LAYERS)


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()


def test_import_drillstring_loads_neither_the_report_nor_jinja2() -> None:
    code = ("import sys, drillstring as ds\n"
            "print('drillstring.report' in sys.modules, 'jinja2' in sys.modules)\n"
            "ds.report\n"
            "print('drillstring.report' in sys.modules)")
    assert _run(code).split() == ["False", "False", "True"]


def test_the_package_has_no_module_outside_its_subpackages_but_the_listed_ones() -> None:
    # the modules at the top level are the bottom layer, the figures and the entry points; every
    # other module lives in the subpackage of its subject (ARCHITECTURE.md)
    top = {p.stem for p in PACKAGE.glob("*.py")} | {p.parent.name for p in PACKAGE.glob("*/__init__.py")}
    assert top == {"__init__", "__main__", "errors", "limits", "plots", "calibration", "cli", "drilling", "io",
                   "live", "model", "report", "solvers", "studies"}


#: What ``import drillstring`` must not load: each costs 0.1-0.4 s of a command line's start.
HEAVY = ("matplotlib", "pandas", "scipy", "xarray", "pyarrow", "pint", "tqdm", "jinja2", "dask")


def test_import_drillstring_loads_no_heavy_dependency() -> None:
    # `import drillstring` (and the drilling package, all a run's command needs first) stays light;
    # the names loaded on first use are then the objects of their modules
    code = ("import sys, importlib, drillstring as ds\n"
            f"heavy = {HEAVY!r}\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy) or 'none')\n"
            "import drillstring.drilling\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy) or 'none')\n"
            "for name, module in sorted(ds._LAZY.items()):\n"
            "    value = getattr(ds, name)\n"
            "    loaded = importlib.import_module(module)\n"
            "    assert value is (loaded if module == f'drillstring.{name}' else getattr(loaded, name)), name\n"
            "print('same')")
    assert _run(code).split() == ["none", "none", "same"]


def test_the_lazy_names_of_the_drilling_package_are_its_modules_objects() -> None:
    from drillstring import drilling

    for name, module in drilling._LAZY.items():
        assert getattr(drilling, name) is getattr(importlib.import_module(f"drillstring.drilling.{module}"), name)
    # the functions named like their modules stay the functions, whatever was imported since
    importlib.import_module("drillstring.drilling.lumped")
    importlib.import_module("drillstring.drilling.torque_drag")
    assert callable(drilling.lumped) and callable(drilling.torque_drag) and callable(ds.torque_drag)
    assert set(drilling._LAZY) <= set(dir(drilling)) and set(ds._LAZY) <= set(dir(ds))


# the stick-slip metrics: one name per metric (``metrics.json``'s)

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
                "periodicity", "slip_period_s", "stick_slip", "settled", "min_cycle_torque_Nm", "stick_slip_verdict",
                "stick_duration_mean_s"]
    from drillstring.drilling.map_table import METRIC_COLUMNS

    assert list(METRICS) == contract and list(METRIC_COLUMNS) == contract
    fields: dict[str, Any] = {**{f: 1.0 for f in contract}, "stick_slip": True, "settled": True, "slip_onsets": 3,
                              "stick_slip_verdict": "yes"}
    m = DrillMetrics.from_core(fields)  # as the core's dict gives them, every metric by its name
    assert list(m.to_dict()) == contract
