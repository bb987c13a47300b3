"""The PDE itself (eq. 18) by the method of lines: :func:`solve_pde` and :class:`PdeSolution`.

The energy ``H`` of the model notes is discretised on ``N`` nodes ``z_j = j h``,
``h = l / (N - 1)`` (trapezoid weights for node terms, cell gradients
``g = (theta_{j+1} - theta_j) / h`` for the gradient terms) and the discrete Euler-Lagrange
equations are integrated: the semi-discrete system conserves the discrete energy exactly, the
Neumann ends (eq. 14) are natural, and the scheme is second order in ``h`` (the lumped-mass
linear finite-element method). The nodes' equations are solved in the Rust core with the same
integrators as the modal system (DOP853 by default; ``"verlet"`` is symplectic Stormer-Verlet).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np

from .. import _core
from ..errors import SolveError, ValidationError
from ..io.output import is_stream, write_to
from ..io.progress import ProgressOption, SolveProgress, check_progress
from ..model.coefficients import PDECoefficients
from ..model.parameters import Parameters
from .modal import FIXED_STEP_METHODS, PDE_METHODS, Method, _count, _output_times, check_solver_options
from .trajectory import TrajectoryResult

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import ArrayLike, NDArray

__all__ = ["PdeSolution", "solve_pde", "pde_system", "MAX_NODES"]

#: Largest grid accepted (the core's ``pde::MAX_NODES``); the memory budget refuses smaller
#: grids whose outputs would not fit (16 bytes a node a sample).
MAX_NODES: int = _core.PDE_MAX_NODES

InitialField = Union[None, "ArrayLike", Callable[["NDArray[np.float64]"], "ArrayLike"]]


def pde_system(params: Parameters, nodes: int = 240) -> Any:
    """The Rust ``PdeSystem`` of ``params`` on ``nodes`` grid points (validated), with the
    viscous damping ``params.damping_rate``."""
    nodes = _count("nodes", nodes, 3, MAX_NODES)
    k = PDECoefficients.from_parameters(params)
    return _core.PdeSystem(
        k.k1, k.k2, k.k3, k.k4, k.k5, k.k6, params.length, nodes, damping_rate=params.damping_rate
    )


def _initial_field(name: str, value: InitialField, z: NDArray[np.float64]) -> Optional[NDArray[np.float64]]:
    if value is None:
        return None
    if callable(value):
        value = value(z.copy())
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError) as exc:  # OverflowError: an int like 10**400
        allowed = f"an array of {z.size} finite floats or a function of z"
        raise ValidationError(name, type(value).__name__, allowed) from exc
    if arr.shape != z.shape:
        raise ValidationError(name, f"an array of shape {arr.shape}", f"shape ({z.size},) (one value per node)")
    if not np.all(np.isfinite(arr)):
        raise ValidationError(name, "an array with NaN or infinite values", "finite values")
    return np.ascontiguousarray(arr)


#: The default output times of :func:`solve_pde` resolve at least this many modes (the core's
#: ``pde::MIN_RESOLVED_MODES``).
MIN_RESOLVED_MODES: int = _core.PDE_MIN_RESOLVED_MODES
#: A cosine mode of the initial condition counts (for the default output times) when its
#: amplitude, in velocity units, is at least this share of the largest one (the core's
#: ``pde::MODE_CONTENT_SHARE``).
MODE_CONTENT_SHARE: float = _core.PDE_MODE_CONTENT_SHARE


def fastest_mode(params: Parameters, twist: NDArray[np.float64], velocity: NDArray[np.float64]) -> tuple[float, str]:
    """The mode the default output times of :func:`solve_pde` resolve: the highest cosine mode
    ``cos(i pi z / l)`` of the initial condition (twist amplitude times ``w_i``, or velocity
    amplitude, at least :data:`MODE_CONTENT_SHARE` of the largest; the nodal fields' discrete
    cosine transform), and at least mode :data:`MIN_RESOLVED_MODES`. Returns its linear
    frequency ``w_i / 2 pi`` (Hz, :meth:`PDECoefficients.linear_frequencies`, the continuum
    value, which bounds the grid's) and ``"mode i"``. The grid's own highest modes are far
    faster but carry no energy unless the initial condition puts it there. Computed by the core
    (``PdeSystem::fastest_mode``)."""
    return _fastest(pde_system(params, np.asarray(twist).size), twist, velocity)


def _fastest(system: Any, twist: NDArray[np.float64], velocity: NDArray[np.float64]) -> tuple[float, str]:
    mode, rate = system.fastest_mode(np.ascontiguousarray(twist, dtype=float),
                                     np.ascontiguousarray(velocity, dtype=float))
    return rate / (2 * math.pi), f"mode {mode}"


class PdeSolution(TrajectoryResult):
    """The result of :func:`solve_pde`.

    Attributes
    ----------
    t : ndarray, shape (samples,)
        Output times, s.
    z : ndarray, shape (nodes,)
        Node positions, m.
    q, qdot : ndarray, shape (nodes, samples)
        ``theta(z_j, t)`` (rad) and its rate (rad/s) at every node and sample.
    field : ndarray, shape (nodes, len(field_t)) or None
        ``theta(z_j, t)`` at every ``save_field_every``-th sample (``None`` when not asked).
    field_t : ndarray or None
        The times of ``field``.
    status, message, stats, method, params
        As :class:`~drillstring.solvers.modal.Simulation`.

    ``theta(z)`` interpolates linearly between nodes (second order, like the scheme).
    """

    def __init__(
        self, params: Parameters, system: Any, method: str, raw: Mapping[str, Any], save_field_every: Optional[int]
    ) -> None:
        super().__init__(params, system, method, raw)
        self.z: NDArray[np.float64] = np.asarray(system.z)
        self.save_field_every = save_field_every
        if save_field_every is None:
            self.field: Optional[NDArray[np.float64]] = None
            self.field_t: Optional[NDArray[np.float64]] = None
        else:
            self.field = self.q[:, ::save_field_every]
            self.field_t = self.t[::save_field_every]

    @property
    def nodes(self) -> int:
        return int(self.z.size)

    def _section_matrix(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        n = self.nodes
        h = self.params.length / (n - 1)
        j = np.minimum(np.floor(z / h).astype(np.int64), n - 2)
        w = z / h - j
        matrix = np.zeros((z.size, n))
        rows = np.arange(z.size)
        matrix[rows, j] = 1.0 - w
        matrix[rows, j + 1] = w
        return matrix

    def _state_columns(self) -> list[str]:
        return []

    def _state_dimension(self) -> tuple[str, NDArray[Any], dict[str, str], str, str]:
        return "z", self.z, {"units": "m", "long_name": "node position"}, "theta", "theta_dot"

    def save_field(self, path: Any) -> Optional[Path]:
        """Writes ``t``, ``z`` and ``theta`` (nodes x samples; the saved field, else every sample)
        to a compressed ``.npz`` and returns the path written (:func:`field_path`: ``.npz`` is
        appended to a file name without it, as numpy does). A file is replaced atomically (an
        interrupted write leaves the old one), a symlink is written through, a device, FIFO or
        ``"-"`` is streamed into (see :mod:`drillstring.io.output`); an open file object is
        written directly."""
        theta = self.q if self.field is None else self.field
        t = self.t if self.field_t is None else self.field_t
        return write_to(
            field_path(path), lambda target: np.savez_compressed(target, t=t, z=self.z, theta=theta), suffix=".npz"
        )

    def __repr__(self) -> str:
        return (
            f"PdeSolution(method={self.method!r}, nodes={self.nodes}, samples={self.t.size}, "
            f"status={self.status!r}, nfev={self.stats.nfev})"
        )


def field_path(path: Any) -> Any:
    """The file :meth:`PdeSolution.save_field` writes for ``path``: ``.npz`` appended to a file
    name without it (as numpy does), unless ``path`` is streamed into (``"-"``, a device or a
    FIFO); an open file object is returned as it is."""
    if isinstance(path, (str, bytes, os.PathLike)) and not is_stream(path):
        text = os.fsdecode(os.fspath(path))
        if not text.endswith(".npz"):
            return f"{text}.npz"
    return path


def solve_pde(
    params: Parameters,
    nodes: int = 240,
    t_end: float = 1.0,
    method: Method = "dop853",
    rtol: float = 1e-9,
    atol: float = 1e-12,
    t_eval: Optional[ArrayLike] = None,
    save_field_every: Optional[int] = None,
    *,
    dt: Optional[float] = None,
    samples: Optional[int] = None,
    initial_twist: InitialField = None,
    initial_velocity: InitialField = None,
    max_steps: Optional[int] = None,
    check: bool = True,
    progress: ProgressOption = False,
) -> PdeSolution:
    """Solves the nonlinear torsion PDE (eq. 18, Neumann ends) on ``nodes`` grid points.

    Parameters
    ----------
    params : Parameters
        Drill string, ``omega`` and the initial modal velocities ``C_i``: by default
        ``theta(z, 0) = 0`` and ``theta_t(z, 0) = sum_i C_i cos(i pi z / l)`` (eq. 13).
    nodes : int
        Grid points ``N >= 3`` including both ends.
    t_end, method, rtol, atol, t_eval, dt, samples, max_steps, check, progress
        As :func:`~drillstring.solvers.modal.simulate`; ``method`` may also be ``"verlet"``
        (symplectic, fixed step). Fixed-step methods default to half the CFL limit ``h / c``.
        The default ``samples`` resolve the highest mode of the initial condition, and at least
        mode 3 (:func:`fastest_mode`), with 20 samples per period (at least 1001 samples, at
        most a quarter of the memory budget): 1868 over 1 s for the aluminium preset. Sparser
        output times issue a :class:`~drillstring.errors.SamplingWarning`.
        With ``params.damping_rate > 0`` (damping ``-k1 c theta_t`` at every node, lumped like
        the inertia) only "dop853", "dopri5", "rk4" and "auto" apply.
    save_field_every : int, optional
        Keep ``theta(z_j, t)`` at every k-th output sample in ``result.field``.
    initial_twist, initial_velocity : array_like or callable, optional
        ``theta(z_j, 0)`` and ``theta_t(z_j, 0)`` as arrays over the nodes or functions of
        ``z``; they replace the modal initial conditions.

    Examples
    --------
    >>> import drillstring as ds
    >>> sol = ds.solve_pde(ds.preset("aluminum"), nodes=120, t_end=0.1)
    >>> sol.theta(200.0 / 3).shape
    (1001,)
    """
    if not isinstance(params, Parameters):
        raise ValidationError("params", type(params).__name__, "a drillstring.Parameters")
    method, t_end_f, rtol_f, atol_f, dt_f, steps = check_solver_options(
        method, t_end, rtol, atol, dt, max_steps, methods=PDE_METHODS
    )
    if not isinstance(check, bool):
        raise ValidationError("check", check, "True or False")
    progress = check_progress(progress)
    every = None if save_field_every is None else _count("save_field_every", save_field_every, 1)
    system = pde_system(params, nodes)
    method = _core.resolve_method(method, system.velocity_dependent, rtol_f)
    z = np.asarray(system.z)
    twist = _initial_field("initial_twist", initial_twist, z)
    velocity = _initial_field("initial_velocity", initial_velocity, z)
    q0 = np.zeros(z.size) if twist is None else twist
    if velocity is None:
        velocity = np.asarray(system.initial_velocity_from_modes(np.asarray(params.initial_velocities, dtype=float)))
    if method in FIXED_STEP_METHODS and dt_f is None:
        dt_f = system.default_dt()  # half the CFL limit h / c
    times = _output_times(
        t_eval, samples, t_end_f, method, state_dim=2 * z.size, dt=dt_f, max_steps=steps,
        fastest=lambda: _fastest(system, q0, velocity), default_field="nodes", default_value=nodes,
    )
    with SolveProgress(progress, t_end_f, "solve_pde") as bar:
        raw = _core.solve_pde(system, q0, velocity, t_end_f, times, method, rtol_f, atol_f, dt=dt_f, max_steps=steps,
                              **bar.core_kwargs())
        result = PdeSolution(params, system, method, raw, every)
        bar.finish(result)
    if check and not result.success:
        raise SolveError(result.status, result.message, result)
    return result
