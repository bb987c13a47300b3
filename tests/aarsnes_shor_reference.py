"""Reference numbers from the open torsional model of Aarsnes & Shor (2018), Well B, MD 2500 m, 40 rpm.

Produced with GNU Octave from the published MATLAB code (see tests/data/aarsnes_shor/README.md).

    from aarsnes_shor_reference import reference, series
    ref = reference()            # dict (reference.json): metrics over 30..60 s, tauMax(1), config values
    s = series()                 # dict of numpy arrays over t = 0:0.01:60 (6001 samples)
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parent / "data" / "aarsnes_shor"


def reference() -> dict:
    """reference.json as a dict."""
    return json.loads((DATA / "reference.json").read_text())


def _csv(name: str) -> dict[str, np.ndarray]:
    path = DATA / name
    with path.open() as fh:
        header = fh.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {h: data[:, i] for i, h in enumerate(header)}


def series() -> dict[str, np.ndarray]:
    """``t_s``, ``motor_torque_Nm`` (MAIN.m y), ``top_drive_speed_rad_s``, ``bit_speed_rad_s`` (last collar cell)."""
    return _csv("series.csv")


def profiles() -> dict[str, np.ndarray]:
    """Per cell (908 pipe then 92 collar): ``md_m``, ``inclination_rad``, ``coulomb_torque_per_m_Nm``, ``tauMax_Nm``."""
    return _csv("profiles.csv")


def scalars() -> dict[str, float]:
    """Octave's scalars.csv (tauMax1, tauMin, phiMax_TD, Jc, Ac, Cro, Jp, Ap, ..., nsub, dtsub, wall_seconds)."""
    out = {}
    with (DATA / "scalars.csv").open() as fh:
        next(fh)
        for line in fh:
            name, value = line.strip().split(",")
            out[name] = float(value)
    return out


def final_state() -> np.ndarray:
    """MAIN.m ``x(:,end)`` after 60 s: pipe strain, collar strain, pipe speed, collar speed, top-drive speed."""
    return _csv("final_state.csv")["x_end"]
