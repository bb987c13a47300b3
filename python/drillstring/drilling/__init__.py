"""The drilling system: torsional stick-slip of a whole drill string in a well.

A string of sections (drill pipe, collars) in a deviated well, driven at the top by a top drive
with a speed controller, with Coulomb friction against the wall along its length and, on
bottom, a velocity-weakening bit-rock torque. The Rust core (``drillstring_core::drilling``)
solves the torsional wave equation on a grid along the string, and computes the friction
profile, the break-off torque, the stick-slip metrics and the energy balance; this package
configures it and renders what it returns. :mod:`.lumped` holds the lumped two-inertia model
of Navarro-Lopez & Cortes (2007) with its equilibria and their stability.

>>> import drillstring as ds
>>> cfg = ds.load_drill_config("examples/on-bottom-3000m.toml")          # doctest: +SKIP
>>> res = ds.drill(cfg.with_overrides(["numerics.duration=20"]))          # doctest: +SKIP
>>> res.metrics.ssi, res.metrics.stuck_fraction                          # doctest: +SKIP
"""

from __future__ import annotations

from .config import (
    Bit,
    Controller,
    DrillConfig,
    Friction,
    MetricsConfig,
    Numerics,
    StringSection,
    TopDrive,
    TorqueDragConfig,
    Well,
    defaults,
    load_drill_config,
)
from .lumped import (
    LumpedEquilibria,
    LumpedParams,
    LumpedResult,
    LumpedRotation,
    lumped,
    lumped_defaults,
    lumped_equilibria,
    lumped_figure,
    lumped_sweep,
    lumped_sweep_figure,
)
from .map_plots import controller_maps, regime_map, ssi_lines, ssi_map
from .maps import drill_map
from .output import FILES
from .result import SERIES, UNITS, DrillMetrics, DrillProfile, DrillResult
from .solve import drill, friction_profile
from .torque_drag import TorqueDragResult, torque_drag, write_torque_drag
from .tuning import ControllerRecommendations, PresetRecommendation, StringNumbers, recommend_controllers

__all__ = [
    "FILES",
    "LumpedEquilibria",
    "LumpedParams",
    "LumpedResult",
    "LumpedRotation",
    "lumped",
    "lumped_defaults",
    "lumped_equilibria",
    "lumped_figure",
    "lumped_sweep",
    "lumped_sweep_figure",
    "SERIES",
    "UNITS",
    "DrillMetrics",
    "DrillProfile",
    "DrillResult",
    "drill",
    "drill_map",
    "torque_drag",
    "TorqueDragResult",
    "write_torque_drag",
    "controller_maps",
    "ssi_lines",
    "ssi_map",
    "regime_map",
    "friction_profile",
    "recommend_controllers",
    "ControllerRecommendations",
    "PresetRecommendation",
    "StringNumbers",
    "Bit",
    "Controller",
    "DrillConfig",
    "Friction",
    "TorqueDragConfig",
    "MetricsConfig",
    "Numerics",
    "StringSection",
    "TopDrive",
    "Well",
    "defaults",
    "load_drill_config",
]

