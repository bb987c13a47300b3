"""How long the command line takes to answer: ``import drillstring`` and ``drillstring drill
examples/on-bottom-3000m.toml --out DIR`` with its figures, each in a fresh interpreter.

Each case runs ``--repeat`` times (default 5); printed are the best wall time and the CPU time
(user + system, the process and everything it forked) of that run, and the median wall time, next
to the bare interpreter (``python -c pass``). On a machine shared with other work the wall time
grows with the load (printed: the load average before and after) while the CPU time stays; the
drill command draws its figures in a forked process beside the data files on more than one core,
so there its wall time can be below its CPU time. ``--pythonpath DIR`` measures the package in
``DIR`` (another checkout) instead of the one this script belongs to.

    python benchmarks/cli_latency.py [--repeat 5] [--pythonpath DIR] [--no-drill]
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"


def processor() -> str:
    """The processor's model name (``lscpu``'s, else ``platform.processor()``)."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as handle:
            for line in handle:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def timed(command: list[str], env: dict[str, str], repeat: int, before: object = None) -> tuple[float, float, float]:
    """(best wall, CPU of that run, median wall) of ``repeat`` runs of ``command``, in seconds;
    ``before()`` runs before each (not timed)."""
    walls, cpus = [], []
    for _ in range(repeat):
        if callable(before):
            before()
        start_cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, env=env, check=True, stdout=subprocess.DEVNULL)
        walls.append(time.perf_counter() - start)
        end_cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append((end_cpu.ru_utime - start_cpu.ru_utime) + (end_cpu.ru_stime - start_cpu.ru_stime))
    best = min(range(repeat), key=walls.__getitem__)
    return walls[best], cpus[best], statistics.median(walls)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=5, help="runs of each case (default 5)")
    parser.add_argument("--pythonpath", default=str(ROOT / "python"),
                        help="the package's folder (default: this checkout's)")
    parser.add_argument("--no-drill", action="store_true", help="time the imports only")
    args = parser.parse_args()
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat} is out of range (allowed: >= 1)")
    env = dict(os.environ, PYTHONPATH=args.pythonpath, OPENBLAS_NUM_THREADS="1")
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    print(f"machine: {processor()}, {cores} cores, python {platform.python_version()}, package {args.pythonpath}")
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"{'case':<52}{'best wall s':>12}{'its CPU s':>11}{'median wall s':>15}")
    python = [sys.executable]
    cases = [("python -c pass", python + ["-c", "pass"], None),
             ("python -c 'import drillstring'", python + ["-c", "import drillstring"], None)]
    folder = Path(tempfile.mkdtemp(prefix="drillstring-cli-latency-"))
    try:
        if not args.no_drill:
            out = folder / "run"
            cases.append(("drillstring drill examples/on-bottom-3000m.toml --out D",
                          python + ["-m", "drillstring", "drill", str(EXAMPLE), "--out", str(out), "--no-progress"],
                          lambda: shutil.rmtree(out, ignore_errors=True)))
        for name, command, before in cases:
            best, cpu, median = timed(command, env, args.repeat, before)
            print(f"{name:<52}{best:12.3f}{cpu:11.3f}{median:15.3f}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
