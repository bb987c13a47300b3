"""drillstring (DOP853, RKN12) vs scipy.integrate.solve_ivp(method="DOP853") on the 3-mode reference case.

Table 1 parameters, C = (0.1, 0.05, 0.02), 0 <= t <= 1, rtol = 1e-12 and atol = 1e-12 (or
``--atol``), ``--samples`` uniform output times (default 20001). scipy gets the fastest numpy
right-hand side we found for it (``_scipy_rhs.py``: M^-1 K precomputed, the quartic terms folded
into a dense matrix over the cubic monomials). Times are the best of several repeats; the
speed-up is scipy time / drillstring time.

Accuracy: every solution is compared at all output times with a converged reference,
drillstring's RKN12 at rtol = 1e-15, atol = 1e-22 (the core's own limit is below the 2.2e-14
that ``simulate`` allows); its distance to drillstring's DOP853 at the same tolerances is
printed too: the reference is good to about that distance, which must be far below the errors
it measures. Errors are max |q - q_ref| over all modes and samples, relative to max |q_ref|,
and the same for qdot.

Each solve also gets its floor: nfev x the measured cost of one right-hand-side evaluation, and
the ratio total / floor (how much of the solve is not spent evaluating the right-hand side).
scipy's evaluation is its numpy rhs called from Python (best per-call time in a loop).
drillstring's is timed inside the Rust solver: a fixed-step RK4 solve of the
same modal system minus the same solve of a same-size system without quartic terms, per
evaluation (``_evalcost.py``): a lower bound of the evaluation cost. drillstring's total is the
core solve (``_core.solve_modal`` on a prepared system, what the floor compares with) and,
separately, the whole ``ds.simulate`` call (projection, validation and result included): the
best of the repeats, and the mean of 50 calls in a row (what a loop of simulations pays,
memory effects included).

The output path: each method's core solve is also timed with 11 output samples (the integration
alone: the same steps, nine interpolated samples) and with ``--samples``; their difference is what
the samples cost (for DOP853 the three extra stages of its dense output in every step that holds a
sample, building and evaluating the interpolant, storing the values; the values reach numpy
without a copy), printed per output value next to one copy of the output array (``np.copyto``
of its samples x 2m values) and as a share of the integration alone.

A last row times RKN12 at scipy's achieved accuracy: the loosest tolerance of a grid at which
both its errors are at most scipy's (scipy's DOP853 misses the requested 1e-12 by far more).

``--crossover`` instead prints, for rtol from 1e-4 to 1e-13, the evaluations and core solve
times of DOP853 and RKN12 (the measurement behind ``_core.AUTO_RKN12_MAX_RTOL``).

``--timeline N`` instead times N RKN12 core solves in a row and prints the median of each of 30
consecutive slices, then the minimum and median of all: how steady the machine is. On a shared
virtual machine the same call can run in phases of seconds whose times differ by 1.5x or more,
which is why the table quotes the best of several repeats.

    python benchmarks/compare_scipy.py [--repeat 5] [--samples 20001] [--atol 1e-12]
                                       [--method dop853 rkn12] [--crossover] [--timeline N]
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from typing import Any, Callable

# One BLAS thread: after numpy's first linear-algebra call its idle BLAS threads spin and compete
# with the timed solves for the two cores (the times then swing by up to 2x). Set before numpy
# loads; an explicit OPENBLAS_NUM_THREADS wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from _evalcost import evaluation_cost, per_call_time
from _scipy_rhs import modal_rhs
from scipy.integrate import solve_ivp

import drillstring as ds
from drillstring import _core

RTOL = 1e-12
# Tolerances tried for the row at scipy's accuracy (``matched_accuracy``).
MATCH_GRID = (1e-12, 2e-12, 5e-12, 1e-11, 2e-11, 3e-11, 5e-11, 1e-10, 2e-10)
REFERENCE = (1e-15, 1e-22)


def at_least(low: int) -> Callable[[str], int]:
    """An argparse type: a whole number >= ``low`` (else a one-line usage error naming the range)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number (allowed: >= {low})") from None
        if value < low:
            raise argparse.ArgumentTypeError(f"{value} is out of range (allowed: >= {low})")
        return value

    return parse


def best_of(repeat: int, fn: Callable[[], Any]) -> tuple[float, Any]:
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def errors(y: np.ndarray, ref: np.ndarray, m: int) -> tuple[float, float]:
    """Relative max errors of q and qdot, ``y`` and ``ref`` of shape (samples, 2m)."""
    eq = np.abs(y[:, :m] - ref[:, :m]).max() / np.abs(ref[:, :m]).max()
    ev = np.abs(y[:, m:] - ref[:, m:]).max() / np.abs(ref[:, m:]).max()
    return float(eq), float(ev)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=at_least(1), default=5)
    parser.add_argument("--samples", type=at_least(2), default=20001)
    parser.add_argument("--atol", type=float, default=1e-12)
    parser.add_argument("--method", nargs="+", default=["dop853", "rkn12"], choices=["dop853", "dopri5", "rkn12"])
    parser.add_argument("--crossover", action="store_true")
    parser.add_argument("--timeline", type=at_least(1), default=None, metavar="N")
    args = parser.parse_args()

    params = ds.preset("aluminum")
    t_eval = np.linspace(0.0, 1.0, args.samples)
    coeff = ds.model.galerkin.project(params, modes=3)
    q0, v0 = coeff.initial_state(params)
    m = len(coeff.indices)
    system = coeff.core_system(0.0, "auto")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"numpy {np.__version__}, python {platform.python_version()}, core kernels {ds.simd_path()}")

    def core(method: str, rtol: float, atol: float, times: np.ndarray = t_eval) -> dict[str, Any]:
        return _core.solve_modal(system, q0, v0, 1.0, times, method, rtol, atol)

    if args.crossover:
        crossover(core, args.repeat)
        return
    if args.timeline is not None:
        timeline(core, args.timeline, args.atol)
        return

    rhs = modal_rhs(coeff)

    ref_rkn, ref_dop = core("rkn12", *REFERENCE), core("dop853", *REFERENCE)
    assert ref_rkn["status"] == ref_dop["status"] == "success"
    ref = ref_rkn["y"]
    agree = errors(ref_dop["y"], ref, m)

    y0 = np.concatenate([q0, v0])
    t_scipy, sp = best_of(
        max(1, args.repeat // 2),
        lambda: solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", t_eval=t_eval, rtol=RTOL, atol=args.atol),
    )
    y_mid = sp.y[:, sp.y.shape[1] // 2].copy()
    cost_sp = per_call_time(lambda: rhs(0.5, y_mid))
    cost_ds, timed = evaluation_cost(system, q0, v0, 1e-4)

    print(f"case: 3 modes, Table 1, C = (0.1, 0.05, 0.02), 0 <= t <= 1, rtol = {RTOL:g}, atol = {args.atol:g}, "
          f"{args.samples} output samples")
    print(f"reference: drillstring rkn12 at rtol = {REFERENCE[0]:g}, atol = {REFERENCE[1]:g} "
          f"({ref_rkn['nfev']} evaluations); drillstring dop853 at the same tolerances differs from it by "
          f"{agree[0]:.1e} (q), {agree[1]:.1e} (qdot), relative to max |q|, max |qdot|")
    print("floor = nfev x cost of one rhs evaluation (measured in this run): "
          f"scipy {cost_sp * 1e6:.3f} us/eval, drillstring {cost_ds * 1e9:.1f} ns/eval")
    print(f"  (drillstring's cost: RK4 solve of this system minus that of a {m}-coordinate system without "
          f"quartic terms, {timed} evaluations each, best of 5)")
    header = (f"{'solver':<24}{'total ms':>10}{'nfev':>8}{'steps':>7}{'err q':>10}{'err qdot':>10}"
              f"{'floor ms':>10}{'total/floor':>12}{'vs scipy':>10}")
    print(header)
    eq_sp, ev_sp = eq, ev = errors(sp.y.T, ref, m)
    floor = sp.nfev * cost_sp
    print(f"{'scipy DOP853':<24}{t_scipy * 1e3:10.2f}{sp.nfev:8d}{'':>7}{eq:10.1e}{ev:10.1e}"
          f"{floor * 1e3:10.3f}{t_scipy / floor:12.2f}{1:10.0f}x")
    for method in args.method:
        t_core, out = best_of(args.repeat, lambda m=method: core(m, RTOL, args.atol))
        t_sim, res = best_of(
            args.repeat,
            lambda m=method: ds.simulate(params, modes=3, t_eval=t_eval, method=m, rtol=RTOL, atol=args.atol),
        )
        assert out["status"] == "success" and res.stats.nfev == out["nfev"]
        eq, ev = errors(out["y"], ref, m)
        floor = out["nfev"] * cost_ds
        ratio = f"{t_core / floor:12.2f}" if floor > 0 else f"{'n/a':>12}"
        print(f"{'drillstring ' + method:<24}{t_core * 1e3:10.3f}{out['nfev']:8d}{out['naccept']:7d}{eq:10.1e}"
              f"{ev:10.1e}{floor * 1e3:10.3f}{ratio}{t_scipy / t_core:10.0f}x")
        print(f"{'  (whole ds.simulate)':<24}{t_sim * 1e3:10.3f}{'':>8}{'':>7}{'':>10}{'':>10}{'':>10}"
              f"{'':>12}{t_scipy / t_sim:10.0f}x")
        output_path(core, method, out, args)
        start, calls = time.perf_counter(), 50
        for _ in range(calls):
            ds.simulate(params, modes=3, t_eval=t_eval, method=method, rtol=RTOL, atol=args.atol)
        t_loop = (time.perf_counter() - start) / calls
        print(f"{'  (50 calls in a row)':<24}{t_loop * 1e3:10.3f}{'':>8}{'':>7}{'':>10}{'':>10}{'':>10}"
              f"{'':>12}{t_scipy / t_loop:10.0f}x")
    if "rkn12" in args.method:
        matched_accuracy(core, ref, m, (eq_sp, ev_sp), t_scipy, cost_ds, args)


def output_path(core: Callable[..., dict[str, Any]], method: str, out: dict[str, Any],
                args: argparse.Namespace) -> None:
    """Prints what the output samples cost: the core solve with ``--samples`` output times minus
    the same solve with 11, per output value, against one memory copy per value."""
    few = np.linspace(0.0, 1.0, 11)
    t_many, _ = best_of(args.repeat * 4, lambda: core(method, RTOL, args.atol))
    t_few, alone = best_of(args.repeat * 4, lambda: core(method, RTOL, args.atol, few))
    y = np.asarray(out["y"])
    target = np.empty_like(y)
    t_copy, _ = best_of(args.repeat * 4, lambda: np.copyto(target, y))
    values = y.size
    overhead = t_many - t_few
    print(f"{'  (output path)':<24}integration alone (11 samples, {alone['nfev']} evaluations) {t_few * 1e3:.3f} ms; "
          f"{y.shape[0]} samples add {overhead * 1e3:.3f} ms = {overhead / values * 1e9:.1f} ns per value "
          f"({overhead / t_few:.0%} of the integration; one copy of the values {t_copy / values * 1e9:.2f} ns "
          f"per value, {t_copy * 1e3:.3f} ms); total / (integration + one copy) "
          f"{t_many / (t_few + t_copy):.2f}")


def matched_accuracy(
    core: Callable[[str, float, float], dict[str, Any]],
    ref: np.ndarray,
    m: int,
    scipy_errors: tuple[float, float],
    t_scipy: float,
    cost_ds: float,
    args: argparse.Namespace,
) -> None:
    """RKN12 at the loosest tolerance of ``MATCH_GRID`` whose errors in q and qdot are both at
    most scipy's (atol scaled with rtol): the comparison at equal achieved accuracy. scipy's
    DOP853 misses its tolerance by far more than RKN12 does, so at equal rtol drillstring
    delivers a more accurate answer than scipy's and this row compares like with like."""
    chosen = None
    for rtol in MATCH_GRID:
        out = core("rkn12", rtol, args.atol * rtol / RTOL)
        eq, ev = errors(out["y"], ref, m)
        if out["status"] == "success" and eq <= scipy_errors[0] and ev <= scipy_errors[1]:
            chosen = (rtol, out, eq, ev)
    if chosen is None:
        print(f"drillstring rkn12: no rtol in {MATCH_GRID} reaches scipy's accuracy")
        return
    rtol, out, eq, ev = chosen
    atol = args.atol * rtol / RTOL
    t_core, out = best_of(args.repeat, lambda: core("rkn12", rtol, atol))
    floor = out["nfev"] * cost_ds
    ratio = f"{t_core / floor:12.2f}" if floor > 0 else f"{'n/a':>12}"
    print(f"at scipy's accuracy: the loosest rtol of {MATCH_GRID} with both errors at most scipy's")
    print(f"{'drillstring rkn12':<24}{t_core * 1e3:10.3f}{out['nfev']:8d}{out['naccept']:7d}{eq:10.1e}"
          f"{ev:10.1e}{floor * 1e3:10.3f}{ratio}{t_scipy / t_core:10.0f}x")
    print(f"  (rtol = {rtol:g}, atol = {atol:g})")


def crossover(core: Callable[[str, float, float], dict[str, Any]], repeat: int) -> None:
    """Evaluations, core solve times and errors of DOP853 and RKN12 over rtol (atol = rtol * 1e-5);
    the errors are those of q against the converged reference, relative to max |q|."""
    ref = core("rkn12", *REFERENCE)["y"]
    m = ref.shape[1] // 2
    print("crossover: core solves, 20001-style output of the command line, atol = 1e-5 rtol")
    print(f"{'rtol':>8}{'dop853 nfev':>13}{'rkn12 nfev':>12}{'dop853 ms':>11}{'rkn12 ms':>10}{'dop/rkn time':>14}"
          f"{'dop853 err q':>14}{'rkn12 err q':>13}")
    for rtol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]:
        atol = rtol * 1e-5
        t_dop, dop = best_of(repeat, lambda r=rtol, a=atol: core("dop853", r, a))
        t_rkn, rkn = best_of(repeat, lambda r=rtol, a=atol: core("rkn12", r, a))
        print(f"{rtol:8.0e}{dop['nfev']:13d}{rkn['nfev']:12d}{t_dop * 1e3:11.3f}{t_rkn * 1e3:10.3f}"
              f"{t_dop / t_rkn:14.2f}{errors(dop['y'], ref, m)[0]:14.1e}{errors(rkn['y'], ref, m)[0]:13.1e}")


def timeline(core: Callable[[str, float, float], dict[str, Any]], calls: int, atol: float) -> None:
    """Times ``calls`` RKN12 core solves in a row; prints the medians of 30 consecutive slices."""
    times = np.empty(calls)
    for i in range(calls):
        start = time.perf_counter()
        core("rkn12", RTOL, atol)
        times[i] = time.perf_counter() - start
    slices = np.array_split(times, min(30, calls))
    print(f"timeline: {calls} rkn12 core solves in a row, median ms of {len(slices)} consecutive slices:")
    print(" ".join(f"{np.median(part) * 1e3:.3f}" for part in slices))
    print(f"all: min {times.min() * 1e3:.3f} ms, median {np.median(times) * 1e3:.3f} ms, "
          f"max {times.max() * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
