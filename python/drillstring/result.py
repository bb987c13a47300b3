"""What a solve returns: samples of the state, the twist at any section, energy, statistics.

:class:`TrajectoryResult` is shared by the modal model (:class:`~drillstring.simulate.Simulation`)
and the finite-difference PDE (:class:`~drillstring.pde.PdeSolution`); they differ only in how
the state maps to the twist ``theta(z, t)`` (a Galerkin basis or interpolation between nodes).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from ._output import write_to
from .errors import ValidationError

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import ArrayLike, NDArray

    from .parameters import Parameters

__all__ = ["SolverStats", "TrajectoryResult"]


@dataclass(frozen=True)
class SolverStats:
    """Work counters of one solve."""

    nfev: int
    """Right-hand-side (acceleration) evaluations."""
    naccept: int
    """Accepted steps."""
    nreject: int
    """Rejected steps (0 for fixed-step methods)."""


class TrajectoryResult:
    """Samples ``t`` of a state ``q`` (rows) and ``qdot``, with statuses and the energy.

    Subclasses define :meth:`_section_matrix` (the linear map from the state to
    ``theta(z)``) and :meth:`_state_columns` (CSV column names of the state rows).
    """

    def __init__(self, params: Parameters, system: Any, method: str, raw: dict[str, Any]) -> None:
        self.params = params
        self.method = method
        self._system = system
        y = np.asarray(raw["y"])
        m = y.shape[1] // 2
        self.t: NDArray[np.float64] = np.asarray(raw["t"])
        self.q: NDArray[np.float64] = np.ascontiguousarray(y[:, :m].T)
        self.qdot: NDArray[np.float64] = np.ascontiguousarray(y[:, m:].T)
        self.status: str = raw["status"]
        self.message: str = raw["message"]
        self.stats = SolverStats(int(raw["nfev"]), int(raw["naccept"]), int(raw["nreject"]))
        self._energy: Optional[NDArray[np.float64]] = None

    def _section_matrix(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        raise NotImplementedError

    def _state_columns(self) -> list[str]:
        raise NotImplementedError

    @property
    def success(self) -> bool:
        """True when the solve reached ``t_end``."""
        return self.status == "success"

    def _sections(self, z: ArrayLike) -> tuple[NDArray[np.float64], bool]:
        try:
            z_arr = np.asarray(z, dtype=np.float64)
        except (TypeError, ValueError, OverflowError) as exc:
            raise ValidationError("z", z, "a number or array of numbers") from exc
        length = self.params.length
        z_flat = np.atleast_1d(z_arr).ravel()
        if z_flat.size == 0 or not np.all(np.isfinite(z_flat)) or np.any(z_flat < 0) or np.any(z_flat > length):
            raise ValidationError("z", z, f"sections with 0 <= z <= length = {length}")
        return self._section_matrix(z_flat), z_arr.ndim == 0

    def theta(self, z: Union[float, ArrayLike]) -> NDArray[np.float64]:
        """Twist angle ``theta(z, t)`` (rad) at section(s) ``z`` (m) over ``t``.

        Returns shape (samples,) for a scalar ``z``, else (len(z), samples).
        """
        matrix, scalar = self._sections(z)
        out = matrix @ self.q
        return out[0] if scalar else out

    def theta_dot(self, z: Union[float, ArrayLike]) -> NDArray[np.float64]:
        """Twist rate ``d theta / dt (z, t)`` (rad/s) at section(s) ``z``; shapes as :meth:`theta`."""
        matrix, scalar = self._sections(z)
        out = matrix @ self.qdot
        return out[0] if scalar else out

    @property
    def energy(self) -> NDArray[np.float64]:
        """The conserved energy ``H`` (J, model notes) of each sample."""
        if self._energy is None:
            self._energy = np.asarray(self._system.energy(self.q, self.qdot))
        return self._energy

    def energy_drift(self) -> float:
        """``max |H(t) - H(0)| / |H(0)|`` over the samples (0 when H(0) = 0)."""
        h = self.energy
        if h.size == 0 or h[0] == 0:
            return 0.0
        return float(np.max(np.abs(h - h[0])) / abs(h[0]))

    def table(self, z: float) -> tuple[list[str], NDArray[np.float64]]:
        """Columns ``t, theta, theta_dot`` at section ``z``, then the state rows that have column
        names (the modal coordinates ``q_i``; none for the PDE's nodal values)."""
        columns = self._state_columns()
        header = ["t", "theta", "theta_dot", *columns]
        parts = [self.t, self.theta(z), self.theta_dot(z)]
        if columns:
            parts.append(self.q.T)
        return header, np.column_stack(parts)

    def to_csv(self, path: Any, z: float) -> Optional[Path]:
        """Writes :meth:`table` at section ``z`` as CSV to ``path`` (or an open file object) and
        returns the path written. A file is replaced atomically (an interrupted write leaves the
        old one), a symlink is written through, a device or FIFO is streamed into, ``"-"`` is
        standard output (see :mod:`drillstring._output`)."""
        header, data = self.table(z)
        return write_to(
            path,
            lambda target: np.savetxt(
                target, data, delimiter=",", header=",".join(header), comments="", fmt="%.10e"
            ),
            suffix=".csv",
        )
