"""Figures of a drilling-system run; every function returns a matplotlib Figure (no pyplot state).

* :func:`time_histories`: surface and bit speed, motor and bit torque against time, with the
  metrics window shaded;
* :func:`space_time_maps`: speed and torque along the string against time (depth downward);
* :func:`torque_depth`: torque along the string against depth (the envelope over the snapshots
  and the last one) with the break-off envelope, the static friction torque from the bit up that
  the core returns (:attr:`DrillResult.profile`), and the friction limit per metre.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from .result import DrillResult

__all__ = ["space_time_maps", "time_histories", "torque_depth"]

_KN = 1e-3


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def _title(result: DrillResult) -> str:
    cfg = result.config
    where = "on bottom" if cfg.bit.on_bottom else "off bottom"
    return (f"{cfg.length:.0f} m string ({len(cfg.sections)} sections), {cfg.top_drive.rpm:g} rpm, "
            f"{cfg.top_drive.controller.type} control, bit {where}")


def _shade_window(ax: object, result: DrillResult) -> None:
    start, end = result.metrics.window
    if np.isfinite(start) and np.isfinite(end) and end > start:
        ax.axvspan(start, end, color="0.92", zorder=0, lw=0)  # type: ignore[attr-defined]


def time_histories(result: DrillResult, title: Optional[str] = None) -> Figure:
    """Surface and bit rpm (top), motor and bit torque in kN m (bottom) against time; the
    metrics window is shaded, the break-off torque drawn as a dotted line and the minimum cycle
    torque it implies as a dash-dotted one."""
    fig = _figure(11, 6.4)
    ax_rpm, ax_torque = fig.subplots(2, 1, sharex=True)
    for ax in (ax_rpm, ax_torque):
        _shade_window(ax, result)
        ax.grid(alpha=0.3)
    ax_rpm.plot(result.t, result.surface_rpm, lw=1.0, color="tab:blue", label="surface (top drive)")
    ax_rpm.plot(result.t, result.bit_rpm, lw=1.0, color="tab:orange", ls="--", label="bit")
    ax_rpm.set_ylabel("speed, rpm")
    ax_rpm.legend(loc="upper right", fontsize=9)
    ax_torque.plot(result.t, result.motor_torque * _KN, lw=1.0, color="tab:blue", label="motor")
    ax_torque.plot(result.t, result.bit_torque * _KN, lw=1.0, color="tab:orange", ls="--", label="bit")
    breakoff = result.profile.breakoff_torque
    if np.isfinite(breakoff) and breakoff > 0:
        ax_torque.axhline(breakoff * _KN, color="k", lw=0.8, ls=":", label="break-off torque (wall friction)")
    low = result.metrics.min_cycle_torque_Nm
    if np.isfinite(low):
        ax_torque.axhline(low * _KN, color="0.4", lw=0.8, ls="-.", label="minimum cycle torque implied by break-off")
    ax_torque.set_ylabel("torque, kN m")
    ax_torque.set_xlabel("t, s")
    ax_torque.legend(loc="upper right", fontsize=9)
    m = result.metrics
    fig.suptitle(title or f"{_title(result)}\nSSI {m.ssi:.3g}, stuck {m.stuck_fraction:.3g}, "
                 f"period {m.period_s:.3g} s (shaded: metrics window)", fontsize=11)
    return fig


def space_time_maps(result: DrillResult, title: Optional[str] = None) -> Figure:
    """Speed (rpm) and torque (kN m) along the string against time, from the snapshots
    (``numerics.field_interval``); depth grows downward."""
    fig = _figure(11, 7.0)
    axes = fig.subplots(2, 1, sharex=True)
    if result.field_t.size == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no snapshots (numerics.field_interval = 0)", ha="center", va="center",
                    transform=ax.transAxes)
        return fig
    t = result.field_t
    z_stride = max(1, result.z.size // 600)  # at most ~600 rows drawn; data untouched
    t_stride = max(1, t.size // 1500)
    z = result.z[::z_stride]
    maps = ((axes[0], result.omega_field, 1.0, "speed, rpm", "viridis"),
            (axes[1], result.torque_field, _KN, "torque, kN m", "RdBu_r"))
    for ax, data, scale, label, cmap in maps:
        values = data[::t_stride, ::z_stride].T * scale
        if cmap == "RdBu_r":
            limit = float(np.nanmax(np.abs(values))) or 1.0
            limits = {"vmin": -limit, "vmax": limit}
        else:
            limits = {}
        mesh = ax.pcolormesh(t[::t_stride], z, values, cmap=cmap, shading="nearest", rasterized=True, **limits)
        fig.colorbar(mesh, ax=ax, pad=0.01).set_label(label)
        ax.set_ylabel("measured depth, m")
        ax.invert_yaxis()
    axes[1].set_xlabel("t, s")
    fig.suptitle(title or f"{_title(result)}: along the string", fontsize=11)
    return fig


def torque_depth(result: DrillResult, title: Optional[str] = None) -> Figure:
    """Left: torque against depth (min-max envelope over the snapshots, the last snapshot) with
    the break-off envelope +-(static friction torque from the bit up). Right: the static friction
    limit per metre against depth."""
    fig = _figure(11, 6.0)
    ax, ax_limit = fig.subplots(1, 2, sharey=True, width_ratios=[2.2, 1])
    profile = result.profile
    ax.fill_betweenx(profile.z, -profile.cumulative * _KN, profile.cumulative * _KN, color="0.9",
                     label="break-off envelope (static friction from the bit up)")
    ax.plot(profile.cumulative * _KN, profile.z, color="k", lw=0.9, ls=":")
    ax.plot(-profile.cumulative * _KN, profile.z, color="k", lw=0.9, ls=":")
    if result.field_t.size:
        low = result.torque_field.min(axis=0) * _KN
        high = result.torque_field.max(axis=0) * _KN
        ax.fill_betweenx(result.z, low, high, color="tab:blue", alpha=0.25, lw=0,
                         label=f"range over {result.field_t.size} snapshots")
        ax.plot(result.torque_field[-1] * _KN, result.z, color="tab:blue", lw=1.2,
                label=f"t = {result.field_t[-1]:.4g} s")
    ax.axvline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel("torque, kN m")
    ax.set_ylabel("measured depth, m")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    ax.invert_yaxis()
    ax_limit.plot(profile.limit_per_m, profile.z, color="tab:red", lw=1.0)
    ax_limit.set_xlabel("static friction limit, N m/m")
    ax_limit.grid(alpha=0.3)
    ax_limit.set_xlim(left=0.0)
    fig.suptitle(title or f"{_title(result)}\nbreak-off torque {profile.breakoff_torque * _KN:.4g} kN m",
                 fontsize=11)
    return fig
