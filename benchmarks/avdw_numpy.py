"""Numpy port of Aarsnes & van de Wouw's (2019) coupled axial-torsional drill string with a regenerative bit.

Source: github.com/ulfjakob/AxialTorsionalDrillString (MIT), commit 934481490111bb9101da743f525d35723282f72c,
folder ``Coupled/``: ``parameters.m``, ``MAIN.m``, ``waveStep_transportBRI.m``. The conventions and quirks
are documented with file:line in ``tests/reference/aarsnes-van-de-wouw-2019/README.md``.

Two modes of one scheme (1000 cells of first-order upwind in Riemann invariants per field, 8 sub-steps
per 0.003 s step, the ghost-cell bit boundary and the imposed top speeds of their code):

* ``published`` (:func:`simulate` with the defaults): their scheme as their code runs it, floating-point
  operations in their order, so the port reproduces GNU Octave's numbers to rounding: the cut surface
  advected by first-order upwind on ``Pl`` = 169 / 84 / 42 cells (30 / 60 / 120 rpm) with the last cell's
  speeds, the velocity damping applied at twice the rate it names (``-dt ka (alpha + beta)`` on each
  invariant), the bit regime decided from the last cell's speeds with thresholds (``vb > 0.001``,
  ``ob < 0.1``, ``|g_tt| > 1e-3``), the contact torque ``gamma mu a W_f`` (no 1/2), the state converted
  to (strain, speed) and back at every step.
* ``converged`` (:func:`simulate` with ``CONVERGED``): the same physics with the cut surface as the exact
  delay ``d_n = x(t) - x(t - t_n)``, ``phi(t) - phi(t - t_n) = 2 pi / N``, interpolated linearly in the
  bit's angle (or, for the convergence study, upwind on any number of cells, sub-cycled to keep their
  Courant number), driven by the bit face's speeds; the damping at its named rate (``damping=1``); and the
  set-valued bit law (no thresholds): lift-off for ``d <= 0``, cutting with the contact force
  ``W_f = clip(W_hold - W_c, 0, a l sigma)``, stick when the torque that holds the face is at most
  ``T_c + T_f``, the face then held axially too unless the string pulls it up.
  The contact torque convention (``gamma mu a W_f``) and the pure delay (the previous pass, cut or not) are
  kept: they are the model, not the numerics.

    python benchmarks/avdw_numpy.py [--rpm 30] [--rop 30] [--t1 25] [--mode published|converged]
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass, replace

import numpy as np
from aarsnes_shor_numpy import _octave_linspace

# Coupled/parameters.m, lines 5-41
_RO, _RI = 0.0635, 0.0540
_A, _EPS, _ZETA, _SIGMA, _WEAR, _GAMMA, _MU, _N = 0.108, 60e6, 0.6, 60e6, 11.0e-3, 1.0, 0.6, 4.0
_L, _E, _G, _RHO = 2000.0, 200e9, 77e9, 8e3


def parameters(rpm: float = 30.0, rop: float = 30.0, cells: int = 1000) -> dict:
    """``parameters.m`` with ``p.omega0 = rpm/60*2*pi`` and ``p.V0 = rop/3600``; same expressions, same order."""
    pi = math.pi
    p: dict = {"ro": _RO, "ri": _RI, "a": _A, "epsilon": _EPS, "zeta": _ZETA, "sigma": _SIGMA, "l": _WEAR,
               "gamma": _GAMMA, "mu": _MU, "N": _N}
    p["Ap"] = pi * (_RO ** 2 - _RI ** 2)
    p["Jp"] = pi / 2 * (_RO ** 4 - _RI ** 4)
    p["L"], p["E"], p["G"], p["rho"] = _L, _E, _G, _RHO
    p["omega0"] = rpm / 60 * 2 * pi
    p["V0"] = rop / 3600
    p["dNom"] = (2 * pi) * p["V0"] / (p["omega0"] * p["N"])
    p["ka"], p["kt"] = 1.0, 1.0
    p["ka_L"], p["kt_L"] = 1.0, 1.0
    p["c_a"] = math.sqrt(p["E"] / p["rho"])
    p["c_t"] = math.sqrt(p["G"] / p["rho"])
    p["tN"] = 2 * pi / (p["N"] * p["omega0"])
    p["P"] = cells
    p["dt"] = 0.003
    dx = p["L"] / p["P"]
    dt = dx / max(p["c_a"], p["c_t"]) * .99
    n = math.ceil(p["dt"] / dt)
    dt = p["dt"] / n
    p["omegaMAX"] = p["omega0"] * 5
    dxl = dt * p["omegaMAX"]
    p["Pl"] = math.floor(1 / dxl)
    p["Wf"] = p["a"] * p["l"] * p["sigma"]
    p["Tf"] = p["gamma"] * p["mu"] * p["a"]
    p["K_a"] = p["a"] * p["zeta"] * p["epsilon"]
    p["K_t"] = p["a"] ** 2 * p["epsilon"] / 2
    return p


@dataclass(frozen=True)
class Scheme:
    """What differs between the published run and its converged twin (defaults: the published code)."""

    cut_surface: str = "upwind"   # "upwind" (a chain of cells) or "delay" (exact, interpolated)
    cut_cells: int | None = None  # upwind cells; None: their Pl
    damping: float = 2.0          # applied rate / named rate: 2 as their update applies it, 1 as named
    regime: str = "threshold"     # "threshold" (their last-cell tests) or "set_valued"
    speeds: str = "cell"          # speeds driving the cut surface: "cell" (their last cell) or "face"


PUBLISHED = Scheme()
CONVERGED = Scheme(cut_surface="delay", damping=1.0, regime="set_valued", speeds="face")

# per-step series (sub-step means, as the Octave recording; "last_" the last sub-step)
_MEANS = ("top_force_N", "top_torque_Nm", "wob_N", "tob_Nm", "depth_of_cut_m", "bit_face_speed_m_s",
          "bit_face_speed_rad_s", "top_power_W", "bit_power_W", "damping_power_W")
_LAST = ("last_wob_N", "last_tob_Nm", "last_d_m", "last_ga", "last_g_tt_Nm", "last_wf_N", "last_stuck")


def initial_state(p: dict) -> tuple[np.ndarray, ...]:
    """``MAIN.m:15-25``: h0, v0, f0, o0, l0 (their initial profiles, not an equilibrium)."""
    n = p["P"]
    v0 = np.ones(n) * p["V0"]
    h0 = _octave_linspace(p["Wf"] / (p["Ap"] * p["E"]) * 1.8 + p["L"] * p["ka"] / p["E"] * p["V0"] * p["rho"],
                          p["Wf"] / (p["Ap"] * p["E"]), n)
    o0 = np.ones(n) * p["omega0"]
    f0 = _octave_linspace(p["Tf"] * p["Wf"] / (p["Jp"] * p["G"]) + p["L"] * p["kt"] / p["G"] * p["omega0"] * p["rho"],
                          p["Tf"] * p["Wf"] / (p["Jp"] * p["G"]), n)
    l0 = _octave_linspace(0.0, 1.0, p["Pl"]) * (2 * math.pi) * p["V0"] / (p["omega0"] * p["N"])
    return h0, v0, f0, o0, l0


class CutDelay:
    """The exact delay: records (angle, axial position) of the bit face, one per sub-step, the surface under
    a blade interpolated linearly in the angle one blade angle back (the previous pass, cut or not)."""

    def __init__(self, p: dict, capacity: int) -> None:
        self.blade = 2 * math.pi / p["N"]
        self.phi = np.empty(capacity + 2)
        self.x = np.empty(capacity + 2)
        # the steady helix of the set-points behind the start: depth per blade dNom, as their l0(end)
        self.phi[0], self.x[0] = -self.blade, -p["dNom"]
        self.phi[1], self.x[1] = 0.0, 0.0
        self.n = 2
        self.k = 0  # phi[k] <= key < phi[k+1] for the last key (keys never decrease)

    def depth_per_blade(self, phi: float, x: float) -> float:
        key = phi - self.blade
        ph, k, last = self.phi, self.k, self.n - 1
        while k + 1 < last and ph[k + 1] <= key:
            k += 1
        self.k = k
        if ph[k + 1] <= key:  # only the current record is beyond: cannot happen with blade > 0
            return x - self.x[last]
        a, b = ph[k], ph[k + 1]
        return x - (self.x[k] + (self.x[k + 1] - self.x[k]) * ((key - a) / (b - a)))

    def push(self, phi: float, x: float) -> None:
        self.phi[self.n], self.x[self.n] = phi, x
        self.n += 1


def upwind_cut_surface(l: np.ndarray, dt: float, dxl: float, omega: float, v: float, blades: float) -> np.ndarray:
    """One step of ``waveStep_transportBRI.m:93-94``: ``l_pad = [0; l];``
    ``l = l - dt/dxl *max(ob,0)*p.N/(2*pi) *diff(l_pad) + dt*vb;`` (their order of operations)."""
    return l - dt / dxl * max(omega, 0.0) * blades / (2 * math.pi) * np.diff(np.concatenate((_ZERO, l))) + dt * v


_ZERO = np.zeros(1)


def set_valued_bit(p: dict, hold_w: float, hold_t: float, d: float) -> tuple[float, float, float, float, bool]:
    """The bit law as a set-valued boundary, no thresholds: ``(W, T, W_f, g_tt, stuck)`` for the depth of cut
    per revolution ``d`` and the loads ``hold_w = Z_a alpha_P``, ``hold_t = Z_t alpha_P^t`` that would hold the
    bit face at rest (the face speeds are then ``alpha_P - W / Z_a``, ``alpha_P^t - T / Z_t``).

    * lift-off, ``d <= 0``: ``W = T = 0``;
    * cutting, ``hold_t > T_c + T_f``: ``W = W_c + W_f``, ``T = T_c + T_f``,
      ``W_f = clip(hold_w - W_c, 0, a l sigma)`` (full while the face advances, the force that holds it
      otherwise, none while it rises), ``T_f = gamma mu a W_f`` (their convention, no 1/2);
    * stick, otherwise: ``T = hold_t`` (face not turning), ``W = max(hold_w, 0)`` (face held axially
      unless the string pulls it up); ``g_tt = hold_t - T_c - T_f`` as their stick torque.
    """
    if d <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, False
    wc, tc = d * p["K_a"], d * p["K_t"]
    wf = min(max(hold_w - wc, 0.0), p["Wf"])
    tf = p["Tf"] * wf
    if hold_t > tc + tf:
        return wc + wf, tc + tf, wf, 0.0, False
    return max(hold_w, 0.0), hold_t, 0.0, hold_t - tc - tf, True


def _energy(p: dict, h: np.ndarray, v: np.ndarray, f: np.ndarray, o: np.ndarray) -> float:
    """Strain and kinetic energy of the string, J (cell sums times dx)."""
    dx = p["L"] / p["P"]
    return float(dx / 2 * (p["Ap"] * p["E"] * np.dot(h, h) + p["rho"] * p["Ap"] * np.dot(v, v)
                           + p["Jp"] * p["G"] * np.dot(f, f) + p["rho"] * p["Jp"] * np.dot(o, o)))


def simulate(rpm: float = 30.0, rop: float = 30.0, t1: float = 25.0, scheme: Scheme = PUBLISHED,
             cells: int = 1000, keep_cut_surface: bool = False) -> dict[str, np.ndarray]:
    """Run ``MAIN.m`` (``t = 0:p.dt:T1``, one ``waveStep_transportBRI`` per entry) with ``scheme``.

    Returns per 0.003 s step: ``t_end_s``, the last cell's speeds after the step
    (``bit_cell_speed_end_m_s``, ``_rad_s``), the sub-step means of the top force and torque, WOB, TOB,
    depth of cut per revolution and bit face speeds, and the last sub-step's bit law (``last_*``;
    ``last_stuck`` 1 where the torsional stick branch acts); the energy ledger (sub-step means of the
    power in at the top ``top_power_W``, into the rock ``bit_power_W``, of the damping at its applied rate
    ``damping_power_W``; the string's energy ``energy_end_J`` after each step, ``energy_start_J``);
    ``final_state`` (h, v, f, o, l of the published state vector; l is empty with the exact delay)."""
    p = parameters(rpm, rop, cells)
    pi = math.pi
    h, v, f, o, lcut = initial_state(p)
    P = p["P"]
    dx = p["L"] / P
    dt = dx / max(p["c_a"], p["c_t"]) * .99
    dxl = 1 / p["Pl"]
    dtl = dxl / p["omegaMAX"]
    n = max(math.ceil(p["dt"] / dt), math.ceil(p["dt"] / dtl))
    dt = p["dt"] / n
    published = scheme == PUBLISHED
    c_a, c_t, V0, omega0 = p["c_a"], p["c_t"], p["V0"], p["omega0"]
    Ap, Jp, E, G, Wf, Tf, K_a, K_t, Nb = p["Ap"], p["Jp"], p["E"], p["G"], p["Wf"], p["Tf"], p["K_a"], p["K_t"], p["N"]
    ka, kt = p["ka"], p["kt"]
    Za, Zt = Ap * E / c_a, Jp * G / c_t
    ca_dx, ct_dx = dt / dx * c_a, dt / dx * c_t
    dka, dkt = dt * ka, dt * kt
    if not published:
        dka, dkt = dka * scheme.damping / 2, dkt * scheme.damping / 2
    # cut surface
    delay = None
    sub = 1
    if scheme.cut_surface == "delay":
        lcut = np.zeros(0)
    elif scheme.cut_surface == "upwind":
        if scheme.cut_cells is not None and scheme.cut_cells != p["Pl"]:
            pl = scheme.cut_cells
            lcut = _octave_linspace(0.0, 1.0, pl) * (2 * pi) * V0 / (omega0 * Nb)
            # sub-cycles keeping their Courant number: dt_l <= 1 / (Pl omegaMAX)
            sub = max(1, math.ceil(pl * dt * p["omegaMAX"] - 1e-12))
            dxl = 1 / pl
    else:
        raise ValueError(f"cut_surface: one of upwind, delay, not {scheme.cut_surface!r}")
    dt_l = dt / sub

    nt = math.floor(t1 / p["dt"] + 1e-9) + 1  # numel(T0:p.dt:T1)
    if delay is None and scheme.cut_surface == "delay":
        delay = CutDelay(p, nt * n)
    out = {k: np.empty(nt) for k in ("t_end_s", "bit_cell_speed_end_m_s", "bit_cell_speed_end_rad_s",
                                     *_MEANS, *_LAST)}
    acc = np.zeros(len(_MEANS))
    # the energy ledger: applied damping rates (each invariant loses dk (alpha + beta) = 2 dk v per sub-step)
    rate_a, rate_t = 2 * dka / dt, 2 * dkt / dt
    damp_a, damp_t = rate_a * p["rho"] * Ap * dx / 4, rate_t * p["rho"] * Jp * dx / 4
    out["energy_end_J"] = np.empty(nt)
    energy = _energy(p, h, v, f, o)
    out["energy_start_J"] = np.array(energy)
    x_bit = phi_bit = 0.0
    pad_a = np.empty(P + 1)
    pad_b = np.empty(P + 1)
    pad_ta = np.empty(P + 1)
    pad_tb = np.empty(P + 1)
    for k in range(nt):
        Aalpha = v + c_a * h
        Abeta = v - c_a * h
        Talpha = o + c_t * f
        Tbeta = o - c_t * f
        acc[:] = 0.0
        for _ in range(n):
            Aalpha0 = -Abeta[0] * p["ka_L"] + 2 * V0
            Talpha0 = -Tbeta[0] * p["kt_L"] + 2 * omega0
            aP, tP = float(Aalpha[P - 1]), float(Talpha[P - 1])
            vb = 1 / 2 * (float(Abeta[P - 1]) + aP)
            ob = 1 / 2 * (float(Tbeta[P - 1]) + tP)
            if delay is None:
                d = Nb * max(float(lcut[-1]), 0.0)
            else:
                d = Nb * max(delay.depth_per_blade(phi_bit, x_bit), 0.0)
            wc = d * K_a
            tc = d * K_t
            if scheme.regime == "threshold":
                ga = 1 / Wf * (aP * Ap * E / c_a - wc)
                ga = float(vb > 0.001) + float(vb <= 0.001) * min(max(ga, 0.0), 1.0)
                wf = Wf * ga
                tf = Tf * Wf * ga
                g_tt = tP * Jp * G / c_t - tc - tf
                g_tt = float(ob < 0.1) * min(g_tt, 0.0)
                g_wt = aP * Ap * E / c_a - wc - wf
                g_wt = g_wt * float(abs(g_tt) > 1e-3)
                tb = tc + tf + g_tt + 0.0
                wb = wc + wf + g_wt + 0.0
                stuck = g_tt != 0.0
            elif scheme.regime == "set_valued":
                wb, tb, wf, g_tt, stuck = set_valued_bit(p, Za * aP, Zt * tP, d)
                ga = wf / Wf
            else:
                raise ValueError(f"regime: one of threshold, set_valued, not {scheme.regime!r}")
            AbetaPp1 = aP - 2 * wb * c_a / (Ap * E)
            TbetaPp1 = tP - 2 * tb * c_t / (Jp * G)
            v_face = (aP + AbetaPp1) / 2
            o_face = (tP + TbetaPp1) / 2
            top_f = Ap * E * (Aalpha0 - Abeta[0]) / (2 * c_a)
            top_t = Jp * G * (Talpha0 - Tbeta[0]) / (2 * c_t)
            sa = Abeta + Aalpha
            st = Tbeta + Talpha
            acc += (top_f, top_t, wb, tb, d, v_face, o_face,
                    top_f * (Aalpha0 + Abeta[0]) / 2 + top_t * (Talpha0 + Tbeta[0]) / 2,
                    wb * v_face + tb * o_face, damp_a * np.dot(sa, sa) + damp_t * np.dot(st, st))

            pad_a[0] = Aalpha0
            pad_a[1:] = Aalpha
            pad_b[:P] = Abeta
            pad_b[P] = AbetaPp1
            pad_ta[0] = Talpha0
            pad_ta[1:] = Talpha
            pad_tb[:P] = Tbeta
            pad_tb[P] = TbetaPp1
            Aalpha = Aalpha - ca_dx * np.diff(pad_a) - dka * sa
            Abeta = Abeta + ca_dx * np.diff(pad_b) - dka * (Abeta + Aalpha)
            Talpha = Talpha - ct_dx * np.diff(pad_ta) - dkt * st
            Tbeta = Tbeta + ct_dx * np.diff(pad_tb) - dkt * (Tbeta + Talpha)

            if scheme.speeds == "cell":
                sv, so = vb, ob
            else:
                sv, so = v_face, o_face
            if delay is None:
                for _c in range(sub):
                    lcut = upwind_cut_surface(lcut, dt_l, dxl, so, sv, Nb)
            else:
                x_bit += dt * sv
                phi_bit += dt * max(so, 0.0)
                delay.push(phi_bit, x_bit)
        v = 1 / 2 * (Abeta + Aalpha)
        h = 1 / (2 * c_a) * (Aalpha - Abeta)
        o = 1 / 2 * (Tbeta + Talpha)
        f = 1 / (2 * c_t) * (Talpha - Tbeta)
        out["t_end_s"][k] = (k + 1) * p["dt"]
        out["energy_end_J"][k] = _energy(p, h, v, f, o)
        out["bit_cell_speed_end_m_s"][k] = v[P - 1]
        out["bit_cell_speed_end_rad_s"][k] = o[P - 1]
        for name, val in zip(_MEANS, acc / n):
            out[name][k] = val
        for name, val in zip(_LAST, (wb, tb, d, ga, g_tt, wf, float(stuck))):
            out[name][k] = val
    out["final_state"] = np.concatenate((h, v, f, o, lcut))
    out["substeps"] = np.array(n)
    return out


RPM = 60.0 / (2.0 * math.pi)


def metrics(res: dict[str, np.ndarray], rpm: float, rop: float, window: tuple[float, float]) -> dict:
    """The metrics of ``make_reference.py`` over the steps starting in ``[window[0], window[1]]``."""
    t_start = res["t_end_s"] - 0.003
    sel = (t_start >= window[0] - 1e-9) & (t_start <= window[1] + 1e-9)
    vb = res["bit_cell_speed_end_m_s"][sel]
    ob = res["bit_cell_speed_end_rad_s"][sel]
    wob, tob = res["wob_N"][sel], res["tob_Nm"][sel]
    v0, om0 = rop / 3600, rpm / 60 * 2 * math.pi
    area = math.pi * _A ** 2
    spread_v = float(vb.max() - vb.min()) / v0
    spread_o = float(ob.max() - ob.min()) / om0
    x = wob - wob.mean()
    spec = np.abs(np.fft.rfft(x * np.hanning(len(x))))
    freq = np.fft.rfftfreq(len(x), d=0.003)
    return {
        "rop_mean_m_per_h": float(vb.mean() * 3600),
        "bit_rpm_mean": float(ob.mean() * RPM), "bit_rpm_min": float(ob.min() * RPM),
        "bit_rpm_max": float(ob.max() * RPM),
        "bit_axial_speed_min_m_s": float(vb.min()), "bit_axial_speed_max_m_s": float(vb.max()),
        "wob_mean_N": float(wob.mean()), "wob_min_N": float(wob.min()), "wob_max_N": float(wob.max()),
        "tob_mean_Nm": float(tob.mean()),
        "depth_of_cut_mean_m": float(res["depth_of_cut_m"][sel].mean()),
        "depth_of_cut_min_m": float(res["depth_of_cut_m"][sel].min()),
        "depth_of_cut_max_m": float(res["depth_of_cut_m"][sel].max()),
        "mse_mean_Pa": float(wob.mean() / area + (tob * ob).mean() / (area * vb.mean())),
        "stuck_fraction": float(res["last_stuck"][sel].mean()),
        "contact_regime_fraction": float((res["last_ga"][sel] < 1.0).mean()),
        "no_cut_fraction": float((res["last_d_m"][sel] == 0.0).mean()),
        "bit_axial_speed_spread_over_V0": spread_v,
        "bit_angular_speed_spread_over_omega0": spread_o,
        "settled": bool(spread_v < 0.01 and spread_o < 0.01),
        "wob_peak_frequency_hz": float(freq[1:][np.argmax(spec[1:])]) if np.any(x) else 0.0,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rpm", type=float, default=30.0)
    ap.add_argument("--rop", type=float, default=30.0)
    ap.add_argument("--t1", type=float, default=25.0)
    ap.add_argument("--mode", choices=("published", "converged"), default="published")
    ap.add_argument("--cut-cells", type=int, default=None, help="upwind cut-surface cells (converged physics)")
    a = ap.parse_args()
    scheme = PUBLISHED if a.mode == "published" else CONVERGED
    if a.cut_cells is not None:
        scheme = replace(scheme, cut_surface="upwind", cut_cells=a.cut_cells)
    t0 = time.perf_counter()
    res = simulate(a.rpm, a.rop, a.t1, scheme)
    wall = time.perf_counter() - t0
    m = metrics(res, a.rpm, a.rop, (a.t1 - 5.0, a.t1))
    print(f"{a.mode} {a.rpm:g} rpm / {a.rop:g} m/h to {a.t1:g} s: {wall:.1f} s wall")
    for k, val in m.items():
        print(f"  {k}: {val:.6g}" if isinstance(val, float) else f"  {k}: {val}")


if __name__ == "__main__":
    main()
