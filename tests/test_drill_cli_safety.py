"""``drill``, ``drill-map``, ``lumped`` (and ``sweep``): output folders written as a whole and locked,
never shared between commands, refused names, one-line errors before any work, axis values
checked before solving, escaped names, a map's memory with its threads, FIFOs in a store."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
import tomllib
from _cli import one_line_error, run_cli

import drillstring as ds
from drillstring import _core
from drillstring.drilling import FILES, DrillConfig, drill, drill_map, load_drill_config
from drillstring.drilling import output as drill_output
from drillstring.drilling.lumped import lumped
from drillstring.drilling.output import MARKER, PLOT_FILES, report_markdown
from drillstring.io.output import lock_directory

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"
SWEEP = ROOT / "examples" / "sweep_length_speed.toml"
SHORT = ["--set", "numerics.duration=2", "--set", "numerics.cells=60", "--set", "numerics.field_interval=0.5"]
NO_PLOT_FILES = sorted(set(FILES) - set(PLOT_FILES))


def refuse_work(monkeypatch: pytest.MonkeyPatch) -> None:
    def called(*args: object, **kwargs: object) -> None:
        raise AssertionError("work was done before the inputs and outputs were checked")

    for name in ("drill_solve", "drill_map", "lumped_solve", "lumped_equilibria"):
        if hasattr(_core, name):
            monkeypatch.setattr(_core, name, called)


def usage_error(err: str, *needles: str) -> None:
    """One line of argparse's usage error (``drillstring CMD: error: argument --opt: ...``)."""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and ": error: " in lines[0] and "Traceback" not in err, err
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])


# --------------------------------------------------------------------------- 1. one writer, whole folder


def test_a_second_drill_into_a_locked_folder_is_refused_before_solving(tmp_path: Path,
                                                                        capsys: pytest.CaptureFixture[str],
                                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    seen: list[str] = []
    real = _core.drill_solve

    def solve(*args: object, **kwargs: object) -> object:  # while the first run solves, a second one starts
        code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
        seen.append(err)
        assert code == 2
        one_line_error(err, "--out", str(out), f"locked by process {os.getpid()}")
        return real(*args, **kwargs)

    monkeypatch.setattr(_core, "drill_solve", solve)
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
    assert code == 0, err
    assert len(seen) == 1
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES  # no lock or marker left


def test_a_folder_locked_by_another_process_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys; from drillstring.io.output import lock_directory\n"
         "h = lock_directory(sys.argv[1], field='x', busy='{holder}')\nprint('locked', flush=True); sys.stdin.read()",
         str(out)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "locked"
        with monkeypatch.context() as m:
            refuse_work(m)
            code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT)
        assert code == 2
        one_line_error(err, "--out", f"locked by process {holder.pid}")
    finally:
        holder.kill()
        holder.wait(timeout=30)
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
    assert code == 0, err
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every file of ``folder`` (name -> bytes)."""
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def test_an_interrupted_write_leaves_the_old_set_whole_and_a_rerun_writes_the_new_one(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT)[0] == 0  # with figures
    assert not (out / MARKER).exists()
    old = snapshot(out)
    assert set(PLOT_FILES) <= set(old)
    real = drill_output.write_text

    def write_text(path: str, text: str, **kwargs: object) -> object:
        if os.path.basename(path) == "config.toml":
            raise KeyboardInterrupt  # Ctrl-C in the middle of the folder
        return real(path, text, **kwargs)

    with monkeypatch.context() as m:
        m.setattr(drill_output, "write_text", write_text)
        code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots",
                               "--set", "top_drive.rpm=60")
    assert code == 130
    assert snapshot(out) == old  # the earlier run's complete set: files of two runs never mix
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # nothing left beside it
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
    assert code == 0, err
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES
    assert load_drill_config(out / "config.toml").top_drive.rpm == load_drill_config(EXAMPLE).top_drive.rpm
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_the_api_save_takes_the_lock_too(tmp_path: Path) -> None:
    result = drill(load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"]))
    out = tmp_path / "out"
    out.mkdir()
    held = lock_directory(out, field="x", busy="busy {holder}")
    try:
        with pytest.raises(ds.ValidationError, match="locked by process"):
            result.save(out, plots=False)
    finally:
        held.close()
    assert sorted(p.name for p in out.iterdir()) == [".lock"]
    result.save(out, plots=False)
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES


# --------------------------------------------------------------------------- 2. another command's folder


def _drill_map_folder(path: Path) -> None:
    path.mkdir()
    (path / "manifest.json").write_text(json.dumps({"format": "drillstring-drill-map-1", "fingerprint": "x"}))
    (path / "map.csv").write_text("top_drive.rpm,status\n")
    (path / "config.toml").write_text("# map\n")


def _drill_folder(path: Path) -> None:
    path.mkdir()
    for name in ("series.csv", "metrics.json", "config.toml"):
        (path / name).write_text("x\n")


def test_drill_refuses_a_drill_map_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    out = tmp_path / "map"
    _drill_map_folder(out)
    code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT)
    assert code == 2
    one_line_error(err, "--out", str(out), "drill-map", "manifest.json")
    assert (out / "config.toml").read_text() == "# map\n"


def test_drill_map_and_sweep_refuse_a_drill_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "run"
    _drill_folder(out)
    with monkeypatch.context() as m:
        refuse_work(m)
        code, _, err = run_cli(capsys, "drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", str(out),
                               *SHORT, "--no-plots")
    assert code == 2
    one_line_error(err, "--out", str(out), "output of drillstring drill", "metrics.json")
    with pytest.raises(ds.ValidationError, match="output of drillstring drill "):
        drill_map(load_drill_config(EXAMPLE), {"top_drive.rpm": [40.0]}, out=out)
    code, _, err = run_cli(capsys, "sweep", str(SWEEP), "--out", str(out), "--no-plots")
    assert code == 2
    one_line_error(err, str(out), "output of drillstring drill")
    assert sorted(p.name for p in out.iterdir()) == ["config.toml", "metrics.json", "series.csv"]
    assert (out / "config.toml").read_text() == "x\n"


# --------------------------------------------------------------------------- 3. --out '' and --out -


@pytest.mark.parametrize("name", ["", "-"])
@pytest.mark.parametrize("command", [
    ["drill", str(EXAMPLE), *SHORT],
    ["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", *SHORT],
    ["lumped", "--duration", "1"],
    ["lumped", "--duration", "1", "--sweep", "wob=40e3,50e3"],
    ["sweep", str(SWEEP)],
    ["convergence", "--t-end", "0.01"],
    ["paper", "--quick"],
])
def test_an_empty_or_dash_out_folder_is_refused(command: list[str], name: str, tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str],
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(capsys, *command, "--out", name)
    assert code == 2
    one_line_error(err, "--out", "not empty", "not '-'")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- 4. DRILLSTRING_MEMORY_BUDGET


@pytest.mark.parametrize("command", [
    ["drill", str(EXAMPLE), "--out", "o", *SHORT],
    ["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", "o", *SHORT],
    ["lumped", "--duration", "1"],
    ["table2"],
])
def test_a_bad_memory_budget_is_refused_by_every_command(command: list[str], tmp_path: Path,
                                                         capsys: pytest.CaptureFixture[str],
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "abc")
    code, out, err = run_cli(capsys, *command)
    assert code == 2 and out == ""
    one_line_error(err, "DRILLSTRING_MEMORY_BUDGET", "abc")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- 5. numbers of options

HUGE = "9" * 400


@pytest.mark.parametrize(("command", "option", "value", "allowed"), [
    (["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", "o"], "--threads", "-1", "1..1024"),
    (["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", "o"], "--threads", HUGE, "1..1024"),
    (["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", "o"], "--chunk-size", HUGE, "1.."),
    (["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", "o"], "--chunk-size", "0", "1.."),
    (["sweep", str(SWEEP), "--out", "o"], "--threads", "-1", "1..1024"),
    (["sweep", str(SWEEP), "--out", "o"], "--chunk-size", HUGE, "1.."),
    (["lumped"], "--duration", "nan", "finite"),
    (["lumped"], "--duration", "1e400", "finite"),
])
def test_option_numbers_out_of_range_are_one_line_errors_before_any_work(
        command: list[str], option: str, value: str, allowed: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as stop:
        run_cli(capsys, *command, option, value)
    assert stop.value.code == 2
    _, err = capsys.readouterr()
    usage_error(err, option, allowed)
    assert HUGE not in err
    assert list(tmp_path.iterdir()) == []


def test_lumped_initial_nan_is_refused_before_any_work(capsys: pytest.CaptureFixture[str],
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    with pytest.raises(SystemExit) as stop:
        run_cli(capsys, "lumped", "--initial", "nan", "0", "0")
    assert stop.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    usage_error(err, "--initial", "finite")
    code, out, err = run_cli(capsys, "lumped", "--set", "wob=nan")
    assert code == 2 and out == ""
    one_line_error(err, "wob", "finite")


def test_the_api_refuses_the_same_values_naming_the_field(monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    cfg = load_drill_config(EXAMPLE)
    for threads in (-1, 10**400, 2.0, True):
        with pytest.raises(ds.ValidationError, match="threads"):
            drill_map(cfg, {"top_drive.rpm": [40.0]}, threads=threads)
    with pytest.raises(ds.ValidationError, match="chunk_size"):
        drill_map(cfg, {"top_drive.rpm": [40.0]}, chunk_size=10**400)
    for initial in ((math.nan, 0.0, 0.0), (10**400, 0, 0), ("a", 0, 0), (1.0, 2.0)):
        with pytest.raises(ds.ValidationError, match="initial"):
            lumped(initial=initial)
    with pytest.raises(ds.ValidationError, match="duration"):
        lumped(duration=10**400)


# --------------------------------------------------------------------------- 6. axis values


def test_axis_list_values_keep_their_commas() -> None:
    from drillstring.cli._common import map_axis

    assert map_axis("well.inclination_deg=[0, 0, 10, 10],[0, 0, 20, 20]") == (
        "well.inclination_deg", [[0, 0, 10, 10], [0, 0, 20, 20]])
    assert map_axis('sections[0].name="a,b",c') == ("sections[0].name", ["a,b", "c"])
    assert map_axis("top_drive.controller.type=pi,soft_torque") == ("top_drive.controller.type",
                                                                    ["pi", "soft_torque"])


@pytest.mark.parametrize(("axis", "needles"), [
    ("top_drive.rpm=40,true", ["--axis", "top_drive.rpm", "a number"]),
    ("bit.on_bottom=true,3", ["--axis", "bit.on_bottom", "true or false"]),
    ("numerics.cells=60,2.5", ["--axis", "numerics.cells", "an integer"]),
    ("well.inclination_deg=[0, 0, 10, 10],20", ["--axis", "one kind"]),
    ("top_drive.rpm=[1,", ["--axis"]),
    ("top_drive.rpm=40,,60", ["--axis", "empty"]),
])
def test_bad_axis_values_are_refused_before_solving_naming_axis(axis: str, needles: list[str], tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str],
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    refuse_work(monkeypatch)
    out = tmp_path / "map"
    code, _, err = run_cli(capsys, "drill-map", str(EXAMPLE), "--axis", axis, "--out", str(out), *SHORT)
    assert code == 2
    line = one_line_error(err, *needles)
    assert "--set" not in line
    assert not out.exists()
    with pytest.raises(ds.ValidationError):  # the API too, before solving
        key, _, raw = axis.partition("=")
        from drillstring.drilling.config import parse_values

        drill_map(load_drill_config(EXAMPLE), {key: parse_values(raw, "x", axis)})


def test_a_list_axis_is_solved_and_stored(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "map"
    code, _, err = run_cli(capsys, "drill-map", str(EXAMPLE), "--axis", "well.inclination_deg=[0, 0, 10, 10],"
                           "[0, 0, 20, 20]", "--out", str(out), *SHORT, "--no-plots", "--threads", "1")
    assert code == 0, err
    import pandas as pd

    frame = pd.read_parquet(out / "map.parquet")
    assert len(frame) == 2 and list(frame["status"]) == ["success", "success"]


# --------------------------------------------------------------------------- 7. names in report.md and config.toml


NASTY = "pipe\x7f|*bold*<b>x</b>\x01\n# head \x85 [l](u) \\ \"q\" é"


def test_control_characters_in_names_round_trip_and_are_escaped_in_the_report(tmp_path: Path) -> None:
    cfg = load_drill_config(EXAMPLE).with_overrides({"sections[0].name": NASTY, "numerics.duration": 1.0,
                                                     "numerics.cells": 40})
    text = cfg.to_toml()
    assert "\x7f" not in text and "\x01" not in text and "\x85" not in text
    assert DrillConfig.from_dict(tomllib.loads(text)) == cfg
    cfg.save(tmp_path / "c.toml")
    assert load_drill_config(tmp_path / "c.toml").sections[0].name == NASTY
    report = report_markdown(drill(cfg), plots=False)
    row = next(line for line in report.splitlines() if "pipe" in line)
    assert row.count("|") - row.count("\\|") == 7  # the table's cells only
    for raw in ("\x7f", "\x01", "\x85", "<b>", "*bold*"):
        assert raw not in report
    assert "U+007F" in row and "U+000A" in row and "\\<b\\>" in row


# --------------------------------------------------------------------------- 8. a map's memory


def test_a_map_counts_its_threads_and_real_series_memory(monkeypatch: pytest.MonkeyPatch) -> None:
    # the core counts each run's series (56 bytes a sample: a run of 600,001 samples measured
    # 50.7, with the period estimator's memory bounded; before, its FFT of the whole series made
    # a map on 6 threads peak at 6.8 GB against a 2 GiB budget) times the threads at once
    cfg = load_drill_config(EXAMPLE).with_overrides(["numerics.duration=3000", "numerics.output_interval=0.001",
                                                      "numerics.field_interval=0", "numerics.cells=100"])
    monkeypatch.setenv("DRILLSTRING_MEMORY_BUDGET", "500M")
    with pytest.raises(ds.ValidationError, match="threads") as info:  # six runs of 3 million samples at once
        drill_map(cfg, {"top_drive.rpm": [40.0] * 6}, threads=6)
    assert info.value.field == "threads" and "DRILLSTRING_MEMORY_BUDGET" in str(info.value)
    frame = drill_map(cfg, {"top_drive.rpm": [40.0]}, threads=1)  # one fits
    assert list(frame["status"]) == ["success"], list(frame["message"])


def test_a_map_does_not_count_snapshots_it_never_keeps() -> None:
    # 600 s of snapshots every 0.1 ms: 6 million of 81 values, far over the core's output limit
    base = {"sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
            "well": {"inclination_deg": 30.0},
            "numerics": {"cells": 40, "duration": 600.0, "field_interval": 1e-4}}
    with pytest.raises(ds.ValidationError, match="field_interval"):
        DrillConfig.from_dict(base)
    frame = drill_map(base, {"top_drive.rpm": [60.0]}, threads=1)
    assert list(frame["status"]) == ["success"], list(frame["message"])
    cfg = DrillConfig.from_dict({**base, "numerics": {**base["numerics"], "field_interval": 0.5}})
    frame = drill_map(cfg, {"top_drive.rpm": [60.0], "numerics.field_interval": [1e-4]}, threads=1)
    assert list(frame["status"]) == ["success"], list(frame["message"])


# --------------------------------------------------------------------------- 9. FIFOs in a store


def _resume_in_child(code: str, tmp_path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=tmp_path)


def test_a_fifo_in_place_of_a_map_chunk_is_refused_not_waited_on(tmp_path: Path) -> None:
    out = tmp_path / "map"
    cfg = load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    cfg.save(tmp_path / "base.toml")
    drill_map(cfg, {"top_drive.rpm": [40.0, 60.0]}, threads=1, out=out, chunk_size=1)
    for victim in ("chunk-00001.parquet", "chunk-00000.json"):
        path = out / "chunks" / victim
        saved = path.read_bytes()
        path.unlink()
        os.mkfifo(path)
        done = _resume_in_child(
            "import sys\nfrom drillstring.drilling import drill_map, load_drill_config\n"
            "try:\n    drill_map(load_drill_config('base.toml'), {'top_drive.rpm': [40.0, 60.0]}, threads=1, "
            f"out={str(out)!r}, chunk_size=1)\nexcept Exception as e:\n    print(e); sys.exit(3)\n", tmp_path)
        assert done.returncode == 3, done.stderr
        assert "FIFO" in done.stdout and victim in done.stdout and "regular file" in done.stdout
        path.unlink()
        path.write_bytes(saved)


def test_a_fifo_in_place_of_a_sweep_chunk_or_manifest_is_refused(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep"
    assert run_cli(capsys, "sweep", str(SWEEP), "--out", str(out), "--no-plots", "--threads", "1")[0] == 0
    for victim in (out / "chunks" / "chunk-00000.parquet", out / "manifest.json"):
        victim.unlink()
        os.mkfifo(victim)
        done = subprocess.run([sys.executable, "-m", "drillstring", "sweep", str(SWEEP), "--out", str(out),
                               "--no-plots", "--threads", "1"], capture_output=True, text=True, timeout=120,
                              cwd=tmp_path)
        assert done.returncode == 2, done.stderr
        one_line_error(done.stderr, "FIFO", victim.name)
        victim.unlink()
