"""What the cut-surface numerics, the damping rate and the regime thresholds of Aarsnes & van de Wouw's code
change: variants of ``avdw_numpy.simulate`` at 30 rpm, 30 and 60 m/h, to ``--t1`` seconds.

    python benchmarks/avdw_study.py [--t1 120] [--jobs 2] [--json OUT.json]

Variants (each changes the published scheme only where named):

* ``published``: their scheme (upwind cut surface on Pl = 169 cells, damping 2k, thresholds);
* ``upwind338`` ... ``upwind1352``: their physics, the upwind chain on 2, 4, 8 times the cells at their
  Courant number (sub-cycled);
* ``delay``: their physics with the exact delay driven by the same last-cell speeds;
* ``delay_set_valued``: the exact delay, the set-valued bit law and the bit face's speeds (damping 2k);
* ``converged``: that with the damping at its named rate k (``avdw_numpy.CONVERGED``).

Per run: the metrics of the last 5 s (``avdw_numpy.metrics``), the torsional stick fraction after the
start-up (t >= 5 s), and the rms difference of the depth of cut per revolution from the ``delay`` run
over the whole run (convergence of the cut surface).
"""

from __future__ import annotations

import argparse
import json
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace

import avdw_numpy as an
import numpy as np

VARIANTS: dict[str, an.Scheme] = {
    "published": an.PUBLISHED,
    "upwind338": replace(an.PUBLISHED, cut_cells=338),
    "upwind676": replace(an.PUBLISHED, cut_cells=676),
    "upwind1352": replace(an.PUBLISHED, cut_cells=1352),
    "delay": replace(an.PUBLISHED, cut_surface="delay"),
    "delay_set_valued": replace(an.CONVERGED, damping=2.0),
    "converged": an.CONVERGED,
}


def run(args: tuple[str, float, float, float]) -> tuple[str, float, dict, np.ndarray, np.ndarray]:
    name, rpm, rop, t1 = args
    t0 = time.perf_counter()
    res = an.simulate(rpm, rop, t1, VARIANTS[name])
    m = an.metrics(res, rpm, rop, (t1 - 5.0, t1))
    m["early"] = an.metrics(res, rpm, rop, (20.0, 25.0))
    m["stuck_fraction_after_5s"] = float(res["last_stuck"][res["t_end_s"] > 5.0].mean())
    m["wall_s"] = time.perf_counter() - t0
    return name, rop, m, res["depth_of_cut_m"], res["t_end_s"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--t1", type=float, default=120.0)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json", default=None)
    ap.add_argument("--rops", default="30,60")
    a = ap.parse_args()
    jobs = [(name, 30.0, float(rop), a.t1) for rop in a.rops.split(",") for name in VARIANTS]
    with ProcessPoolExecutor(a.jobs) as pool:
        done = list(pool.map(run, jobs))
    table: dict = {}
    for name, rop, m, d, _t in done:
        ref = next(dd for n2, r2, _, dd, _ in done if n2 == "delay" and r2 == rop)
        m["depth_of_cut_rms_vs_delay_m"] = float(np.sqrt(np.mean((d - ref) ** 2)))
        m["depth_of_cut_rms_vs_delay_last5s_m"] = float(np.sqrt(np.mean((d[-1667:] - ref[-1667:]) ** 2)))
        table[f"rpm30_rop{rop:g}.{name}"] = m
    cols = ("rop_mean_m_per_h", "bit_rpm_min", "bit_rpm_max", "bit_axial_speed_min_m_s", "bit_axial_speed_max_m_s",
            "wob_min_N", "wob_max_N", "depth_of_cut_mean_m", "stuck_fraction", "stuck_fraction_after_5s",
            "contact_regime_fraction", "settled", "wob_peak_frequency_hz", "depth_of_cut_rms_vs_delay_m")
    print("| run | " + " | ".join(cols) + " |")
    for key, m in table.items():
        print(f"| {key} | " + " | ".join(f"{m[c]:.5g}" if isinstance(m[c], float) else str(m[c]) for c in cols) + " |")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(table, fh, indent=1)


if __name__ == "__main__":
    main()
