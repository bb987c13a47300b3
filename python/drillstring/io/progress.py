"""Progress of long work: tqdm bars on stderr, or a function of the caller.

``progress`` options of the solvers are ``False`` (nothing), ``True`` (a tqdm bar of the solve time
reached, on stderr) or a callable ``f(t_reached, t_end)``. The solves run in the Rust core with
the GIL released; the core calls back with the time reached about every 20 ms while it steps
(its interrupt hook re-attaches to the interpreter that often anyway), and the report also comes
at the start (``t = 0``) and at the end of the solve.
"""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Union

from ..errors import ValidationError

__all__ = ["ProgressOption", "SolveProgress", "check_progress", "on_terminal", "bar"]

#: What a ``progress=`` option of a solver accepts.
ProgressOption = Union[bool, Callable[[float, float], Any]]


def on_terminal() -> bool:
    """Whether stderr is a terminal (the default of the command line's ``--progress``)."""
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


def bar(
    total: float, desc: str, unit: str, *, enabled: bool = True, bar_format: Optional[str] = None,
    every_update: bool = False,
) -> Any:
    """A tqdm bar on stderr (disabled: a bar that prints nothing); ``every_update`` redraws on
    every update (for coarse units such as sweep chunks) instead of at most every 0.1 s."""
    from tqdm import tqdm  # on first use: ``import drillstring`` does not load it

    extra: dict[str, Any] = {"mininterval": 0.0, "miniters": 1} if every_update else {}
    # Without tqdm's monitor thread (it only tunes the redraw rate of bars updated by their
    # iteration; ours are updated when the work reports), which would outlive the bar and keep a
    # command from forking the processes that draw its figures.
    interval, tqdm.monitor_interval = tqdm.monitor_interval, 0
    try:
        return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, disable=not enabled,
                    bar_format=bar_format, dynamic_ncols=True, **extra)
    finally:
        tqdm.monitor_interval = interval


def check_progress(value: Any) -> ProgressOption:
    """Validates a ``progress=`` option: ``True``, ``False`` or a callable ``f(t_reached, t_end)``."""
    if isinstance(value, bool) or callable(value):
        return value
    raise ValidationError("progress", value, "True, False or a callable f(t_reached, t_end)")


class SolveProgress:
    """Reports the solve time reached to a tqdm bar or a callable, as a context manager.

    ``report(t)`` is what the core calls while it steps (when it can); :meth:`finish` reports the
    time the solve ended at. A callable's exception propagates (and stops a core that reports).
    """

    def __init__(self, option: ProgressOption, t_end: float, desc: str) -> None:
        self.t_end = t_end
        self.reached = 0.0
        self._callback: Optional[Callable[[float, float], Any]] = None
        self._bar: Any = None
        if option is True:
            self._bar = bar(t_end, desc, "s", bar_format="{desc}: {percentage:3.0f}%|{bar}| t = {n:.4g}/{total:.4g} s "
                            "[{elapsed}<{remaining}]")
        elif callable(option):
            self._callback = option

    @property
    def enabled(self) -> bool:
        return self._bar is not None or self._callback is not None

    def report(self, t: float) -> None:
        t = min(max(float(t), self.reached), self.t_end)
        if t <= self.reached:
            return  # only forward moves are reported
        self.reached = t
        if self._bar is not None:
            self._bar.n = t
            self._bar.refresh()
        if self._callback is not None:
            self._callback(t, self.t_end)

    def core_kwargs(self) -> dict[str, Any]:
        """The core solve's ``progress`` argument: :meth:`report` when a report is wanted."""
        return {"progress": self.report} if self.enabled else {}

    def finish(self, result: Any) -> None:
        """Reports where a solve ended: ``t_end`` on success, else its last sample's time."""
        if result.success:
            self.report(self.t_end)
        elif result.t.size:
            self.report(float(result.t[-1]))

    def __enter__(self) -> SolveProgress:
        if self._callback is not None:
            self._callback(0.0, self.t_end)
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._bar is not None:
            self._bar.close()
