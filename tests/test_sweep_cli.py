"""`drillstring sweep`: the shipped example, shrunk, end to end; errors as one line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from drillstring.cli import main  # noqa: E402
from drillstring.io.toml import load_toml  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "sweep_length_speed.toml"


def shrunk_example(tmp_path: Path) -> Path:
    """The shipped example with a 4 x 3 grid and t_end = 0.2 s (same tables and keys)."""
    text = EXAMPLE.read_text()
    document = load_toml(EXAMPLE)
    assert set(document) == {"base", "solver", "grid"} and set(document["grid"]) == {"length", "omega"}
    text = text.replace("length = {linspace = [100.0, 500.0, 41]}", "length = {linspace = [100.0, 500.0, 4]}")
    text = text.replace("omega = {linspace = [0.0, 250.0, 41]}", "omega = [0.0, 100.0, 250.0]")
    text = text.replace("t_end = 1.0", "t_end = 0.2").replace("samples = 1024", "samples = 256")
    path = tmp_path / "small.toml"
    path.write_text(text)
    assert load_toml(path)["grid"]["omega"] == [0.0, 100.0, 250.0]
    return path


def test_sweep_command_writes_tables_and_plots(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sweep", str(shrunk_example(tmp_path)), "--out", str(out), "--no-progress"]) == 0
    stdout = capsys.readouterr().out
    assert "12 runs in" in stdout and "12 ok, 0 failed, 0 invalid" in stdout
    table = pd.read_parquet(out / "results.parquet")
    assert len(table) == 12 and (table["status"] == "success").all()
    assert table["length"].tolist() == [l for l in (100.0, 233.33333333333334, 366.6666666666667, 500.0)
                                        for _ in range(3)]
    assert table["unstable_modes"].max() >= 2  # 250 rad/s exceeds Omega_crit,2 at l >= 366 m
    csv = pd.read_csv(out / "results.csv")
    assert list(csv.columns) == list(table.columns)
    for metric in ("max_theta", "dominant_frequency_hz", "unstable_modes", "energy_drift", "share_mode_3"):
        png = out / "plots" / f"{metric}.png"
        assert png.read_bytes()[:4] == b"\x89PNG" and png.stat().st_size > 10_000


def test_sweep_command_reports_failed_and_invalid_rows(tmp_path, capsys):
    config = tmp_path / "bad.toml"
    config.write_text(
        '[base]\npreset = "aluminum"\n[solver]\nmodes = 1\nt_end = 0.1\nsamples = 64\nmax_steps = 200\n'
        "[grid]\nlength = [5.0, 100.0]\ninner_diameter = [0.1, 0.3]\n"
    )
    assert main(["sweep", str(config), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    assert "4 runs in" in capsys.readouterr().out
    table = pd.read_parquet(tmp_path / "o" / "results.parquet")
    assert table["status"].tolist() == ["max_steps", "invalid", "success", "invalid"]
    assert not (tmp_path / "o" / "plots").exists()


def test_sweep_command_errors_are_one_line(tmp_path):
    config = tmp_path / "typo.toml"
    config.write_text('[base]\npreset = "aluminum"\n[grid]\nlenght = [100.0]\n')
    proc = subprocess.run([sys.executable, "-m", "drillstring", "sweep", str(config), "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "lenght" in proc.stderr and "typo.toml" in proc.stderr
    config.write_text("[base]\n[solver]\nrtol = 'tight'\n")
    assert main(["sweep", str(config), "--out", str(tmp_path / "o")]) == 2


def test_a_resume_that_recomputes_chunks_says_so_in_one_line(tmp_path, capsys):
    config = tmp_path / "sweep.toml"
    config.write_text('[base]\npreset = "aluminum"\n[solver]\nt_end = 0.05\nsamples = 64\n'
                      '[grid]\nlength = [100.0, 150.0, 200.0]\n')
    args = ["sweep", str(config), "--out", str(tmp_path / "out"), "--chunk-size", "2", "--no-plots"]
    assert main(args) == 0
    chunk = tmp_path / "out" / "chunks" / "chunk-00001.parquet"
    chunk.write_bytes(chunk.read_bytes()[:-1] + b"\0")
    capsys.readouterr()
    assert main(args) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("drillstring: warning: resuming the sweep in ")
    assert "chunk 1: its bytes differ from those written (SHA-256 mismatch)" in err[0]
