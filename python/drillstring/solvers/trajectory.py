"""What a solve returns: samples of the state, the twist at any section, energy, statistics.

:class:`TrajectoryResult` is shared by the modal model (:class:`~drillstring.solvers.modal.Simulation`)
and the finite-difference PDE (:class:`~drillstring.solvers.pde.PdeSolution`); they differ only in how
the state maps to the twist ``theta(z, t)`` (a Galerkin basis or interpolation between nodes).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..io.extras import require
from ..io.output import atomic_write, write_to

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from ..model.parameters import Parameters

__all__ = ["SolverStats", "TrajectoryResult", "UNITS", "default_section"]

#: Units of the quantities in exported tables and datasets.
UNITS = {"t": "s", "z": "m", "theta": "rad", "theta_dot": "rad/s", "q": "rad", "qdot": "rad/s", "energy": "J"}


def default_section(length: float) -> float:
    """The section the paper reports, ``z_k = 2 l / 3`` (m): the core's
    ``model::default_section``, the default section of every twist output."""
    return _core.default_section(float(length))


@dataclass(frozen=True)
class SolverStats:
    """Work counters of one solve."""

    nfev: int
    """Right-hand-side (acceleration) evaluations, counted by the core: those of the steps and
    those the dense output needs. DOP853: ``2 + 12 naccept + 11 nreject`` plus 3 for each
    accepted step with an output time strictly inside it (so it grows with ``samples`` for the
    same steps); RKN12: ``2 + 17 naccept + 16 nreject`` plus, with output times, the two steps
    before ``t0`` and the two after ``t_end`` its interpolants take (68 when none is rejected);
    DOPRI5: ``2 + 6 (naccept + nreject)``; RK4: 4 a step; central differences and
    Stormer-Verlet: ``1 + steps``."""
    naccept: int
    """Accepted steps."""
    nreject: int
    """Rejected steps (0 for fixed-step methods)."""
    ndense: int = 0
    """Of ``nfev``, the evaluations made only for the dense output (DOP853's 3 extra stages for
    each accepted step with an output time strictly inside it, RKN12's steps before ``t0`` and
    after ``t_end``; 0 for the other methods):
    ``nfev - ndense`` is the same whatever the output times."""


class TrajectoryResult:
    """Samples ``t`` of a state ``q`` (rows) and ``qdot``, with statuses and the energy.

    ``q`` and ``qdot`` (``n x samples``) are views of the core's sample-major state array,
    not copies: their rows are strided (``np.ascontiguousarray(res.q)`` gives a contiguous
    copy). Copying them into rows of their own took longer than a 3-mode solve with 20,001
    samples, mostly in page faults of the fresh memory.

    Subclasses define :meth:`_section_matrix` (the linear map from the state to
    ``theta(z)``), :meth:`_state_columns` (CSV column names of the state rows) and
    :meth:`_state_dimension` (how :meth:`to_xarray` names the state rows).
    """

    def __init__(self, params: Parameters, system: Any, method: str, raw: Mapping[str, Any]) -> None:
        self.params = params
        self.method = method
        self._system = system
        y = np.asarray(raw["y"])
        m = y.shape[1] // 2
        self.t: NDArray[np.float64] = np.asarray(raw["t"])
        self.q: NDArray[np.float64] = y[:, :m].T
        self.qdot: NDArray[np.float64] = y[:, m:].T  # views (see the class docstring)
        self.status: str = raw["status"]
        self.message: str = raw["message"]
        self.stats = SolverStats(int(raw["nfev"]), int(raw["naccept"]), int(raw["nreject"]), int(raw.get("ndense", 0)))
        self._energy: Optional[NDArray[np.float64]] = None
        dissipated = raw.get("dissipated")
        #: With damping: the energy (J) the damping took out from ``t = 0`` to each sample,
        #: integrated by the core with the state; ``None`` for the undamped model.
        self.dissipated: Optional[NDArray[np.float64]] = None if dissipated is None else np.asarray(dissipated)

    def _section_matrix(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        raise NotImplementedError

    def _state_columns(self) -> list[str]:
        raise NotImplementedError

    def _state_dimension(self) -> tuple[str, NDArray[Any], dict[str, str], str, str]:
        """``(dimension, coordinate values, coordinate attributes, name of q, name of qdot)``."""
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
        """``max |H(t) - H(0)| / |H(0)|`` over the samples (0 when H(0) = 0).

        With damping, the error of the energy balance: ``max |H(t) + D(t) - H(0)| / |H(0)|``
        with ``D`` = :attr:`dissipated`; it closes to the order of the solve's tolerance.
        Computed by the core, as a sweep's ``energy_drift``."""
        return _core.energy_drift(self.energy, self.dissipated)

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
        standard output (see :mod:`drillstring.io.output`)."""
        header, data = self.table(z)
        return write_to(
            path,
            lambda target: np.savetxt(
                target, data, delimiter=",", header=",".join(header), comments="", fmt="%.10e"
            ),
            suffix=".csv",
        )

    def _attributes(self) -> dict[str, Any]:
        """The run's parameters and solver outcome as netCDF-ready attributes (numbers, strings
        and 1-D float arrays)."""
        from .._core import __version__

        attrs: dict[str, Any] = {}
        for name, value in self.params.to_dict().items():
            if isinstance(value, bool):
                attrs[name] = int(value)  # netCDF has no boolean attributes
            elif isinstance(value, (list, tuple)):
                attrs[name] = np.asarray(value, dtype=np.float64)
            elif value is not None:
                attrs[name] = value
        attrs.update(
            method=self.method, status=self.status, message=self.message, nfev=self.stats.nfev,
            naccept=self.stats.naccept, nreject=self.stats.nreject, drillstring_version=__version__,
        )
        return attrs

    def to_pandas(self, z: Union[None, float, ArrayLike] = None) -> pd.DataFrame:
        """The time series at section(s) ``z`` (m; default the paper's ``z_k = 2l/3``) as a
        :class:`pandas.DataFrame` indexed by ``t`` (s).

        A single section gives the columns ``theta`` (rad) and ``theta_dot`` (rad/s); several
        sections give two-level columns ``(quantity, z)``, e.g. ``df["theta"][z]``. The values are
        exactly :meth:`theta` and :meth:`theta_dot`. ``df.attrs`` holds ``units``, ``z``,
        ``method``, ``status`` and ``parameters`` (:meth:`Parameters.to_dict`).
        """
        import pandas as pd

        z = default_section(self.params.length) if z is None else z
        theta, theta_dot = self.theta(z), self.theta_dot(z)
        index = pd.Index(self.t, name="t")
        if theta.ndim == 1:
            frame = pd.DataFrame({"theta": theta, "theta_dot": theta_dot}, index=index)
            sections: Any = float(np.asarray(z, dtype=np.float64))
        else:
            sections = np.asarray(z, dtype=np.float64).ravel()
            columns = pd.MultiIndex.from_product([["theta", "theta_dot"], sections], names=["quantity", "z"])
            frame = pd.DataFrame(np.vstack([theta, theta_dot]).T, index=index, columns=columns)
            sections = sections.tolist()
        frame.attrs.update(
            units={key: UNITS[key] for key in ("t", "z", "theta", "theta_dot")}, z=sections,
            method=self.method, status=self.status, parameters=self.params.to_dict(),
        )
        return frame

    def to_xarray(self) -> xr.Dataset:
        """The whole solution as an :class:`xarray.Dataset`: the state over ``t`` (the modal
        coordinates ``q(mode, t)`` and ``qdot``, or the PDE field ``theta(z, t)`` and
        ``theta_dot``), ``energy(t)`` and with damping ``dissipated(t)``, each with its ``units``;
        the attributes are the run's parameters (``initial_velocities`` as an array), the method,
        status, message, work counters and the drillstring version. The arrays are copies of the
        result's. Needs the extra ``netcdf`` (xarray); without it raises
        :class:`~drillstring.errors.MissingExtraError`.
        """
        require("netcdf", "an xarray Dataset of a run")
        import xarray as xr

        dim, coord, coord_attrs, q_name, qdot_name = self._state_dimension()
        coords = {"t": ("t", self.t.copy(), {"units": UNITS["t"], "long_name": "time"}),
                  dim: (dim, np.asarray(coord).copy(), coord_attrs)}
        data = {
            q_name: ((dim, "t"), self.q.copy(), {"units": UNITS[q_name]}),
            qdot_name: ((dim, "t"), self.qdot.copy(), {"units": UNITS[qdot_name]}),
            "energy": (("t",), np.asarray(self.energy).copy(), {"units": UNITS["energy"],
                                                                "long_name": "conserved energy H"}),
        }
        if self.dissipated is not None:
            data["dissipated"] = (("t",), self.dissipated.copy(), {
                "units": UNITS["energy"], "long_name": "energy dissipated by the damping since t = 0"})
        return xr.Dataset(data, coords=coords, attrs=self._attributes())

    def save(self, path: Any) -> Path:
        """Writes :meth:`to_xarray` to ``path`` as netCDF-4 (HDF5, through h5netcdf) and returns
        the path. Read it back with ``xarray.open_dataset(path)``. A file is replaced atomically
        (an interrupted write leaves the old one), a symlink is written through, a device, FIFO
        or ``"-"`` is streamed into (see :mod:`drillstring.io.output`). Needs the extra ``netcdf``
        (xarray, h5netcdf and h5py); without it raises :class:`~drillstring.errors.MissingExtraError`
        before anything is written."""
        require("netcdf", "writing netCDF")
        dataset = self.to_xarray()
        return atomic_write(path, lambda tmp: dataset.to_netcdf(tmp, engine="h5netcdf"), suffix=".nc")
