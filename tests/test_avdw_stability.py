"""Aarsnes & van de Wouw's linear stability condition (``drillstring.drilling.coupled_stability``)
against their own scripts run in GNU Octave (tests/reference/aarsnes-van-de-wouw-2019: the
non-dimensional map of ``MAIN_Torsional_FreqStabMap.m`` and the dimensional loops of
``Coupled/freqPlots.m``), and the torsional condition ``M_T > 1`` against the onset of stick-slip
found by simulation (``ds.drill`` of the converged twin, exact delay, 180-240 s)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from avdw_reference import reference, stability

from drillstring.drilling import drill, load_drill_config
from drillstring.drilling.coupled_stability import (
    negative_real_axis_gains,
    regenerative_loop_gains,
    torsional_gain_nondim,
)

CONVERGED = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-van-de-wouw-2019-converged.toml"


def _cfg(rpm: float, rop: float, damping: float = 2.0):  # type: ignore[no-untyped-def]
    return load_drill_config(CONVERGED).with_overrides(
        {"top_drive.rpm": rpm, "hoist.speed": rop / 3600, "damping_rate": damping})


@pytest.mark.parametrize("rop", [30, 60])
def test_the_dimensional_loops_are_their_octave_numbers(rop: int) -> None:
    """M_T, M_A and M_G of freqPlots.m's loops at 30 / 60 / 120 rpm with the damping applied (2 1/s) and
    named (1 1/s), and the torsional boundary between the 0.5 rpm steps of their sweep."""
    ref = reference()["stability"]["dimensional"][f"rop{rop}"]
    for rpm, want in ref["at_cases"].items():
        got = regenerative_loop_gains(_cfg(float(rpm), rop))
        assert got.torsional == pytest.approx(want["MT_2k"], rel=1e-9)
        assert got.axial == pytest.approx(want["MA_2k"], rel=1e-9)
        assert got.combined == pytest.approx(want["MG_2k"], rel=1e-9)
        assert got.torsional_frequency == pytest.approx(want["wT_2k_rad_s"], rel=1e-9)
        named = regenerative_loop_gains(_cfg(float(rpm), rop, damping=1.0))
        assert named.torsional == pytest.approx(want["MT_named"], rel=1e-9)
        assert named.axial == pytest.approx(want["MA_named"], rel=1e-9)
    ((lo, hi),) = ref["MT_2k"]["switches_between_rpm"]
    assert regenerative_loop_gains(_cfg(lo, rop)).torsionally_unstable
    assert not regenerative_loop_gains(_cfg(hi, rop)).torsionally_unstable


def test_the_nondimensional_map_is_theirs() -> None:
    """Every 7th point of their 120 x 120 map (eta = 0.7) and its stability boundary."""
    s = stability()
    v0, om, z = s["nondim.V0"], s["nondim.Om"], s["nondim.Z"]
    for i in range(0, 120, 7):
        for j in range(3, 120, 7):
            assert torsional_gain_nondim(float(v0[i]), float(om[j])) == pytest.approx(z[i, j], rel=1e-9, abs=1e-300)
    assert (z > 1).any() and (z <= 1).any()


def test_the_crossing_criterion_on_a_closed_form() -> None:
    """G = 2 exp(-j w) / (1 + j w / 10): crossings where w + atan(w / 10) = (2 k + 1) pi (seven below
    w = 40) with the gain 2 / sqrt(1 + w^2/100), largest first; a loop that never reaches the negative
    axis has none."""
    w = np.linspace(1e-3, 40.0, 400_001)
    g = 2 * np.exp(-1j * w) / (1 + 1j * w / 10)
    gains, freqs = negative_real_axis_gains(g, w)
    assert len(gains) == 7 and np.all(np.diff(gains) < 0)
    for k, wc in enumerate(freqs):
        assert (wc + np.arctan(wc / 10)) / np.pi == pytest.approx(2 * k + 1, abs=1e-8)
        assert gains[k] == pytest.approx(2 / np.sqrt(1 + wc**2 / 100), rel=1e-8)
    assert len(negative_real_axis_gains(1 / (1 + 1j * w), w)[0]) == 0


def test_one_uniform_section_only() -> None:
    cfg = load_drill_config(CONVERGED)
    two = cfg.with_overrides({"sections": [cfg.to_dict()["sections"][0]] * 2})
    with pytest.raises(ValueError, match="sections"):
        regenerative_loop_gains(two)


def _stick(rpm: float, rop: float) -> float:
    r = drill(_cfg(rpm, rop))
    assert r.success and abs(r.energy["balance_error"]) < 1e-12
    return r.metrics.stuck_fraction


# The simulated onset of stick-slip (the bit stuck in 180-240 s), bracketed in the ROP at each rotary
# speed by the sweep of the drilling guide, and the largest ROP found without it.
ONSET = {30.0: (27.5, 30.0), 60.0: (80.0, 90.0)}
ONSET_SLOW = {120.0: (250.0, 300.0)}


def _check_onset(rpm: float, below: float, above: float) -> None:
    """Stick-slip starts between ``below`` and ``above`` m/h; their torsional condition (M_T
    proportional to the ROP: ``K_t`` is, nothing else in ``G_t`` depends on it) puts the onset of the
    linear instability at the ROP where M_T = 1, 5 to 10 times lower: M_T is between 5 and 10 at the
    simulated onset (measured: 8.5-9.2 at 30 rpm, 6.5-7.3 at 60 rpm, 5.1-6.1 at 120 rpm)."""
    m_below = regenerative_loop_gains(_cfg(rpm, below)).torsional
    m_above = regenerative_loop_gains(_cfg(rpm, above)).torsional
    assert m_above / m_below == pytest.approx(above / below, rel=1e-9)  # M_T proportional to the ROP
    linear_onset = below / m_below
    assert regenerative_loop_gains(_cfg(rpm, linear_onset * 0.999)).torsional < 1.0
    assert regenerative_loop_gains(_cfg(rpm, linear_onset * 1.001)).torsional > 1.0
    assert _stick(rpm, below) == 0.0
    assert _stick(rpm, above) > 0.0
    assert 5.0 <= m_below and m_above <= 10.0


@pytest.mark.parametrize("rpm", sorted(ONSET))
def test_stick_slip_starts_where_the_torsional_gain_is_5_to_10(rpm: float) -> None:
    _check_onset(rpm, *ONSET[rpm])


@pytest.mark.slow
@pytest.mark.parametrize("rpm", sorted(ONSET_SLOW))
def test_stick_slip_starts_where_the_torsional_gain_is_5_to_10_at_120_rpm(rpm: float) -> None:
    _check_onset(rpm, *ONSET_SLOW[rpm])


def test_the_linear_boundary_in_rpm_against_the_simulations() -> None:
    """At 30 m/h their torsional condition is unstable below 93.5-94 rpm (M_T = 9.2 at 30 rpm, 2.45 at
    60, 0.61 at 120); the simulations stick-slip only at 30 rpm (stuck 0.9 %), and oscillate without
    sticking at 45-150 rpm (the axial loop is unstable at all of them, M_A 4.6-11.3): the sweep of the
    drilling guide. Here its ends: 45 rpm, M_T = 4.3 > 1 and no stick."""
    assert regenerative_loop_gains(_cfg(45.0, 30.0)).torsional == pytest.approx(4.31, abs=0.01)
    assert _stick(45.0, 30.0) == 0.0
