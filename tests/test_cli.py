"""The drillstring command line: outputs and one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import drillstring as ds
from drillstring.cli import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "drillstring", *args], capture_output=True, text=True, timeout=300)


def test_simulate_writes_csv_and_plot(tmp_path):
    out, png = tmp_path / "run.csv", tmp_path / "run.png"
    code = main(["simulate", "--preset", "aluminum", "--modes", "2", "--t-end", "0.2", "--samples", "201",
                 "--out", str(out), "--plot", str(png)])
    assert code == 0
    header = out.read_text().splitlines()[0]
    assert header == "t,theta,theta_dot,q1,q2"
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert data.shape == (201, 5)
    res = ds.simulate(ds.preset("aluminum"), modes=2, t_end=0.2, samples=201)
    np.testing.assert_allclose(data[:, 1], res.theta(200.0 / 3), rtol=1e-9, atol=1e-16)
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_simulate_from_toml_with_overrides(tmp_path, capsys):
    out = tmp_path / "r.csv"
    code = main(["simulate", str(EXAMPLES / "reference.toml"), "--length", "250", "--rigid-mode", "--t-end", "0.1",
                 "--z", "10", "--out", str(out)])
    assert code == 0
    assert out.read_text().splitlines()[0] == "t,theta,theta_dot,q0,q1,q2,q3"
    res = ds.simulate(ds.preset("aluminum").replace(length=250.0), modes=3, rigid_mode=True, t_end=0.1,
                      samples=2001, rtol=1e-10, atol=1e-12)
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_allclose(data[:, 1], res.theta(10.0), rtol=1e-9, atol=1e-16)


def test_table2_json():
    proc = run("table2", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert f"{data[0]['max_amplitude']:.3e}" == "5.061e-04"
    assert [round(d["difference_percent"], 3) for k, d in enumerate(data) if k != 2] == [0.0, 0.481, 0.030, 0.005]


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["simulate", "--length", "-5"], "length"),
        (["simulate", "--rtol", "0"], "rtol"),
        (["simulate", "--modes", "0"], "modes"),
        (["simulate", "--z", "1000"], "z"),
        (["simulate", "does-not-exist.toml"], "does-not-exist.toml"),
    ],
)
def test_errors_are_one_line(args, needle):
    proc = run(*args)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("drillstring: error:") and needle in lines[0]
    assert "Traceback" not in proc.stderr


def test_bad_toml_names_file_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[parameters]\nlength = 100.0\n[solver]\nmodez = 3\n")
    proc = run("simulate", str(bad))
    assert proc.returncode == 2 and "bad.toml" in proc.stderr and "modez" in proc.stderr
    bad.write_text("[parameters]\nlength = = 1\n")
    proc = run("simulate", str(bad))
    assert proc.returncode == 2 and "bad.toml" in proc.stderr and "line 2" in proc.stderr
