"""The Detournay bit with velocity-weakening wear-flat friction (``bit.law =
"detournay_weakening"``, examples/detournay-weakening.toml) against its closed form: steady
drilling at the rate of penetration ``V`` and the bit speed ``Omega`` cuts ``d = 2 pi V / Omega``
per revolution with the weight ``W = a zeta eps d + a l sigma`` and the torque
``T = a^2 eps d / 2 + gamma mu(Omega) a^2 l sigma / 2``, ``mu(w) = mu + (mu_0 - mu) exp(-decay |w|)``
(Detournay & Defourny 1992; Richard, Germay & Detournay 2007; the weakening of Navarro-Lopez &
Cortes 2007). Without weakening (``mu_0 = mu``) the law is the Detournay law to the bit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from drillstring.drilling import DrillConfig, drill, load_drill_config
from drillstring.errors import ValidationError

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "detournay-weakening.toml"

#: A shorter, coarser run of the example (the closed form holds on any grid).
SHORT = {"numerics.cells": 200, "numerics.duration": 40.0, "metrics.window": [30.0, 40.0],
         "numerics.initial_state": "steady"}


def _closed_form(cfg: DrillConfig, rop: float, omega: float) -> tuple[float, float]:
    """The law's steady weight and torque on bit at ``rop`` m/s and ``omega`` rad/s, written out."""
    a, d_ = cfg.bit.radius, cfg.bit.detournay
    mu = d_.friction + (cfg.bit.weakening.static_friction - d_.friction) * math.exp(-cfg.bit.weakening.decay * omega)
    depth = 2.0 * math.pi * rop / omega
    weight = a * d_.cutting_ratio * d_.intrinsic_specific_energy * depth + a * d_.wear_flat_length * d_.contact_strength
    torque = 0.5 * a * a * d_.intrinsic_specific_energy * depth \
        + 0.5 * d_.geometry * mu * a * a * d_.wear_flat_length * d_.contact_strength
    return weight, torque


def test_steady_drilling_is_the_closed_form() -> None:
    # decay = 1 s/rad: at 30 rpm mu = 0.6 + 0.3 exp(-pi) = 0.613, the steady state holds (the
    # example's 0.5 s/rad, a steeper fall of the torque with the speed, stick-slips instead)
    cfg = load_drill_config(EXAMPLE).with_overrides({**SHORT, "bit.weakening.decay": 1.0})
    assert (cfg.bit.law, cfg.bit.weakening.static_friction) == ("detournay_weakening", 0.9)
    result = drill(cfg)
    assert result.success, result.message
    m = result.coupled_metrics
    assert m is not None and m["bounce_fraction"] == 0.0
    window = (result.t >= 30.0) & (result.t <= 40.0)
    omega = float(np.mean(result.bit_rpm[window])) * math.pi / 30.0
    rop = m["rop_mean_m_per_h"] / 3600.0
    weight, torque = _closed_form(cfg, rop, omega)
    assert omega == pytest.approx(math.pi, rel=1e-3)  # the top drive's 30 rpm
    assert m["wob_mean_N"] == pytest.approx(weight, rel=1e-5)
    assert m["tob_mean_Nm"] == pytest.approx(torque, rel=1e-5)
    # the weakened friction at 30 rpm is above the fast one: 1 % more torque than the Detournay law's
    plain = drill(cfg.with_overrides({"bit.law": "detournay"}))
    assert m["tob_mean_Nm"] > plain.coupled_metrics["tob_mean_Nm"] * 1.005
    assert abs(result.energy["balance_error"]) < 1e-12


def test_without_weakening_it_is_the_detournay_law_to_the_bit() -> None:
    cfg = load_drill_config(EXAMPLE).with_overrides(
        {**SHORT, "numerics.duration": 10.0, "metrics.window": [5.0, 10.0], "numerics.initial_state": "rest",
         "bit.weakening.static_friction": 0.6})
    weak = drill(cfg)
    plain = drill(cfg.with_overrides({"bit.law": "detournay"}))
    assert weak.success and plain.success
    for name in ("bit_rpm", "motor_torque", "bit_torque"):
        np.testing.assert_array_equal(getattr(weak, name), getattr(plain, name))
    np.testing.assert_array_equal(weak.axial["weight_on_bit"], plain.axial["weight_on_bit"])


@pytest.mark.parametrize(("key", "value"), [("bit.weakening.static_friction", 0.5), ("bit.weakening.decay", -1.0)])
def test_bad_keys_are_refused_by_name(key: str, value: float) -> None:
    with pytest.raises(ValidationError, match=key.replace(".", r"\.")):
        drill(load_drill_config(EXAMPLE).with_overrides({key: value}))


def test_the_law_needs_a_hoist() -> None:
    cfg = load_drill_config(EXAMPLE)
    with pytest.raises(ValidationError, match=r"bit\.law"):
        drill(cfg.with_overrides({"hoist": None}))
