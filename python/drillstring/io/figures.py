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
