"""The README as a new user meets it: a fresh virtual environment, `pip install .` from the
checkout, then every shell command and Python example of the README, as written. The commands of
the documentation pages (docs/) parse with the CLI's parser, and their Python examples run.

This builds an environment and installs the package and its dependencies from the package
index, so it runs only where ``DRILLSTRING_README_VENV=1`` is set (``.ci/run`` sets it: once per
CI run). The install reuses the checkout's compiled core (cargo's ``target/`` is up to date
after the CI's own install), so it adds no second release build.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import _docs
import pytest

from drillstring.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

needs_fresh_env = pytest.mark.skipif(
    os.environ.get("DRILLSTRING_README_VENV") != "1",
    reason="builds a fresh environment from the package index: set DRILLSTRING_README_VENV=1 (CI does)",
)

#: Commands that cannot run on one machine without a cluster, or are this suite itself.
NOT_HERE = {
    "dask scheduler": "starts a long-running cluster scheduler",
    "dask worker": "needs a running scheduler",
    "--scheduler tcp://HEAD:8786": "needs a cluster",
    "cargo test": "the test suite itself (CI runs it)",
}

#: Seconds one README command may take (the paper, the slowest, takes ~15 s on 2 cores).
COMMAND_TIMEOUT = 600


def _blocks(language: str) -> list[str]:
    text = README.read_text(encoding="utf-8")
    return re.findall(rf"^```{language}\n(.*?)^```", text, flags=re.S | re.M)


def _commands(blocks: list[str] | None = None) -> list[str]:
    """Every shell command of the README (comments removed), in order, or of ``blocks``."""
    commands = []
    for block in _blocks("bash") if blocks is None else blocks:
        for line in block.splitlines():
            command = line.split(" #", 1)[0].strip()
            if command and not command.startswith("#"):
                commands.append(command)
    return commands


def test_the_readme_has_its_two_commands_near_the_top() -> None:
    commands = _commands()
    assert commands[0] == "python3 -m pip install . && drillstring paper --out paper-output"
    assert commands[1].startswith("python3 -m pip install '.[test]' && cargo test")


@pytest.fixture(scope="module")
def fresh_env(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A new virtual environment (no system site-packages) with nothing installed but pip."""
    env = tmp_path_factory.mktemp("venv") / "env"
    venv.EnvBuilder(with_pip=True, clear=True).create(env)
    return env


@needs_fresh_env
def test_every_readme_command_and_example_runs_in_a_fresh_environment(fresh_env: Path, tmp_path: Path) -> None:
    bin_dir = fresh_env / "bin"
    environ = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}",
               "VIRTUAL_ENV": str(fresh_env), "MPLBACKEND": "Agg"}
    environ.pop("PYTHONPATH", None)
    work = tmp_path / "work"  # where the commands write their outputs (not the checkout)
    shutil.copytree(ROOT / "examples", work / "examples")
    ran = []
    for command in _commands():
        if any(marker in command for marker in NOT_HERE):
            continue
        # `pip install .` installs the checkout: run it there; every other command in `work`
        is_install = command.startswith("python3 -m pip install")
        install, _, rest = command.partition(" && ") if is_install else ("", "", command)
        for part, cwd in ((install, ROOT), (rest, work)):
            if not part:
                continue
            done = subprocess.run(
                ["bash", "-c", part], cwd=cwd, env=environ, capture_output=True, text=True, timeout=COMMAND_TIMEOUT
            )
            output = f"{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
            assert done.returncode == 0, f"{part!r} failed ({done.returncode}):\n{output}"
            ran.append(part)
    assert any(c.startswith("python3 -m pip install .") for c in ran) and any("drillstring paper" in c for c in ran)
    # The installed package is the fresh environment's, not the checkout's.
    where = subprocess.run(["python3", "-c", "import drillstring; print(drillstring.__file__)"], cwd=work,
                           env=environ, capture_output=True, text=True, check=True).stdout
    assert str(fresh_env) in where, where
    # the live display's page and its vendored plotting library ship inside the installed package
    static = Path(where.strip()).parent / "live" / "static"
    assert all((static / name).is_file() for name in ("index.html", "app.js", "style.css", "vendor/dygraph.min.js"))
    assert (work / "paper-output" / "report.html").exists() and (work / "run.csv").exists()
    # Every Python example, as written, with the fresh environment's interpreter.
    for number, block in enumerate(_blocks("python")):
        script = work / f"example_{number}.py"
        script.write_text(block, encoding="utf-8")
        done = subprocess.run([str(bin_dir / "python3"), str(script)], cwd=work, env=environ,
                              capture_output=True, text=True, timeout=COMMAND_TIMEOUT)
        assert done.returncode == 0, f"README Python example {number} failed:\n{block}\n{done.stderr[-3000:]}"
    print(f"ran {len(ran)} README commands and {len(_blocks('python'))} Python examples in {fresh_env} "
          f"({sys.version.split()[0]})")


def _parsed(commands: list[str]) -> list[str]:
    """The subcommand of every ``drillstring ...`` command, each parsed by the CLI's parser."""
    parsed = []
    for command in commands:
        for part in command.split(" && "):
            argv = shlex.split(part)
            if argv[0] != "drillstring":
                continue
            try:
                args = build_parser().parse_args(argv[1:])
            except SystemExit as exc:  # argparse's usage error
                raise AssertionError(f"README command {part!r} is refused by the CLI") from exc
            assert args.command == argv[1], part
            parsed.append(argv[1])
    return parsed


def test_every_drillstring_command_of_the_readme_is_one_the_cli_accepts() -> None:
    """The README's ``drillstring ...`` commands, split as a shell would, parse with the CLI's own
    parser (an option or command renamed in the CLI and not in the README fails here)."""
    parsed = _parsed(_commands())
    assert {"paper", "simulate", "table2", "pde", "convergence", "drill", "drill-map", "lumped",
            "sweep"} <= set(parsed), parsed


def test_every_drillstring_command_of_the_documentation_is_one_the_cli_accepts() -> None:
    pages = [p for p in _docs.pages() if p != README]
    parsed = _parsed(_commands(_docs.blocks("bash", pages)))
    assert {"paper", "simulate", "pde", "sweep", "drill", "drill-map", "torque-drag"} <= set(parsed), parsed


#: Examples that other tests run and check (tests/test_api.py, test_lumped.py, test_stickslip_metrics.py,
#: test_docs_claims.py, test_rig_log.py: the rig-log example reads the shared log beside the repository).
RUN_ELSEWHERE = ("res.to_xarray()", "ds.sweep(", "lumped_equilibria", "stick_slip_metrics", "ds.fit(",
                 "ds.rig_log(")


def test_every_python_example_of_the_documentation_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The README's and the pages' Python examples, as written, from a folder holding the
    checkout's ``examples/`` (the fresh-environment test above runs the README's once more)."""
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    examples = [b for b in _docs.blocks("python") if not any(marker in b for marker in RUN_ELSEWHERE)]
    assert len(examples) >= 5
    for number, block in enumerate(examples):
        exec(compile(block, f"documentation example {number}", "exec"), {"__name__": "__example__"})
