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

from typing import TYPE_CHECKING, Any

# Bound now: the functions ``lumped`` and ``torque_drag`` share their modules' names, and a module
# loaded after its package's attribute was set would replace the function by the module.
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
from .torque_drag import TorqueDragResult, torque_drag, write_torque_drag

if TYPE_CHECKING:  # pragma: no cover
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
    from .map_plots import controller_maps, regime_map, ssi_lines, ssi_map
    from .maps import drill_map
    from .output import FILES
    from .result import SERIES, UNITS, DrillMetrics, DrillProfile, DrillResult
    from .session import DrillSession, DrillSnapshot
    from .solve import drill, friction_profile
    from .tuning import ControllerRecommendations, PresetRecommendation, StringNumbers, recommend_controllers

#: The names of the package, each -> its module, loaded on first use (PEP 562, ``__getattr__``
#: below): a run needs its configuration, solve and result, not the maps and their figures
#: (matplotlib, pandas), and the command line imports only what its verb uses.
_LAZY = {
    "Bit": "config",
    "Controller": "config",
    "DrillConfig": "config",
    "Friction": "config",
    "MetricsConfig": "config",
    "Numerics": "config",
    "StringSection": "config",
    "TopDrive": "config",
    "TorqueDragConfig": "config",
    "Well": "config",
    "defaults": "config",
    "load_drill_config": "config",
    "controller_maps": "map_plots",
    "regime_map": "map_plots",
    "ssi_lines": "map_plots",
    "ssi_map": "map_plots",
    "drill_map": "maps",
    "FILES": "output",
    "SERIES": "result",
    "UNITS": "result",
    "DrillMetrics": "result",
    "DrillProfile": "result",
    "DrillResult": "result",
    "drill": "solve",
    "friction_profile": "solve",
    "DrillSession": "session",
    "DrillSnapshot": "session",
    "ControllerRecommendations": "tuning",
    "PresetRecommendation": "tuning",
    "StringNumbers": "tuning",
    "recommend_controllers": "tuning",
}

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
    "DrillSession",
    "DrillSnapshot",
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


if not TYPE_CHECKING:

    def __getattr__(name: str) -> Any:
        if name in _LAZY:
            import importlib

            value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
            globals()[name] = value
            return value
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(globals()) | set(_LAZY))
