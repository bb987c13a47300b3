"""drillstring: nonlinear torsional dynamics of rotating drill strings.

The model is the nonlinear wave-type PDE for the twist angle ``theta(z, t)`` of a rotating drill
string derived from finite-strain elasticity (paper eqs. 12, 17, 18), reduced by Bubnov-Galerkin
projection on ``cos(i pi z / l)`` to ``n`` coupled Duffing-type ODEs and integrated in a Rust core.

Quick start
-----------
>>> import drillstring as ds
>>> params = ds.preset("aluminum")              # Table 1, C = (0.1, 0.05, 0.02)
>>> res = ds.simulate(params, modes=3, t_end=1.0)
>>> theta_k = res.theta(ds.solvers.trajectory.default_section(params.length))  # z_k = 2l/3, rad
>>> res.energy_drift() < 1e-6
True

The API
-------
``__all__`` lists the functions, classes and constants above. The subpackages are attributes of
the package as well: ``model`` (the paper's model: ``parameters``, ``cross_section``,
``coefficients``, ``galerkin``), ``solvers`` (``modal``, ``pde``, ``trajectory``), ``studies``
(``analysis``, ``stability``, ``convergence``, ``sweeps``, ``sweep_axes``, ``table2``),
``drilling`` (the drilling system, its stick-slip ``metrics``, torque and drag, the lumped
model), ``io`` (files, figures, TOML, progress, the sweep store), and the modules ``limits`` and
``plots``. ``report`` (the reproduction report, ``drillstring paper``), ``drilling``,
``calibration``, ``plots`` and the names of the drilling system, the calibration and sweeps load
their modules on first use: ``import drillstring`` itself loads numpy and the core, not matplotlib,
pandas or scipy.
``ds.sweep`` is the function; its module is ``drillstring.studies.sweeps``.
``ds.table2`` is the function; its module is ``drillstring.studies.table2``.

The drilling system (stick-slip of a string in a well with a top drive, wall friction and a bit):
``ds.load_drill_config("examples/on-bottom-3000m.toml")``, ``ds.drill(config)`` returns a
:class:`DrillResult`, ``ds.drill_map(config, axes)`` a table of stick-slip metrics over the product
of axes of configuration values; the package :mod:`drillstring.drilling` holds the configuration dataclasses.
"""

from __future__ import annotations

import importlib as _importlib
from typing import TYPE_CHECKING

# The modules, re-exported as attributes (``x as x``), not part of ``__all__``.
from . import io as io
from . import limits as limits
from . import model as model
from . import solvers as solvers
from . import studies as studies
from ._core import __version__, simd_path
from .errors import DrillstringError, SolveError, ValidationError
from .model.coefficients import PDECoefficients
from .model.galerkin import ModalCoefficients, project
from .model.parameters import PRESETS, Parameters, load, preset
from .solvers.modal import METHODS, Method, Simulation, SolverStats, simulate
from .solvers.pde import PdeSolution, solve_pde
from .studies.sweep_axes import linspace, logspace
from .studies.table2 import Table2Row, table2

#: The names loaded on first use (PEP 562, ``__getattr__`` below), each -> its module (the module
#: itself for a name of a module): the drilling system, the calibration, the sweeps and the
#: figures import the configuration schema, tqdm, pandas or matplotlib, which ``import drillstring``
#: and ``ds.simulate`` need none of.
_LAZY = {
    "drilling": "drillstring.drilling",
    "calibration": "drillstring.calibration",
    "plots": "drillstring.plots",
    "report": "drillstring.report",
    **dict.fromkeys(
        ("DrillConfig", "DrillMetrics", "DrillResult", "DrillSession", "DrillSnapshot", "TorqueDragResult", "drill",
         "drill_map",
         "load_drill_config", "recommend_controllers", "torque_drag"), "drillstring.drilling"),
    "FitResult": "drillstring.calibration.fit",
    "fit": "drillstring.calibration.fit",
    "RigLogResult": "drillstring.calibration.rig_log",
    "rig_log": "drillstring.calibration.rig_log",
    "SweepTrajectories": "drillstring.studies.sweeps",
    "sweep": "drillstring.studies.sweeps",
}

if TYPE_CHECKING:  # pragma: no cover
    # The return type of sweep() follows ``trajectories`` (the runtime function is sweeps.sweep;
    # tests/test_api.py checks that these signatures match it).
    from collections.abc import Iterable, Mapping
    from typing import Any, Literal, Optional, Union, overload

    import pandas as pd

    from . import calibration as calibration
    from . import drilling as drilling
    from . import plots as plots
    from . import report as report
    from .calibration.fit import FitResult, fit
    from .calibration.rig_log import RigLogResult, rig_log
    from .drilling import (
        DrillConfig,
        DrillMetrics,
        DrillResult,
        DrillSession,
        DrillSnapshot,
        drill,
        drill_map,
        load_drill_config,
        recommend_controllers,
    )
    from .drilling.torque_drag import TorqueDragResult, torque_drag
    from .studies.sweeps import SweepTrajectories

    @overload
    def sweep(
        base_params: Union[Parameters, str, Mapping[str, Any], None] = ...,
        axes: Optional[Mapping[str, Any]] = ...,
        *,
        runs: Optional[Iterable[Union[Parameters, Mapping[str, Any]]]] = ...,
        modes: int = ...,
        rigid_mode: bool = ...,
        t_end: float = ...,
        method: Method = ...,
        rtol: float = ...,
        atol: float = ...,
        dt: Optional[float] = ...,
        max_steps: Optional[int] = ...,
        samples: int = ...,
        z: Optional[float] = ...,
        threads: Optional[int] = ...,
        chunk_size: int = ...,
        out_dir: Any = ...,
        client: Any = ...,
        progress: Optional[bool] = ...,
        trajectories: Literal[False] = ...,
    ) -> pd.DataFrame: ...

    @overload
    def sweep(
        base_params: Union[Parameters, str, Mapping[str, Any], None] = ...,
        axes: Optional[Mapping[str, Any]] = ...,
        *,
        runs: Optional[Iterable[Union[Parameters, Mapping[str, Any]]]] = ...,
        modes: int = ...,
        rigid_mode: bool = ...,
        t_end: float = ...,
        method: Method = ...,
        rtol: float = ...,
        atol: float = ...,
        dt: Optional[float] = ...,
        max_steps: Optional[int] = ...,
        samples: int = ...,
        z: Optional[float] = ...,
        threads: Optional[int] = ...,
        chunk_size: int = ...,
        out_dir: Any = ...,
        client: Any = ...,
        progress: Optional[bool] = ...,
        trajectories: Literal[True],
    ) -> tuple[pd.DataFrame, SweepTrajectories]: ...

    @overload
    def sweep(
        base_params: Union[Parameters, str, Mapping[str, Any], None] = ...,
        axes: Optional[Mapping[str, Any]] = ...,
        *,
        runs: Optional[Iterable[Union[Parameters, Mapping[str, Any]]]] = ...,
        modes: int = ...,
        rigid_mode: bool = ...,
        t_end: float = ...,
        method: Method = ...,
        rtol: float = ...,
        atol: float = ...,
        dt: Optional[float] = ...,
        max_steps: Optional[int] = ...,
        samples: int = ...,
        z: Optional[float] = ...,
        threads: Optional[int] = ...,
        chunk_size: int = ...,
        out_dir: Any = ...,
        client: Any = ...,
        progress: Optional[bool] = ...,
        trajectories: bool = ...,
    ) -> Union[pd.DataFrame, tuple[pd.DataFrame, SweepTrajectories]]: ...

    def sweep(*args: Any, **kwargs: Any) -> Any: ...  # seen by type checkers only

__all__ = [
    "__version__",
    "simd_path",
    # parameters and coefficients
    "Parameters",
    "PRESETS",
    "preset",
    "load",
    "PDECoefficients",
    "ModalCoefficients",
    "project",
    # solvers and their results
    "simulate",
    "solve_pde",
    "Simulation",
    "PdeSolution",
    "SolverStats",
    "METHODS",
    "Method",
    # sweeps
    "sweep",
    "SweepTrajectories",
    "linspace",
    "logspace",
    # the drilling system (stick-slip)
    "drill",
    "DrillSession",
    "DrillSnapshot",
    "drill_map",
    "torque_drag",
    "TorqueDragResult",
    "DrillConfig",
    "DrillResult",
    "DrillMetrics",
    "load_drill_config",
    "recommend_controllers",
    # calibration from measured data
    "fit",
    "FitResult",
    "rig_log",
    "RigLogResult",
    # the paper
    "table2",
    "Table2Row",
    # errors
    "DrillstringError",
    "ValidationError",
    "SolveError",
]


# Loaded with the package, so that ``ds.studies.stability``, ``ds.model.cross_section``, ... need
# no import of their own.
for _name in ("model.cross_section", "studies.analysis", "studies.convergence", "studies.stability"):
    _importlib.import_module(f"{__name__}.{_name}")
del _name

if not TYPE_CHECKING:

    def __getattr__(name: str) -> object:
        """PEP 562: the names of ``_LAZY`` load their modules on first use (the reproduction
        report, the drilling system, the calibration, sweeps and figures, as scipy's submodules
        do) and are attributes from then on."""
        import importlib

        if name in _LAZY:
            module = importlib.import_module(_LAZY[name])
            value = module if module.__name__ == f"{__name__}.{name}" else getattr(module, name)
            globals()[name] = value
            return value
        raise AttributeError(f"module 'drillstring' has no attribute {name!r}")

    def __dir__() -> list[str]:
        # the API, the modules and the names loaded on first use; not the names this file needs
        # for itself
        return sorted((set(globals()) | set(_LAZY)) - {"TYPE_CHECKING", "annotations"})
