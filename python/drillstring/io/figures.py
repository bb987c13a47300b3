"""Figure files: the file a figure is written to and its atomic save (any figure of the package:
the paper model's, the drilling system's, the report's)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..errors import ValidationError

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["plot_path", "save"]


def plot_path(path: Any, field: str = "path") -> Any:
    """The file :func:`save` writes for ``path``: a file name without an extension gets
    matplotlib's default format (``savefig.format``, normally ``.png``) appended, as ``savefig``
    does, unless ``path`` is streamed into (``"-"``, a device or a FIFO); an open file object is
    returned as it is. An extension that is not an image format matplotlib writes raises
    :class:`~drillstring.errors.ValidationError` naming ``field``."""
    import os

    import matplotlib
    from matplotlib.backend_bases import FigureCanvasBase

    from .output import is_path, is_stream

    if not is_path(path) or is_stream(path):
        return path
    text = os.fsdecode(os.fspath(path))
    extension = os.path.splitext(text)[1].lstrip(".").lower()
    if not extension:
        return f"{text}.{matplotlib.rcParams['savefig.format']}"
    formats = sorted(FigureCanvasBase.get_supported_filetypes())
    if extension not in formats:
        raise ValidationError(field, text, "a file name ending in one of ." + ", .".join(formats))
    return path


def save(fig: Figure, path: Any, dpi: int = 130) -> Any:
    """Saves a figure to ``path`` (format from the extension, else matplotlib's default) and
    returns the path written (:func:`plot_path`). A file is replaced atomically (an interrupted
    save leaves the old one), a symlink is written through, a device, FIFO or ``"-"`` is streamed
    into (see :mod:`drillstring.io.output`); an open file object is written directly."""
    import os

    import matplotlib

    from .output import is_path, write_to

    target = plot_path(path)
    extension = os.path.splitext(os.fsdecode(os.fspath(target)))[1].lstrip(".") if is_path(target) else ""
    fmt = extension.lower() or matplotlib.rcParams["savefig.format"]
    return write_to(target, lambda handle: fig.savefig(handle, dpi=dpi, format=fmt), suffix=f".{fmt}")


class FigureJobs:
    """Figures drawn and saved (:func:`save`) while the caller does other work: ``jobs`` are
    ``(make, path)``, ``make()`` returning the figure. With ``workers`` > 0, where ``os.fork``
    exists and this process runs no other thread, matplotlib is imported once here and that
    many forked processes draw their share of the figures (round robin, one share left to this
    process) from the moment of construction; :meth:`finish` draws this process's share, waits
    for the others and returns the paths written, in the order of ``jobs``. Drawing is the slow
    part of writing a figure (0.2-0.4 s each, matplotlib in pure Python), and a command that
    writes several figures on a machine of several cores waits for the slowest share only.
    An exception raised in a forked process is raised by :meth:`finish` (as itself where it can
    be pickled, else as a ``RuntimeError`` with its text); an exception here, Ctrl-C included,
    ends the forked processes first."""

    def __init__(self, jobs: list[tuple[Any, Any]], workers: int = 0) -> None:
        import os
        import threading

        self._jobs = list(jobs)
        self._paths: list[Any] = [None] * len(self._jobs)
        self._children: list[tuple[int, int, list[int]]] = []
        workers = min(workers, len(self._jobs) - 1)
        if workers <= 0 or not hasattr(os, "fork") or threading.active_count() > 1:
            self._here = list(range(len(self._jobs)))
            return
        # loaded once, before the fork, for all the processes
        import matplotlib.backends.backend_agg
        import matplotlib.figure  # noqa: F401

        shares = [list(range(len(self._jobs)))[k::workers + 1] for k in range(workers + 1)]
        self._here = shares.pop(1)  # the forked processes take the first and third figures of three
        for share in shares:
            self._fork(share)

    def _fork(self, share: list[int]) -> None:
        import os
        import pickle

        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:  # the forked process: draw, report a failure through the pipe, exit at once
            os.close(read)
            code = 0
            try:
                for k in share:
                    make, path = self._jobs[k]
                    save(make(), path)
            except BaseException as exc:  # any failure, Ctrl-C included, goes back to the parent
                code = 1
                try:
                    message = pickle.dumps(exc)
                except Exception:
                    message = pickle.dumps(RuntimeError(f"{type(exc).__name__}: {exc}"))
                with os.fdopen(write, "wb") as pipe:
                    pipe.write(message)
            finally:
                os._exit(code)  # no atexit handlers, no flush of the parent's buffers
        os.close(write)
        self._children.append((pid, read, share))

    def finish(self) -> list[Any]:
        """Draws this process's share, waits for the forked processes; the paths written."""
        import os
        import pickle

        try:
            for k in self._here:
                make, path = self._jobs[k]
                self._paths[k] = save(make(), path)
            while self._children:
                pid, read, share = self._children[0]
                with os.fdopen(read, "rb") as pipe:
                    message = pipe.read()
                _, status = os.waitpid(pid, 0)
                self._children.pop(0)
                if message:
                    try:
                        exc = pickle.loads(message)
                    except Exception:
                        exc = RuntimeError("a figure could not be drawn")
                    raise exc
                if status != 0:
                    raise RuntimeError(f"the process drawing {len(share)} figure(s) ended with status {status}")
                for k in share:
                    self._paths[k] = plot_path(self._jobs[k][1])
        finally:
            self.cancel()  # those left after a failure
        return self._paths

    def cancel(self) -> None:
        """Ends the forked processes still drawing (after a failure of the caller's work)."""
        import os
        import signal

        for pid, read, _ in self._children:
            try:
                os.kill(pid, signal.SIGTERM)
                os.waitpid(pid, 0)
            except OSError:
                pass
            try:
                os.close(read)
            except OSError:
                pass
        self._children = []
