"""The numpy port of Aarsnes & van de Wouw's (2019) coupled axial-torsional scheme (``benchmarks/avdw_numpy.py``)
against the Octave run of their published MATLAB code (tests/reference/aarsnes-van-de-wouw-2019), and the
parts of its converged twin (exact delay, set-valued bit law) against closed forms.

The published mode evaluates their floating-point operations in their order, so its numbers are Octave's:
every stored float32 sample equals the port's float64 value rounded to float32, and the stored final cut
surface (float64) is equal, not close. The verdicts of the converged twin (the README, section
"Independent port") come from ``benchmarks/avdw_study.py``; the slow tests below pin them.
"""

from __future__ import annotations

import importlib
import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from avdw_reference import CASES, LONG_CASES, final_cut_surface, full, reference, window

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
SERIES = ("wob_N", "tob_Nm", "top_force_N", "top_torque_Nm", "depth_of_cut_m", "bit_cell_speed_end_m_s",
          "bit_cell_speed_end_rad_s")
WINDOW_EXTRA = ("bit_face_speed_m_s", "bit_face_speed_rad_s", "last_wob_N", "last_tob_Nm", "last_d_m", "last_ga",
                "last_g_tt_Nm", "last_wf_N")


@pytest.fixture(scope="module")
def an():  # type: ignore[no-untyped-def]
    sys.path.insert(0, str(BENCHMARKS))
    try:
        yield importlib.import_module("avdw_numpy")
    finally:
        sys.path.remove(str(BENCHMARKS))


def setpoints(case: str) -> tuple[float, float]:
    rpm, rop = case.removeprefix("rpm").split("_rop")
    return float(rpm), float(rop)


def as_stored(x: np.ndarray) -> np.ndarray:
    return np.asarray(x).astype(np.float32).astype(np.float64)


# ---------------------------------------------------------------- the published mode is their run


@pytest.mark.parametrize("case", ["rpm30_rop30", "rpm60_rop60"])
def test_published_port_is_the_octave_run_over_the_start(an, case: str) -> None:  # type: ignore[no-untyped-def]
    """3 s (the stuck start of their initial state, the torsional stick branch, the break-away): every
    stored sample of the whole-run series (every 10th step, float32) is the port's value rounded."""
    rpm, rop = setpoints(case)
    res = an.simulate(rpm, rop, 3.0)
    ref = full(case)
    k = len(res["t_end_s"]) // 10
    assert k == 100
    np.testing.assert_array_equal(as_stored(res["t_end_s"][9::10]), ref["t_end_s"][:k])
    for col in SERIES:
        np.testing.assert_array_equal(as_stored(res[col][9::10]), ref[col][:k], err_msg=col)
    assert res["last_stuck"][:300].any()  # the start is stuck: the stick branch is exercised


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES)
def test_published_port_is_the_octave_run(an, case: str) -> None:  # type: ignore[no-untyped-def]
    """The whole 25 s run: the 20-25 s window at every step, the decimated run, the final cut surface."""
    rpm, rop = setpoints(case)
    res = an.simulate(rpm, rop, 25.0)
    assert len(res["t_end_s"]) == reference()["cases"][case]["published_25s"]["steps"]
    w, f = window(case), full(case)
    n = len(w["t_end_s"])
    for col in SERIES + WINDOW_EXTRA:
        np.testing.assert_array_equal(as_stored(res[col][-n:]), w[col], err_msg=col)
    for col in SERIES:
        np.testing.assert_array_equal(as_stored(res[col][9::10]), f[col], err_msg=col)
    cut = final_cut_surface(case)
    np.testing.assert_array_equal(res["final_state"][-len(cut):], cut)
    np.testing.assert_array_equal(as_stored(res["last_stuck"][-n:]), (w["last_g_tt_Nm"] != 0).astype(float))
    got = an.metrics(res, rpm, rop, (20.0, 25.0))
    want = reference()["cases"][case]["published_25s"]["metrics"]
    assert got["rop_mean_m_per_h"] == pytest.approx(want["rop_mean_m_per_h"], rel=1e-9)
    assert got["wob_mean_N"] == pytest.approx(want["wob_N"]["mean"], rel=1e-9)
    assert got["tob_mean_Nm"] == pytest.approx(want["tob_Nm"]["mean"], rel=1e-9)
    assert got["mse_mean_Pa"] == pytest.approx(want["mse_mean_Pa"], rel=1e-9)
    assert got["stuck_fraction"] == want["torsional_stick_fraction"]
    assert got["contact_regime_fraction"] == want["contact_regime_fraction"]
    assert got["settled"] == want["settled"]


@pytest.mark.slow
@pytest.mark.parametrize("case", LONG_CASES)
def test_published_port_is_the_octave_run_to_120s(an, case: str) -> None:  # type: ignore[no-untyped-def]
    rpm, rop = setpoints(case)
    res = an.simulate(rpm, rop, 120.0)
    w = window(case, long=True)
    n = len(w["t_end_s"])
    for col in SERIES:
        np.testing.assert_array_equal(as_stored(res[col][-n:]), w[col], err_msg=col)
    cut = final_cut_surface(case, long=True)
    np.testing.assert_array_equal(res["final_state"][-len(cut):], cut)


# ---------------------------------------------------------------- the parts of the converged twin


def test_set_valued_bit_law_phases(an) -> None:  # type: ignore[no-untyped-def]
    """The phases in closed form with parameters.m's constants (K_a = a zeta eps = 3.888e6 N/m,
    K_t = a^2 eps / 2 = 3.4992e5 N, W_f = a l sigma = 71280 N, T_f = gamma mu a W_f = 4618.944 N m)."""
    p = an.parameters(30, 30)
    d = 2e-3
    wc, tc = 7776.0, 699.84
    # cutting, full contact (the string pushes harder than the law): the law's loads
    w, t, wf, g, stuck = an.set_valued_bit(p, 2e5, 1e5, d)
    assert (w, t, wf, g, stuck) == pytest.approx((wc + 71280.0, tc + 4618.944, 71280.0, 0.0, False), rel=1e-12)
    assert stuck is False
    # partial contact: the force that holds the face, the contact torque in proportion
    w, t, wf, g, stuck = an.set_valued_bit(p, wc + 30000.0, 1e5, d)
    assert (w, t, wf) == pytest.approx((wc + 30000.0, tc + 0.0648 * 30000.0, 30000.0), rel=1e-12)
    # rising face while cutting: no contact force, the cutting loads only
    w, t, wf, g, stuck = an.set_valued_bit(p, 0.5 * wc, 1e5, d)
    assert (w, t, wf) == pytest.approx((wc, tc, 0.0), rel=1e-12)
    # stick: the torque that holds the face at rest, below T_c + T_f (negative too), face held axially
    for hold_t in (tc + 4618.944 - 1.0, -50.0):
        w, t, wf, g, stuck = an.set_valued_bit(p, 1e5, hold_t, d)
        assert stuck and t == hold_t and w == 1e5 and g == pytest.approx(hold_t - tc - 4618.944, abs=1e-9)
    # stick with the string pulling the bit up: no weight
    assert an.set_valued_bit(p, -10.0, 0.0, d)[0] == 0.0
    # lift-off
    assert an.set_valued_bit(p, 1e5, 1e5, 0.0) == (0.0, 0.0, 0.0, 0.0, False)
    assert an.set_valued_bit(p, 1e5, 1e5, -1e-3)[4] is False


def test_exact_delay_against_a_surface_known_in_closed_form(an) -> None:  # type: ignore[no-untyped-def]
    """A bit whose depth is a known function of its angle, x = g(phi), turning at a varying speed (stopping
    once): the delay returns g(phi) - g(phi - 2 pi / N) up to the interpolation error (<= max g'' dphi^2 / 8),
    and exactly where g is linear."""
    p = an.parameters(30, 30)
    blade = 2 * math.pi / p["N"]
    dt = 3.75e-4
    t = np.arange(1, 20001) * dt
    omega = np.pi * (1.0 + 0.9 * np.sin(2 * np.pi * 0.7 * t))
    omega[(t > 2.0) & (t < 2.3)] = 0.0  # stick
    phi = np.cumsum(omega * dt)
    g2 = 2e-3

    def g(x: np.ndarray) -> np.ndarray:
        return p["dNom"] / blade * x + g2 * np.sin(3.0 * x)

    delay = an.CutDelay(p, len(t))
    # the records before the start lie on the helix of the set-points: start g with g(0) = 0, same slope
    errors, linear_errors = [], []
    lin = an.CutDelay(p, len(t))
    for ph in phi:
        x = float(g(np.array(ph)))
        d = delay.depth_per_blade(ph, x)
        if ph > blade:
            errors.append(d - (x - float(g(np.array(ph - blade)))))
        xl = p["dNom"] / blade * ph
        linear_errors.append(lin.depth_per_blade(ph, xl) - p["dNom"])
        delay.push(ph, x)
        lin.push(ph, xl)
    dphi = float(np.max(np.diff(phi)))
    assert np.max(np.abs(errors)) <= g2 * 9.0 * dphi**2 / 8 * 1.0001
    assert np.max(np.abs(errors)) > 0.0
    assert np.max(np.abs(linear_errors)) < 1e-15


def upwind_vs_delay(an, cells: int, freq: float) -> float:  # type: ignore[no-untyped-def]
    """Their chain of ``cells`` upwind cells at their Courant number (sub-cycled as ``simulate`` does) against
    the exact delay, driven by a bit turning at omega0 = 30 rpm and advancing at V0 (1 + 0.5 sin 2 pi f t):
    the amplitude of the difference in the depth of cut over that of the bit's axial oscillation, once
    periodic (``|exp(-s tN) - H(s)|`` with ``H`` the chain's transfer function)."""
    p = an.parameters(30, 30)
    dt = 0.003 / 8
    sub = max(1, math.ceil(cells * dt * p["omegaMAX"] - 1e-12))
    lcut = np.linspace(0.0, 1.0, cells) * p["dNom"]
    steps = int(round(4.0 / dt))
    t = np.arange(steps) * dt
    vb = p["V0"] * (1 + 0.5 * np.sin(2 * np.pi * freq * t))
    d_chain = np.empty(steps)
    for i in range(steps):
        d_chain[i] = lcut[-1]
        for _ in range(sub):
            lcut = an.upwind_cut_surface(lcut, dt / sub, 1 / cells, p["omega0"], float(vb[i]), p["N"])
    x = np.concatenate(([0.0], np.cumsum(vb * dt)))[:-1]  # position at t (piecewise linear in t)
    d_delay = x - np.interp(t - p["tN"], t, x)
    tail = t > 2.0
    amp_x = 0.5 * p["V0"] / (2 * np.pi * freq)
    return float(np.ptp(d_chain[tail] - d_delay[tail])) / (2 * amp_x)


def test_upwind_cut_surface_converges_to_the_exact_delay(an) -> None:  # type: ignore[no-untyped-def]
    """At 2 Hz (the blade-pass frequency at 30 rpm, where their runs' axial oscillation lives) the chain on
    their 169 cells misses the delay by 0.1 of the bit's axial amplitude (its gain there is 0.903, the
    README's transfer function), and the miss halves with each doubling of the cells (first order: the
    spread of delays of a chain of geometric stages has the variance tN^2 (1 - C) / Pl)."""
    errors = [upwind_vs_delay(an, cells, 2.0) for cells in (169, 338, 676)]
    assert errors[0] == pytest.approx(1 - 0.903, abs=0.003)
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.1)
    assert errors[1] / errors[2] == pytest.approx(2.0, rel=0.1)


def test_converged_scheme_is_the_published_one_where_the_physics_agrees(an) -> None:  # type: ignore[no-untyped-def]
    """The variants' code path with every switch at its published value (the upwind chain on Pl cells named
    explicitly, the damping factor 2, thresholds, last-cell speeds) reproduces the published run bit for bit;
    the damping at its named rate does not."""
    a = an.simulate(60, 30, 0.3)
    b = an.simulate(60, 30, 0.3, replace(an.PUBLISHED, cut_cells=84))
    c = an.simulate(60, 30, 0.3, replace(an.PUBLISHED, cut_cells=84, damping=1.0))
    for col in SERIES:
        np.testing.assert_array_equal(a[col], b[col])
    assert not np.array_equal(a["top_force_N"], c["top_force_N"])


# ---------------------------------------------------------------- the verdicts of the converged twin


@pytest.mark.slow
def test_exact_delay_grows_an_axial_limit_cycle_where_their_run_settles(an) -> None:  # type: ignore[no-untyped-def]
    """30 rpm / 30 m/h, their physics (damping 2k, thresholds) with the exact delay: at 115-120 s the bit
    bounces between rising and 4.8 V0 with the contact force partial half the time, where their run (the
    reference's 120 s run) has settled to steady drilling."""
    published = reference()["cases"]["rpm30_rop30"]["long_120s"]["metrics"]
    assert published["settled"] and published["bit_axial_speed_spread_over_V0"] < 1e-3
    res = an.simulate(30, 30, 120.0, replace(an.PUBLISHED, cut_surface="delay"))
    m = an.metrics(res, 30, 30, (115.0, 120.0))
    assert not m["settled"]
    assert m["bit_axial_speed_spread_over_V0"] > 3.0
    assert m["bit_axial_speed_min_m_s"] < 0.0
    assert m["contact_regime_fraction"] > 0.3
    assert m["stuck_fraction"] == 0.0  # axial, not torsional


@pytest.mark.slow
def test_exact_delay_stick_slips_where_their_run_does_not(an) -> None:  # type: ignore[no-untyped-def]
    """30 rpm / 60 m/h: with the exact delay (their damping and thresholds) the bit sticks about 13 % of
    115-120 s and peaks near 4 times the set-point; their run has no stick after its start."""
    published = reference()["cases"]["rpm30_rop60"]["long_120s"]["metrics"]
    assert not published["stick_slip"] and published["settled"]
    res = an.simulate(30, 60, 120.0, replace(an.PUBLISHED, cut_surface="delay"))
    m = an.metrics(res, 30, 60, (115.0, 120.0))
    assert 0.05 < m["stuck_fraction"] < 0.3
    assert m["bit_rpm_max"] > 90.0


@pytest.mark.parametrize("variant", ["published", "converged"])
def test_energy_balance_closes_at_the_applied_damping_rate(an, variant: str) -> None:  # type: ignore[no-untyped-def]
    """0-5 s at 30 rpm / 30 m/h (the stuck start, the break-away, the set-valued phases): the string's energy
    change equals the work of the top minus that into the rock and that of the damping at the rate each mode
    applies (2k published, k converged), up to the upwind schemes' numerical dissipation (a loss: at most
    1e-3 of the work in, never a gain beyond 1e-6); the other rate misses by more than 2 %."""
    scheme = an.PUBLISHED if variant == "published" else an.CONVERGED
    res = an.simulate(30, 30, 5.0, scheme)
    step = 0.003
    energy = np.concatenate(([float(res["energy_start_J"])], res["energy_end_J"]))
    work_in = step * float(res["top_power_W"].sum())
    rock, damping = step * float(res["bit_power_W"].sum()), step * float(res["damping_power_W"].sum())
    residual = energy[-1] - energy[0] - (work_in - rock - damping)
    assert -1e-3 * work_in < residual < 1e-6 * work_in
    per_step = np.diff(energy) - step * (res["top_power_W"] - res["bit_power_W"] - res["damping_power_W"])
    assert per_step.max() < 1e-6 * work_in
    other = 0.5 if variant == "published" else 2.0  # the named rate against the applied one, and back
    assert abs(residual - (1 - other) * damping) > 0.02 * work_in
