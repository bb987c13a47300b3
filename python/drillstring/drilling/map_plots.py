"""The figures of a stick-slip map (:func:`~drillstring.drilling.maps.drill_map`'s table).

:func:`ssi_map` (the stick-slip severity over two axes with the stick-slip boundary, the contour
SSI = 1: the bit-speed oscillation as large as its mean, where the bit starts to stop),
:func:`controller_maps` (one such panel per controller, side by side, on one colour scale),
:func:`ssi_lines` (SSI against one axis, one line per value of another), for a coupled map
:func:`regime_map` (the regimes, ROP and MSE over two axes); :func:`map_figures` those of
``drillstring drill-map``. Each takes ``units="si"`` (the default) or ``"field"``: the axes and the
values in the panels' titles in the field unit of their key
(:func:`~drillstring.drilling.map_labels.axis_label`); the table stays SI. One panel or line per
value of every axis not plotted (at most :data:`MAX_PANELS`), never an average of runs."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from ..errors import ValidationError
from .map_labels import axis_label, map_title, value_text, well_name
from .map_table import CONTROLLER_AXIS, is_numeric, numeric_axes
from .metrics import MSE_MEAN, OUTPUTS, REGIME, ROP_MEAN, SSI, STUCK_FRACTION
from .result import COUPLED_REGIMES
from .units import reported_unit, system_of

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = ["MAX_PANELS", "REGIME_COLOURS", "boundary_note", "controller_maps", "map_figures", "regime_map",
           "ssi_lines", "ssi_map"]

#: Most panels a map figure draws (one per combination of the values of the axes it does not plot).
MAX_PANELS = 48


def _split(frame: pd.DataFrame, plotted: Sequence[str], first: Optional[str] = None, units: str = "si"
           ) -> list[tuple[str, pd.DataFrame]]:
    """The frame cut by the values of every axis of the map not in ``plotted`` that takes more
    than one value (``first`` leading), as ``(panel title, rows)``; one ``("", frame)`` without
    such an axis. Runs of different configurations are never averaged into one cell or point."""
    keys = [k for k in frame.attrs.get("axes", {}) if k not in plotted and k in frame.columns]
    if first is not None and first in keys:
        keys = [first] + [k for k in keys if k != first]
    keys = [k for k in keys if frame[k].astype(str).nunique() > 1]
    if not keys:
        return [("", frame)]
    axes = frame.attrs.get("axes", {})

    def position(key: str, value: Any) -> int:
        listed = list(axes.get(key) or ())
        return next((i for i, v in enumerate(listed) if v == value), len(listed))

    groups = []
    for values, part in frame.groupby(keys, sort=False, dropna=False):
        values = values if isinstance(values, tuple) else (values,)
        groups.append((tuple(position(k, v) for k, v in zip(keys, values)), values, part))
    groups.sort(key=lambda g: g[0])  # in the order of the axes' values
    parts = [(", ".join(value_text(k, v, frame[k].tolist(), units) for k, v in zip(keys, values)), part)
             for _, values, part in groups]
    if len(parts) > MAX_PANELS:
        raise ValidationError("axes", ", ".join(keys), f"at most {MAX_PANELS} panels (values of the axes not "
                              f"plotted), not {len(parts)}: select rows of the map first")
    return parts


def _grid(frame: pd.DataFrame, x: str, y: str, value: str) -> tuple[Any, Any, Any]:
    # one run per cell (the frame is split by every other axis first, _split): a repeated value of
    # an axis repeats the same run
    table = frame.pivot_table(index=y, columns=x, values=value, aggfunc="mean", dropna=False)
    return (table.columns.to_numpy(dtype=float), table.index.to_numpy(dtype=float),
            np.ma.masked_invalid(table.to_numpy(dtype=float)))


def boundary_note(ssi: Any) -> Optional[str]:
    """What a panel says when it has no SSI = 1 boundary: ``"SSI > 1 everywhere in this range"``,
    ``"SSI < 1 everywhere in this range"`` or ``"no successful run"``; None when the finite values
    lie on both sides of 1 (or touch it)."""
    finite = np.asarray(ssi, dtype=float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return "no successful run"
    if finite.min() > 1.0:
        return "SSI > 1 everywhere in this range"
    if finite.max() < 1.0:
        return "SSI < 1 everywhere in this range"
    return None


def _note(ax: Any, text: str) -> None:
    ax.text(0.5, 0.03, text, transform=ax.transAxes, ha="center", va="bottom", fontsize=9,
            bbox={"boxstyle": "round", "facecolor": "white", "alpha": 0.85, "edgecolor": "0.6"})


def _panel(ax: Any, frame: pd.DataFrame, x: str, y: str, value: str, vmax: float,
           scales: tuple[float, float]) -> Any:
    xs, ys, z = _grid(frame, x, y, value)
    xs, ys = xs * scales[0], ys * scales[1]
    mesh = ax.pcolormesh(xs, ys, z, shading="nearest", cmap="magma_r", vmin=0.0, vmax=vmax)
    if value == SSI:
        note = boundary_note(z.compressed())
        if note is None and (xs.size < 2 or ys.size < 2):
            note = "SSI = 1 in this range (one value of an axis: no contour)"
        if note is None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ax.contour(xs, ys, z, levels=[1.0], colors="tab:cyan", linewidths=2.0)
        else:
            _note(ax, note)
    return mesh


def _check_axes(frame: pd.DataFrame, keys: Sequence[str]) -> None:
    for key in keys:
        if not is_numeric(frame, key):
            raise ValidationError("axis", key, f"a numeric axis of the map (one of {', '.join(numeric_axes(frame))})")


def _vmax(values: Any) -> float:
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    return float(max(1.5, finite.max())) if finite.size else 1.5


def _ssi_panels(frame: pd.DataFrame, x: str, y: str, first: Optional[str], title: Optional[str],
                units: str = "si") -> Figure:
    from .plots import _figure

    _check_axes(frame, (x, y))
    parts = _split(frame, (x, y), first, units)
    cols = min(len(parts), 4)
    rows = -(-len(parts) // cols)
    fig = _figure(4.2 * cols + 1.4, 3.9 * rows + 0.6)
    axs = fig.subplots(rows, cols, sharex=True, sharey=True, squeeze=False).ravel()
    vmax = _vmax(frame[SSI])
    (xlabel, xscale), (ylabel, yscale) = (axis_label(x, frame[x].tolist(), units),
                                          axis_label(y, frame[y].tolist(), units))
    mesh = None
    for ax, (name, part) in zip(axs, parts):
        mesh = _panel(ax, part, x, y, SSI, vmax, (xscale, yscale))
        if name:
            ax.set_title(name, fontsize=10)
    for ax in axs[len(parts):]:
        ax.set_visible(False)
    for ax in axs[:len(parts)]:
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
    assert mesh is not None  # at least one panel
    fig.colorbar(mesh, ax=list(axs[:len(parts)]), label="stick-slip severity SSI (cyan: SSI = 1)")
    fig.suptitle(title or map_title(frame, "stick-slip severity SSI", units))
    return fig


def ssi_map(frame: pd.DataFrame, x: str, y: str, *, title: Optional[str] = None, units: str = "si") -> Figure:
    """The stick-slip severity over the numeric axes ``x`` and ``y`` of a map (a cell per run),
    with the stick-slip boundary SSI = 1 (cyan).

    One panel per combination of the values of the map's other axes (the controller's first), so
    that no cell averages runs of different configurations; a panel without an SSI = 1 boundary
    in its range says so (``"SSI > 1 everywhere in this range"`` or ``"< 1"``). The axes are
    labelled by quantity and unit in readable magnitudes
    (:func:`~drillstring.drilling.map_labels.axis_label`); the title names the well
    (``frame.attrs["name"]``) and the controller. Failed runs are blank.

    Parameters
    ----------
    frame : pandas.DataFrame
        A map (:func:`~drillstring.drilling.maps.drill_map`).
    x, y : str
        Two numeric axes of the map (dotted keys).
    title : str, optional
        The figure's title instead of the default.
    units : {"si", "field"}, optional
        The unit system of the axes and the panels' titles (default ``"si"``; ``"field"``: the
        field unit of each key, :func:`~drillstring.drilling.map_labels.axis_label`).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> frame = drill_map("examples/on-bottom-3000m.toml",  # doctest: +SKIP
    ...                   {"top_drive.rpm": [40, 80, 120], "bit.weight_on_bit": [50e3, 100e3]})
    >>> ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit").savefig("ssi_map.png")  # doctest: +SKIP
    >>> ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit", units="field")  # doctest: +SKIP
    """
    return _ssi_panels(frame, x, y, CONTROLLER_AXIS, title, units)


def controller_maps(frame: pd.DataFrame, x: str, y: str, *, controller: str = CONTROLLER_AXIS,
                    title: Optional[str] = None, units: str = "si") -> Figure:
    """:func:`ssi_map` panels, one per value of the ``controller`` axis (and of any other axis
    not plotted), on one colour scale, each with its SSI = 1 boundary or a note that it has none;
    ``units`` as :func:`ssi_map`'s."""
    _check_axes(frame, (x, y))
    if controller not in frame.columns:
        raise ValidationError("controller", controller, "an axis of the map")
    return _ssi_panels(frame, x, y, controller,
                       title or f"{well_name(frame, units)}: stick-slip severity SSI by controller", units)


def ssi_lines(frame: pd.DataFrame, x: str, by: Optional[str] = None, *, title: Optional[str] = None,
              units: str = "si") -> Figure:
    """SSI (and the stuck fraction) against the numeric axis ``x``: one line per combination of
    the values of the map's other axes (``by`` first; no line averages runs of different
    configurations), with SSI = 1 dashed; ``units`` as :func:`ssi_map`'s."""
    from .plots import _figure

    _check_axes(frame, (x,))
    xlabel, scale = axis_label(x, frame[x].tolist(), units)
    fig = _figure(6.4, 4.8)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    parts = _split(frame, (x,), by or CONTROLLER_AXIS, units)
    for name, part in parts:
        part = part.groupby(x, sort=True)[[SSI, STUCK_FRACTION]].mean()  # repeated values: the same run
        label = name or None
        ax1.plot(part.index.to_numpy(dtype=float) * scale, part[SSI], marker="o", label=label)
        ax2.plot(part.index.to_numpy(dtype=float) * scale, part[STUCK_FRACTION], marker="o", label=label)
    ax1.axhline(1.0, color="0.5", ls="--", lw=1)
    note = boundary_note(frame[SSI])
    if note is not None:
        _note(ax1, note)
    ax1.set_ylabel("SSI")
    ax2.set_ylabel("stuck fraction")
    ax2.set_xlabel(xlabel)
    if len(parts) > 1:
        ax1.legend(fontsize="small")
    ax1.set_title(title or map_title(frame, "stick-slip severity", units))
    return fig


#: The colours of the coupled regimes in :func:`regime_map` (:data:`COUPLED_REGIMES` order).
REGIME_COLOURS: dict[str, str] = {
    "smooth drilling": "#4daf4a", "stick-slip": "#e41a1c", "bit bounce": "#377eb8",
    "stick-slip and bit bounce": "#984ea3", "off bottom": "#bdbdbd", "undetermined": "#ffff99",
}


def regime_map(frame: pd.DataFrame, x: str, y: str, *, title: Optional[str] = None, units: str = "si") -> Figure:
    """The regimes of a coupled map over the numeric axes ``x`` and ``y`` (a cell per run, one
    colour per regime: smooth drilling, stick-slip, bit bounce, both, off bottom, undetermined;
    the core's criterion, :data:`~drillstring.drilling.result.COUPLED_REGIME_CRITERION`) beside
    the mean rate of penetration (m/h; ft/h in field units) and the mechanical specific energy
    (MPa; psi) over the same axes; the stick-slip boundary SSI = 1 (cyan) on the ROP panel. One
    row of three panels per combination of the values of the map's other axes; failed runs are
    blank. ``units`` as :func:`ssi_map`'s.

    Examples
    --------
    >>> frame = drill_map("examples/coupled-rpm-wob-map.toml",  # doctest: +SKIP
    ...                   {"top_drive.rpm": [30, 60, 90], "hoist.weight_on_bit": [40e3, 80e3]})
    >>> regime_map(frame, "top_drive.rpm", "hoist.weight_on_bit").savefig("regime_map.png")  # doctest: +SKIP
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    from .plots import _figure

    _check_axes(frame, (x, y))
    if REGIME not in frame.columns:
        raise ValidationError("frame", "a map without a regime column", "a map of a coupled configuration ([hoist])")
    parts = _split(frame, (x, y), CONTROLLER_AXIS, units)
    fig = _figure(14.0, 3.9 * len(parts) + 0.9)
    axs = fig.subplots(len(parts), 3, sharex=True, sharey=True, squeeze=False)
    (xlabel, xscale), (ylabel, yscale) = (axis_label(x, frame[x].tolist(), units),
                                          axis_label(y, frame[y].tolist(), units))
    cmap = ListedColormap([REGIME_COLOURS[r] for r in COUPLED_REGIMES])
    norm = BoundaryNorm(np.arange(len(COUPLED_REGIMES) + 1) - 0.5, cmap.N)
    seen: set[str] = set()
    meshes: list[Any] = [None, None]
    rop_scale, rop_unit = reported_unit(str(OUTPUTS[ROP_MEAN].unit), units)
    mse_scale, mse_unit = reported_unit(str(OUTPUTS[MSE_MEAN].unit), units)
    rop_max = float(np.nanmax(frame[ROP_MEAN].to_numpy(dtype=float), initial=0.0)) * rop_scale
    mse = frame[MSE_MEAN].to_numpy(dtype=float) * mse_scale
    mse = mse[np.isfinite(mse)]
    mse_range = (float(mse.min()), float(mse.max())) if mse.size else (0.0, 1.0)
    for row, (name, part) in zip(axs, parts):
        ok = part["status"] == "success"
        codes = part[REGIME].map({r: i for i, r in enumerate(COUPLED_REGIMES)}).astype(float).where(ok)
        seen.update(part[REGIME][ok])
        xs, ys, z = _grid(part.assign(_regime=codes), x, y, "_regime")
        row[0].pcolormesh(xs * xscale, ys * yscale, z, shading="nearest", cmap=cmap, norm=norm)
        xs, ys, z = _grid(part.assign(_rop=(part[ROP_MEAN] * rop_scale).where(ok)), x, y, "_rop")
        meshes[0] = row[1].pcolormesh(xs * xscale, ys * yscale, z, shading="nearest", cmap="viridis", vmin=0.0,
                                      vmax=max(rop_max, 1e-9))
        _, _, ssi = _grid(part.assign(_ssi=part[SSI].where(ok)), x, y, "_ssi")
        if boundary_note(ssi.compressed()) is None and xs.size > 1 and ys.size > 1:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                row[1].contour(xs * xscale, ys * yscale, ssi, levels=[1.0], colors="tab:cyan", linewidths=2.0)
        xs, ys, z = _grid(part.assign(_mse=(part[MSE_MEAN] * mse_scale).where(ok)), x, y, "_mse")
        meshes[1] = row[2].pcolormesh(xs * xscale, ys * yscale, np.ma.masked_invalid(z), shading="nearest",
                                      cmap="magma_r", vmin=mse_range[0], vmax=max(mse_range[1], mse_range[0] + 1e-9))
        for ax, what in zip(row, (OUTPUTS[REGIME].label, "mean ROP", "mechanical specific energy")):
            ax.set_title(f"{what}{', ' + name if name else ''}", fontsize=10)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
    fig.colorbar(meshes[0], ax=list(axs[:, 1]), label=f"mean rate of penetration [{rop_unit}] (cyan: SSI = 1)")
    fig.colorbar(meshes[1], ax=list(axs[:, 2]), label=f"MSE of the means [{mse_unit}]")
    handles = [Patch(facecolor=REGIME_COLOURS[r], edgecolor="0.5", label=r) for r in COUPLED_REGIMES if r in seen]
    if handles:
        axs[0, 0].legend(handles=handles, fontsize="small", loc="upper left", framealpha=0.85)
    fig.suptitle(title or map_title(frame, "coupled regime, ROP and MSE", units))
    return fig


def map_figures(frame: pd.DataFrame, units: str = "si") -> dict[str, Figure]:
    """The figures a map gets (file name -> figure): with two numeric axes ``ssi_map.png``, for a
    coupled map ``regime_map.png`` (:func:`regime_map`) and,
    when ``top_drive.controller.type`` is an axis too, ``controllers.png``; with one numeric
    axis ``ssi_lines.png`` (a line per combination of the other axes' values, if any). None
    otherwise. Every figure has one panel (or line) per value of the axes it does not plot; a map
    needing more than :data:`MAX_PANELS` panels gets no figure (a warning says so). ``units`` is
    the unit system of the figures (:func:`ssi_map`)."""
    units = system_of(units, "units")
    axes = list(frame.attrs.get("axes", {}))
    numeric = numeric_axes(frame)
    out: dict[str, Figure] = {}
    try:
        if len(numeric) >= 2:
            x, y = numeric[0], numeric[1]
            out["ssi_map.png"] = ssi_map(frame, x, y, units=units)
            if REGIME in frame.columns:
                out["regime_map.png"] = regime_map(frame, x, y, units=units)
            if CONTROLLER_AXIS in axes:
                out["controllers.png"] = controller_maps(frame, x, y, units=units)
        elif len(numeric) == 1:
            others = [k for k in axes if k != numeric[0]]
            out["ssi_lines.png"] = ssi_lines(frame, numeric[0], others[0] if others else None, units=units)
    except ValidationError as exc:
        warnings.warn(f"no map figure: {exc}", stacklevel=2)
    return out
