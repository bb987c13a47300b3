"""Vectorised numpy port of the open torsional drill-string model of Aarsnes & Shor (2018).

Source: github.com/Open-Source-Drilling-Community/Aarsnes-and-Shor-Torsional-Model (MIT),
commit 67002405b46a8f70dec3f25c2211fcb9a9db23f8: MAIN.m + parameters_WellB.m + torsionalWaveStep.m.

The port keeps their scheme and their quirks on purpose (it is a reference, not a corrected model):

* the collar polar moment ``Jc`` carries an extra factor pi (``pi*sum(L*pi*(OD^4-ID^4)/32)/sum(L)``);
* the collar uses the pipe wave speed ``c_t = sqrt(Gp/rho)`` (not ``sqrt(Gc/rho)``), so the
  pipe/collar impedance ratio is ``Jc*Gc/(Jp*Gp)``;
* the viscous source ``dt*kt*(alpha+beta)`` is multiplied by the sub-step ``dt`` again in the
  update, an effective damping rate ``d omega/dt = -2*kt*dt_sub*omega`` (0.0833 1/s for Well B);
* the cell size is ``L/P`` but the friction profile is evaluated on ``linspace(0, L, P)``;
* the state is converted to (strain, speed) and back to Riemann invariants at every 0.01 s step;
* PI controller (38e3, 100e3) on the top-drive speed, setpoint ramp
  ``sp += (sp_final - sp)/(1/dt)`` before each step, explicit Euler on the top drive.

Floating-point operations are evaluated in the same order as the MATLAB code so the port
reproduces GNU Octave's numbers to rounding. Only the cell loop is vectorised (pipe and collar
cells in one array with per-cell coefficients); the sub-step loop stays in Python.

    python benchmarks/aarsnes_shor_numpy.py [--md 2500] [--rpm 40] [--duration 60] [--cells 1000]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

# Well B (parameters_WellB.m)
_LCV = (48.700, 114.800, 56.700, 38.880)
_ODV = (0.150473, 0.187322, 0.209550, 0.247280)
_IDV = (0.096207, 0.098912, 0.071438, 0.123391)
_MD_PROF = np.array([0.0, 500.0, 1600.0, 4000.0])
_INC_PROF = np.array([0.0, 0.0, 60.0, 60.0])


def _octave_round(x: float) -> int:
    """MATLAB/Octave ``round`` (half away from zero)."""
    return int(math.floor(abs(x) + 0.5)) * (1 if x >= 0 else -1)


def _octave_linspace(a: float, b: float, n: int) -> np.ndarray:
    """Octave 7 ``linspace``: filled symmetrically from both ends, ends exact."""
    if n == 1:
        return np.array([b])
    delta = (b - a) / (n - 1)
    i = np.arange(n, dtype=float)
    out = np.empty(n)
    half = n // 2
    out[:half] = a + i[:half] * delta
    out[half:] = b - (n - 1 - i[half:]) * delta
    if n % 2 == 1:
        out[half] = (a + b) / 2
    out[0], out[-1] = a, b
    return out


def _seq_sum(values) -> float:
    s = 0.0
    for v in values:
        s += v
    return s


def parameters_well_b(md: float = 2500.0, mu: float = 0.3, f_rat: float = 0.65, o_thres: float = 1.5,
                      cells: int = 1000) -> dict:
    """``parameters_WellB(MD, mu, fRat, oThres)`` with ``Pt = cells``; same expressions, same order."""
    pi = math.pi
    p: dict = {}
    sum_l = _seq_sum(_LCV)
    p["Ac"] = _seq_sum(l * pi * ((od / 2) ** 2 - (idd / 2) ** 2) for l, od, idd in zip(_LCV, _ODV, _IDV)) / sum_l
    p["Jc"] = pi * _seq_sum(l * pi * (od ** 4 - idd ** 4) / 32 for l, od, idd in zip(_LCV, _ODV, _IDV)) / sum_l
    p["Cro"] = _seq_sum(l * od / 2 for l, od in zip(_LCV, _ODV)) / sum_l
    p["Pro"] = 0.146529 / 2
    p["Pri"] = 0.123024 / 2
    p["Jp"] = pi / 2 * (p["Pro"] ** 4 - p["Pri"] ** 4)
    p["Ap"] = pi * (p["Pro"] ** 2 - p["Pri"] ** 2)
    p["Gp"] = 61e9
    p["Gc"] = 67e9
    p["rho"] = 7850.0
    p["I_TD"] = 2900.0
    p["kt"] = 50.0 * 1
    p["c_t"] = math.sqrt(p["Gp"] / p["rho"])
    p["Lc"] = 230.0
    p["Lp"] = md - p["Lc"]
    pt = cells
    p["Pp"] = _octave_round(pt * p["Lp"] / (p["Lp"] + p["Lc"]))
    p["Pc"] = pt - p["Pp"]
    p["xp"] = _octave_linspace(0.0, p["Lp"], p["Pp"])
    p["xc"] = p["Lp"] + _octave_linspace(0.0, p["Lc"], p["Pc"])
    # interp1 'linear' (Octave: slope = dy/dx, then slope*(xi - x0) + y0, as np.interp)
    p["PthetaVec"] = np.interp(p["xp"], _MD_PROF, _INC_PROF) * pi / 180
    p["CthetaVec"] = np.interp(p["xc"], _MD_PROF, _INC_PROF) * pi / 180
    p["f_thres"], p["f_tRat"], p["o_thres"] = mu, f_rat, o_thres
    g = 9.81
    sin_p = np.array([math.sin(v) for v in p["PthetaVec"]])  # libm sin, as Octave
    sin_c = np.array([math.sin(v) for v in p["CthetaVec"]])
    p["P_thresProfile"] = g * sin_p * p["rho"] * p["Ap"] * p["Pro"] * p["f_thres"]
    p["C_thresProfile"] = g * sin_c * p["rho"] * p["Ac"] * p["Cro"] * p["f_thres"]
    return p


def _cumtrapz(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Octave ``cumtrapz(x, y)`` for column vectors: ``[0; 0.5*cumsum(diff(x).*(y1+y2))]``."""
    z = 0.5 * np.cumsum(np.diff(x) * (y[:-1] + y[1:]))
    return np.concatenate(([0.0], z))


def analytics(p: dict, f_rat: float) -> dict:
    """MAIN.m 'Basic analytics': tauMax (stored static torque profile), phiMax(1), tauMin."""
    x = np.concatenate((p["xp"], p["xc"]))
    prof = np.concatenate((p["P_thresProfile"], p["C_thresProfile"]))
    tau_max = _cumtrapz(x[::-1], -prof[::-1])[::-1]
    pp = p["Pp"]
    tw = np.concatenate((tau_max[:pp] / (p["Jp"] * p["Gp"]), tau_max[pp:] / (p["Jc"] * p["Gc"])))
    phi_max = _cumtrapz(x[::-1], tw[::-1])[::-1]
    return {"tau_max": tau_max, "tau_max_1": float(tau_max[0]), "phi_max_td": float(phi_max[0]),
            "tau_min": float(tau_max[0] * (1 - 2 * (1 - f_rat)))}


def substeps(p: dict, dt: float = 0.01) -> tuple[int, float]:
    """(n, dt_sub) exactly as torsionalWaveStep.m computes them."""
    dxp = p["Lp"] / p["Pp"]
    dtp = dxp / p["c_t"] * .99
    dxc = p["Lc"] / p["Pc"]
    dtc = dxc / p["c_t"] * .99
    n = math.ceil(dt / min(dtp, dtc))
    return n, dt / n


def simulate(md: float = 2500, rpm: float = 40, duration: float = 60, cells: int = 1000, mu: float = 0.3,
             f_rat: float = 0.65, o_thres: float = 1.5, dt: float = 0.01, keep_state: bool = False,
             top_drive: str = "explicit") -> dict:
    """Run MAIN.m for Well B. Returns numpy arrays over ``t = 0:dt:duration`` (Nt samples):

    ``t`` (s), ``motor_torque`` (N m, MAIN's ``y(k)``, computed from the state at ``t[k]``),
    ``top_drive_speed`` (rad/s, ``x(2Pt+1,k)``), ``bit_speed`` (rad/s, last collar cell ``x(2Pt,k)``),
    ``setpoint`` (rad/s), plus scalars ``tau_max_1``, ``tau_min``, ``phi_max_td``, ``substeps``,
    ``dt_sub`` and the parameter dict ``params``; ``final_state`` (MAIN's ``x(:,end)``, the state
    after the last step) if ``keep_state``.

    ``top_drive="implicit"`` changes one thing: the top drive is implicit Euler in the string
    torque, ``(I/dt + Z) Otd' = I Otd/dt + tau_m + Z beta_1`` (``Z = Jp Gp / c_t``) before each
    sub-step, as drillstring's solver does, instead of their explicit update after it.
    """
    if top_drive not in ("explicit", "implicit"):
        raise ValueError(f"top_drive: got {top_drive!r}, expected 'explicit' or 'implicit'")
    implicit = top_drive == "implicit"
    p = parameters_well_b(md, mu, f_rat, o_thres, cells)
    an = analytics(p, f_rat)
    omega_stat = rpm / 60 * 2 * math.pi
    # t = T0:p.dt:T1 (Octave ranges: base + i*increment, the last element clipped to the limit)
    nt = int(math.floor(duration / dt * (1 + 4 * np.finfo(float).eps))) + 1
    t = 0.0 + np.arange(nt) * dt
    t[-1] = min(t[-1], duration)

    pp, pc = p["Pp"], p["Pc"]
    npt = pp + pc
    c_t = p["c_t"]
    dxp, dxc = p["Lp"] / pp, p["Lc"] / pc
    n, dts = substeps(p, dt)
    # per-cell coefficients (pipe cells then collar cells), each the same double as the scalar
    cdx = np.concatenate((np.full(pp, 1 / dxp * c_t), np.full(pc, 1 / dxc * c_t)))        # 1/dx *c_t
    dtcdx = np.concatenate((np.full(pp, dts / dxp * c_t), np.full(pc, dts / dxc * c_t)))   # dt/dx *c_t
    jcell = np.concatenate((np.full(pp, p["Jp"]), np.full(pc, p["Jc"])))
    jrho = np.concatenate((np.full(pp, p["Jp"] * p["rho"]), np.full(pc, p["Jc"] * p["rho"])))
    rho = p["rho"]
    thr = np.concatenate((p["P_thresProfile"], p["C_thresProfile"]))
    nthr = -thr
    thr_kin = thr * p["f_tRat"]           # sign(o).*Th*fRat == sign(o).*(Th*fRat) exactly (sign = 0, +-1)
    othr = p["o_thres"]
    dtkt = dts * p["kt"]
    zbar = p["Jc"] * p["Gc"] / (p["Jp"] * p["Gp"])
    inv1z = 1 / (1 + zbar)
    one_m_z = 1 - zbar
    two_z = 2 * zbar
    tau_coef = p["Jp"] * p["Gp"] / (2 * c_t)
    otd_coef = 1 / p["I_TD"] * dts
    inv2c = 1 / (2 * c_t)
    tb_term = 2 * 0 * c_t / (p["Jc"] * p["Gc"])   # bit torque tb = 0 (off bottom)

    f = np.zeros(npt)        # strain, pipe then collar
    o = np.zeros(npt)        # angular velocity
    otd = 0.0
    y = np.zeros(nt)
    td = np.zeros(nt)
    bit = np.zeros(nt)
    sp_hist = np.zeros(nt)
    omega_sp = 0.0
    ii = 0.0
    # work arrays
    s = np.empty(npt)
    op = np.empty(npt)
    d_a = np.empty(npt)
    d_b = np.empty(npt)
    vf = np.empty(npt)
    ci = np.empty(npt)
    tmp = np.empty(npt)
    fc = np.empty(npt)
    kin = np.empty(npt)
    stick = np.empty(npt, dtype=bool)
    pm1, last = pp - 1, npt - 1
    for k in range(nt):
        omega_sp = omega_sp + (omega_stat - omega_sp) / (1 / dt)
        td[k] = otd
        bit[k] = o[last]
        sp_hist[k] = omega_sp
        tau_motor = (omega_sp - otd) * 38e3 + ii * 100e3
        ii = ii + dt * (omega_sp - otd)
        y[k] = tau_motor
        # ---- torsionalWaveStep ----
        alpha = o + c_t * f
        beta = o - c_t * f
        for _ in range(n):
            np.add(beta, alpha, out=s)
            np.multiply(0.5, s, out=op)
            if implicit:
                otd = (p["I_TD"] / dts * otd + tau_motor + 2 * tau_coef * beta[0]) / (p["I_TD"] / dts + 2 * tau_coef)
            alpha0 = -beta[0] + 2 * otd
            cbeta_end = alpha[last] - tb_term
            pa_end, cb_first = alpha[pm1], beta[pp]
            pbeta_end = inv1z * (pa_end * one_m_z + two_z * cb_first)
            calpha0 = inv1z * (2 * pa_end - cb_first * one_m_z)
            # diff(alpha_pad), diff(beta_pad) with the interface values
            np.subtract(alpha[1:], alpha[:-1], out=d_a[1:])
            d_a[0] = alpha[0] - alpha0
            d_a[pp] = alpha[pp] - calpha0
            np.subtract(beta[1:], beta[:-1], out=d_b[:-1])
            d_b[pm1] = pbeta_end - beta[pm1]
            d_b[last] = cbeta_end - beta[last]
            np.multiply(dtkt, s, out=vf)                 # dt*kt*(beta+alpha)
            # ci = (alpha/dt - cdx*dA + beta/dt + cdx*dB - 2*vf)/2 * J * rho
            np.divide(alpha, dts, out=ci)
            np.multiply(cdx, d_a, out=tmp)
            ci -= tmp
            np.divide(beta, dts, out=tmp)
            ci += tmp
            np.multiply(cdx, d_b, out=tmp)
            ci += tmp
            np.multiply(2, vf, out=tmp)
            ci -= tmp
            ci /= 2
            ci *= jcell
            ci *= rho
            # friction: clipped 'static' torque below o_thres, kinetic fRat*Th*sign(o) above
            np.minimum(ci, thr, out=ci)
            np.maximum(ci, nthr, out=ci)
            np.sign(op, out=kin)
            kin *= thr_kin
            np.abs(op, out=tmp)
            np.less(tmp, othr, out=stick)
            np.copyto(kin, ci, where=stick)
            fc = kin
            # source S = vf + Fc/(J rho); upwind update
            np.divide(fc, jrho, out=tmp)
            tmp += vf
            tmp *= dts                                   # dt*S
            np.multiply(dtcdx, d_a, out=s)
            alpha -= s
            alpha -= tmp
            np.multiply(dtcdx, d_b, out=s)
            beta += s
            beta -= tmp
            if not implicit:
                tau_td = tau_coef * (alpha[0] - beta[0])
                otd = otd + otd_coef * (tau_motor - tau_td)
        o = 0.5 * (beta + alpha)
        f = inv2c * (alpha - beta)
    out = {"t": t, "motor_torque": y, "top_drive_speed": td, "bit_speed": bit, "setpoint": sp_hist,
           "tau_max_1": an["tau_max_1"], "tau_min": an["tau_min"], "phi_max_td": an["phi_max_td"],
           "substeps": n, "dt_sub": dts, "params": p}
    if keep_state:
        out["final_state"] = np.concatenate((f, o, [otd]))
    return out


def upward_crossing_period(t: np.ndarray, v: np.ndarray) -> tuple[float, int]:
    """Mean interval between upward crossings of ``v``'s mean (linear interpolation between samples);
    returns (period s, number of crossings)."""
    m = v.mean()
    d = v - m
    i = np.nonzero((d[:-1] < 0) & (d[1:] >= 0))[0]
    tc = t[i] - d[i] * (t[i + 1] - t[i]) / (d[i + 1] - d[i])
    if tc.size < 2:
        return float("nan"), int(tc.size)
    return float(np.mean(np.diff(tc))), int(tc.size)


def summary(res: dict, t0: float | None = None) -> dict:
    """Motor-torque range, cycle period and bit rpm over ``t >= t0`` (default: the last half)."""
    t = res["t"]
    if t0 is None:
        t0 = t[-1] / 2
    w = t >= t0 - 1e-9
    tq = res["motor_torque"][w]
    bit_rpm = res["bit_speed"][w] * 60 / (2 * math.pi)
    period, ncross = upward_crossing_period(t[w], tq)
    return {"window_start_s": float(t[w][0]), "window_end_s": float(t[w][-1]),
            "motor_torque_min": float(tq.min()), "motor_torque_max": float(tq.max()),
            "cycle_period_s": period, "upward_crossings": ncross,
            "bit_rpm_min": float(bit_rpm.min()), "bit_rpm_max": float(bit_rpm.max()),
            "bit_rpm_mean": float(bit_rpm.mean())}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--md", type=float, default=2500.0)
    ap.add_argument("--rpm", type=float, default=40.0)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--cells", type=int, default=1000)
    args = ap.parse_args()
    t0 = time.perf_counter()
    res = simulate(md=args.md, rpm=args.rpm, duration=args.duration, cells=args.cells)
    wall = time.perf_counter() - t0
    s = summary(res)
    print(f"Aarsnes & Shor Well B, MD {args.md:g} m, {args.rpm:g} rpm, {args.duration:g} s, {args.cells} cells, "
          f"{res['substeps']} sub-steps of {res['dt_sub']:.6g} s per 0.01 s")
    print(f"wall {wall:.2f} s = {wall / args.duration * 60:.2f} s per simulated minute")
    print(f"tauMax(1) {res['tau_max_1']:.6f} N m, tauMin {res['tau_min']:.6f} N m")
    print(f"over {s['window_start_s']:g}..{s['window_end_s']:g} s:")
    print(f"  motor torque {s['motor_torque_min']:.3f} .. {s['motor_torque_max']:.3f} N m")
    print(f"  cycle period {s['cycle_period_s']:.4f} s (mean interval between {s['upward_crossings']} upward "
          f"crossings of the motor torque's mean)")
    print(f"  bit speed {s['bit_rpm_min']:.3f} .. {s['bit_rpm_max']:.3f} rpm (mean {s['bit_rpm_mean']:.3f})")


if __name__ == "__main__":
    main()
