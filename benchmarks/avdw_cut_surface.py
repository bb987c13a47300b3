"""The numbers of the drilling guide's coupled section on Aarsnes & van de Wouw's case: the upwind cut surface
against the exact delay as its cells grow, and their linear torsional condition against the onset of stick-slip
in the engine's runs (``ds.drill`` of ``examples/aarsnes-van-de-wouw-2019-converged.toml``, 180-240 s).

    python benchmarks/avdw_cut_surface.py convergence [--cells 169,338,676,1352,2704,5408] [--rops 30,60]
    python benchmarks/avdw_cut_surface.py onset-rpm [--rop 30] [--rpms 30,45,60,75,90,100,110,120,150]
    python benchmarks/avdw_cut_surface.py onset-rop --rpm 60 [--rops 10,20,30,45,60,80,90,100,120]

Per run: mean WOB (kN) and its range, mean TOB (kN m), MSE (MPa), the bit's speed range (rpm), the share of the
window the bit is at rest (stuck), the energy ledger's relative residual; for the onset sweeps their loop gains
M_T and M_A (``drillstring.drilling.coupled_stability``).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from drillstring.drilling import drill, load_drill_config
from drillstring.drilling.coupled_stability import regenerative_loop_gains

CONVERGED = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-van-de-wouw-2019-converged.toml"


def row(overrides: dict, gains: bool) -> str:
    cfg = load_drill_config(CONVERGED).with_overrides(overrides)
    r = drill(cfg)
    late = r.t >= 180.0
    wob, rpm = r.axial["weight_on_bit"][late] / 1e3, r.bit_rpm[late]
    m = r.coupled_metrics or {}
    cells = [f"{m.get('wob_mean_N', float('nan')) / 1e3:.2f} [{wob.min():.2f}, {wob.max():.2f}]",
             f"{m.get('tob_mean_Nm', float('nan')) / 1e3:.3f}", f"{m.get('mse_mean_Pa', float('nan')) / 1e6:.2f}",
             f"[{rpm.min():.2f}, {rpm.max():.2f}]", f"{r.metrics.stuck_fraction:.4f}",
             f"{r.energy['balance_error']:.1e}"]
    if gains:
        g = regenerative_loop_gains(cfg)
        cells = [f"{g.torsional:.3f}", f"{g.axial:.3f}", *cells]
    return " | ".join(cells)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=("convergence", "onset-rpm", "onset-rop"))
    ap.add_argument("--cells", default="169,338,676,1352,2704,5408")
    ap.add_argument("--rops", default=None)
    ap.add_argument("--rop", type=float, default=30.0)
    ap.add_argument("--rpm", type=float, default=60.0)
    ap.add_argument("--rpms", default="30,45,60,75,90,100,110,120,150")
    a = ap.parse_args()
    head = "WOB kN mean [min, max] | TOB kN m | MSE MPa | bit rpm [min, max] | stuck | energy residual"
    if a.what == "convergence":
        print(f"| ROP m/h | cut surface | {head} |")
        for rop in (float(x) for x in (a.rops or "30,60").split(",")):
            base = {"hoist.speed": rop / 3600}
            for cells in [None, *(int(x) for x in a.cells.split(","))]:
                o = dict(base) if cells is None else {**base, "bit.detournay.cut_surface": "upwind",
                                                      "bit.detournay.cut_surface_cells": cells}
                print(f"| {rop:g} | {'exact delay' if cells is None else f'upwind {cells}'} | {row(o, False)} |",
                      flush=True)
    elif a.what == "onset-rpm":
        print(f"| rpm | M_T | M_A | {head} |")
        for rpm in (float(x) for x in a.rpms.split(",")):
            print(f"| {rpm:g} | {row({'top_drive.rpm': rpm, 'hoist.speed': a.rop / 3600}, True)} |", flush=True)
    else:
        print(f"| ROP m/h | M_T | M_A | {head} |")
        for rop in (float(x) for x in (a.rops or "10,20,30,45,60,80,90,100,120").split(",")):
            print(f"| {rop:g} | {row({'top_drive.rpm': a.rpm, 'hoist.speed': rop / 3600}, True)} |", flush=True)


if __name__ == "__main__":
    main()
