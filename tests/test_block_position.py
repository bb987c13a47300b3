"""The block position of a coupled run (``block_position``, the top of the string's position from
the start, down positive): the hoist's ramped velocity integrated, and in steady drilling the
block follows the bit."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import drillstring as ds

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_a_pick_ups_block_travel_is_the_ramped_hoist_speed_integrated() -> None:
    cfg = ds.load_drill_config(EXAMPLES / "pickup-3200m.toml")
    hoist = cfg.hoist
    assert hoist is not None and hoist.mode == "velocity"
    result = ds.drill(cfg, progress=False)
    t, block = result.t, result.axial["block_position"]
    v, tau = hoist.speed, hoist.ramp_time
    # the setpoint's first-order approach from rest: v (1 - exp(-t / tau)), integrated
    expected = v * (t - tau * (1.0 - np.exp(-t / tau)))
    assert block[0] == 0.0
    assert block[-1] == pytest.approx(expected[-1], rel=2e-4)
    assert np.max(np.abs(block - expected)) < 2e-4 * abs(expected[-1])


def test_in_steady_drilling_the_block_descends_at_the_bits_rate() -> None:
    result = ds.drill(EXAMPLES / "coupled-deviated-3200m.toml", progress=False)
    t, a = result.t, result.axial
    late = t >= 0.5 * t[-1]
    block_rate = np.polyfit(t[late], a["block_position"][late], 1)[0]
    bit_rate = np.polyfit(t[late], a["bit_depth"][late], 1)[0]
    assert block_rate > 0.0 and math.isfinite(block_rate)
    assert block_rate == pytest.approx(bit_rate, rel=5e-3)
    assert "block_position" in result.to_pandas().columns


def test_a_torsion_only_run_has_no_block_position() -> None:
    result = ds.drill(ds.load_drill_config(EXAMPLES / "on-bottom-3000m.toml").with_overrides(
        {"numerics.duration": 2.0, "numerics.cells": 100}), progress=False)
    assert "block_position" not in result.to_pandas().columns
