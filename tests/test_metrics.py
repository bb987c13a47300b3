"""The core's metrics of a sampled run (``drillstring._core.spectral_peaks``,
``energy_drift``): the numpy oracles of ``tests/oracles.py`` to rounding, analytic cases, and
single solves, PDE solves and sweeps giving the same numbers through the one implementation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from oracles import energy_drift as drift_oracle
from oracles import max_modal_shares, modal_energies
from oracles import spectral_peaks as peaks_oracle

import drillstring as ds
from drillstring import _core
from drillstring.errors import ValidationError
from drillstring.studies import analysis as an

T1 = np.linspace(0.0, 1.0, 4001)
DT = 1.0 / 4000.0
RNG = np.random.default_rng(12)

RECORDS = {
    "sine": 2e-4 * np.sin(2 * np.pi * 31.37 * T1 + 1.1),
    "two sines and an offset": 1e-3 * np.sin(2 * np.pi * 31.6 * T1) + 2e-4 * np.sin(2 * np.pi * 62.3 * T1 + 1) + 5e-5,
    "three close sines": sum(a * np.sin(2 * np.pi * f * T1) for a, f in [(1.0, 20.0), (0.3, 23.5), (0.05, 90.0)]),
    "noise and a sine": RNG.standard_normal(T1.size) + np.sin(2 * np.pi * 50.0 * T1),
    "modulated sine": (1.0 + 0.5 * np.sin(2 * np.pi * 6.0 * T1)) * np.sin(2 * np.pi * 40.0 * T1),
}


@pytest.mark.parametrize("name", list(RECORDS))
@pytest.mark.parametrize("pad", [1, 3, 8])
@pytest.mark.parametrize("threshold", [1e-3, 0.0])
def test_spectral_peaks_are_the_numpy_oracle(name: str, pad: int, threshold: float) -> None:
    x = RECORDS[name]
    freqs, amps = _core.spectral_peaks(x, DT, 6, pad, threshold)
    expected = peaks_oracle(x, DT, 6, pad, threshold)
    assert len(freqs) == len(expected) > 0
    np.testing.assert_allclose(freqs, [f for f, _ in expected], rtol=1e-12)
    np.testing.assert_allclose(amps, [a for _, a in expected], rtol=1e-9)


@pytest.mark.parametrize("freq", [13.3, 31.3, 97.0, 555.5])
def test_frequency_and_amplitude_of_a_pure_sine(freq: float) -> None:
    freqs, amps = _core.spectral_peaks(0.7 * np.sin(2 * np.pi * freq * T1 + 0.4) - 2.0, DT, 3, 8, 1e-3)
    assert freqs.tolist() == pytest.approx([freq], rel=2e-5)
    assert amps.tolist() == pytest.approx([0.7], rel=1e-3)


def test_no_peaks_without_a_spectrum() -> None:
    for x in (np.full(100, 3.0), np.zeros(100), np.array([1.0, 2.0, 3.0]), np.r_[np.ones(9), np.nan]):
        freqs, amps = _core.spectral_peaks(x, 0.01, 3, 8, 1e-3)
        assert freqs.size == amps.size == 0
    assert _core.spectral_peaks(np.sin(np.arange(100.0)), 0.0, 3, 8, 1e-3)[0].size == 0
    assert an.spectral_peaks(T1, np.full(T1.size, 3.0)) == []


@pytest.mark.parametrize("field, count, pad", [("count", 0, 8), ("count", True, 8), ("pad", 3, 0), ("pad", 3, 2**62)])
def test_spectral_peaks_refuses_bad_count_and_pad(field: str, count: int, pad: int) -> None:
    with pytest.raises(ValidationError, match=field):
        _core.spectral_peaks(np.sin(np.arange(100.0)), 0.01, count, pad, 1e-3)


def test_analysis_functions_report_the_core() -> None:
    x = RECORDS["two sines and an offset"]
    freqs, amps = _core.spectral_peaks(x, float(np.diff(T1).mean()), 3, an.DEFAULT_PAD, an.DEFAULT_THRESHOLD)
    assert [p.frequency for p in an.spectral_peaks(T1, x)] == freqs.tolist()
    assert [p.amplitude for p in an.spectral_peaks(T1, x)] == amps.tolist()
    assert an.dominant_frequencies(T1, x, 2).tolist() == freqs[:2].tolist()
    assert (an.DEFAULT_PAD, an.DEFAULT_THRESHOLD) == (_core.SPECTRAL_PAD, _core.PEAK_THRESHOLD)


def test_energy_drift_analytic_and_oracle() -> None:
    assert _core.energy_drift(np.array([2.0, 2.5, 1.0])) == 0.5
    assert _core.energy_drift(np.array([0.0, 1.0])) == 0.0
    assert _core.energy_drift(np.array([])) == 0.0
    assert _core.energy_drift(np.array([2.0, 1.5, 1.0]), np.array([0.0, 0.5, 1.0])) == 0.0
    assert math.isnan(_core.energy_drift(np.array([1.0, np.nan, 1.0])))
    h = 1.0 + 1e-9 * RNG.standard_normal(500)
    d = np.abs(1e-3 * RNG.standard_normal(500)).cumsum()
    assert _core.energy_drift(h) == pytest.approx(drift_oracle(h), rel=1e-12)
    assert _core.energy_drift(h - d, d) == pytest.approx(drift_oracle(h - d, d), rel=1e-6)
    with pytest.raises(ValidationError, match="dissipated"):
        _core.energy_drift(h, d[:10])


def test_energy_of_a_known_state_and_its_drift() -> None:
    """One linear mode ``M q'' + K q = 0``: ``H = (M v^2 + K q^2) / 2`` at every sample of the exact
    solution, so the drift is rounding only; a wrong sample shows up exactly."""
    system = _core.ModalSystem(np.array([2.0]), np.array([8.0]), np.zeros((0, 4), dtype=np.int64), np.zeros(0))
    t = np.linspace(0.0, 3.0, 301)
    q, v = 0.5 * np.sin(2.0 * t), np.cos(2.0 * t)  # w = 2, H = M v0^2 / 2 = 1
    energy = system.energy(q[None, :], v[None, :])
    np.testing.assert_allclose(energy, 1.0, rtol=1e-14)
    assert _core.energy_drift(energy) < 1e-14
    v[100] *= 1.1
    assert _core.energy_drift(system.energy(q[None, :], v[None, :])) == pytest.approx(
        0.5 * 2.0 * (1.21 - 1.0) * math.cos(2.0 * t[100]) ** 2, rel=1e-12)


def test_modal_energies_are_the_oracle_and_known_values() -> None:
    mass, stiffness = np.array([2.0, 1.0]), np.array([4.0, -1.0])
    q, v = np.array([[1.0, 0.0], [0.0, 2.0]]), np.array([[0.0, 1.0], [1.0, 0.0]])
    np.testing.assert_array_equal(_core.modal_energies(mass, stiffness, q, v), [[2.0, 1.0], [0.5, -2.0]])
    res = ds.simulate(ds.Parameters(), modes=3, t_end=0.2, samples=200)
    c = res.coefficients
    got = _core.modal_energies(c.mass, c.stiffness, res.q, res.qdot)
    np.testing.assert_allclose(got, modal_energies(c.mass, c.stiffness, res.q, res.qdot), rtol=1e-14, atol=0)
    # a transposed (non-contiguous) view gives the same numbers
    np.testing.assert_array_equal(_core.modal_energies(c.mass, c.stiffness, res.q.T.copy().T, res.qdot), got)
    with pytest.raises(ValidationError, match="q"):
        _core.modal_energies(c.mass, c.stiffness, res.q[:2], res.qdot[:2])
    with pytest.raises(ValidationError, match="stiffness"):
        _core.modal_energies(c.mass, c.stiffness[:2], res.q, res.qdot)


@pytest.mark.parametrize("damping_rate", [0.0, 0.5])
def test_single_solve_and_pde_drift_are_the_oracle(damping_rate: float) -> None:
    params = ds.Parameters(damping_rate=damping_rate)
    res = ds.simulate(params, modes=3, t_end=0.5, samples=1001)
    pde = ds.solve_pde(params, nodes=31, t_end=0.2, samples=401)
    for sol in (res, pde):
        assert sol.energy_drift() == pytest.approx(drift_oracle(sol.energy, sol.dissipated), rel=1e-9, abs=1e-300)


def test_sweep_metrics_are_the_single_solve_metrics() -> None:
    """A sweep row and a single solve of the same run through the same core functions."""
    params = ds.Parameters(length=180.0, damping_rate=0.3)
    table = ds.sweep(runs=[params], modes=3, t_end=1.0, rtol=1e-10, samples=1024, progress=False)
    row = table.iloc[0]
    res = ds.simulate(params, modes=3, t_end=1.0, rtol=1e-10, samples=1024)
    theta = res.theta(2 * params.length / 3)
    assert row["dominant_frequency_hz"] == pytest.approx(an.dominant_frequencies(res.t, theta, 1)[0], rel=1e-8)
    assert row["energy_drift"] == pytest.approx(res.energy_drift(), rel=1e-3, abs=1e-12)
    shares = max_modal_shares(res.coefficients.mass, res.coefficients.stiffness, res.q, res.qdot)
    np.testing.assert_allclose([row[f"share_mode_{i}"] for i in (1, 2, 3)], shares, rtol=1e-8)
    assert row["max_theta"] == pytest.approx(np.max(np.abs(theta)), rel=1e-8)
    assert row["rms_theta"] == pytest.approx(np.sqrt(np.mean(theta**2)), rel=1e-8)


@pytest.mark.parametrize("model", ["paper", "consistent"])
def test_quartic_share_is_the_numpy_formula(model: str) -> None:
    """The report's quartic energy share, computed in the core, is max |V| / |H(0)|."""
    res = ds.simulate(ds.preset("aluminum").replace(model=model), modes=3, t_end=0.2)
    core = res.coefficients.core_system()
    h0 = float(res.energy[0])
    want = float(np.max(np.abs(res.coefficients.potential(res.q)))) / abs(h0)
    assert core.quartic_share(res.q, h0) == want
    assert math.isnan(core.quartic_share(res.q, 0.0))
    with pytest.raises(ValidationError) as info:
        core.quartic_share(res.q[:2], h0)
    assert info.value.field == "q"


def test_bar_speed_is_sqrt_e_over_rho() -> None:
    al = ds.preset("aluminum")
    assert _core.bar_speed(al.youngs_modulus, al.density) == math.sqrt(al.youngs_modulus / al.density)
