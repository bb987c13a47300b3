"""``numerics.energy_balance = false``: the run without the energy ledger is the run with it bit
for bit in every series, snapshot and metric; every energy output is NaN and the run says the
balance was not kept (warnings, ``report.md``, ``metrics.json``)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import drillstring as ds
from drillstring.drilling import load_drill_config

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SHORT = {
    # torsion alone, on bottom, stick-slip (upwind below Courant number 1)
    "on-bottom-3000m.toml": {"numerics.cells": 120, "numerics.duration": 12.0, "numerics.courant": 0.95},
    # coupled, with the wall friction on both fields
    "coupled-deviated-3200m.toml": {"numerics.cells": 120, "numerics.duration": 6.0},
}


def _bits(x: object) -> bytes:
    return np.ascontiguousarray(np.asarray(x, dtype=np.float64)).tobytes()


@pytest.mark.parametrize("example", sorted(SHORT))
def test_a_run_without_the_ledger_is_the_run_with_it_bit_for_bit(example: str, tmp_path: Path) -> None:
    overrides = {**SHORT[example], "metrics.window": [SHORT[example]["numerics.duration"] / 2,
                                                      SHORT[example]["numerics.duration"]]}
    cfg = load_drill_config(EXAMPLES / example).with_overrides(overrides)
    assert cfg.numerics.energy_balance is True
    kept = ds.drill(cfg, progress=False)
    off = ds.drill(cfg.with_overrides({"numerics.energy_balance": False}), progress=False)
    assert kept.success and off.success
    for name in ("t", "surface_rpm", "bit_rpm", "motor_torque", "bit_torque", "omega_field", "torque_field"):
        assert _bits(getattr(off, name)) == _bits(getattr(kept, name)), name
    assert kept.axial.keys() == off.axial.keys()
    for name in kept.axial:
        assert _bits(off.axial[name]) == _bits(kept.axial[name]), name
    assert off.metrics == kept.metrics or repr(off.metrics) == repr(kept.metrics)
    assert repr(off.coupled_metrics) == repr(kept.coupled_metrics)
    # the ledger's balance closes; without it every energy output is NaN, and the run says so
    assert abs(kept.energy["balance_error"]) < 1e-11
    assert off.energy.keys() == kept.energy.keys()
    assert all(math.isnan(v) for v in off.energy.values())
    note = [w for w in off.warnings if "energy_balance" in w]
    assert len(note) == 1 and "not kept" in note[0]
    assert [w for w in off.warnings if w not in note] == list(kept.warnings)
    off.save(tmp_path / "off", plots=False)
    report = (tmp_path / "off" / "report.md").read_text()
    assert "Not kept (`numerics.energy_balance = false`)" in report
    saved = json.loads((tmp_path / "off" / "metrics.json").read_text())
    assert all(v is None for v in saved["energy"].values())


def test_energy_balance_takes_a_boolean() -> None:
    cfg = load_drill_config(EXAMPLES / "on-bottom-3000m.toml")
    with pytest.raises(ds.ValidationError) as err:
        ds.drill(cfg.with_overrides({"numerics.energy_balance": "no", "numerics.duration": 1.0}), progress=False)
    assert err.value.field == "numerics.energy_balance"
