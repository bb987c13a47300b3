"""Write reference.json of this directory from the Octave outputs (series.csv, scalars.csv).

    python3 make_reference.py          (numpy + pandas; reads and writes only this directory)

Every number comes from the Octave run of Aarsnes & Shor's MAIN.m; this script only takes
minima, maxima, means and crossing times of the saved series.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
WINDOW = (30.0, 60.0)


def upward_crossings(t: np.ndarray, v: np.ndarray, level: float) -> np.ndarray:
    """Times where v crosses ``level`` upwards (v[i] < level <= v[i+1]), linearly interpolated."""
    d = v - level
    i = np.nonzero((d[:-1] < 0) & (d[1:] >= 0))[0]
    return t[i] - d[i] * (t[i + 1] - t[i]) / (d[i + 1] - d[i])


def main() -> None:
    se = pd.read_csv(HERE / "series.csv")
    sc = pd.read_csv(HERE / "scalars.csv", index_col=0)["value"]
    t = se["t_s"].to_numpy()
    w = (t >= WINDOW[0] - 1e-9) & (t <= WINDOW[1] + 1e-9)
    tw = t[w]
    tq = se["motor_torque_Nm"].to_numpy()[w]
    bit_rpm = se["bit_speed_rad_s"].to_numpy()[w] * 60 / (2 * math.pi)
    td_rpm = se["top_drive_speed_rad_s"].to_numpy()[w] * 60 / (2 * math.pi)
    cross = upward_crossings(tw, tq, tq.mean())
    bit_cross = upward_crossings(tw, bit_rpm, bit_rpm.mean())
    # instants where the bit speed falls below the friction model's stick threshold (o_thres rad/s)
    o_thres_rpm = 1.5 * 60 / (2 * math.pi)
    b = bit_rpm
    stick_onsets = tw[1:][(b[:-1] >= o_thres_rpm) & (b[1:] < o_thres_rpm)]

    pp, pc = int(sc["Pp"]), int(sc["Pc"])
    prof = pd.read_csv(HERE / "profiles.csv")["coulomb_torque_per_m_Nm"].to_numpy()
    pipe_sum = float(prof[:pp].sum() * sc["dxp"])
    collar_sum = float(prof[pp:].sum() * sc["dxc"])
    g_ratio = float(sc["Gc"] / sc["Gp"])
    ref = {
        "source": {
            "repository": "https://github.com/Open-Source-Drilling-Community/Aarsnes-and-Shor-Torsional-Model",
            "commit": "67002405b46a8f70dec3f25c2211fcb9a9db23f8",
            "files": ["MAIN.m", "parameters_WellB.m", "torsionalWaveStep.m"],
            "run_with": "GNU Octave 7.3.0 (Debian 7.3.0-2, x86_64), plotting commented out (headless.diff)",
        },
        "case": {"well": "B", "md_m": 2500.0, "mu": 0.3, "f_rat": 0.65, "o_thres_rad_s": 1.5, "rpm": 40.0,
                 "duration_s": 60.0, "dt_s": 0.01, "cells": 1000, "samples": int(len(t))},
        "window_s": list(WINDOW),
        "window_samples": int(w.sum()),
        "motor_torque_min_Nm": float(tq.min()),
        "motor_torque_max_Nm": float(tq.max()),
        "motor_torque_mean_Nm": float(tq.mean()),
        "cycle_period_s": float(np.mean(np.diff(cross))),
        "cycle_period_definition": ("mean interval between upward crossings of the motor torque's own mean "
                                    "over 30..60 s (samples t >= 30 and t <= 60, both ends included), crossing "
                                    "instants linearly interpolated between samples"),
        "motor_torque_upward_crossings_s": [float(x) for x in cross],
        "cycle_period_check": {
            "bit_rpm_upward_crossings_of_its_mean_s": [float(x) for x in bit_cross],
            "bit_rpm_crossing_period_s": float(np.mean(np.diff(bit_cross))),
            "bit_stick_onsets_s": [float(x) for x in stick_onsets],
            "bit_stick_onset_definition": "first sample with bit speed below o_thres = 1.5 rad/s after one at or above",
        },
        "bit_rpm_min": float(bit_rpm.min()),
        "bit_rpm_max": float(bit_rpm.max()),
        "bit_rpm_mean": float(bit_rpm.mean()),
        "top_drive_rpm_min": float(td_rpm.min()),
        "top_drive_rpm_max": float(td_rpm.max()),
        "tau_max_1_Nm": float(sc["tauMax1"]),
        "tau_max_1_definition": ("MAIN.m tauMax(1): cumtrapz of the Coulomb torque per metre P_thresProfile/"
                                 "C_thresProfile over the node positions [xp; xc] = [linspace(0,Lp,Pp); "
                                 "Lp + linspace(0,Lc,Pc)], from the bit up"),
        "tau_min_Nm": float(sc["tauMin"]),
        "tau_min_definition": "tauMax(1)*(1 - 2*(1 - fRat))",
        "phi_max_td_rad": float(sc["phiMax_TD"]),
        "phi_max_td_note": "as printed by MAIN.m; negative because cumtrapz runs over decreasing depth",
        "model_static_torque": {
            "pipe_cell_sum_Nm": pipe_sum,
            "collar_cell_sum_Nm": collar_sum,
            "cell_sum_Nm": pipe_sum + collar_sum,
            "cell_sum_collar_times_Gc_over_Gp_Nm": pipe_sum + g_ratio * collar_sum,
            "note": ("sums of the Coulomb torque per metre times the cell length L/P. In the scheme the collar "
                     "torque is Jc*Gc*strain but the collar bulk obeys Jc*rho*omega_t = Jc*rho*c_t^2*strain_z - F "
                     "(c_t^2 = Gp/rho), so the torque a collar friction load F adds at the pipe/collar interface "
                     "is (Gc/Gp)*F: the scheme's own static torque at the top is the last number, about 5 % above "
                     "tauMax(1)"),
        },
        "drillstring_equivalent_collar": {
            "polar_moment": float(sc["Jc"]),
            "area": float(sc["Ac"]),
            "contact_diameter": float(2 * sc["Cro"]),
            "shear_modulus": float(sc["Gc"]),
            "density": float(sc["rho"] * g_ratio),
            "note": ("a uniform collar section with these values has the same continuum equations as the "
                     "scheme's collar: wave speed sqrt(G/density) = c_t, torque per strain J*G = Jc*Gc at the "
                     "interface, friction "
                     "and damping accelerations F/(J*density) equal to the scheme's (friction per metre scales "
                     "with the density). The pipe maps directly (Jp, Ap, contact diameter 2*Pro, Gp, rho)"),
        },
        "config": {
            "collar_polar_moment_m4": float(sc["Jc"]),
            "collar_polar_moment_note": "pi*sum(L.*pi.*(OD.^4-ID.^4)/32)/sum(L): an extra factor pi "
                                        "(without it 1.4981927743832943e-04)",
            "collar_area_m2": float(sc["Ac"]),
            "collar_contact_radius_m": float(sc["Cro"]),
            "collar_shear_modulus_Pa": float(sc["Gc"]),
            "collar_length_m": float(sc["Lc"]),
            "pipe_polar_moment_m4": float(sc["Jp"]),
            "pipe_area_m2": float(sc["Ap"]),
            "pipe_contact_radius_m": float(sc["Pro"]),
            "pipe_inner_radius_m": float(sc["Pri"]),
            "pipe_shear_modulus_Pa": float(sc["Gp"]),
            "pipe_length_m": float(sc["Lp"]),
            "density_kg_m3": float(sc["rho"]),
            "wave_speed_m_s": float(sc["c_t"]),
            "wave_speed_note": "sqrt(Gp/rho), used for pipe AND collar",
            "kt": float(sc["kt"]),
            "dt_sub_s": float(sc["dtsub"]),
            "substeps_per_step": int(sc["nsub"]),
            "step_s": 0.01,
            "viscous_damping_rate_1_s": float(sc["damping_rate_2_kt_dtsub"]),
            "viscous_damping_rate_note": "2*kt*dt_sub: the source dt*kt*(alpha+beta) is multiplied by dt again "
                                         "in the update, so d(omega)/dt = -2*kt*dt_sub*omega",
            "pipe_cells": pp,
            "collar_cells": pc,
            "cell_length_m": float(sc["dxp"]),
            "top_drive_inertia_kg_m2": float(sc["I_TD"]),
            "pi_kp_Nms_rad": 38e3,
            "pi_ki_Nm_rad": 100e3,
            "controller_note": ("per 0.01 s step k: sp += (sp_final - sp)/(1/dt); tau = (sp - Otd)*38e3 + II*100e3; "
                                "II += dt*(sp - Otd); then 12 sub-steps with tau held, Otd by explicit Euler"),
            "gravity_m_s2": 9.81,
            "survey_md_m": [0, 500, 1600, 4000],
            "survey_inclination_deg": [0, 0, 60, 60],
        },
    }
    (HERE / "reference.json").write_text(json.dumps(ref, indent=2) + "\n")


if __name__ == "__main__":
    main()
