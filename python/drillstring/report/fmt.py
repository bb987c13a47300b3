"""How numbers appear in the report's prose and tables."""

from __future__ import annotations

import math
from collections.abc import Sequence


def sci(x: float, digits: int = 3) -> str:
    """Compact scientific notation: 5.061e-4 (``n/a`` if not finite)."""
    if not math.isfinite(x):
        return "n/a"
    mant, exp = f"{x:.{digits}e}".split("e")
    return f"{mant}e{int(exp)}"


def hz(freqs: Sequence[float], n: int = 3) -> str:
    """The first ``n`` frequencies, ``31.62, 63.20 Hz`` (``none found`` if there are none)."""
    return ", ".join(f"{f:.2f}" for f in freqs[:n]) + " Hz" if len(freqs) else "none found"


def pct(a: float, b: float) -> str:
    """``a`` relative to ``b``: ``+1.8 %``."""
    return f"{(a / b - 1) * 100:+.1f} %"
