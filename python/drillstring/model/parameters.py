"""Physical parameters of the drill string (paper Tables 1 and 3), their presets and TOML I/O.

A :class:`Parameters` holds every physical input of the model in SI units: the length ``l``,
the material (``E``, ``rho``, ``nu``), the annular section (``D``, ``d``), the rotation speed
``Omega`` and the initial generalised velocities ``C_i`` of eq. 13. It is immutable and
validated on construction; every bad value raises :class:`~drillstring.errors.ValidationError`
naming the field, the value and the allowed range.

TOML format (see ``examples/reference.toml``)::

    # drillstring parameters: Table 1 of the paper (aluminium reference), SI units
    [parameters]
    preset = "aluminum"   # optional: start from a preset, then override fields below
    length = 100.0
    initial_velocities = [0.1, 0.05, 0.02]
    k5_variant = "paper"
    model = "paper"       # or "consistent": the finite-strain re-derivation

Other tables (e.g. ``[solver]``) may be present; :func:`load` reads only ``[parameters]``,
:func:`drillstring.io.toml.load_toml` returns the whole document.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from numbers import Real
from typing import Any, Union

import tomlkit

from .. import _core
from ..errors import ValidationError
from ..io.toml import load_toml, toml_string, with_toml_line
from ..limits import _shown, json_ready

__all__ = [
    "K5_VARIANTS",
    "MODELS",
    "PRESETS",
    "Parameters",
    "load",
    "preset",
]

PathLike = Union[str, "os.PathLike[str]"]

#: Names accepted by :func:`preset` (``"aluminium"`` is also accepted as an alias).
PRESETS: tuple[str, ...] = ("aluminum", "steel")

#: Accepted values of :attr:`Parameters.k5_variant`.
K5_VARIANTS: tuple[str, ...] = ("paper", "energy")

#: Accepted values of :attr:`Parameters.model`.
MODELS: tuple[str, ...] = ("paper", "consistent")

#: Fields whose values are names (strings), not numbers.
CHOICE_FIELDS: dict[str, tuple[str, ...]] = {"k5_variant": K5_VARIANTS, "model": MODELS}

_PRESET_ALIASES = {"aluminium": "aluminum"}

_TOML_HEADER = "drillstring parameters: Table 1 of the paper (aluminium reference), SI units"


@dataclass(frozen=True)
class Parameters:
    """Physical parameters of the rotating drill string, SI units.

    Defaults are Table 1 of the paper (aluminium reference) with ``C = (0.1, 0.05, 0.02)``:
    ``Parameters()`` is ``preset("aluminum")``; :func:`preset` gives the sets used for the
    paper's figures.

    Parameters
    ----------
    length:
        String length ``l`` in m, ``> 0``.
    youngs_modulus:
        Young's modulus ``E`` in Pa, ``> 0``.
    density:
        Density ``rho`` in kg/m^3, ``> 0`` (Table 1 prints kg/m^2, a typo).
    poisson_ratio:
        Poisson's ratio ``nu``, ``-1 < nu < 0.5`` (``k3``, ``k4``, ``k5`` of eq. 17 contain
        ``1/(1 - 2 nu)``).
    outer_diameter:
        Outer diameter ``D`` in m, ``> 0``.
    inner_diameter:
        Inner diameter ``d`` in m, ``0 <= d < D``.
    omega:
        Rotation speed ``Omega`` in rad/s (any finite value; it enters eq. 17 only as
        ``k6 = rho I_p Omega^2``).
    initial_velocities:
        ``(C_1, C_2, ...)`` in rad/s: ``C_i`` is the initial generalised velocity of mode
        ``cos(i pi z / l)``, ``i = 1, 2, ...`` (eq. 13:
        ``theta_t(z, 0) = sum_i C_i cos(i pi z / l)``, ``theta(z, 0) = 0``). Modes beyond the
        tuple, and the rigid mode ``i = 0`` when it is included, start at rest. May be empty.
        Lists are accepted and stored as a tuple of floats.
    k5_variant:
        ``"paper"``: ``k5 = G (I_r - I_{x^2y^2} (5 - 6 nu)) / (8 (1 - 2 nu))`` as printed in
        eq. 17; ``"energy"``: the re-derived ``k5`` with a plus sign (model notes, erratum 2).
        Used by the ``"paper"`` model only.
    model:
        ``"paper"`` (default): eq. 12 / 17 as printed, which reproduces the paper's results
        (``k2 = 4 G I_p``: wave speed ``2 sqrt(G / rho)``, rotation softening ``k6``).
        ``"consistent"``: finite-strain torsion of rigidly rotating circular sections
        (Green-Lagrange strain, St Venant-Kirchhoff energy): ``k2 = G I_p``,
        ``k3 = k4 = k6 = 0``, ``k5 = M J4 / 2``; wave speed ``sqrt(G / rho)``, no force from a
        uniform twist, independent of a constant ``Omega``
        (:mod:`drillstring.model.coefficients`).
    damping_rate:
        Viscous damping rate ``c`` in 1/s, finite and ``>= 0`` (default 0: the paper's
        undamped model). Adds the force ``-rho I_p c theta_t`` per unit length (the convention
        of the Aarsnes-Shor torsional model), so every linear mode decays as
        ``exp(-c t / 2)``. With ``c > 0`` the energy is no longer conserved: the diagnostic is
        the energy balance ``H(t) + dissipated(t) = H(0)``, and the fixed-step methods
        ``"central"`` and ``"verlet"`` (which advance ``q'' = a(q)`` only) are refused.

    Raises
    ------
    ValidationError
        If any field is out of range or of the wrong type.
    """

    length: float = 100.0
    youngs_modulus: float = 0.7e11
    density: float = 2.7e3
    poisson_ratio: float = 0.34
    outer_diameter: float = 0.20
    inner_diameter: float = 0.12
    omega: float = 2.0 * math.pi * 0.5
    initial_velocities: tuple[float, ...] = field(default=(0.1, 0.05, 0.02))
    k5_variant: str = "paper"
    model: str = "paper"
    damping_rate: float = 0.0

    def __post_init__(self) -> None:
        # The core is the one validator (``_core.parameters_validate``): its message, with the
        # value as given here. Numbers are then stored as Python floats of the values given.
        plain = {name: getattr(self, name) for name in self.field_names()}
        velocities = plain["initial_velocities"]
        if isinstance(velocities, (list, tuple)) or (hasattr(velocities, "__iter__")
                                                     and not isinstance(velocities, (str, bytes, Mapping))):
            plain["initial_velocities"] = list(velocities)
        try:
            _core.parameters_validate(json.dumps(json_ready(plain)))
        except ValidationError as exc:
            raise ValidationError(exc.field, _shown(_value_at(plain, exc.field, exc.value)), exc.allowed) from None
        for name in self.field_names():
            value = plain[name]
            if name == "initial_velocities":
                object.__setattr__(self, name, tuple(float(v) for v in value))
            elif not isinstance(value, str):
                object.__setattr__(self, name, float(value))

    # ------------------------------------------------------------------ copies and dicts

    @classmethod
    def field_names(cls) -> tuple[str, ...]:
        """Names of the fields, in declaration order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    def replace(self, **changes: Any) -> Parameters:
        """Return a copy with some fields changed (validated like the constructor).

        Raises
        ------
        ValidationError
            For an unknown field name (the message lists the valid ones) or a bad value.
        """
        names = self.field_names()
        for name, value in changes.items():
            if name not in names:
                raise ValidationError(name, value, "a field of Parameters: " + ", ".join(names))
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """Plain ``{field: value}`` dict (``initial_velocities`` as a list), JSON/TOML-ready."""
        out: dict[str, Any] = {name: getattr(self, name) for name in self.field_names()}
        out["initial_velocities"] = list(self.initial_velocities)
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str | None = None) -> Parameters:
        """Build from a mapping of field names (the ``[parameters]`` table of a TOML file).

        An optional ``"preset"`` key selects the starting set (see :func:`preset`); the other
        keys override its fields. Without ``"preset"`` the start is the default
        :class:`Parameters` (Table 1, ``C = (0.1, 0.05, 0.02)``, the ``"aluminum"`` preset).

        Parameters
        ----------
        data:
            Mapping of field names to values.
        source:
            Where the mapping came from (e.g. a file name); prefixed to error messages.

        Raises
        ------
        ValidationError
            For an unknown key, an unknown preset or a bad value; ``source`` is attached.
        """
        if not isinstance(data, Mapping):
            raise ValidationError(
                "parameters", data, "a table/mapping of parameter fields", source=source
            )
        names = cls.field_names()
        changes: dict[str, Any] = {}
        base_name: Any = None
        for key, value in data.items():
            if key == "preset":
                base_name = value
            elif key in names:
                changes[key] = value
            else:
                raise ValidationError(
                    str(key),
                    value,
                    "a field of Parameters: preset, " + ", ".join(names),
                    source=source,
                )
        try:
            base = cls() if base_name is None else preset(base_name)
            return dataclasses.replace(base, **changes)
        except ValidationError as exc:
            if source is None:
                raise
            raise ValidationError(exc.field, exc.value, exc.allowed, source=source) from exc

    # ------------------------------------------------------------------ TOML

    def to_toml(self) -> str:
        """Format as a TOML document with a ``[parameters]`` table (written by tomlkit).

        Floats are written in their shortest exact form (``repr``) so that :func:`load`
        reproduces them bit-for-bit.
        """
        document = tomlkit.parse(f"# {_TOML_HEADER}\n[parameters]\n")
        table = document["parameters"]
        for name in self.field_names():
            value = getattr(self, name)
            if name == "initial_velocities":
                table.add(name, [float(v) for v in value])
            elif name in CHOICE_FIELDS:
                table.add(name, toml_string(value))
            else:
                table.add(name, float(value))
        return document.as_string()

    def save(self, path: PathLike) -> os.PathLike[str]:
        """Write :meth:`to_toml` to ``path`` (UTF-8) and return the path written: an existing file
        is replaced atomically, a symlink is written through, a device, FIFO or ``"-"`` is
        streamed into (see :mod:`drillstring.io.output`); the path is a :class:`pathlib.Path`."""
        from ..io.output import write_text

        return write_text(path, self.to_toml())


def check_damping_rate(value: Any) -> float:
    """A viscous damping rate (1/s) as a float: finite and ``>= 0`` (the core's rule,
    ``_core.check_damping_rate``), else :class:`~drillstring.errors.ValidationError` naming
    ``damping_rate``."""
    try:
        number = float(value) if isinstance(value, Real) and not isinstance(value, bool) else math.nan
    except (OverflowError, ValueError, TypeError):
        number = math.nan
    try:
        return float(_core.check_damping_rate(number))
    except ValidationError as exc:
        raise ValidationError("damping_rate", _shown(value), exc.allowed) from None


def _value_at(plain: Mapping[str, Any], field: str, default: Any) -> Any:
    """The value of ``plain`` at the field ``field`` (``length``, ``initial_velocities[2]``)."""
    name, _, index = field.partition("[")
    if name not in plain:
        return default
    value = plain[name]
    if index:
        try:
            return value[int(index.rstrip("]"))]
        except (TypeError, ValueError, IndexError, KeyError):
            return default
    return value


def preset(name: str) -> Parameters:
    """A named parameter set.

    * ``"aluminum"`` (alias ``"aluminium"``): Table 1 with ``C = (0.1, 0.05, 0.02)``, the
      defaults of :class:`Parameters`.
    * ``"steel"``: Table 3 (``E = 2.1e11`` Pa, ``rho = 7.8e3`` kg/m^3, ``nu = 0.28``) on the
      geometry, ``Omega`` and ``C`` of the aluminium set.

    Raises
    ------
    ValidationError
        For an unknown name (the message lists the valid ones).
    """
    key = _PRESET_ALIASES.get(name, name) if isinstance(name, str) else name
    aluminum = Parameters()
    if key == "aluminum":
        return aluminum
    if key == "steel":
        return aluminum.replace(youngs_modulus=2.1e11, density=7.8e3, poisson_ratio=0.28)
    raise ValidationError(
        "preset", name, "one of " + ", ".join(map(repr, PRESETS + tuple(_PRESET_ALIASES)))
    )


def load(path: PathLike) -> Parameters:
    """Read the ``[parameters]`` table of a TOML file (other tables are ignored).

    Raises
    ------
    ValidationError
        If the file is malformed, has no ``[parameters]`` table, or holds an unknown key or a
        bad value; messages name the file, the line (``source`` and ``line`` attributes) and the
        key.
    """
    source = os.fspath(path)
    document = load_toml(source)
    if "parameters" not in document:
        raise ValidationError(
            "parameters", None, "a [parameters] table in the TOML file", source=source
        )
    try:
        return Parameters.from_dict(document["parameters"], source=source)
    except ValidationError as exc:
        raise with_toml_line(exc, source, "parameters") from exc
