"""``drillstring drill``: the output folder, ``--set``, checks before any work, never clobbering,
one-line errors with exit status 2, Ctrl-C."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _children import python_child
from _cli import one_line_error, run_cli
from _drill_folder import METRIC_KEYS

from drillstring import _core
from drillstring.drilling import FILES, load_drill_config
from drillstring.drilling.output import PLOT_FILES

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"
#: A short run of the example: a few seconds of a coarse grid.
SHORT = ["--set", "numerics.duration=3", "--set", "numerics.cells=60", "--set", "numerics.field_interval=0.5"]


def test_drill_writes_the_output_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    code, stdout, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT,
                                "--set", "top_drive.rpm=50", "--no-progress")
    assert code == 0, err
    assert sorted(p.name for p in out.iterdir()) == sorted(FILES)
    assert "SSI" in stdout and f"wrote {len(FILES)} files to {out}" in stdout
    metrics = json.loads((out / "metrics.json").read_text())
    assert METRIC_KEYS <= set(metrics) and metrics["status"] == "success"
    assert metrics["window"] == [metrics["window_start"], metrics["window_end"]]
    series = pd.read_csv(out / "series.csv", index_col="t")
    assert list(series.columns) == ["surface_rpm", "bit_rpm", "motor_torque", "bit_torque"]
    parquet = pd.read_parquet(out / "series.parquet")
    np.testing.assert_allclose(parquet.to_numpy(), series.to_numpy(), rtol=1e-9)
    np.testing.assert_allclose(parquet.index.to_numpy(), series.index.to_numpy(), rtol=1e-9)
    assert series.index[-1] == pytest.approx(3.0)
    solved = load_drill_config(out / "config.toml")
    expected = load_drill_config(EXAMPLE).with_overrides(
        ["numerics.duration=3", "numerics.cells=60", "numerics.field_interval=0.5", "top_drive.rpm=50"])
    assert solved == expected and solved.top_drive.rpm == 50.0
    with np.load(out / "fields.npz") as fields:
        nt, nz = fields["t"].size, fields["z"].size
        assert nt == 7 and nz >= 2
        assert fields["omega_rpm"].shape == fields["torque_Nm"].shape == (nt, nz)
        assert float(fields["breakoff_torque_Nm"]) == pytest.approx(metrics["breakoff_torque_Nm"], rel=1e-12)
    for name in PLOT_FILES:
        assert (out / name).read_bytes()[:4] == b"\x89PNG"
    report = (out / "report.md").read_text()
    assert "success" in report and "time_histories.png" in report
    # the same command again replaces every file atomically: no temporary files left behind, and
    # the figures of the earlier run are removed (the folder never mixes files of two runs)
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")[0] == 0
    assert sorted(p.name for p in out.iterdir()) == sorted(set(FILES) - set(PLOT_FILES))


def test_no_plots(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(tmp_path / "o"), *SHORT, "--no-plots")
    assert code == 0, err
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == sorted(set(FILES) - set(PLOT_FILES))


def refuse_solve(monkeypatch: pytest.MonkeyPatch) -> None:
    def called(*args: object, **kwargs: object) -> None:
        raise AssertionError("the solver ran before the inputs and outputs were checked")

    monkeypatch.setattr(_core, "drill_solve", called)


def test_inputs_are_never_overwritten(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_solve(monkeypatch)
    out = tmp_path / "out"
    out.mkdir()
    config = out / "config.toml"  # the input is where the output folder's config.toml goes
    original = EXAMPLE.read_bytes()
    config.write_bytes(original)
    code, _, err = run_cli(capsys, "drill", str(config), "--out", str(out), *SHORT)
    assert code == 2
    one_line_error(err, "--out", "config.toml", "input")
    # a hard link to the input under another output name is the same file
    other = tmp_path / "cfg.toml"
    other.write_bytes(original)
    config.unlink()
    os.link(other, out / "series.csv")
    code, _, err = run_cli(capsys, "drill", str(other), "--out", str(out), *SHORT)
    assert code == 2
    one_line_error(err, "series.csv", "input")
    assert other.read_bytes() == original and (out / "series.csv").read_bytes() == original
    assert sorted(p.name for p in out.iterdir()) == ["series.csv"]


@pytest.mark.parametrize("kind", ["file", "under-a-file", "directory-entry"])
def test_bad_destinations_are_refused_before_solving(kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_solve(monkeypatch)
    plain = tmp_path / "plain.txt"
    plain.write_text("keep me\n")
    if kind == "file":
        out = plain
    elif kind == "under-a-file":
        out = plain / "out"
    else:
        out = tmp_path / "out"
        (out / "metrics.json").mkdir(parents=True)  # a directory where a file must go
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT)
    assert code == 2
    one_line_error(err, "--out")
    assert plain.read_text() == "keep me\n"


def test_existing_files_are_replaced_and_links_written_through(tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    out.mkdir()
    elsewhere = tmp_path / "kept" / "series.csv"
    elsewhere.parent.mkdir()
    elsewhere.write_text("old\n")
    (out / "series.csv").symlink_to(elsewhere)
    (out / "metrics.json").write_text("{}")
    (out / "metrics.json").chmod(0o640)
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
    assert code == 0, err
    assert (out / "series.csv").is_symlink() and elsewhere.read_text().startswith("t,surface_rpm")
    assert (out / "metrics.json").stat().st_mode & 0o777 == 0o640
    assert json.loads((out / "metrics.json").read_text())["status"] == "success"


@pytest.mark.parametrize(
    ("args", "needles"),
    [
        (["missing.toml"], ["missing.toml"]),
        ([str(EXAMPLE), "--set", "top_drive.rpmm=3"], ["top_drive.rpmm", "rpm"]),
        ([str(EXAMPLE), "--set", "top_drive.rpm"], ["--set", "key=value"]),
        ([str(EXAMPLE), "--set", "sections[9].length=3"], ["sections[9]"]),
        ([str(EXAMPLE), "--set", "top_drive.inertia=0"], ["top_drive.inertia", "> 0"]),
        ([str(EXAMPLE), "--set", "bit.on_bottom=yes please"], ["--set"]),
        ([str(EXAMPLE), "--set", "numerics.cells=2.5"], ["numerics.cells", "integer"]),
    ],
)
def test_bad_input_is_one_line_with_exit_status_2(args: list[str], needles: list[str], tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str],
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_solve(monkeypatch)
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(capsys, "drill", *args, "--out", str(tmp_path / "out"))
    assert code == 2
    one_line_error(err, *needles)
    assert not (tmp_path / "out").exists()


def test_bad_config_file_names_file_line_and_field(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    text = EXAMPLE.read_text()
    assert "\ninertia = 2900.0" in text
    bad.write_text(text.replace("\ninertia = 2900.0", "\ninertia = -5.0", 1))
    line = next(k for k, text in enumerate(bad.read_text().splitlines(), 1) if text.startswith("inertia = -5.0"))
    done = subprocess.run([sys.executable, "-m", "drillstring", "drill", str(bad), "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 2 and done.stdout == ""
    one_line_error(done.stderr, f"{bad}, line {line}: invalid top_drive.inertia")
    done = subprocess.run([sys.executable, "-m", "drillstring", "drill", str(bad)], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert done.returncode == 2 and "--out" in done.stderr and len(done.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()


def test_ctrl_c_stops_the_run_with_status_130_and_no_files(tmp_path: Path) -> None:
    out = tmp_path / "out"
    script = f"""
        import sys
        from drillstring.cli import main
        print("ready", flush=True)
        sys.exit(main(["drill", {str(EXAMPLE)!r}, "--out", {str(out)!r}, "--set", "numerics.duration=86400",
                       "--set", "numerics.output_interval=1", "--set", "numerics.field_interval=0",
                       "--set", "numerics.cells=2000", "--no-progress"]))  # minutes of solving
    """
    with python_child(script, cwd=tmp_path) as child:
        time.sleep(1.5)
        child.interrupt()
        _, err = child.communicate(timeout=60)
        assert child.proc.returncode == 130, err
        assert err.strip().splitlines()[-1] == "drillstring: interrupted" and "Traceback" not in err
    assert not out.exists() or list(out.iterdir()) == []
