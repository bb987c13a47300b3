"""Table 2 of the paper: numerical accuracy of the one-mode model.

The maximum amplitude ``max |theta_1(t)|`` over ``0 <= t <= 1`` of the one-mode Duffing equation
(eq. 19) from classical RK4 at ``dt = 1e-4`` (the reference ``A_ref``) and from the explicit
central-difference scheme ``x[n+1] = 2x[n] - x[n-1] - dt^2 (a2 x[n] + a3 x[n]^3)/a1``, started
with ``x[0] = 0``, ``x[1] = dt C1`` (model notes, erratum 5) at four steps, with the relative
difference ``delta_A = |A_h - A_ref| / A_ref * 100 %`` (eq. 22).
"""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Optional

import numpy as np

from ..io.output import write_text
from ..model.parameters import Parameters, preset
from ..solvers.modal import Method, simulate

__all__ = ["Table2Row", "PAPER_TABLE2", "table2", "format_table2", "write_table2_csv", "table2_json"]

#: The rows as printed in the paper: (method, dt, max amplitude, difference %).
PAPER_TABLE2 = (
    ("Runge-Kutta", 1.0e-4, 5.061e-4, 0.000),
    ("Finite difference", 1.0e-3, 5.086e-4, 0.481),
    ("Finite difference", 5.0e-4, 5.068e-4, 0.120),
    ("Finite difference", 2.5e-4, 5.063e-4, 0.030),
    ("Finite difference", 1.0e-4, 5.062e-4, 0.005),
)

#: Steps of the central-difference rows.
CENTRAL_STEPS = (1.0e-3, 5.0e-4, 2.5e-4, 1.0e-4)


@dataclass(frozen=True)
class Table2Row:
    method: str
    """"Runge-Kutta" (the reference) or "Finite difference"."""
    dt: float
    """Time step, s."""
    max_amplitude: float
    """``max |theta_1(t)|`` over ``0 <= t <= 1``, rad."""
    difference_percent: float
    """``|A_h - A_ref| / A_ref * 100``."""


def _max_amplitude(params: Parameters, method: Method, dt: float, t_end: float) -> float:
    # t_eval=None: every step, so the maximum is over all step values as in the paper.
    result = simulate(params, modes=1, t_end=t_end, method=method, dt=dt)
    return float(np.max(np.abs(result.q[0])))


def table2(
    params: Optional[Parameters] = None,
    *,
    reference_dt: float = 1.0e-4,
    steps: Sequence[float] = CENTRAL_STEPS,
    t_end: float = 1.0,
) -> list[Table2Row]:
    """Computes Table 2 (default: the paper's reference set, Table 1 with C1 = 0.1).

    Examples
    --------
    >>> rows = table2()
    >>> f"{rows[0].max_amplitude:.3e}"
    '5.061e-04'
    """
    params = preset("aluminum") if params is None else params
    reference = _max_amplitude(params, "rk4", reference_dt, t_end)
    rows = [Table2Row("Runge-Kutta", reference_dt, reference, 0.0)]
    for dt in steps:
        amplitude = _max_amplitude(params, "central", dt, t_end)
        rows.append(
            Table2Row("Finite difference", dt, amplitude, abs(amplitude - reference) / reference * 100)
        )
    return rows


def format_table2(rows: Sequence[Table2Row]) -> str:
    """The table as aligned text, with the paper's printed values beside ours."""
    lines = [
        f"{'Numerical method':<18} {'dt, s':>9} {'Max. amplitude, rad':>20} {'Difference, %':>14}"
        f"   {'paper: amplitude':>16} {'difference':>10}"
    ]
    for row, paper in zip(rows, PAPER_TABLE2):
        lines.append(
            f"{row.method:<18} {row.dt:>9.1e} {row.max_amplitude:>20.4e} {row.difference_percent:>14.3f}"
            f"   {paper[2]:>16.3e} {paper[3]:>10.3f}"
        )
    return "\n".join(lines)


def table2_json(rows: Sequence[Table2Row]) -> str:
    """JSON: a list of objects with keys method, dt, max_amplitude, difference_percent."""
    return json.dumps([asdict(row) for row in rows], indent=2)


def write_table2_csv(rows: Sequence[Table2Row], path: Any) -> Path:
    """Writes the rows as CSV (method, dt, max_amplitude, difference_percent) to ``path`` and
    returns it (see :mod:`drillstring.io.output` for how existing files, symlinks, devices and
    ``"-"`` are treated)."""
    text = io.StringIO(newline="")
    writer = csv.writer(text)
    writer.writerow(["method", "dt", "max_amplitude", "difference_percent"])
    for row in rows:
        writer.writerow([row.method, repr(row.dt), repr(row.max_amplitude), repr(row.difference_percent)])
    return write_text(path, text.getvalue())
