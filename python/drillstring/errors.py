"""Exceptions raised by drillstring.

* :class:`ValidationError` (a :class:`ValueError`): an input was refused before any work was
  done. The message names the field, the value and the allowed range; so do the attributes.
* :class:`SolveError` (a :class:`RuntimeError`): a solve ended early (step limit, step-size
  underflow, non-finite state). ``status`` is the short status name; ``result`` holds what was
  computed before the failure.
* :class:`MissingExtraError` (an :class:`ImportError`): an optional output was asked for without
  the optional dependencies (the extra) it needs; the message names the extra to install.

Ctrl-C during a solve raises :class:`KeyboardInterrupt` within a few milliseconds (the Rust core
polls Python's signal handlers while it runs without the GIL).
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "DrillstringError", "ValidationError", "SolveError", "MissingExtraError", "DrillstringWarning", "ResumeWarning",
    "SamplingWarning",
]


class DrillstringError(Exception):
    """Base class of every exception raised by drillstring."""


class ValidationError(DrillstringError, ValueError):
    """An input value outside its allowed range.

    Attributes
    ----------
    field:
        Name of the offending field or option (e.g. ``"poisson_ratio"``).
    value:
        The value that was given.
    allowed:
        Human-readable description of the allowed values (e.g. ``"-1 < poisson_ratio < 0.5"``).
    source:
        The file the value came from (e.g. a TOML file), or ``None``.
    line:
        Its line in ``source`` (1-based), when known.
    """

    def __init__(
        self, field: str, value: Any, allowed: str, *, source: str | None = None, line: int | None = None
    ) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        self.source = source
        self.line = line
        where = f"{source}, line {line}: " if source and line else f"{source}: " if source else ""
        super().__init__(f"{where}invalid {field}: got {value!r}, expected {allowed}")


class SolveError(DrillstringError, RuntimeError):
    """A solve ended before ``t_end``.

    Attributes
    ----------
    status:
        ``"max_steps"``, ``"step_size_underflow"`` or ``"non_finite"`` (a solve interrupted by
        Ctrl-C raises ``KeyboardInterrupt`` instead).
    result:
        The partial result (samples up to the failure), or ``None``.
    """

    def __init__(self, status: str, message: str, result: Any = None) -> None:
        self.status = status
        self.result = result
        super().__init__(f"solve failed ({status}): {message}")


class MissingExtraError(DrillstringError, ImportError):
    """An optional output needs modules that are not installed: those of an extra of the package.

    Attributes
    ----------
    extra:
        The extra that brings them (``"netcdf"``).
    missing:
        The modules that could not be imported.
    """

    def __init__(self, extra: str, purpose: str, missing: tuple[str, ...]) -> None:
        self.extra = extra
        self.missing = missing
        super().__init__(
            f"{purpose} needs the optional dependencies of the extra '{extra}' ({', '.join(missing)} not installed):"
            f" pip install '.[{extra}]' (or '.[all]') in the drillstring checkout",
            name=missing[0] if missing else None,
        )


class DrillstringWarning(UserWarning):
    """Base class of the warnings drillstring issues (the command line prints each as one line,
    ``drillstring: warning: ...``)."""


class ResumeWarning(DrillstringWarning):
    """A resumed sweep found a stored chunk that failed verification (altered bytes, a file of
    another chunk or sweep, a missing checksum record) and recomputed it; the message names the
    chunk and the reason."""


class SamplingWarning(DrillstringWarning):
    """Output times too sparse to resolve the fastest retained mode: fewer than
    :data:`~drillstring.limits.SAMPLES_PER_PERIOD` samples per period (plots become polygonal,
    peak amplitudes are cut, and below 2 an FFT of the output finds an alias). The message gives
    the samples per period and the samples needed."""
