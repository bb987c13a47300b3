"""The public API: names, types, the Python examples of the README and the documentation pages, and
what they say about them."""

import ast
import importlib
import inspect
import re
import subprocess
import sys
import types
import typing
from pathlib import Path
from typing import Any

import _docs
import numpy as np
import pandas as pd
import pytest

import drillstring as ds

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
DOCS = _docs.text()  # the README and the documentation pages
PYTHON_EXAMPLES = _docs.blocks("python")


def _example(marker: str) -> str:
    """The one Python example of the documentation that contains ``marker``."""
    (block,) = [b for b in PYTHON_EXAMPLES if marker in b]
    return block


def test_all_lists_functions_classes_and_constants_not_modules():
    for name in ds.__all__:
        assert hasattr(ds, name), name
        assert not isinstance(getattr(ds, name), types.ModuleType), name
    for module in ("drilling", "io", "limits", "model", "plots", "report", "solvers", "studies"):
        assert isinstance(getattr(ds, module), types.ModuleType) and module not in ds.__all__


def test_sweep_and_table2_are_functions_and_their_modules_are_importable():
    # the sweep module has its own name: importing it gives the module, never the function
    import drillstring.studies.sweeps as sweeps

    assert isinstance(sweeps, types.ModuleType) and ds.sweep is sweeps.sweep
    sweep_module = importlib.import_module("drillstring.studies.sweeps")
    import drillstring.studies.table2 as table2_module_imported

    assert ds.table2 is table2_module_imported.table2
    table2_module = importlib.import_module("drillstring.studies.table2")
    assert isinstance(sweep_module, types.ModuleType) and ds.sweep is sweep_module.sweep
    assert isinstance(table2_module, types.ModuleType) and ds.table2 is table2_module.table2
    from drillstring.studies.sweeps import SweepTrajectories

    assert ds.SweepTrajectories is SweepTrajectories


def test_method_names_are_one_literal():
    assert ds.METHODS == typing.get_args(ds.Method) == (
        "dop853", "dopri5", "rkn12", "rk4", "central", "verlet", "auto"
    )
    assert inspect.signature(ds.simulate).parameters["method"].default == "dop853"


def _overloads(name):
    tree = ast.parse((ROOT / "python/drillstring/__init__.py").read_text(encoding="utf-8"))
    return [node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef) and node.name == name
            and any(getattr(d, "id", None) == "overload" for d in node.decorator_list)]


def test_sweep_overloads_match_the_function():
    real = inspect.signature(ds.sweep).parameters
    overloads = _overloads("sweep")
    assert len(overloads) == 3
    for node in overloads:
        positional = [a.arg for a in node.args.args]
        keyword = [a.arg for a in node.args.kwonlyargs]
        assert positional + keyword == list(real)
        assert keyword == [n for n, p in real.items() if p.kind is inspect.Parameter.KEYWORD_ONLY]
    returns = [ast.unparse(node.returns) for node in overloads]
    assert returns[:2] == ["pd.DataFrame", "tuple[pd.DataFrame, SweepTrajectories]"]


def test_sweep_returns_what_the_overloads_say():
    grid = {"length": [100.0, 150.0]}
    table = ds.sweep("aluminum", grid, modes=1, t_end=0.05)
    assert isinstance(table, pd.DataFrame) and len(table) == 2
    table2, kept = ds.sweep("aluminum", grid, modes=1, t_end=0.05, trajectories=True)
    assert isinstance(kept, ds.SweepTrajectories) and kept.theta.shape[0] == 2
    np.testing.assert_array_equal(table2["max_theta"], table["max_theta"])


def test_readme_python_examples_run(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    first: dict = {}
    exec(compile(_example("res.to_xarray()"), "the paper model's Python example", "exec"), first)
    assert first["res"].status == "success" and first["res"].indices.tolist() == list(range(9))
    assert 1e-4 < float(np.abs(first["theta"]).max()) < 1e-3
    assert first["df"].shape == (1868, 2) and first["data"]["q"].shape == (3, 1868)  # the default samples
    sweep: dict = {}
    exec(compile(_example("ds.sweep("), "the sweep example", "exec"), sweep)
    assert sweep["df"].shape[0] == 41 * 41 and set(sweep["df"]["status"]) == {"success"}
    assert list(tmp_path.iterdir()) == []  # the examples write no files


@pytest.mark.slow
def test_readme_python_examples_type_check(tmp_path):
    """mypy (the project's configuration and cache) accepts the documentation's examples and rejects a
    wrong method name and a sweep table taken for a pair."""
    pytest.importorskip("mypy")
    files = []
    for k, code in enumerate(PYTHON_EXAMPLES):
        files.append(tmp_path / f"docs_example_{k + 1}.py")
        files[-1].write_text(code, encoding="utf-8")
    bad = tmp_path / "bad.py"
    bad.write_text('import drillstring as ds\n'
                   'ds.simulate(ds.preset("aluminum"), method="rk5")\n'
                   'pair: tuple[object, object] = ds.sweep("aluminum", {"length": [1.0]})\n', encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml"),
                           "--cache-dir", str(ROOT / ".mypy_cache"), *map(str, [*files, bad])],
                          capture_output=True, text=True, cwd=tmp_path)
    errors = [line for line in done.stdout.splitlines() if ": error:" in line]
    assert len(errors) == 2, done.stdout + done.stderr
    assert errors[0].startswith("bad.py:2: error: Argument \"method\" to \"simulate\" has incompatible type "
                                "\"Literal['rk5']\"")
    assert errors[1].startswith("bad.py:3: error: Incompatible types in assignment (expression has type "
                                "\"DataFrame\"")


def test_nfev_counts_as_the_readme_says():
    params = ds.preset("aluminum")
    two = ds.simulate(params, samples=2).stats
    default = ds.simulate(params).stats
    assert (two.naccept, two.nreject) == (default.naccept, default.nreject) == (1217, 218)
    assert two.nfev == 2 + 12 * two.naccept + 11 * two.nreject == 17004
    assert default.nfev == 20652  # + 3 for each of the 1216 steps with an output time inside
    dense = ds.simulate(params, samples=20001).stats
    assert dense.nfev - two.nfev == 3 * dense.naccept  # every step holds an output time
    for samples in (2, 1868):
        s = ds.simulate(params, method="dopri5", samples=samples).stats
        assert s.nfev == 2 + 6 * (s.naccept + s.nreject)
    assert "17004 with `samples=2` and 20652 with the default 1868 samples" in DOCS.replace("\n  ", " ")


def _pyproject() -> dict[str, Any]:
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        import tomli as tomllib
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]


def _names(requirements: list[str]) -> set[str]:
    return {re.split(r"[<>=;\[ ]", d)[0] for d in requirements}


def test_plain_install_has_what_the_readme_uses():
    project = _pyproject()
    names = _names(project["dependencies"])
    # drill's series.parquet and the sweep store (pyarrow), progress bars, the paper's report (jinja2)
    assert {"numpy", "matplotlib", "pandas", "pyarrow", "tqdm", "jinja2"} <= names
    # netCDF output is an extra (xarray, h5netcdf and its HDF5 backend h5py)
    assert not names & {"xarray", "h5netcdf", "h5py"}
    assert "sweep" not in project["optional-dependencies"]
    sources = "".join(p.read_text(encoding="utf-8") for p in (ROOT / "python/drillstring").rglob("*.py"))
    assert "drillstring[" not in sources and "drillstring[" not in README
    assert "import h5py" not in sources
    assert "pip install '.[dask]'" in README and "'.[netcdf]'" in README


def test_the_extras_of_optional_outputs_are_the_modules_the_package_checks():
    from drillstring.io.extras import EXTRAS

    extras = {name: _names(reqs) for name, reqs in _pyproject()["optional-dependencies"].items()}
    for extra, modules in EXTRAS.items():
        assert extras[extra] == set(modules), extra
    # `all` is every optional output; the tests have all of them
    optional = set().union(*(extras[e] for e in ("netcdf", "dask", "las", "live")))
    assert extras["all"] == optional
    assert optional <= extras["test"]


def test_dir_lists_the_api_and_no_import_machinery() -> None:
    names = dir(ds)
    assert "TYPE_CHECKING" not in names and "annotations" not in names
    assert set(ds.__all__) <= set(names) and {"drilling", "report", "studies"} <= set(names)
    assert names == sorted(names)


def test_import_does_not_load_the_report_engine() -> None:
    # the paper report's Jinja2 templates are compiled when a report is rendered, not on import
    code = "import drillstring, sys; print('jinja2' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert done.stdout.strip() == "False", done.stdout + done.stderr
