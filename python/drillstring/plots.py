"""Plots of simulation results; every function returns a matplotlib Figure.

matplotlib is imported lazily and figures are built with :class:`matplotlib.figure.Figure`
(Agg canvas, no pyplot state), so the functions work on headless machines and in threads. Style
a returned figure as usual (``fig.axes``, ``ax.lines``) and write it with :func:`save` or
``fig.savefig``.

The paper's figures (``drillstring paper``, :mod:`drillstring.report`) are built from:

* :func:`modal_response`, :func:`modal_phase_portrait`: one modal coordinate ``theta_i(t)`` and
  its phase portrait (Figs. 1, 2);
* :func:`linear_vs_nonlinear`, :func:`linear_vs_nonlinear_phase`: the linearised against the
  nonlinear model, with the accumulated phase shift and a zoom on the amplitude (Figs. 3-5);
* :func:`section_response`, :func:`section_phase_portrait`: ``theta(z_k, t)`` at a section
  (default ``z_k = 2l/3``) and the phase-plane projection ``(theta, theta_dot)`` there, for one
  run or several runs compared (Figs. 6-15).

Curves are told apart by colour *and* line style (blue solid, orange dashed, green dash-dot, as
listed in :data:`COLORS` and :data:`LINESTYLES`). When several runs are compared, the figure
shows them overlaid, as in the paper, and again one per panel with its own scale, so that a
small response is not flattened by a large one.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from .io.figures import plot_path, save  # noqa: F401 (plot_path stays importable from here)
from .solvers.trajectory import default_section

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from .solvers.modal import Simulation

__all__ = [
    "COLORS",
    "LINESTYLES",
    "time_history_and_phase",
    "modal_response",
    "modal_phase_portrait",
    "linear_vs_nonlinear",
    "linear_vs_nonlinear_phase",
    "section_response",
    "section_phase_portrait",
    "save",
]

#: Colours of the 1st, 2nd, 3rd... curve of a figure (the paper's blue, orange, green).
COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")
#: Line styles of the 1st, 2nd, 3rd... curve.
LINESTYLES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1)))

Runs = Union["Simulation", Mapping[str, "Simulation"]]
Window = Optional[Sequence[float]]


def _figure(**kwargs: object) -> Figure:
    from matplotlib.figure import Figure

    return Figure(**kwargs)  # type: ignore[arg-type]


def time_history_and_phase(result: Simulation, z: Optional[float] = None, title: Optional[str] = None) -> Figure:
    """Time history ``theta(z, t)`` and phase portrait ``(theta, theta_dot)`` at section ``z``.

    ``z`` defaults to ``z_k = 2l/3``, the paper's section.
    """
    length = result.params.length
    z = default_section(length) if z is None else z
    theta = result.theta(z)
    theta_dot = result.theta_dot(z)
    fig = _figure(figsize=(11, 4.2), layout="constrained")
    ax_t, ax_p = fig.subplots(1, 2, width_ratios=[1.6, 1])
    ax_t.plot(result.t, theta, lw=0.9)
    ax_t.set_xlabel("t, s")
    ax_t.set_ylabel(r"$\theta(z, t)$, rad")
    ax_t.grid(alpha=0.3)
    ax_p.plot(theta, theta_dot, lw=0.6)
    ax_p.set_xlabel(r"$\theta$, rad")
    ax_p.set_ylabel(r"$\dot\theta$, rad/s")
    ax_p.grid(alpha=0.3)
    for ax in (ax_t, ax_p):
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 3))
    modes = ", ".join(str(i) for i in result.indices)
    fig.suptitle(title or f"z = {z:.4g} m of l = {length:.4g} m, modes {modes}, {result.method}")
    return fig


# --------------------------------------------------------------------------- helpers


def _style(k: int) -> dict[str, object]:
    return {"color": COLORS[k % len(COLORS)], "linestyle": LINESTYLES[k % len(LINESTYLES)]}


def _window_mask(t: np.ndarray, window: Window) -> np.ndarray:
    if window is None:
        return np.ones(t.shape, dtype=bool)
    lo, hi = float(window[0]), float(window[1])
    span = hi - lo
    return (t >= lo - 1e-9 * span) & (t <= hi + 1e-9 * span)


def _title(fig: Figure, title: Optional[str], width: int = 110) -> None:
    if title:
        fig.suptitle("\n".join(textwrap.wrap(title, width)), fontsize=11)


def _sci(ax: Axes) -> None:
    ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
    ax.grid(alpha=0.3)


def _legend_above(ax: Axes, ncol: int = 3, fontsize: float = 9) -> None:
    """Legend above the top-right corner of the axes, clear of the oscillating curves."""
    ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=ncol, fontsize=fontsize,
              frameon=False, borderaxespad=0.1, handlelength=2.6)


def _runs(results: Runs) -> dict[str, Simulation]:
    if isinstance(results, Mapping):
        return dict(results)
    length = results.params.length
    return {f"l = {length:g} m": results}


def _section(result: Simulation, z: Optional[float]) -> float:
    return default_section(result.params.length) if z is None else float(z)


def _phase_axes_labels(ax: Axes, symbol: str) -> None:
    ax.set_xlabel(rf"${symbol}$, rad")
    ax.set_ylabel(rf"$\dot{{{symbol}}}$, rad/s" if "_" not in symbol else rf"$d{symbol}/dt$, rad/s")


# --------------------------------------------------------------------------- one mode


def modal_response(
    result: Simulation, mode: int = 1, *, window: Window = None, title: Optional[str] = None
) -> Figure:
    """Time history of the generalised coordinate ``theta_i(t)`` (``q`` of mode ``i``), Fig. 1."""
    k = int(np.nonzero(result.indices == mode)[0][0])
    mask = _window_mask(result.t, window)
    fig = _figure(figsize=(10, 4.2), layout="constrained", dpi=120)
    ax = fig.subplots()
    label = rf"$\theta_{mode}(t)$, {result.indices.size}-mode model"
    ax.plot(result.t[mask], result.q[k][mask], lw=1.0, label=label, **_style(0))
    ax.set_xlabel("t, s")
    ax.set_ylabel(rf"$\theta_{mode}(t)$, rad")
    ax.set_xlim(result.t[mask][0], result.t[mask][-1])
    _legend_above(ax, 1)
    _sci(ax)
    _title(fig, title)
    return fig


def modal_phase_portrait(
    result: Simulation, mode: int = 1, *, window: Window = None, title: Optional[str] = None
) -> Figure:
    """Phase portrait ``(theta_i, d theta_i / dt)`` of one modal coordinate, Fig. 2.

    The start ``t = 0`` is marked; the orbit of a centre is retraced once per period.
    """
    k = int(np.nonzero(result.indices == mode)[0][0])
    mask = _window_mask(result.t, window)
    q, v = result.q[k][mask], result.qdot[k][mask]
    fig = _figure(figsize=(6.4, 5.6), layout="constrained", dpi=120)
    ax = fig.subplots()
    ax.plot(q, v, lw=0.8, alpha=0.8, label=rf"trajectory, $0 \leq t \leq {result.t[mask][-1]:g}$ s", **_style(0))
    ax.plot(q[0], v[0], "o", color="black", ms=5, label=f"t = {result.t[mask][0]:g} s")
    _arrow(ax, q, v, COLORS[0])
    ax.plot(0, 0, "+", color="black", ms=9, mew=1.2, label="equilibrium")
    _phase_axes_labels(ax, rf"\theta_{mode}")
    # inside the orbit of a centre there is room for the legend
    ax.legend(loc="center", bbox_to_anchor=(0.5, 0.3), fontsize=8)
    _sci(ax)
    _title(fig, title, 60)
    return fig


def _arrow(ax: Axes, x: np.ndarray, y: np.ndarray, color: str) -> None:
    """Direction of motion: an arrow head on the trajectory about 1/8 of a turn after the start."""
    sx = float(np.ptp(x)) or 1.0
    sy = float(np.ptp(y)) or 1.0
    dist = np.hypot((x - x[0]) / sx, (y - y[0]) / sy)
    far = np.nonzero(dist > 0.3)[0]
    n = int(far[0]) if far.size else len(x) - 1
    back = max(0, n - max(2, n // 6))
    ax.annotate("", xy=(x[n], y[n]), xytext=(x[back], y[back]),
                arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.5, "mutation_scale": 16})


def linear_vs_nonlinear(
    linear: Simulation,
    nonlinear: Simulation,
    mode: int = 1,
    *,
    window: Window = None,
    title: Optional[str] = None,
) -> Figure:
    """``theta_i(t)`` of the linearised and the nonlinear model (Figs. 3, 5) and, below, the
    accumulated phase shift of the nonlinear response (zero crossings, :func:`analysis.phase_shift`)
    over the whole record, the window shaded.
    """
    from .studies.analysis import phase_shift

    k = int(np.nonzero(linear.indices == mode)[0][0])
    mask = _window_mask(linear.t, window)
    t = linear.t
    fig = _figure(figsize=(10, 6.2), layout="constrained", dpi=120)
    ax, ax_s = fig.subplots(2, 1, gridspec_kw={"height_ratios": [2.3, 1]})
    for j, (label, res) in enumerate((("linear", linear), ("nonlinear", nonlinear))):
        ax.plot(t[mask], res.q[k][mask], lw=1.1 if j == 0 else 1.0, label=label, **_style(j))
    ax.set_xlabel("t, s")
    ax.set_ylabel(rf"$\theta_{mode}(t)$, rad")
    ax.set_xlim(t[mask][0], t[mask][-1])
    _legend_above(ax, 2)
    _sci(ax)
    shift = np.degrees(phase_shift(t, linear.q[k], nonlinear.q[k], t))
    ax_s.plot(t, shift, color="black", lw=1.2, label="nonlinear minus linear")
    if window is not None:
        ax_s.axvspan(t[mask][0], t[mask][-1], color=COLORS[1], alpha=0.15, lw=0, label="window above")
    ax_s.set_xlabel("t, s")
    ax_s.set_ylabel("phase shift, deg")
    ax_s.set_xlim(t[0], t[-1])
    ax_s.legend(loc="upper left", fontsize=8)
    ax_s.grid(alpha=0.3)
    _title(fig, title)
    return fig


def linear_vs_nonlinear_phase(
    linear: Simulation,
    nonlinear: Simulation,
    mode: int = 1,
    *,
    window: Window = None,
    title: Optional[str] = None,
) -> Figure:
    """Phase portraits ``(theta_i, d theta_i/dt)`` of the linearised and nonlinear models
    (Fig. 4), with a zoom on the turning points ``theta_i = max`` where they differ."""
    k = int(np.nonzero(linear.indices == mode)[0][0])
    mask = _window_mask(linear.t, window)
    fig = _figure(figsize=(11, 5.4), layout="constrained", dpi=120)
    ax, ax_z = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.35, 1]})
    tops = []
    for j, (label, res) in enumerate((("linear", linear), ("nonlinear", nonlinear))):
        q, v = res.q[k][mask], res.qdot[k][mask]
        tops.append(float(np.max(q)))
        for target in (ax, ax_z):
            target.plot(q, v, lw=1.6 if j == 0 else 1.1, alpha=0.9, label=label, **_style(j))
    ax.plot(0, 0, "+", color="black", ms=9, mew=1.2, label="equilibrium")
    top = max(tops)
    vmax = float(np.max(np.abs(linear.qdot[k][mask])))
    ax_z.set_xlim(0.94 * min(tops), 1.01 * top)
    ax_z.set_ylim(-0.3 * vmax, 0.3 * vmax)
    ax.indicate_inset_zoom(ax_z, edgecolor="0.4")
    ax_z.set_title(rf"zoom on the turning points $\theta_{mode} = \max$", fontsize=10)
    for target in (ax, ax_z):
        _phase_axes_labels(target, rf"\theta_{mode}")
        _sci(target)
    ax.legend(loc="upper right", fontsize=8)
    _title(fig, title)
    return fig


# --------------------------------------------------------------------------- sections


def section_response(
    results: Runs,
    *,
    z: Optional[float] = None,
    window: Window = None,
    modal: Optional[bool] = None,
    title: Optional[str] = None,
) -> Figure:
    """``theta(z_k, t)`` at the section ``z_k`` (default ``2l/3`` of each string), Figs. 6, 8, 10.

    ``results`` is one :class:`~drillstring.solvers.modal.Simulation` or a mapping
    ``{"l = 100 m": sim, ...}`` (the keys label the curves). Several runs: all overlaid on the
    top panel and each again below on its own scale. One run: below it, with ``modal`` (default
    for one run), the modal contributions ``theta_i(t) cos(i pi z_k / l)`` whose sum it is.
    """
    runs = _runs(results)
    n = len(runs)
    modal = (n == 1) if modal is None else modal
    rows = [2.2] + ([1.0] * n if n > 1 else []) + ([1.3] if modal and n == 1 else [])
    fig = _figure(figsize=(10, 2.2 + 1.45 * (len(rows) - 1) + 1.3), layout="constrained", dpi=120)
    axes = fig.subplots(len(rows), 1, sharex=True, squeeze=False, gridspec_kw={"height_ratios": rows})[:, 0]
    top = axes[0]
    t0 = t1 = None
    for j, (label, res) in enumerate(runs.items()):
        zk = _section(res, z)
        mask = _window_mask(res.t, window)
        t, theta = res.t[mask], res.theta(zk)[mask]
        t0, t1 = t[0], t[-1]
        top.plot(t, theta, lw=0.9, alpha=0.9, label=label, **_style(j))
        if n > 1:
            ax = axes[1 + j]
            ax.plot(t, theta, lw=0.8, **_style(j))
            ax.set_ylabel(r"$\theta$, rad")
            ax.set_title(label, fontsize=9, loc="right", pad=3, color=COLORS[j % len(COLORS)])
            _sci(ax)
    top.set_ylabel(r"$\theta(z_k, t)$, rad")
    _legend_above(top, min(n, 3))
    _sci(top)
    if n > 1:
        top.set_title("overlaid (as in the paper)", fontsize=9, loc="left")
        axes[1].set_title("each run on its own scale", fontsize=9, loc="left")
    if modal and n == 1:
        res = next(iter(runs.values()))
        zk = _section(res, z)
        mask = _window_mask(res.t, window)
        ax = axes[-1]
        basis = res.coefficients.basis(zk)[0]
        for j, i in enumerate(res.indices.tolist()):
            ax.plot(res.t[mask], res.q[j][mask] * basis[j], lw=0.8,
                    label=rf"$\theta_{i}(t)\,\cos({i}\pi z_k/l)$", **_style(j))
        ax.set_ylabel("modal parts, rad")
        _legend_above(ax, len(res.indices), 8)
        _sci(ax)
    axes[-1].set_xlabel("t, s")
    if t0 is not None:
        axes[-1].set_xlim(t0, t1)
    _title(fig, title)
    return fig


def section_phase_portrait(
    results: Runs,
    *,
    z: Optional[float] = None,
    window: Window = None,
    title: Optional[str] = None,
) -> Figure:
    """Phase-plane projection ``(theta(z_k, t), theta_dot(z_k, t))``, Figs. 7, 9, 11.

    One run: the trajectory coloured by time (colour bar), thin lines, the start marked.
    Several runs: overlaid, semi-transparent, on the left (as in the paper) and each on its own
    scale on the right.
    """
    from matplotlib.collections import LineCollection

    runs = _runs(results)
    n = len(runs)
    if n == 1:
        label, res = next(iter(runs.items()))
        zk = _section(res, z)
        mask = _window_mask(res.t, window)
        x, y, t = res.theta(zk)[mask], res.theta_dot(zk)[mask], res.t[mask]
        fig = _figure(figsize=(7.4, 5.8), layout="constrained", dpi=120)
        ax = fig.subplots()
        points = np.column_stack([x, y])
        segments = np.stack([points[:-1], points[1:]], axis=1)
        lines = LineCollection(segments, cmap="viridis", linewidths=0.6, alpha=0.85)
        lines.set_array(0.5 * (t[:-1] + t[1:]))
        ax.add_collection(lines)
        ax.autoscale()
        ax.plot(x[0], y[0], "o", color="black", ms=5, label=f"t = {t[0]:g} s")
        ax.plot(0, 0, "+", color="red", ms=9, mew=1.2, label="equilibrium")
        fig.colorbar(lines, ax=ax, label="t, s")
        ax.legend(loc="upper right", fontsize=8, title=label, title_fontsize=8)
        ax.set_xlabel(r"$\theta(z_k, t)$, rad")
        ax.set_ylabel(r"$\dot\theta(z_k, t)$, rad/s")
        _sci(ax)
        _title(fig, title, 70)
        return fig
    fig = _figure(figsize=(12, 7.2), layout="constrained", dpi=120)
    grid = fig.add_gridspec(n, 2, width_ratios=[1.7, 1])
    main = fig.add_subplot(grid[:, 0])
    for j, (label, res) in enumerate(runs.items()):
        zk = _section(res, z)
        mask = _window_mask(res.t, window)
        x, y = res.theta(zk)[mask], res.theta_dot(zk)[mask]
        # largest first underneath: draw order by run, thin and semi-transparent
        main.plot(x, y, lw=0.65, alpha=0.55, color=COLORS[j % len(COLORS)],
                  linestyle=LINESTYLES[j % len(LINESTYLES)])
        main.plot([], [], lw=1.5, label=label, **_style(j))  # opaque legend entry
        ax = fig.add_subplot(grid[j, 1])
        ax.plot(x, y, lw=0.45, alpha=0.6, color=COLORS[j % len(COLORS)])
        ax.plot(x[0], y[0], "o", color="black", ms=3)
        ax.text(0.02, 0.95, label, transform=ax.transAxes, ha="left", va="top", fontsize=9,
                bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.7", "alpha": 0.9})
        ax.set_ylabel(r"$\dot\theta$, rad/s", fontsize=9)
        ax.tick_params(labelsize=8)
        ax.margins(x=0.04, y=0.22)
        _sci(ax)
        if j == n - 1:
            ax.set_xlabel(r"$\theta$, rad", fontsize=9)
    main.plot(0, 0, "+", color="black", ms=9, mew=1.2)
    main.set_xlabel(r"$\theta(z_k, t)$, rad")
    main.set_ylabel(r"$\dot\theta(z_k, t)$, rad/s")
    main.legend(loc="upper right", fontsize=9)
    main.set_title("overlaid (as in the paper)", fontsize=9, loc="left")
    _sci(main)
    _title(fig, title)
    return fig


def space_time(result: Any, z: Optional[float] = None, title: Optional[str] = None) -> Figure:
    """Space-time map of ``theta(z, t)`` from a PDE solution, and ``theta(z_k, t)`` below it.

    Uses ``result.field`` (``save_field_every``) when present, else every sample.
    """
    length = result.params.length
    z = default_section(length) if z is None else z
    theta = result.q if result.field is None else result.field
    t = result.t if result.field_t is None else result.field_t
    stride = max(1, t.size // 1500)  # at most ~1500 columns drawn; data untouched
    fig = _figure(figsize=(11, 6.4), layout="constrained")
    ax_map, ax_k = fig.subplots(2, 1, height_ratios=[2.2, 1], sharex=True)
    limit = float(np.abs(theta).max()) or 1.0
    mesh = ax_map.pcolormesh(
        t[::stride], result.z, theta[:, ::stride], cmap="RdBu_r", vmin=-limit, vmax=limit, shading="nearest",
        rasterized=True,
    )
    cbar = fig.colorbar(mesh, ax=ax_map, pad=0.01)
    cbar.set_label(r"$\theta(z, t)$, rad")
    cbar.formatter.set_powerlimits((-3, 3))
    ax_map.axhline(z, color="k", lw=0.8, ls="--")
    ax_map.annotate(r"$z_k$", (t[-1], z), xytext=(4, 0), textcoords="offset points", va="center", fontsize=9)
    ax_map.set_ylabel("z, m")
    ax_k.plot(result.t, result.theta(z), lw=0.8, color="C0")
    ax_k.set_xlabel("t, s")
    ax_k.set_ylabel(rf"$\theta(z_k={z:.4g}\,\mathrm{{m}}, t)$, rad")
    ax_k.grid(alpha=0.3)
    _sci(ax_k)
    fig.suptitle(title or f"PDE, {result.nodes} nodes, l = {length:.4g} m, {result.method}")
    return fig


# --------------------------------------------------------------------------- parameter sweeps

#: Axis labels (with units) of the sweep table's parameter and metric columns.
SWEEP_LABELS = {
    "length": "l, m",
    "youngs_modulus": "E, Pa",
    "density": r"$\rho$, kg/m$^3$",
    "poisson_ratio": r"$\nu$",
    "outer_diameter": "D, m",
    "inner_diameter": "d, m",
    "omega": r"$\Omega$, rad/s",
    "k5_variant": "k5 variant",
    "model": "model",
    "initial_velocities": "initial velocities C, rad/s",
    "z": "z, m",
    "max_theta": r"max $|\theta(z_k, t)|$, rad",
    "rms_theta": r"RMS $\theta(z_k, t)$, rad",
    "dominant_frequency_hz": "dominant frequency, Hz",
    "energy_drift": r"energy drift $\max|H - H_0| / |H_0|$",
    "unstable_modes": "linearly unstable modes",
    "nfev": "right-hand-side evaluations",
}


def _sweep_label(column: str) -> str:
    if column in SWEEP_LABELS:
        return SWEEP_LABELS[column]
    if column.startswith("share_mode_"):
        return f"max energy share of mode {column[len('share_mode_'):]}"
    if column[:1] == "c" and column[1:].isdigit():
        return f"$C_{{{column[1:]}}}$, rad/s"
    return column


def _sweep_axes(table: Any, axes: Optional[Sequence[str]]) -> list[str]:
    if axes is None:
        axes = list(table.attrs.get("axes", {}))
    out = []
    for name in axes:
        column = name
        if name == "initial_velocities":  # swept as a whole: plot against c1 if it varies
            varying = [c for c in table.columns if c[:1] == "c" and c[1:].isdigit() and table[c].nunique() > 1]
            column = varying[0] if varying else "c1"
        if column in table.columns and table[column].nunique(dropna=False) > 1:
            out.append(column)
    return out


def _axis_positions(values: Any) -> tuple[np.ndarray, Optional[list[str]], bool]:
    """Sorted distinct values of an axis as positions, tick labels (categorical) and log flag."""
    import pandas as pd

    numeric = pd.to_numeric(pd.Series(values), errors="coerce")
    if numeric.notna().all():
        u = np.unique(numeric.to_numpy(dtype=float))
        log = bool(u.size > 2 and u[0] > 0 and np.allclose(np.diff(np.log(u)), np.log(u[1] / u[0]), rtol=1e-6)
                   and not np.allclose(np.diff(u), u[1] - u[0], rtol=1e-6))
        return u, None, log
    labels = sorted({str(v) for v in values})
    return np.arange(len(labels), dtype=float), labels, False


def _edges(centres: np.ndarray, log: bool) -> np.ndarray:
    c = np.log(centres) if log else centres
    if c.size == 1:
        e = np.array([c[0] - 0.5, c[0] + 0.5]) if not log else np.array([c[0] - 0.1, c[0] + 0.1])
    else:
        mid = 0.5 * (c[1:] + c[:-1])
        e = np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])
    return np.exp(e) if log else e


def _critical_speeds(table: Any, length: np.ndarray, count: int) -> list[np.ndarray]:
    """The critical speeds ``Omega_crit,i(l)`` of :meth:`PDECoefficients.critical_speed` for
    i = 1..count at each length, for the material and section of the first row; none when a run
    uses a model without rotation softening (``model="consistent"``: no critical speed)."""
    from .model.coefficients import PDECoefficients
    from .model.parameters import Parameters

    if "model" in table and (table["model"].astype(str) != "paper").any():
        return []
    row = table.iloc[0]
    fields = ("youngs_modulus", "density", "poisson_ratio", "outer_diameter", "inner_diameter")
    base = Parameters(**{name: float(row[name]) for name in fields}, k5_variant=str(row.get("k5_variant", "paper")))
    modes = np.arange(1, count + 1)
    speeds = np.array([PDECoefficients.from_parameters(base.replace(length=float(l))).critical_speed(modes)
                       for l in np.atleast_1d(length)])  # (lengths, modes)
    return [speeds[:, i].reshape(np.shape(length)) for i in range(count)]


def _label_curve(ax: Axes, x: np.ndarray, y: np.ndarray, text: str, xlim: Any, ylim: Any) -> None:
    """Writes ``text`` on a curve at its last point inside the axes (the right or top edge)."""
    inside = np.nonzero((x >= min(xlim)) & (x <= max(xlim)) & (y >= min(ylim)) & (y <= max(ylim)))[0]
    if inside.size == 0:
        return
    k = int(inside[-1])
    ax.annotate(text, (float(x[k]), float(y[k])), xytext=(-3, 4), textcoords="offset points", ha="right",
                va="bottom", fontsize=9, color="k",
                bbox={"boxstyle": "round,pad=0.15", "fc": "w", "ec": "none", "alpha": 0.8})


def sweep_metric(
    table: Any,
    metric: str,
    axes: Optional[Sequence[str]] = None,
    *,
    title: Optional[str] = None,
) -> Figure:
    """A metric of a sweep table over its swept axes.

    One axis: the metric against it (one marker per run). Two axes: a heat map (colour bar;
    blank cells are runs without the metric, e.g. failed or invalid). More axes: a heat map over
    the first two, of the largest value over the others. Log-spaced axes are drawn on log
    scales; a positive metric spanning more than three decades gets a log colour scale.

    When ``omega`` and ``length`` are both swept, the critical speeds
    ``Omega_crit,i(l) = (i pi / l) sqrt(4 G / rho)`` of the retained elastic modes are drawn
    (``G``, ``rho`` of the first row): above ``Omega_crit,i`` mode ``i`` is linearly unstable.
    A sweep of ``omega`` alone at one length marks them as vertical lines. Not drawn when a run
    uses the ``"consistent"`` model, which has no critical speed.

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`drillstring.sweep` table (:mod:`drillstring.studies.sweeps`).
    metric : str
        A column, e.g. ``"max_theta"``, ``"dominant_frequency_hz"``, ``"share_mode_1"``.
    axes : sequence of str, optional
        Columns to plot against; default the grid axes in ``table.attrs["axes"]`` that vary.
    """
    import pandas as pd
    from matplotlib.colors import BoundaryNorm, LogNorm

    if metric not in table.columns:
        raise ValueError(f"no column {metric!r} in the sweep table")
    names = _sweep_axes(table, axes)
    if not names:
        raise ValueError("the sweep has no varying axis to plot against (pass axes=...)")
    # length on x and omega on y, so that the critical-speed curves are Omega(l)
    if len(names) >= 2 and names[0] == "omega" and names[1] == "length":
        names[0], names[1] = names[1], names[0]
    values = pd.to_numeric(table[metric], errors="coerce").astype(float)
    modes = [c for c in table.columns if c.startswith("share_mode_") and c != "share_mode_0"]
    fig = _figure(figsize=(7.4, 5.4) if len(names) >= 2 else (7.4, 4.6), layout="constrained")
    ax = fig.subplots()
    if len(names) == 1:
        x, labels, log = _axis_positions(table[names[0]])
        key = table[names[0]] if labels is None else table[names[0]].astype(str)
        order = pd.DataFrame({"x": key, "v": values}).groupby("x", sort=True)["v"].max()
        xs = order.index.to_numpy(dtype=float) if labels is None else np.arange(len(order))
        ax.plot(xs, order.to_numpy(), marker="o", ms=3, lw=1.0, color=COLORS[0])
        if labels is not None:
            ax.set_xticks(xs, order.index.tolist())
        if log:
            ax.set_xscale("log")
        ax.set_xlabel(_sweep_label(names[0]))
        ax.set_ylabel(_sweep_label(metric))
        ax.grid(alpha=0.3)
        if names[0] == "omega" and table["length"].nunique() == 1 and "density" in table:
            lo, hi = np.nanmin(xs), np.nanmax(xs)
            for i, crit in enumerate(_critical_speeds(table, np.array([float(table["length"].iloc[0])]), len(modes))):
                if lo <= crit[0] <= hi:
                    ax.axvline(crit[0], color="k", lw=0.9, ls="--" if i else "-")
                    ax.annotate(rf"$\Omega_{{crit,{i + 1}}}$", (crit[0], 1.0), xycoords=("data", "axes fraction"),
                                xytext=(3, -12), textcoords="offset points", fontsize=9)
    else:
        xname, yname = names[0], names[1]
        x, xlabels, xlog = _axis_positions(table[xname])
        y, ylabels, ylog = _axis_positions(table[yname])
        xkey = table[xname].astype(str) if xlabels is not None else pd.to_numeric(table[xname])
        ykey = table[yname].astype(str) if ylabels is not None else pd.to_numeric(table[yname])
        grid = (
            pd.DataFrame({"x": xkey, "y": ykey, "v": values})
            .groupby(["y", "x"], sort=True)["v"].max()
            .unstack("x")
        )
        grid = grid.reindex(index=ylabels if ylabels is not None else y, columns=xlabels if xlabels is not None else x)
        z = grid.to_numpy(dtype=float)
        finite = z[np.isfinite(z)]
        norm = None
        cmap = "viridis"
        if metric == "unstable_modes" and finite.size:
            top = int(finite.max())
            norm = BoundaryNorm(np.arange(-0.5, top + 1.5), 256)
        elif finite.size and finite.min() > 0 and finite.max() > 1e3 * finite.min():
            norm = LogNorm(finite.min(), finite.max())
        mesh = ax.pcolormesh(_edges(x, xlog), _edges(y, ylog), np.ma.masked_invalid(z), cmap=cmap, norm=norm,
                             rasterized=True)
        cbar = fig.colorbar(mesh, ax=ax, pad=0.01)
        cbar.set_label(_sweep_label(metric))
        if metric == "unstable_modes" and finite.size:
            cbar.set_ticks(np.arange(0, int(finite.max()) + 1))
        for axis_set, labels, pos in ((ax.set_xticks, xlabels, x), (ax.set_yticks, ylabels, y)):
            if labels is not None:
                axis_set(pos, labels)
        if xlog:
            ax.set_xscale("log")
        if ylog:
            ax.set_yscale("log")
        ax.set_xlabel(_sweep_label(xname))
        ax.set_ylabel(_sweep_label(yname))
        if {xname, yname} == {"length", "omega"} and "density" in table:
            xlim, ylim = ax.get_xlim(), ax.get_ylim()
            lim, log = (xlim, xlog) if xname == "length" else (ylim, ylog)
            span = np.geomspace(*lim, 400) if log else np.linspace(*lim, 400)
            span = span[span > 0]
            for i, crit in enumerate(_critical_speeds(table, span, max(len(modes), 1))):
                xy = (span, crit) if xname == "length" else (crit, span)
                label = r"$\Omega_{crit,i}(l) = (i\pi/l)\sqrt{4G/\rho}$" if i == 0 else None
                ax.plot(*xy, color="w", lw=1.6 if i == 0 else 1.0, ls="-" if i == 0 else "--", label=label)
                ax.plot(*xy, color="k", lw=0.6 if i == 0 else 0.4, ls="-" if i == 0 else "--")
                _label_curve(ax, np.asarray(xy[0]), np.asarray(xy[1]), rf"$\Omega_{{crit,{i + 1}}}$", xlim, ylim)
            ax.set_xlim(xlim)
            ax.set_ylim(ylim)
            if ax.get_legend_handles_labels()[0]:
                ax.legend(loc="upper right", fontsize=8, framealpha=0.8)
    suffix = f" (max over {', '.join(names[2:])})" if len(names) > 2 else ""
    ax.set_title(title or f"{_sweep_label(metric)}{suffix}", fontsize=10)
    return fig


def sweep_plots(table: Any, out_dir: object, axes: Optional[Sequence[str]] = None) -> list[str]:
    """Write one PNG per metric of a sweep table (:func:`sweep_metric`) to ``out_dir``:
    ``<metric>.png`` for every metric and modal energy share; returns the paths written.
    Nothing is written when the sweep has no varying axis."""
    import os

    from .studies.sweeps import METRICS

    if not _sweep_axes(table, axes):
        return []
    os.makedirs(os.fspath(out_dir), exist_ok=True)
    written = []
    for metric in [*METRICS, *(c for c in table.columns if c.startswith("share_mode_"))]:
        path = os.path.join(os.fspath(out_dir), f"{metric}.png")
        save(sweep_metric(table, metric, axes), path)
        written.append(path)
    return written


__all__ += ["SWEEP_LABELS", "sweep_metric", "sweep_plots"]
