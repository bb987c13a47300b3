"""The reproduction: :func:`reproduce` runs the figures (plots, data, measurements, checks), Table 2,
the stability table and the truncation study, and writes every file through
:mod:`drillstring.io.output`; :func:`figure` gives one figure alone.
"""

from __future__ import annotations

import csv
import io
import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Optional

import numpy as np

from .. import plots
from ..errors import ValidationError
from ..io.output import check_destination, write_bytes, write_text, writing_folder
from ..io.progress import bar as progress_bar
from ..model.parameters import preset
from ..studies import analysis
from ..studies import convergence as _convergence
from ..studies.stability import analyse
from ..studies.table2 import table2, write_table2_csv
from . import document, render, specs
from .checks import assess
from .document import FigureResult, ReproductionReport
from .measure import Runs, StabilityRow, measure, physics_notes, references, safe, signal, stability_rows, window_mask
from .specs import DPI, RUNS, SAMPLES_PER_SECOND, FigureSpec, PathLike


def _plot(spec: FigureSpec, runs: Runs, window: tuple[float, float], title: str) -> Any:
    sims = {label: runs[key] for key, label, _ in spec.runs}
    if spec.kind == "modal":
        return plots.modal_response(next(iter(sims.values())), window=window, title=title)
    if spec.kind == "modal_phase":
        return plots.modal_phase_portrait(next(iter(sims.values())), window=window, title=title)
    if spec.kind == "linear":
        return plots.linear_vs_nonlinear(sims["linear"], sims["nonlinear"], window=window, title=title)
    if spec.kind == "linear_phase":
        return plots.linear_vs_nonlinear_phase(sims["linear"], sims["nonlinear"], window=window, title=title)
    if spec.kind == "section":
        return plots.section_response(sims, window=window, title=title)
    if spec.kind == "section_phase":
        return plots.section_phase_portrait(sims, window=window, title=title)
    raise ValueError(f"unknown figure kind {spec.kind!r}")  # pragma: no cover


def _figure_table(spec: FigureSpec, runs: Runs, window: tuple[float, float]) -> tuple[list[str], np.ndarray]:
    """The data behind a figure: ``t`` and per curve the plotted signal and its rate."""
    first = runs[spec.runs[0][0]]
    mask = window_mask(first.t, window)
    header = ["t"]
    columns = [first.t[mask]]
    modal = not spec.kind.startswith("section")
    for key, _, tag in spec.runs:
        res = runs[key]
        x, v, _ = signal(spec.kind, res)
        name, rate = ("theta1", "theta1_dot") if modal else ("theta_zk", "theta_dot_zk")
        suffix = f"_{tag}" if len(spec.runs) > 1 else ""
        header += [name + suffix, rate + suffix]
        columns += [x[mask], v[mask]]
    if spec.kind == "linear":
        lin, nl = runs["linear10"], runs["nonlinear10"]
        shift = safe(analysis.phase_shift, lin.t, lin.q[0], nl.q[0], lin.t[mask],
                      default=np.full(int(mask.sum()), math.nan))
        header.append("phase_shift_deg")
        columns.append(np.degrees(shift))
    if spec.kind.startswith("section") and len(spec.runs) == 1:
        res = first
        for j, i in enumerate(res.indices.tolist()):
            header.append(f"q{i}")
            columns.append(res.q[j][mask])
    return header, np.column_stack(columns)


def _write_csv(path: Path, header: Sequence[str], data: np.ndarray) -> Path:
    text = io.BytesIO()
    np.savetxt(text, data, delimiter=",", header=",".join(header), comments="", fmt="%.17g")
    return write_bytes(path, text.getvalue(), field="out_dir")


STABILITY_COLUMNS = (
    "parameter_set", "material", "length_m", "omega_rad_s", "modes", "mode", "eigenvalue_real",
    "eigenvalue_imag", "linear_frequency_hz", "critical_speed_rad_s", "omega_over_critical",
    "mode_classification", "classification", "figures",
)


def _write_stability_csv(rows: Sequence[StabilityRow], path: Path) -> Path:
    text = io.StringIO(newline="")
    writer = csv.writer(text)
    writer.writerow(STABILITY_COLUMNS)
    for r in rows:
        writer.writerow([
            r.parameter_set, r.material, repr(r.length), repr(r.omega), r.modes, r.mode,
            repr(r.eigenvalue.real), repr(r.eigenvalue.imag), repr(r.linear_frequency_hz),
            repr(r.critical_speed), repr(r.omega_over_critical), r.mode_classification,
            r.classification, r.figures,
        ])
    return write_text(path, text.getvalue(), field="out_dir")


def _progress_stream(progress: Optional[bool]) -> Optional[Any]:
    if progress is None:
        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    return sys.stderr if progress else None


def reproduce(
    out_dir: PathLike,
    *,
    t_end_scale: float = 1.0,
    samples_per_second: int = SAMPLES_PER_SECOND,
    progress: Optional[bool] = None,
    command: Optional[str] = None,
    convergence: bool = True,
) -> ReproductionReport:
    """Regenerates every numerical result of the paper into ``out_dir`` (created if needed).

    Parameters
    ----------
    out_dir :
        Directory for ``fig01.png`` ... ``fig15.png``, ``figNN.csv``, ``table2.csv``,
        ``stability.csv``, ``report.md`` and ``report.html``.
    t_end_scale :
        Multiplies every time span (end times, windows, phase-shift times); 1 reproduces the
        paper, 0.1 is the quick test run. Table 2 and the stability table do not depend on it.
    samples_per_second :
        Output samples per second of simulated time.
    progress :
        Print one line per figure to stderr ("[ 3/15] fig03 linear vs nonlinear ... 0.4 s");
        default: when stderr is a terminal.
    command :
        The command line to quote in the report (default: the equivalent ``drillstring paper``).
    convergence :
        Add the truncation study beyond the paper (:mod:`drillstring.studies.convergence`: Galerkin
        models against the converged PDE solution; ``convergence.csv``, ``grids.csv``,
        ``reference.csv``, ``convergence.png``).

    Returns
    -------
    ReproductionReport
    """
    if isinstance(t_end_scale, bool) or not isinstance(t_end_scale, (int, float)) or not (
        math.isfinite(t_end_scale) and 0 < t_end_scale <= 10
    ):
        raise ValidationError("t_end_scale", t_end_scale, "a number with 0 < t_end_scale <= 10")
    if isinstance(samples_per_second, bool) or not isinstance(samples_per_second, int) or not (
        100 <= samples_per_second <= 100_000
    ):
        raise ValidationError(
            "samples_per_second", samples_per_second, "an integer, 100 <= samples_per_second <= 100000"
        )
    check_destination(out_dir, field="out_dir", directory=True, files=output_names(convergence))
    start = time.perf_counter()
    with writing_folder(out_dir, field="out_dir", owned=_owned) as folder:
        out, at = folder.path, folder.directory
        stream = _progress_stream(progress)
        scale = float(t_end_scale)
        if command is None:
            command = f"drillstring paper --out {out}" + ("" if scale == 1.0 else f" --t-end-scale {scale:g}")
            if samples_per_second != SAMPLES_PER_SECOND:
                command += f"  # samples_per_second={samples_per_second}"
        runs = Runs(scale, samples_per_second)
        timings: dict[str, float] = {}
        files: list[Path] = []
        images: dict[str, bytes] = {}

        # On a terminal a tqdm bar of the steps under the lines; elsewhere the lines alone.
        bar = progress_bar(len(specs.FIGURES) + (4 if convergence else 3), "paper", "steps",
                           enabled=stream is not None and bool(getattr(stream, "isatty", lambda: False)()))

        def tick(label: str, seconds: float) -> None:
            timings[label] = seconds
            if stream is not None:
                bar.write(f"{label} ... {seconds:.1f} s", file=stream)
                bar.update(1)

        t0 = time.perf_counter()
        ctx = references(runs)
        ctx["rigid"] = float(analyse(preset("aluminum"), modes=1, rigid_mode=True).mode_eigenvalues[0].real)
        tick("[ 0/15] simulations and reference values", time.perf_counter() - t0)
        results: list[FigureResult] = []
        total = len(specs.FIGURES)
        for spec in specs.FIGURES:
            t0 = time.perf_counter()
            window = (spec.window[0] * scale, spec.window[1] * scale)
            title = spec.caption if scale == 1.0 else f"{spec.caption} (quick run, times x{scale:g})"
            fig = _plot(spec, runs, window, title)
            png = out / f"{spec.stem}.png"
            image = io.BytesIO()
            fig.savefig(image, dpi=DPI, format="png")
            images[png.name] = image.getvalue()
            write_bytes(at / png.name, images[png.name], field="out_dir")
            header, data = _figure_table(spec, runs, window)
            csv_path = out / f"{spec.stem}.csv"
            _write_csv(at / csv_path.name, header, data)
            curves = measure(spec, runs, window)
            findings, verdict = assess(spec.number, curves, ctx)
            keys = list(dict.fromkeys(key for key, _, _ in spec.runs))
            python = [f"{key} = {RUNS[key].python(scale, samples_per_second)}" for key in keys]
            cli = [c for c in (RUNS[key].cli(scale, samples_per_second) for key in keys) if c]
            python.append(_plot_call(spec, window))
            seconds = time.perf_counter() - t0
            results.append(FigureResult(spec.number, spec.caption, spec.kind, png, csv_path, curves,
                                        spec.claim, findings, verdict, seconds, python, cli))
            files += [png, csv_path]
            tick(f"[{spec.number:2d}/{total}] {spec.stem} {spec.name}", seconds)
        t0 = time.perf_counter()
        rows2 = table2()
        write_table2_csv(rows2, at / "table2.csv")
        files.append(out / "table2.csv")
        srows = stability_rows()
        _write_stability_csv(srows, at / "stability.csv")
        files.append(out / "stability.csv")
        tick("        table 2 and stability", time.perf_counter() - t0)
        study = None
        if convergence:
            t0 = time.perf_counter()
            quick: dict[str, Any] = {} if scale == 1.0 else {"cells": 60, "max_nodes": 241, "tol": 1e-3,
                                                              "modes": (1, 2, 3, 6)}
            study = _convergence.study(preset("aluminum"), t_end=scale, samples=max(201, int(1000 * scale) + 1),
                                       **quick)
            rendered = _convergence.render(study)
            files += [folder.shown(write_bytes(at / name, data, field="out_dir")) for name, data in rendered.items()]
            images.update((name, data) for name, data in rendered.items() if name.endswith(".png"))
            tick("        truncation study against the PDE", time.perf_counter() - t0)
        t0 = time.perf_counter()
        rep = ReproductionReport(out, scale, samples_per_second, results, rows2, srows, files, timings, 0.0)
        rep.notes = {"context": ctx, "convergence": study, "physics": physics_notes()}
        rep.total_seconds = time.perf_counter() - start
        doc = document.build(rep, ctx, command)
        write_text(at / rep.report_md.name, render.markdown(doc), field="out_dir")
        write_text(at / rep.report_html.name, render.html(doc, images), field="out_dir")
        files += [rep.report_md, rep.report_html]
        tick("        report.md, report.html", time.perf_counter() - t0)
        bar.close()
        rep.total_seconds = time.perf_counter() - start
        return rep


def _owned(name: str) -> bool:
    """Whether ``name`` is a file of the reproduction (:func:`output_names`): replaced by each
    run; the folder's other entries are kept."""
    return name in _ALL_NAMES


def output_names(convergence: bool = True) -> list[str]:
    """The names of the files :func:`reproduce` writes into its directory."""
    names = [f"{spec.stem}.{ext}" for spec in specs.FIGURES for ext in ("png", "csv")]
    names += ["table2.csv", "stability.csv"]
    if convergence:
        names += list(_convergence.FILES)
    return [*names, "report.md", "report.html"]


def figure(
    number: int, *, t_end_scale: float = 1.0, samples_per_second: int = SAMPLES_PER_SECOND
) -> Any:
    """One of the paper's figures (1-15) as a matplotlib Figure, computed from scratch.

    >>> fig = figure(10)                    # doctest: +SKIP
    >>> fig.axes[0].set_ylim(-2e-3, 2e-3)   # doctest: +SKIP
    >>> fig.savefig("fig10.svg")            # doctest: +SKIP
    """
    by_number = {spec.number: spec for spec in specs.FIGURES}
    if number not in by_number:
        raise ValidationError("number", number, "a figure number, 1 <= number <= 15")
    spec = by_number[number]
    window = (spec.window[0] * t_end_scale, spec.window[1] * t_end_scale)
    return _plot(spec, Runs(float(t_end_scale), samples_per_second), window, spec.caption)


def _plot_call(spec: FigureSpec, window: tuple[float, float]) -> str:
    win = f"window=({window[0]:g}, {window[1]:g})"
    title = f"title={spec.caption!r}"
    if spec.kind in ("modal", "modal_phase"):
        func = "modal_response" if spec.kind == "modal" else "modal_phase_portrait"
        return f"fig = ds.plots.{func}(one_mode, {win}, {title})"
    if spec.kind in ("linear", "linear_phase"):
        func = "linear_vs_nonlinear" if spec.kind == "linear" else "linear_vs_nonlinear_phase"
        return f"fig = ds.plots.{func}(linear10, nonlinear10, {win}, {title})"
    func = "section_response" if spec.kind == "section" else "section_phase_portrait"
    runs = "{" + ", ".join(f"{label!r}: {key}" for key, label, _ in spec.runs) + "}"
    return f"fig = ds.plots.{func}({runs}, {win}, {title})"


_ALL_NAMES = frozenset(output_names(True))
