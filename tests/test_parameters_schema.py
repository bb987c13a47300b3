"""The paper model's Parameters and the lumped model's parameters are validated by the core
(``_core.parameters_validate``, ``lumped_*``): one validator, Python forwarding its message."""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import pytest

from drillstring import _core
from drillstring.drilling.lumped import lumped, lumped_defaults
from drillstring.errors import ValidationError
from drillstring.model.parameters import Parameters, check_damping_rate


def test_every_parameters_field_and_default_is_the_cores() -> None:
    core = _core.parameters_defaults()
    fields = {f.name: f.default for f in dataclasses.fields(Parameters)}
    assert set(fields) == set(core)
    for name, default in fields.items():
        assert default == (tuple(core[name]) if isinstance(core[name], list) else core[name]), name
    # Table 1 of the paper (aluminium reference): an oracle of the values
    assert (core["length"], core["youngs_modulus"], core["density"], core["poisson_ratio"]) == (100.0, 0.7e11,
                                                                                                  2.7e3, 0.34)
    assert (core["outer_diameter"], core["inner_diameter"], core["omega"]) == (0.2, 0.12, math.pi)


@pytest.mark.parametrize(("changes", "field", "allowed"), [
    ({"length": "long"}, "length", "a finite real number, 0 < length < inf"),
    ({"length": -1.0}, "length", "0 < length < inf"),
    ({"density": math.nan}, "density", "a finite real number, 0 < density < inf"),
    ({"inner_diameter": 0.3}, "inner_diameter", "0 <= inner_diameter < outer_diameter = 0.2"),
    ({"poisson_ratio": -1.0}, "poisson_ratio", "-1 < poisson_ratio < 0.5"),
    ({"omega": math.inf}, "omega", "a finite real number (rad/s, any sign)"),
    ({"damping_rate": -0.5}, "damping_rate", "a finite real number >= 0 (1/s)"),
    ({"damping_rate": True}, "damping_rate", "a finite real number >= 0 (1/s)"),
    ({"initial_velocities": "0.1"}, "initial_velocities", "a sequence of finite real numbers (C_1, C_2, ...) in rad/s"),
    ({"initial_velocities": [0.1, "x"]}, "initial_velocities[1]", "a finite real number (rad/s)"),
    ({"k5_variant": 2}, "k5_variant", "one of 'paper', 'energy'"),
    ({"model": "exact"}, "model", "one of 'paper', 'consistent'"),
])
def test_the_core_validates_and_python_forwards_the_message(changes: dict[str, Any], field: str,
                                                            allowed: str) -> None:
    with pytest.raises(ValidationError) as err:
        Parameters(**changes)
    assert err.value.field == field and err.value.allowed == allowed, str(err.value)
    (value,) = changes.values()
    shown = value[1] if field.endswith("]") else value
    assert err.value.value is shown or err.value.value == shown  # the value as given, not its JSON
    if not any(isinstance(v, float) and not math.isfinite(v) for v in changes.values()):
        with pytest.raises(ValidationError) as core:  # the core's own message, forwarded
            _core.parameters_validate(json.dumps(changes))
        assert (core.value.field, core.value.allowed) == (field, allowed)


def test_values_are_stored_as_given_floats() -> None:
    p = Parameters(length=250, initial_velocities=[1, 0.5], omega=0.1 + 0.2)
    assert p.length == 250.0 and isinstance(p.length, float)
    assert p.initial_velocities == (1.0, 0.5) and p.omega == 0.1 + 0.2
    assert check_damping_rate(2) == 2.0
    with pytest.raises(ValidationError) as err:
        check_damping_rate(-1.0)
    assert err.value.field == "damping_rate"


def test_lumped_parameters_are_the_cores_with_field_messages() -> None:
    assert lumped_defaults()["jr"] == 2122.0  # Navarro-Lopez & Cortes 2007
    for params, field, allowed in [({"weight": 1.0}, "weight", "one of jr, jb, kt"),
                                   ({"tm": "6000"}, "tm", "a number"),
                                   ({"tm": math.nan}, "tm", "a finite number"),
                                   ({"jb": 0.0}, "jb", "")]:
        with pytest.raises(ValidationError) as err:
            lumped(params, duration=1.0)
        assert err.value.field == field and err.value.allowed.startswith(allowed), str(err.value)
