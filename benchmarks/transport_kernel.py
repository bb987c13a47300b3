"""The drilling solver's transport kernel against a numba port and a numpy port of the same scheme.

Case: examples/aarsnes-shor-well-b-corrected.toml (Well B, 2500 m, two sections, ~1000 cells,
60 s, PI control to 40 rpm, bit off bottom, set-valued wall friction with its stick phase,
damping; Courant numbers 0.998 and 0.999, so the upwind form of the update). The ports step the
same scheme as ``rust/core/src/drilling/engine`` (the Riemann invariants with an impedance
junction, the implicit top drive under the sampled PI controller, the free bit end, the sources
at the transported speed with the stick phase, the energy terms summed in 8 lanes per
section), in the same order of operations, so they reproduce ``ds.drill``'s series to rounding;
the check runs inside the benchmark before the timing.

Printed: seconds per run and ns per cell update (wall time / (cells x steps), one thread; the
numba time excludes compilation, the ds.drill time includes its setup, sampling and metrics),
the ratios and the core count.

    python benchmarks/transport_kernel.py [--duration 60] [--repeat 5]
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np
from numba import njit

import drillstring as ds

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-shor-well-b-corrected.toml"
RPM = 60.0 / (2.0 * math.pi)
WIDTH = 8
TINY = 5e-324  # the least positive double: "slow" below it means exactly at rest


def setup(cfg):
    """The grid of the solver (drilling/grid.rs, linear law) and the per-cell constants."""
    props = []
    for s in cfg.sections:
        od, id_ = s.outer_diameter, s.inner_diameter
        j = (
            s.polar_moment
            if s.polar_moment is not None
            else math.pi / 32.0 * ((od * od) * (od * od) - (id_ * id_) * (id_ * id_))
        )
        g, rho = s.shear_modulus, s.density
        props.append((s.length, math.sqrt(g / rho), j * math.sqrt(g * rho), rho * j))
    travel = sum(length / c for length, c, _, _ in props)
    shortest = min(length / c for length, c, _, _ in props)
    dt = min(travel / cfg.numerics.cells, shortest)
    counts, courant, spacing = [], [], []
    for length, c, _, _ in props:
        exact = length / (c * dt)
        n = max(math.floor(exact * (1.0 + 1e-9)), 1.0)
        cn = n / exact
        if abs(cn - 1.0) < 1e-9:
            cn = 1.0
        counts.append(int(n))
        courant.append(cn * cfg.numerics.courant)
        spacing.append(length / n)
    dt *= cfg.numerics.courant
    # The wall's friction limit per metre at the cell centres, as the solver has it.
    limit = np.asarray(ds.drilling.friction_profile(cfg).limit_per_m)
    offsets, stop, k = [], [], 0
    for s, (_, _, _, m) in enumerate(props):
        offsets.append(len(stop))
        stop.append(0.0)
        for _ in range(counts[s]):
            stop.append(dt * limit[k] / m)
            k += 1
        stop.append(0.0)
    stop = np.array(stop)
    slip = -(cfg.friction.kinetic_ratio * stop)
    return {
        "dt": dt,
        "offsets": np.array(offsets, dtype=np.int64),
        "counts": np.array(counts, dtype=np.int64),
        "courant": np.array(courant),
        "impedance": np.array([p[2] for p in props]),
        "e": np.array([0.25 * p[3] * h for p, h in zip(props, spacing)]),
        "stop": stop,
        "slip": slip,
        "cells": sum(counts),
    }


@njit(cache=False)
def _numba_run(
    steps, dt, offsets, counts, courant, impedance, e, stop, slip, damping, stick_speed, kinetic_ratio,
    inertia, kp, ki, limit, control_interval, approach, target, report_stick,
):  # fmt: skip
    """The solver's run loop (linear law, set-valued friction, PI, free bit without BHA)."""
    n_pad = stop.shape[0]
    alpha = np.zeros(n_pad)
    beta = np.zeros(n_pad)
    alpha_next = np.zeros(n_pad)
    beta_next = np.zeros(n_pad)
    # (t, omega_top, omega_bit reported, motor, bit torque) at every step end, the start first
    out = np.empty((steps + 1, 5))
    out[0, 0] = 0.0
    out[0, 1] = 0.0
    out[0, 2] = 0.0
    ledger = np.zeros(6)  # motor, friction, damping, bit, upwind, inertia
    jump = np.zeros(WIDTH)
    fric = np.zeros(WIDTH)
    damp = np.zeros(WIDTH)
    setpoint = 0.0
    omega = 0.0
    integral = 0.0
    torque = 0.0
    nxt = 0.0
    omega_bit = 0.0
    slow_below = stick_speed if stick_speed > 0.0 else TINY
    ns = offsets.shape[0]
    last = ns - 1
    for n in range(steps):
        t = n * dt
        setpoint = setpoint + (target - setpoint) * approach
        # top drive under the sampled PI controller
        z0 = impedance[0]
        beta1 = beta[offsets[0] + 1]
        if t + 0.5 * dt >= nxt:
            holds = 0.0
            while nxt <= t + 0.5 * dt:
                nxt += control_interval
                holds += 1.0
            err = setpoint - omega
            raw = kp * err + ki * integral
            torque = min(max(raw, -limit), limit)
            if not ((raw > limit and err > 0.0) or (raw < -limit and err < 0.0)):
                integral += holds * control_interval * err
        omega1 = (inertia * omega / dt + torque + z0 * beta1) / (inertia / dt + z0)
        alpha[offsets[0]] = 2.0 * omega1 - beta1
        ledger[0] += dt * torque * omega1
        ledger[5] += 0.5 * inertia * (omega1 - omega) * (omega1 - omega)
        omega = omega1
        # free bit end (no BHA inertia)
        zl = impedance[last]
        end = offsets[last] + counts[last]
        alpha_n = alpha[end]
        wb1 = (0.0 * omega_bit / dt + zl * alpha_n) / (0.0 / dt + zl)
        beta[end + 1] = 2.0 * wb1 - alpha_n
        ledger[5] += 0.5 * 0.0 * (wb1 - omega_bit) * (wb1 - omega_bit)
        omega_bit = wb1
        # junctions
        for k in range(1, ns):
            za, zb = impedance[k - 1], impedance[k]
            aa = alpha[offsets[k - 1] + counts[k - 1]]
            bb = beta[offsets[k] + 1]
            w = (za * aa + zb * bb) / (za + zb)
            beta[offsets[k - 1] + counts[k - 1] + 1] = 2.0 * w - aa
            alpha[offsets[k]] = 2.0 * w - bb
        # cells: upwind transport, then damping and friction at the transported speed
        for s in range(ns):
            c = courant[s]
            jump[:] = 0.0
            fric[:] = 0.0
            damp[:] = 0.0
            o = offsets[s] + 1
            for base in range(0, counts[s], WIDTH):
                for lane in range(min(WIDTH, counts[s] - base)):
                    i = o + base + lane
                    da = alpha[i] - alpha[i - 1]
                    db = beta[i] - beta[i + 1]
                    a1 = alpha[i] - c * da
                    b1 = beta[i] - c * db
                    w1 = 0.5 * (a1 + b1)
                    lim = stop[i]
                    dd = -damping * w1
                    wd = w1 + dd
                    # one threshold: the static limit when slow, the kinetic one when sliding
                    awd = abs(wd)
                    thr = lim if abs(w1) < slow_below else -slip[i]
                    stuck = awd <= thr
                    mag = thr if thr < awd else awd
                    df = mag if math.copysign(1.0, w1) < 0.0 else -mag
                    d = dd + df
                    wbar = w1 + 0.5 * d
                    s1 = 0.5 * (a1 - b1)
                    alpha_next[i] = s1 if stuck else a1 + d
                    beta_next[i] = -s1 if stuck else b1 + d
                    jump[lane] += da * da + db * db
                    fric[lane] += df * wbar
                    damp[lane] += dd * wbar
            ledger[4] += e[s] * c * (1.0 - c) * jump.sum()
            ledger[1] -= 4.0 * e[s] * fric.sum()
            ledger[2] -= 4.0 * e[s] * damp.sum()
        alpha, alpha_next = alpha_next, alpha
        beta, beta_next = beta_next, beta
        # the reported bit speed: at rest below a stuck last cell
        w_last = 0.5 * (alpha[end] + beta[end])
        bit = 0.0 if (w_last == 0.0 and abs(omega_bit) < report_stick) else omega_bit
        out[n + 1, 0] = (n + 1) * dt
        out[n + 1, 1] = omega
        out[n + 1, 2] = bit
        out[n + 1, 3] = torque
        out[n + 1, 4] = 0.0
        if n == 0:
            out[0, 3] = torque
    return out, ledger


def numpy_run(steps, g, damping, fr, td, approach, target, report_stick):
    """The same loop with each section's cells as numpy arrays (the step loop in Python)."""
    dt, offsets, counts = g["dt"], g["offsets"], g["counts"]
    alpha = np.zeros(g["stop"].size)
    beta = np.zeros_like(alpha)
    out = np.empty((steps + 1, 5))
    out[0] = 0.0
    inertia, kp, ki, limit = td.inertia, td.controller.kp, td.controller.ki, td.torque_limit
    slow_below = fr.stick_speed if fr.stick_speed > 0.0 else TINY
    setpoint = omega = integral = torque = nxt = omega_bit = 0.0
    z = g["impedance"]
    views = [slice(o + 1, o + 1 + n) for o, n in zip(offsets, counts)]
    last = len(offsets) - 1
    end = offsets[last] + counts[last]
    for n in range(steps):
        t = n * dt
        setpoint = setpoint + (target - setpoint) * approach
        beta1 = beta[offsets[0] + 1]
        if t + 0.5 * dt >= nxt:
            holds = 0.0
            while nxt <= t + 0.5 * dt:
                nxt += td.control_interval
                holds += 1.0
            err = setpoint - omega
            raw = kp * err + ki * integral
            torque = min(max(raw, -limit), limit)
            if not ((raw > limit and err > 0.0) or (raw < -limit and err < 0.0)):
                integral += holds * td.control_interval * err
        omega = (inertia * omega / dt + torque + z[0] * beta1) / (inertia / dt + z[0])
        alpha[offsets[0]] = 2.0 * omega - beta1
        alpha_n = alpha[end]
        omega_bit = (0.0 * omega_bit / dt + z[last] * alpha_n) / (0.0 / dt + z[last])
        beta[end + 1] = 2.0 * omega_bit - alpha_n
        for k in range(1, len(offsets)):
            aa, bb = alpha[offsets[k - 1] + counts[k - 1]], beta[offsets[k] + 1]
            w = (z[k - 1] * aa + z[k] * bb) / (z[k - 1] + z[k])
            beta[offsets[k - 1] + counts[k - 1] + 1] = 2.0 * w - aa
            alpha[offsets[k]] = 2.0 * w - bb
        new_a, new_b = alpha.copy(), beta.copy()
        for s, v in enumerate(views):
            c = g["courant"][s]
            a0, b0 = alpha[v], beta[v]
            a1 = a0 - c * (a0 - alpha[v.start - 1 : v.stop - 1])
            b1 = b0 - c * (b0 - beta[v.start + 1 : v.stop + 1])
            w1 = 0.5 * (a1 + b1)
            lim, sl = g["stop"][v], g["slip"][v]
            dd = -damping * w1
            wd = w1 + dd
            awd = np.abs(wd)
            thr = np.where(np.abs(w1) < slow_below, lim, -sl)
            stuck = awd <= thr
            mag = np.where(thr < awd, thr, awd)
            df = np.where(np.signbit(w1), mag, -mag)
            d = dd + df
            s1 = 0.5 * (a1 - b1)
            new_a[v] = np.where(stuck, s1, a1 + d)
            new_b[v] = np.where(stuck, -s1, b1 + d)
        alpha, beta = new_a, new_b
        w_last = 0.5 * (alpha[end] + beta[end])
        bit = 0.0 if (w_last == 0.0 and abs(omega_bit) < report_stick) else omega_bit
        out[n + 1] = ((n + 1) * dt, omega, bit, torque, 0.0)
        if n == 0:
            out[0, 3] = torque
    return out


def sample(out, output_interval, n_samples):
    """The sampler of engine/sampler.rs: linear between the step ends around each sample time."""
    t = out[:, 0]
    rows = []
    n = 1
    for k in range(n_samples):
        ts = k * output_interval
        while n < len(t) and ts > t[n] * (1.0 + 1e-12):
            n += 1
        prev, cur = out[n - 1], out[n]
        w = min(max((ts - prev[0]) / (cur[0] - prev[0]), 0.0), 1.0) if cur[0] > prev[0] else 1.0
        rows.append([ts, *(prev[i] + w * (cur[i] - prev[i]) for i in (1, 2, 3))])
    r = np.array(rows)
    return r[:, 0], r[:, 1] * RPM, r[:, 2] * RPM, r[:, 3]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=60.0, help="simulated seconds")
    parser.add_argument("--repeat", type=int, default=5, help="runs per tool (the best is kept)")
    args = parser.parse_args()
    cfg = ds.load_drill_config(EXAMPLE).with_overrides({"numerics.duration": args.duration})
    td, fr = cfg.top_drive, cfg.friction
    g = setup(cfg)
    dt = g["dt"]
    steps = math.ceil((args.duration / dt) * (1.0 - 1e-12))
    approach = 1.0 - math.exp(-dt / td.ramp_time)
    target = td.rpm / RPM
    damping = dt * cfg.damping_rate
    report_stick = max(fr.stick_speed, cfg.metrics.stick_speed)
    assert not cfg.bit.on_bottom and cfg.bit.bha_inertia == 0.0 and td.controller.type == "pi"
    assert fr.model == "set_valued" and not td.steps

    def numba_call():
        return _numba_run(
            steps, dt, g["offsets"], g["counts"], g["courant"], g["impedance"], g["e"], g["stop"], g["slip"],
            damping, fr.stick_speed, fr.kinetic_ratio, td.inertia, td.controller.kp, td.controller.ki,
            td.torque_limit, td.control_interval, approach, target, report_stick,
        )  # fmt: skip

    # The check: the ports against ds.drill on the same case.
    res = ds.drill(cfg, progress=False)
    assert res.success, res.message
    assert res.stats["cells"] == g["cells"] and res.stats["steps"] == steps and res.stats["dt"] == dt
    out, ledger = numba_call()
    n_samples = res.t.size
    t, top, bit, motor = sample(out, cfg.numerics.output_interval, n_samples)
    for name, mine, theirs in (
        ("t", t, res.t),
        ("surface_rpm", top, res.surface_rpm),
        ("bit_rpm", bit, res.bit_rpm),
        ("motor_torque", motor, res.motor_torque),
    ):
        err = np.max(np.abs(mine - theirs)) / max(np.max(np.abs(theirs)), 1e-300)
        exact = np.array_equal(mine, theirs)
        print(f"numba vs ds.drill, {name}: {'bit-identical' if exact else f'max relative difference {err:.1e}'}")
        assert err < 1e-9, name
    for name, k in (("motor_work", 0), ("friction_loss", 1), ("damping_loss", 2), ("upwind_loss", 4)):
        mine, theirs = ledger[k], res.energy[name]
        same = "bit-identical" if mine == theirs else f"relative difference {abs(mine - theirs) / abs(theirs):.1e}"
        print(f"numba vs ds.drill, energy {name}: {same}")
        assert abs(mine - theirs) <= 1e-9 * abs(theirs), name
    out_np = numpy_run(
        steps if args.duration <= 6.0 else math.ceil(6.0 / dt), g, damping, fr, td, approach, target, report_stick
    )
    k = len(out_np)
    err = np.max(np.abs(out_np[:, 1:4] - out[:k, 1:4])) / np.max(np.abs(out[:k, 1:4]))
    print(f"numpy vs numba, first {k - 1} steps: max relative difference {err:.1e}")
    assert err < 1e-9

    # The timing (best of --repeat runs each, interleaved).
    # Wall time and the thread's CPU time (the same on an idle machine; on a loaded one the
    # CPU time is the one to compare).
    best = {name: [math.inf, math.inf] for name in ("ds.drill", "numba", "numpy")}

    def timed(name, call, scale=1.0):
        wall, cpu = time.perf_counter(), time.thread_time()
        call()
        cpu, wall = time.thread_time() - cpu, time.perf_counter() - wall
        best[name] = [min(best[name][0], wall * scale), min(best[name][1], cpu * scale)]

    np_steps = math.ceil(min(args.duration, 2.0) / dt)
    for _ in range(args.repeat):
        timed("ds.drill", lambda: ds.drill(cfg, progress=False))
        timed("numba", numba_call)
    timed("numpy", lambda: numpy_run(np_steps, g, damping, fr, td, approach, target, report_stick), steps / np_steps)
    updates = g["cells"] * steps
    print(f"\n{g['cells']} cells x {steps} steps ({args.duration:g} s simulated), one thread, {os.cpu_count()} cores")
    for name, (wall, cpu) in best.items():
        note = " (extrapolated from 2 s)" if name == "numpy" else ""
        print(
            f"  {name:9s} wall {wall:7.3f} s = {wall / updates * 1e9:7.3f} ns per cell update, "
            f"thread CPU {cpu:7.3f} s = {cpu / updates * 1e9:7.3f} ns{note}"
        )
    for k, kind in enumerate(("wall", "CPU")):
        ref = best["ds.drill"][k]
        numba, numpy = best["numba"][k] / ref, best["numpy"][k] / ref
        print(f"  {kind}: numba / ds.drill = {numba:.2f}, numpy / ds.drill = {numpy:.1f}")


if __name__ == "__main__":
    main()
