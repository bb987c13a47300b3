"""Output folders are replaced all or nothing: ``kill -9``, a full disk or Ctrl-C at any moment
leave the complete old set or the complete new one, never a mix; what an interrupted run left
beside the folder is cleaned (or put back) by the next run; errors name the user's path.

The full disk is simulated by making the low-level write or the delivery of a file raise
``OSError(ENOSPC)``; ``kill -9`` is sent to a real ``drillstring fit`` child stopped before a
chosen step of its writing (each change of the file system under the output folder's parent
waits for the test's go, so the kill lands at a known step however loaded the machine is).
"""

from __future__ import annotations

import errno
import io
import json
import os
import random
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from _children import CHILD_PROLOGUE, Child
from _cli import one_line_error, run_cli

import drillstring as ds
from drillstring import _core
from drillstring.drilling import FILES
from drillstring.drilling.output import MARKER, PLOT_FILES
from drillstring.io import output as io_output
from drillstring.io.output import ASIDE_TAG, LOCK, STAGE_TAG, OutputError, lock_directory

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"
WELL_B = ROOT / "examples" / "aarsnes-shor-well-b.toml"
SHORT = ["--set", "numerics.duration=2", "--set", "numerics.cells=60", "--set", "numerics.field_interval=0.5"]
NO_PLOT_FILES = sorted(set(FILES) - set(PLOT_FILES))


def snapshot(folder: Path, lock: bool = True) -> dict[str, bytes]:
    """Every entry of ``folder`` (name -> bytes; a directory's name -> b"<dir>"); without the
    lock file with ``lock=False`` (``kill -9`` leaves it: the next run takes it over)."""
    return {p.name: (b"<dir>" if p.is_dir() else p.read_bytes()) for p in sorted(folder.iterdir())
            if lock or p.name != LOCK}


def beside(folder: Path) -> list[str]:
    """The hidden leftovers of a replacement next to ``folder``."""
    return sorted(p.name for p in folder.parent.iterdir() if p.name.startswith(f".{folder.name}."))


def disk_full_at(monkeypatch: pytest.MonkeyPatch, count: int) -> list[str]:
    """Makes the ``count``-th delivery of a file (0-based; the marker file not counted) fail as
    on a full disk; returns the list of the files delivered before (their names)."""
    delivered: list[str] = []
    real = io_output._deliver

    def deliver(tmp: str, target: Any) -> None:
        if os.path.basename(target.real) == MARKER:
            return real(tmp, target)
        if len(delivered) == count:
            raise OSError(errno.ENOSPC, "No space left on device")
        real(tmp, target)
        delivered.append(os.path.basename(target.real))

    monkeypatch.setattr(io_output, "_deliver", deliver)
    return delivered


# --------------------------------------------------------------------------- a full disk mid-write (drill)


def test_a_full_disk_mid_write_leaves_the_old_drill_folder_whole(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT)[0] == 0
    (out / "notes.txt").write_text("the user's own notes\n")
    old = snapshot(out)
    with monkeypatch.context() as m:
        delivered = disk_full_at(m, 2)  # series.parquet and series.csv written, then the disk is full
        code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots",
                               "--set", "top_drive.rpm=60")
    assert delivered == ["series.parquet", "series.csv"]
    assert code == 2
    line = one_line_error(err, f"cannot write {out / 'metrics.json'}", "No space left on device")
    assert STAGE_TAG not in line
    assert snapshot(out) == old  # the complete old set: no new series.csv beside the old config.toml
    assert beside(out) == []
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")[0] == 0
    assert sorted(p.name for p in out.iterdir()) == sorted([*NO_PLOT_FILES, "notes.txt"])
    assert (out / "notes.txt").read_text() == "the user's own notes\n"


def test_a_full_disk_at_any_file_of_the_api_save_keeps_the_old_set(tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    old_run, new_run = ds.drill(cfg), ds.drill(cfg.with_overrides(["top_drive.rpm=60"]))
    out = tmp_path / "out"
    old_run.save(out, plots=True)
    old = snapshot(out)
    with monkeypatch.context() as m:  # how many files a save delivers
        count = disk_full_at(m, 10**6)
        new_run.save(tmp_path / "count", plots=False)
    assert len(count) == len(NO_PLOT_FILES)
    for n in range(len(count)):
        with monkeypatch.context() as m:
            disk_full_at(m, n)
            with pytest.raises(OutputError) as info:
                new_run.save(out, plots=False)
        assert info.value.errno == errno.ENOSPC and info.value.filename == str(out / count[n])
        assert snapshot(out) == old, n
        assert beside(out) == []
    written = new_run.save(out, plots=False)
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES
    assert sorted(written) == sorted(out / name for name in NO_PLOT_FILES)


@pytest.mark.parametrize("step", ["carry", "lock", "exchange"])
def test_a_failure_at_the_swap_keeps_the_old_set(step: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    out = tmp_path / "out"
    ds.drill(cfg).save(out, plots=False)
    (out / "notes.txt").write_text("kept\n")
    old = snapshot(out)

    def full(*args: object, **kwargs: object) -> Any:
        raise OSError(errno.ENOSPC, "No space left on device")

    with monkeypatch.context() as m:
        if step == "carry":
            m.setattr(io_output, "_link_or_copy", full)
        elif step == "lock":  # the new folder's own lock, taken before the exchange
            real_lock = io_output.lock_directory
            m.setattr(io_output, "lock_directory",
                      lambda d, **kw: full() if STAGE_TAG in os.fspath(d) else real_lock(d, **kw))
        else:
            m.setattr(io_output, "_exchange", full)
        with pytest.raises(OutputError) as info:
            ds.drill(cfg.with_overrides(["top_drive.rpm=60"])).save(out, plots=False)
    assert info.value.filename == str(out) and "No space left" in str(info.value)
    assert snapshot(out) == old and beside(out) == []


# --------------------------------------------------------------------------- torque-drag


def test_a_full_disk_mid_write_leaves_the_old_torque_drag_folder_whole(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    well = ROOT / "examples" / "s-well-3d.toml"
    out = tmp_path / "td"
    assert run_cli(capsys, "torque-drag", str(well), "--out", str(out))[0] == 0  # with figures
    old = snapshot(out)
    assert "well_path.png" in old
    with monkeypatch.context() as m:
        delivered = disk_full_at(m, 3)
        code, _, err = run_cli(capsys, "torque-drag", str(well), "--out", str(out), "--no-plots",
                               "--set", "friction.static=0.3")
    assert code == 2 and delivered == ["torque_drag.json", "profiles.csv", "broomstick.csv"]
    one_line_error(err, f"cannot write {out / 'survey.csv'}", "No space left on device")
    assert snapshot(out) == old and beside(out) == []
    assert run_cli(capsys, "torque-drag", str(well), "--out", str(out), "--no-plots")[0] == 0
    assert sorted(p.name for p in out.iterdir()) == sorted(["torque_drag.json", "profiles.csv", "broomstick.csv",
                                                            "survey.csv", "config.toml", "report.md"])


# --------------------------------------------------------------------------- drill-map's final files


def tree(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` (relative path -> bytes), the lock file left out."""
    return {os.fspath(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != LOCK}


def test_a_full_disk_at_a_maps_final_files_keeps_the_earlier_set_and_the_store(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "map"
    command = ["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", str(out), *SHORT,
               "--threads", "1", "--chunk-size", "1"]
    assert run_cli(capsys, *command)[0] == 0
    old = tree(out)
    assert {"map.parquet", "map.csv", "config.toml", "ssi_lines.png", "chunks/chunk-00001.parquet"} <= set(old)
    with monkeypatch.context() as m:
        disk_full_at(m, 1)  # map.parquet written beside, then the disk is full
        code, _, err = run_cli(capsys, *command, "--no-plots")
    assert code == 2
    line = one_line_error(err, f"cannot write {out / 'map.csv'}", "No space left on device")
    assert STAGE_TAG not in line
    assert tree(out) == old and beside(out) == []  # the earlier figures, tables and store as they were
    code, printed, err = run_cli(capsys, *command, "--no-plots")  # resumes: every chunk reused
    assert code == 0, err
    assert "recomputed" not in printed + err
    new = tree(out)
    assert "ssi_lines.png" not in new and {name: old[name] for name in new if name.startswith("chunks/")} == {
        name: data for name, data in new.items() if name.startswith("chunks/")}
    assert sorted(p.name for p in out.iterdir()) == ["chunks", "config.toml", "manifest.json", "map.csv",
                                                     "map.parquet"]


def test_ctrl_c_while_a_maps_figures_are_drawn_keeps_the_earlier_set_and_the_resume(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    from drillstring.io import figures

    out = tmp_path / "map"
    command = ["drill-map", str(EXAMPLE), "--axis", "top_drive.rpm=40,60", "--out", str(out), *SHORT,
               "--threads", "1", "--chunk-size", "1"]
    assert run_cli(capsys, *command, "--no-plots")[0] == 0
    old = tree(out)

    def interrupted(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(figures, "save", interrupted)
        code, _, err = run_cli(capsys, *command, "--units", "field")
    assert code == 130 and "the same command resumes the map" in err
    assert tree(out) == old and beside(out) == []  # no figure beside the earlier tables, the store whole
    code, printed, err = run_cli(capsys, *command, "--units", "field")
    assert code == 0 and "recomputed" not in printed + err
    assert "ssi_lines.png" in tree(out)


# --------------------------------------------------------------------------- a full disk at the lock


def test_a_full_disk_at_the_lock_names_the_path_and_leaves_no_lock_file(tmp_path: Path,
                                                                        capsys: pytest.CaptureFixture[str],
                                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    real_write, real_fdopen = os.write, os.fdopen

    def is_lock(fd: int) -> bool:
        return os.readlink(f"/proc/self/fd/{fd}").endswith(os.sep + LOCK)

    def write(fd: int, data: Any) -> int:
        if is_lock(fd):
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_write(fd, data)

    class Full(io.FileIO):
        def write(self, data: Any) -> int:
            raise OSError(errno.ENOSPC, "No space left on device")

    def fdopen(fd: int, *args: Any, **kwargs: Any) -> Any:
        if not is_lock(fd):
            return real_fdopen(fd, *args, **kwargs)
        return io.TextIOWrapper(io.BufferedRandom(Full(fd, "r+")), encoding="utf-8")

    if not os.path.exists("/proc/self/fd"):  # pragma: no cover - not Linux
        pytest.skip("needs /proc/self/fd")
    out = tmp_path / "out"
    out.mkdir()
    (out / LOCK).write_text("process 1 on a host that was killed\n")  # a stale lock file, too
    fresh = tmp_path / "fresh"
    for folder in (out, fresh):
        with monkeypatch.context() as m:
            m.setattr(os, "write", write)
            m.setattr(os, "fdopen", fdopen)
            code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(folder), *SHORT, "--no-plots")
        assert code == 2
        one_line_error(err, f"cannot write {folder / LOCK}", "No space left on device")
        assert "[Errno" not in err
    assert list(out.iterdir()) == [] and not fresh.exists()
    with monkeypatch.context() as m:
        m.setattr(os, "write", write)
        m.setattr(os, "fdopen", fdopen)
        with pytest.raises(OutputError) as info:
            lock_directory(out, field="out", busy="{holder}")
    assert info.value.filename == str(out / LOCK) and info.value.errno == errno.ENOSPC
    assert list(out.iterdir()) == []
    lock_directory(out, field="out", busy="{holder}").close()  # with room again it works


# --------------------------------------------------------------------------- leftovers of an interrupted swap


def test_leftovers_beside_the_folder_are_removed_and_an_old_set_moved_aside_is_put_back(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")[0] == 0
    stage = tmp_path / f".out{STAGE_TAG}0123456789ab"  # a new set being written when the run was killed
    stage.mkdir()
    (stage / "series.csv").write_text("half\n")
    aside = tmp_path / f".out{ASIDE_TAG}0123456789ab"  # an old set, after the new one was moved in
    aside.mkdir()
    (aside / "report.md").write_text("old\n")
    unrelated = tmp_path / ".out.other"
    unrelated.mkdir()
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")[0] == 0
    assert not stage.exists() and not aside.exists() and unrelated.exists()
    # killed between moving the old folder aside and the new one in (no atomic exchange): put back
    old = snapshot(out)
    out.rename(aside)
    (tmp_path / f".out{STAGE_TAG}0123456789ab").mkdir()

    def interrupted(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    with monkeypatch.context() as m:  # a run stopped while solving: nothing written, but the old set is back
        m.setattr(_core, "drill_solve", interrupted)
        code, _, err = run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")
    assert code == 130
    assert snapshot(out) == old and not aside.exists()
    assert run_cli(capsys, "drill", str(EXAMPLE), "--out", str(out), *SHORT, "--no-plots")[0] == 0
    assert beside(out) == [".out.other"]


def test_without_an_atomic_exchange_the_folder_is_swapped_by_two_renames(tmp_path: Path,
                                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    out = tmp_path / "out"
    ds.drill(cfg).save(out, plots=True)
    monkeypatch.setattr(io_output, "_exchange", lambda a, b: False)
    ds.drill(cfg).save(out, plots=False)
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES and beside(out) == []


@pytest.mark.parametrize("why", ["mount point", "parent not writable"])
def test_a_folder_that_cannot_be_swapped_is_written_in_place(why: str, tmp_path: Path,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    out = tmp_path / "out"
    ds.drill(cfg).save(out, plots=True)
    real_mkdir = os.mkdir

    def mkdir(path: Any, *args: Any, **kwargs: Any) -> None:
        if STAGE_TAG in os.fspath(path):
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        real_mkdir(path, *args, **kwargs)

    if why == "mount point":
        monkeypatch.setattr(io_output.os.path, "ismount", lambda p: os.fspath(p) == str(out))
    else:
        monkeypatch.setattr(os, "mkdir", mkdir)
    inode = out.stat().st_ino
    written = ds.drill(cfg).save(out, plots=False)
    assert out.stat().st_ino == inode  # the same folder, written file by file
    assert sorted(p.name for p in out.iterdir()) == NO_PLOT_FILES  # the stale figures removed, no marker
    assert sorted(written) == sorted(out / name for name in NO_PLOT_FILES) and beside(out) == []


def test_a_symlinked_folder_stays_a_link_and_the_working_directory_follows(tmp_path: Path,
                                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(["numerics.duration=1", "numerics.cells=40"])
    real = tmp_path / "real"
    real.mkdir()
    (real / "sub").mkdir()
    (real / "sub" / "kept.txt").write_text("kept\n")
    (tmp_path / "link").symlink_to(real)
    monkeypatch.chdir(real / "sub")
    written = ds.drill(cfg).save(tmp_path / "link", plots=False)
    assert (tmp_path / "link").is_symlink() and sorted(written)[0].parent == tmp_path / "link"
    assert sorted(p.name for p in real.iterdir()) == sorted([*NO_PLOT_FILES, "sub"])
    assert Path("kept.txt").read_text() == "kept\n"  # the working directory is the new folder's sub
    assert os.path.samefile(os.getcwd(), real / "sub")


# --------------------------------------------------------------------------- kill -9 of a real fit

CHILD = """
import os, shutil, sys
from drillstring.io import output as o

name = sys.argv[1]
step = 0

def pause(op, *paths):
    global step
    paths = [p for p in paths if isinstance(p, (str, bytes, os.PathLike))]
    if any(name in os.fsdecode(os.fspath(p)) for p in paths):
        print(f"@@ {step} {op} {' '.join(os.path.basename(os.fsdecode(os.fspath(p))) for p in paths)}", flush=True)
        step += 1
        if sys.stdin.readline().strip() != "go":
            os._exit(9)

def hook(module, attr):
    real = getattr(module, attr)
    def wrapped(*args, **kwargs):
        pause(attr, *args[:2])
        return real(*args, **kwargs)
    setattr(module, attr, wrapped)

for attr in ("replace", "rename", "unlink", "mkdir", "rmdir", "link"):
    hook(os, attr)
hook(shutil, "rmtree")
if hasattr(o, "_exchange"):
    hook(o, "_exchange")
from drillstring.cli import main
code = main(sys.argv[2:])
print(f"@@ done {code}", flush=True)
"""


@pytest.fixture(scope="module")
def fit_inputs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """A short well (Well B, 100 cells, 4 s) and its start-up's surface series."""
    folder = tmp_path_factory.mktemp("fit-inputs")
    cfg = ds.load_drill_config(WELL_B).with_overrides({"numerics.cells": 100, "numerics.duration": 4.0,
                                                       "numerics.field_interval": 0.0})
    cfg.save(folder / "well.toml")
    run = ds.drill(cfg)
    rng = np.random.default_rng(1)
    pd.DataFrame({"t": run.t[::5], "surface_rpm": run.surface_rpm[::5],
                  "motor_torque": run.motor_torque[::5] + rng.normal(0.0, 200.0, run.t[::5].size)}
                 ).to_csv(folder / "data.csv", index=False)
    return folder / "well.toml", folder / "data.csv"


def _fit_args(inputs: tuple[Path, Path], out: Path, *extra: str) -> list[str]:
    return ["fit", str(inputs[0]), "--data", str(inputs[1]), "--param", "friction.static=0.1:0.6",
            "--samples", "4", "--no-landscape", "--threads", "1", "--out", str(out), *extra]


def _fit_child(args: list[str], cwd: Path) -> Child:
    proc = subprocess.Popen([sys.executable, "-c", CHILD_PROLOGUE + textwrap.dedent(CHILD), *args], cwd=cwd,
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    return Child(proc)


def _steps(child: Child, until: int) -> list[str]:
    """Lets the child take its steps up to ``until`` (exclusive) and returns them; it is then
    stopped before step ``until`` (or has finished: the last entry is ``done N``)."""
    assert child.proc.stdin is not None
    seen: list[str] = []
    while True:
        line = child.read_line(timeout=300)
        if not line.startswith("@@ "):
            continue
        seen.append(line[3:])
        if line.startswith("@@ done") or len(seen) > until:
            return seen
        child.proc.stdin.write(b"go\n")
        child.proc.stdin.flush()


def _complete_new_set(out: Path, others: set[str]) -> bool:
    """Whether ``out`` holds a complete ``--no-plots`` fit (and the user's ``others``)."""
    names = {p.name for p in out.iterdir()} - {LOCK}
    if names != {"config.toml", "fit.json", "fit_series.csv", "report.md", *others}:
        return False
    json.loads((out / "fit.json").read_text())
    ds.load_drill_config(out / "config.toml")
    return (out / "report.md").read_text().endswith("\n")


def test_a_fit_killed_at_any_step_of_writing_leaves_the_old_or_the_new_set(tmp_path: Path, fit_inputs: Any,
                                                                          capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "calibrated-k9"
    from drillstring.cli import main

    assert main(_fit_args(fit_inputs, out, "--param", "friction.kinetic_ratio=0.3:0.95")) == 0  # with figures
    capsys.readouterr()
    (out / "notes.txt").write_text("the user's notes\n")
    old = snapshot(out)
    assert {"fit_series.png", "report.md"} <= set(old)
    pristine = tmp_path / "pristine"
    shutil.copytree(out, pristine)
    args = [out.name, *_fit_args(fit_inputs, out, "--no-plots")]
    counting = tmp_path / "count"
    counting.mkdir()
    shutil.copytree(pristine, counting / out.name)
    child = _fit_child([out.name, *_fit_args(fit_inputs, counting / out.name, "--no-plots")], tmp_path)
    try:
        steps = _steps(child, 10**6)
    finally:
        child.kill()
    assert steps[-1] == "done 0", steps
    assert _complete_new_set(counting / out.name, {"notes.txt"})
    steps = steps[:-1]
    swap = [i for i, s in enumerate(steps) if s.split()[1] in ("_exchange", "rename")]
    sample = random.Random(36).sample(range(len(steps)), min(4, len(steps)))
    chosen = {0, len(steps) - 1, *swap, *(i + 1 for i in swap), *sample}
    outcomes = {}
    for k in sorted(chosen):
        for leftover in [out, *(tmp_path / name for name in beside(out))]:  # the same steps each time
            shutil.rmtree(leftover)
        shutil.copytree(pristine, out)
        child = _fit_child(args, tmp_path)
        try:
            seen = _steps(child, k)
            assert len(seen) == k + 1 and not seen[-1].startswith("done"), (k, seen)
        finally:
            child.kill()  # kill -9 (the whole group) while stopped before step k
        if snapshot(out, lock=False) == old:
            outcomes[k] = "old"
        else:
            assert _complete_new_set(out, {"notes.txt"}), (k, steps[k], sorted(p.name for p in out.iterdir()))
            outcomes[k] = "new"
        assert (out / "notes.txt").read_text() == "the user's notes\n"
    assert swap, steps  # the folder was swapped in, not written file by file
    assert "old" in outcomes.values() and "new" in outcomes.values(), outcomes
    # the next fit cleans what the killed one left beside the folder
    assert beside(out)
    assert main(_fit_args(fit_inputs, out, "--no-plots")) == 0
    assert _complete_new_set(out, {"notes.txt"}) and beside(out) == []
