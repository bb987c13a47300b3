"""Default output times resolve the fastest retained mode; sparser requests are warned about."""

from __future__ import annotations

import contextlib
import io
import math
import warnings

import _docs
import numpy as np
import pandas as pd
import pytest

import drillstring as ds
from drillstring import limits
from drillstring import report as paper
from drillstring.cli import main
from drillstring.errors import DrillstringWarning, SamplingWarning
from drillstring.model.coefficients import PDECoefficients
from drillstring.model.galerkin import project
from drillstring.solvers.modal import fastest_mode
from drillstring.studies import analysis

ALUMINIUM = ds.preset("aluminum")
DOCS = _docs.text()  # the README and the documentation pages
ZK = 200.0 / 3


def mode_hz(params: ds.Parameters, i: int) -> float:
    return float(PDECoefficients.from_parameters(params).linear_frequencies(i)) / (2 * math.pi)


@contextlib.contextmanager
def no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", DrillstringWarning)
        yield


def test_long_default_run_from_the_command_line_resolves_the_dominant_frequency_to_1_percent(tmp_path):
    # The reference: mode 1's frequency from a short, densely sampled run (nonlinear, 31.65 Hz;
    # the linear 31.10 Hz is 1.8 % below it).
    dense = ds.simulate(ALUMINIUM, t_end=1.0, samples=40001)
    reference = analysis.dominant_frequencies(dense.t, dense.q[0], 1)[0]
    assert reference == pytest.approx(31.65, abs=0.01)
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["simulate", "--preset", "aluminum", "--t-end", "100", "--out", str(tmp_path / "run.csv")])
    assert code == 0 and err.getvalue() == ""  # no warning: the default resolves the motion
    table = pd.read_csv(tmp_path / "run.csv")
    assert len(table) == 186616 == limits.samples_to_resolve(100.0, mode_hz(ALUMINIUM, 3))
    found = analysis.dominant_frequencies(table["t"].to_numpy(), table["theta"].to_numpy(), 1)[0]
    assert abs(found / reference - 1) < 0.01
    # the former default, 1001 samples over 100 s, found an alias at 1.65 Hz, now with a warning
    with pytest.warns(SamplingWarning) as record:
        old = ds.simulate(ALUMINIUM, t_end=100.0, samples=1001)
    assert analysis.dominant_frequencies(old.t, old.theta(ZK), 1)[0] == pytest.approx(1.65, abs=0.01)
    message = str(record[0].message)
    assert "samples = 1001 over t_end = 100 s gives 0.107 samples per period" in message
    assert "mode 3, 93.31 Hz" in message
    assert "samples >= 186616 (the default, with samples and t_eval unset, resolves it)" in message


def test_default_sample_counts() -> None:
    f3 = fastest_mode(project(ALUMINIUM, modes=3))
    assert f3[1] == "mode 3" and f3[0] == pytest.approx(93.3071, rel=1e-5) == mode_hz(ALUMINIUM, 3)
    with no_warning():
        assert ds.simulate(ALUMINIUM).t.size == 1868 == math.ceil(20 * f3[0]) + 1
        assert ds.simulate(ALUMINIUM, t_end=0.01).t.size == limits.MIN_DEFAULT_SAMPLES == 1001
        eight = ds.simulate(ALUMINIUM, modes=8, rigid_mode=True, t_end=2.0)
        assert eight.t.size == limits.samples_to_resolve(2.0, mode_hz(ALUMINIUM, 8)) == 9954
        # the PDE: the highest mode of the initial condition, at least mode 3
        assert ds.solve_pde(ALUMINIUM, nodes=60, t_end=1.0).t.size == 1868
        one = ds.solve_pde(ALUMINIUM.replace(initial_velocities=(0.1,)), nodes=60, t_end=1.0)
        assert one.t.size == 1868
        mixed = lambda z: 0.05 * np.cos(np.pi * z / 100) + 0.01 * np.cos(7 * np.pi * z / 100)  # noqa: E731
        seven = ds.solve_pde(ALUMINIUM, nodes=60, t_end=1.0, initial_velocity=mixed)
        assert seven.t.size == limits.samples_to_resolve(1.0, mode_hz(ALUMINIUM, 7)) == 4356
    assert "1868" in DOCS and "186 616" in DOCS


def test_resolved_runs_have_twenty_samples_per_period() -> None:
    res = ds.simulate(ALUMINIUM, modes=3, t_end=3.0)
    per_period = 1.0 / (np.diff(res.t).max() * mode_hz(ALUMINIUM, 3))
    assert limits.SAMPLES_PER_PERIOD <= per_period < limits.SAMPLES_PER_PERIOD + 0.02


def test_sparse_requests_warn_with_the_samples_needed() -> None:
    with pytest.warns(SamplingWarning, match=r"t_eval \(largest spacing 0.002004 s\) gives 5.35 samples per "
                                             r"period .* a spacing of at most 0.0005359 s \(samples >= 1868"):
        ds.simulate(ALUMINIUM, t_eval=np.linspace(0.0, 1.0, 500))
    with pytest.warns(SamplingWarning, match="samples = 51 over t_end = 0.5 s gives 0.459 samples per period "
                                             r"of the fastest retained mode \(mode 7"):
        ds.solve_pde(ALUMINIUM, nodes=40, t_end=0.5, samples=51,
                     initial_velocity=lambda z: 0.1 * np.cos(7 * np.pi * z / 100))
    # resolved requests, the default, and one or two output times (states, not a history) are quiet
    with no_warning():
        ds.simulate(ALUMINIUM, samples=1868)
        ds.simulate(ALUMINIUM, samples=2)
        ds.simulate(ALUMINIUM, t_eval=[0.0, 1.0])
        ds.simulate(ALUMINIUM, t_eval=np.linspace(0.2, 0.3, 200))
        ds.simulate(ALUMINIUM, method="rk4", dt=1e-4)  # every step


def test_the_command_line_prints_the_warning_as_one_line(tmp_path) -> None:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["simulate", "--preset", "aluminum", "--t-end", "2", "--samples", "201"])
    assert code == 0
    lines = err.getvalue().splitlines()
    assert len(lines) == 1 and lines[0].startswith("drillstring: warning: under-resolved output: samples = 201")
    assert "samples >= 3734" in lines[0]


def test_the_default_is_capped_by_the_memory_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "4M")
    cap = int(limits.DEFAULT_OUTPUT_SHARE * 4 * 1024**2) // limits.output_bytes(1, 6)
    with pytest.warns(SamplingWarning, match="the default output .* the most that fit 0.25 of the memory budget"):
        res = ds.simulate(ALUMINIUM, t_end=100.0)
    assert res.t.size == cap == 10082
    with no_warning():  # a run the cap does not cut
        assert ds.simulate(ALUMINIUM, t_end=1.0).t.size == 1868


def test_paper_runs_are_resolved_so_the_reproduction_never_warns() -> None:
    for per_second in (paper.SAMPLES_PER_SECOND, paper.QUICK_SAMPLES_PER_SECOND):
        for spec in paper.RUNS.values():
            hz, _ = fastest_mode(project(spec.params(), modes=spec.modes))
            assert per_second / hz >= limits.SAMPLES_PER_PERIOD, (spec.key, per_second)
