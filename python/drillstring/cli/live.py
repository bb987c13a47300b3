"""``drillstring live``: the driller's display of a run in the browser, stepped in real time."""

from __future__ import annotations

import argparse
from typing import Any

from ._common import drilling_config, int_in, say


def _speed(text: str) -> float:
    from ..live.driver import parse_speed

    try:
        return parse_speed(text, "--speed")
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"got {text!r}, expected a real-time factor > 0 or max") from exc


def add_parser(subparsers: Any) -> None:
    """Adds ``drillstring live`` to ``subparsers``: its arguments, help and example."""
    p = subparsers.add_parser(
        "live",
        help="the driller's display of a run in the browser: tracks, the string, setpoints changed while it runs",
        description="Run CONFIG.toml in real time and show it in the browser as the driller's display: log tracks "
        "against time (surface rpm and torque, hook load, WOB, ROP, bit rpm, torque on bit), the speed, torque, "
        "axial force and wall contact along the string, the stick-slip verdict of the last window; change the rpm "
        "and WOB setpoints and the controller while it runs, pause, reset, and record what ran as a drill output "
        "folder. Prints the page's address; Ctrl-C stops. Needs the extra live (pip install '.[live]').",
        epilog="example: drillstring live examples/on-bottom-3000m.toml",
    )
    p.add_argument("config", metavar="CONFIG.toml", help="drilling configuration (examples/*.toml)")
    p.add_argument("--host", default="127.0.0.1",
                   help="the address to serve on (default: 127.0.0.1, this machine only)")
    p.add_argument("--port", type=int_in(0, 65535), default=0, help="the port (default 0: any free port)")
    p.add_argument("--no-browser", action="store_true", help="print the address only; do not open a browser")
    p.add_argument("--speed", type=_speed, default=1.0, metavar="X",
                   help="real-time factor: simulated seconds per second (default 1), or max")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help="change a field before the run starts, e.g. top_drive.rpm=60 (repeatable)")
    p.add_argument("--record-dir", default=".", metavar="DIR",
                   help="where Record writes its folders (live-DATE-TIME-tNs, drill's outputs; default: here)")
    p.add_argument("--units", choices=("si", "field"), default=None,
                   help="the unit system of the page (field: ft, klbf, kft-lbf, ft/h; default: the configuration's "
                   "units key, si without one); a recording's data files are SI either way")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Runs ``drillstring live`` until Ctrl-C; returns its exit status."""
    import asyncio
    import sys
    import webbrowser
    from pathlib import Path

    from ..io.extras import require

    require("live", "drillstring live")
    from ..live.driver import Driver
    from ..live.server import LiveApp, start

    config = drilling_config(args)
    driver = Driver(config, speed=args.speed, record_dir=args.record_dir)
    live = LiveApp(driver, system=args.units or config.units, name=Path(args.config).stem)

    async def serve() -> None:
        stop = asyncio.Event()
        loop = asyncio.get_running_loop()

        def interrupted() -> None:
            loop.call_soon_threadsafe(stop.set)

        driver.on_interrupt = interrupted
        runner, url = await start(live, args.host, args.port)
        try:
            say(f"drillstring live: {url} (Ctrl-C stops)")
            sys.stdout.flush()
            if not args.no_browser:
                webbrowser.open(url)
            await stop.wait()
        finally:
            await runner.cleanup()

    try:
        asyncio.run(serve())
    except KeyboardInterrupt:
        say("drillstring live: stopped")
    return 0
