"""The crossing of one drilling run's result from the core to Python: the bindings' serializer
(``rust/python/src/convert.rs``, numeric sequences as numpy arrays) against pythonize (lists, and
numpy arrays made from them), on the same run of 60 s, best of 7; beside the solve's own time.

    cd benchmarks/crossing && cargo build --release && cp target/release/libresult_crossing.so \
        result_crossing.abi3.so && cd ../..
    PYTHONPATH=python:benchmarks/crossing python3 benchmarks/crossing_time.py
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np
import result_crossing

import drillstring as ds

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def best(f: Callable[[], Any], k: int = 7) -> float:
    times = []
    for _ in range(k):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def arrays(d: dict[str, Any]) -> dict[str, Any]:
    return {k: np.asarray(v, dtype=float) if isinstance(v, list) and v and isinstance(v[0], float) else v
            for k, v in d.items()}


def main() -> None:
    for name in ("on-bottom-3000m.toml", "aarsnes-van-de-wouw-2019.toml"):
        cfg = ds.load_drill_config(EXAMPLES / name).with_overrides(
            {"numerics.duration": 60.0, "metrics.window": [30.0, 60.0]})
        text = json.dumps(cfg.to_dict())
        solve = best(lambda text=text: result_crossing.solve(text), 3)
        numbers = sum(v.size for v in result_crossing.cross_today().values() if isinstance(v, np.ndarray))
        today = best(result_crossing.cross_today)
        pythonize = best(result_crossing.cross_pythonize)
        with_arrays = best(lambda: arrays(result_crossing.cross_pythonize()))
        print(f"{name}: {numbers} numbers in arrays; solve {solve * 1e3:.1f} ms; the bindings' serializer "
              f"{today * 1e3:.2f} ms, pythonize {pythonize * 1e3:.2f} ms (lists; as numpy arrays "
              f"{with_arrays * 1e3:.2f} ms)")


if __name__ == "__main__":
    main()
