"""Deprecated module paths of the package: each old path forwards its names to their new
module and warns (PEP 562 module ``__getattr__``, as scipy does), for one release."""

from __future__ import annotations

import importlib
import warnings
from typing import Any


def forward(old: str, name: str, targets: tuple[str, ...]) -> Any:
    """``name`` of the deprecated module ``old`` from the first of ``targets`` that has it, with
    a DeprecationWarning at the caller's line."""
    if name.startswith("__"):
        raise AttributeError(name)
    for target in targets:
        module = importlib.import_module(target)
        if hasattr(module, name):
            warnings.warn(f"{old} is deprecated: use {target}.{name} (the old path works for one release)",
                          DeprecationWarning, stacklevel=3)
            return getattr(module, name)
    raise AttributeError(f"module {old!r} has no attribute {name!r}")


def names(targets: tuple[str, ...]) -> list[str]:
    """The public names of ``targets`` (for ``dir()`` and star imports)."""
    out: set[str] = set()
    for target in targets:
        out |= {n for n in dir(importlib.import_module(target)) if not n.startswith("_")}
    return sorted(out)
