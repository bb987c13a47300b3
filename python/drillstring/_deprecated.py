"""Deprecated module paths and names of the package: each old path forwards its names to their
new module and each old name gives its new object, with a DeprecationWarning at the caller's line
(PEP 562 module ``__getattr__``, as scipy does), for one release."""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Mapping
from typing import Any


def forward(old: str, name: str, targets: tuple[str, ...]) -> Any:
    """``name`` of the deprecated module ``old`` from the first of ``targets`` that has it, with
    a DeprecationWarning at the caller's line."""
    if name.startswith("__"):
        raise AttributeError(name)
    for target in targets:
        module = importlib.import_module(target)
        # a name the new module renamed (``_RENAMED``: old -> new) is named by its new name
        new = vars(module).get("_RENAMED", {}).get(name, name)
        if new in vars(module):
            warnings.warn(f"{old} is deprecated: use {target}.{new} (the old path works for one release)",
                          DeprecationWarning, stacklevel=3)
            return vars(module)[new]
    raise AttributeError(f"module {old!r} has no attribute {name!r}")


def renamed(module: str, name: str, namespace: Mapping[str, Any]) -> Any:
    """The body of a module ``__getattr__`` for its renamed names: ``namespace`` (the module's
    globals) maps each old name to its new one in ``_RENAMED``; the old name gives the same object
    with a DeprecationWarning at the caller's line."""
    names = namespace.get("_RENAMED", {})
    if name in names:
        new = names[name]
        warnings.warn(f"{module}.{name} is deprecated: use {module}.{new} (the old name works for one release)",
                      DeprecationWarning, stacklevel=3)
        return namespace[new]
    raise AttributeError(f"module {module!r} has no attribute {name!r}")


def names(targets: tuple[str, ...]) -> list[str]:
    """The public names of ``targets`` (for ``dir()`` and star imports)."""
    out: set[str] = set()
    for target in targets:
        out |= {n for n in dir(importlib.import_module(target)) if not n.startswith("_")}
    return sorted(out)
