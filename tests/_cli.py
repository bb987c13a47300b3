"""Helpers of the command-line tests: run ``drillstring.cli.main`` in-process, check one-line errors."""

from __future__ import annotations

import pytest

from drillstring.cli import main


def run_cli(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    """``main(args)``'s exit code and what it printed to stdout and stderr."""
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(err: str, *needles: str) -> str:
    """The single ``drillstring: error:`` line of ``err``, containing every needle (no temporary
    file name, no traceback)."""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("drillstring: error:"), err
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    assert ".tmp" not in lines[0] and "Traceback" not in err
    return lines[0]
