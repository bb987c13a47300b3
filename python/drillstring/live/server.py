"""The live display's server: the page and its assets over HTTP, and one WebSocket per open page
(aiohttp, one asyncio loop: a local display for one user needs no more). Every
:data:`FRAME_EVERY` s it sends each page a frame: the new series rows decimated to what the page
draws, the along-string state, the status, and the verdict when the driver has a new one.

Messages (JSON). Server to page: ``hello`` (what to draw, in which units, the controls),
``frame``, ``reset`` (the run started again: clear the tracks), ``reply`` (to a command, with
``ok`` and the error message or the recorded folder). Page to server: ``{"type": "set", "id": n,
"key": "top_drive.rpm", "value": 80.0}`` (values in SI), ``pause``, ``resume``, ``reset``,
``speed`` (``value``: a factor or ``"max"``), ``record``."""

from __future__ import annotations

import asyncio
import contextlib
import json
import math
import threading
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Optional
from urllib.parse import urlsplit

import numpy as np

from ..errors import DrillstringError
from .display import controls, decimate, describe, verdict
from .driver import COMMANDS, Driver

__all__ = ["FRAME_EVERY", "STATIC", "Background", "LiveApp"]

#: The folder of the page and its assets.
STATIC = Path(__file__).parent / "static"
#: How often a frame is sent (s): about 20 frames a second.
FRAME_EVERY = 0.05
#: The span of time the page's tracks show (s) and the points it draws over it.
WINDOW_S = 60.0
POINTS = 1200
#: The most points of a view along the string.
PROFILE_POINTS = 400


def _numbers(values: Any) -> str:
    """A JSON array of the numbers ``values`` to 6 significant digits, null where not finite."""
    a = np.asarray(values, dtype=np.float64).ravel()
    if a.size == 0:
        return "[]"
    text = np.char.mod("%.6g", a)
    text[~np.isfinite(a)] = "null"
    return "[" + ",".join(text.tolist()) + "]"


def _object(parts: Mapping[str, str]) -> str:
    return "{" + ",".join(f"{json.dumps(k)}:{v}" for k, v in parts.items()) + "}"


class LiveApp:
    """The aiohttp application of a :class:`~drillstring.live.driver.Driver`'s display."""

    def __init__(self, driver: Driver, *, system: str = "si", name: str = "") -> None:
        from aiohttp import web

        self.driver = driver
        self.system = system
        self.name = name
        self.clients: set[Any] = set()
        self._drawn = -math.inf
        self._bounce = False
        self._history: list[dict[str, np.ndarray]] = []
        self._answering: set[asyncio.Future[None]] = set()
        self.app = web.Application()
        self.app.router.add_get("/", self._index)
        self.app.router.add_get("/ws", self._socket)
        self.app.router.add_static("/static/", STATIC, follow_symlinks=False)
        self.app.on_startup.append(self._on_startup)
        self.app.on_cleanup.append(self._on_cleanup)

    async def _index(self, request: Any) -> Any:
        from aiohttp import web

        return web.FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    def hello(self) -> dict[str, Any]:
        """What a page needs first: the tracks, views and controls in the run's units, the window."""
        driver = self.driver  # its copies: the session is the stepping thread's alone
        return {
            "type": "hello", "name": self.name, "units": self.system, "coupled": driver.coupled,
            **describe(driver.coupled, self.system),
            "controls": controls(driver.settable, driver.config, self.system, driver.values),
            "window_s": WINDOW_S, "points": POINTS, "dt": driver.dt,
            "record_dir": str(self.driver.record_dir),
        }

    async def _socket(self, request: Any) -> Any:
        from aiohttp import WSMsgType, web

        origin = request.headers.get("Origin")
        if origin is not None and urlsplit(origin).netloc != request.host:
            # another site's page in the same browser may not drive the run
            raise web.HTTPForbidden(text=f"WebSocket from another origin ({origin}) refused")
        ws = web.WebSocketResponse(heartbeat=20.0)
        await ws.prepare(request)
        await ws.send_str(json.dumps(self.hello()))
        await ws.send_str(self._past())
        self.clients.add(ws)
        try:
            async for message in ws:
                if message.type == WSMsgType.TEXT:
                    task = asyncio.ensure_future(self._answer(ws, message.data))
                    self._answering.add(task)  # held until done (the loop keeps weak references only)
                    task.add_done_callback(self._answering.discard)
        finally:
            self.clients.discard(ws)
        return ws

    async def _answer(self, ws: Any, text: str) -> None:
        """Carries out one command of a page and replies with its outcome."""
        ident: Any = None
        try:
            message = json.loads(text)
            if not isinstance(message, dict):
                raise ValueError("a command is a JSON object")
            ident = message.get("id")
            kind = message.get("type")
            if kind not in COMMANDS:
                raise ValueError(f"unknown command {kind!r}: one of {', '.join(COMMANDS)}")
            value = (message.get("key"), message.get("value")) if kind == "set" else message.get("value")
            result = await asyncio.wrap_future(self.driver.submit(kind, value))
            reply = {"type": "reply", "id": ident, "command": kind, "ok": True, "result": result}
        except (DrillstringError, ValueError, TypeError, OSError) as exc:
            reply = {"type": "reply", "id": ident, "ok": False, "message": str(exc)}
        with contextlib.suppress(ConnectionError, RuntimeError):
            await ws.send_str(json.dumps(reply))

    def frame(self) -> Optional[str]:
        """The next frame as JSON text (and a ``reset`` message before it after a reset)."""
        update = self.driver.take()
        parts: dict[str, str] = {"type": '"frame"', "status": json.dumps(update.status)}
        prefix = ""
        if update.reset:
            self._drawn = -math.inf
            self._history = []
            prefix = json.dumps({**self.hello(), "type": "reset"}) + "\n"
        rows = update.rows
        if rows and "t" in rows and rows["t"].size:
            keep = decimate(rows["t"], WINDOW_S / POINTS, self._drawn)
            if keep.size:
                self._drawn = float(rows["t"][keep[-1]])
            names = ["t", *(c["name"] for c in describe(self.driver.coupled, self.system)["tracks"])]
            drawn = {k: rows[k][keep] for k in names if k in rows}
            self._remember(drawn)
            parts["rows"] = _object({k: _numbers(v) for k, v in drawn.items()})
            if "weight_on_bit" in rows:
                self._bounce = bool(rows["weight_on_bit"][-1] <= 0.0)
        if update.state is not None:
            parts["state"] = self._state(update.state)
        if update.verdict is not None:
            parts["verdict"] = json.dumps(verdict(update.verdict["metrics"], update.verdict["window"],
                                                  self.driver.coupled, self.system))
        if update.events:
            parts["events"] = json.dumps(update.events, default=str)
        return prefix + _object(parts)

    def _remember(self, rows: dict[str, np.ndarray]) -> None:
        """Keeps the rows drawn over the last window, for a page that connects later."""
        if rows["t"].size:
            self._history.append(rows)
        end = self._drawn
        while self._history and self._history[0]["t"][-1] < end - WINDOW_S:
            self._history.pop(0)

    def _past(self) -> str:
        """A frame of the rows of the last window (what a page that connects now has missed)."""
        parts = {"type": '"frame"', "status": json.dumps(self.driver.take_status())}
        if self._history:
            parts["rows"] = _object({k: _numbers(np.concatenate([h[k] for h in self._history]))
                                     for k in self._history[0]})
        return _object(parts)

    def _state(self, state: Mapping[str, Any]) -> str:
        """The along-string state (at most :data:`PROFILE_POINTS` cells of each grid) and the indicators."""
        out: dict[str, str] = {}
        for grid, fields in (("z_m", ("omega_rpm", "torque_Nm", "contact_N_per_m")),
                             ("axial_z_m", ("axial_force_N",))):
            if grid not in state:
                continue
            z = np.asarray(state[grid])
            pick = np.unique(np.linspace(0, z.size - 1, min(z.size, PROFILE_POINTS)).round().astype(np.int64))
            out[grid] = _numbers(z[pick])
            out.update({k: _numbers(np.asarray(state[k])[pick]) for k in fields if k in state})
        stuck = np.asarray(state.get("stuck", ()))
        scalars = {k: float(state[k]) for k in ("t_s", "surface_rpm", "bit_rpm", "motor_torque_Nm", "bit_torque_Nm")
                   if k in state}
        out["scalars"] = _object({k: _numbers([v])[1:-1] for k, v in scalars.items()})
        out["bit_stuck"] = "true" if stuck.size and bool(stuck[-1]) else "false"
        out["stuck_cells"] = str(int(stuck.sum())) if stuck.size else "0"
        out["bit_bounce"] = "true" if self._bounce else "false"
        return _object(out)

    async def _broadcast(self) -> None:
        loop = asyncio.get_running_loop()
        due = loop.time()
        while True:
            due = max(due + FRAME_EVERY, loop.time())  # on a fixed beat; a late frame does not pile up
            await asyncio.sleep(due - loop.time())
            text = self.frame()
            if text is None:
                continue
            for ws in list(self.clients):
                for line in text.split("\n"):
                    with contextlib.suppress(ConnectionError, RuntimeError):
                        await ws.send_str(line)

    async def _on_startup(self, app: Any) -> None:
        self.driver.start()
        self._task = asyncio.ensure_future(self._broadcast())

    async def _on_cleanup(self, app: Any) -> None:
        self._task.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await self._task
        for ws in list(self.clients):
            await ws.close()
        await asyncio.get_running_loop().run_in_executor(None, self.driver.stop)


async def start(live: LiveApp, host: str, port: int) -> tuple[Any, str]:
    """Starts serving ``live`` on ``host:port`` (0: a free port); returns the runner and the URL."""
    from aiohttp import web

    runner = web.AppRunner(live.app, handle_signals=False, access_log=None)
    await runner.setup()
    site = web.TCPSite(runner, host, port)
    await site.start()
    bound = runner.addresses[0]
    shown = f"[{bound[0]}]" if ":" in str(bound[0]) else str(bound[0])
    return runner, f"http://{shown}:{bound[1]}/"


class Background:
    """A display served from a thread of its own (tests, benchmarks, the screenshot): ``url``;
    :meth:`close` stops the server and the driver."""

    def __init__(self, live: LiveApp, host: str = "127.0.0.1", port: int = 0) -> None:
        self.live = live
        self._loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._error: Optional[BaseException] = None
        self.url = ""
        self._thread = threading.Thread(target=self._run, args=(host, port), daemon=True)
        self._thread.start()
        self._ready.wait()
        if self._error is not None:
            raise self._error

    def _run(self, host: str, port: int) -> None:
        asyncio.set_event_loop(self._loop)
        try:
            self._runner, self.url = self._loop.run_until_complete(start(self.live, host, port))
        except BaseException as exc:  # handed to the caller's thread
            self._error = exc
            self._ready.set()
            return
        self._ready.set()
        self._loop.run_forever()
        self._loop.run_until_complete(self._runner.cleanup())
        self._loop.close()

    def close(self) -> None:
        if self._error is None:
            self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join()

    def __enter__(self) -> Background:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
