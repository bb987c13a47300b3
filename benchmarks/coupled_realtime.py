"""Real-time factor of a coupled axial-torsional run at a given cell count.

Runs ``ds.drill`` on a configuration (default: examples/aarsnes-van-de-wouw-2019.toml) with
``numerics.cells`` set (and any ``--set KEY=VALUE``, e.g. ``--set numerics.energy_balance=false``),
best of ``--repeat`` runs by the CPU time of the thread that runs the solve (one thread; the
process's CPU time, which also counts idle library threads, beside it), and prints the simulated
seconds per CPU second and the time per step and torsional cell.

    python benchmarks/coupled_realtime.py [--config PATH] [--cells 1000] [--repeat 3] [--set KEY=VALUE]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import drillstring as ds

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-van-de-wouw-2019.toml"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", type=Path, default=EXAMPLE)
    parser.add_argument("--cells", type=int, default=1000, help="numerics.cells (torsional)")
    parser.add_argument("--repeat", type=int, default=3, help="runs (the best is kept)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a configuration override")
    args = parser.parse_args()
    cfg = ds.load_drill_config(args.config).with_overrides([f"numerics.cells={args.cells}", *args.set])
    best, process = float("inf"), float("inf")
    for _ in range(args.repeat):
        start, start_process = time.thread_time(), time.process_time()
        res = ds.drill(cfg, progress=False)
        best = min(best, time.thread_time() - start)
        process = min(process, time.process_time() - start_process)
    assert res.success, res.message
    duration = cfg.numerics.duration
    cells, steps = res.stats["cells"], res.stats["steps"]
    name = args.config.name
    settings = f" ({', '.join(args.set)})" if args.set else ""
    print(f"{name}{settings}: {cells} torsional cells x {steps} steps, {duration:g} s simulated, "
          f"{os.cpu_count()} cores")
    print(
        f"  {best:.3f} s thread CPU (best of {args.repeat}; process CPU {process:.3f} s): "
        f"{duration / best:.0f}x real time, "
        f"{best / steps * 1e6:.2f} us per step, {best / (cells * steps) * 1e9:.2f} ns per torsional cell and step"
    )


if __name__ == "__main__":
    main()
