"""What an output does to whatever is at its path (files, symlinks, devices, FIFOs, standard output).

* a regular file or a new path: replaced atomically (temporary file beside it, fsync, rename);
* a symlink (a chain, a dangling one): written through, the link stays a link;
* a character device (here a pty), a FIFO or "-": the bytes are streamed into it;
* block devices, directories, sockets and the command's own input files are refused;
* every destination is checked before any solving, and errors name the path the user gave;
* a closed or failing standard output is an error with exit status 2.

Special files are made in the test's temporary directory (FIFOs, sockets, a block node of the
non-existent device 0:0, a pty from os.openpty); no test writes to a real device node.
"""

from __future__ import annotations

import errno
import importlib
import os
import select
import shutil
import socket
import stat
import subprocess
import sys
import threading
import tty
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest
from _cli import one_line_error, run_cli

import drillstring as ds
from drillstring.io.output import OutputError, atomic_write, check_destination, command_inputs, write_bytes
from drillstring.studies.table2 import Table2Row, write_table2_csv

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX special files")

QUICK = ["--t-end", "0.01", "--samples", "21"]  # 20 samples per period of mode 3: no warning


def reference_csv(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> bytes:
    """The CSV of `simulate QUICK` written to a plain new file."""
    plain = tmp_path / "reference-output.csv"
    assert run_cli(capsys, "simulate", *QUICK, "--out", str(plain))[0] == 0
    data = plain.read_bytes()
    plain.unlink()
    return data


def refuse_call(monkeypatch: pytest.MonkeyPatch, module: str, name: str) -> None:
    """Makes ``module.name`` fail the test if called: the check must come before any work."""

    def called(*args: Any, **kwargs: Any) -> None:
        raise AssertionError(f"{module}.{name} was called before the output was checked")

    monkeypatch.setattr(importlib.import_module(module), name, called)


def read_fifo_in_thread(path: Path) -> tuple[threading.Thread, list[bytes]]:
    got: list[bytes] = []

    def reader() -> None:
        with open(path, "rb") as handle:  # blocks until the writer opens the FIFO
            got.append(handle.read())

    thread = threading.Thread(target=reader, daemon=True)
    thread.start()
    return thread, got


# --------------------------------------------------------------------------- regular files, symlinks


def test_a_regular_file_is_replaced_atomically_and_keeps_its_permissions(tmp_path, capsys):
    expected = reference_csv(tmp_path, capsys)
    out = tmp_path / "run.csv"
    out.write_text("old results\n")
    out.chmod(0o640)
    code, stdout, _ = run_cli(capsys, "simulate", *QUICK, "--out", str(out))
    assert code == 0 and f"wrote {out}" in stdout
    assert out.read_bytes() == expected and not out.is_symlink()
    assert stat.S_IMODE(out.stat().st_mode) == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]


def test_a_symlink_chain_is_written_through_and_stays_a_link(tmp_path, capsys):
    expected = reference_csv(tmp_path, capsys)
    data_dir = tmp_path / "data"
    data_dir.mkdir()
    real = data_dir / "real.csv"
    real.write_text("old\n")
    first = tmp_path / "first.csv"
    first.symlink_to(real)
    second = tmp_path / "second.csv"
    second.symlink_to("first.csv")  # relative link to a link
    code, stdout, _ = run_cli(capsys, "simulate", *QUICK, "--out", str(second))
    assert code == 0 and f"wrote {second}" in stdout
    assert second.is_symlink() and os.readlink(second) == "first.csv"
    assert first.is_symlink() and os.readlink(first) == str(real)
    assert real.read_bytes() == expected and not real.is_symlink()
    assert sorted(p.name for p in data_dir.iterdir()) == ["real.csv"]  # no temporary left beside it


def test_a_dangling_symlink_creates_its_target(tmp_path, capsys):
    link = tmp_path / "link.csv"
    link.symlink_to(tmp_path / "new" / "target.csv")
    # the target's directory does not exist: refused before solving, naming the link
    code, _, err = run_cli(capsys, "simulate", *QUICK, "--out", str(link))
    assert code == 2
    one_line_error(err, "--out", str(link))
    (tmp_path / "new").mkdir()
    code, _, _ = run_cli(capsys, "simulate", *QUICK, "--out", str(link))
    assert code == 0 and link.is_symlink()
    assert (tmp_path / "new" / "target.csv").read_text().startswith("t,theta,theta_dot")


def test_an_interrupted_write_through_a_symlink_leaves_the_target_and_no_temporary(tmp_path):
    (tmp_path / "a").mkdir()
    target = tmp_path / "a" / "target.txt"
    target.write_text("old\n")
    link = tmp_path / "link.txt"
    link.symlink_to(target)

    def writer(path: str) -> None:
        Path(path).write_text("half of the new content")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(link, writer)
    assert target.read_text() == "old\n" and link.is_symlink()
    assert [p.name for p in (tmp_path / "a").iterdir()] == ["target.txt"]
    assert write_bytes(link, b"new\n") == link
    assert target.read_text() == "new\n" and link.is_symlink()


def test_python_writers_go_through_the_same_mechanism(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    links = {}
    for name in ("steel.toml", "table2.csv", "run.csv", "field.npz", "plot.svg"):
        (real / name).write_text("old")
        links[name] = tmp_path / name
        links[name].symlink_to(real / name)
    assert ds.preset("steel").save(links["steel.toml"]) == links["steel.toml"]
    rows = [Table2Row("Runge-Kutta", 1e-4, 5.061e-4, 0.0)]
    assert write_table2_csv(rows, links["table2.csv"]) == links["table2.csv"]
    res = ds.solve_pde(ds.preset("aluminum"), nodes=12, t_end=0.01, samples=5)
    assert res.to_csv(links["run.csv"], 10.0) == links["run.csv"]
    assert res.save_field(tmp_path / "field") == links["field.npz"]  # .npz appended, then the link followed
    assert ds.plots.save(ds.plots.space_time(res, 10.0), links["plot.svg"]) == links["plot.svg"]
    assert all(link.is_symlink() for link in links.values())
    assert ds.load(real / "steel.toml") == ds.preset("steel")
    assert (real / "table2.csv").read_text().splitlines()[0] == "method,dt,max_amplitude,difference_percent"
    assert (real / "run.csv").read_text().startswith("t,theta,theta_dot")
    with np.load(real / "field.npz") as data:
        assert data["theta"].shape == (12, 5)
    assert (real / "plot.svg").read_text().lstrip().startswith("<?xml")
    assert sorted(p.name for p in real.iterdir()) == sorted(links)


def test_convergence_files_go_through_the_same_mechanism(tmp_path):
    from drillstring.studies import convergence

    result = convergence.study(ds.preset("aluminum"), t_end=0.01, samples=11, modes=(1,), cells=8, max_nodes=33,
                               tol=1e-2)
    out = tmp_path / "out"
    out.mkdir()
    elsewhere = tmp_path / "elsewhere.csv"
    elsewhere.write_text("old")
    (out / "grids.csv").symlink_to(elsewhere)
    os.mkfifo(out / "reference.csv")
    thread, got = read_fifo_in_thread(out / "reference.csv")
    paths = convergence.write(result, out)
    thread.join(10)
    assert [p.name for p in paths] == list(convergence.FILES)
    assert got and got[0].startswith(b"t,theta_reference")
    assert stat.S_ISFIFO((out / "reference.csv").lstat().st_mode)
    assert (out / "grids.csv").is_symlink() and elsewhere.read_text().startswith("nodes,grid_spacing_m")
    assert (out / "convergence.png").read_bytes()[:4] == b"\x89PNG"


# --------------------------------------------------------------------------- streams: FIFO, pty, "-"


def test_a_fifo_gets_the_csv_streamed_and_stays_a_fifo(tmp_path, capsys):
    expected = reference_csv(tmp_path, capsys)
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    thread, got = read_fifo_in_thread(fifo)
    code, stdout, _ = run_cli(capsys, "simulate", *QUICK, "--out", str(fifo))
    thread.join(10)
    assert code == 0 and f"wrote {fifo}" in stdout
    assert got == [expected]
    assert stat.S_ISFIFO(fifo.lstat().st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipe"]


def test_a_plot_to_a_fifo_is_a_png_without_an_appended_extension(tmp_path):
    fifo = tmp_path / "plot"
    os.mkfifo(fifo)
    res = ds.simulate(ds.preset("aluminum"), modes=1, t_end=0.01, samples=5)
    thread, got = read_fifo_in_thread(fifo)
    assert ds.plots.save(ds.plots.time_history_and_phase(res, 10.0), fifo) == fifo
    thread.join(10)
    assert got and got[0][:4] == b"\x89PNG"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plot"]


@pytest.fixture
def pty_device(tmp_path: Path) -> Iterator[tuple[Path, Callable[[int], bytes]]]:
    """A character device of our own: the slave side of a pty (raw mode, so no newline
    translation), reached through a symlink in the temporary directory; and a function that
    reads n bytes from the master side."""
    master, slave = os.openpty()
    tty.setraw(slave)
    link = tmp_path / "terminal"
    link.symlink_to(os.ttyname(slave))

    def read(n: int) -> bytes:
        data = b""
        while len(data) < n:
            ready, _, _ = select.select([master], [], [], 10)
            if not ready:
                break
            data += os.read(master, n - len(data))
        return data

    try:
        yield link, read
    finally:
        os.close(slave)
        os.close(master)


def test_a_character_device_is_streamed_into(tmp_path, capsys, pty_device):
    expected = reference_csv(tmp_path, capsys)
    link, read = pty_device
    got: list[bytes] = []
    thread = threading.Thread(target=lambda: got.append(read(len(expected))), daemon=True)
    thread.start()
    code, _, _ = run_cli(capsys, "simulate", *QUICK, "--out", str(link))
    thread.join(10)
    assert code == 0 and got == [expected]
    assert link.is_symlink() and stat.S_ISCHR(link.stat().st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["terminal"]


def test_dash_writes_the_csv_to_stdout_and_the_messages_to_stderr(tmp_path, capsys):
    expected = reference_csv(tmp_path, capsys)
    proc = subprocess.run([sys.executable, "-m", "drillstring", "simulate", *QUICK, "--out", "-"], cwd=tmp_path,
                          capture_output=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == expected
    assert b"dop853" in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no file named "-"


def test_an_output_to_the_file_stdout_is_redirected_to_goes_through_stdout(tmp_path, capsys):
    # `drillstring simulate --out run.csv > run.csv`: renaming a new file over run.csv would leave
    # stdout writing into the unlinked old one; the CSV is written through stdout instead
    expected = reference_csv(tmp_path, capsys)
    out = tmp_path / "run.csv"
    with open(out, "wb") as stdout:
        proc = subprocess.run([sys.executable, "-m", "drillstring", "simulate", *QUICK, "--out", str(out)],
                              stdout=stdout, stderr=subprocess.PIPE, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes() == expected
    assert "dop853" in proc.stderr and "wrote" not in proc.stderr


def test_parameters_save_to_dash_writes_toml_to_stdout(capsysbinary):
    ds.preset("steel").save("-")
    assert capsysbinary.readouterr().out == ds.preset("steel").to_toml().encode()


def test_two_outputs_to_stdout_are_refused_before_solving(capsys, monkeypatch):
    refuse_call(monkeypatch, "drillstring.cli.simulate", "simulate")
    code, _, err = run_cli(capsys, "simulate", *QUICK, "--out", "-", "--plot", "-")
    assert code == 2
    one_line_error(err, "--plot", "--out")


# --------------------------------------------------------------------------- refused destinations


@pytest.fixture
def special_files(tmp_path: Path) -> Iterator[dict[str, Path]]:
    files = {"a directory": tmp_path / "dir"}
    files["a directory"].mkdir()
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    files["a socket"] = tmp_path / "sock"
    sock.bind(str(files["a socket"]))
    try:
        # device 0:0 does not exist: opening this node fails with ENXIO, so nothing can reach a disk
        os.mknod(tmp_path / "blk", stat.S_IFBLK | 0o600, os.makedev(0, 0))
        files["a block device"] = tmp_path / "blk"
    except (PermissionError, AttributeError):  # no CAP_MKNOD: the other kinds are still tested
        pass
    try:
        yield files
    finally:
        sock.close()


def test_directories_sockets_and_block_devices_are_refused(capsys, monkeypatch, special_files):
    refuse_call(monkeypatch, "drillstring.cli.simulate", "simulate")
    for what, path in special_files.items():
        mode = path.lstat().st_mode
        code, _, err = run_cli(capsys, "simulate", *QUICK, "--out", str(path))
        assert code == 2
        one_line_error(err, "invalid --out", str(path), what)
        assert path.lstat().st_mode == mode
        with pytest.raises(ds.ValidationError) as info:
            write_bytes(path, b"x", field="out")
        assert info.value.field == "out" and what in info.value.allowed


def test_the_input_config_is_never_overwritten(tmp_path, capsys, monkeypatch):
    config = tmp_path / "config.toml"
    shutil.copy(Path(__file__).resolve().parents[1] / "examples" / "reference.toml", config)
    before = config.read_bytes()
    os.link(config, tmp_path / "hard.toml")
    (tmp_path / "soft.toml").symlink_to(config)
    refuse_call(monkeypatch, "drillstring.cli.simulate", "simulate")
    for out in ("config.toml", "hard.toml", "soft.toml"):
        code, _, err = run_cli(capsys, "simulate", str(config), "--out", str(tmp_path / out))
        assert code == 2
        one_line_error(err, "--out", str(tmp_path / out), str(config))
        assert config.read_bytes() == before and (tmp_path / "soft.toml").is_symlink()
    # and from Python: any writer refuses a declared input
    with command_inputs(config), pytest.raises(ds.ValidationError):
        ds.preset("steel").save(tmp_path / "hard.toml")
    assert config.read_bytes() == before
    ds.preset("steel").save(tmp_path / "other.toml")  # outside the block nothing is an input


def test_a_config_as_field_or_plot_of_pde_is_refused(tmp_path, capsys, monkeypatch):
    config = tmp_path / "config.toml"
    ds.preset("aluminum").save(config)  # [parameters] only: pde has no "modes"
    before = config.read_bytes()
    (tmp_path / "field.npz").symlink_to(config)
    refuse_call(monkeypatch, "drillstring.solvers.pde", "solve_pde")
    code, _, err = run_cli(capsys, "pde", str(config), "--field", str(tmp_path / "field"))
    assert code == 2
    one_line_error(err, "--field", "field.npz")
    assert config.read_bytes() == before


# --------------------------------------------------------------------------- checked before any work


@pytest.fixture
def unwritable_dir(tmp_path: Path) -> Iterator[Path]:
    """A directory in which no file can be created. Root ignores permission bits (chmod 555
    would not stop it), so as root the directory gets the immutable attribute (chattr +i): then
    even root cannot create files in it and access(2) reports it as not writable. Skipped where
    chattr is unavailable (no CAP_LINUX_IMMUTABLE, a file system without it)."""
    locked = tmp_path / "locked"
    locked.mkdir()
    if os.geteuid() != 0:
        locked.chmod(0o555)
        yield locked
        locked.chmod(0o755)
        return
    chattr = shutil.which("chattr")
    if chattr is None or subprocess.run([chattr, "+i", str(locked)], capture_output=True).returncode != 0:
        pytest.skip("chattr +i is not available here")
    try:
        assert not os.access(locked, os.W_OK)
        yield locked
    finally:
        subprocess.run([chattr, "-i", str(locked)], check=True)


def test_an_unwritable_directory_is_refused_before_solving(capsys, monkeypatch, unwritable_dir):
    refuse_call(monkeypatch, "drillstring.cli.simulate", "simulate")
    refuse_call(monkeypatch, "drillstring.solvers.pde", "solve_pde")
    refuse_call(monkeypatch, "drillstring.studies.convergence", "study")
    target = str(unwritable_dir / "run.csv")
    for args in (["simulate", "--out", target], ["simulate", "--plot", str(unwritable_dir / "p.png")],
                 ["pde", "--field", target], ["convergence", "--out", str(unwritable_dir / "conv")]):
        code, _, err = run_cli(capsys, *args)
        assert code == 2, args
        one_line_error(err, args[-2], args[-1], "writable")


@pytest.mark.parametrize(
    ("command", "module", "name", "extra"),
    [
        ("simulate", "drillstring.cli.simulate", "simulate", ["--out", "{bad}/run.csv"]),
        ("simulate", "drillstring.cli.simulate", "simulate", ["--plot", "{bad}/plot.png"]),
        ("pde", "drillstring.solvers.pde", "solve_pde", ["--out", "{bad}/run.csv"]),
        ("pde", "drillstring.solvers.pde", "solve_pde", ["--field", "{bad}/field"]),
        ("pde", "drillstring.solvers.pde", "solve_pde", ["--plot", "{bad}/map.png"]),
        ("convergence", "drillstring.studies.convergence", "study", ["--out", "{bad}/dir"]),
        ("paper", "drillstring.report", "reproduce", ["--out", "{bad}/dir"]),
        ("sweep", "drillstring.studies.sweeps", "sweep", ["--out", "{bad}/dir"]),
    ],
)
def test_a_destination_under_a_regular_file_is_refused_before_any_work(
    tmp_path, capsys, monkeypatch, command, module, name, extra
):
    # works as root too: nobody can create anything below a regular file (ENOTDIR)
    bad = tmp_path / "a-file"
    bad.write_text("not a directory\n")
    args = [arg.format(bad=bad) for arg in extra]
    if command == "sweep":
        sweep_file = tmp_path / "sweep.toml"
        sweep_file.write_text('[base]\npreset = "aluminum"\n[grid]\nlength = [100.0, 200.0]\n')
        args.insert(0, str(sweep_file))
    refuse_call(monkeypatch, module, name)
    code, _, err = run_cli(capsys, command, *args)
    assert code == 2
    one_line_error(err, args[-2], args[-1])
    assert bad.read_text() == "not a directory\n"


@pytest.mark.parametrize("command", ["convergence", "paper", "sweep"])
def test_an_output_directory_that_is_a_file_or_holds_a_directory_is_refused(tmp_path, capsys, monkeypatch, command):
    module, name = {"convergence": ("drillstring.studies.convergence", "study"), "paper": ("drillstring.report",
                                                                                           "reproduce"),
                    "sweep": ("drillstring.studies.sweeps", "sweep")}[command]
    refuse_call(monkeypatch, module, name)
    prefix = []
    if command == "sweep":
        sweep_file = tmp_path / "sweep.toml"
        sweep_file.write_text('[base]\npreset = "aluminum"\n[grid]\nlength = [100.0, 200.0]\n')
        prefix = [str(sweep_file)]
    a_file = tmp_path / "results"
    a_file.write_text("keep me\n")
    code, _, err = run_cli(capsys, command, *prefix, "--out", str(a_file))
    assert code == 2
    one_line_error(err, "--out", str(a_file), "directory")
    assert a_file.read_text() == "keep me\n"
    out = tmp_path / "out"
    inner = {"convergence": "convergence.csv", "paper": "report.md", "sweep": "results.csv"}[command]
    (out / inner).mkdir(parents=True)
    code, _, err = run_cli(capsys, command, *prefix, "--out", str(out))
    assert code == 2
    one_line_error(err, "--out", str(out / inner), "not a directory")


def test_paper_reproduce_checks_its_files_before_any_run(tmp_path, monkeypatch):
    from drillstring import report as paper

    refuse_call(monkeypatch, "drillstring.report", "_Runs")
    (tmp_path / "fig03.csv").mkdir()
    with pytest.raises(ds.ValidationError) as info:
        paper.reproduce(tmp_path, t_end_scale=0.1)
    assert info.value.field == "out_dir" and "fig03.csv" in str(info.value)


def test_check_destination_accepts_what_can_be_written(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "old.csv").write_text("x")
    for path in ("-", tmp_path / "new.csv", tmp_path / "old.csv", tmp_path / "fifo"):
        check_destination(path, field="--out")
    for directory in (tmp_path, tmp_path / "new" / "deeper"):
        check_destination(directory, field="--out", directory=True, files=("old.csv",))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "old.csv"]  # the check writes nothing


def test_a_failing_final_write_names_the_users_path_and_keeps_the_old_file(tmp_path, capsys, monkeypatch):
    out = tmp_path / "run.csv"
    out.write_text("old results\n")

    def disk_full(src: Any, dst: Any) -> None:
        raise OSError(errno.ENOSPC, "No space left on device", os.fspath(src))

    monkeypatch.setattr(os, "replace", disk_full)
    code, _, err = run_cli(capsys, "simulate", *QUICK, "--out", str(out))
    assert code == 2
    line = one_line_error(err, f"cannot write {out}", "No space left on device")
    assert ".run.csv" not in line
    assert out.read_text() == "old results\n" and sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]
    with pytest.raises(OutputError) as info:
        write_bytes(out, b"new")
    assert info.value.errno == errno.ENOSPC and info.value.filename == str(out)


# --------------------------------------------------------------------------- "wrote" names the file written


def test_wrote_messages_name_the_files_actually_written(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, stdout, _ = run_cli(capsys, "simulate", *QUICK, "--plot", "runplot")
    assert code == 0 and "wrote runplot.png" in stdout.splitlines()
    assert Path("runplot.png").read_bytes()[:4] == b"\x89PNG" and not Path("runplot").exists()
    code, stdout, _ = run_cli(capsys, "pde", *QUICK, "--nodes", "12", "--field", "field", "--plot", "map")
    assert code == 0
    assert {"wrote field.npz", "wrote map.png"} <= set(stdout.splitlines())
    assert Path("field.npz").is_file() and not Path("field").exists()


def test_an_unknown_plot_format_is_refused_before_solving(capsys, monkeypatch):
    refuse_call(monkeypatch, "drillstring.cli.simulate", "simulate")
    code, _, err = run_cli(capsys, "simulate", "--plot", "run.csv")
    assert code == 2
    one_line_error(err, "--plot", "run.csv", ".png")


# --------------------------------------------------------------------------- standard output must work


def test_table2_with_stdout_closed_exits_2():
    proc = subprocess.run(["sh", "-c", '"$0" -m drillstring table2 >&-', sys.executable], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2
    one_line_error(proc.stderr, "standard output", "closed")


def child_env(buffered: bool) -> dict[str, str]:
    """The environment of a child drillstring: stdout block-buffered (the default: the failure
    shows at the final flush) or unbuffered (it shows at the first print)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    if not buffered:
        env["PYTHONUNBUFFERED"] = "1"
    return env


@pytest.mark.parametrize("buffered", [True, False], ids=["buffered", "unbuffered"])
def test_table2_into_a_pipe_without_reader_exits_2(buffered):
    read_end, write_end = os.pipe()
    os.close(read_end)  # every write to the pipe now fails with EPIPE
    try:
        proc = subprocess.run([sys.executable, "-m", "drillstring", "table2"], stdout=write_end,
                              stderr=subprocess.PIPE, text=True, timeout=120, env=child_env(buffered))
    finally:
        os.close(write_end)
    assert proc.returncode == 2
    one_line_error(proc.stderr, "cannot write standard output", "Broken pipe")


@pytest.mark.parametrize("buffered", [True, False], ids=["buffered", "unbuffered"])
def test_table2_into_a_fifo_whose_reader_left_exits_2(tmp_path, buffered):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # lets the writer open it ...
    writer = os.open(fifo, os.O_WRONLY)
    os.close(reader)  # ... and then goes away
    try:
        proc = subprocess.run([sys.executable, "-m", "drillstring", "table2", "--json"], stdout=writer,
                              stderr=subprocess.PIPE, text=True, timeout=120, env=child_env(buffered))
    finally:
        os.close(writer)
    assert proc.returncode == 2
    one_line_error(proc.stderr, "cannot write standard output")


def test_a_dash_output_into_a_closed_pipe_exits_2():
    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        proc = subprocess.run([sys.executable, "-m", "drillstring", "simulate", *QUICK, "--out", "-"],
                              stdout=write_end, stderr=subprocess.PIPE, text=True, timeout=120, env=child_env(True))
    finally:
        os.close(write_end)
    assert proc.returncode == 2
    one_line_error(proc.stderr.splitlines()[-1], "cannot write standard output", "Broken pipe")
