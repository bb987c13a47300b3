"""Checks of the Octave reference run of Aarsnes & van de Wouw's (2019) coupled axial-torsional code.

The stored series (tests/reference/aarsnes-van-de-wouw-2019, produced by make_reference.sh from their
published MATLAB code) are checked against relations they must satisfy whatever their code does
internally: the parameters against their formulas, the bit law with the constants of parameters.json,
the discrete momentum and energy balances of the string (which fix the damping rate and the boundary
forces), the steady drilling state in closed form (depth of cut per revolution = ROP / rotary speed),
and their transfer functions recomputed with numpy. These verify both the data and the reading of
their conventions written down in the README and parameters.json.

Not checkable here (stated, not tested): the paper's own figures (no digitised data). Whether the cut
surface converges, and the time series against an independent solver: tests/test_avdw_oracle.py (the
numpy port of benchmarks/avdw_numpy.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from avdw_reference import CASES, LONG_CASES, final_cut_surface, full, parameters, reference, stability, window

PAR = parameters()
REF = reference()
STR = PAR["string"]
BIT = PAR["bit"]
RHO = STR["density_kg_m3"]
AREA = STR["sections"][0]["area_m2"]
POLAR = STR["sections"][0]["polar_moment_m4"]
LENGTH = STR["sections"][0]["length_m"]
K_NAMED = PAR["damping"]["ka_named_1_s"]
K_APPLIED = PAR["damping"]["axial_velocity_damping_rate_applied_1_s"]
STEP = PAR["discretisation"]["output_step_s"]


def setpoints(case: str) -> tuple[float, float]:
    """omega0 (rad/s) and V0 (m/s) from the case name, in closed form."""
    rpm, rop = case.removeprefix("rpm").split("_rop")
    return float(rpm) * 2 * math.pi / 60, float(rop) / 3600


# ---------------------------------------------------------------- parameters: the reading of parameters.m


def test_parameters_json_matches_the_octave_struct():
    """parameters.json (written from reading parameters.m) equals the struct p their code built."""
    sc = REF["scalars_30rpm_30mh"]
    sec = STR["sections"][0]
    pairs = {
        "Ap": sec["area_m2"], "Jp": sec["polar_moment_m4"], "L": LENGTH, "E": STR["youngs_modulus_Pa"],
        "G": STR["shear_modulus_Pa"], "rho": RHO, "c_a": STR["axial_wave_speed_m_s"],
        "c_t": STR["torsional_wave_speed_m_s"], "a": BIT["radius_a_m"],
        "epsilon": BIT["intrinsic_specific_energy_epsilon_Pa"],
        "zeta": BIT["zeta"], "sigma": BIT["contact_stress_sigma_Pa"], "l": BIT["wear_flat_length_l_m"],
        "gamma": BIT["gamma"], "mu": BIT["mu"], "N": BIT["blades_N"], "K_a": BIT["cutting_axial_K_a_N_per_m"],
        "K_t": BIT["cutting_torsional_K_t_N"], "Wf": BIT["contact_force_Wf_N"],
        "Tf": BIT["contact_torque_per_force_Tf_m"], "ka": K_NAMED, "kt": PAR["damping"]["kt_named_1_s"],
        "P": PAR["discretisation"]["cells_P"], "dt": STEP, "Mb": 0.0, "ka_L": 1.0, "kt_L": 1.0,
    }
    for name, mine in pairs.items():
        assert sc[name] == pytest.approx(mine, rel=1e-12, abs=0), name
    # the closed forms of the law's constants
    a = BIT["radius_a_m"]
    eps = BIT["intrinsic_specific_energy_epsilon_Pa"]
    assert BIT["cutting_axial_K_a_N_per_m"] == pytest.approx(a * BIT["zeta"] * eps)
    assert BIT["cutting_torsional_K_t_N"] == pytest.approx(a**2 * eps / 2)
    assert BIT["contact_force_Wf_N"] == pytest.approx(a * BIT["wear_flat_length_l_m"] * BIT["contact_stress_sigma_Pa"])
    assert BIT["contact_torque_per_force_Tf_m"] == pytest.approx(BIT["gamma"] * BIT["mu"] * a)


@pytest.mark.parametrize("case", CASES)
def test_scheme_constants_closed_form(case):
    """Sub-steps, cut-surface cells Pl = floor(1/(dt_sub 5 omega0)) (169 / 84 / 42) and its Courant ~0.127."""
    om0, v0 = setpoints(case)
    sch = REF["cases"][case]["scheme"]
    dx = LENGTH / PAR["discretisation"]["cells_P"]
    n = math.ceil(STEP / (dx / STR["axial_wave_speed_m_s"] * 0.99))
    dt_sub = STEP / n
    pl = math.floor(1 / (dt_sub * 5 * om0))
    assert sch["substeps_per_step"] == n == 8
    assert sch["dt_sub_s"] == pytest.approx(dt_sub, rel=1e-15)
    assert sch["cut_surface_cells_Pl"] == pl == {30: 169, 60: 84, 120: 42}[round(om0 * 60 / (2 * math.pi))]
    courant = dt_sub * pl * om0 * BIT["blades_N"] / (2 * math.pi)
    assert sch["cut_surface_courant_at_omega0"] == pytest.approx(courant, rel=1e-12)
    assert 0.125 < courant < 0.128
    assert sch["axial_courant"] == pytest.approx(0.9375)
    assert sch["torsional_courant"] == pytest.approx(0.58170, rel=1e-4)
    assert sch["tN_s"] == pytest.approx(2 * math.pi / (BIT["blades_N"] * om0))
    assert sch["dNom_m"] == pytest.approx(2 * math.pi * v0 / (om0 * BIT["blades_N"]))
    assert len(final_cut_surface(case)) == pl


def test_recording_changed_no_number():
    """The unmodified waveStep_transportBRI.m gives the same final state and outputs, exactly."""
    chk = REF["recording_changes_nothing"]
    assert chk["final_state_max_abs_difference"] == 0.0
    assert chk["y_max_abs_difference"] == 0.0


# ---------------------------------------------------------------- the bit law with the constants of parameters.json


@pytest.mark.parametrize("case", CASES)
def test_bit_law_with_their_constants(case):
    """W = K_a d + Wf ga + g_wt and T = K_t d + Tf Wf ga + g_tt at every step's last sub-step, and the
    regime thresholds on the last cell's speeds (ga = 1 when vb > 0.001 m/s; no torsional stick term when
    ob >= 0.1 rad/s)."""
    w = window(case)
    d, ga = w["last_d_m"], w["last_ga"]
    wf, ka = BIT["contact_force_Wf_N"], BIT["cutting_axial_K_a_N_per_m"]
    kt, tf = BIT["cutting_torsional_K_t_N"], BIT["contact_torque_per_force_Tf_m"]
    tol_w, tol_t = 1e-6 * (wf + ka * d.max()), 1e-6 * (tf * wf + kt * d.max())
    np.testing.assert_allclose(w["last_wc_N"], ka * d, rtol=0, atol=tol_w)
    np.testing.assert_allclose(w["last_tc_Nm"], kt * d, rtol=0, atol=tol_t)
    np.testing.assert_allclose(w["last_wf_N"], wf * ga, rtol=0, atol=tol_w)
    np.testing.assert_allclose(w["last_tf_Nm"], tf * wf * ga, rtol=0, atol=tol_t)
    np.testing.assert_allclose(w["last_wob_N"], ka * d + wf * ga + w["last_g_wt_N"], rtol=0, atol=tol_w)
    np.testing.assert_allclose(w["last_tob_Nm"], kt * d + tf * wf * ga + w["last_g_tt_Nm"], rtol=0, atol=tol_t)
    assert np.all(d >= 0) and np.all((ga >= 0) & (ga <= 1))
    assert np.all(ga[w["last_vb_m_s"] > 0.001] == 1.0)
    assert np.all(w["last_g_tt_Nm"][w["last_ob_rad_s"] >= 0.1] == 0.0)
    assert np.all(w["last_g_tt_Nm"] <= 0.0)


def _cut_surface_chain(w: dict[str, np.ndarray], sch: dict) -> np.ndarray:
    """Step means of d = N max(l_Pl, 0) from first-order upwind on Pl cells driven by the stored step
    means of the last cell's speeds: l <- l - C diff([0; l]) + dt vb, C = dt Pl max(ob, 0) N/(2 pi)."""
    pl, dts, nsub, nb = sch["cut_surface_cells_Pl"], sch["dt_sub_s"], sch["substeps_per_step"], BIT["blades_N"]
    vb, ob = w["bit_cell_speed_m_s"], w["bit_cell_speed_rad_s"]
    cut = np.zeros(pl)
    out = np.empty(len(vb))
    for k in range(len(vb)):
        courant = dts * pl * max(ob[k], 0.0) * nb / (2 * math.pi)
        acc = 0.0
        for _ in range(nsub):
            acc += nb * max(cut[-1], 0.0)
            cut = cut - courant * np.diff(cut, prepend=0.0) + dts * vb[k]
        out[k] = acc / nsub
    return out


def _exact_delay(w: dict[str, np.ndarray]) -> np.ndarray:
    """d = N (x(t) - x(t - tau)) with the bit's angle advancing 2 pi/N over tau (step means, NaN at the start)."""
    nb = BIT["blades_N"]
    x = np.concatenate(([0.0], np.cumsum(w["bit_cell_speed_m_s"] * STEP)))
    phi = np.concatenate(([0.0], np.cumsum(w["bit_cell_speed_rad_s"] * STEP)))
    out = np.full(len(x) - 1, np.nan)
    for k in range(1, len(x)):
        target = phi[k] - 2 * math.pi / nb
        if target < 0 or np.any(np.diff(phi[: k + 1]) < 0):
            continue
        out[k - 1] = nb * (x[k] - np.interp(target, phi[: k + 1], x[: k + 1]))
    return out


@pytest.mark.parametrize("case", CASES)
def test_cut_surface_is_first_order_upwind_on_pl_cells(case):
    """Their depth of cut is the output of a chain of Pl upwind cells (waveStep_transportBRI.m:93-94), not
    a delay: re-running that chain on the stored step-mean speeds reproduces d to 1e-4 after 1.5 s (the
    initial content has left), while the exact delay differs by orders of magnitude more."""
    w = window(case)
    d = w["depth_of_cut_m"]
    chain = _cut_surface_chain(w, REF["cases"][case]["scheme"])
    exact = _exact_delay(w)
    sl = slice(int(1.5 / STEP), None)
    err_chain = np.sqrt(np.mean((chain[sl] - d[sl]) ** 2))
    err_exact = np.sqrt(np.nanmean((exact[sl] - d[sl]) ** 2))
    assert err_chain < 1e-4 * d.mean()  # step means stand in for the sub-step speeds
    assert err_exact > 20 * err_chain


@pytest.mark.parametrize(("rpm", "pl", "f_hz", "attenuation"),
                         [(30, 169, 2.0, 0.903), (30, 169, 8.0, 0.199), (60, 84, 3.6, 0.847), (120, 42, 7.2, 0.719)])
def test_cut_surface_attenuation_closed_form(rpm, pl, f_hz, attenuation):
    """The README's numbers: the chain's transfer function (C z/(1 - (1 - C) z))^Pl, z = exp(-s dt_sub),
    has the phase of the exact delay exp(-s tN) and a gain below 1 (numerical diffusion of the delayed
    term); the standard deviation of its delay is sqrt(Pl (1 - C)) dt_sub / C."""
    om0 = rpm * 2 * math.pi / 60
    dts = STEP / 8
    courant = dts * pl * om0 * BIT["blades_N"] / (2 * math.pi)
    tn = 2 * math.pi / (BIT["blades_N"] * om0)
    s = 2j * math.pi * f_hz
    z = np.exp(-s * dts)
    phi = (courant * z / (1 - (1 - courant) * z)) ** pl
    assert abs(phi) == pytest.approx(attenuation, abs=1e-3)
    assert abs(np.angle(phi * np.exp(s * tn))) < 0.16
    sigma = math.sqrt(pl * (1 - courant)) * dts / courant
    assert sigma / tn == pytest.approx({30: 0.072, 60: 0.102, 120: 0.144}[rpm], abs=1e-3)


# ---------------------------------------------------------------- balances of the string


def _balance(case: str, rate: float, axial: bool) -> tuple[float, float]:
    """Residual and scale of the discrete momentum balance over the 20..25 s window:
    rho A (M(25) - M(20)) = sum dt (F_top - W - rate rho A M_mean) (torsion: rho J, T_top, T)."""
    w = window(case)
    if axial:
        m_end, top, bit, m_mean, inertia = (w["axial_momentum_end_m2_s"], w["top_force_N"], w["wob_N"],
                                             w["axial_momentum_m2_s"], RHO * AREA)
    else:
        m_end, top, bit, m_mean, inertia = (w["angular_momentum_end_m_rad_s"], w["top_torque_Nm"], w["tob_Nm"],
                                             w["angular_momentum_m_rad_s"], RHO * POLAR)
    # steps 2..n of the window: the first row's end state is the start
    lhs = inertia * (m_end[-1] - m_end[0])
    rhs = STEP * np.sum(top[1:] - bit[1:] - rate * inertia * m_mean[1:])
    scale = STEP * np.sum(rate * inertia * m_mean[1:])
    return float(lhs - rhs), float(scale)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("axial", [True, False], ids=["axial", "torsional"])
def test_momentum_balance_fixes_the_damping_rate(case, axial):
    """Their velocity damping acts at 2 k (waveStep_transportBRI.m:86-89), not the named k: the
    momentum balance closes with 2 k to 1e-3 of the damping term and misses by half of it with k.
    This also fixes the boundary forces: top force A E (V0 - beta_1)/c_a, WOB A E h at the bit face."""
    res, scale = _balance(case, K_APPLIED, axial)
    assert abs(res) < 1e-3 * scale
    res_named, _ = _balance(case, K_NAMED, axial)
    assert abs(res_named) > 0.4 * scale
    assert K_APPLIED == 2 * K_NAMED


@pytest.mark.parametrize("case", CASES)
def test_energy_balance(case):
    """E(25) - E(20) = int (F_top V0 + T_top omega0 - W v_bit - T omega_bit - 2k rho (A int v^2 + J int omega^2)) dt
    to within the scheme's numerical dissipation, which is small and not negative."""
    w = window(case)
    sl = slice(1, None)
    p_in = STEP * np.sum(w["top_axial_power_W"][sl] + w["top_torsional_power_W"][sl])
    p_bit = STEP * np.sum(w["bit_axial_power_W"][sl] + w["bit_torsional_power_W"][sl])
    p_visc = STEP * np.sum(K_APPLIED * RHO * (AREA * w["axial_speed_sq_int_m3_s2"][sl]
                                              + POLAR * w["angular_speed_sq_int_m_rad2_s2"][sl]))
    d_e = w["energy_end_J"][-1] - w["energy_end_J"][0]
    numerical = p_in - p_bit - p_visc - d_e
    assert -1e-5 * p_in < numerical < 1e-3 * p_in
    assert abs(p_in - p_bit - p_visc / 2 - d_e) > 0.02 * p_in  # the named rate would not close it


def test_top_power_is_force_times_imposed_speed():
    """The top boundary imposes V0 and omega0: the top power equals the top force/torque times them."""
    for case in CASES:
        om0, v0 = setpoints(case)
        w = window(case)
        np.testing.assert_allclose(w["top_axial_power_W"], w["top_force_N"] * v0, rtol=1e-6)
        np.testing.assert_allclose(w["top_torsional_power_W"], w["top_torque_Nm"] * om0, rtol=1e-6)


# ---------------------------------------------------------------- steady drilling in closed form


def _long_metrics(case: str) -> dict:
    run = REF["cases"][case]["long_120s"]
    if run.get("not_run"):
        pytest.skip(f"the 120 s run of {case} is not stored")
    return run["metrics"]


def _settled_long_cases() -> list[str]:
    runs = [REF["cases"][c]["long_120s"] for c in LONG_CASES]
    return [c for c, run in zip(LONG_CASES, runs) if not run.get("not_run") and run["metrics"]["settled"]]


@pytest.mark.parametrize("case", LONG_CASES)
def test_steady_drilling_closed_form(case):
    """Where the 120 s run has settled: bit speeds V0 and omega0, depth of cut per revolution
    d = 2 pi V0 / omega0 = ROP / rotary speed, WOB = K_a d + Wf, TOB = K_t d + gamma mu a Wf, top force
    and torque exceeding them by the damping load 2 k rho (A, J) L (V0, omega0)."""
    _long_metrics(case)
    if case not in _settled_long_cases():
        pytest.skip(f"{case} does not settle within 120 s (limit cycle or stick-slip): no closed form")
    om0, v0 = setpoints(case)
    w = window(case, long=True)
    d = 2 * math.pi * v0 / om0
    wob = BIT["cutting_axial_K_a_N_per_m"] * d + BIT["contact_force_Wf_N"]
    tob = BIT["cutting_torsional_K_t_N"] * d + BIT["contact_torque_per_force_Tf_m"] * BIT["contact_force_Wf_N"]
    np.testing.assert_allclose(w["bit_cell_speed_end_m_s"], v0, rtol=1e-2)
    np.testing.assert_allclose(w["bit_cell_speed_end_rad_s"], om0, rtol=1e-2)
    np.testing.assert_allclose(w["depth_of_cut_m"], d, rtol=1e-2)
    # with the bit's own speeds the relation is tighter: d = 2 pi v_b / omega_b
    np.testing.assert_allclose(w["depth_of_cut_m"],
                               2 * math.pi * w["bit_cell_speed_end_m_s"] / w["bit_cell_speed_end_rad_s"], rtol=2e-4)
    np.testing.assert_allclose(w["wob_N"], wob, rtol=1e-2)
    np.testing.assert_allclose(w["tob_Nm"], tob, rtol=1e-2)
    np.testing.assert_allclose(w["top_force_N"] - w["wob_N"], K_APPLIED * RHO * AREA * LENGTH * v0, rtol=2e-2)
    np.testing.assert_allclose(w["top_torque_Nm"] - w["tob_Nm"], K_APPLIED * RHO * POLAR * LENGTH * om0, rtol=2e-2)


def test_some_case_settles():
    """At least one operating point reaches steady drilling, so the closed form above is exercised."""
    assert _settled_long_cases()


@pytest.mark.parametrize("case", LONG_CASES)
def test_long_run_mean_rates(case):
    """Over the 115..120 s window the mean bit speeds equal the imposed top speeds (the string neither
    stretches nor winds up on average) and the mean depth of cut per revolution is ROP / rotary speed."""
    om0, v0 = setpoints(case)
    m = _long_metrics(case)
    assert m["bit_axial_speed_m_s"]["mean"] == pytest.approx(v0, rel=0.05)
    assert m["bit_rpm"]["mean"] == pytest.approx(om0 * 60 / (2 * math.pi), rel=0.02)
    if m["no_cut_fraction"] == 0.0 and m["torsional_stick_fraction"] == 0.0:
        assert m["depth_of_cut_per_rev_m"]["mean"] == pytest.approx(2 * math.pi * v0 / om0, rel=0.05)


def test_metrics_recomputed_from_stored_series():
    """reference.json's window metrics (float64 in Octave) agree with the stored float32 series."""
    for case in CASES:
        w = window(case)
        m = REF["cases"][case]["published_25s"]["metrics"]
        assert m["samples"] == len(w["t_end_s"])
        assert w["t_end_s"][0] > 20.0 and w["t_end_s"][-1] == pytest.approx(25.002, abs=1e-3)
        assert m["wob_N"]["mean"] == pytest.approx(w["wob_N"].mean(), rel=1e-6)
        bit_rpm_min = w["bit_cell_speed_end_rad_s"].min() * 60 / (2 * math.pi)
        assert m["bit_rpm"]["min"] == pytest.approx(bit_rpm_min, rel=1e-5, abs=1e-4)
        assert m["stick_slip"] == bool(np.any(w["last_g_tt_Nm"] != 0))
        f = full(case)
        assert len(f["t_end_s"]) == 833


# ---------------------------------------------------------------- linear stability recomputed with numpy


def _crossings(g: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """|G| and frequency where G crosses the negative real axis (imag changes sign, linear interpolation)."""
    im = g.imag
    i = np.nonzero((im[:-1] * im[1:] <= 0) & (im[:-1] != im[1:]))[0]
    frac = im[i] / (im[i] - im[i + 1])
    gc = g[i] + frac * (g[i + 1] - g[i])
    wc = w[i] + frac * (w[i + 1] - w[i])
    keep = gc.real < 0
    return np.abs(gc[keep]), wc[keep]


def _dimensional_gains(rpm: float, rop: float, rate: float, nw: int) -> tuple[float, float]:
    """Largest |Gt| and |Ga + Gt| at -180 deg, Gt = gt Kt/s (1 - e^{-s tN}) as in Coupled/freqPlots.m."""
    om0, v0 = rpm * 2 * math.pi / 60, rop / 3600
    nb, a, eps, zeta = BIT["blades_N"], BIT["radius_a_m"], BIT["intrinsic_specific_energy_epsilon_Pa"], BIT["zeta"]
    kt_gain = (v0 / om0) * a**2 * eps * nb / (2 * STR["torsional_impedance_N_m_s"])
    ka_gain = a * zeta * eps * nb / STR["axial_impedance_N_s_m"]
    tn = 2 * math.pi / (nb * om0)
    w = np.linspace(3e-3, 10 * 2 * math.pi, nw)
    s = 1j * w
    root = np.sqrt(1 + rate / s)
    gt = -np.tanh(LENGTH * s / STR["torsional_wave_speed_m_s"] * root) / root
    ga = -np.tanh(LENGTH * s / STR["axial_wave_speed_m_s"] * root) / root
    delay = 1 - np.exp(-s * tn)
    big_gt = gt * kt_gain / s * delay
    big_ga = -ga * ka_gain / s * delay
    mt, _ = _crossings(big_gt, w)
    mg, _ = _crossings(big_ga + big_gt, w)
    return float(mt.max(initial=0.0)), float(mg.max(initial=0.0))


@pytest.mark.parametrize("rop", [30, 60])
def test_dimensional_torsional_stability_recomputed(rop):
    """The stored loop gains at 30/60/120 rpm equal freqPlots.m's transfer functions evaluated with numpy
    on a 5x finer grid (the -180 deg crossings move by less than 0.5 %), and the stored boundary rpm is where
    M_T crosses 1 (M_T falls with rpm)."""
    st = REF["stability"]["dimensional"][f"rop{rop}"]
    for rpm in (30, 60, 120):
        for rate, suffix in ((K_NAMED, "named"), (K_APPLIED, "2k")):
            mt, mg = _dimensional_gains(rpm, rop, rate, 100_000)
            assert st["at_cases"][str(rpm)][f"MT_{suffix}"] == pytest.approx(mt, rel=5e-3)
            assert st["at_cases"][str(rpm)][f"MG_{suffix}"] == pytest.approx(mg, rel=5e-3)
    for suffix, rate in (("named", K_NAMED), ("2k", K_APPLIED)):
        lo, hi = st[f"MT_{suffix}"]["switches_between_rpm"][0]
        assert _dimensional_gains(lo, rop, rate, 100_000)[0] > 1.0 > _dimensional_gains(hi, rop, rate, 100_000)[0]


def test_nondimensional_map_recomputed():
    """MAIN_Torsional_FreqStabMap.m's map at a sample of grid points equals numpy's evaluation of
    Gt = -gt/s V0/Om (1 - e^{-s/Om}), gt = (1 + Z tanh s)/(Z + tanh s), Z = (1 + 0.7)/(1 - 0.7), on
    their grid; OmLine is the last Om of the low-Om unstable band of each row."""
    s_ = stability()
    v0s, oms, zmap, line = s_["nondim.V0"], s_["nondim.Om"], s_["nondim.Z"], s_["nondim.OmLine"]
    assert zmap.shape == (120, 120) and len(line) == 120
    w = np.linspace(3e-3, 10 * 2 * math.pi, 3000)
    s = 1j * w
    z = (1 + 0.7) / (1 - 0.7)
    gt = (1 + z * np.tanh(s)) / (z + np.tanh(s))
    rng = np.random.default_rng(3)
    for i, j in zip(rng.integers(0, 120, 25), rng.integers(0, 120, 25)):
        g = -gt / s * v0s[i] / oms[j] * (1 - np.exp(-s / oms[j]))
        m, _ = _crossings(g, w)
        assert zmap[i, j] == pytest.approx(m.max(initial=0.0), rel=1e-9, abs=1e-12)
    for i in range(120):
        first_stable = int(np.argmax(zmap[i] <= 1.0)) + 1         # MATLAB index of find(Zss(i,:)<0.5,1)
        ind = min(max(first_stable - 1, 0), 119)
        assert line[i] == oms[ind - 1]
