"""Controller presets and the tuning helper: the gains each preset (``stiff``,
``soft_torque``, ``z_torque``) gives a configuration's string, computed by the core
(``drillstring_core::drilling::tuning``, where the rules and their sources are documented).

>>> import drillstring as ds
>>> rec = ds.recommend_controllers("examples/on-bottom-3000m.toml")      # doctest: +SKIP
>>> rec["soft_torque"].controller["kp"]                                 # doctest: +SKIP
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Union

from .. import _core
from .config import DrillConfig
from .solve import _config

__all__ = ["ControllerRecommendations", "PresetRecommendation", "StringNumbers", "recommend_controllers"]


@dataclass(frozen=True)
class StringNumbers:
    """What the tuning rules take from a configuration."""

    impedance: float
    """Characteristic impedance of the top section ``J sqrt(G rho)``, N m s."""
    first_mode_hz: float
    """First natural frequency of the string (top fixed, bit free or with the BHA), Hz."""
    top_drive_inertia: float
    """Top-drive inertia, kg m^2."""
    stiffness: float
    """Static torsional stiffness of the whole string ``1 / sum L / (G J)``, N m/rad."""

    def line(self) -> str:
        """The numbers as ``drillstring tune`` prints them."""
        return (f"string: Z = {self.impedance:.4g} N m s (top section), f1 = {self.first_mode_hz:.4g} Hz, "
                f"I_TD = {self.top_drive_inertia:.4g} kg m^2, k = {self.stiffness:.4g} N m/rad")


@dataclass(frozen=True)
class PresetRecommendation:
    """One preset's settings for a string and what they give."""

    preset: str
    """``"stiff"``, ``"soft_torque"`` or ``"z_torque"``."""
    controller: Mapping[str, Any]
    """The ``top_drive.controller`` table the preset sets (``type``, ``preset``, ``kp`` N m s/rad,
    ``ki`` N m/rad, ``tuning_frequency`` Hz or None, ``z_factor``, ``torque_highpass_time`` s)."""
    damping: float
    """The damping the top drive presents to torque waves, N m s."""
    reflection: float
    """The reflection coefficient of a torque wave at the top, ``(c - Z) / (c + Z)``."""
    speed_bandwidth_hz: float
    """``stiff``, ``soft_torque``: the speed loop's bandwidth ``kp / (2 pi I_TD)``, Hz (NaN for ``z_torque``)."""
    windup_speed_ratio: float
    """``z_torque``: the fraction of the setpoint the top turns at while the string winds up (NaN otherwise)."""
    rule: str
    """The rule with its numbers."""

    def line(self) -> str:
        """One line: the settings with their units, the rule and what it gives."""
        extra = [f"reflection {self.reflection:.2f}"]
        if not math.isnan(self.speed_bandwidth_hz):
            extra.append(f"speed loop {self.speed_bandwidth_hz:.3g} Hz")
        if not math.isnan(self.windup_speed_ratio):
            extra.append(f"top at {100 * self.windup_speed_ratio:.0f} % of the setpoint while winding up")
        return (f"{self.preset}: top_drive.controller.type = {self.controller['type']}; {self.rule}; "
                + ", ".join(extra))


@dataclass(frozen=True)
class ControllerRecommendations:
    """The recommended settings of every preset for one string (:func:`recommend_controllers`);
    ``rec["z_torque"]`` is one preset's."""

    string: StringNumbers
    presets: tuple[PresetRecommendation, ...]

    def __getitem__(self, preset: str) -> PresetRecommendation:
        for p in self.presets:
            if p.preset == preset:
                return p
        raise KeyError(preset)

    def lines(self, units: str = "si") -> list[str]:
        """What ``drillstring tune`` prints: the string's numbers, then one line per preset. With
        ``units="field"`` each SI quantity is followed by its field value (``14825 N m s/rad
        (10935 ft-lbf s/rad)``; :func:`drillstring.drilling.units.annotate`); the gains a
        configuration takes are the SI ones either way (or write them with their unit)."""
        from .units import annotate

        return [annotate(line, units) for line in (self.string.line(), *(p.line() for p in self.presets))]


def recommend_controllers(
        config: Union[DrillConfig, Mapping[str, Any], str, os.PathLike[str]]) -> ControllerRecommendations:
    """The gains of every controller preset for ``config``'s string, and the numbers they were
    computed from (``_core.recommend_controllers``). Set one with
    ``top_drive.controller.preset = "soft_torque"`` (or ``--set top_drive.controller.preset=...``).

    Raises
    ------
    ValidationError
        A configuration the core refuses.
    """
    raw = _core.recommend_controllers(_config(config).to_json())
    presets = tuple(
        PresetRecommendation(preset=p["preset"], controller=dict(p["controller"]), damping=p["damping"],
                             reflection=p["reflection"], speed_bandwidth_hz=p["speed_bandwidth_hz"],
                             windup_speed_ratio=p["windup_speed_ratio"], rule=p["rule"])
        for p in raw["presets"])
    return ControllerRecommendations(string=StringNumbers(**raw["string"]), presets=presets)
