"""Write reference.npz and reference.json of this directory from the Octave outputs of make_reference.sh.

    python3 make_reference.py RAW_DIR          (numpy + pandas; reads RAW_DIR, writes only this directory)

Every number comes from the Octave runs of Aarsnes & van de Wouw's Coupled/ code and of their torsional
stability map; this script only selects, decimates and summarises (means, minima, maxima, fractions,
a spectral peak) the saved series.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPOSITORY = "https://github.com/ulfjakob/AxialTorsionalDrillString"
COMMIT = "934481490111bb9101da743f525d35723282f72c"
CASES = [(30, 30), (30, 60), (60, 30), (60, 60), (120, 30), (120, 60)]
RUNS = {  # name prefix: (end time s, metrics window s, decimation of the whole-run series)
    "": (25.0, (20.0, 25.0), 10),
    "long_": (120.0, (115.0, 120.0), 50),
}
# series of the metrics window, stored at every 0.003 s step (float32)
WINDOW_COLUMNS = [
    "t_end_s", "bit_cell_speed_end_m_s", "bit_cell_speed_end_rad_s", "wob_N", "tob_Nm", "top_force_N",
    "top_torque_Nm", "depth_of_cut_m", "bit_face_speed_m_s", "bit_face_speed_rad_s",
    "last_wob_N", "last_tob_Nm", "last_d_m", "last_ga", "last_g_tt_Nm", "last_g_wt_N", "last_wc_N",
    "last_tc_Nm", "last_wf_N", "last_tf_Nm", "last_vb_m_s", "last_ob_rad_s", "bit_cell_speed_m_s",
    "bit_cell_speed_rad_s",
    "axial_momentum_m2_s", "angular_momentum_m_rad_s", "axial_momentum_end_m2_s", "angular_momentum_end_m_rad_s",
    "axial_speed_sq_int_m3_s2", "angular_speed_sq_int_m_rad2_s2", "top_axial_power_W", "top_torsional_power_W",
    "bit_axial_power_W", "bit_torsional_power_W", "energy_end_J",
]
LONG_WINDOW_COLUMNS = WINDOW_COLUMNS[:8] + ["last_ga", "last_g_tt_Nm", "last_d_m", "last_wob_N", "last_tob_Nm"]
# series of the whole run, every DECIMATE-th step (a sample, not an average; float32)
FULL_COLUMNS = ["t_end_s", "bit_cell_speed_end_m_s", "bit_cell_speed_end_rad_s", "wob_N", "tob_Nm", "top_force_N",
                "top_torque_Nm", "depth_of_cut_m"]
RPM = 60.0 / (2.0 * math.pi)


def stats(v: np.ndarray) -> dict[str, float]:
    return {"mean": float(v.mean()), "min": float(v.min()), "max": float(v.max())}


def peak_frequency(t: np.ndarray, v: np.ndarray) -> float:
    """Frequency (Hz) of the largest periodogram peak of v minus its mean (Hann window), 0 if v is constant."""
    x = v - v.mean()
    if not np.any(x):
        return 0.0
    spec = np.abs(np.fft.rfft(x * np.hanning(len(x))))
    f = np.fft.rfftfreq(len(x), d=float(t[1] - t[0]))
    return float(f[1:][np.argmax(spec[1:])])


def in_window(d: pd.DataFrame, window: tuple[float, float]) -> pd.DataFrame:
    """The steps that start at or after window[0] (to the end of the run, which ends at window[1])."""
    return d[d["t_start_s"] >= window[0] - 1e-9]


def metrics(d: pd.DataFrame, sc: pd.Series, window: tuple[float, float]) -> dict:
    w = in_window(d, window)
    t = w["t_end_s"].to_numpy()
    vb = w["bit_cell_speed_end_m_s"].to_numpy()
    ob = w["bit_cell_speed_end_rad_s"].to_numpy()
    wob = w["wob_N"].to_numpy()
    tob = w["tob_Nm"].to_numpy()
    stuck = w["last_g_tt_Nm"].to_numpy() != 0.0
    ga = w["last_ga"].to_numpy()
    v0, om0 = float(sc["V0"]), float(sc["omega0"])
    area = math.pi * float(sc["a"]) ** 2
    spread_v = float(vb.max() - vb.min()) / v0
    spread_o = float(ob.max() - ob.min()) / om0
    return {
        "window_s": list(window),
        "window_definition": "the steps starting at t >= window_s[0] to the end of the run (t_end up to T1 + 0.003 s)",
        "samples": int(len(t)),
        "bit_axial_speed_m_s": stats(vb),
        "rop_mean_m_per_h": float(vb.mean() * 3600.0),
        "bit_rpm": stats(ob * RPM),
        "wob_N": stats(wob),
        "tob_Nm": stats(tob),
        "top_force_N": stats(w["top_force_N"].to_numpy()),
        "top_torque_Nm": stats(w["top_torque_Nm"].to_numpy()),
        "depth_of_cut_per_rev_m": stats(w["depth_of_cut_m"].to_numpy()),
        "depth_of_cut_per_rev_nominal_m": 2 * math.pi * v0 / om0,
        "mse_mean_Pa": float(wob.mean() / area + (tob * ob).mean() / (area * vb.mean())),
        "torsional_stick_fraction": float(stuck.mean()),
        "stick_slip": bool(stuck.any()),
        "contact_regime_fraction": float((ga < 1.0).mean()),
        "off_bottom_fraction": float((w["last_wob_N"].to_numpy() == 0.0).mean()),
        "no_cut_fraction": float((w["last_d_m"].to_numpy() == 0.0).mean()),
        "bit_axial_speed_spread_over_V0": spread_v,
        "bit_angular_speed_spread_over_omega0": spread_o,
        "settled": bool(spread_v < 0.01 and spread_o < 0.01),
        "wob_peak_frequency_hz": peak_frequency(t, wob),
        "bit_rpm_peak_frequency_hz": peak_frequency(t, ob),
        "blade_pass_frequency_hz": float(sc["N"]) * om0 / (2 * math.pi),
    }


def main() -> None:
    raw = Path(sys.argv[1])
    arrays: dict[str, np.ndarray] = {}
    cases = {}
    walls = dict(line.strip().split(",") for line in (raw / "wall_seconds.csv").read_text().splitlines() if line)
    for rpm, rop in CASES:
        name = f"rpm{rpm}_rop{rop}"
        entry: dict = {"rpm": rpm, "rop_m_per_h": rop}
        for prefix, (t1, window, decimate) in RUNS.items():
            if not (raw / f"{prefix}{name}_series.csv").exists():
                entry["long_120s" if prefix else "published_25s"] = {"end_time_s": t1, "not_run": True}
                continue
            d = pd.read_csv(raw / f"{prefix}{name}_series.csv")
            sc = pd.read_csv(raw / f"{prefix}{name}_scalars.csv", index_col=0)["value"]
            assert float(sc["T1"]) == t1 and int(sc["Nt"]) == len(d)
            d["energy_end_J"] = (d["axial_strain_energy_end_J"] + d["torsional_strain_energy_end_J"]
                                 + d["axial_kinetic_energy_end_J"] + d["torsional_kinetic_energy_end_J"])
            key = f"{prefix}{name}"
            sub = in_window(d, window)
            for c in (WINDOW_COLUMNS if prefix == "" else LONG_WINDOW_COLUMNS):
                arrays[f"{key}.window.{c}"] = sub[c].to_numpy(np.float32)
            for c in FULL_COLUMNS:
                arrays[f"{key}.full.{c}"] = d[c].to_numpy(np.float32)[decimate - 1::decimate]
            final = pd.read_csv(raw / f"{prefix}{name}_final.csv")["x_end"].to_numpy()
            arrays[f"{key}.final_cut_surface_m"] = final[4 * int(sc["P"]):]
            dt_sub = float(d["dt_sub_s"].iloc[0])
            pl, nb = int(sc["Pl"]), float(sc["N"])
            entry["scheme"] = {
                "substeps_per_step": int(d["substeps"].iloc[0]),
                "dt_sub_s": dt_sub,
                "cut_surface_cells_Pl": pl,
                "cut_surface_courant_at_omega0": dt_sub * pl * float(sc["omega0"]) * nb / (2 * math.pi),
                "axial_courant": dt_sub * float(sc["c_a"]) * float(sc["P"]) / float(sc["L"]),
                "torsional_courant": dt_sub * float(sc["c_t"]) * float(sc["P"]) / float(sc["L"]),
                "omega_max_rad_s": float(sc["omegaMAX"]),
                "Ka_1_s": float(sc["Ka"]), "Kt_1_s": float(sc["Kt"]), "tN_s": float(sc["tN"]),
                "dNom_m": float(sc["dNom"]),
            }
            entry["setpoints"] = {"omega0_rad_s": float(sc["omega0"]), "V0_m_s": float(sc["V0"])}
            run = "published_25s" if prefix == "" else "long_120s"
            entry[run] = {
                "end_time_s": t1,
                "steps": int(sc["Nt"]),
                "wall_seconds": float(walls[key]),
                "whole_run_decimation": decimate,
                "metrics": metrics(d, sc, window),
            }
        cases[name] = entry

    # the recording lines change no number
    rec = pd.read_csv(raw / "rpm30_rop30_final.csv")["x_end"].to_numpy()
    unrec = np.loadtxt(raw / "unrecorded_rpm30_rop30.csv")
    d30 = pd.read_csv(raw / "rpm30_rop30_series.csv")
    n_x = len(rec)
    y_unrec = unrec[n_x:].reshape(-1, 3)   # y(:) of MAIN.m, 3 rows, column-major
    check = {
        "final_state_max_abs_difference": float(np.max(np.abs(unrec[:n_x] - rec))),
        "y_max_abs_difference": float(max(np.max(np.abs(y_unrec[1:, 0] - d30["y1_d_m"].to_numpy())),
                                          np.max(np.abs(y_unrec[1:, 1] - d30["y2_one_minus_ga"].to_numpy())),
                                          np.max(np.abs(y_unrec[1:, 2] - d30["y3_wf_N"].to_numpy())))),
    }

    nd = pd.read_csv(raw / "stability_nondim.csv")
    zmap = pd.read_csv(raw / "stability_nondim_Z.csv")
    arrays["stability.nondim.V0"] = nd["V0"].to_numpy()
    arrays["stability.nondim.OmLine"] = nd["OmLine"].to_numpy()
    arrays["stability.nondim.Om"] = np.array([float(c) for c in zmap.columns[1:]])
    arrays["stability.nondim.Z"] = zmap.iloc[:, 1:].to_numpy()
    dim = pd.read_csv(raw / "stability_dimensional.csv")
    sweep = dim
    stab: dict = {"nondim": {
        "script": "Coupled - nondim/MAIN_Torsional_FreqStabMap.m (eta = 0.7, 120 x 120 grid, nw = 3000)",
        "V0": nd["V0"].tolist(), "OmLine": nd["OmLine"].tolist()}, "dimensional": {}}
    for rop in (30, 60):
        q = sweep[sweep["rop_m_per_h"] == rop]
        grid = q.iloc[:-3]                       # the sweep; the last three rows repeat 30, 60, 120 rpm
        arrays[f"stability.dimensional.rop{rop}.rpm"] = grid["rpm"].to_numpy()
        per = {}
        for col in ("MT_named", "MT_2k", "MA_named", "MA_2k", "MG_named", "MG_2k"):
            arrays[f"stability.dimensional.rop{rop}.{col}"] = grid[col].to_numpy()
            unstable = grid[col].to_numpy() > 1.0
            r = grid["rpm"].to_numpy()
            switches = [[float(r[i]), float(r[i + 1])] for i in np.nonzero(unstable[1:] != unstable[:-1])[0]]
            per[col] = {"unstable_at_lowest_rpm": bool(unstable[0]), "switches_between_rpm": switches}
        at = q.iloc[-3:]
        per["at_cases"] = {str(int(row.rpm)): {c: float(getattr(row, c)) for c in
                                                ("MT_named", "MT_2k", "wT_2k_rad_s", "MA_named", "MA_2k",
                                                 "MG_named", "MG_2k")}
                           for row in at.itertuples()}
        stab["dimensional"][f"rop{rop}"] = per
    stab["dimensional"]["definition"] = (
        "Coupled/freqPlots.m lines 17-36 at Coupled/parameters.m with omega0 and V0 of each rpm and ROP: "
        "Gt = gt Kt/s (1-exp(-s tN)), Ga = -ga Ka/s (1-exp(-s tN)); M = largest |G(jw)| where G crosses the "
        "negative real axis (w = linspace(3e-3, 20 pi, 2e4) rad/s); unstable when M > 1. MT: Gt, MA: Ga, "
        "MG: Ga + Gt. '_named': damping rate ka = kt = 1 1/s as freqPlots.m uses it; '_2k': 2 1/s, the rate "
        "the time stepping applies")

    np.savez_compressed(HERE / "reference.npz", **arrays)
    sc30 = pd.read_csv(raw / "rpm30_rop30_scalars.csv", index_col=0)["value"]
    ref = {
        "source": {"repository": REPOSITORY, "commit": COMMIT,
                   "files": ["Coupled/MAIN.m", "Coupled/parameters.m", "Coupled/waveStep_transportBRI.m",
                             "Coupled/freqPlots.m (transfer functions)",
                             "Coupled - nondim/MAIN_Torsional_FreqStabMap.m"],
                   "run_with": "GNU Octave 7.3.0 (Debian 7.3.0-2, x86_64), headless (make_headless.py)"},
        "parameters": "parameters.json",
        "time_convention": ("step k advances t(k) -> t(k) + 0.003 s in 8 sub-steps; t_end_s = t(k) + 0.003; "
                            "'_end' columns are the state after the step; wob_N, tob_Nm, top_*, depth_of_cut_m, "
                            "powers and integrals are means over the step's sub-steps, each taken before the "
                            "sub-step's update; 'last_*' are the bit law of the step's last sub-step"),
        "recording_changes_nothing": check,
        "cases": cases,
        "stability": stab,
        "scalars_30rpm_30mh": {k: float(v) for k, v in sc30.items()},
    }
    (HERE / "reference.json").write_text(json.dumps(ref, indent=1) + "\n")


if __name__ == "__main__":
    main()
