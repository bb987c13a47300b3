"""The session driver of the live display: one worker thread owns the drilling session, steps it
paced to the real-time factor (``step`` releases the GIL, so the server's thread keeps serving),
carries out the page's commands between steps and collects what the page needs: the new series
rows, the along-string state (at most :data:`STATE_EVERY` apart), the verdict of the last window
(every :data:`VERDICT_EVERY` s, over the last :data:`VERDICT_WINDOW` s of simulated time)."""

from __future__ import annotations

import math
import os
import queue
import threading
import time
from concurrent.futures import Future
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Optional

import numpy as np

from ..errors import DrillstringError, ValidationError

__all__ = ["COMMANDS", "Driver", "Update"]

#: The longest stretch of wall-clock time one step call covers at a real-time factor (s): the
#: display gets new rows at least this often.
MAX_CHUNK_WALL = 0.04
#: Behind the real-time factor by more than this (s of wall clock), the pacing starts again from
#: now: a run the machine cannot keep up with goes as fast as it can, its measured factor lower.
MAX_LAG_WALL = 0.5
#: How often the along-string state is taken (s of wall clock).
STATE_EVERY = 0.05
#: How often the verdict of the last window is computed (s of wall clock), over how much of the
#: run (s of simulated time), and from how much simulated time on.
VERDICT_EVERY = 3.0
VERDICT_WINDOW = 15.0
VERDICT_MIN = 4.0
#: The commands the page can send.
COMMANDS = ("set", "preset", "pause", "resume", "reset", "speed", "record")


def parse_speed(value: Any, field: str = "speed") -> float:
    """A real-time factor: a finite number > 0, or ``"max"`` (as fast as the machine steps: ``inf``)."""
    if isinstance(value, str) and value.strip().lower() == "max":
        return math.inf
    try:
        speed = float(value)
    except (TypeError, ValueError):
        speed = math.nan
    if not (math.isfinite(speed) and 0.0 < speed <= 1e6):
        raise ValidationError(field, value, "a real-time factor in (0, 1e6] or max")
    return speed


@dataclass
class Update:
    """What the driver collected since the last :meth:`Driver.take`."""

    rows: dict[str, np.ndarray]
    state: Optional[dict[str, Any]]
    verdict: Optional[dict[str, Any]]
    status: dict[str, Any]
    reset: bool
    events: list[dict[str, Any]] = field(default_factory=list)


def _default_session(config: Any) -> Any:
    from ..drilling.session import DrillSession

    return DrillSession(config)


class Driver:
    """Steps the session of ``config`` (``make_session(config)``, default
    ``drillstring.DrillSession``) in a worker thread at the real-time factor ``speed`` (``inf``:
    as fast as it goes); :meth:`submit` hands it a command, :meth:`take` what it collected."""

    def __init__(self, config: Any, *, speed: float = 1.0, record_dir: Any = ".",
                 make_session: Optional[Callable[[Any], Any]] = None) -> None:
        self.config = config
        self.record_dir = Path(record_dir)
        self._make = make_session or _default_session
        self._speed = speed
        self._commands: queue.Queue[tuple[str, Any, Future[Any]]] = queue.Queue()
        self._lock = threading.Lock()
        self._stopping = threading.Event()
        self._thread: Optional[threading.Thread] = None
        self.on_interrupt: Optional[Callable[[], None]] = None
        """Called (from the worker thread) when Ctrl-C stopped a step: the command then stops too."""
        self.session = self._make(config)
        self._begin(reset=False)

    # ----------------------------------------------------------------- state kept by the worker

    def _begin(self, reset: bool) -> None:
        # what the server reads from its own thread, taken while no step runs: the session
        # itself is only ever touched by the thread stepping it
        self.settable: tuple[str, ...] = tuple(self.session.settable)
        self.dt = float(self.session.dt)
        self.values: dict[str, Any] = {}
        """The keys changed so far and their SI values (what a page that connects later shows)."""
        self._row = 0
        self._paused = False
        self._failed = False
        self._chunk = 0.05
        self._rebase()
        self._last_state = -math.inf
        self._last_verdict = time.monotonic()
        self._history: list[tuple[float, float]] = []
        with self._lock:
            self._pending: list[dict[str, np.ndarray]] = []
            self._state: Optional[dict[str, Any]] = None
            self._verdict: Optional[dict[str, Any]] = None
            self._reset = reset
            self._events: list[dict[str, Any]] = []
        self._collect(force=True)

    def _rebase(self) -> None:
        self._wall0 = time.monotonic()
        self._sim0 = float(self.session.t)

    @property
    def coupled(self) -> bool:
        return getattr(self.config, "hoist", None) is not None

    # ----------------------------------------------------------------- the page's side

    def start(self) -> None:
        self._thread = threading.Thread(target=self._loop, name="drillstring-live", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        """Stops the worker after its step; commands not carried out fail with a message."""
        self._stopping.set()
        if self._thread is not None:
            self._thread.join()
        while True:
            try:
                _, _, future = self._commands.get_nowait()
            except queue.Empty:
                return
            future.set_exception(DrillstringError("the display stopped before the command was carried out"))

    def submit(self, command: str, value: Any = None) -> Future[Any]:
        """Queues a command of :data:`COMMANDS` for the worker: its future is done once it took
        effect (``record``: once the folder is written; its result is the folder's path), with
        the session's error for a value it refuses."""
        future: Future[Any] = Future()
        if command not in COMMANDS:
            future.set_exception(ValidationError("command", command, f"one of {', '.join(COMMANDS)}"))
        else:
            self._commands.put((command, value, future))
        return future

    def take(self) -> Update:
        """The rows, the latest state and verdict collected since the last call, and the status."""
        with self._lock:
            pending, self._pending = self._pending, []
            state, self._state = self._state, None
            verdict, self._verdict = self._verdict, None
            reset, self._reset = self._reset, False
            events, self._events = self._events, []
            status = dict(self._status)
        rows: dict[str, np.ndarray] = {}
        if pending:
            rows = {k: np.concatenate([p[k] for p in pending]) for k in pending[0]}
        return Update(rows, state, verdict, status, reset, events)

    def take_status(self) -> dict[str, Any]:
        """The status of the run now (time, step, status and message, paused, factors)."""
        with self._lock:
            return dict(self._status)

    # ----------------------------------------------------------------- the worker

    def _loop(self) -> None:
        while not self._stopping.is_set():
            if self._paused or self._failed:
                self._command(timeout=0.05)
                continue
            chunk = self._next_chunk()
            if chunk is None:
                continue
            began = time.monotonic()
            try:
                self.session.step(chunk)
            except DrillstringError:
                self._failed = True
            except KeyboardInterrupt:  # Ctrl-C seen by the engine while it stepped in this thread
                self._stopping.set()
                if self.on_interrupt is not None:
                    self.on_interrupt()
                return
            if math.isinf(self._speed):
                took = max(time.monotonic() - began, 1e-4)
                self._chunk = min(max(self._chunk * min(max(MAX_CHUNK_WALL / took, 0.5), 2.0), 1e-4), 10.0)
            self._collect()
            self._command(timeout=0.0)

    def _next_chunk(self) -> Optional[float]:
        """The simulated time of the next step call, or None after waiting for the clock (or a command)."""
        if math.isinf(self._speed):
            return self._chunk
        now = time.monotonic()
        lag = self._sim0 + self._speed * (now - self._wall0) - float(self.session.t)
        if lag > self._speed * MAX_LAG_WALL:
            self._wall0, self._sim0 = now, float(self.session.t)
            lag = 0.0
        dt = float(self.session.dt)
        if lag < dt:
            self._command(timeout=min((dt - lag) / self._speed, 0.02))
            return None
        return min(lag, self._speed * MAX_CHUNK_WALL)

    def _command(self, timeout: float) -> None:
        """Carries out the queued commands (waiting up to ``timeout`` s for the first)."""
        try:
            item = self._commands.get(timeout=timeout) if timeout > 0 else self._commands.get_nowait()
        except queue.Empty:
            return
        while True:
            name, value, future = item
            try:
                result = self._carry_out(name, value, future)
            except (DrillstringError, ValueError, TypeError, OSError) as exc:
                future.set_exception(exc)
            else:
                if result is not _LATER:
                    future.set_result(result)
            try:
                item = self._commands.get_nowait()
            except queue.Empty:
                return

    def _carry_out(self, name: str, value: Any, future: Future[Any]) -> Any:
        if name == "set":
            key, number = value
            self._set(str(key), number)
        elif name == "preset":
            return self._preset(str(value))
        elif name == "pause":
            self._paused = True
        elif name == "resume":
            self._paused = False
            self._rebase()
        elif name == "speed":
            self._speed = parse_speed(value)
            self._chunk = 0.05
            self._rebase()
        elif name == "reset":
            self.session = self._make(self.config)
            self._begin(reset=True)
        elif name == "record":
            result = self.session.result()
            folder = self.record_dir / f"live-{time.strftime('%Y%m%d-%H%M%S')}-t{float(self.session.t):.0f}s"
            threading.Thread(target=_save, args=(result, folder, future), daemon=True).start()
            return _LATER
        self._collect(force=True)
        return None

    def _preset(self, name: str) -> list[str]:
        """Sets the controller's type and gains of the preset ``name`` for this string (the core's
        rules, :func:`~drillstring.drilling.tuning.recommend_controllers`); returns the keys set."""
        from ..drilling.tuning import recommend_controllers
        from .display import PRESET_KEYS

        presets = {p.preset: p.controller for p in recommend_controllers(self.config).presets}
        if name not in presets:
            raise ValidationError("top_drive.controller.preset", name, f"one of {', '.join(presets)}")
        done = []
        for part in PRESET_KEYS:
            value = presets[name].get(part)
            if value is not None:
                key = f"top_drive.controller.{part}"
                self._set(key, value)
                done.append(key)
        self._collect(force=True)
        return done

    def _set(self, key: str, value: Any) -> None:
        """Sets ``key`` to the SI ``value`` (the page's and the presets' values are SI; the session
        reads plain numbers in the configuration's unit system, so a field configuration's get
        theirs with the SI unit written out)."""
        sent = value
        system = getattr(self.config, "units", "si")
        if system != "si" and isinstance(value, (int, float)) and not isinstance(value, bool):
            from ..drilling.config import config_schema

            entry: dict[str, Any] = dict(config_schema().get(key) or {})
            unit = entry.get("unit")
            if unit:
                sent = f"{float(value)!r} {unit}"
        self.session.set(key, sent)
        self.values = {**self.values, key: value}  # a new dict: the server's thread reads it whole
        self._event({"type": "set", "key": key, "value": value, "t": float(self.session.t)})

    def _event(self, event: dict[str, Any]) -> None:
        with self._lock:
            self._events.append(event)

    def _collect(self, force: bool = False) -> None:
        """Takes the session's new rows, and its state and the verdict when they are due."""
        s = self.session
        rows = {str(k): np.asarray(v) for k, v in s.rows(self._row).items()}
        count = len(next(iter(rows.values()))) if rows else 0
        self._row += count
        now = time.monotonic()
        t = float(s.t)
        self._history = [(w, x) for w, x in self._history if now - w <= 2.0] + [(now, t)]
        (w0, t0), (w1, t1) = self._history[0], self._history[-1]
        state = None
        if force or now - self._last_state >= STATE_EVERY:
            state = {str(k): v for k, v in s.state().items()}
            self._last_state = now
        verdict = None
        if now - self._last_verdict >= VERDICT_EVERY and t >= VERDICT_MIN:
            window = (max(0.0, t - VERDICT_WINDOW), t)
            verdict = {"window": window, "metrics": s.metrics(window=window)}
            self._last_verdict = now
        status = {
            "t": t, "dt": float(s.dt), "status": str(s.status), "message": str(s.message),
            "paused": self._paused, "speed": "max" if math.isinf(self._speed) else self._speed,
            "rtf": (t1 - t0) / (w1 - w0) if w1 - w0 > 0.2 else None, "rows": self._row,
        }
        with self._lock:
            if count:
                self._pending.append(rows)
            if state is not None:
                self._state = state
            if verdict is not None:
                self._verdict = verdict
            self._status = status


class _Later:
    """The result of a command whose future is completed later (by another thread)."""


_LATER = _Later()


def _save(result: Any, folder: Path, future: Future[Any]) -> None:
    try:
        os.makedirs(folder.parent, exist_ok=True)
        result.save(folder)
    except (DrillstringError, ValueError, OSError) as exc:
        future.set_exception(exc)
    else:
        future.set_result(str(folder))

