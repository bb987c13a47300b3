"""Test-suite options: tests marked ``slow`` (each over ~5 s on a 2-core machine: the symbolic
derivation, the README type check, the heaviest interrupt test) run in CI (``CI=true``), with
``--run-slow`` or with ``DRILLSTRING_SLOW=1``; a plain ``python3 -m pytest`` skips them and says so."""

from __future__ import annotations

import os

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--run-slow", action="store_true", help="also run the tests marked slow (CI does)")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "slow: over ~5 s; run in CI, with --run-slow or DRILLSTRING_SLOW=1")


def _run_slow(config: pytest.Config) -> bool:
    env = lambda name: os.environ.get(name, "").strip().lower() in ("1", "true", "yes")  # noqa: E731
    return bool(config.getoption("--run-slow")) or env("CI") or env("DRILLSTRING_SLOW")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if _run_slow(config):
        return
    skip = pytest.mark.skip(reason="slow: run with --run-slow or DRILLSTRING_SLOW=1 (CI runs it)")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
