"""Solver speed of extension builds made with different release profiles.

Build each profile into its own target directory first, e.g.::

    for v in "fat 1" "thin 16" "false 16"; do set -- $v
      CARGO_TARGET_DIR=/tmp/bp-$1-$2 CARGO_PROFILE_RELEASE_LTO=$1 CARGO_PROFILE_RELEASE_CODEGEN_UNITS=$2 \\
        /usr/bin/time cargo build --release -p drillstring-python
    done
    python benchmarks/build_profiles.py fat-1=/tmp/bp-fat-1/release/lib_core.so \\
        thin-16=/tmp/bp-thin-16/release/lib_core.so false-16=/tmp/bp-false-16/release/lib_core.so

Each build is copied beside a copy of ``python/drillstring`` and timed in its own process, the
builds interleaved (so that a loaded machine slows them alike), one thread each; the best of
``--repeat`` rounds of three calls is printed. Results: benchmarks/README.md, "Build profiles".
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CHILD = r"""
import sys, time
import drillstring as ds
cfg = ds.load_drill_config(sys.argv[1]).with_overrides(["numerics.cells=1000"])
p = ds.Parameters()
def best(f):
    b = float("inf")
    for _ in range(3):
        t = time.perf_counter(); f(); b = min(b, time.perf_counter() - t)
    return b
print(best(lambda: ds.drill(cfg, progress=False)), best(lambda: ds.simulate(p, modes=8, t_end=5.0)))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("builds", nargs="+", help="LABEL=PATH of a built lib_core.so")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    builds = dict(b.split("=", 1) for b in args.builds)
    times: dict[str, list[tuple[float, float]]] = {label: [] for label in builds}
    with tempfile.TemporaryDirectory() as tmp:
        for label, so in builds.items():
            shutil.copytree(ROOT / "python", Path(tmp) / label)
            shutil.copy(so, Path(tmp) / label / "drillstring" / "_core.abi3.so")
        case = str(ROOT / "examples" / "aarsnes-shor-well-b-corrected.toml")
        for _ in range(args.repeat):
            for label in builds:
                env = {**os.environ, "PYTHONPATH": str(Path(tmp) / label), "RAYON_NUM_THREADS": "1"}
                out = subprocess.run([sys.executable, "-c", CHILD, case], env=env, capture_output=True,
                                     text=True, cwd=tmp, check=True)
                a, b = map(float, out.stdout.split())
                times[label].append((a, b))
    print(f"{os.cpu_count()} cores; best of {args.repeat} x 3 calls, one thread")
    for label, rows in times.items():
        print(f"{label}: ds.drill corrected Well B 1000 cells 60 s {1e3 * min(r[0] for r in rows):.1f} ms; "
              f"ds.simulate 8 modes 5 s {1e3 * min(r[1] for r in rows):.1f} ms")


if __name__ == "__main__":
    main()
