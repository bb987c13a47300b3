"""Reproduce every numerical result of the paper as a readable report: ``drillstring paper``.

:func:`reproduce` writes into one directory

* ``fig01.png`` ... ``fig15.png``: the paper's figures (same content and parameters; the plot
  functions are in :mod:`drillstring.plots`), each with the data behind it as ``figNN.csv``;
* ``table2.csv``: Table 2 (:func:`drillstring.studies.table2.table2`);
* ``stability.csv``: eigenvalues of the Jacobian at the equilibrium, classification and critical
  speeds (:mod:`drillstring.studies.stability`) for 1, 2 and 3 modes on every parameter set of the
  figures;
* ``report.md`` and ``report.html`` (self-contained, images embedded): per figure and table the
  paper's claim and the numbers measured here that check it (amplitude, dominant frequencies
  from an FFT of the plotted signal, boundedness, energy drift, phase shift...), the physics
  notes (where the printed model departs from classical torsion), the errata of the printed
  equations and how the software handles them, and the exact call behind each result.

The package is split by job:

* :mod:`~drillstring.report.specs`: the figures as data (runs, time spans, what is plotted, the
  paper's claim);
* :mod:`~drillstring.report.measure`: the runs and the numbers measured on them;
* :mod:`~drillstring.report.checks`: one checker per figure group, each stating its criterion;
* :mod:`~drillstring.report.document` and :mod:`~drillstring.report.render`: the report as a list
  of blocks and its Markdown and HTML through Jinja2 templates;
* :mod:`~drillstring.report.run`: :func:`reproduce` and :func:`figure`, the files written.
"""

from __future__ import annotations

from . import checks, document, measure, render, run, specs
from .checks import CRITERIA
from .document import FigureResult, ReproductionReport
from .measure import CurveMetrics, PhysicsNotes, StabilityRow, physics_notes, stability_rows
from .run import STABILITY_COLUMNS, figure, output_names, reproduce
from .specs import (
    ATOL,
    DPI,
    FIGURES,
    METHOD,
    PARAMETER_SETS,
    QUICK_SAMPLES_PER_SECOND,
    QUICK_T_END_SCALE,
    RTOL,
    RUNS,
    SAMPLES_PER_SECOND,
    FigureSpec,
    RunSpec,
)

#: The runs of a reproduction (computed on demand, cached).
_Runs = measure.Runs

__all__ = [
    "RTOL",
    "ATOL",
    "METHOD",
    "DPI",
    "SAMPLES_PER_SECOND",
    "QUICK_SAMPLES_PER_SECOND",
    "QUICK_T_END_SCALE",
    "RunSpec",
    "FigureSpec",
    "RUNS",
    "FIGURES",
    "PARAMETER_SETS",
    "CRITERIA",
    "STABILITY_COLUMNS",
    "CurveMetrics",
    "FigureResult",
    "StabilityRow",
    "PhysicsNotes",
    "ReproductionReport",
    "reproduce",
    "figure",
    "output_names",
    "stability_rows",
    "physics_notes",
    "checks",
    "document",
    "measure",
    "render",
    "run",
    "specs",
]
