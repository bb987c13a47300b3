"""Atomic file output: write to a temporary file beside the target, then ``os.replace`` it.

An interrupted or failed write (Ctrl-C, a full disk, an exception in the writer) leaves the target
as it was, never half-written; the temporary file is removed. The temporary name keeps the
target's extension, so writers that infer a format from it (matplotlib's ``savefig``) or append
one (``numpy.savez``) behave as they would on the target.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any, Callable, Union

__all__ = ["atomic_path", "atomic_write", "is_path"]

PathLike = Union[str, "os.PathLike[str]"]


def is_path(target: Any) -> bool:
    """Whether ``target`` names a file (rather than being an open file object)."""
    return isinstance(target, (str, bytes, os.PathLike))


@contextmanager
def atomic_path(path: PathLike) -> Iterator[str]:
    """Yields a temporary path in the directory of ``path``; on a normal exit it is flushed to
    disk and renamed onto ``path`` (atomically), on an exception it is removed."""
    target = os.fsdecode(os.fspath(path))
    directory, name = os.path.split(os.path.abspath(target))
    extension = os.path.splitext(name)[1]
    tmp = os.path.join(directory, f".{name}.{secrets.token_hex(6)}.tmp{extension}")
    try:
        yield tmp
        with open(tmp, "rb") as handle:
            os.fsync(handle.fileno())
        os.replace(tmp, target)
    except BaseException:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


def atomic_write(path: Any, writer: Callable[[Any], None]) -> None:
    """Calls ``writer(tmp)`` with a temporary path and moves the result onto ``path``.

    An open file object (anything but a path) is passed to ``writer`` directly.
    """
    if not is_path(path):
        writer(path)
        return
    with atomic_path(path) as tmp:
        writer(tmp)
