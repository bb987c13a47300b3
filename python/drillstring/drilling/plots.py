"""Figures of a drilling-system run; every function returns a matplotlib Figure (no pyplot state).

* :func:`time_histories`: surface and bit speed, motor and bit torque against time, with the
  metrics window shaded;
* :func:`space_time_maps`: speed and torque along the string against time (depth downward);
* :func:`torque_depth`: torque along the string against depth (the envelope over the snapshots
  and the last one) with the break-off envelope, the static torque the string holds at break-off
  that the core returns (:attr:`DrillResult.profile`: the wall's friction from the bit up plus,
  on bottom, the bit's static torque), and the friction limit per metre;
* a coupled run's (``[hoist]``) :func:`axial_histories`: weight on bit and hook load, torque on
  bit, rate of penetration and bit axial speed, depth of cut against time; and
  :func:`axial_space_time`: axial speed and force along the string against time.

:meth:`DrillResult.plot` draws any of them by name (:data:`KINDS`). Each function takes an optional
``fig`` (a :class:`~matplotlib.figure.Figure` or a ``SubFigure``) to draw into, for a figure of
several runs; without it a new figure is made; and ``units``, the unit system of its axes and
titles: ``"si"`` (the default: m, kN m) or ``"field"`` (ft, kft-lbf; speeds in rpm and times in
s either way), converted by :func:`drillstring.drilling.units.axis_unit`. The data are SI.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable, Optional, TypeVar

import numpy as np

from .units import axis_unit, metric_texts

if TYPE_CHECKING:  # pragma: no cover
    from typing import Union

    from matplotlib.figure import Figure, SubFigure

    from .result import DrillResult

    FigureLike = Union[Figure, SubFigure]

_F = TypeVar("_F", bound=Callable[..., Any])

__all__ = ["KINDS", "axial_histories", "axial_space_time", "space_time_maps", "time_histories", "torque_depth"]



def _figure(width: float, height: float) -> Figure:
    """A new constrained-layout figure of that size."""
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def _title(result: DrillResult, units: str = "si") -> str:
    cfg = result.config
    where = "on bottom" if cfg.bit.on_bottom else "off bottom"
    if cfg.hoist is not None:  # a coupled run: the bit on the Detournay law, the hoist's mode
        where = f"{cfg.bit.law}, hoist {cfg.hoist.mode.replace('_', ' ')}"
    name = getattr(result, "name", None)
    depth, unit = axis_unit("m", units)
    return ((f"{name}: " if name else "") + f"{cfg.length * depth:.0f} {unit} string ({len(cfg.sections)} sections), "
            f"{cfg.top_drive.rpm:g} rpm, {cfg.top_drive.controller.type} controller, bit {where}")


def _breakoff_label(result: DrillResult) -> str:
    if result.profile.bit_static_torque > 0:
        return "break-off torque (wall friction + bit static torque)"
    return "break-off torque (wall friction)"


def _shade_window(ax: object, result: DrillResult) -> None:
    start, end = result.metrics.window
    if np.isfinite(start) and np.isfinite(end) and end > start:
        ax.axvspan(start, end, color="0.92", zorder=0, lw=0)  # type: ignore[attr-defined]


_SHARED_DOC = """

    Parameters
    ----------
    result : DrillResult
        A run (:func:`drillstring.drill`).
    title : str, optional
        The figure's title instead of the default.
    fig : Figure or SubFigure, optional
        Draw into this (empty) figure instead of a new one.
    units : {{"si", "field"}}, optional
        The unit system of the axes and the title (default ``"si"``; ``"field"``: depths in ft,
        torques in kft-lbf).

    Returns
    -------
    matplotlib.figure.Figure
        The figure (``fig``'s figure when given); save it with ``savefig``.

    Examples
    --------
    >>> import drillstring as ds
    >>> result = ds.drill("examples/on-bottom-3000m.toml")  # doctest: +SKIP
    >>> {name}(result).savefig("{file}")  # doctest: +SKIP
    >>> {name}(result, units="field").savefig("{file}")  # doctest: +SKIP
    """


def _documented(file: str) -> Callable[[_F], _F]:
    """Appends the parameters, returns and an example (saving ``file``) shared by the figures of
    a run to the function's docstring."""

    def add(function: _F) -> _F:
        function.__doc__ = (function.__doc__ or "").rstrip() + _SHARED_DOC.format(name=function.__name__, file=file)
        return function

    return add


@_documented("time_histories.png")
def time_histories(result: DrillResult, title: Optional[str] = None, *, fig: Optional[FigureLike] = None,
                   units: str = "si") -> Figure:
    """Speeds and torques of a run against time.

    Top: surface (top-drive) and bit speed, rpm. Bottom: motor and bit torque, kN m (kft-lbf), with the
    break-off torque dotted (the static torque the motor must exceed to break the string free:
    the wall's friction and, with the bit on bottom, the bit's static torque;
    :attr:`DrillProfile.static_torque`) and the minimum cycle torque it implies dash-dotted. The
    metrics window is shaded; the title gives the string, the controller and the stick-slip
    verdict with SSI, stuck fraction and period.
    """
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    fig = _figure(11, 6.4) if fig is None else fig
    ax_rpm, ax_torque = fig.subplots(2, 1, sharex=True)
    for ax in (ax_rpm, ax_torque):
        _shade_window(ax, result)
        ax.grid(alpha=0.3)
    ax_rpm.plot(result.t, result.surface_rpm, lw=1.0, color="tab:blue", label="surface (top drive)")
    ax_rpm.plot(result.t, result.bit_rpm, lw=1.0, color="tab:orange", ls="--", label="bit")
    ax_rpm.set_ylabel("speed, rpm")
    ax_rpm.legend(loc="upper right", fontsize=9)
    ax_torque.plot(result.t, result.motor_torque * torque, lw=1.0, color="tab:blue", label="motor")
    ax_torque.plot(result.t, result.bit_torque * torque, lw=1.0, color="tab:orange", ls="--", label="bit")
    breakoff = result.profile.static_torque
    if np.isfinite(breakoff) and breakoff > 0:
        ax_torque.axhline(breakoff * torque, color="k", lw=0.8, ls=":", label=_breakoff_label(result))
    low = result.metrics.min_cycle_torque_Nm
    if np.isfinite(low):
        ax_torque.axhline(low * torque, color="0.4", lw=0.8, ls="-.", label="minimum cycle torque implied by break-off")
    ax_torque.set_ylabel(f"torque, {torque_unit}")
    ax_torque.set_xlabel("t, s")
    ax_torque.legend(loc="upper right", fontsize=9)
    m = result.metrics
    fig.suptitle(title or f"{_title(result, units)}\nstick-slip: {m.stick_slip_verdict}; SSI {m.ssi:.3g}, "
                 f"stuck {m.stuck_fraction:.3g}, period {m.period_s:.3g} s (shaded: metrics window)", fontsize=11)
    return _root(fig)


def _root(fig: FigureLike) -> Figure:
    """The figure ``fig`` belongs to (itself for a Figure)."""
    from matplotlib.figure import Figure

    while not isinstance(fig, Figure):
        fig = fig.figure
    return fig


@_documented("space_time.png")
def space_time_maps(result: DrillResult, title: Optional[str] = None, *, fig: Optional[FigureLike] = None,
                    units: str = "si") -> Figure:
    """Speed and torque along the string against time.

    Top: speed, rpm; bottom: torque, kN m (kft-lbf; a diverging scale around 0); measured depth,
    m (ft), grows downward. Drawn from the snapshots of ``numerics.field_interval``; without snapshots each
    panel says so.
    """
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    depth, depth_unit = axis_unit("m", units)
    fig = _figure(11, 7.0) if fig is None else fig
    axes = fig.subplots(2, 1, sharex=True)
    if result.field_t.size == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no snapshots (numerics.field_interval = 0)", ha="center", va="center",
                    transform=ax.transAxes)
        return _root(fig)
    t = result.field_t
    _space_time_panels(fig, t, result.z * depth, depth_unit, (
        (axes[0], result.omega_field, 1.0, "speed, rpm", "viridis"),
        (axes[1], result.torque_field, torque, f"torque, {torque_unit}", "RdBu_r")))
    fig.suptitle(title or f"{_title(result, units)}: along the string", fontsize=11)
    return _root(fig)


def _space_time_panels(fig: FigureLike, t: Any, z: Any, depth_unit: str, maps: Any) -> None:
    """Draws each ``(ax, data[t, z], scale, label, cmap)`` of ``maps`` against time ``t`` and
    depth ``z`` (drawn units), depth downward; ``"RdBu_r"`` on a scale symmetric about 0. At most
    ~600 depths and ~1500 times are drawn (the data untouched)."""
    z_stride = max(1, z.size // 600)
    t_stride = max(1, t.size // 1500)
    for ax, data, scale, label, cmap in maps:
        values = data[::t_stride, ::z_stride].T * scale
        limits = {}
        if cmap == "RdBu_r":
            limit = float(np.nanmax(np.abs(values))) or 1.0
            limits = {"vmin": -limit, "vmax": limit}
        mesh = ax.pcolormesh(t[::t_stride], z[::z_stride], values, cmap=cmap, shading="nearest", rasterized=True,
                             **limits)
        fig.colorbar(mesh, ax=ax, pad=0.01).set_label(label)
        ax.set_ylabel(f"measured depth, {depth_unit}")
        ax.invert_yaxis()
    maps[-1][0].set_xlabel("t, s")


@_documented("torque_depth.png")
def torque_depth(result: DrillResult, title: Optional[str] = None, *, fig: Optional[FigureLike] = None,
                 units: str = "si") -> Figure:
    """Torque along the string against depth, inside its break-off envelope.

    Left: the torque's range over the snapshots and the last snapshot, kN m (kft-lbf), within the
    break-off envelope ``+-`` the static torque the string holds at break-off
    (:attr:`DrillProfile.holding`: the wall's static friction from the bit up plus, with the bit
    on bottom, the bit's static torque). Right: the static friction limit per metre, N m/m
    (ft-lbf/ft). Measured depth, m (ft), grows downward.
    """
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    depth, depth_unit = axis_unit("m", units)
    limit, limit_unit = axis_unit("N*m/m", units)
    fig = _figure(11, 6.0) if fig is None else fig
    ax, ax_limit = fig.subplots(1, 2, sharey=True, width_ratios=[2.2, 1])
    profile = result.profile
    envelope = profile.holding if profile.holding.size == profile.z.size else profile.cumulative
    what = ("wall friction from the bit up + bit static torque" if profile.bit_static_torque > 0
            else "static friction from the bit up")
    profile_z = profile.z * depth
    ax.fill_betweenx(profile_z, -envelope * torque, envelope * torque, color="0.9",
                     label=f"break-off envelope ({what})")
    ax.plot(envelope * torque, profile_z, color="k", lw=0.9, ls=":")
    ax.plot(-envelope * torque, profile_z, color="k", lw=0.9, ls=":")
    if result.field_t.size:
        z = result.z * depth
        low = result.torque_field.min(axis=0) * torque
        high = result.torque_field.max(axis=0) * torque
        ax.fill_betweenx(z, low, high, color="tab:blue", alpha=0.25, lw=0,
                         label=f"range over {result.field_t.size} snapshots")
        ax.plot(result.torque_field[-1] * torque, z, color="tab:blue", lw=1.2,
                label=f"t = {result.field_t[-1]:.4g} s")
    ax.axvline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel(f"torque, {torque_unit}")
    ax.set_ylabel(f"measured depth, {depth_unit}")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    ax.invert_yaxis()
    ax_limit.plot(profile.limit_per_m * limit, profile_z, color="tab:red", lw=1.0)
    ax_limit.set_xlabel(f"static friction limit, {limit_unit}")
    ax_limit.grid(alpha=0.3)
    ax_limit.set_xlim(left=0.0)
    fig.suptitle(title or f"{_title(result, units)}\nbreak-off torque {profile.static_torque * torque:.4g} "
                 f"{torque_unit}"
                 + (f" (wall {profile.breakoff_torque * torque:.4g} + bit {profile.bit_static_torque * torque:.4g})"
                    if profile.bit_static_torque > 0 else ""), fontsize=11)
    return _root(fig)


def _depth_of_cut_axis(units: str) -> tuple[float, str]:
    """Depth of cut per revolution in mm (SI) or inches (field, the bit size's unit)."""
    from .units import convert

    if units == "field":
        factor, unit = convert(1.0, "m", units, key="bit.radius")
        assert factor is not None
        return factor, unit
    return 1e3, "mm"


def _no_axial(fig: FigureLike, axes: Any, what: str) -> Figure:
    for ax in np.atleast_1d(axes):
        ax.text(0.5, 0.5, what, ha="center", va="center", transform=ax.transAxes)
    return _root(fig)


@_documented("axial_time.png")
def axial_histories(result: DrillResult, title: Optional[str] = None, *, fig: Optional[FigureLike] = None,
                    units: str = "si") -> Figure:
    """A coupled run's bit on bottom against time (:attr:`DrillResult.axial`).

    From the top: weight on bit and hook load, kN (klbf); torque on bit, kN m (kft-lbf); rate of
    penetration and the bit's axial speed, m/h (ft/h); depth of cut per revolution, mm (in). The
    metrics window is shaded; the title gives the coupled metrics (mean ROP, weight and torque on
    bit, bit bounce). A torsion-only run's figure says it has no axial series.
    """
    force, force_unit = axis_unit("N", units, kilo=True)
    torque, torque_unit = axis_unit("N*m", units, kilo=True)
    speed, speed_unit = axis_unit("m/h", units)
    cut, cut_unit = _depth_of_cut_axis(units)
    fig = _figure(11, 8.0) if fig is None else fig
    axes = fig.subplots(4, 1, sharex=True)
    a = result.axial
    if not a:
        return _no_axial(fig, axes, "no axial series (a torsion-only run: no [hoist] table)")
    for ax in axes:
        _shade_window(ax, result)
        ax.grid(alpha=0.3)
    t = result.t
    axes[0].plot(t, a["weight_on_bit"] * force, lw=1.0, color="tab:orange", label="weight on bit")
    axes[0].plot(t, a["hook_load"] * force, lw=1.0, color="tab:blue", label="hook load")
    axes[0].set_ylabel(f"force, {force_unit}")
    axes[1].plot(t, result.bit_torque * torque, lw=1.0, color="tab:orange", label="torque on bit")
    axes[1].set_ylabel(f"torque, {torque_unit}")
    axes[2].plot(t, a["bit_axial_speed"] * 3600.0 * speed, lw=0.8, color="0.5", label="bit axial speed")
    axes[2].plot(t, a["rop"] * speed, lw=1.0, color="tab:green", label="rate of penetration")
    axes[2].set_ylabel(f"speed, {speed_unit}")
    axes[3].plot(t, a["depth_of_cut"] * cut, lw=1.0, color="tab:red", label="depth of cut per revolution")
    axes[3].set_ylabel(f"depth of cut, {cut_unit}")
    axes[3].set_xlabel("t, s")
    for ax in axes:
        ax.legend(loc="upper right", fontsize=9)
    c = result.coupled_metrics  # (the registry's first four: the means of ROP, weight and torque on bit, the bounce)
    summary = ", ".join(metric_texts(c, list(c)[:4], units)) if c else "no coupled metrics"
    fig.suptitle(title or f"{_title(result, units)}\non bottom: {summary} (shaded: metrics window)", fontsize=11)
    return _root(fig)


@_documented("axial_space_time.png")
def axial_space_time(result: DrillResult, title: Optional[str] = None, *, fig: Optional[FigureLike] = None,
                     units: str = "si") -> Figure:
    """A coupled run's axial field along the string against time.

    Top: axial speed, m/h (ft/h), down positive; bottom: axial force, kN (klbf), compression
    positive (a diverging scale around 0: tension above the neutral point, compression below);
    measured depth, m (ft), grows downward. Drawn from the snapshots of
    ``numerics.field_interval``; without snapshots or without a hoist each panel says so.
    """
    force, force_unit = axis_unit("N", units, kilo=True)
    speed, speed_unit = axis_unit("m/h", units)
    depth, depth_unit = axis_unit("m", units)
    fig = _figure(11, 7.0) if fig is None else fig
    axes = fig.subplots(2, 1, sharex=True)
    if result.axial_z.size == 0:
        return _no_axial(fig, axes, "no axial field (a torsion-only run: no [hoist] table)")
    if result.field_t.size == 0:
        return _no_axial(fig, axes, "no snapshots (numerics.field_interval = 0)")
    _space_time_panels(fig, result.field_t, result.axial_z * depth, depth_unit, (
        (axes[0], result.axial_speed_field, 3600.0 * speed, f"axial speed (down +), {speed_unit}", "viridis"),
        (axes[1], result.axial_force_field, force, f"axial force (compression +), {force_unit}", "RdBu_r")))
    fig.suptitle(title or f"{_title(result, units)}: axial field along the string", fontsize=11)
    return _root(fig)


#: The figures of a run by name (:meth:`DrillResult.plot`'s ``kind``).
KINDS = {"time": time_histories, "space_time": space_time_maps, "torque_depth": torque_depth}
KINDS.update(axial=axial_histories, axial_space_time=axial_space_time)
