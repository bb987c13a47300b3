"""The size of the package's units: no function longer than :data:`MAX_FUNCTION_LINES`, no Rust
source file longer than :data:`MAX_RUST_FILE_LINES`, and the command line one module per verb,
each with ``add_parser`` and ``run`` and listed in the registry."""

from __future__ import annotations

import ast
from pathlib import Path

import drillstring as ds
from drillstring import cli

PACKAGE = Path(ds.__file__).parent
CLI = PACKAGE / "cli"
RUST = Path(__file__).resolve().parent.parent / "rust"

#: The longest function (or method) of the package, lines from ``def`` to its last line.
MAX_FUNCTION_LINES = 150
#: The longest Rust source file under ``rust/``, lines.
MAX_RUST_FILE_LINES = 1000


def _long_functions(root: Path, limit: int) -> list[str]:
    """``file:line: name is N lines`` of every function under ``root`` longer than ``limit``."""
    found = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = (node.end_lineno or node.lineno) - node.lineno + 1
                if length > limit:
                    found.append(f"{path.relative_to(root.parent)}:{node.lineno}: {node.name} is {length} lines "
                                 f"(at most {limit})")
    return found


def test_no_function_is_longer_than_the_limit() -> None:
    assert _long_functions(PACKAGE, MAX_FUNCTION_LINES) == []


def test_the_size_check_finds_a_long_function(tmp_path: Path) -> None:
    package = tmp_path / "pkg"
    package.mkdir()
    body = "".join(f"    x{k} = {k}\n" for k in range(MAX_FUNCTION_LINES))
    (package / "long.py").write_text(f"def short():\n    pass\n\n\nasync def too_long():\n{body}")
    assert _long_functions(package, MAX_FUNCTION_LINES) == [
        f"pkg/long.py:5: too_long is {MAX_FUNCTION_LINES + 1} lines (at most {MAX_FUNCTION_LINES})"]


def _long_files(root: Path, limit: int) -> list[str]:
    """``file is N lines`` of every Rust source file under ``root`` (build output aside) longer
    than ``limit``."""
    found = []
    for path in sorted(root.rglob("*.rs")):
        if "target" in path.relative_to(root).parts:
            continue
        length = len(path.read_text(encoding="utf-8").splitlines())
        if length > limit:
            found.append(f"{path.relative_to(root.parent)} is {length} lines (at most {limit})")
    return found


def test_no_rust_file_is_longer_than_the_limit() -> None:
    assert RUST.is_dir(), f"no Rust sources at {RUST}"
    assert _long_files(RUST, MAX_RUST_FILE_LINES) == []


def test_the_size_check_finds_a_long_rust_file(tmp_path: Path) -> None:
    rust = tmp_path / "rust"
    (rust / "src").mkdir(parents=True)
    (rust / "target").mkdir()
    (rust / "src" / "short.rs").write_text("fn f() {}\n" * MAX_RUST_FILE_LINES)
    (rust / "src" / "long.rs").write_text("fn f() {}\n" * (MAX_RUST_FILE_LINES + 1))
    (rust / "target" / "generated.rs").write_text("fn f() {}\n" * (MAX_RUST_FILE_LINES + 1))
    assert _long_files(rust, MAX_RUST_FILE_LINES) == [
        f"rust/src/long.rs is {MAX_RUST_FILE_LINES + 1} lines (at most {MAX_RUST_FILE_LINES})"]


def _verb_modules() -> list[str]:
    """The modules of ``drillstring/cli/`` that are verbs: all but the package's own and the
    shared ones (a leading underscore)."""
    return sorted(p.stem for p in CLI.glob("*.py") if not p.stem.startswith("_"))


def test_every_verb_module_has_add_parser_and_run_and_is_registered() -> None:
    import importlib

    verbs = _verb_modules()
    assert sorted(cli.VERBS) == verbs
    for name in verbs:
        module = importlib.import_module(f"drillstring.cli.{name}")
        assert callable(getattr(module, "add_parser", None)), f"drillstring/cli/{name}.py has no add_parser"
        assert callable(getattr(module, "run", None)), f"drillstring/cli/{name}.py has no run"


def test_each_verb_runs_its_own_module() -> None:
    parser = cli.build_parser()
    subcommands = next(a for a in parser._actions if a.dest == "command").choices
    assert subcommands is not None
    assert sorted(subcommands) == sorted(name.replace("_", "-") for name in cli.VERBS)
    for verb, sub in subcommands.items():
        run = sub.get_default("func")
        assert run.__module__ == f"drillstring.cli.{verb.replace('-', '_')}" and run.__name__ == "run", verb
