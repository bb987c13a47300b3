"""Sweep axes: values of :class:`~drillstring.model.parameters.Parameters` fields and their product.

The axes are a mapping ``{field: values}`` (a sweep file's ``[grid]`` table). The keys are
:class:`Parameters` field names, or ``c1``, ``c2``, ..., ``c256`` for one initial velocity ``C_i``
(the other ``C_j`` keep their base values; missing ones are 0; ``i`` is at most
:data:`~drillstring.model.galerkin.MAX_MODES`, the largest model). The values are

* a list, tuple or 1-D array of values (``initial_velocities``: a list of sequences);
* ``{"linspace": [start, stop, count]}``: ``count`` evenly spaced values, both ends included
  (``numpy.linspace``);
* ``{"logspace": [start, stop, count]}``: ``count`` values evenly spaced on a log scale from
  ``start`` to ``stop`` (both > 0), ends included (``numpy.geomspace``). Note: ``start`` and
  ``stop`` are the end *values*, not powers of ten as in ``numpy.logspace``;
* a single value (a one-point axis).

:func:`linspace` and :func:`logspace` build the two dicts in Python. The runs are the
Cartesian product of the axes in the order given, the last axis varying fastest
(:func:`expand_axes`).
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping, Sequence
from typing import Any, Union

import numpy as np

from ..errors import ValidationError
from ..limits import as_float, as_int, check_run_count
from ..model.galerkin import MAX_MODES
from ..model.parameters import Parameters

__all__ = [
    "linspace",
    "logspace",
    "axis_values",
    "expand_axes",
    "grid_fields",
    "run_overrides",
    "apply_overrides",
]

_VELOCITY_KEY = re.compile(r"^c([1-9][0-9]*)$")

Axes = Mapping[str, Any]


def linspace(start: float, stop: float, count: int) -> dict[str, list[float]]:
    """``{"linspace": [start, stop, count]}``: ``count`` evenly spaced values, ends included."""
    return {"linspace": [start, stop, count]}


def logspace(start: float, stop: float, count: int) -> dict[str, list[float]]:
    """``{"logspace": [start, stop, count]}``: ``count`` log-spaced values from ``start`` to
    ``stop`` (end values, both > 0; not powers of ten)."""
    return {"logspace": [start, stop, count]}


def grid_fields() -> tuple[str, ...]:
    """Keys a grid may use: the :class:`Parameters` fields (``c1``, ``c2``, ... also accepted)."""
    return Parameters.field_names()


def _check_key(key: Any) -> str:
    """A grid key: a Parameters field, or ``c<i>`` for the initial velocity of a mode
    ``1 <= i <= MAX_MODES`` (a mode beyond is never in a model: its ``C_i`` could not matter)."""
    if isinstance(key, str):
        velocity = _VELOCITY_KEY.match(key)
        if key in Parameters.field_names() or (velocity and len(velocity.group(1)) <= 6
                                               and int(velocity.group(1)) <= MAX_MODES):
            return key
    raise ValidationError(
        "grid", key, "a Parameters field (" + ", ".join(Parameters.field_names()) + f") or c1, c2, ..., c{MAX_MODES}"
    )


def _spacing(key: str, kind: str, spec: Any) -> list[float]:
    allowed = f"{{{kind} = [start, stop, count]}} with finite start, stop and an integer count >= 1"
    if not isinstance(spec, Sequence) or isinstance(spec, str) or len(spec) != 3:
        raise ValidationError(f"grid.{key}", spec, allowed)
    start_f = as_float(f"grid.{key}.start", spec[0], allowed)
    stop_f = as_float(f"grid.{key}.stop", spec[1], allowed)
    count = as_int(f"grid.{key}.count", spec[2], 1)
    check_run_count(f"grid.{key}.count", count, count)
    if kind == "linspace":
        return np.linspace(start_f, stop_f, count).tolist()
    if not (start_f > 0 and stop_f > 0):
        raise ValidationError(
            f"grid.{key}", spec, "logspace end values start > 0 and stop > 0 (the values themselves, "
            "not powers of ten: {logspace = [0.1, 100.0, 4]} gives 0.1, 1, 10, 100)"
        )
    return np.geomspace(start_f, stop_f, count).tolist()


def _plain(value: Any) -> Any:
    """numpy scalars and arrays to Python floats/ints/lists (JSON-ready)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def axis_values(key: str, spec: Any) -> list[Any]:
    """The values of one grid axis (see the module docstring)."""
    key = _check_key(key)
    if isinstance(spec, Mapping):
        if len(spec) != 1 or next(iter(spec)) not in ("linspace", "logspace"):
            raise ValidationError(
                f"grid.{key}", dict(spec), "a list of values, {linspace = [start, stop, count]} or "
                "{logspace = [start, stop, count]}"
            )
        kind = next(iter(spec))
        return _spacing(key, kind, spec[kind])
    if key == "initial_velocities":
        # a list of sequences; a single flat sequence of numbers is one value
        if isinstance(spec, np.ndarray) and spec.ndim == 2:
            return [_plain(row) for row in spec]
        if isinstance(spec, (list, tuple)) and spec and all(
            isinstance(v, (list, tuple, np.ndarray)) for v in spec
        ):
            return [_plain(v) for v in spec]
        return [_plain(spec)]
    if isinstance(spec, (list, tuple, np.ndarray)):
        values = np.ravel(spec).tolist() if isinstance(spec, np.ndarray) else [_plain(v) for v in spec]
        if not values:
            raise ValidationError(f"grid.{key}", spec, "at least one value")
        return values
    return [_plain(spec)]


def expand_axes(axes: Axes) -> tuple[dict[str, list[Any]], list[dict[str, Any]]]:
    """The values of each axis ``{key: values}`` and the runs of their Cartesian product, each a
    dict of overrides. Errors name the field as a sweep file does (``grid.length``).

    Raises
    ------
    ValidationError
        For an unknown key or a malformed axis, or a product of more runs than the memory
        budget allows to plan (:func:`drillstring.limits.check_run_count`), before listing them.
    """
    if not isinstance(axes, Mapping):
        raise ValidationError("grid", axes, "a mapping {Parameters field: values}")
    values = {_check_key(key): axis_values(key, spec) for key, spec in axes.items()}
    sizes = [len(v) for v in values.values()]
    check_run_count("grid", " x ".join(f"{len(v)} {k}" for k, v in values.items()), math.prod(sizes))
    names = list(values)
    runs = [dict(zip(names, combo)) for combo in itertools.product(*values.values())]
    return values, runs


def run_overrides(run: Union[Parameters, Mapping[str, Any]]) -> dict[str, Any]:
    """One explicit run (a :class:`Parameters`, or a mapping of field overrides) as overrides."""
    if isinstance(run, Parameters):
        return run.to_dict()
    if not isinstance(run, Mapping):
        raise ValidationError("runs", run, "a list of Parameters or of mappings {field: value}")
    return {_check_key(key): _plain(value) for key, value in run.items()}


def apply_overrides(base: dict[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` (a :meth:`Parameters.to_dict`) with ``overrides`` applied; ``c<i>`` keys set
    ``initial_velocities[i - 1]`` (after any ``initial_velocities`` override), padding with 0."""
    full = dict(base)
    velocity_keys = []
    for key, value in overrides.items():
        match = _VELOCITY_KEY.match(key)
        if match:
            velocity_keys.append((int(match.group(1)), value))
        else:
            full[key] = value
    if velocity_keys:
        current = full.get("initial_velocities")
        velocities = list(current) if isinstance(current, (list, tuple)) else []
        for i, value in sorted(velocity_keys):
            velocities.extend([0.0] * (i - len(velocities)))
            velocities[i - 1] = value
        full["initial_velocities"] = velocities
    return full

