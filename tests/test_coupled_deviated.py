"""examples/coupled-deviated-3200m.toml: a coupled axial-torsional run in a deviated well with the
wall friction on both fields. The numbers its header states, the energy balance, and the weight
the wall's axial friction takes from the bit (none without it)."""

from __future__ import annotations

from pathlib import Path

import pytest

import drillstring as ds

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "coupled-deviated-3200m.toml"


@pytest.fixture(scope="module")
def runs() -> dict[str, ds.DrillResult]:
    cfg = ds.load_drill_config(EXAMPLE)
    return {c: ds.drill(cfg.with_overrides([f"friction.coupling={c}"]), progress=False)
            for c in ("axial_torsional", "torsion_only")}


def test_the_header_numbers(runs: dict[str, ds.DrillResult]) -> None:
    res = runs["axial_torsional"]
    assert res.success and res.metrics_finite
    c = res.coupled_metrics
    assert c is not None and res.coupled_regime == "smooth drilling"
    assert c["rop_mean_m_per_h"] == pytest.approx(34.5, abs=0.05)
    assert c["wob_mean_N"] == pytest.approx(118.0e3, abs=50.0)
    assert c["tob_mean_Nm"] == pytest.approx(9.08e3, abs=5.0)
    assert c["mse_mean_Pa"] == pytest.approx(112e6, abs=0.5e6)
    m = res.metrics
    assert (m.bit_rpm_min, m.bit_rpm_max) == (pytest.approx(18.4, abs=0.05), pytest.approx(63.5, abs=0.05))
    assert m.ssi == pytest.approx(0.56, abs=0.005) and m.stick_slip_verdict == "no"
    other = runs["torsion_only"]
    assert other.metrics.ssi == pytest.approx(0.75, abs=0.005)
    assert (other.metrics.bit_rpm_min, other.metrics.bit_rpm_max) == (pytest.approx(8.2, abs=0.05),
                                                                    pytest.approx(68.5, abs=0.05))


def test_the_axial_friction_takes_weight_only_when_it_acts(runs: dict[str, ds.DrillResult]) -> None:
    set_wob = 120e3
    coupled, torsion_only = runs["axial_torsional"], runs["torsion_only"]
    assert coupled.coupled_metrics is not None and torsion_only.coupled_metrics is not None
    # the wall's axial friction: a loss in the ledger and a few per cent of the weight
    assert coupled.energy["axial_friction_loss"] > 0.0
    assert 0.01 < 1.0 - coupled.coupled_metrics["wob_mean_N"] / set_wob < 0.1
    # without it: no axial loss, the weight held to the string's velocity damping
    assert torsion_only.energy["axial_friction_loss"] == 0.0
    assert torsion_only.coupled_metrics["wob_mean_N"] == pytest.approx(set_wob, rel=5e-3)


def test_the_energy_balance_closes(runs: dict[str, ds.DrillResult]) -> None:
    for res in runs.values():
        e = res.energy
        assert abs(e["balance_error"]) < 1e-12, e
