"""Units at the edge: quantities with units in a configuration, the field unit system, outputs
converted for display.

The core works in SI only (angles in degrees, speeds in rpm, as the keys say). Here, before a
configuration reaches the core, every number may be written as a string with a unit
(``length = "9842.5 ft"``, ``outer_diameter = "5 in"``, ``weight_on_bit = "18 klbf"``,
``mud_density = "10.8 ppg"``, ``build = "3 deg/100ft"``), converted with pint to the SI unit the
core's reference gives for the key (:func:`~drillstring.drilling.config.config_schema`); and a
top-level ``units = "field"`` makes plain numbers mean the field unit of their key
(:data:`FIELD_UNITS`, :data:`FIELD_UNITS_BY_KEY`) instead of SI (``units = "si"``, the default).
A plain number in SI is passed on untouched (bit for bit).

Outputs stay SI; :func:`convert` and :func:`shown` give a value in another unit system for the
console and ``metrics.json``'s converted copy (``drillstring drill --units field``), and
:func:`axis_unit` the factor and unit text of a figure's axis (the figures of a run, of a map and
of torque and drag take ``units="field"``).
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping
from decimal import Decimal
from typing import Any, Optional

from .. import _core
from ..errors import ValidationError

__all__ = [
    "FIELD_UNITS", "FIELD_UNITS_BY_KEY", "SYSTEMS", "UNIT_SUFFIXES", "annotate", "axis_unit", "chosen_units",
    "convert", "factor", "field_error", "field_unit", "field_value", "hoist_after", "in_field_units", "override_to_si",
    "quantity", "shown", "shown_unit", "system_of", "to_si", "unit_key",
]

#: The unit systems: ``si`` (the core's units; plain numbers pass untouched) and ``field``.
SYSTEMS: tuple[str, ...] = ("si", "field")

#: The field unit of each SI unit of the reference and of the outputs (units as pint parses them;
#: ``ppg`` is pounds per US gallon; ``N/m`` and ``N*m/m``, the normal force and the friction limit
#: per length, and ``m/h``, a coupled run's rate of penetration, only in outputs). Axial speeds
#: (``m/s``: the block velocity, the autodriller's ROP setpoint and its limits) are in ft/h, the
#: unit of the rate of penetration the block drives, as the figures draw them; the autodriller's
#: gains on the weight on bit in (ft/h)/klbf and (ft/h)/(klbf s). SI units not listed (rpm, s,
#: Hz, deg, rad/s, 1/s, dimensionless) are the same in both systems.
FIELD_UNITS: dict[str, str] = {
    "m": "ft",
    "m^2": "in^2",
    "m^4": "in^4",
    "m^6": "in^6",
    "Pa": "psi",
    "kg/m^3": "ppg",
    "m/s^2": "ft/s^2",
    "N": "klbf",
    "N*m": "ft*lbf",
    "kg*m^2": "lb*ft^2",
    "kg": "lb",
    "N*m*s/rad": "ft*lbf*s/rad",
    "N*m*s": "ft*lbf*s",
    "N*m/rad": "ft*lbf/rad",
    "deg/(30 m)": "deg/(100 ft)",
    "N/m": "lbf/ft",
    "N*m/m": "ft*lbf/ft",
    "m/h": "ft/h",
    "m/s": "ft/h",
    "m/(N*s)": "ft/h/klbf",
    "m/(N*s^2)": "ft/h/klbf/s",
}

#: Keys whose field unit is not their SI unit's in :data:`FIELD_UNITS`: diameters (of the pipe, its
#: tool joints and the hole), the tool joints' length and the bit's lengths (its size, the wear
#: flats) in inches; every other length of the reference (section
#: lengths, depths, plan holds, the torque-and-drag element) is in ft.
FIELD_UNITS_BY_KEY: dict[str, str] = {
    "sections[].outer_diameter": "in",
    "sections[].inner_diameter": "in",
    "sections[].contact_diameter": "in",
    "sections[].tool_joint_outer_diameter": "in",
    "sections[].tool_joint_inner_diameter": "in",
    "sections[].tool_joint_length": "in",
    "well.hole_diameter": "in",
    "well.hole_sections[].diameter": "in",
    "bit.radius": "in",
    "bit.diameter": "in",
    "bit.detournay.wear_flat_length": "in",
}

#: How unit systems are named in messages.
_SYSTEM_FORM = "one of si (the default: SI, angles in degrees, speeds in rpm), field (ft, in, klbf, ppg, psi, ...)"

_INDEX = re.compile(r"\[\d+\]")
# "deg/100ft", "deg/100 ft": a number in a denominator belongs to the unit after it
_PER_NUMBER = re.compile(r"/\s*(\d+(?:\.\d*)?)\s*([A-Za-z_]\w*)")
# a string read as a quantity: a number first ("5 in", "1e3 ft", "0.3")
_QUANTITY = re.compile(r"^\s*[-+]?(\d|\.\d)")
# "ft-lbf", "lbf-ft": a hyphen between two unit names is a product
_HYPHEN = re.compile(r"(?<=[A-Za-z])-(?=[A-Za-z])")


@functools.lru_cache(maxsize=1)
def _registry() -> Any:
    """The pint unit registry (imported on first use), with ``ppg`` (pound per US gallon). Its
    numbers are decimals: the conversion factors are exact (``ft`` is ``0.3048 m``), so that a
    converted value is the correctly rounded float of the exact product (``"5 in"`` is
    ``0.127``, ``1000 ft`` is ``304.8``)."""
    import pint

    registry: Any = pint.UnitRegistry(non_int_type=Decimal)
    registry.define("ppg = pound / gallon")
    return registry


@functools.lru_cache(maxsize=1)
def _schema() -> dict[str, Any]:
    return _core.drill_config_schema()


def _expression(text: str) -> Any:
    """``text`` parsed by pint after the two spellings it reads otherwise (``deg/100ft``,
    ``ft-lbf``) are rewritten."""
    text = _HYPHEN.sub("*", _PER_NUMBER.sub(r"/(\1 \2)", text.strip()))
    return _registry().parse_expression(text)


def _magnitude(value: Any, unit: str) -> float:
    """The pint quantity ``value`` as a number in ``unit`` (a pint expression, which may hold a
    factor: ``deg/(30 m)``), rounded to a float once."""
    ratio = value / _expression(unit or "1")
    return float(ratio.to("dimensionless").magnitude if hasattr(ratio, "to") else ratio)


def _in(number: float, unit: str) -> Any:
    """The float ``number`` as a quantity in ``unit``: the decimal of its shortest repr (the
    number as written, ``5.123`` and not its binary neighbour), so that a plain number converts
    to the same float as the string ``"5.123 in"``."""
    return (Decimal(repr(number)) if isinstance(number, float) else Decimal(number)) * _expression(unit)


def field_unit(key: str, unit: Optional[str] = None) -> Optional[str]:
    """The field unit of the reference key ``key`` (``sections[].outer_diameter``), or None when
    the key is no number or its field unit is its SI unit. ``unit``: the key's SI unit where its
    mode chooses it (:func:`chosen_units`), else the reference's."""
    if key in FIELD_UNITS_BY_KEY:
        return FIELD_UNITS_BY_KEY[key]
    unit = unit if unit is not None else _unit_of(key)
    return FIELD_UNITS.get(unit) if unit is not None else None


def _key(path: str) -> str:
    """The reference key of the field ``path``: indices as ``[]``, but the last index of a pair
    of a list of pairs (``top_drive.steps[2][1]``: ``top_drive.steps[][1]``)."""
    key = _INDEX.sub("[]", path)
    last = _INDEX.findall(path)
    if key.endswith("[][]") and last and f"{key[:-2]}{last[-1]}" in _schema():
        return f"{key[:-2]}{last[-1]}"
    return key


def _unit_of(key: str) -> Optional[str]:
    """The SI unit of the reference key ``key`` (a list's entries take the list's unit)."""
    schema = _schema()
    entry = schema.get(key)
    if entry is None and key.endswith("[]"):
        entry = schema.get(key[:-2])
    if entry is None or entry["type"] not in ("number", "array"):
        return None  # integers are counts: no units
    unit = entry["unit"]
    return unit if isinstance(unit, str) else None


#: The quantity an SI unit of the reference measures, for messages.
_DIMENSIONS = {
    "": "dimensionless", "m": "length", "m^2": "area", "m^4": "length^4", "m^6": "length^6", "Pa": "pressure",
    "kg/m^3": "density", "m/s^2": "acceleration", "deg": "angle", "deg/(30 m)": "angle per length",
    "rad/s": "angular speed", "rpm": "angular speed", "s/rad": "time per angle", "s": "time", "1/s": "rate",
    "Hz": "frequency", "N": "force", "N*m": "torque", "kg*m^2": "moment of inertia", "kg": "mass",
    "N*m*s/rad": "torque per angular speed", "N*m/rad": "torque per angle", "m/s": "speed", "1": "dimensionless",
    "m/(N*s)": "speed per force", "m/(N*s^2)": "speed per force and time",
}


def _dimension(unit: str) -> str:
    if " or " in unit:  # a key whose unit is its target's (hoist.autodriller.setpoint: N or m/s)
        return " or ".join(_dimension(u) for u in unit.split(" or "))
    return _DIMENSIONS.get(unit) or str(_expression(unit or "1").dimensionality)


def chosen_units(hoist: Any) -> dict[str, tuple[str, str]]:
    """The SI unit of each key whose unit is its target's (``hoist.steps[][1]``: ``m/s or N``;
    ``hoist.autodriller.setpoint``: ``N or m/s``; the autodriller's gains), as the hoist table
    ``hoist`` (a plain mapping, None without a hoist) chooses it by its ``mode`` and its
    autodriller's ``target`` (their defaults where unset): ``{key: (unit, why)}``, ``why`` the
    setting that chose it for messages (``hoist.mode = "velocity"``). A mode or target that is not
    one of the core's is left out (the core refuses it)."""
    if not isinstance(hoist, Mapping):
        return {}
    schema = _schema()
    mode = hoist.get("mode") or schema["hoist.mode"]["default"]
    autodriller = hoist.get("autodriller")
    target = (autodriller.get("target") if isinstance(autodriller, Mapping) else None) \
        or schema["hoist.autodriller.target"]["default"]
    out: dict[str, tuple[str, str]] = {}
    by_target = {"weight_on_bit": ("N", "m/(N*s)", "m/(N*s^2)"), "rop": ("m/s", "1", "1/s")}.get(str(target))
    why_target = f'hoist.autodriller.target = "{target}"'
    if by_target is not None:
        for name, unit in zip(("setpoint", "kp", "ki"), by_target):
            out[f"hoist.autodriller.{name}"] = (unit, why_target)
    step = {"velocity": "m/s", "hook_load": "N", "weight_on_bit": "N",
            "autodriller": by_target[0] if by_target else None}.get(str(mode))
    if step is not None:
        why = f'hoist.mode = "{mode}"' + (f" and {why_target}" if mode == "autodriller" else "")
        out["hoist.steps[][1]"] = (step, why)
    return out


def quantity(path: str, value: Any, system: str = "si",
             chosen: Optional[Mapping[str, tuple[str, str]]] = None) -> Any:
    """The value of the configuration field ``path`` (``sections[1].outer_diameter``) in the
    core's SI unit: a string with a unit (``"5 in"``) converted, a plain number (or a string
    without a unit) in ``system``'s unit of the key; anything else (a name, a boolean, a key
    that takes no number, a string that does not start with a number) unchanged: the core
    refuses what is wrong there. ``chosen`` (:func:`chosen_units`) gives the unit of a key whose
    unit is its target's (the hoist's steps, the autodriller's setpoint and gains): a quantity
    must be of that unit's dimension and a plain number is in ``system``'s unit of it.

    Raises
    ------
    ValidationError
        A string starting with a number that pint cannot read, or of another dimension than the
        key's, naming the field, the value and the dimension expected.
    """
    key = _key(path)
    unit = _unit_of(key)
    why = ""
    if unit is not None and chosen and key in chosen:
        unit, why = chosen[key]
        why = f" ({why})"
    if unit is None or isinstance(value, bool):
        return value
    if isinstance(value, str):
        if not _QUANTITY.match(value):
            return value  # no number first ("fast"): the core says what the key takes
        try:
            parsed = _expression(value)
        except Exception:  # pint's parse errors (undefined unit, syntax) have no common base
            parsed = None
        if parsed is None or not _is_number(parsed):
            raise ValidationError(path, value, _expected(key, unit, "a quantity pint reads")) from None
        if str(getattr(parsed, "units", "dimensionless")) == "dimensionless":
            value = float(getattr(parsed, "magnitude", parsed))  # a number written as a string: a plain number
        else:
            for choice in unit.split(" or "):  # "N or m/s": the unit of the quantity's dimension
                try:
                    return _magnitude(parsed, choice)
                except Exception:  # pint's DimensionalityError
                    continue
            raise ValidationError(path, value, _expected(key, unit, f"a quantity of {_dimension(unit)}{why}"))
    if system == "field" and isinstance(value, (int, float)) and math.isfinite(value):
        source = field_unit(key, unit)
        if source is not None:
            return _magnitude(_in(value, source), unit)
    return value


def _is_number(parsed: Any) -> bool:
    magnitude = getattr(parsed, "magnitude", parsed)
    return isinstance(magnitude, (int, float, Decimal)) and not isinstance(magnitude, bool) and math.isfinite(magnitude)


def _expected(key: str, unit: str, what: str) -> str:
    """What a numeric field takes, for messages."""
    if not unit or unit == "1":
        return f"{what}: a dimensionless number (a string such as \"30 %\" is read too)"
    field = field_unit(key, unit)
    return f"{what}: a number (in {unit}) or a string with a unit of {_dimension(unit)}, e.g. \"1.5 {field or unit}\""


#: The path of a ``[[changes]]`` entry.
_CHANGE = re.compile(r"changes\[\d+\]")


def _convert(path: str, value: Any, system: str, chosen: Mapping[str, tuple[str, str]]) -> Any:
    """``value`` at ``path`` with every quantity in SI (tables and lists entry by entry; a
    ``[[changes]]`` entry's ``value`` in the unit of the key it changes)."""
    if isinstance(value, Mapping) and _CHANGE.fullmatch(path) and isinstance(value.get("key"), str):
        return {k: quantity(value["key"].replace(" ", ""), v, system, chosen) if k == "value" and v is not None
                else _convert(f"{path}.{k}", v, system, chosen) for k, v in value.items()}
    if isinstance(value, Mapping):
        return {k: _convert(f"{path}.{k}" if path else str(k), v, system, chosen) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_convert(f"{path}[{i}]", v, system, chosen) for i, v in enumerate(value)]
    if value is None:
        return value
    return quantity(path, value, system, chosen)


def system_of(value: Any, field: str = "units") -> str:
    """A unit system's name checked (``si`` or ``field``); errors name ``field``."""
    if value not in SYSTEMS:
        raise ValidationError(field, value, _SYSTEM_FORM)
    return str(value)


def to_si(config: Mapping[str, Any]) -> dict[str, Any]:
    """The plain configuration ``config`` (nested dicts and lists, as TOML gives it) with every
    quantity in the core's SI units: strings with units converted, plain numbers read in the
    system of its top-level ``units`` key (``si`` when absent; the key is removed)."""
    data = dict(config)
    system = system_of(data.pop("units", "si"))
    return _convert("", data, system, chosen_units(data.get("hoist")))


def override_to_si(key: str, value: Any, system: str = "si",
                   chosen: Optional[Mapping[str, tuple[str, str]]] = None) -> Any:
    """The value of an override of the dotted key ``key`` (``sections[1].outer_diameter``, a
    table such as ``bit``) with its quantities in SI: plain numbers in ``system``'s unit of the
    key (a configuration's own system, :attr:`DrillConfig.units
    <drillstring.drilling.config.DrillConfig.units>`), the hoist's and the autodriller's
    alternatives as ``chosen`` (:func:`chosen_units`) says."""
    return _convert(key, value, system_of(system), chosen or {})


def hoist_after(hoist: Any, pairs: Any) -> Any:
    """The hoist table ``hoist`` (plain, None without a hoist) after the overrides ``pairs``
    (``(dotted key, value)``) of its mode and its autodriller's target: what
    :func:`chosen_units` reads for the values of the same overrides."""
    table = dict(hoist) if isinstance(hoist, Mapping) else None
    for key, value in pairs:
        key = str(key).replace(" ", "")
        if key == "hoist":
            table = dict(value) if isinstance(value, Mapping) else None
        elif key.startswith("hoist."):
            table = dict(table or {})
            if key == "hoist.mode":
                table["mode"] = value
            elif key == "hoist.autodriller":
                table["autodriller"] = value
            elif key == "hoist.autodriller.target":
                autodriller = table.get("autodriller")
                table["autodriller"] = {**(autodriller if isinstance(autodriller, Mapping) else {}), "target": value}
    return table


def convert(value: Optional[float], unit: str, system: str, *, key: Optional[str] = None
            ) -> tuple[Optional[float], str]:
    """An SI ``value`` in ``unit`` (pint's form, ``"N*m"``) as ``system`` shows it:
    ``(value, unit)``, the value unchanged in SI or where the field unit is the same. With the
    reference ``key`` of the value (``sections[].outer_diameter``), the key's own field unit if it
    has one (:data:`FIELD_UNITS_BY_KEY`: diameters in inches)."""
    system = system_of(system, "output_units")
    target = None
    if system == "field":
        target = FIELD_UNITS_BY_KEY.get(key or "") or FIELD_UNITS.get(unit)
    if target is None or value is None or (isinstance(value, float) and math.isnan(value)):
        return value, unit
    return _magnitude(_in(value, unit), target), target


def factor(unit: str, target: str) -> Optional[float]:
    """The value of one ``unit`` (as people write it: ``"kft-lbf"``, ``"daN"``) in ``target``
    (pint's form, ``"N*m"``), or None when pint does not know ``unit`` or it is of another
    dimension."""
    try:
        return _magnitude(_in(1, unit), target)
    except Exception:  # pint's parse and dimensionality errors have no common base
        return None


#: The suffix a key's name gives its unit by (``motor_torque_max_Nm``, ``rop_mean_m_per_h``).
UNIT_SUFFIXES: dict[str, str] = {
    "N*m": "Nm", "ft*lbf": "ftlbf", "N": "N", "klbf": "klbf", "m/h": "m_per_h", "ft/h": "ft_per_h", "Pa": "Pa",
    "psi": "psi", "m": "m", "ft": "ft", "in": "in", "N/m": "N_per_m", "lbf/ft": "lbf_per_ft", "s": "s",
    "rpm": "rpm",
}


def unit_key(name: str, unit: str, target: str) -> str:
    """The name of the value ``name`` (a key in SI ``unit``) in the unit ``target``: keys whose
    name carries a unit always hold that unit, so a converted value is written under its SI
    suffix replaced by the target's (``motor_torque_max_Nm`` in ``ft*lbf``:
    ``motor_torque_max_ftlbf``; ``rop_mean_m_per_h`` in ``ft/h``: ``rop_mean_ft_per_h``); a name
    without its unit's suffix, or a unit unchanged, keeps its name (``bit_rpm_mean``)."""
    suffix, other = UNIT_SUFFIXES.get(unit), UNIT_SUFFIXES.get(target)
    if target == unit or suffix is None or not name.endswith(f"_{suffix}"):
        return name
    if other is None:
        raise ValueError(f"no key suffix for the unit {target!r}")  # a new field unit needs its suffix
    return f"{name[: -len(suffix)]}{other}"


#: How units are written on the console.
_SHOWN = {"N*m": "N m", "ft*lbf": "ft-lbf", "kg*m^2": "kg m^2", "lb*ft^2": "lb ft^2", "N*m/m": "N m/m",
          "ft*lbf/ft": "ft-lbf/ft", "deg/(30 m)": "deg/30 m", "deg/(100 ft)": "deg/100 ft",
          "ft/h/klbf": "(ft/h)/klbf", "ft/h/klbf/s": "(ft/h)/(klbf s)", "ft*lbf*s/rad": "ft-lbf s/rad",
          "ft*lbf/rad": "ft-lbf/rad", "ft*lbf*s": "ft-lbf s", "N*m*s/rad": "N m s/rad", "N*m/rad": "N m/rad"}


def shown_unit(unit: str, system: str, *, kilo: bool = False) -> str:
    """How the console writes the SI ``unit`` in ``system`` (``"kN m"``, ``"kft-lbf"`` with
    ``kilo``)."""
    target = convert(1.0, unit, system)[1]
    text = _SHOWN.get(target, target)
    return f"k{text}" if kilo else text


def shown(value: float, unit: str, system: str, *, kilo: bool = False, digits: int = 4) -> str:
    """An SI ``value`` in ``unit`` as text in ``system`` (``"24.1 kN m"``, ``"17.8 kft-lbf"``
    with ``kilo``)."""
    number = convert(value, unit, system)[0]
    number = number / 1e3 if kilo and number is not None else number
    return f"{number:.{digits}g} {shown_unit(unit, system, kilo=kilo)}"


def axis_unit(unit: str, system: str, *, kilo: bool = False) -> tuple[float, str]:
    """The factor a figure multiplies an SI quantity in ``unit`` by to draw it in ``system``, and
    the unit its axis writes: the value of one ``unit`` in the system's unit (:func:`convert`:
    the correctly rounded float of the exact factor, ``1 / 0.3048`` for ``m`` in field units),
    a thousandth of it with ``kilo`` (``"N*m"``: ``(1e-3, "kN m")`` in SI,
    ``(1e-3 / (0.3048 * 4.4482216152605), "kft-lbf")`` in field units) unless the system's unit
    is a thousand of one already (``"N"`` with ``kilo``: ``"kN"`` in SI, ``"klbf"`` in field
    units). A unit the same in both systems has the factor 1 (``"rpm"``: ``(1.0, "rpm")``).

    Raises
    ------
    ValidationError
        An unknown ``system``, naming ``units`` and the systems.
    """
    system = system_of(system, "units")
    factor, target = convert(1.0, unit, system)
    assert factor is not None  # a number converts to a number
    kilo = kilo and not target.startswith("k")
    return (factor / 1e3 if kilo else factor), shown_unit(unit, system, kilo=kilo)


def reported_unit(unit: str, system: str) -> tuple[float, str]:
    """The factor and the unit text the console and ``report.md`` write an SI quantity in ``unit``
    with in ``system``: forces and torques in thousands (``kN``, ``kN m``; ``klbf``, ``kft-lbf``),
    a pressure in MPa (psi in field units), any other unit as :func:`axis_unit` writes it."""
    if unit == "Pa" and system_of(system, "units") == "si":
        return 1e-6, "MPa"
    return axis_unit(unit, system, kilo=unit in ("N", "N*m"))


def metric_texts(values: Mapping[str, Any], names: Any, system: str) -> list[str]:
    """``"<label> <value> <unit>"`` of each metric of ``names`` in ``values`` (SI, by the names of
    the core's registry of outputs), with its registry label, in ``system``'s
    :func:`reported_unit` (4 significant digits; a dimensionless number 3, a text as it is)."""
    from .metrics import OUTPUTS

    out = []
    for name in names:
        o, value = OUTPUTS[name], values[name]
        if o.kind != "number":
            out.append(f"{o.label} {value}")
        elif not o.unit:
            out.append(f"{o.label} {value:.3g}")
        else:
            scale, unit = reported_unit(o.unit, system)
            out.append(f"{o.label} {value * scale:.4g} {unit}")
    return out


# ---------------------------------------------------------------------- messages in field units

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
#: The SI units a message writes a quantity in (as the core writes them), longest first, with their
#: pint form: a number before one of them is converted by :func:`annotate`.
_MESSAGE_UNITS: tuple[tuple[str, str], ...] = (
    ("kN m", "kN*m"), ("N m s/rad", "N*m*s/rad"), ("N m/rad", "N*m/rad"), ("N m s", "N*m*s"), ("N m/m", "N*m/m"),
    ("N m", "N*m"), ("kg m^2", "kg*m^2"), ("kg/m^3", "kg/m^3"), ("kg/m³", "kg/m^3"), ("MPa", "MPa"),
    ("GPa", "GPa"), ("Pa", "Pa"), ("kN", "kN"), ("N/m", "N/m"), ("N", "N"), ("m/h", "m/h"), ("m/s", "m/s"),
    ("km", "km"), ("mm", "mm"), ("m", "m"),
)
_MESSAGE_QUANTITY = re.compile(  # "1378 N m", and a range "from 808.1 to 1378 N m"
    rf"(?<![\w.])(?:({_NUMBER}) to )?({_NUMBER})\s?({'|'.join(re.escape(text) for text, _ in _MESSAGE_UNITS)})"
    r"(?![\w/^*³²])")
#: What :func:`annotate` appends after a quantity: `` (1016 ft-lbf)``, `` (3098 to 4004 ft-lbf)``.
_ANNOTATION = re.compile(rf" \((?:{_NUMBER} to )?{_NUMBER} [A-Za-z]")


def _field_number(value: float, unit: str, target: str) -> str:
    return f"{_magnitude(_in(value, unit), target):.6g}"


def _field_of(unit: str) -> Optional[tuple[str, str]]:
    """The field unit of the SI ``unit`` (a prefixed one, ``kN``, by its base) and its text."""
    base = {"kN*m": "N*m", "kN": "N", "MPa": "Pa", "GPa": "Pa", "km": "m", "mm": "m"}.get(unit, unit)
    target = FIELD_UNITS.get(base)
    if target is None:
        return None
    if base in ("N*m",) and unit.startswith("k"):
        return "kft*lbf", "kft-lbf"
    return target, _SHOWN.get(target, target)


def annotate(text: str, system: str) -> str:
    """A message (a warning) with each SI quantity in it followed by its value in ``system``'s
    unit: ``"1378 N m"`` as ``"1378 N m (1016 ft-lbf)"`` in field units; the text unchanged in
    SI. A quantity already followed by a parenthesis (an annotated message) is left as it is, so
    annotating twice changes nothing."""
    if system_of(system) == "si":
        return text
    forms = dict(_MESSAGE_UNITS)

    def one(match: re.Match[str]) -> str:
        if _ANNOTATION.match(match.string, match.end()):  # annotated before: once is enough
            return match.group(0)
        unit = forms[match.group(3)]
        field = _field_of(unit)
        if field is None:
            return match.group(0)
        start = f"{_field_number(float(match.group(1)), unit, field[0])} to " if match.group(1) else ""
        return f"{match.group(0)} ({start}{_field_number(float(match.group(2)), unit, field[0])} {field[1]})"

    return _MESSAGE_QUANTITY.sub(one, text)


def in_field_units(text: str, path: str) -> Optional[str]:
    """The allowed range ``text`` of the configuration field ``path`` (as the core words it, in
    the key's SI unit) with its quantities in the key's field unit (``"a finite number > 0 m, at
    most 10 m"`` of ``sections[0].outer_diameter``: ``"a finite number > 0 in, at most 393.701
    in"``), or None when the key has no other field unit or nothing in the text is in its unit."""
    key = _key(path)
    unit = _unit_of(key)
    target = field_unit(key)
    if not unit or " or " in unit or target is None:
        return None
    shown_si, shown_field = _SHOWN.get(unit, unit), _SHOWN.get(target, target)
    si = re.escape(shown_si)
    end = r"(?![\w/^*³²])"

    def number(match: re.Match[str]) -> str:
        return _field_number(float(match.group(0)), unit, target)

    def interval(match: re.Match[str]) -> str:
        return (f"{match.group(1)}{_field_number(float(match.group(2)), unit, target)}, "
                f"{_field_number(float(match.group(3)), unit, target)}{match.group(4)}{match.group(5)}{shown_field}")

    def quantity_(match: re.Match[str]) -> str:
        return f"{_field_number(float(match.group(1)), unit, target)}{match.group(2)}{shown_field}"

    text = re.sub(r"\s*\(in metres:[^)]*\)", "", text)  # the SI hint of a field number: moot here
    out = re.sub(rf"([\[(])\s*({_NUMBER})\s*,\s*({_NUMBER})\s*([\])])(\s*){si}{end}", interval, text)
    out = re.sub(rf"(?<![\w.])({_NUMBER})(\s?){si}{end}", quantity_, out)
    if out.rstrip().endswith(f"({shown_si})"):  # "a finite number >= 0 (N)": every number in the unit
        head = out.rstrip()[: -len(shown_si) - 2]
        out = re.sub(rf"(?<![\w.^]){_NUMBER}(?![\w.])", number, head) + f"({shown_field})"
    return out if out != text else None


def field_error(error: ValidationError, system: str) -> ValidationError:
    """``error`` of a configuration field, with the value and the allowed range in field units
    appended when ``system`` is ``"field"`` (``"... at most 10 m (in field units: got 500 in;
    at most 393.701 in)"``); ``error`` itself otherwise or when it has no quantity to convert."""
    if system_of(system) != "field" or not isinstance(error.field, str) or "(in field units:" in error.allowed:
        return error
    allowed = in_field_units(error.allowed, error.field)
    if allowed is None:
        return error
    got = ""
    target = field_unit(_key(error.field))
    unit = _unit_of(_key(error.field))
    try:
        value = float(error.value)
    except (TypeError, ValueError):
        value = math.nan
    if target is not None and unit is not None and math.isfinite(value):
        got = f"got {_field_number(value, unit, target)} {_SHOWN.get(target, target)}; "
    return ValidationError(error.field, error.value, f"{error.allowed} (in field units: {got}{allowed})",
                           source=error.source, line=error.line)


def field_value(path: str, value: float, system: str, digits: int = 6) -> Optional[str]:
    """The SI ``value`` of the configuration field ``path`` as text in ``system``'s unit of the
    key (``"20 klbf"`` for ``bit.weight_on_bit`` in field units), or None in SI, for a key that
    takes no number or whose unit is the same in both systems."""
    if system_of(system) == "si":
        return None
    key = _key(path)
    unit, target = _unit_of(key), field_unit(key)
    if unit is None or target is None or " or " in unit or not math.isfinite(value):
        return None
    return f"{_magnitude(_in(value, unit), target):.{digits}g} {_SHOWN.get(target, target)}"
