"""Speed of the static soft-string torque and drag on the 4000 m 3-D S well of
``examples/s-well-3d.toml`` (135 survey stations, elements of at most 1 m: 4132 nodes).

Timed in the same run: the core's four operations (pick-up, slack-off, rotating off and on
bottom) with a broomstick of 2 depths; the core's broomstick over 400 bit depths (pick-up,
slack-off and rotating at each, one friction factor); and the tool a user would otherwise pick,
welleng 0.30.0's ``TorqueDrag`` on the same survey interpolated to 1 m stations (four operations
on 4001 stations), if welleng is installed (``pip install welleng==0.30.0``), else a plain
Python loop of the same stepped equations (the baseline any script would be). Targets: the
four operations in under 10 ms and the 400-depth broomstick in under a second.

Also timed: the whole report (five operations, the limits, the broomstick of 100 bit depths at
four friction factors) of the 10,000 ft directional well of
``examples/directional-10000ft-td-field.toml``, with its hole (buckling: the critical loads of
every element) and with the hole removed, and the implied friction factors of its 12 measured
points (``examples/directional-10000ft-measured.csv``).

    python benchmarks/torque_drag.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np

import drillstring as ds
from drillstring import _core

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "s-well-3d.toml"
DIRECTIONAL = ROOT / "examples" / "directional-10000ft-td-field.toml"
MEASURED = ROOT / "examples" / "directional-10000ft-measured.csv"


def best(fn: Callable[[], Any], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def python_loop(survey: dict[str, np.ndarray], cfg: Any) -> float:
    """The stepped pick-up tension of the string in a plain Python loop (the baseline without
    welleng): directions by linear interpolation of inclination and azimuth at 1 m nodes (the
    cost, not the accuracy, is what is measured)."""
    md = np.arange(0.0, cfg.length + 0.5, 1.0)
    inc = np.radians(np.interp(md, survey["md"], survey["inc_deg"]))
    azi = np.radians(np.interp(md, survey["md"], survey["azi_deg"]))
    t = np.stack([np.sin(inc) * np.cos(azi), np.sin(inc) * np.sin(azi), np.cos(inc)], axis=1).tolist()
    tops = np.cumsum([0.0] + [s.length for s in cfg.sections])
    weights = [(s.density - cfg.well.mud_density) * cfg.well.gravity * math.pi / 4
               * (s.outer_diameter**2 - s.inner_diameter**2) for s in cfg.sections]
    tension = 0.0
    for j in range(len(md) - 2, -1, -1):
        mid = 0.5 * (md[j] + md[j + 1])
        w = weights[min(int(np.searchsorted(tops, mid, side="right")) - 1, len(weights) - 1)] * (md[j + 1] - md[j])
        ta, tb = t[j], t[j + 1]
        m = [ta[k] + tb[k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in m))
        m = [x / n for x in m]
        v = [tension * (tb[k] - ta[k]) - w * m[2] * m[k] + (w if k == 2 else 0.0) for k in range(3)]
        tension += w * m[2] + 0.3 * math.sqrt(sum(x * x for x in v))
    return tension


def directional(repeat: int) -> dict[str, float]:
    """The directional well's report with and without its hole, and its measured points, ms."""
    from drillstring.calibration.td_measured import implied_friction, read_td_measured

    cfg = ds.load_drill_config(DIRECTIONAL)
    with_hole = cfg.to_json()
    doc = json.loads(with_hole)
    doc["well"]["hole_diameter"], doc["well"]["hole_sections"] = None, []
    without = json.dumps(doc)
    points = read_td_measured(MEASURED)
    times = {"directional_report_hole_ms": 1e3 * best(lambda: _core.well_torque_drag(with_hole), repeat),
             "directional_report_no_hole_ms": 1e3 * best(lambda: _core.well_torque_drag(without), repeat),
             "directional_measured_12_ms": 1e3 * best(lambda: implied_friction(cfg, points), repeat)}
    print(f"core, directional report with its hole: {times['directional_report_hole_ms']:8.2f} ms")
    print(f"core, the same without the hole:        {times['directional_report_no_hole_ms']:8.2f} ms")
    print(f"core, its 12 measured points' factors:  {times['directional_measured_12_ms']:8.2f} ms")
    return times


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    cfg = ds.load_drill_config(EXAMPLE)
    four = cfg.with_overrides(["torque_drag.broomstick_points=2", "torque_drag.friction_factors=[0.3]"]).to_json()
    broom = cfg.with_overrides(["torque_drag.broomstick_points=400", "torque_drag.friction_factors=[0.3]"]).to_json()
    print(f"machine: {os.cpu_count()} cores; drillstring {ds.__version__}, SIMD {ds.simd_path()}")
    t_four = best(lambda: _core.well_torque_drag(four), args.repeat)
    t_broom = best(lambda: _core.well_torque_drag(broom), args.repeat) - t_four
    print(f"core, four operations (4132 nodes):      {1e3 * t_four:8.2f} ms  (target < 10 ms)")
    print(f"core, broomstick of 400 bit depths:     {1e3 * t_broom:8.2f} ms  (target < 1000 ms)")
    extra = directional(args.repeat)
    survey = _core.well_trajectory(four)
    try:
        import welleng  # noqa: F401
    except ImportError:
        t_py = best(lambda: python_loop(survey, cfg), args.repeat)
        print(f"plain Python loop, pick-up only:        {1e3 * t_py:8.2f} ms  "
              f"(core four operations {t_py / t_four:.0f}x faster; welleng not installed)")
        return
    import importlib.util

    # welleng's TorqueDrag set up exactly as the reference numbers were computed
    spec = importlib.util.spec_from_file_location("welleng_reference",
                                                  ROOT / "tests" / "reference" / "welleng" / "welleng_reference.py")
    assert spec is not None and spec.loader is not None
    ref = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ref)
    md_st, inc_st, azi_st = ref.read_survey(str(ROOT / "examples" / "s-well-3d-survey.csv"))
    dense = ref.make_survey(md_st, inc_st, azi_st).interpolate_mds(np.arange(0.0, ref.BIT_MD + 0.5, 1.0))
    bha = ref.make_bha(ref.SECTIONS, ref.BIT_MD)
    wb = ref.make_wellbore([(ref.SHOE_MD, ref.MU_CASED), (ref.BIT_MD, ref.MU_OPEN)], ref.BIT_MD)
    t_w = best(lambda: ref.run_welleng(dense, bha, wb, ref.TorqueDrag), args.repeat)
    print(f"welleng 0.30.0, four operations:        {1e3 * t_w:8.2f} ms  (core {t_w / t_four:.0f}x faster)")
    print(json.dumps({"core_four_ms": 1e3 * t_four, "core_broomstick_400_ms": 1e3 * t_broom,
                      "welleng_four_ms": 1e3 * t_w, **extra}))


if __name__ == "__main__":
    main()
