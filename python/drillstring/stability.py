"""Deprecated: ``drillstring.stability`` moved to ``drillstring.studies.stability``. This path works
for one release; each name used through it warns with a DeprecationWarning."""

from __future__ import annotations

from typing import Any

from drillstring._deprecated import forward, names

_TARGETS = ('drillstring.studies.stability',)


def __getattr__(name: str) -> Any:
    return forward(__name__, name, _TARGETS)


def __dir__() -> list[str]:
    return names(_TARGETS)
