"""Reference numbers from welleng 0.30.0 for the 3-D S-well survey and torque-and-drag case.

Command (from the repository root, in a virtual environment holding welleng 0.30.0:
`python -m venv /tmp/wl && /tmp/wl/bin/pip install welleng==0.30.0`):

    /tmp/wl/bin/python tests/reference/welleng/welleng_reference.py [--survey PATH] [--out DIR]

Defaults: survey examples/s-well-3d-survey.csv (columns md_m, inc_deg, azi_deg; read only),
output directory = the folder of this script. Writes

    welleng_s_well_3d_survey.json       minimum curvature by welleng.survey.Survey
    welleng_s_well_3d_torque_drag.json  torque and drag: welleng as is, welleng corrected, direct

and prints the small verification cases to stdout.

Library: welleng 0.30.0 (PyPI), modules welleng.survey (Survey, interpolate_mds) and
welleng.torque_drag (TorqueDrag, HookLoad, force_normal, force_tension_delta, torsion_delta),
welleng.architecture (BHA, WellBore).

The case (examples/s-well-3d.toml): from the top, drill pipe 3720 m (OD 0.127 m, ID 0.1086 m,
contact diameter 0.1683 m), drill collars 280 m (OD 0.1651 m, ID 0.0714 m, contact = OD), steel
7850 kg/m^3, mud 1200 kg/m^3, g = 9.81 m/s^2, friction factor 0.2 for md 0-1800 m and 0.3 below,
WOB 100 kN, TOB 4000 N m, block weight 300 kN, bit at md 4000 m.

Conventions compared with (the "direct" implementation in this file)
-------------------------------------------------------------------
* buoyed weight per metre w = (rho_steel - rho_mud) g A, A = pi/4 (OD^2 - ID^2);
  effective tension; soft string.
* nodes: every 1 m from 0 to 4000 m plus the survey stations (section boundary 3720 m and
  friction boundary 1800 m are on the 1 m grid). Node directions by minimum curvature (slerp of
  the unit tangents of the bracketing survey stations), written here independently of welleng.
* element a (top) - b (bottom), length L, unit tangents t_a, t_b, mean direction
  m = (t_a + t_b)/|t_a + t_b|, cos(i_mean) = m_z, z_perp = d - (d.m) m with d = (0, 0, 1) down;
  stepped from the bit up with the tension at the element's bottom:
      N   = |T_b (t_b - t_a) + w L z_perp|
      T_a = T_b + w L cos(i_mean) + s mu N      (s = +1 pick-up, -1 slack-off, 0 rotating)
      M_a = M_b + mu r N                        (rotating only; r = contact radius)
  w, mu, r of the element are those at its mid md. Off bottom T = M = 0 at the bit; rotating on
  bottom T = -WOB, M = TOB. Hook load = T(surface) + block weight.

How welleng 0.30.0 is made to use the same inputs
------------------------------------------------
* BHA sections carry unit_weight = rho_steel g A (N/m in air) and density = 7.85 (SG); the fluid
  density is 1.2 (SG). welleng multiplies by its buoyancy factor (rho_s - rho_f)/rho_s, which gives
  exactly w = (rho_s - rho_m) g A (mud inside and outside).
* contact radius: welleng uses tooljoint_od/2 when a section has 'tooljoint_od', else od/2; the
  pipe is given tooljoint_od = 0.1683.
* friction: WellBore sections 0-1800 m (0.2) and 1800-4000 m (0.3); welleng assigns each
  interval the coefficient of the section containing the interval's lower station.
* nodes: welleng steps over survey stations only, so the survey is first densified with welleng's
  own minimum-curvature interpolation, Survey.interpolate_mds(np.arange(0, 4001, 1.0)), giving
  the same node set as the direct implementation. (Numbers at the survey's own 135 stations are
  given as well, under "*_survey_stations".)
* welleng's tensions exclude the block weight: 300 kN is added to every hook load reported here.
* welleng does not return its normal forces; for "welleng_as_is" they are recovered exactly from
  its pick-up profile, N = (T_top - T_bottom - W cos(inc_avg)) / mu (the inverse of its
  force_tension_delta), and for the on-bottom / rotating cases from its torque, N = dM / (mu r).

Differences found between welleng 0.30.0 and the conventions above
------------------------------------------------------------------
Defects (confirmed on small cases printed by this script, corrected in TorqueDragCorrected):
 D1. Sign of the curvature term in the inclination plane. welleng's force_normal uses
     (T * inc_delta + W sin(inc_avg)) with inc_delta = inc(lower) - inc(upper). In a build
     (inc_delta > 0) tension is then ADDED to the weight term, in a drop it is subtracted: the
     reverse of the physics (a tensioned string is pulled to the high side in a build, to the low
     side in a drop; force balance gives |W sin i - T dinc| in a build and W sin i + T |dinc| in
     a drop). Fix: pass -inc_delta.
 D2. Radius array walked from the top while the loop steps from the bit: in
     get_forces_and_torsion the zip reverses every per-interval array ([::-1]) except
     self.radius. Element j (interval ending at station j, index = number of intervals + 1)
     gets radius[index-1-j]: the collars get the pipe's contact radius and the topmost
     intervals (as many as the collar intervals, less one) get the collars'. Fix: radius[::-1].
Convention / modelling differences (not defects, left as welleng has them):
 C1. Johancsik's decomposition N = sqrt((T dazi sin(inc_avg))^2 + (T dinc + W sin(inc_avg))^2)
     with arithmetic-mean inclination, instead of the vector form |T_b (t_b - t_a) + w L z_perp|;
     identical to first order in the element's dogleg.
 C2. Axial weight term W cos(inc_avg) (arithmetic mean of inclinations) instead of the
     inclination of the mean direction; second order per element.
 C3. welleng's Survey sets the azimuth of every vertical station (inc below
     vertical_inc_limit) to 0. The kick-off element (vertical node -> first inclined node) then
     carries a spurious azimuth change of 60 deg in the Johancsik term T dazi sin(inc_avg).
     This is the main source of the residual between corrected welleng and the direct method.
 C4. Block weight is not part of welleng's tension (added here).
 C5. HookLoad sets ONE friction factor for every wellbore section (ff_range), so it cannot
     represent the 0.2 / 0.3 intervals; it is run here with uniform 0.2 and 0.3 as a
     cross-check that its bit-at-TD values equal TorqueDrag's with uniform friction.
 C6. Inputs in SG (densities) and N/m (unit_weight); welleng applies buoyancy through a factor.
 C7. In the on-bottom call welleng also recomputes 'pickup' from T = 0 and returns 'sliding'
     (slack-off with T = -WOB at the bit) and 'drilling' (rotating, T = -WOB, M = TOB).
Survey (welleng.survey.Survey): minimum curvature with RF = tan(beta/2)/(beta/2), identical to the
hand-written formula here to round-off (largest difference 5e-13 m in position, 2e-11 deg/30 m in
DLS); welleng's DLS of a station is the dogleg of the interval ending at it per 30 m (0 at the
first station). Its 1 m interpolation (interpolate_mds) gives node tangents equal to the slerp
written here to 1e-15.

Results (1 m nodes; hook loads include the block; N, N m)
-------------------------------------------------------
                          welleng as is   welleng corrected   direct
  pick-up hook load          1 712 882        1 725 248       1 725 220
  slack-off hook load        1 102 975        1 099 361       1 099 376
  rotating off bottom        1 357 039        1 357 039       1 357 039
  rotating on bottom         1 257 039        1 257 039       1 257 039
  torque off bottom             25 142           25 723          25 721
  torque on bottom              26 130           26 705          26 704
  max N (pick-up), N/m      1 864.7 @616.7    1 872.1 @616.7  1 872.1 @616.7
D1 alone moves pick-up by +12.4 kN, slack-off by -3.6 kN, torque by about +600 N m; D2 alone moves
the torque by -26 N m (collar radius 0.08255 m vs pipe joints 0.08415 m). Corrected welleng minus
direct: +28 N pick-up, -15 N slack-off, +1.7 N m torque; all of it comes from the 0.91 m kick-off
element 591.09-592 m (C3): with no azimuth change below vertical nodes the differences fall to
0.02 N and 0.002 N m. Both methods use the tension at the element's bottom for its normal force.
"""

import argparse
import json
import math
from pathlib import Path

import numpy as np
import welleng
from welleng.architecture import BHA, WellBore
from welleng.survey import Survey, SurveyHeader
from welleng.torque_drag import (
    HookLoad,
    TorqueDrag,
    force_normal,
    force_tension_delta,
    torsion_delta,
)

WELLENG_VERSION = getattr(welleng, "__version__", None) or "0.30.0"

# ----------------------------------------------------------------------------- the case
G = 9.81
RHO_STEEL = 7850.0
RHO_MUD = 1200.0
BIT_MD = 4000.0
WOB = 100e3
TOB = 4000.0
BLOCK = 300e3
SHOE_MD = 1800.0
MU_CASED, MU_OPEN = 0.2, 0.3
SECTIONS = [  # top to bottom
    dict(name="drill pipe", length=3720.0, od=0.127, id=0.1086, contact=0.1683),
    dict(name="drill collars", length=280.0, od=0.1651, id=0.0714, contact=0.1651),
]


def area(od, id_):
    return math.pi / 4.0 * (od ** 2 - id_ ** 2)


def buoyed_w(sec):
    """Buoyed weight per metre, N/m: (rho_steel - rho_mud) g A."""
    return (RHO_STEEL - RHO_MUD) * G * area(sec["od"], sec["id"])


# ----------------------------------------------------------------------------- survey
def read_survey(path):
    d = np.loadtxt(path, delimiter=",", skiprows=1)
    assert d.shape[1] == 3
    return d[:, 0], d[:, 1], d[:, 2]


def make_survey(md, inc_deg, azi_deg):
    header = SurveyHeader(azi_reference="grid", convergence=0.0)
    return Survey(md=md, inc=inc_deg, azi=azi_deg, header=header, deg=True)


def tangent(inc_rad, azi_rad):
    """Unit tangent (north, east, down)."""
    return np.stack([np.sin(inc_rad) * np.cos(azi_rad),
                     np.sin(inc_rad) * np.sin(azi_rad),
                     np.cos(inc_rad)], axis=-1)


def hand_min_curve(md, inc_deg, azi_deg):
    """Minimum curvature written out: RF = tan(beta/2)/(beta/2)."""
    i, a = np.radians(inc_deg), np.radians(azi_deg)
    i1, i2, a1, a2 = i[:-1], i[1:], a[:-1], a[1:]
    L = np.diff(md)
    cosb = np.cos(i2 - i1) - np.sin(i1) * np.sin(i2) * (1.0 - np.cos(a2 - a1))
    beta = np.arccos(np.clip(cosb, -1.0, 1.0))
    half = beta / 2.0
    rf = np.where(beta > 1e-12, np.tan(half) / np.where(half > 0, half, 1.0), 1.0)
    dn = L / 2 * (np.sin(i1) * np.cos(a1) + np.sin(i2) * np.cos(a2)) * rf
    de = L / 2 * (np.sin(i1) * np.sin(a1) + np.sin(i2) * np.sin(a2)) * rf
    dv = L / 2 * (np.cos(i1) + np.cos(i2)) * rf
    n = np.concatenate([[0.0], np.cumsum(dn)])
    e = np.concatenate([[0.0], np.cumsum(de)])
    v = np.concatenate([[0.0], np.cumsum(dv)])
    dls = np.concatenate([[0.0], np.degrees(beta) / L * 30.0])
    return n, e, v, dls


def slerp_tangents(md_st, inc_deg, azi_deg, md_nodes):
    """Node tangents by minimum curvature between survey stations (independent of welleng)."""
    t = tangent(np.radians(inc_deg), np.radians(azi_deg))
    k = np.clip(np.searchsorted(md_st, md_nodes, side="right") - 1, 0, len(md_st) - 2)
    t1, t2 = t[k], t[k + 1]
    f = ((md_nodes - md_st[k]) / (md_st[k + 1] - md_st[k]))[:, None]
    beta = np.arccos(np.clip(np.sum(t1 * t2, axis=1), -1.0, 1.0))[:, None]
    sb = np.sin(beta)
    small = beta < 1e-9
    wa = np.where(small, 1.0 - f, np.sin((1.0 - f) * beta) / np.where(small, 1.0, sb))
    wb = np.where(small, f, np.sin(f * beta) / np.where(small, 1.0, sb))
    out = wa * t1 + wb * t2
    return out / np.linalg.norm(out, axis=1)[:, None]


# ----------------------------------------------------------------------------- welleng objects
def make_bha(sections, bottom):
    """welleng BHA, built bottom up (HookLoad's BHA.depth needs the 'length' keys)."""
    bha = BHA("string", top=0.0, bottom=bottom)
    for sec in reversed(sections):
        kw = dict(name=sec["name"], length=sec["length"], od=sec["od"], id=sec["id"],
                  unit_weight=RHO_STEEL * G * area(sec["od"], sec["id"]),  # N/m in air
                  density=RHO_STEEL / 1000.0)                             # SG
        if sec["contact"] != sec["od"]:
            kw["tooljoint_od"] = sec["contact"]
        bha.add_section(**kw)
    assert bha.complete
    return bha


def make_wellbore(friction, bottom):
    """friction: list of (bottom_md, mu) from the top."""
    wb = WellBore("hole", top=0.0, bottom=bottom, method="top_down")
    for b, mu in friction:
        wb.add_section(name=f"to {b:g} m", id=0.2159, bottom=b, coeff_friction_sliding=mu)
    assert wb.complete
    return wb


# ----------------------------------------------------------------------------- corrected copy
def corrected_get_forces_and_torsion(self, wob=False, tob=False, overpull=False):
    """welleng 0.30.0 TorqueDrag.get_forces_and_torsion with defects D1 and D2 corrected.

    Line-for-line copy of the library method; the only changes are marked CHANGE D1 / D2
    (each switchable through the class attributes fix_d1 / fix_d2, to show the effect of
    each alone). It also keeps the normal forces (self.normal_force), which the library
    discards; that does not change any result.
    """
    if any((wob, tob)):
        assert tob, "Can't have WOB without TOB"
        assert wob, "Can't have TOB wihtouh WOB"
        ft = [np.array([0.0, -wob, -wob])]
        tn = [tob]
    else:
        ft = [np.zeros(3)]
        tn = [0]
    if overpull:
        ft[0][0] = overpull
    fn = []
    for row in zip(
        self.inc_average[:self.index][::-1],
        self.inc_delta[:self.index][::-1],
        self.azi_delta[:self.index][::-1],
        self.weight_buoyed[::-1],
        self.coeff_friction_sliding[:self.index][::-1],
        # CHANGE D2: was `self.radius` -- the only array not reversed, so it was walked from
        # the top while every other array is walked from the bit.
        self.radius[:self.index][::-1] if self.fix_d2 else self.radius,
    ):
        (
            inc_average, inc_delta, azi_delta, weight_buoyed,
            coeff_friction_sliding, radius
        ) = row

        # CHANGE D1: was `inc_delta` (= inc(lower) - inc(upper)); the curvature term of the
        # inclination plane must be T * (inc(upper) - inc(lower)) against + W sin(inc_avg).
        fn.append(force_normal(
            ft[-1], inc_average, -inc_delta if self.fix_d1 else inc_delta,
            azi_delta, weight_buoyed
        ))
        ft.append(ft[-1] + np.array(force_tension_delta(
            weight_buoyed, inc_average, coeff_friction_sliding, fn[-1]
        )))
        tn.append(tn[-1] + np.array(torsion_delta(
            coeff_friction_sliding, fn[-1][2], radius
        )))

    fn = np.array(fn)[::-1]
    ft = np.array(ft)[::-1][1:]
    tn = np.array(tn)[::-1][1:]
    if not hasattr(self, "normal_force"):
        self.normal_force = {}
    if wob:
        self.tension["drilling"] = ft[:, 2]
        self.tension["sliding"] = ft[:, 1]
        self.normal_force["drilling"] = fn[:, 2]
        self.normal_force["sliding"] = fn[:, 1]
    else:
        self.tension['slackoff'] = ft[:, 1]
        self.tension['rotating'] = ft[:, 2]
        self.normal_force["slackoff"] = fn[:, 1]
        self.normal_force["rotating"] = fn[:, 2]

    if tob:
        self.torque['drilling'] = tn
    else:
        self.torque['rotating'] = tn

    if overpull:
        self.tension['overpull'] = ft[:, 0]
    else:
        self.tension['pickup'] = ft[:, 0]
        self.normal_force["pickup"] = fn[:, 0]

    self.wob, self.tob, self.overpull = wob, tob, overpull


class PatchedTorqueDrag(TorqueDrag):
    fix_d1 = True
    fix_d2 = True
    get_forces_and_torsion = corrected_get_forces_and_torsion


class TorqueDragCorrected(PatchedTorqueDrag):
    """welleng's TorqueDrag with D1 and D2 corrected (the "welleng_corrected" numbers)."""


class TorqueDragD1Only(PatchedTorqueDrag):
    fix_d2 = False


class TorqueDragD2Only(PatchedTorqueDrag):
    fix_d1 = False


# ----------------------------------------------------------------------------- welleng results
def welleng_normal_forces(td):
    """Per-element normal forces of a welleng TorqueDrag (element j = interval ending at station j).

    Recovered from its own outputs: pick-up and slack-off from the tension steps, rotating and
    drilling from the torque steps (welleng's radius as it actually used it)."""
    n = td.index
    W = td.weight_buoyed[1:n]
    ia = td.inc_average[1:n]
    mu = td.coeff_friction_sliding[1:n]
    out = {}
    T = td.tension["pickup"]
    out["pickup"] = (T[:-1] - T[1:] - W * np.cos(ia)) / mu
    if "slackoff" in td.tension:
        T = td.tension["slackoff"]
        out["slackoff"] = -(T[:-1] - T[1:] - W * np.cos(ia)) / mu
    # radius as welleng pairs it with element j (the loop's k-th row, k = n-1-j)
    r_used = np.asarray(td.radius)[n - 1 - np.arange(1, n)]  # as welleng 0.30.0 pairs them
    for key in ("rotating", "drilling"):
        if key in td.torque:
            M = td.torque[key]
            out[key] = (M[:-1] - M[1:]) / (mu * r_used)
    return out


def summarize_welleng(td, td_on):
    md = td.survey.md[: td.index]
    L = np.diff(md)
    mid = 0.5 * (md[1:] + md[:-1])
    nf = td.normal_force if isinstance(td, PatchedTorqueDrag) else welleng_normal_forces(td)
    nf = {k: (v[1:] if len(v) == len(md) else v) for k, v in nf.items()}
    if isinstance(td_on, PatchedTorqueDrag):
        nf_on = {k: v[1:] for k, v in td_on.normal_force.items()}
    else:
        nf_on = welleng_normal_forces(td_on)
    res = {
        "hook_load_pickup_N": float(td.tension["pickup"][0] + BLOCK),
        "hook_load_slackoff_N": float(td.tension["slackoff"][0] + BLOCK),
        "hook_load_rotating_N": float(td.tension["rotating"][0] + BLOCK),
        "hook_load_rotating_on_bottom_N": float(td_on.tension["drilling"][0] + BLOCK),
        "surface_torque_off_bottom_Nm": float(td.torque["rotating"][0]),
        "surface_torque_on_bottom_Nm": float(td_on.torque["drilling"][0]),
    }
    per_m = nf["pickup"] / L
    j = int(np.argmax(per_m))
    res["max_normal_force_N_per_m"] = float(per_m[j])
    res["max_normal_force_md"] = float(mid[j])
    res["max_normal_force_case"] = "pickup"
    res["max_normal_force_by_case"] = {}
    for key, arr in list(nf.items()) + [("rotating_on_bottom", nf_on["drilling"])]:
        p = arr / L
        jj = int(np.argmax(p))
        res["max_normal_force_by_case"][key] = {"N_per_m": float(p[jj]), "md": float(mid[jj])}
    profiles = dict(md=md, pickup=td.tension["pickup"], slackoff=td.tension["slackoff"],
                    rotating=td.tension["rotating"], torque_rotating=td.torque["rotating"],
                    rotating_on_bottom=td_on.tension["drilling"],
                    torque_on_bottom=td_on.torque["drilling"])
    return res, profiles, {"md_mid": mid, "L": L, **nf, "rotating_on_bottom": nf_on["drilling"]}


def run_welleng(survey, bha, wellbore, cls):
    td = cls(survey, wellbore, bha, fluid_density=RHO_MUD / 1000.0)
    td_on = cls(survey, wellbore, bha, fluid_density=RHO_MUD / 1000.0, wob=WOB, tob=TOB)
    return td, td_on


# ----------------------------------------------------------------------------- direct method
def direct_td(md, t, w_of, mu_of, r_of, bit_T=0.0, bit_M=0.0, cases=("pickup", "slackoff",
                                                                       "rotating")):
    """Straightforward soft-string stepping from the bit up (see module docstring).

    md (n,), t (n, 3) unit tangents (north, east, down). Returns tension/torque per node and
    normal force per element for each case."""
    ta, tb = t[:-1], t[1:]
    L = np.diff(md)
    mid = 0.5 * (md[1:] + md[:-1])
    m = ta + tb
    m /= np.linalg.norm(m, axis=1)[:, None]
    cos_i = m[:, 2]
    d = np.array([0.0, 0.0, 1.0])
    zperp = d[None, :] - cos_i[:, None] * m
    w = w_of(mid)
    mu = mu_of(mid)
    r = r_of(mid)
    dt = tb - ta
    wz = (w * L)[:, None] * zperp
    axial = w * L * cos_i
    sign = {"pickup": 1.0, "slackoff": -1.0, "rotating": 0.0}
    out = {}
    ne = len(L)
    for case in cases:
        s = sign[case]
        T = np.empty(ne + 1)
        M = np.empty(ne + 1)
        N = np.empty(ne)
        T[-1], M[-1] = bit_T, (bit_M if s == 0.0 else 0.0)
        for j in range(ne - 1, -1, -1):
            Tb = T[j + 1]
            v = Tb * dt[j] + wz[j]
            Nj = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            N[j] = Nj
            T[j] = Tb + axial[j] + s * mu[j] * Nj
            M[j] = M[j + 1] + (mu[j] * r[j] * Nj if s == 0.0 else 0.0)
        out[case] = dict(T=T, M=M, N=N)
    return out, mid, L


def case_functions(sections, friction):
    bottoms = np.cumsum([s["length"] for s in sections])
    ws = np.array([buoyed_w(s) for s in sections])
    rs = np.array([s["contact"] / 2.0 for s in sections])
    fb = np.array([b for b, _ in friction])
    fm = np.array([mu for _, mu in friction])

    def idx(mid):
        return np.clip(np.searchsorted(bottoms, mid), 0, len(sections) - 1)

    def fidx(mid):
        return np.clip(np.searchsorted(fb, mid), 0, len(fb) - 1)

    return (lambda x: ws[idx(x)]), (lambda x: fm[fidx(x)]), (lambda x: rs[idx(x)])


def summarize_direct(md, res_off, res_on, mid, L):
    out = {
        "hook_load_pickup_N": float(res_off["pickup"]["T"][0] + BLOCK),
        "hook_load_slackoff_N": float(res_off["slackoff"]["T"][0] + BLOCK),
        "hook_load_rotating_N": float(res_off["rotating"]["T"][0] + BLOCK),
        "hook_load_rotating_on_bottom_N": float(res_on["rotating"]["T"][0] + BLOCK),
        "surface_torque_off_bottom_Nm": float(res_off["rotating"]["M"][0]),
        "surface_torque_on_bottom_Nm": float(res_on["rotating"]["M"][0]),
    }
    p = res_off["pickup"]["N"] / L
    j = int(np.argmax(p))
    out["max_normal_force_N_per_m"] = float(p[j])
    out["max_normal_force_md"] = float(mid[j])
    out["max_normal_force_case"] = "pickup"
    out["max_normal_force_by_case"] = {}
    for key, arr in [("pickup", res_off["pickup"]["N"]), ("slackoff", res_off["slackoff"]["N"]),
                     ("rotating", res_off["rotating"]["N"]),
                     ("rotating_on_bottom", res_on["rotating"]["N"])]:
        q = arr / L
        jj = int(np.argmax(q))
        out["max_normal_force_by_case"][key] = {"N_per_m": float(q[jj]), "md": float(mid[jj])}
    return out


def run_direct(md_nodes, md_st, inc_deg, azi_deg, sections, friction, wob=WOB, tob=TOB):
    t = slerp_tangents(md_st, inc_deg, azi_deg, md_nodes)
    w_of, mu_of, r_of = case_functions(sections, friction)
    off, mid, L = direct_td(md_nodes, t, w_of, mu_of, r_of)
    on, _, _ = direct_td(md_nodes, t, w_of, mu_of, r_of, bit_T=-wob, bit_M=tob,
                         cases=("rotating",))
    return off, on, mid, L, t


# ----------------------------------------------------------------------------- small cases
def small_case(title, md, inc, azi, sections, friction, show_at=None):
    """Runs welleng as is, corrected and direct on one small case; returns a dict."""
    bottom = md[-1]
    s = make_survey(md, inc, azi)
    bha = make_bha(sections, bottom)
    wb = make_wellbore(friction, bottom)
    td = TorqueDrag(s, wb, bha, fluid_density=RHO_MUD / 1000.0)
    tc = TorqueDragCorrected(s, wb, bha, fluid_density=RHO_MUD / 1000.0)
    off, _, mid, L, _ = run_direct(np.asarray(td.survey.md[: td.index]), md, inc, azi,
                                   sections, friction, wob=1.0, tob=1.0)
    nf_as = welleng_normal_forces(td)
    r = {
        "case": title,
        "pickup_surface_N": {"welleng_as_is": float(td.tension["pickup"][0]),
                             "welleng_corrected": float(tc.tension["pickup"][0]),
                             "direct": float(off["pickup"]["T"][0])},
        "slackoff_surface_N": {"welleng_as_is": float(td.tension["slackoff"][0]),
                               "welleng_corrected": float(tc.tension["slackoff"][0]),
                               "direct": float(off["slackoff"]["T"][0])},
        "torque_off_bottom_Nm": {"welleng_as_is": float(td.torque["rotating"][0]),
                                 "welleng_corrected": float(tc.torque["rotating"][0]),
                                 "direct": float(off["rotating"]["M"][0])},
    }
    if show_at is not None:
        j = int(np.argmin(np.abs(mid - show_at)))
        Tb = off["pickup"]["T"][j + 1]
        w = buoyed_w(sections[0])
        i_m = math.radians(np.interp(mid[j], md, inc))
        dinc = math.radians(inc[j + 1] - inc[j])      # inc(lower) - inc(upper)
        W_sin = w * L[j] * math.sin(i_m)
        r["element"] = {"md_top": float(md[j]), "md_bottom": float(md[j + 1]),
                        "inc_lower_minus_upper_rad": dinc, "W_sin_inc_avg_N": W_sin}
        r["pickup_normal_force_of_element"] = {}
        for key, T_b, N in (("welleng_as_is", td.tension["pickup"][j + 1], nf_as["pickup"][j]),
                            ("welleng_corrected", tc.tension["pickup"][j + 1],
                             tc.normal_force["pickup"][j + 1]),
                            ("direct", Tb, off["pickup"]["N"][j])):
            r["pickup_normal_force_of_element"][key] = {
                "T_bottom_N": float(T_b), "N": float(N),
                "T_b*dinc + W_sin (welleng's form)": float(T_b * dinc + W_sin),
                "|W_sin - T_b*dinc| (force balance)": float(abs(W_sin - T_b * dinc))}
    return r, td, tc, off


def run_small_cases():
    dp = dict(name="pipe", length=1000.0, od=0.127, id=0.1086, contact=0.1683)
    md = np.arange(0.0, 1000.0 + 1e-9, 10.0)
    fr = [(1000.0, 0.3)]
    zero_azi = np.zeros_like(md)
    out = []
    # A: pure build, 10 -> 60 deg over 1000 m (1.5 deg/30 m), azimuth 0
    inc_b = 10.0 + 0.05 * md
    rA, tdA, tcA, offA = small_case("pure build 10->60 deg, 1.5 deg/30 m, 1000 m pipe, mu 0.3",
                                    md, inc_b, zero_azi, [dp], fr, show_at=105.0)
    out.append(rA)
    # B: pure drop, 60 -> 10 deg
    inc_d = 60.0 - 0.05 * md
    rB, tdB, tcB, offB = small_case("pure drop 60->10 deg, 1.5 deg/30 m, 1000 m pipe, mu 0.3",
                                    md, inc_d, zero_azi, [dp], fr, show_at=105.0)
    out.append(rB)
    # C: two sections, straight slant at 60 deg, very different contact radii
    pipe = dict(name="pipe", length=800.0, od=0.127, id=0.1086, contact=0.10)   # r = 0.05
    dc = dict(name="collars", length=200.0, od=0.1651, id=0.0714, contact=0.30)  # r = 0.15
    inc_c = np.full_like(md, 60.0)
    rC, tdC, tcC, offC = small_case("two sections (800 m r=0.05 over 200 m r=0.15), 60 deg slant",
                                    md, inc_c, zero_azi, [pipe, dc], fr)
    mu, s60 = 0.3, math.sin(math.radians(60.0))
    w1, w2 = buoyed_w(pipe), buoyed_w(dc)
    exact = mu * s60 * (0.05 * w1 * 800.0 + 0.15 * w2 * 200.0)
    # the mirror mapping: element j gets radius[index-1-j] (index = 101): collars (elements
    # 81..100) get radius[19..0] = pipe's; elements 1..19 get radius[99..81] = collars'.
    mirrored = mu * s60 * 10.0 * (w2 * 20 * 0.05 + w1 * (19 * 0.15 + 61 * 0.05))
    rC["torque_off_bottom_Nm"]["exact_closed_form"] = exact
    rC["torque_off_bottom_Nm"]["closed_form_with_mirrored_radius"] = mirrored
    out.append(rC)
    return out


# ----------------------------------------------------------------------------- main
def profile_at(md, arr, grid):
    idx = np.searchsorted(md, grid)
    assert np.allclose(md[idx], grid)
    return [float(x) for x in np.asarray(arr)[idx]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--survey", default=str(Path(__file__).resolve().parents[3] / "examples" / "s-well-3d-survey.csv"))
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent))
    args = ap.parse_args()
    outdir = Path(args.out)
    outdir.mkdir(parents=True, exist_ok=True)

    md_st, inc_st, azi_st = read_survey(args.survey)
    assert len(md_st) == 135 and md_st[-1] == BIT_MD

    # 1. survey -----------------------------------------------------------------------
    s = make_survey(md_st, inc_st, azi_st)
    hn, he, hv, hdls = hand_min_curve(md_st, inc_st, azi_st)
    diffs = {"north_m": float(np.max(np.abs(s.n - hn))), "east_m": float(np.max(np.abs(s.e - he))),
             "tvd_m": float(np.max(np.abs(s.tvd - hv))),
             "dls_deg_per_30m": float(np.max(np.abs(s.dls - hdls)))}
    survey_json = {
        "welleng_version": WELLENG_VERSION,
        "md": md_st.tolist(), "north": s.n.tolist(), "east": s.e.tolist(),
        "tvd": s.tvd.tolist(), "dls_deg_per_30m": s.dls.tolist(),
        "max_abs_difference_vs_hand_minimum_curvature": diffs,
    }
    (outdir / "welleng_s_well_3d_survey.json").write_text(json.dumps(survey_json, indent=1))
    print("survey: max |welleng - hand formula|:", diffs)
    print(f"  end of well: N {s.n[-1]:.3f} E {s.e[-1]:.3f} TVD {s.tvd[-1]:.3f}, "
          f"max DLS {s.dls.max():.4f} deg/30m at md {md_st[np.argmax(s.dls)]}")

    # 2. small cases ------------------------------------------------------------------
    small = run_small_cases()
    for c in small:
        print(json.dumps(c, indent=1))

    # 3. the case ---------------------------------------------------------------------
    friction = [(SHOE_MD, MU_CASED), (BIT_MD, MU_OPEN)]
    bha = make_bha(SECTIONS, BIT_MD)
    wb = make_wellbore(friction, BIT_MD)
    s1 = s.interpolate_mds(np.arange(0.0, BIT_MD + 0.5, 1.0))   # welleng's own interpolation

    results, profiles, normals = {}, {}, {}
    for label, survey in (("", s1), ("_survey_stations", s)):
        variants = [("welleng_as_is", TorqueDrag), ("welleng_corrected", TorqueDragCorrected)]
        if label == "":
            variants += [("welleng_d1_fixed_only", TorqueDragD1Only),
                         ("welleng_d2_fixed_only", TorqueDragD2Only)]
        for name, cls in variants:
            td, td_on = run_welleng(survey, bha, wb, cls)
            r, p, n = summarize_welleng(td, td_on)
            results[name + label], profiles[name + label], normals[name + label] = r, p, n
        md_nodes = np.asarray(td.survey.md[: td.index])
        off, on, mid, L, t_nodes = run_direct(md_nodes, md_st, inc_st, azi_st, SECTIONS, friction)
        results["direct" + label] = summarize_direct(md_nodes, off, on, mid, L)
        profiles["direct" + label] = dict(
            md=md_nodes, pickup=off["pickup"]["T"], slackoff=off["slackoff"]["T"],
            rotating=off["rotating"]["T"], torque_rotating=off["rotating"]["M"],
            rotating_on_bottom=on["rotating"]["T"], torque_on_bottom=on["rotating"]["M"])
        normals["direct" + label] = {"pickup": off["pickup"]["N"], "rotating": off["rotating"]["N"],
                                     "rotating_on_bottom": on["rotating"]["N"], "L": L, "md_mid": mid}
        if label == "":
            # node directions: welleng's interpolation against the slerp written here
            t_wl = tangent(td.survey.inc_rad[: td.index], td.survey.azi_grid_rad[: td.index])
            node_dir_diff = float(np.max(np.linalg.norm(t_wl - t_nodes, axis=1)))
            n_nodes = len(md_nodes)

    # HookLoad cross-check (uniform friction; bit depth stepped every 500 m)
    hl = HookLoad(s, wb, bha, fluid_density=RHO_MUD / 1000.0, step=500.0, ff_range=(0.2, 0.3, 0.1))
    hookload = {"note": "welleng HookLoad: one friction factor for all sections; tensions at "
                        "surface + block weight; string stations = survey stations",
                "bit_md": [float(x) for x in hl.md_range]}
    for ff, dd in hl.data.items():
        hookload[f"ff_{ff:.1f}"] = {k: [float(v) + BLOCK for v in vals] for k, vals in dd.items()}
    for ff in (0.2, 0.3):
        wbu = make_wellbore([(SHOE_MD, ff), (BIT_MD, ff)], BIT_MD)  # same stations as HookLoad
        tdu = TorqueDrag(s, wbu, bha, fluid_density=RHO_MUD / 1000.0)
        hookload[f"ff_{ff:.1f}"]["torquedrag_at_td_pickup_N"] = float(tdu.tension["pickup"][0] + BLOCK)
        hookload[f"ff_{ff:.1f}"]["torquedrag_at_td_slackoff_N"] = float(tdu.tension["slackoff"][0] + BLOCK)

    # comparisons ----------------------------------------------------------------------
    keys = ["hook_load_pickup_N", "hook_load_slackoff_N", "hook_load_rotating_N",
            "hook_load_rotating_on_bottom_N", "surface_torque_off_bottom_Nm",
            "surface_torque_on_bottom_Nm", "max_normal_force_N_per_m"]

    def compare(a, b):
        ra, rb = results[a], results[b]
        pa, pb = profiles[a], profiles[b]
        assert np.array_equal(pa["md"], pb["md"])
        d = {k: float(ra[k] - rb[k]) for k in keys}
        for k in ("pickup", "slackoff", "rotating", "torque_rotating", "rotating_on_bottom",
                  "torque_on_bottom"):
            d[f"max_abs_profile_difference_{k}"] = float(np.max(np.abs(np.asarray(pa[k]) - pb[k])))
        return d

    comparisons = {
        "welleng_corrected_minus_direct": compare("welleng_corrected", "direct"),
        "welleng_as_is_minus_direct": compare("welleng_as_is", "direct"),
        "welleng_corrected_minus_direct_survey_stations":
            compare("welleng_corrected_survey_stations", "direct_survey_stations"),
        "welleng_as_is_minus_direct_survey_stations":
            compare("welleng_as_is_survey_stations", "direct_survey_stations"),
    }

    # residual analysis: where do corrected welleng and direct normal forces differ?
    nc, nd = normals["welleng_corrected"], normals["direct"]
    dN = nc["pickup"] - nd["pickup"]
    order = np.argsort(-np.abs(dN))[:5]
    mu_el = np.where(nd["md_mid"] < SHOE_MD, MU_CASED, MU_OPEN)
    kick = int(np.argmax(np.abs(dN)))
    residual = {
        "largest_pickup_normal_force_differences_N": [
            {"element_md_mid": float(nd["md_mid"][j]), "L_m": float(nd["L"][j]),
             "welleng_corrected_N": float(nc["pickup"][j]), "direct_N": float(nd["pickup"][j])}
            for j in order],
        "sum_mu_dN_pickup_N": float(np.sum(mu_el * dN)),
        "sum_mu_dN_pickup_excluding_largest_element_N":
            float(np.sum(mu_el * dN) - mu_el[kick] * dN[kick]),
        "max_node_direction_difference_welleng_interpolation_vs_slerp": node_dir_diff,
    }

    dNr = nc["rotating"] - nd["rotating"]
    r_el = np.where(nd["md_mid"] < BIT_MD - SECTIONS[1]["length"], SECTIONS[0]["contact"] / 2,
                    SECTIONS[1]["contact"] / 2)
    kr = int(np.argmax(np.abs(dNr)))
    residual["sum_mu_r_dN_rotating_Nm"] = float(np.sum(mu_el * r_el * dNr))
    residual["sum_mu_r_dN_rotating_excluding_largest_element_Nm"] = float(
        np.sum(mu_el * r_el * dNr) - mu_el[kr] * r_el[kr] * dNr[kr])
    # C3 check: give the element below a vertical node no azimuth change (the azimuth of a
    # vertical station is undefined; welleng stores 0 there) and rerun the corrected stepping.
    tk, tk_on = run_welleng(s1, bha, wb, TorqueDragCorrected)
    for t_ in (tk, tk_on):
        vert = np.where(t_.survey.inc_rad[:-1] < 1e-12)[0] + 1
        t_.azi_delta[vert] = 0.0
        t_.tension, t_.torque = {}, {}
        t_.get_forces_and_torsion()
    tk_on.get_forces_and_torsion(wob=WOB, tob=TOB)
    rk, _, _ = summarize_welleng(tk, tk_on)
    residual["welleng_corrected_with_zero_azimuth_change_below_vertical_nodes_minus_direct"] = {
        k: float(rk[k] - results["direct"][k]) for k in keys}

    grid = np.arange(0.0, BIT_MD + 0.5, 100.0)
    pdir = profiles["direct"]
    prof_json = {
        "md": grid.tolist(),
        "tension_pickup_N": profile_at(pdir["md"], pdir["pickup"], grid),
        "tension_rotating_off_bottom_N": profile_at(pdir["md"], pdir["rotating"], grid),
        "torque_rotating_off_bottom_Nm": profile_at(pdir["md"], pdir["torque_rotating"], grid),
        "torque_pickup_Nm": [0.0] * len(grid),
        "tension_slackoff_N": profile_at(pdir["md"], pdir["slackoff"], grid),
        "tension_rotating_on_bottom_N": profile_at(pdir["md"], pdir["rotating_on_bottom"], grid),
        "torque_rotating_on_bottom_Nm": profile_at(pdir["md"], pdir["torque_on_bottom"], grid),
    }
    other_profiles = {}
    for name in ("welleng_as_is", "welleng_corrected"):
        p = profiles[name]
        other_profiles[name] = {
            "md": grid.tolist(),
            "tension_pickup_N": profile_at(p["md"], p["pickup"], grid),
            "tension_rotating_off_bottom_N": profile_at(p["md"], p["rotating"], grid),
            "torque_rotating_off_bottom_Nm": profile_at(p["md"], p["torque_rotating"], grid),
            "tension_slackoff_N": profile_at(p["md"], p["slackoff"], grid),
        }

    td_json = {
        "welleng_version": WELLENG_VERSION,
        "units": "N, N m, m; tensions are effective tensions without block weight; hook loads "
                 "include the 300 kN block weight",
        "nodes": f"{n_nodes} nodes: every 1 m from 0 to 4000 m plus the survey stations "
                 "(welleng: Survey.interpolate_mds); *_survey_stations: the 135 survey stations",
        "inputs": {"w_pipe_N_per_m": buoyed_w(SECTIONS[0]), "w_collars_N_per_m": buoyed_w(SECTIONS[1]),
                   "r_pipe_m": SECTIONS[0]["contact"] / 2, "r_collars_m": SECTIONS[1]["contact"] / 2,
                   "mu": {"0-1800": MU_CASED, "1800-4000": MU_OPEN}, "wob_N": WOB, "tob_Nm": TOB,
                   "block_weight_N": BLOCK, "g": G, "rho_steel": RHO_STEEL, "rho_mud": RHO_MUD},
        "max_normal_force_note": "N/L of the element with the largest pick-up normal force; md = "
                                 "element mid md; other cases under max_normal_force_by_case",
        "welleng_as_is": results["welleng_as_is"],
        "welleng_corrected": results["welleng_corrected"],
        "direct": results["direct"],
        "welleng_as_is_survey_stations": results["welleng_as_is_survey_stations"],
        "welleng_corrected_survey_stations": results["welleng_corrected_survey_stations"],
        "direct_survey_stations": results["direct_survey_stations"],
        "defect_decomposition_1m_nodes": {
            name: {k: results[name][k] for k in keys}
            for name in ("welleng_as_is", "welleng_d1_fixed_only", "welleng_d2_fixed_only",
                         "welleng_corrected")},
        "comparisons": comparisons,
        "residual_corrected_vs_direct": residual,
        "direct_profiles_every_100m": prof_json,
        "welleng_profiles_every_100m": other_profiles,
        "welleng_hookload": hookload,
        "small_cases": small,
    }
    (outdir / "welleng_s_well_3d_torque_drag.json").write_text(json.dumps(td_json, indent=1))

    for name in ("welleng_as_is", "welleng_corrected", "direct"):
        print(name, json.dumps({k: round(v, 3) for k, v in results[name].items()
                                if isinstance(v, float)}))
    print(json.dumps(comparisons, indent=1))
    print(json.dumps(residual, indent=1))


if __name__ == "__main__":
    main()
