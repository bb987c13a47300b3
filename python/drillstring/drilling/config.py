"""Configuration of the drilling-system simulator: frozen dataclasses, TOML, ``--set`` overrides.

A :class:`DrillConfig` mirrors the configuration of the Rust core (``drillstring_core::drilling``):
the string as :class:`StringSection` s from the top, the :class:`Well` survey, the side-wall
:class:`Friction`, the :class:`TopDrive` and its :class:`Controller`, the :class:`Bit`, the
:class:`Numerics` and where the stick-slip metrics are measured (:class:`MetricsConfig`). SI units;
angles in degrees and speeds in rpm where the field name says so. Any number may be given as a
string with a unit (``"5 in"``, ``"18 klbf"``), and ``units = "field"`` in a document makes plain
numbers field units (:mod:`drillstring.drilling.units`, ``docs/units.md``); they are converted to
SI before the core sees them. :func:`config_schema` is the reference of every key.

Every default and every allowed range lives once, in Rust: the dataclass defaults are read from
``_core.drill_defaults()``, and constructing a :class:`DrillConfig` sends it to
``_core.drill_validate``, which fills what is unset and refuses a bad value with a
:class:`~drillstring.errors.ValidationError` naming the dotted field (``sections[1].outer_diameter``,
``top_drive.controller.kp``; an unknown key lists the allowed ones, a value of the wrong type says
what the field takes). :meth:`DrillConfig.with_overrides` sets its dotted keys in the core too
(``_core.drill_config_override``), as the stick-slip maps set their axes. Python only builds the
dataclasses from the core's normalised output. A :class:`DrillConfig` is therefore always valid
and normalised.

TOML (``examples/on-bottom-3000m.toml``)::

    damping_rate = 0.0            # top-level scalars first
    nonlinearity = "linear"       # or "consistent" (finite-strain torque-twist law)

    [[sections]]                  # one table per section, from the top
    name = "drill pipe"
    length = 3000.0
    outer_diameter = 0.127
    inner_diameter = 0.1086

    [well]
    md = [0.0, 500.0, 1600.0, 4000.0]
    inclination_deg = [0.0, 0.0, 60.0, 60.0]

    [top_drive]
    rpm = 40.0

    [top_drive.controller]
    type = "pi"
"""

from __future__ import annotations

import copy as _copy
import dataclasses
import json
import math
import os
import re
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional, Union

import tomlkit

from .. import _core
from ..errors import ValidationError
from ..io.toml import toml_line, toml_string
from ..limits import json_ready
from . import units as _units

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = [
    "Autodriller",
    "Bit",
    "Change",
    "Controller",
    "Detournay",
    "DrillConfig",
    "Friction",
    "Hoist",
    "MetricsConfig",
    "Numerics",
    "StringSection",
    "TopDrive",
    "TorqueDragConfig",
    "Weakening",
    "Well",
    "config_schema",
    "defaults",
    "load_drill_config",
]

PathLike = Union[str, "os.PathLike[str]"]

#: The default configuration of the core (``_core.drill_defaults()``), as JSON values.
_DEFAULTS: dict[str, Any] = _core.drill_defaults()


def defaults() -> dict[str, Any]:
    """The core's default configuration as a plain dict (a fresh copy): what every unset field takes."""
    return _core.drill_defaults()


def config_schema() -> dict[str, _core.ConfigKeyDoc]:
    """The reference of the configuration: every key by dotted path (``sections[].outer_diameter``,
    ``top_drive.controller.kp``, ``bit.weight_on_bit``; ``[]`` stands for any index of a list,
    ``top_drive.steps[][0]`` for the first entry of each pair), sorted by path. Each entry is a
    dict with exactly:

    ``type``
        ``"number"``, ``"integer"``, ``"string"``, ``"boolean"``, ``"array"`` or ``"table"``;
    ``unit``
        the SI unit of a number (or of each number of a list) as pint parses it (``"m"``,
        ``"N*m"``, ``"kg/m^3"``, ``"deg/(30 m)"``; ``""`` dimensionless), None otherwise;
    ``label``
        a short name of the quantity for axes (``"weight on bit"``);
    ``default``
        the default as a JSON value, None when the key is required, computed (the description
        says how) or a table;
    ``description``
        what the key means, its allowed range in words and what null means.

    The core derives it from its configuration structs (``_core.drill_config_schema()``): the
    keys, types and defaults from the structs, the descriptions from their doc comments. The one
    key read here and not by the core, ``units`` (the unit system of plain numbers,
    :mod:`drillstring.drilling.units`), is added.
    """
    schema = _core.drill_config_schema()
    schema["units"] = {
        "type": "string", "unit": None, "label": "unit system", "default": "si",
        "description": "The unit of plain numbers: si (SI, angles in degrees, speeds in rpm) or field (ft, in for "
                       "diameters, klbf, ft-lbf, ppg, psi, deg/100ft; see docs/units.md); a string with a unit "
                       "(\"5 in\") is read in its own unit either way. One of: si, field.",
    }
    return dict(sorted(schema.items()))


def _frozen(value: Any) -> Any:
    """JSON lists as tuples (hashable dataclass defaults)."""
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    return value


def _section_defaults() -> Mapping[str, Any]:
    sections = _DEFAULTS.get("sections") or [{}]
    return sections[0] if isinstance(sections[0], Mapping) else {}


def _default(table: Optional[str], key: str, *, kind: str) -> Any:
    """A dataclass field whose default is the core's (``table.key`` of :func:`defaults`; ``table``
    ``"sections"`` reads the first default section; no default when the core has none). Its unit
    and description are the core's schema's (:func:`config_schema`), never declared here;
    ``kind`` is how :meth:`DrillConfig.from_dict` builds its value."""
    if table == "sections":
        source: Mapping[str, Any] = _section_defaults()
    elif table is None:
        source = _DEFAULTS
    else:
        source = _DEFAULTS
        for part in table.split("."):
            source = source.get(part) or {}
        if not source:  # an optional table unset by default (``hoist``): its keys' defaults
            source = {k[len(table) + 1:]: v["default"] for k, v in _core.drill_config_schema().items()
                      if k.startswith(table + ".") and "." not in k[len(table) + 1:]}
    metadata = {"kind": kind}
    if key not in source:
        return field(metadata=metadata)
    return field(default=_frozen(source[key]), metadata=metadata)


# --------------------------------------------------------------------------- the dataclasses


@dataclass(frozen=True)
class StringSection:
    """One section of the string (drill pipe, heavy-weight pipe, collars), listed from the top.

    The polar moment ``J`` and area ``A`` follow from the diameters (``pi/32 (OD^4 - ID^4)``,
    ``pi/4 (OD^2 - ID^2)``) unless given; the friction lever arm is ``contact_diameter / 2``
    (default the tool joints' outer diameter when the section has tool joints, else the outer
    diameter). Unset fields take the core's defaults.
    """

    length: float = field(metadata={"kind": "float"})
    """Measured length of the section, m (required)."""
    outer_diameter: float = field(metadata={"kind": "float"})
    """Outer diameter, m (required)."""
    inner_diameter: float = field(metadata={"kind": "float"})
    """Inner diameter, m (required)."""
    name: str = _default("sections", "name", kind="str")
    """A label for tables and plots."""
    shear_modulus: float = _default("sections", "shear_modulus", kind="float")
    """Shear modulus G, Pa."""
    density: float = _default("sections", "density", kind="float")
    """Density of the steel, kg/m^3."""
    contact_diameter: Optional[float] = _default("sections", "contact_diameter", kind="float?")
    """Diameter at which the wall friction acts, m (None: the tool joints' outer diameter, else
    the outer diameter)."""
    polar_moment: Optional[float] = _default("sections", "polar_moment", kind="float?")
    """Override of the polar moment of area J, m^4 (None: from the diameters)."""
    area: Optional[float] = _default("sections", "area", kind="float?")
    """Override of the cross-section area A, m^2 (None: from the diameters)."""
    quartic_moment: Optional[float] = _default("sections", "quartic_moment", kind="float?")
    """Override of ``J4 = int r^4 dA``, m^6, which sets the ``"consistent"`` law's cubic torque
    ``k5 = M J4 / 2`` (None: ``pi/192 (OD^6 - ID^6)``, from the diameters; unused by
    ``"linear"``). A section with an overridden ``polar_moment`` needs it too."""
    poisson_ratio: float = _default("sections", "poisson_ratio", kind="float")
    """Poisson's ratio nu, ``0 < nu < 0.5``: with ``shear_modulus`` the P-wave modulus
    ``M = 2 G (1 - nu) / (1 - 2 nu)`` of the ``"consistent"`` nonlinearity (unused by ``"linear"``)."""
    grade: Optional[str] = _default("sections", "grade", kind="str?")
    """API drill-pipe grade, ``"E-75"``, ``"X-95"``, ``"G-105"`` or ``"S-135"`` (the torque and
    drag's utilisation; None: none)."""
    yield_strength: Optional[float] = _default("sections", "yield_strength", kind="float?")
    """Minimum yield strength, Pa, in place of ``grade``."""
    nominal_weight: Optional[float] = _default("sections", "nominal_weight", kind="float?")
    """Adjusted weight in air with the tool joints, N/m (field: lb/ft); None: from the tool joints
    or the body."""
    tool_joint_outer_diameter: Optional[float] = _default("sections", "tool_joint_outer_diameter",
                                                          kind="float?")
    """Tool-joint outer diameter, m; the wall friction acts at it unless ``contact_diameter`` is
    given."""
    tool_joint_inner_diameter: Optional[float] = _default("sections", "tool_joint_inner_diameter",
                                                          kind="float?")
    """Tool-joint inner diameter, m."""
    tool_joint_length: Optional[float] = _default("sections", "tool_joint_length", kind="float?")
    """Length of one tool joint (pin and box), m."""
    joint_length: Optional[float] = _default("sections", "joint_length", kind="float?")
    """Length of one joint, m (None: 9.144 m, API range 2)."""
    makeup_torque: Optional[float] = _default("sections", "makeup_torque", kind="float?")
    """Make-up torque of the tool joints, N m (None: not checked)."""


@dataclass(frozen=True)
class Well:
    """The well path and the fluid. The path is a survey of stations (measured depth,
    inclination, azimuth) joined by minimum curvature, given one of three ways: the stations
    ``md``, ``inclination_deg`` (and ``azimuth_deg``); a survey file ``survey`` (CSV with
    columns md, inc, azi; units in the header as ``md_m``/``md_ft``, ``inc_deg``/``inc_rad``,
    default m and degrees); or a ``plan`` of segments. One inclination number without ``md`` is
    a straight hole. A survey shorter than the string is refused unless ``extend`` is true."""

    md: Optional[tuple[float, ...]] = _default("well", "md", kind="floats?")
    """Measured depths of the survey stations, m (None with a constant inclination)."""
    inclination_deg: Union[float, tuple[float, ...]] = _default("well", "inclination_deg",
                                                                kind="float|floats")
    """Inclination at each station, degrees (one number: constant, without ``md``)."""
    mud_density: float = _default("well", "mud_density", kind="float")
    """Mud density for buoyancy, kg/m^3 (0: none)."""
    gravity: float = _default("well", "gravity", kind="float")
    """Acceleration of gravity, m/s^2."""
    azimuth_deg: Union[float, tuple[float, ...]] = _default("well", "azimuth_deg", kind="float|floats")
    """Azimuth, degrees clockwise from north: one number for every station, or one per ``md``
    station (with a plan: the azimuth of its first build)."""
    survey: Optional[str] = _default("well", "survey", kind="str?")
    """A survey file (CSV) in place of the stations; in a TOML file, relative to that file."""
    plan: Optional[tuple[Mapping[str, float], ...]] = _default("well", "plan", kind="tables?")
    """A plan in place of the stations, from the surface: ``{hold = m}``, ``{build = deg/30 m,
    inclination = deg}``, ``{drop = deg/30 m, inclination = deg}``, ``{turn = deg/30 m (positive
    clockwise), azimuth = deg}``; e.g. a J well ``[{hold = 500}, {build = 3, inclination = 60},
    {hold = 2000}]``."""
    extend: bool = _default("well", "extend", kind="bool")
    """Continue a survey shorter than the string straight on from its last station (default:
    refuse it)."""
    hole_diameter: Optional[float] = _default("well", "hole_diameter", kind="float?")
    """Open-hole diameter, m (field: in), below ``hole_sections``: the torque and drag's
    buckling (None: buckling not evaluated)."""
    hole_sections: tuple[Mapping[str, float], ...] = _default("well", "hole_sections", kind="tables")
    """Casing and hole sections from the surface, ``{bottom_md, diameter, friction}`` (friction
    optional). In TOML: ``[[well.hole_sections]]`` tables."""


@dataclass(frozen=True)
class Friction:
    """Coulomb friction between the string and the wall: the static limit per metre is the
    friction factor times the contact radius times the normal force per metre, the soft-string
    one of the torque-and-drag solution (``contact = "soft_string"``: buoyed weight and tension
    times curvature) or the buoyed weight times sin(inclination) (``"weight"``, Aarsnes & Shor)."""

    static: float = _default("friction", "static", kind="float")
    """Static friction coefficient."""
    kinetic_ratio: float = _default("friction", "kinetic_ratio", kind="float")
    """Kinetic over static friction."""
    stick_speed: float = _default("friction", "stick_speed", kind="float")
    """Speed below which a cell sticks (Aarsnes-Shor ``o_thres``), rad/s."""
    model: str = _default("friction", "model", kind="str")
    """``"set_valued"`` (stick / slip switch) or ``"regularised"`` (smooth, ``tanh``-like)."""
    regularisation_speed: float = _default("friction", "regularisation_speed", kind="float")
    """Speed scale of the regularised model, rad/s."""
    contact: str = _default("friction", "contact", kind="str")
    """The normal force of the friction limit: ``"soft_string"`` (default; rotating off bottom,
    or on bottom with the weight on bit) or ``"weight"`` (Aarsnes & Shor 2018, eq. 6)."""
    intervals: tuple[Mapping[str, float], ...] = _default("friction", "intervals", kind="tables")
    """Static friction factors over depth intervals, ``{top_md, bottom_md, static}`` (cased and
    open hole); ``static`` applies elsewhere. In TOML: ``[[friction.intervals]]`` tables."""
    coupling: str = _default("friction", "coupling", kind="str")
    """A coupled run's (``[hoist]``) wall friction: ``"axial_torsional"`` (default; against the
    sliding velocity, axial speed and contact radius times angular speed, on both fields with one
    stick phase: a rotating string slides axially with little drag) or ``"torsion_only"`` (the
    torsional field alone, the coupled runs before this key). No effect without a hoist."""


@dataclass(frozen=True)
class Controller:
    """The top-drive speed controller."""

    type: str = _default("top_drive.controller", "type", kind="str")
    """``"pi"``, ``"soft_torque"``, ``"z_torque"`` or ``"speed"`` (ideal speed source)."""
    kp: float = _default("top_drive.controller", "kp", kind="float")
    """``pi``: proportional gain, N m s/rad: motor torque per rad/s of speed error, the damping the
    top drive presents to the string (``kp >> Z``, the pipe's impedance: a stiff top that reflects
    torque waves; ``kp = Z``: a matched one that absorbs them). ``soft_torque``: ``z_factor Z``."""
    ki: float = _default("top_drive.controller", "ki", kind="float")
    """``pi``: integral gain, N m/rad: motor torque per radian of accumulated speed error (a spring
    to the setpoint's angle). ``soft_torque``: ``(2 pi f)^2 I_TD``, cancelling the top-drive inertia
    at the tuning frequency ``f``."""
    tuning_frequency: Optional[float] = _default("top_drive.controller", "tuning_frequency",
                                                 kind="float?")
    """Soft-torque tuning frequency, Hz (None: the string's first mode)."""
    z_factor: float = _default("top_drive.controller", "z_factor", kind="float")
    """Soft-torque / Z-torque damping as a multiple of the top section's impedance ``J sqrt(G rho)``
    (default 4: Simulator4nDOF's published SoftTorque gain ``4 Z`` and ZTorque factor ``0.25``)."""
    torque_highpass_time: float = _default("top_drive.controller", "torque_highpass_time", kind="float")
    """Z-torque: time constant of the low-pass that takes the mean string torque out of the
    impedance feedback, s."""
    preset: Optional[str] = _default("top_drive.controller", "preset", kind="str?")
    """A named tuning, ``"stiff"``, ``"soft_torque"`` or ``"z_torque"``: fills in ``type`` and the
    gains from the string when the configuration is read (:func:`~drillstring.recommend_controllers`
    shows them); keys given beside it keep their values. None: the keys as given."""


@dataclass(frozen=True)
class TopDrive:
    """The top drive: its inertia, torque limit, speed setpoint and controller."""

    inertia: float = _default("top_drive", "inertia", kind="float")
    """Rotor inertia, kg m^2."""
    torque_limit: float = _default("top_drive", "torque_limit", kind="float")
    """Largest motor torque, N m, for every controller. Default 60 kN m, the continuous rating of a
    large top drive; a run warns when the string's static torque exceeds it. A very large value
    (1e12) for no limit."""
    rpm: float = _default("top_drive", "rpm", kind="float")
    """Speed setpoint, rpm."""
    ramp_time: float = _default("top_drive", "ramp_time", kind="float")
    """Time constant of the first-order approach of the setpoint from 0, s (0: a step)."""
    steps: tuple[tuple[float, float], ...] = _default("top_drive", "steps", kind="pairs")
    """Setpoint changes ``(time s, rpm)``."""
    controller: Controller = field(default_factory=Controller, metadata={"kind": "table"})
    """The speed controller."""
    control_interval: float = _default("top_drive", "control_interval", kind="float")
    """Zero-order-hold period of the controller, s."""
    motor_bandwidth: float = _default("top_drive", "motor_bandwidth", kind="float")
    """``speed`` and ``z_torque``: bandwidth of the motor's speed loop, Hz. The top speed follows
    the speed these controllers ask for as a first-order lag of time constant
    ``1 / (2 pi motor_bandwidth)``, so that the motor torque is a real drive's and converges as
    the grid is refined."""
    mode: str = _default("top_drive", "mode", kind="str")
    """What drives the top: ``"controller"`` (default; the controller follows the setpoint) or
    ``"measured_speed"`` (the top speed is ``speed_series``, imposed exactly; the motor torque is
    the torque that imposes it, the top-drive inertia's acceleration torque plus the string torque
    at the top; controller, setpoint and torque limit unused)."""
    speed_series: tuple[tuple[float, float], ...] = _default("top_drive", "speed_series",
                                                             kind="pairs")
    """``measured_speed``: the top-drive speed ``(time s, rpm)``, linearly interpolated; times
    strictly increasing, covering ``0 .. numerics.duration``."""


@dataclass(frozen=True)
class Bit:
    """The bit: off bottom (free end) or on bottom with a velocity-weakening bit-rock torque
    ``T = W r (mu_k + (mu_s - mu_k) exp(-decay |w|)) sign(w)``."""

    on_bottom: bool = _default("bit", "on_bottom", kind="bool")
    """Whether the bit cuts (bit-rock torque) or hangs free."""
    weight_on_bit: float = _default("bit", "weight_on_bit", kind="float")
    """Weight on bit W, N."""
    radius: float = _default("bit", "radius", kind="float")
    """Bit radius r, m."""
    mu_static: float = _default("bit", "mu_static", kind="float")
    """Static bit-rock friction coefficient."""
    mu_kinetic: float = _default("bit", "mu_kinetic", kind="float")
    """Kinetic bit-rock friction coefficient."""
    decay: float = _default("bit", "decay", kind="float")
    """Velocity-weakening rate, 1/(rad/s)."""
    stick_speed: float = _default("bit", "stick_speed", kind="float")
    """Speed below which the bit sticks, rad/s."""
    bha_inertia: float = _default("bit", "bha_inertia", kind="float")
    """Extra lumped inertia at the bit, kg m^2."""
    diameter: Optional[float] = _default("bit", "diameter", kind="float?")
    """Bit diameter, m, in place of ``radius`` (giving both is refused). The configuration is
    normalised to the radius: after construction this is None and ``radius`` half the diameter."""
    law: str = _default("bit", "law", kind="str")
    """The bit-rock law: ``"velocity_weakening"`` (the default, the torque above at
    ``weight_on_bit``, torsion only), ``"detournay"`` (the Detournay law of ``detournay`` with the
    depth of cut per revolution ``2 pi v / omega`` of the bit's speeds) or ``"rgd"`` (the same law
    with the regenerative depth of cut, one blade pass back) or ``"detournay_weakening"`` (the
    Detournay law of the rate form with the wear flats' friction falling with the bit's speed,
    :class:`Weakening`). The laws but ``velocity_weakening`` need a :class:`Hoist` (the coupled
    axial-torsional run) and the reverse."""
    detournay: Detournay = field(default_factory=lambda: Detournay(),
                                 metadata={"kind": "table"})
    """The Detournay law's rock and bit parameters (the radius is ``radius``)."""
    weakening: Weakening = field(default_factory=lambda: Weakening(),
                                 metadata={"kind": "table"})
    """The wear flats' velocity weakening of ``law = "detournay_weakening"``."""
    bha_mass: float = _default("bit", "bha_mass", kind="float")
    """Lumped mass at the bit on the axial field of a coupled run, kg (0: none): its inertia and
    its buoyed weight along the hole, carried by the string's initial static tension."""


@dataclass(frozen=True)
class Detournay:
    """The Detournay cutting + frictional-contact law (Richard, Germay & Detournay 2007):
    cutting ``W_c = a zeta eps d``, ``T_c = a^2 eps d / 2``, contact ``W_f <= a l sigma``,
    ``T_f = gamma mu a W_f / 2`` (``a`` the bit radius, ``d`` the depth of cut per revolution).
    Defaults: Aarsnes & van de Wouw (2019)."""

    blades: int = _default("bit.detournay", "blades", kind="int")
    """Number of blades n."""
    intrinsic_specific_energy: float = _default("bit.detournay", "intrinsic_specific_energy", kind="float")
    """Intrinsic specific energy of the rock eps, Pa."""
    cutting_ratio: float = _default("bit.detournay", "cutting_ratio", kind="float")
    """Ratio zeta of the vertical to the horizontal cutting force."""
    contact_strength: float = _default("bit.detournay", "contact_strength", kind="float")
    """Contact strength sigma under the wear flats, Pa."""
    wear_flat_length: float = _default("bit.detournay", "wear_flat_length", kind="float")
    """Total wear-flat length l, m."""
    friction: float = _default("bit.detournay", "friction", kind="float")
    """Wear-flat/rock friction coefficient mu."""
    geometry: float = _default("bit.detournay", "geometry", kind="float")
    """Bit geometry factor gamma (1: flat profile)."""
    cut_surface: str = _default("bit.detournay", "cut_surface", kind="str")
    """The regenerative depth of cut of ``law = "rgd"``: ``"exact_delay"`` (the bit's position one
    blade angle back) or ``"upwind"`` (Aarsnes & van de Wouw's first-order upwind cut surface on
    ``cut_surface_cells`` cells)."""
    cut_surface_cells: int = _default("bit.detournay", "cut_surface_cells", kind="int")
    """Cells of the ``upwind`` cut surface over one blade angle."""


@dataclass(frozen=True)
class Weakening:
    """The wear flats' friction of ``bit.law = "detournay_weakening"``, falling with the bit's
    speed ``w``: ``mu(w) = mu + (mu_0 - mu) exp(-decay |w|)``, ``mu`` the kinetic
    ``bit.detournay.friction`` (Detournay & Defourny 1992 with the velocity weakening of
    Navarro-Lopez & Cortes 2007)."""

    static_friction: float = _default("bit.weakening", "static_friction", kind="float")
    """Friction coefficient mu_0 of a bit at rest, at least ``bit.detournay.friction``."""
    decay: float = _default("bit.weakening", "decay", kind="float")
    """Rate of the friction's fall with the bit's speed, s/rad."""


@dataclass(frozen=True)
class Hoist:
    """The hoist at the top of the string; with one, a run is coupled axial-torsional with the
    bit on bottom (``bit.law`` ``"detournay"`` or ``"rgd"``)."""

    mode: str = _default("hoist", "mode", kind="str")
    """``"velocity"`` (the block velocity ``speed``), ``"hook_load"`` (the force ``hook_load``
    holding the string up), ``"weight_on_bit"`` (the hook load held at the static hook load of
    the string hanging off bottom less ``weight_on_bit``, as a rig's weight indicator reads it) or
    ``"autodriller"`` (the block velocity of the PI :class:`Autodriller`)."""
    speed: float = _default("hoist", "speed", kind="float")
    """Block velocity, m/s, down positive."""
    hook_load: float = _default("hoist", "hook_load", kind="float")
    """Hook load of ``hook_load`` mode, N."""
    weight_on_bit: float = _default("hoist", "weight_on_bit", kind="float")
    """Weight on bit of ``weight_on_bit`` mode, N (ramped from 0 with ``ramp_time``)."""
    ramp_time: float = _default("hoist", "ramp_time", kind="float")
    """Time constant of the setpoint's approach (the block velocity from 0, the hook load from the
    static hook load, the weight on bit from 0), s (0: a step)."""
    steps: tuple[tuple[float, float], ...] = _default("hoist", "steps", kind="pairs")
    """Changes of the mode's target ``(time s, value)`` at increasing times, approached with
    ``ramp_time`` like the top drive's ``steps``: the block velocity (m/s), the hook load (N) or
    the autodriller's setpoint (N or m/s) by ``mode``; plain numbers are in the document's unit
    system (field: ft/h, klbf), a string with a unit must be of the mode's dimension."""
    autodriller: Autodriller = field(default_factory=lambda: Autodriller(),
                                     metadata={"kind": "table"})
    """The autodriller of ``mode = "autodriller"``."""


@dataclass(frozen=True)
class Autodriller:
    """The autodriller (``hoist.mode = "autodriller"``): a PI on the weight on bit or the rate of
    penetration giving the block velocity, ``u = u_ff + kp e + ki int e`` within
    ``[min_speed, max_speed]`` (no integration while saturated in the error's direction), ``e`` the
    setpoint less the measured value, ``u_ff`` the setpoint itself with ``target = "rop"``.
    ``kp`` and ``ki`` are not both 0 (refused: the block would not answer)."""

    target: str = _default("hoist.autodriller", "target", kind="str")
    """``"weight_on_bit"`` (default) or ``"rop"``."""
    setpoint: float = _default("hoist.autodriller", "setpoint", kind="float")
    """The target's setpoint: N (``weight_on_bit``) or m/s (``rop``); a plain number is in the
    document's unit system (field: klbf or ft/h), a string with a unit (``"18 klbf"``,
    ``"60 ft/h"``) of the target's dimension is converted."""
    kp: float = _default("hoist.autodriller", "kp", kind="float")
    """Proportional gain: (m/s)/N on the weight on bit, dimensionless on ROP."""
    ki: float = _default("hoist.autodriller", "ki", kind="float")
    """Integral gain: (m/s)/(N s) on the weight on bit, 1/s on ROP."""
    min_speed: float = _default("hoist.autodriller", "min_speed", kind="float")
    """Least block velocity, m/s, down positive (negative: the block may pull up)."""
    max_speed: float = _default("hoist.autodriller", "max_speed", kind="float")
    """Largest block velocity, m/s (default 100 m/h)."""


@dataclass(frozen=True)
class Numerics:
    """Grid, duration and output sampling."""

    cells: int = _default("numerics", "cells", kind="int")
    """Cells along the whole string."""
    duration: float = _default("numerics", "duration", kind="float")
    """Simulated time, s."""
    output_interval: float = _default("numerics", "output_interval", kind="float")
    """Spacing of the time series, s."""
    field_interval: float = _default("numerics", "field_interval", kind="float")
    """Spacing of the space-time snapshots, s (0: none)."""
    max_cells: int = _default("numerics", "max_cells", kind="int")
    """Largest ``cells`` accepted (a guard against typos)."""
    max_shear_strain: float = _default("numerics", "max_shear_strain", kind="float")
    """``"consistent"`` only: the largest shear strain at the outer surface the time step is made
    for (Courant number <= 1 at the tangent wave speed of that strain); a run exceeding it says so
    in its message and ``stats["courant_peak"]`` > 1."""
    courant: float = _default("numerics", "courant", kind="float")
    """The Courant number ``c dt / h`` the step is made for, in (0, 1]: the step is this fraction
    of the grid's Courant-1 step, the cells unchanged (1: the exact shift; below 1 the upwind
    transport diffuses, reported as ``upwind_loss``)."""
    source_speed: str = _default("numerics", "source_speed", kind="str")
    """The speed of a cell its sources (friction threshold and direction, damping) are evaluated
    at: ``"after_transport"`` (default) or ``"before_transport"`` (the speed at the step start,
    the scheme of Aarsnes & Shor's torsionalWaveStep.m, to reproduce their published runs; both
    converge with the grid)."""
    initial_state: str = _default("numerics", "initial_state", kind="str")
    """Where a coupled run starts: ``"rest"`` (default; the string at rest under its static
    tension, the setpoints ramping up) or ``"steady"`` (the bit law's steady drilling at the
    setpoints of t = 0, where Aarsnes & van de Wouw's code starts: the string turning at the
    top-drive speed with the torque of steady rotation, moving down at the hoist's rate,
    compressed to the steady weight on bit, the bit at its steady depth of cut)."""
    energy_balance: bool = _default("numerics", "energy_balance", kind="bool")
    """Whether the run keeps its energy ledger (default True). False gives a faster step and
    every energy output NaN, with a warning saying so; the series, snapshots and metrics are bit
    for bit those of the run with the ledger."""


@dataclass(frozen=True)
class MetricsConfig:
    """Where and how the stick-slip metrics are measured."""

    window: Optional[tuple[float, float]] = _default("metrics", "window", kind="pair?")
    """``(t_start, t_end)`` of the metrics window, s (None: the last half of the run)."""
    stick_speed: float = _default("metrics", "stick_speed", kind="float")
    """The bit counts as stuck at or below this speed, rad/s."""


@dataclass(frozen=True)
class TorqueDragConfig:
    """The static torque-and-drag analysis (``drillstring torque-drag``)."""

    bit_torque: float = _default("torque_drag", "bit_torque", kind="float")
    """Torque on bit when drilling (rotating on bottom), N m."""
    block_weight: float = _default("torque_drag", "block_weight", kind="float")
    """Travelling block, hook and top drive, added to every hook load, N."""
    step: float = _default("torque_drag", "step", kind="float")
    """The longest element of the stepped solution, m."""
    friction_factors: tuple[float, ...] = _default("torque_drag", "friction_factors", kind="floats")
    """The friction factors of the broomstick plot (each uniform along the hole)."""
    broomstick_points: int = _default("torque_drag", "broomstick_points", kind="int")
    """Bit depths of the broomstick plot, evenly spaced to the string's length."""


def _table(cls: type) -> Any:
    return field(default_factory=cls, metadata={"kind": "table"})


@dataclass(frozen=True)
class Change:
    """A value changed during a run (``[[changes]]``, what a :class:`~drillstring.drilling.session.DrillSession`'s
    changes replay as): from the step starting at the step boundary nearest ``time`` on, ``key``
    (one of the keys that may change during a run, ``DrillSession.settable``) is ``value`` (SI)."""

    time: float
    """Time the change takes effect from, s, in [0, numerics.duration]."""
    key: str
    """The dotted key changed (``top_drive.rpm``, ``friction.static``, ``hoist.weight_on_bit``, ...)."""
    value: Any
    """The new value, as the key takes it in the configuration."""


@dataclass(frozen=True)
class DrillConfig:
    """A whole drilling system: string, well, friction, top drive, bit and numerics.

    Constructing one validates and normalises it in the core: every unset field takes the
    core's default and a bad value raises :class:`~drillstring.errors.ValidationError` naming
    the dotted field. Sub-tables may be given as the dataclasses or as mappings
    (``DrillConfig(sections=[{"length": 1000.0}], top_drive={"rpm": 60.0})``).

    Build one from TOML with :func:`load_drill_config`, from a dict with :meth:`from_dict`;
    change fields with :meth:`with_overrides` (``["top_drive.rpm=60"]``) or
    :func:`dataclasses.replace`.
    """

    sections: tuple[StringSection, ...]
    """The string from the top (at least one section)."""
    well: Well = _table(Well)
    friction: Friction = _table(Friction)
    damping_rate: float = _default(None, "damping_rate", kind="float")
    """Viscous damping rate c, 1/s: force ``-rho J c omega`` per unit length."""
    nonlinearity: str = _default(None, "nonlinearity", kind="str")
    """The torque-twist law: ``"linear"`` (``tau = G J eps``, the default) or ``"consistent"``
    (finite strain, ``tau = k2 eps + k5 eps^3``, ``k5 = M J4 / 2``; a first-order Godunov scheme)."""
    top_drive: TopDrive = _table(TopDrive)
    bit: Bit = _table(Bit)
    numerics: Numerics = _table(Numerics)
    metrics: MetricsConfig = _table(MetricsConfig)
    torque_drag: TorqueDragConfig = _table(TorqueDragConfig)
    hoist: Optional[Hoist] = field(default=None, metadata={"kind": "table?"})
    """The hoist: None (the default) for a torsion-only run, else the coupled axial-torsional run."""
    changes: tuple[Change, ...] = field(default=(), metadata={"kind": "changes"})
    """Values changed during the run (``[[changes]]``), in time order of effect."""

    #: The unit system of plain numbers given to this configuration after it was read (see :attr:`units`).
    _units = "si"

    def __post_init__(self) -> None:
        plain = _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self)})
        normal = _core.drill_validate(_core_json(_units.to_si(plain)))
        for name, value in _from_core(type(self), normal).items():
            object.__setattr__(self, name, value)

    @property
    def units(self) -> str:
        """The unit system the configuration was written in: ``"field"`` when its document said
        ``units = "field"`` (:meth:`from_dict`, :func:`load_drill_config`), else ``"si"``. The
        numbers it holds are SI either way (equal configurations compare equal whatever their
        systems); the system says how plain numbers given to it later are read
        (:meth:`with_overrides`, a stick-slip map's axes, the bounds of a fit) and in which units
        the commands report on it. :meth:`with_units` changes it; :meth:`with_overrides` keeps
        it; the constructor and :func:`dataclasses.replace` give ``"si"`` (their plain numbers are
        SI)."""
        return self._units

    def with_units(self, system: str) -> DrillConfig:
        """The same configuration (the same SI numbers) with :attr:`units` ``system`` (``"si"``
        or ``"field"``): the unit system of plain numbers given to it later and of its reports.

        Raises
        ------
        ValidationError
            An unknown system, naming ``units``.
        """
        system = _units.system_of(system)
        copy = _copy.copy(self)
        object.__setattr__(copy, "_units", system)
        return copy

    @classmethod
    def _from_core(cls, normal: Union[str, Mapping[str, Any]]) -> DrillConfig:
        """The config of the core's normalised configuration ``normal`` (JSON or its dict)."""
        return cls(**_from_core(cls, json.loads(normal) if isinstance(normal, str) else normal))


    # ------------------------------------------------------------------ dicts and JSON

    @property
    def length(self) -> float:
        """Total measured length of the string, m (the sum of the section lengths)."""
        return math.fsum(s.length for s in self.sections)

    def to_dict(self) -> dict[str, Any]:
        """The configuration as nested plain dicts and lists (unset optional fields are ``None``),
        JSON-ready; :meth:`from_dict` of it gives an equal config."""
        return _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self)})

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON, unset optional fields left out: what the core receives."""
        return json.dumps(_unset_left_out(self.to_dict()), allow_nan=False)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: Optional[str] = None) -> DrillConfig:
        """Builds a config from nested mappings (a parsed TOML or JSON document). A top-level
        ``units`` (``"si"``, the default, or ``"field"``) sets the unit of plain numbers; strings
        with units are converted (:func:`drillstring.drilling.units.to_si`).

        Unknown keys raise :class:`~drillstring.errors.ValidationError` naming the key and listing
        the allowed ones; so do values of the wrong type and values the core refuses. ``source``
        (a file name) is attached to the error, with the line of the key when it can be found.
        """
        try:
            if not isinstance(data, Mapping):
                raise ValidationError("config", data, "a table/mapping of the configuration")
            system = _units.system_of(data.get("units", "si"))
            try:
                config = cls._from_core(_core.drill_validate(_core_json(_units.to_si(_plain(data)))))
            except ValidationError as exc:  # a field file's user reads the range in field units too
                error = _units.field_error(exc, system)
                if error is exc:
                    raise
                raise error from None
            object.__setattr__(config, "_units", system)
            return config
        except ValidationError as exc:
            if source is None or exc.source is not None:
                raise
            raise ValidationError(exc.field, exc.value, exc.allowed, source=source,
                                  line=toml_line(source, exc.field)) from exc

    # ------------------------------------------------------------------ TOML

    def to_toml(self) -> str:
        """The configuration as a TOML document, written by tomlkit (:func:`load_drill_config`
        reads it back equal; floats in their shortest exact form, so bit for bit). Unset optional
        fields are left out."""
        document = tomlkit.document()
        document.add(tomlkit.comment(
            "drillstring drilling-system configuration (SI units; angles in degrees, speeds in rpm)"))
        plain = self.to_dict()
        for key, value in plain.items():
            if not isinstance(value, (dict, list)) and value is not None:
                document.add(key, _toml_item(value))
        sections = tomlkit.aot()
        for section in plain["sections"]:
            sections.append(_toml_table(section))
        document.add("sections", sections)
        if plain.get("changes"):
            changes = tomlkit.aot()
            for change in plain["changes"]:
                changes.append(_toml_table(change))
            document.add("changes", changes)
        for key, value in plain.items():
            if isinstance(value, dict):
                document.add(key, _toml_table(value))
        return document.as_string()

    def save(self, path: Any) -> Path:
        """Writes :meth:`to_toml` to ``path`` and returns the path written (atomic replacement,
        symlinks written through, devices and ``"-"`` streamed into; see
        :mod:`drillstring.io.output`)."""
        from ..io.output import write_text

        return write_text(path, self.to_toml())

    # ------------------------------------------------------------------ overrides

    def with_overrides(self, assignments: Union[Iterable[str], Mapping[str, Any]], *,
                       units: Optional[str] = None) -> DrillConfig:
        """A copy with some fields changed, by dotted keys with indices.

        ``assignments`` is a list of ``"key=value"`` strings, as ``drillstring drill --set``
        takes them (the value is TOML: ``60``, ``3.5e4``, ``true``, ``"pi"``, ``[0, 30]``, and a
        bare word such as ``soft_torque`` is a string, ``null`` unsets an optional field such as
        ``top_drive.controller.tuning_frequency``, and a number with a unit such as ``5 in`` or
        ``"18 klbf"`` is converted to the key's SI unit), or a mapping of dotted keys to values; a
        table given for a table (``{"top_drive.controller": {"kp": 1.0}}``) is merged into it.
        Plain numbers are in the configuration's unit system (:attr:`units`: field units when its
        file says ``units = "field"``, ``5`` for ``sections[0].outer_diameter`` is then 5 in) or
        in ``units`` when given (``"si"`` or ``"field"``); the hoist's steps and the autodriller's
        setpoint take the unit of the hoist's mode and target (after these overrides), and a
        quantity of another dimension is refused. The copy keeps :attr:`units`.
        Setting ``bit.radius`` replaces a ``bit.diameter`` and the reverse.
        The core sets them (``_core.drill_config_override``, as a stick-slip map its axes). Setting
        ``well.inclination_deg`` to one number (a constant inclination) without ``well.md``
        drops the survey stations::

            cfg.with_overrides(["top_drive.rpm=60", "sections[0].length=3000", "bit.on_bottom=true"])
            cfg.with_overrides({"top_drive.controller.type": "soft_torque"})

        Raises
        ------
        ValidationError
            A malformed assignment or key (``field="--set"``), a key that is not in the
            configuration (naming it and listing the keys allowed there), an index out of
            range, or a value of the wrong type or refused by the core (naming the field; for
            a field configuration with the value and the range in field units too).
        """
        items = list(assignments.items() if isinstance(assignments, Mapping) else (
            _split_assignment(a) for a in _assignment_list(assignments)))
        system = _units.system_of(self.units if units is None else units)
        for key, _ in items:
            if not isinstance(key, str):
                raise ValidationError("--set", key, _SET_FORM)
        chosen = self.chosen_units(items)
        pairs = [[key.strip(), json_ready(_units.override_to_si(key.strip(), _plain(value), system, chosen))]
                 for key, value in items]
        try:
            config = type(self)._from_core(_core.drill_config_override(self.to_json(), json.dumps(pairs), "--set"))
        except ValidationError as exc:  # a field configuration's user reads the range in field units too
            error = _units.field_error(exc, self.units)
            if error is exc:
                raise
            raise error from None
        object.__setattr__(config, "_units", self.units)
        return config

    def chosen_units(self, overrides: Iterable[tuple[str, Any]] = ()) -> dict[str, tuple[str, str]]:
        """The SI unit of each key whose unit is its target's (the hoist's steps, the autodriller's
        setpoint and gains) as this configuration's hoist chooses it, after the ``(key, value)``
        ``overrides`` of its mode and target (:func:`drillstring.drilling.units.chosen_units`)."""
        hoist = _plain(self.hoist) if self.hoist is not None else None
        return _units.chosen_units(_units.hoist_after(hoist, [(k, _plain(v)) for k, v in overrides]))


# --------------------------------------------------------------------------- the core's JSON


_TABLES: dict[str, type] = {}  # field name -> dataclass of a sub-table (filled below)


def _from_core(cls: type, data: Mapping[str, Any]) -> dict[str, Any]:
    """The fields of ``cls`` from the core's normalised (validated) JSON ``data``: sub-tables as
    their dataclasses, lists as tuples. No checks: the core made them."""
    out: dict[str, Any] = {}
    for f in dataclasses.fields(cls):
        value = data[f.name]
        if f.name == "sections":
            out[f.name] = tuple(StringSection(**_from_core(StringSection, s)) for s in value)
        elif f.name == "changes":
            out[f.name] = tuple(Change(float(c["time"]), str(c["key"]), _frozen(c["value"])) for c in value)
        elif f.metadata.get("kind") == "table?" and value is None:
            out[f.name] = None
        elif f.metadata.get("kind") in ("table", "table?"):
            table = _TABLES[f.name]
            out[f.name] = table(**_from_core(table, value))
        else:
            out[f.name] = _frozen(value)
    return out


def _core_json(plain: Any) -> str:
    """The plain config ``plain`` as the JSON the core parses (unset fields left out)."""
    return json.dumps(_unset_left_out(json_ready(plain)), allow_nan=False)


def _unset_left_out(value: Any) -> Any:
    """The plain config without its ``None`` (unset) fields: the core fills them (an unset
    ``well.md`` with one inclination number means no survey stations)."""
    if isinstance(value, dict):
        return {k: _unset_left_out(v) for k, v in value.items() if v is not None}
    if isinstance(value, list):
        return [_unset_left_out(v) for v in value]
    return value


def _plain(value: Any) -> Any:
    """Dataclasses as dicts, tuples as lists (JSON / TOML-ready)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


_TABLES.update(detournay=Detournay, weakening=Weakening, hoist=Hoist)
_TABLES.update(autodriller=Autodriller)
_TABLES.update(well=Well, friction=Friction, top_drive=TopDrive, controller=Controller, bit=Bit, numerics=Numerics,
               metrics=MetricsConfig, torque_drag=TorqueDragConfig)


# --------------------------------------------------------------------------- TOML writing


def _toml_item(value: Any) -> Any:
    """A plain value as a tomlkit item: strings escaped (:func:`drillstring.io.toml.toml_string`),
    a list as an array, a dict as an inline table (a plan's segment, a friction interval)."""
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, list):
        array = tomlkit.array()
        array.extend(_toml_item(v) for v in value)
        return array
    if isinstance(value, dict):
        inline = tomlkit.inline_table()
        inline.update({k: _toml_item(v) for k, v in value.items() if v is not None})
        return inline
    return value  # bool, int, float (finite: validated)


def _toml_table(table: Mapping[str, Any]) -> Any:
    """A table of the configuration: its values (a section's name first), then its subtables."""
    out = tomlkit.table()
    for key in sorted(table, key=lambda k: k != "name"):
        if table[key] is not None and not isinstance(table[key], dict):
            out.add(key, _toml_item(table[key]))
    for key, value in table.items():
        if isinstance(value, dict):
            out.add(key, _toml_table(value))
    return out


# --------------------------------------------------------------------------- TOML reading


def _load_document(path: PathLike) -> dict[str, Any]:
    """The TOML document of a configuration file, its survey file's path made relative to the
    configuration file (as the file says it)."""
    from ..io.toml import load_toml

    source = os.fspath(path)
    document = load_toml(source)
    well = document.get("well")
    if isinstance(well, dict) and isinstance(well.get("survey"), str) and not os.path.isabs(well["survey"]):
        well = {**well, "survey": os.path.join(os.path.dirname(os.path.abspath(source)), well["survey"])}
        document = {**document, "well": well}
    return document


def load_drill_config(path: PathLike) -> DrillConfig:
    """Reads a drilling-system configuration from a TOML file (see the module docstring).

    Raises
    ------
    ValidationError
        A file that cannot be read or is not valid TOML, an unknown key, a value of the wrong
        type or refused by the core; the message names the file, the line when it can be found,
        and the dotted field.
    """
    source = os.fspath(path)
    return DrillConfig.from_dict(_load_document(source), source=source)


# --------------------------------------------------------------------------- overrides

_BARE_WORD = re.compile(r"^[A-Za-z_][A-Za-z0-9_-]*$")
_QUANTITY = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*[A-Za-z%(][^=]*$")
_SET_FORM = "key=value with a dotted key (top_drive.rpm, sections[0].length) and a TOML value"


def _assignment_list(assignments: Iterable[str]) -> list[str]:
    if isinstance(assignments, (str, bytes)):
        raise ValidationError("--set", assignments, "a list of key=value strings")
    return list(assignments)


def _split_assignment(text: Any, field: str = "--set") -> tuple[str, Any]:
    """``key=value`` as ``(key, value)`` (the value TOML or a bare word); errors name ``field``."""
    if not isinstance(text, str) or "=" not in text:
        raise ValidationError(field, text, _SET_FORM)
    key, _, raw = text.partition("=")
    key, raw = key.strip(), raw.strip()
    if not raw:
        raise ValidationError(field, text, _SET_FORM + " (the value is empty)")
    return key, _parse_value(raw, field, text)


def _parse_value(raw: str, field: str, text: str) -> Any:
    """One value of an assignment: TOML (``60``, ``true``, ``"pi"``, ``[0, 30]``), a bare word
    (a string) or ``null`` (``None``); ``ValidationError`` naming ``field`` with ``text``."""
    try:
        return tomllib.loads(f"value = {raw}")["value"]
    except (ValueError, RecursionError):  # tomllib.TOMLDecodeError: maybe a bare word or a quantity
        if _QUANTITY.match(raw):
            return raw  # a number with a unit (5 in, 18 klbf): converted with the key's unit
        if not _BARE_WORD.match(raw):
            raise ValidationError(field, text, _SET_FORM + " (number, true/false, \"string\", [list])") from None
        return None if raw == "null" else raw  # null: unset an optional field (TOML has no null)


def split_values(raw: str) -> list[str]:
    """``raw`` split at its top-level commas: commas inside ``[...]``, ``{...}`` or a quoted
    string stay (``[0, 30], [10, 40]`` is two values)."""
    items: list[str] = []
    depth = 0
    quote = ""
    start = 0
    escaped = False
    for i, ch in enumerate(raw):
        if quote:
            if escaped:
                escaped = False
            elif ch == "\\" and quote == '"':
                escaped = True
            elif ch == quote:
                quote = ""
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            items.append(raw[start:i])
            start = i + 1
    items.append(raw[start:])
    return [item.strip() for item in items]


def parse_values(raw: str, field: str, text: str) -> list[Any]:
    """The comma-separated values ``raw`` (:func:`split_values`), each as :func:`_parse_value`
    reads it; an empty one raises ``ValidationError`` naming ``field`` with ``text``."""
    values = []
    for item in split_values(raw):
        if not item:
            raise ValidationError(field, text, "comma-separated values (an empty value)")
        values.append(_parse_value(item, field, text))
    return values

