"""drillstring: nonlinear torsional dynamics of rotating drill strings.

The model is the nonlinear wave-type PDE for the twist angle ``theta(z, t)`` of a rotating drill
string derived from finite-strain elasticity (paper eqs. 12, 17, 18), reduced by Bubnov-Galerkin
projection on ``cos(i pi z / l)`` to ``n`` coupled Duffing-type ODEs and integrated in a Rust core.

Quick start
-----------
>>> import drillstring as ds
>>> params = ds.preset("aluminum")              # Table 1, C = (0.1, 0.05, 0.02)
>>> res = ds.simulate(params, modes=3, t_end=1.0)
>>> theta_k = res.theta(2 * params.length / 3)  # twist at z_k = 2l/3, rad
>>> res.energy_drift() < 1e-6
True
"""

from __future__ import annotations

from . import analysis, coefficients, convergence, galerkin, limits, paper, pde, plots, section, stability
from ._core import __version__, simd_path
from .coefficients import PDECoefficients
from .errors import DrillstringError, SolveError, ValidationError
from .galerkin import ModalCoefficients, project
from .grid import linspace, logspace
from .parameters import PRESETS, Parameters, load, preset
from .pde import PdeSolution, solve_pde
from .simulate import METHODS, Simulation, SolverStats, simulate
from .sweep import SweepTrajectories, sweep
from .table2 import Table2Row, table2

__all__ = [
    "__version__",
    "simd_path",
    "Parameters",
    "PRESETS",
    "preset",
    "load",
    "PDECoefficients",
    "ModalCoefficients",
    "project",
    "simulate",
    "solve_pde",
    "PdeSolution",
    "pde",
    "convergence",
    "Simulation",
    "SolverStats",
    "METHODS",
    "table2",
    "Table2Row",
    "DrillstringError",
    "ValidationError",
    "SolveError",
    "coefficients",
    "galerkin",
    "section",
    "analysis",
    "paper",
    "plots",
    "stability",
    "limits",
    "sweep",
    "linspace",
    "logspace",
    "SweepTrajectories",
]
