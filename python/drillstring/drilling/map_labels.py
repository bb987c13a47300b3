"""The labels of a stick-slip map's figures: an axis by its quantity and unit from the core's
configuration schema (:func:`axis_label`: SI or field units, the prefix that keeps the numbers
readable), a value of an axis not plotted, the well and the title of a figure."""

from __future__ import annotations

import numbers
import re
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .. import _core
from .map_table import CONTROLLER_AXIS
from .units import axis_unit, convert, system_of

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["axis_label"]

#: Units (the schema's, as pint writes them) a figure writes with the SI prefix that keeps the
#: numbers readable (``N`` -> ``kN``, ``N*m`` -> ``kN m``, ``Pa`` -> ``GPa``): those that start
#: with newtons, pascals, joules or watts; in field units, with foot-pounds force, pounds force
#: or psi (``ft*lbf`` -> ``kft-lbf``, ``psi`` -> ``Mpsi``).
_PREFIXED = r"(N|Pa|J|W|ft\*lbf|lbf|psi)(?=$|[*/ ])"

_PREFIXES = ((1e9, "G"), (1e6, "M"), (1e3, "k"))


_NO_UNIT = ("", "1", "-", "dimensionless")

_SUPERSCRIPTS = str.maketrans({"2": "²", "3": "³", "4": "⁴"})


def _readable_unit(unit: str) -> str:
    """A pint unit as a figure writes it: ``N*m`` -> ``N m``, ``kg*m^2`` -> ``kg m²``,
    ``ft*lbf`` -> ``ft-lbf``."""
    unit = unit.replace("**", "^").replace("ft*lbf", "ft-lbf").replace("*", " ")
    return re.sub(r"\^([234])(?!\d)", lambda m: m.group(1).translate(_SUPERSCRIPTS), unit)


def _schema() -> Mapping[str, Mapping[str, Any]]:
    """The core's configuration schema (``_core.drill_config_schema()``: dotted key, ``sections[]``
    for a section's keys, -> ``type``, ``unit``, ``label``, ``default``, ``description``); empty
    with a core that has none."""
    get = getattr(_core, "drill_config_schema", None)
    return get() if callable(get) else {}


def axis_label(key: str, values: Any = (), units: str = "si") -> tuple[str, float]:
    """The label ``"quantity [unit]"`` of the configuration key ``key`` (its label and unit from
    the core's schema, :func:`_schema`; without one, the key's last name) and the factor its
    SI ``values`` are drawn at: forces, torques, pressures, energies and powers get the SI prefix
    that keeps the largest value below 1000 (``bit.weight_on_bit`` up to 200000 N:
    ``"weight on bit [kN]"``, factor 1e-3). A section's key names its section
    (``sections[1].length``: ``"length, section 2 [m]"``). With ``units="field"`` the quantity
    is in the field unit of its key (:func:`drillstring.drilling.units.field_unit`: lengths in
    ft, diameters in in, weight on bit in klbf, torques in ft-lbf or kft-lbf, psi or Mpsi), the
    factor the conversion's (:func:`drillstring.drilling.units.convert`) times the prefix's."""
    system = system_of(units, "units")
    match = re.fullmatch(r"sections\[(\d+)\]\.(.+)", key)
    generic = f"sections[].{match.group(2)}" if match else key
    entry = _schema().get(generic) or {}
    label = str(entry.get("label") or generic.rsplit(".", 1)[-1].replace("_", " "))
    if match:
        label = f"{label}, section {int(match.group(1)) + 1}"
    unit = str(entry.get("unit") or "")
    factor = 1.0
    if system != "si" and unit and entry.get("type") in ("number", "array"):
        converted, unit = convert(1.0, unit, system, key=generic)
        factor = float(converted if converted is not None else 1.0)
    finite = np.asarray([v for v in values if isinstance(v, numbers.Real) and not isinstance(v, bool)], dtype=float)
    finite = finite[np.isfinite(finite)]
    if re.match(_PREFIXED, unit) and finite.size:
        biggest = float(np.abs(finite).max()) * factor
        for size, prefix in _PREFIXES:
            if biggest >= size:
                factor, unit = factor / size, prefix + unit
                break
    return (label if unit in _NO_UNIT else f"{label} [{_readable_unit(unit)}]"), factor


def value_text(key: str, value: Any, values: Any, units: str = "si") -> str:
    """``"label = value unit"`` of one value of an axis (the controller: ``"pi controller"``)."""
    if key == CONTROLLER_AXIS:
        return f"{value} controller"
    label, factor = axis_label(key, values, units)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        name, _, unit = label.partition(" [")
        return f"{name} = {float(value) * factor:.4g}" + (f" {unit[:-1]}" if unit else "")
    return f"{label} = {value}"


def well_name(frame: pd.DataFrame, units: str = "si") -> str:
    """The map's well: its name (``frame.attrs["name"]``: the configuration file's stem or the
    ``name`` given to :func:`~drillstring.drilling.maps.drill_map`), else the string's length (in ``units``)."""
    name = frame.attrs.get("name")
    if name:
        return str(name)
    sections = (frame.attrs.get("config") or {}).get("sections") or ()
    length = sum(float(s.get("length", 0.0)) for s in sections if isinstance(s, Mapping))
    scale, unit = axis_unit("m", units)
    return f"{length * scale:.0f} {unit} string" if length > 0 else "drilling system"


def _controller(frame: pd.DataFrame) -> Optional[str]:
    """The base configuration's controller type (None when it is an axis of the map)."""
    if CONTROLLER_AXIS in frame.attrs.get("axes", {}):
        return None
    kind = (((frame.attrs.get("config") or {}).get("top_drive") or {}).get("controller") or {}).get("type")
    return None if kind is None else str(kind)


def map_title(frame: pd.DataFrame, what: str, units: str = "si") -> str:
    controller = _controller(frame)
    return f"{well_name(frame, units)}: {what}" + (f", {controller} controller" if controller else "")
