"""The live display in a real headless Chromium (the system's, driven by Playwright): the page loads
with no console error, its tracks advance, a moved rpm setpoint moves the surface rpm, a preset
sets the controller, pause stops the clock, Record writes a drill output folder. Skipped without
Chromium or Playwright, except in CI (``CI`` set), where a missing browser is a failure."""

from __future__ import annotations

import os
import shutil
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Callable

import pytest
from _drill_folder import check_drill_folder

from drillstring.drilling import load_drill_config
from drillstring.live.driver import Driver
from drillstring.live.server import Background, LiveApp

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"
#: The browsers tried, by the names Debian and others install them under.
BROWSERS = ("chromium", "chromium-browser", "google-chrome")


def chromium() -> str:
    """The path of the system's Chromium; a skip without one, a failure in CI."""
    path = next((p for p in map(shutil.which, BROWSERS) if p), None)
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        path = None
    if path is None:
        if os.environ.get("CI"):
            pytest.fail("CI needs Chromium and Playwright for the live display's test (.ci/run installs them)")
        pytest.skip("no Chromium or no Playwright (apt-get install chromium; pip install playwright)")
    return path


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    path = chromium()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        launched = p.chromium.launch(executable_path=path, args=["--no-sandbox", "--disable-gpu"])
        yield launched
        launched.close()


def until(condition: Callable[[], Any], timeout: float, what: str) -> Any:
    """Waits for ``condition()`` to be true (polling), else fails naming ``what``."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = condition()
        if value:
            return value
        time.sleep(0.05)
    pytest.fail(f"not within {timeout} s: {what}")


@pytest.mark.slow
def test_the_display_runs_takes_setpoints_pauses_and_records(browser: Any, tmp_path: Path) -> None:
    config = load_drill_config(EXAMPLE).with_overrides(["numerics.cells=100"])
    driver = Driver(config, speed=1.0, record_dir=tmp_path)
    problems: list[str] = []
    with Background(LiveApp(driver, name="on-bottom")) as server:
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.on("console", lambda m: problems.append(m.text) if m.type in ("error", "warning") else None)
        page.on("pageerror", lambda e: problems.append(str(e)))
        page.goto(server.url)
        stats = lambda: page.evaluate("window.drillstringStats")  # noqa: E731
        last = lambda name: page.evaluate(  # noqa: E731
            f"document.querySelector('.track[data-channel={name}] .value').textContent")

        # the tracks advance: time increases and the page renders
        first = until(lambda: stats()["t"] > 0.5 and stats()["renders"] > 0 and stats(), 20, "a first render")
        later = until(lambda: stats()["t"] > first["t"] + 1.0 and stats(), 20, "time to advance")
        assert later["renders"] > first["renders"] and later["rows"] > first["rows"]
        assert page.locator(".track").count() == 4 and page.locator(".profile").count() == 3

        # the rpm setpoint from 40 to 80 rpm: the surface rpm follows within the controller's time
        field = page.locator('.control[data-key="top_drive.rpm"] input[type=number]')
        field.fill("80")
        field.dispatch_event("change")
        until(lambda: any(r.get("command") == "set" and r["ok"] for r in stats()["replies"]), 10, "the set's reply")
        until(lambda: float(last("surface_rpm")) > 70.0, 20, "the surface rpm to reach the new setpoint")

        # a preset: the controller type and gains of this string, the type shown on the page
        page.select_option('select[data-key="top_drive.controller.preset"]', "soft_torque")
        until(lambda: page.locator('select[data-key="top_drive.controller.type"]').input_value() == "soft_torque",
              10, "the preset's controller type on the page")

        # a key that cannot change during a run: the server's message on the page
        page.evaluate("window.drillstringCommand({type: 'set', key: 'numerics.cells', value: 50})")
        until(lambda: "numerics.cells" in page.locator("#message").text_content(), 10, "the error message")

        # pause stops the clock
        page.click("#pause")
        until(lambda: page.locator("#run-status").text_content() == "paused", 10, "paused")
        held = stats()["t"]
        time.sleep(0.6)
        assert stats()["t"] == held
        page.click("#resume")
        until(lambda: stats()["t"] > held, 10, "time to run again")

        # record: a drill output folder of what ran, with the setpoint's change
        page.click("#record")
        reply = until(lambda: next((r for r in stats()["replies"] if r.get("command") == "record" or
                                    (not r["ok"] and "record" in r.get("message", ""))), None), 120, "the recording")
        assert reply["ok"], reply
        folder = Path(reply["result"])
        series = check_drill_folder(folder)
        changes = load_drill_config(folder / "config.toml").changes
        rpm = [c for c in changes if c.key == "top_drive.rpm"]
        assert rpm and all(c.value == 80.0 for c in rpm)
        assert {c.key: c.value for c in changes}["top_drive.controller.type"] == "soft_torque"
        assert series["surface_rpm"][series.index < rpm[0].time].max() < 60.0
        assert series["surface_rpm"][series.index > rpm[0].time].max() > 70.0

        # a run longer than the tracks' window: the page keeps a fixed number of rows
        page.select_option("#speed", "max")
        until(lambda: stats()["t"] > 75.0, 120, "75 s of the run at full speed")
        held = stats()
        assert held["rows"] > held["capacity"] >= held["buffered"] and 0 < held["drawn"] <= held["capacity"]
        assert problems == []
        page.close()
