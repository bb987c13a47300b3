"""drillstring: nonlinear torsional dynamics of rotating drill strings.

The model is the nonlinear wave-type PDE for the twist angle ``theta(z, t)`` of a rotating drill
string derived from finite-strain elasticity (paper eqs. 12, 17, 18), reduced by Bubnov-Galerkin
projection on ``cos(i pi z / l)`` to ``n`` coupled Duffing-type ODEs and integrated in a Rust core.

Quick start
-----------
>>> import drillstring as ds
>>> params = ds.preset("aluminum")              # Table 1, C = (0.1, 0.05, 0.02)
>>> res = ds.simulate(params, modes=3, t_end=1.0)
>>> theta_k = res.theta(ds.result.default_section(params.length))  # twist at z_k = 2l/3, rad
>>> res.energy_drift() < 1e-6
True

The API
-------
``__all__`` lists the functions, classes and constants above; the modules behind them
(``analysis``, ``coefficients``, ``convergence``, ``drilling``, ``galerkin``, ``grid``, ``limits``,
``paper``, ``pde``, ``plots``, ``section``, ``stability``) are attributes of the package as well.
``ds.sweep`` is the function; its module is ``drillstring.sweeps`` (``import drillstring.sweeps``).
``ds.table2`` is the function; its module is ``drillstring.paper.table2``.

The drilling system (stick-slip of a string in a well with a top drive, wall friction and a bit):
``ds.load_drill_config("examples/on-bottom-3000m.toml")``, ``ds.drill(config)`` returns a
:class:`DrillResult`, ``ds.drill_map(config, axes)`` a table of stick-slip metrics over a grid of
configuration values; the package :mod:`drillstring.drilling` holds the configuration dataclasses.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

# The modules, re-exported as attributes (``x as x``), not part of ``__all__``.
from . import analysis as analysis
from . import coefficients as coefficients
from . import convergence as convergence
from . import drilling as drilling
from . import galerkin as galerkin
from . import grid as grid
from . import limits as limits
from . import paper as paper
from . import pde as pde
from . import plots as plots
from . import section as section
from . import stability as stability
from ._core import __version__, simd_path
from .coefficients import PDECoefficients
from .drilling import (
    DrillConfig,
    DrillMetrics,
    DrillResult,
    TorqueDragResult,
    drill,
    drill_map,
    load_drill_config,
    torque_drag,
)
from .errors import DrillstringError, SolveError, ValidationError
from .galerkin import ModalCoefficients, project
from .grid import linspace, logspace
from .paper.table2 import Table2Row, table2
from .parameters import PRESETS, Parameters, load, preset
from .pde import PdeSolution, solve_pde
from .simulate import METHODS, Method, Simulation, SolverStats, simulate
from .sweeps import SweepTrajectories

if TYPE_CHECKING:  # pragma: no cover
    # The return type of sweep() follows ``trajectories`` (the runtime function is sweeps.sweep;
    # tests/test_api.py checks that these signatures match it).
    from collections.abc import Iterable, Mapping
    from typing import Any, Literal, Optional, Union, overload

    import pandas as pd

    @overload
    def sweep(
        base_params: Union[Parameters, str, Mapping[str, Any], None] = ...,
        grid: Optional[Mapping[str, Any]] = ...,
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
        grid: Optional[Mapping[str, Any]] = ...,
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
        grid: Optional[Mapping[str, Any]] = ...,
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
else:
    from .sweeps import sweep

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
    "drill_map",
    "torque_drag",
    "TorqueDragResult",
    "DrillConfig",
    "DrillResult",
    "DrillMetrics",
    "load_drill_config",
    # the paper
    "table2",
    "Table2Row",
    # errors
    "DrillstringError",
    "ValidationError",
    "SolveError",
]
