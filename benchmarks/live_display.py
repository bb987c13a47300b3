"""Screen updates per second of the live display (``drillstring live``) in a headless Chromium.

Case: examples/on-bottom-3000m.toml on ``--cells`` cells (default 1000) at real-time factor
``--speed`` (default 1). The display is served in-process on a free port, the system's Chromium
(driven by Playwright, no browser download) opens the page, and after ``--warmup`` s the page's
own counters (``window.drillstringStats``: renders of the tracks and views, frames received,
their bytes) are read over ``--seconds`` s. Printed: updates (renders) per second, frames per
second, bytes per frame, the simulated time reached against the wall clock (the run's real-time
factor), the processor and the core count. The target is at least 10 updates per second at 1x.

``--screenshot PATH`` also saves the page as a PNG (the documentation's
docs/_static/live-display.png: ``--cells 300 --speed 2 --seconds 20 --screenshot ...``).

    python benchmarks/live_display.py [--cells 1000] [--speed 1] [--seconds 20] [--screenshot PATH]
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import tempfile
import time
from pathlib import Path

import drillstring as ds
from drillstring.live.driver import Driver, parse_speed
from drillstring.live.server import Background, LiveApp

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "on-bottom-3000m.toml"


def processor() -> str:
    """The processor's model name (``/proc/cpuinfo``), else what the platform says."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=str(EXAMPLE))
    parser.add_argument("--cells", type=int, default=1000)
    parser.add_argument("--speed", default="1", help="real-time factor, or max")
    parser.add_argument("--warmup", type=float, default=3.0)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--screenshot", default=None, metavar="PATH")
    parser.add_argument("--units", default=None, choices=("si", "field"))
    args = parser.parse_args()

    from playwright.sync_api import sync_playwright

    browser_path = next((p for p in map(shutil.which, ("chromium", "chromium-browser", "google-chrome")) if p), None)
    if browser_path is None:
        raise SystemExit("no Chromium found (apt-get install chromium)")
    config = ds.load_drill_config(args.config).with_overrides([f"numerics.cells={args.cells}"])
    driver = Driver(config, speed=parse_speed(args.speed), record_dir=tempfile.mkdtemp())
    with Background(LiveApp(driver, system=args.units or config.units, name=Path(args.config).stem)) as server, \
            sync_playwright() as p:
        browser = p.chromium.launch(executable_path=browser_path, args=["--no-sandbox", "--disable-gpu"])
        page = browser.new_page(viewport={"width": 1440, "height": 900})
        page.goto(server.url)
        time.sleep(args.warmup)
        before, wall0 = page.evaluate("({...window.drillstringStats})"), time.monotonic()
        time.sleep(args.seconds)
        after, wall1 = page.evaluate("({...window.drillstringStats})"), time.monotonic()
        if args.screenshot:  # the page down to the end of its panels
            bottom = page.evaluate("document.querySelector('main').getBoundingClientRect().bottom")
            page.screenshot(path=args.screenshot, clip={"x": 0, "y": 0, "width": 1440, "height": bottom + 8})
        browser.close()
    wall = wall1 - wall0
    frames = after["frames"] - before["frames"]
    print(f"case: {Path(args.config).name}, {args.cells} cells, dt {driver.session.dt:.3g} s, "
          f"real-time factor asked {args.speed}")
    print(f"screen updates: {(after['renders'] - before['renders']) / wall:.1f} per s "
          f"(frames received {frames / wall:.1f} per s, {(after['bytes'] - before['bytes']) / max(frames, 1):.0f} "
          f"bytes per frame)")
    print(f"simulated {after['t'] - before['t']:.2f} s in {wall:.2f} s of wall clock: "
          f"real-time factor {(after['t'] - before['t']) / wall:.3f}")
    print(f"machine: {processor()}, {os.cpu_count()} cores")
    if args.screenshot:
        print(f"wrote {args.screenshot}")


if __name__ == "__main__":
    main()
