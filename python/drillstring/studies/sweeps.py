"""Parameter sweeps: thousands of Galerkin runs solved in parallel in Rust, one table row each.

>>> import drillstring as ds
>>> table = ds.sweep(ds.preset("aluminum"),
...                  {"length": ds.linspace(100.0, 300.0, 3), "omega": [0.0, 3.14]},
...                  modes=3, t_end=0.2, samples=256)
>>> table[["length", "omega", "status", "max_theta", "unstable_modes"]].shape
(6, 5)

How it works
------------
The runs (the Cartesian product of axes, see :mod:`drillstring.studies.sweep_axes`, or an explicit list)
are split into chunks of ``chunk_size`` runs. A chunk is solved by one call of the Rust batch
solver (``drillstring._core.batch_solve``): each run's ``k1..k6`` (eq. 17) scale the
dimensionless Galerkin integrals of the basis, generated once, into its modal system; the runs
are integrated in parallel with the GIL released, on a thread pool made for the call (so a
forked child process can sweep too); the metrics are computed in Rust from ``theta(z, t)``
sampled at ``samples`` uniform times. Each chunk becomes a block of rows; the table is the
blocks in run order.

* Before any work the sweep is checked as a whole: the thread count (``1..=MAX_THREADS``),
  the memory of one chunk and, with ``trajectories``, of all kept samples (the core's estimate,
  ``drillstring._core.batch_plan``), and the size of the plan and the table, against
  :func:`drillstring.limits.memory_budget`. A request that cannot fit is a
  :class:`~drillstring.errors.ValidationError` naming the field, never an abort.
* A problem of one run (a value out of range, a number too large for a float, a coefficient
  that overflows) is that run's row (status ``"invalid"`` and a message); the others are solved.
* ``out_dir``: chunks are written as they finish (atomically, see
  :mod:`drillstring.io.sweep_store`, which also locks the directory against a second writer);
  running the same sweep again with the same ``out_dir`` resumes: it reuses each stored chunk
  that verifies against the plan and its checksum, recomputes (and names, with a
  :class:`~drillstring.errors.ResumeWarning`) those that do not, and returns the same table as
  an uninterrupted run. A Ctrl-C stops the runs under way within a fraction of a second; the
  chunk is stored with its finished runs, and a resume solves only the interrupted ones.
* ``client``: a ``dask.distributed.Client`` (or a scheduler address); every chunk is one task
  on the cluster, calling the same chunk function as the local path, so the table is the same.

Columns
-------
The parameters of each run as requested (``length``, ``youngs_modulus``, ``density``,
``poisson_ratio``, ``outer_diameter``, ``inner_diameter``, ``omega``, ``c1``, ``c2``, ... for
``initial_velocities``, ``k5_variant``, ``model``), ``z`` (the section of the metrics, m), then

* ``status``: ``"success"``, ``"invalid"`` (the parameter set was refused; no solve),
  ``"max_steps"``, ``"step_size_underflow"``, ``"non_finite"``, ``"out_of_memory"``,
  ``"interrupted"`` (only in a stored chunk awaiting its resume) or ``"error"``; ``message``
  says why ("" on success);
* ``max_theta`` = ``max |theta(z, t)|`` (rad) and ``rms_theta`` (rad) over the samples;
* ``dominant_frequency_hz``: the strongest peak of the Hann-windowed spectrum of
  ``theta(z, t)`` (zero-padded x8, log-parabolic interpolation;
  :func:`drillstring.studies.analysis.dominant_frequencies`);
* ``energy_drift`` = ``max |H - H(0)| / |H(0)|`` over the samples (with ``damping_rate > 0``
  the energy balance error ``max |H + dissipated - H(0)| / |H(0)|``);
* ``unstable_modes``: the number of retained modes with ``K_ii < 0`` (linearly unstable at the
  equilibrium, the saddles of :func:`drillstring.studies.stability.analyse`: a ``K_ii / M_ii`` within
  ``1e-12`` of the largest ``|K_jj / M_jj|`` counts as 0; the rigid mode counts whenever
  ``omega^2`` exceeds that); ``<NA>`` for invalid runs;
* ``nfev``: right-hand-side evaluations;
* ``share_mode_<i>`` for each retained mode ``i``: the largest share of the quadratic modal
  energy ``E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`` in ``sum_j E_j`` that mode ``i`` reached
  (modal energy exchange; with a negative ``K_i`` a share may be negative or exceed 1).

Metrics are NaN for runs that did not succeed. pandas and pyarrow are dependencies of
drillstring; dask is the extra ``dask`` (``pip install '.[dask]'`` in a drillstring checkout).
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from numbers import Real
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..io.cluster import check_client, require_distributed
from ..io.progress import bar as progress_bar
from ..io.progress import on_terminal
from ..io.sweep_store import core_build
from ..limits import as_float, check_table_size, memory_budget
from ..model.coefficients import PDECoefficients
from ..model.galerkin import dimensionless_integrals
from ..model.parameters import CHOICE_FIELDS, Parameters, preset
from ..solvers.modal import FIXED_STEP_METHODS, SWEEP_METHODS, check_solver_options
from .sweep_axes import apply_overrides, expand_axes, linspace, logspace, run_overrides

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from numpy.typing import NDArray

__all__ = [
    "sweep",
    "linspace",
    "logspace",
    "SweepTrajectories",
    "ChunkTask",
    "solve_chunk",
    "METRICS",
    "DEFAULT_CHUNK_SIZE",
]

#: Metric columns of every sweep table (plus ``share_mode_<i>`` per retained mode).
METRICS = ("max_theta", "rms_theta", "dominant_frequency_hz", "energy_drift", "unstable_modes", "nfev")

#: Runs per chunk: the unit of resumption, of progress and of a Dask task.
DEFAULT_CHUNK_SIZE = 500

#: Version of the chunk/manifest layout (part of the fingerprint).
_FORMAT = 1

_NUMERIC_FIELDS = tuple(
    name for name in Parameters.field_names() if name != "initial_velocities" and name not in CHOICE_FIELDS
)


# --------------------------------------------------------------------------- one chunk


@dataclass(frozen=True)
class ChunkTask:
    """A chunk of runs: everything :func:`solve_chunk` needs (picklable, sent to Dask workers).

    ``runs`` are full parameter dicts as requested (possibly invalid); ``solver`` holds
    ``modes, rigid_mode, t_end, method, rtol, atol, dt, max_steps, samples``.
    """

    index: int
    start: int
    runs: tuple[dict[str, Any], ...]
    solver: dict[str, Any]
    z: Optional[float]
    velocity_columns: int
    threads: Optional[int] = None
    keep_trajectories: bool = False


def _as_float(value: Any) -> float:
    """A requested value as its table entry: the float, +-inf for a number too large for one,
    NaN for anything else (the row's message says why it was refused)."""
    if type(value) is float:
        return value
    if isinstance(value, Real) and not isinstance(value, bool):
        try:
            return float(value)
        except OverflowError:
            return math.inf if value > 0 else -math.inf  # type: ignore[operator]  # a Real int
    return math.nan


def _velocity_row(value: Any, count: int) -> list[float]:
    if isinstance(value, (list, tuple, np.ndarray)):
        values = [_as_float(v) for v in list(value)[:count]]
        return values + [0.0] * (count - len(values))
    return [math.nan] * count


def _coefficients(params: Parameters, cache: dict[tuple[Any, ...], tuple[float, ...]]) -> tuple[float, ...]:
    """``k1..k6`` of ``params``, exactly as :meth:`PDECoefficients.from_parameters`.

    ``k1..k5`` do not depend on ``length`` and ``omega`` (the axes most sweeps vary): they are
    computed once per material, section and model, and ``k6 = (k6 / Omega^2) Omega^2`` per run
    by the core's rule (``_core.k6``: ``rho I_p Omega^2`` in the paper model, 0 in the
    consistent one).
    """
    key = (params.youngs_modulus, params.density, params.poisson_ratio, params.outer_diameter,
           params.inner_diameter, params.k5_variant, params.model)
    fixed = cache.get(key)
    if fixed is None:
        k = PDECoefficients.from_parameters(params.replace(omega=0.0))
        fixed = cache[key] = (k.k1, k.k2, k.k3, k.k4, k.k5, k.k6_per_omega_squared or 0.0)
    return (*fixed[:5], _core.k6(fixed[5], params.omega))


def columns(velocity_columns: int, indices: Sequence[int]) -> list[str]:
    """Column names of a sweep table, in order."""
    names: list[str] = []
    for name in Parameters.field_names():
        if name == "initial_velocities":
            names.extend(f"c{i + 1}" for i in range(velocity_columns))
        else:
            names.append(name)
    return names + ["z", "status", "message", *METRICS] + [f"share_mode_{i}" for i in indices]


def _default_z(requested: Mapping[str, Any], z: Optional[float]) -> float:
    """The section of a run's metrics: ``z``, or ``2 l / 3`` of its requested length (NaN when
    that is not a number)."""
    if z is not None:
        return z
    return _core.default_section(_as_float(requested.get("length")))


def parameter_columns(task: ChunkTask) -> pd.DataFrame:
    """The requested parameters of a chunk's runs as table columns (``c1``, ``c2``, ... for
    ``initial_velocities``) and ``z``, indexed by run number: the part of a chunk's rows that
    its plan fixes (a resumed sweep checks stored chunks against it)."""
    import pandas as pd
    n = len(task.runs)
    data: dict[str, Any] = {}
    for name in Parameters.field_names():
        if name == "initial_velocities":
            block = np.array(
                [_velocity_row(r.get(name), task.velocity_columns) for r in task.runs], dtype=float
            ).reshape(n, task.velocity_columns)
            for i in range(task.velocity_columns):
                data[f"c{i + 1}"] = block[:, i]
        elif name in CHOICE_FIELDS:
            data[name] = pd.array([str(r.get(name)) for r in task.runs], dtype="str")
        else:
            data[name] = np.array([_as_float(r.get(name)) for r in task.runs], dtype=float)
    data["z"] = np.array([_default_z(r, task.z) for r in task.runs], dtype=float)
    return pd.DataFrame(data, index=pd.RangeIndex(task.start, task.start + n))


def _run_inputs(
    requested: Mapping[str, Any],
    task: ChunkTask,
    indices: list[int],
    material: dict[tuple[Any, ...], tuple[float, ...]],
) -> tuple[tuple[float, ...], float, list[float], float, float]:
    """``k1..k6``, length, initial modal velocities, section and damping rate of one run; raises
    ValidationError (or any other error: the row becomes ``"invalid"`` with its message)."""
    params = Parameters(**requested)
    k = _coefficients(params, material)
    if not math.isfinite(k[5]):
        raise ValidationError(
            "omega", params.omega, "a rotation speed whose k6 = rho I_p omega^2 is a finite number"
        )
    c = params.initial_velocities
    velocities = [c[i - 1] if 1 <= i <= len(c) else 0.0 for i in indices]
    section = _core.default_section(params.length) if task.z is None else float(task.z)
    return k, params.length, velocities, section, params.damping_rate


def _solve_chunk_raw(task: ChunkTask) -> tuple[pd.DataFrame, Optional[dict[str, Any]], Optional[BaseException]]:
    """Solves a chunk: its rows, its trajectories (when kept) and the exception that
    interrupted it (Ctrl-C; the rows of the runs that did not finish then have status
    ``"interrupted"``), or None."""
    import pandas as pd
    solver = task.solver
    integrals = dimensionless_integrals(solver["modes"], solver["rigid_mode"])
    indices = integrals.indices.tolist()
    m = len(indices)
    n = len(task.runs)
    status = np.full(n, "invalid", dtype=object)
    message = np.full(n, "", dtype=object)
    metrics = {name: np.full(n, math.nan) for name in METRICS[:4]}
    unstable = np.full(n, -1, dtype=np.int64)
    nfev = np.zeros(n, dtype=np.int64)
    shares = np.full((n, m), math.nan)

    material: dict[tuple[Any, ...], tuple[float, ...]] = {}
    valid: list[int] = []
    k_rows: list[tuple[float, ...]] = []
    lengths: list[float] = []
    velocities: list[list[float]] = []
    sections: list[float] = []
    dampings: list[float] = []
    for j, requested in enumerate(task.runs):
        try:
            k, length, c, section, damping = _run_inputs(requested, task, indices, material)
        except ValidationError as exc:
            message[j] = str(exc)
            continue
        except Exception as exc:  # any other problem of this run is its row, not the sweep's
            message[j] = f"invalid parameters ({type(exc).__name__}): {exc}"
            continue
        valid.append(j)
        k_rows.append(k)
        lengths.append(length)
        velocities.append(c)
        sections.append(section)
        dampings.append(damping)

    raw: Optional[_core.BatchOutput] = None
    if valid:
        raw = _core.batch_solve(
            np.asarray(k_rows, dtype=float).reshape(-1, 6),
            np.asarray(lengths, dtype=float),
            np.asarray(velocities, dtype=float).reshape(-1, m),
            np.asarray(sections, dtype=float),
            integrals.indices,
            np.ascontiguousarray(integrals.quartic_index, dtype=np.int64),
            integrals.cos4,
            integrals.mixed,
            integrals.sin4,
            solver["t_end"],
            solver["samples"],
            solver["method"],
            solver["rtol"],
            solver["atol"],
            dt=solver["dt"],
            max_steps=solver["max_steps"],
            keep_trajectories=task.keep_trajectories,
            threads=task.threads,
            memory_budget=memory_budget(),
            damping_rate=np.asarray(dampings, dtype=float),
        )
        rows = np.asarray(valid)
        status[rows] = raw["status"]
        message[rows] = raw["message"]
        metrics["max_theta"][rows] = raw["max_theta"]
        metrics["rms_theta"][rows] = raw["rms_theta"]
        metrics["dominant_frequency_hz"][rows] = raw["dominant_frequency_hz"]
        metrics["energy_drift"][rows] = raw["energy_drift"]
        unstable[rows] = raw["unstable_modes"]
        nfev[rows] = raw["nfev"]
        shares[rows] = raw["max_share"]

    data: dict[str, Any] = {str(name): column.array for name, column in parameter_columns(task).items()}
    data["status"] = pd.array(status.tolist(), dtype="str")
    data["message"] = pd.array(message.tolist(), dtype="str")
    data.update(metrics)
    data["unstable_modes"] = pd.array([int(u) if u >= 0 else pd.NA for u in unstable], dtype="Int64")
    data["nfev"] = nfev
    for col, i in enumerate(indices):
        data[f"share_mode_{i}"] = shares[:, col]
    frame = pd.DataFrame(data, index=pd.RangeIndex(task.start, task.start + n))

    trajectories = None
    if task.keep_trajectories:
        samples = solver["samples"]
        y = np.full((n, samples, 2 * m), math.nan)
        theta = np.full((n, samples), math.nan)
        t = np.linspace(0.0, solver["t_end"], samples)
        if raw is not None:
            rows = np.asarray(valid)
            y[rows] = raw["y"]
            theta[rows] = raw["theta"]
        trajectories = {"t": t, "y": y, "theta": theta}
    interrupt = raw.get("interrupt") if raw is not None else None
    return frame, trajectories, interrupt


def solve_chunk(task: ChunkTask) -> pd.DataFrame:
    """Solve one chunk of runs (one Rust batch call) and return its rows.

    A module-level function so that Dask workers can run it (they import ``drillstring``).
    """
    return _solve_chunk_raw(task)[0]


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class SweepTrajectories:
    """The samples of every run of a sweep (``sweep(..., trajectories=True)``).

    Attributes
    ----------
    t : ndarray (S,)
        Sample times, s.
    theta : ndarray (R, S)
        ``theta(z, t)`` of each run at its section ``z`` (column ``z`` of the table).
    q, qdot : ndarray (R, m, S)
        Modal coordinates and rates, rows in the order of ``indices``.
    indices : ndarray (m,)
        Mode numbers of the retained basis.

    Runs that were invalid or stopped early are NaN (from where they stopped).
    """

    t: NDArray[np.float64]
    theta: NDArray[np.float64]
    q: NDArray[np.float64]
    qdot: NDArray[np.float64]
    indices: NDArray[np.int64]


def _progress_bar(total: int, enabled: bool) -> Any:
    """A tqdm bar of the runs on stderr, updated per chunk (prints nothing unless ``enabled``)."""
    return progress_bar(total, "sweep", "runs", enabled=enabled, every_update=True,
                        bar_format="{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} runs "
                        "[{elapsed}<{remaining}, {rate_fmt}]")


def _check_count(field: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValidationError(field, value, f"an integer >= {minimum}")
    return int(value)


def _base(base_params: Any) -> Parameters:
    if base_params is None:
        return Parameters()
    if isinstance(base_params, Parameters):
        return base_params
    if isinstance(base_params, str):
        return preset(base_params)
    if isinstance(base_params, Mapping):
        return Parameters.from_dict(base_params)
    raise ValidationError("base_params", base_params, "a Parameters, a preset name or a mapping of fields")


def _plan(
    base: Parameters, axes: Optional[Mapping[str, Any]], runs: Optional[Iterable[Any]]
) -> tuple[dict[str, list[Any]], list[dict[str, Any]]]:
    if axes is not None and runs is not None:
        raise ValidationError("runs", "both axes and runs", "either axes or an explicit list of runs")
    if runs is not None:
        if isinstance(runs, (str, bytes, Mapping)) or not isinstance(runs, Iterable):
            raise ValidationError("runs", runs, "a list of Parameters or of mappings {field: value}")
        overrides = [run_overrides(r) for r in runs]
        if not overrides:
            raise ValidationError("runs", [], "at least one run")
        named: dict[str, list[Any]] = {}
    elif axes is not None:
        named, overrides = expand_axes(axes)
    else:
        named, overrides = {}, [{}]
    base_dict = base.to_dict()
    return named, [apply_overrides(base_dict, o) for o in overrides]


def sweep(
    base_params: Union[Parameters, str, Mapping[str, Any], None] = None,
    axes: Optional[Mapping[str, Any]] = None,
    *,
    runs: Optional[Iterable[Union[Parameters, Mapping[str, Any]]]] = None,
    modes: int = 3,
    rigid_mode: bool = False,
    t_end: float = 1.0,
    method: str = "dop853",
    rtol: float = 1e-8,
    atol: float = 1e-12,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    samples: int = 1024,
    z: Optional[float] = None,
    threads: Optional[int] = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    out_dir: Any = None,
    client: Any = None,
    progress: Optional[bool] = None,
    trajectories: bool = False,
) -> Any:
    """Solve the Galerkin model for every parameter set of the product of axes (or a list); one row per run.

    Parameters
    ----------
    base_params : Parameters, str or mapping, optional
        The parameters the axes vary (a preset name or a ``{field: value}`` mapping with an
        optional ``"preset"`` key are accepted); default :class:`Parameters()`.
    axes : mapping, optional
        ``{field: values}``; the runs are the Cartesian product (:mod:`drillstring.studies.sweep_axes`:
        lists, :func:`linspace`, :func:`logspace`, ``c1``/``c2``/... for single velocities). A
        sweep file holds them in its ``[grid]`` table.
    runs : list of Parameters or mappings, optional
        Instead of ``axes``: explicit parameter sets (a mapping overrides fields of
        ``base_params``). An invalid set becomes a row with status ``"invalid"``.
    modes, rigid_mode : int, bool
        The basis, as in :func:`~drillstring.solvers.modal.simulate`.
    t_end, method, rtol, atol, dt, max_steps :
        Solver options, as in :func:`~drillstring.solvers.modal.simulate` (``rtol`` default 1e-8),
        with a named method (not ``"auto"``). ``max_steps`` applies to each run.
    samples : int
        Uniform samples of ``0 <= t <= t_end`` the metrics are computed from (>= 4).
    z : float, optional
        Section of ``theta(z, t)``, m; default ``2 l / 3`` of each run.
    threads : int, optional
        Threads of the Rust batch solve (default: all cores).
    chunk_size : int
        Runs per chunk (unit of progress, resumption and Dask tasks).
    out_dir : path, optional
        Write chunks as they finish and ``results.parquet`` / ``results.csv`` at the end;
        resume a previous, interrupted run of the same sweep (:mod:`drillstring.io.sweep_store`).
    client : dask.distributed.Client or str, optional
        Run the chunks on this Dask cluster (a str is a scheduler address to connect to).
    progress : bool, optional
        Show a progress bar on stderr (default: when stderr is a terminal).
    trajectories : bool
        Also return every run's samples: the result is ``(table, SweepTrajectories)``. Only
        without ``out_dir`` and ``client``.

    Returns
    -------
    pandas.DataFrame
        One row per run in run order (columns: see the module docstring); ``attrs["axes"]``
        holds the axes, ``attrs["solver"]`` the solver options.

    Raises
    ------
    ValidationError
        For bad shared input (solver options, axis keys, a foreign ``out_dir``); a bad
        parameter set is a row, not an error.
    ImportError
        Without dask for ``client`` (``pip install '.[dask]'`` in the drillstring checkout).
    """
    base = _base(base_params)
    named, fulls = _plan(base, axes, runs)
    solver, integrals, z, size, threads_i = _checked_options(
        fulls, modes=modes, rigid_mode=rigid_mode, t_end=t_end, method=method, rtol=rtol, atol=atol, dt=dt,
        max_steps=max_steps, samples=samples, z=z, threads=threads, chunk_size=chunk_size, out_dir=out_dir,
        client=client, trajectories=trajectories,
    )
    velocity_columns = max(
        [1] + [len(f["initial_velocities"]) for f in fulls if isinstance(f.get("initial_velocities"), (list, tuple))]
    )
    names = columns(velocity_columns, integrals.indices.tolist())
    check_table_size(len(fulls), len(names), velocity_columns)
    tasks = [
        ChunkTask(i, start, tuple(fulls[start : start + size]), solver, z, velocity_columns, threads_i, trajectories)
        for i, start in enumerate(range(0, len(fulls), size))
    ]
    store, fingerprint = _open_store(out_dir, solver, z, size, velocity_columns, fulls, len(tasks), list(named))
    try:
        table, raws = _run_tasks(tasks, names, store, fingerprint, client, len(fulls), progress)
        if store is not None:
            store.save_results(table)
    finally:
        if store is not None:
            store.close()
    table.attrs["axes"] = {key: values for key, values in named.items()}
    table.attrs["solver"] = dict(solver)
    if not trajectories:
        return table
    return table, _trajectories(tasks, raws, integrals.indices, len(fulls))


def _checked_options(
    fulls: list[dict[str, Any]], *, modes: int, rigid_mode: bool, t_end: float, method: str, rtol: float,
    atol: float, dt: Optional[float], max_steps: Optional[int], samples: int, z: Optional[float],
    threads: Optional[int], chunk_size: int, out_dir: Any, client: Any, trajectories: bool,
) -> tuple[dict[str, Any], Any, Optional[float], int, Optional[int]]:
    """The checked options of :func:`sweep`: the solver's options of every run, the Galerkin
    integrals of the basis, the section, the chunk size and the threads; the memory of a chunk
    (and of every kept trajectory) checked against the budget."""
    method, t_end_f, rtol_f, atol_f, dt_f, steps = check_solver_options(
        method, t_end, rtol, atol, dt, max_steps, methods=SWEEP_METHODS
    )
    samples_i = _check_count("samples", samples, 4)
    integrals = dimensionless_integrals(modes, rigid_mode)
    size = _check_count("chunk_size", chunk_size, 1)
    threads_i = None if threads is None else _check_count("threads", threads, 1)
    if z is not None:
        z = as_float("z", z, "a finite section position in m, or None for 2l/3")
    if not isinstance(trajectories, bool):
        raise ValidationError("trajectories", trajectories, "True or False")
    check_client(client)
    if trajectories and (out_dir is not None or client is not None):
        raise ValidationError("trajectories", True, "False with out_dir or client (trajectories stay in memory)")
    m = integrals.indices.size
    # Threads (1..=MAX_THREADS) and the memory of one chunk, then of every kept trajectory.
    _core.batch_plan(m, samples_i, min(size, len(fulls)), threads_i, trajectories, memory_budget())
    if trajectories:
        _core.batch_plan(m, samples_i, len(fulls), threads_i, True, memory_budget())
    solver = {
        "modes": int(modes),
        "rigid_mode": bool(rigid_mode),
        "t_end": t_end_f,
        "method": method,
        "rtol": rtol_f,
        "atol": atol_f,
        "dt": dt_f if method in FIXED_STEP_METHODS else None,
        "max_steps": steps,
        "samples": samples_i,
    }
    return solver, integrals, z, size, threads_i


def _open_store(out_dir: Any, solver: dict[str, Any], z: Optional[float], size: int, velocity_columns: int,
                fulls: list[dict[str, Any]], chunks: int, axes: list[str]) -> tuple[Any, str]:
    """The sweep's store in ``out_dir`` (None without one) and the fingerprint of the sweep."""
    if out_dir is None:
        return None, ""
    from ..io.sweep_store import SweepStore

    identity = {
        "format": _FORMAT,
        "drillstring_version": _core.__version__,
        "core_build": core_build(),
        "solver": solver,
        "z": z,
        "chunk_size": size,
        "velocity_columns": velocity_columns,
        "runs": len(fulls),
    }
    fingerprint = _digest({**identity, "parameters": fulls})
    manifest = {**identity, "fingerprint": fingerprint, "chunks": chunks, "axes": axes}
    return SweepStore.open(out_dir, manifest), fingerprint


def _trajectories(tasks: list[ChunkTask], raws: list[Any], indices: Any, runs: int) -> SweepTrajectories:
    """Every run's samples from the chunks' trajectories (each chunk's copy dropped as it is read)."""
    m = indices.size
    t = raws[0]["t"]
    traj = SweepTrajectories(
        t=t,
        theta=np.empty((runs, t.size)),
        q=np.empty((runs, m, t.size)),
        qdot=np.empty((runs, m, t.size)),
        indices=indices,
    )
    for task in tasks:  # fill the arrays chunk by chunk, dropping each chunk's copy
        rows = slice(task.start, task.start + len(task.runs))
        raw = raws[task.index]
        traj.theta[rows] = raw["theta"]
        traj.q[rows] = raw["y"][:, :, :m].transpose(0, 2, 1)
        traj.qdot[rows] = raw["y"][:, :, m:].transpose(0, 2, 1)
        raws[task.index] = None
    return traj


def _digest(value: Any) -> str:
    """SHA-256 of a JSON-able value (sorted keys; anything else by its repr)."""
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=repr).encode()).hexdigest()


def chunk_plan(fingerprint: str, task: ChunkTask) -> str:
    """The plan digest of a stored chunk: the sweep's fingerprint, the chunk's position and its
    runs' parameters (a chunk file written for any other chunk or sweep has another)."""
    return _digest({"fingerprint": fingerprint, "index": task.index, "start": task.start, "runs": list(task.runs)})


@dataclass
class _Job:
    """A chunk to solve: all its runs, or (resuming an interrupted chunk) the rows ``rows`` of
    the stored ``frame``."""

    task: ChunkTask
    frame: Any = None
    rows: Any = None

    def solve_task(self) -> ChunkTask:
        if self.rows is None:
            return self.task
        runs = tuple(self.task.runs[i] for i in self.rows)
        return ChunkTask(self.task.index, 0, runs, self.task.solver, self.task.z, self.task.velocity_columns,
                         self.task.threads, self.task.keep_trajectories)

    def merge(self, solved: Any) -> Any:
        """The chunk's rows: ``solved`` itself, or the stored rows with ``solved`` in place of
        the interrupted ones."""
        if self.rows is None:
            return solved
        import pandas as pd
        solved = solved.set_axis(self.frame.index[self.rows])
        return pd.concat([self.frame.drop(index=solved.index), solved]).sort_index()


def _resume(
    tasks: list[ChunkTask], names: list[str], store: Any, fingerprint: str
) -> tuple[list[Any], list[_Job], dict[str, Any]]:
    """What a store already holds: verified chunks (complete ones are reused, interrupted runs
    become jobs), the chunks to solve, and a summary for ``attrs["resume"]``. Chunks that fail
    verification are recomputed, with a :class:`ResumeWarning` naming them and why."""
    frames: list[Any] = [None] * len(tasks)
    jobs: list[_Job] = []
    summary: dict[str, Any] = {"reused": [], "recomputed": {}, "resumed_runs": 0}
    for task in tasks:
        if store is None:
            jobs.append(_Job(task))
            continue
        frame, reason = store.load_chunk(task.index, chunk_plan(fingerprint, task), parameter_columns(task), names)
        if frame is None:
            if reason is not None:
                summary["recomputed"][task.index] = reason
            jobs.append(_Job(task))
            continue
        interrupted = np.flatnonzero((frame["status"] == "interrupted").to_numpy())
        if interrupted.size:
            summary["resumed_runs"] += int(interrupted.size)
            jobs.append(_Job(task, frame, interrupted))
        else:
            summary["reused"].append(task.index)
            frames[task.index] = frame
    if summary["recomputed"]:
        from ..errors import ResumeWarning

        reasons = "; ".join(f"chunk {i}: {why}" for i, why in summary["recomputed"].items())
        warnings.warn(
            f"resuming the sweep in {store.root}: {len(summary['recomputed'])} stored chunk(s) failed verification "
            f"and are recomputed ({reasons})",
            ResumeWarning,
            stacklevel=3,
        )
    return frames, jobs, summary


def _run_tasks(
    tasks: list[ChunkTask],
    names: list[str],
    store: Any,
    fingerprint: str,
    client: Any,
    total: int,
    progress: Optional[bool],
) -> tuple[Any, list[Any]]:
    """Solves what the store does not hold (locally, or on Dask), saving each chunk as it
    finishes; returns the table and each chunk's trajectories (None unless kept).

    A Ctrl-C during a local chunk stops its runs within a fraction of a second; the chunk is
    saved with its finished runs (the others have status ``"interrupted"`` and are solved by
    the next resume) and the interrupt is raised.
    """
    import pandas as pd
    frames, jobs, summary = _resume(tasks, names, store, fingerprint)
    raws: list[Any] = [None] * len(tasks)
    bar = _progress_bar(total, on_terminal() if progress is None else bool(progress))
    bar.update(total - sum(len(j.task.runs) if j.rows is None else len(j.rows) for j in jobs))

    def finished(job: _Job, solved: Any) -> None:
        frame = job.merge(solved)
        complete = not bool((frame["status"] == "interrupted").any())
        if store is not None:
            store.save_chunk(job.task.index, chunk_plan(fingerprint, job.task), frame, complete)
        frames[job.task.index] = frame
        bar.update(len(solved))

    try:
        if client is not None and jobs:
            _run_on_dask(client, jobs, finished)
        else:
            for job in jobs:
                solved, raws[job.task.index], interrupt = _solve_chunk_raw(job.solve_task())
                finished(job, solved)
                if interrupt is not None:
                    raise interrupt
    finally:
        bar.close()
    table = pd.concat(frames, ignore_index=True) if len(frames) > 1 else frames[0].reset_index(drop=True)
    table.attrs["resume"] = summary
    return table, raws


def _run_on_dask(client: Any, jobs: list[_Job], finished: Any) -> None:
    """Submit every chunk as a task and hand each result to ``finished`` as it completes."""
    distributed = require_distributed()
    own = None
    if isinstance(client, str):
        own = client = distributed.Client(client)
    try:
        futures = {}
        for job in jobs:
            futures[client.submit(solve_chunk, job.solve_task(), pure=False)] = job
        try:
            for future in distributed.as_completed(list(futures)):
                finished(futures[future], future.result())
        except BaseException:
            client.cancel(list(futures))
            raise
    finally:
        if own is not None:
            own.close()
