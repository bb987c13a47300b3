"""Deprecated: ``drillstring.grid`` moved to ``drillstring.studies.sweep_axes``. This path works for
one release; each name used through it warns with a DeprecationWarning."""

from __future__ import annotations

from typing import Any

from drillstring._deprecated import forward, names

_TARGETS = ('drillstring.studies.sweep_axes',)


def __getattr__(name: str) -> Any:
    return forward(__name__, name, _TARGETS)


def __dir__() -> list[str]:
    return names(_TARGETS)
