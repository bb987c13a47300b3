"""The baselines of ``benchmarks/drill_vs_numpy.py`` compute the published scheme: the numpy port
(``benchmarks/aarsnes_shor_numpy.py``) and the published Python port copied into
``benchmarks/aarsnes_shor_published/`` both reproduce the Octave run of Aarsnes & Shor's MATLAB
code (``tests/data/aarsnes_shor``, see its README) over the first 12 s of Well B."""

from __future__ import annotations

import csv
import importlib
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"
SERIES = ROOT / "tests" / "data" / "aarsnes_shor" / "series.csv"
DURATION = 12.0  # s: the ramp, the wind-up, the first break-off of the bit (7.8 s) and its first slip


@pytest.fixture(scope="module")
def octave() -> dict[str, np.ndarray]:
    with SERIES.open() as fh:
        rows = [r for r in csv.DictReader(fh) if float(r["t_s"]) <= DURATION + 1e-9]
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


@pytest.fixture(scope="module")
def drill_vs_numpy():  # type: ignore[no-untyped-def]
    sys.path.insert(0, str(BENCHMARKS))
    try:
        yield importlib.import_module("drill_vs_numpy")
    finally:
        sys.path.remove(str(BENCHMARKS))


def test_numpy_port_is_the_published_scheme(drill_vs_numpy, octave: dict[str, np.ndarray]) -> None:  # type: ignore[no-untyped-def]
    res = drill_vs_numpy.asn.simulate(duration=DURATION)
    assert res["t"].size == octave["t_s"].size
    torque = octave["motor_torque_Nm"]
    assert np.abs(res["motor_torque"] - torque).max() < 1e-12 * np.abs(torque).max()
    bit = octave["bit_speed_rad_s"]
    assert np.abs(bit).max() > 1.0  # the bit has turned
    assert np.abs(res["bit_speed"] - bit).max() < 1e-12 * np.abs(bit).max()


@pytest.mark.slow
def test_published_port_copy_is_the_published_scheme(drill_vs_numpy, octave: dict[str, np.ndarray]) -> None:  # type: ignore[no-untyped-def]
    pytest.importorskip("scipy")  # its parameter file interpolates the survey with scipy
    res = drill_vs_numpy.published_port(str(drill_vs_numpy.PUBLISHED), DURATION)
    n = octave["t_s"].size
    assert res["t"].size == n
    # Equal to rounding (2e-15 measured); their loop repeats the last torque sample instead of
    # computing it, so it is left out.
    torque = octave["motor_torque_Nm"]
    assert np.abs(res["motor_torque"][: n - 1] - torque[: n - 1]).max() < 1e-12 * np.abs(torque).max()
    bit = octave["bit_speed_rad_s"]
    assert np.abs(bit).max() > 1.0
    assert np.abs(res["bit_speed"] - bit).max() < 1e-12 * np.abs(bit).max()
