"""Stick-slip map throughput: a ``--rpm`` x ``--mu`` map (default 20 x 20 = 400 runs) of the
Aarsnes-Shor Well B example (``examples/aarsnes-shor-well-b.toml``: 2500 m, 1000 cells, 60 s,
PI control), setpoint rpm x static wall-friction coefficient, solved by
:func:`drillstring.drilling.drill_map` on 1 and on 2 threads (``--threads``). Reports the wall
time, the runs per second, the CPU seconds the machine used meanwhile (the machine may be
shared), the core count and the build profile of the extension (a dev build is several times
slower than ``pip install .``). Both maps are checked equal (one code path, any thread count).

    python benchmarks/drill_map.py [--rpm 20] [--mu 20] [--duration 60] [--cells 1000] [--threads 1 2]
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from pathlib import Path

import numpy as np

import drillstring as ds
from drillstring.drilling import drill_map, load_drill_config

ROOT = Path(__file__).resolve().parents[1]


def machine_cpu() -> float:
    """CPU seconds used by every process so far, from /proc/stat (0 where it does not exist)."""
    try:
        with open("/proc/stat") as handle:
            fields = [int(v) for v in handle.readline().split()[1:9]]
    except OSError:
        return 0.0
    user, nice, system, _idle, _iowait, irq, softirq, _steal = fields
    return (user + nice + system + irq + softirq) / os.sysconf("SC_CLK_TCK")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rpm", type=int, default=20, help="setpoint values, 20..200 rpm")
    parser.add_argument("--mu", type=int, default=20, help="static friction values, 0.1..0.5")
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--cells", type=int, default=1000)
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--config", default=str(ROOT / "examples" / "aarsnes-shor-well-b.toml"))
    args = parser.parse_args()

    cfg = load_drill_config(args.config).with_overrides(
        [f"numerics.duration={args.duration}", f"numerics.cells={args.cells}"])
    axes = {"top_drive.rpm": list(np.linspace(20.0, 200.0, args.rpm)),
            "friction.static": list(np.linspace(0.1, 0.5, args.mu))}
    runs = args.rpm * args.mu
    print(f"drillstring {ds.__version__}, {platform.machine()}, os.cpu_count() = {os.cpu_count()}, "
          f"sched_getaffinity = {len(os.sched_getaffinity(0)) if hasattr(os, 'sched_getaffinity') else '?'}, "
          f"SIMD {ds._core.simd_path()}")
    print(f"map: {args.rpm} x {args.mu} = {runs} runs of {args.duration:g} s at {cfg.numerics.cells} cells "
          f"({args.config})")
    frames = []
    for threads in args.threads:
        cpu0, t0 = machine_cpu(), time.perf_counter()
        frame = drill_map(cfg, axes, threads=threads)
        wall, cpu = time.perf_counter() - t0, machine_cpu() - cpu0
        frames.append(frame)
        ok = int((frame["status"] == "success").sum())
        print(f"threads {threads}: {wall:.2f} s wall, {runs / wall:.1f} runs/s, machine CPU {cpu:.1f} s "
              f"({cpu / wall:.2f} cores busy), {ok}/{runs} successful, SSI {frame['ssi'].min():.3g}.."
              f"{frame['ssi'].max():.3g}, stick-slip (SSI >= 1) in {int((frame['ssi'] >= 1).sum())} runs")
    for other in frames[1:]:
        assert frames[0].drop(columns="message").equals(other.drop(columns="message")), "maps differ by thread count"


if __name__ == "__main__":
    main()
