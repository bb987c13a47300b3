"""Former home of the atomic writer; kept as a re-export of :mod:`drillstring.io.output`."""

from __future__ import annotations

from .output import atomic_path, atomic_write, is_path, write_bytes

__all__ = ["atomic_path", "atomic_write", "is_path", "write_bytes"]
