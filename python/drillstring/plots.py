"""Plots of simulation results; every function returns a matplotlib Figure.

matplotlib is imported lazily with the non-interactive Agg backend when no backend was chosen,
so the functions work on headless machines.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional


if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from .simulate import Simulation

__all__ = ["time_history_and_phase"]


def _figure(**kwargs: object) -> "Figure":
    from matplotlib.figure import Figure

    return Figure(**kwargs)  # type: ignore[arg-type]


def time_history_and_phase(result: "Simulation", z: Optional[float] = None, title: Optional[str] = None) -> "Figure":
    """Time history ``theta(z, t)`` and phase portrait ``(theta, theta_dot)`` at section ``z``.

    ``z`` defaults to ``z_k = 2l/3``, the paper's section.
    """
    length = result.params.length
    z = 2 * length / 3 if z is None else z
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


def save(fig: "Figure", path: object, dpi: int = 130) -> None:
    """Saves a figure to ``path`` (format from the extension)."""
    fig.savefig(path, dpi=dpi)  # type: ignore[arg-type]


