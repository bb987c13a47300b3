"""Parameter sweeps: thousands of Galerkin runs solved in parallel in Rust, one table row each.

>>> import drillstring as ds
>>> table = ds.sweep(ds.preset("aluminum"),
...                  {"length": ds.linspace(100.0, 300.0, 3), "omega": [0.0, 3.14]},
...                  modes=3, t_end=0.2, samples=256)
>>> table[["length", "omega", "status", "max_theta", "unstable_modes"]].shape
(6, 5)

How it works
------------
The runs (the Cartesian product of a grid, see :mod:`drillstring.grid`, or an explicit list)
are split into chunks of ``chunk_size`` runs. A chunk is solved by one call of the Rust batch
solver (``drillstring._core.batch_solve``): each run's ``k1..k6`` (eq. 17) scale the
dimensionless Galerkin integrals of the basis, generated once, into its modal system; the runs
are integrated in parallel on a rayon pool with the GIL released; the metrics are computed in
Rust from ``theta(z, t)`` sampled at ``samples`` uniform times. Each chunk becomes a block of
rows; the table is the blocks in run order.

* ``out_dir``: chunks are written as they finish (atomically, see
  :mod:`drillstring.sweep_store`); running the same sweep again with the same ``out_dir``
  resumes, skipping finished chunks, and returns the same table as an uninterrupted run.
  A Ctrl-C is handled between chunks (the finished ones are kept).
* ``client``: a ``dask.distributed.Client`` (or a scheduler address); every chunk is one task
  on the cluster, calling the same chunk function as the local path, so the table is the same.

Columns
-------
The parameters of each run as requested (``length``, ``youngs_modulus``, ``density``,
``poisson_ratio``, ``outer_diameter``, ``inner_diameter``, ``omega``, ``c1``, ``c2``, ... for
``initial_velocities``, ``k5_variant``), ``z`` (the section of the metrics, m), then

* ``status``: ``"success"``, ``"invalid"`` (the parameter set was refused; no solve),
  ``"max_steps"``, ``"step_size_underflow"``, ``"non_finite"`` or ``"error"``; ``message``
  says why ("" on success);
* ``max_theta`` = ``max |theta(z, t)|`` (rad) and ``rms_theta`` (rad) over the samples;
* ``dominant_frequency_hz``: the strongest peak of the Hann-windowed spectrum of
  ``theta(z, t)`` (zero-padded x8, log-parabolic interpolation;
  :func:`drillstring.analysis.dominant_frequencies`);
* ``energy_drift`` = ``max |H - H(0)| / |H(0)|`` over the samples;
* ``unstable_modes``: the number of retained modes with ``K_ii < 0`` (linearly unstable at the
  equilibrium; the rigid mode counts whenever ``omega != 0``); ``<NA>`` for invalid runs;
* ``nfev``: right-hand-side evaluations;
* ``share_mode_<i>`` for each retained mode ``i``: the largest share of the quadratic modal
  energy ``E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`` in ``sum_j E_j`` that mode ``i`` reached
  (modal energy exchange; with a negative ``K_i`` a share may be negative or exceed 1).

Metrics are NaN for runs that did not succeed. pandas (and pyarrow for ``out_dir``) are the
optional extra ``drillstring[sweep]``; dask is ``drillstring[dask]``.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from numbers import Real
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from . import _core
from .coefficients import PDECoefficients
from .errors import ValidationError
from .galerkin import dimensionless_integrals
from .grid import apply_overrides, expand_grid, linspace, logspace, run_overrides
from .parameters import Parameters, preset
from .simulate import FIXED_STEP_METHODS, check_solver_options

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
    name for name in Parameters.field_names() if name not in ("initial_velocities", "k5_variant")
)


def _require_pandas() -> Any:
    try:
        import pandas as pd
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "drillstring.sweep needs pandas (and pyarrow to write results): "
            "pip install 'drillstring[sweep]'"
        ) from exc
    return pd


def _require_pyarrow() -> None:
    try:
        import pyarrow  # noqa: F401
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "writing sweep results (out_dir) needs pyarrow: pip install 'drillstring[sweep]'"
        ) from exc


def _require_distributed() -> Any:
    try:
        import distributed
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "running a sweep on a Dask cluster needs dask.distributed: pip install 'drillstring[dask]'"
        ) from exc
    return distributed


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
    if type(value) is float:
        return value
    if isinstance(value, Real) and not isinstance(value, bool):
        return float(value)
    return math.nan


def _velocity_row(value: Any, count: int) -> list[float]:
    if isinstance(value, (list, tuple, np.ndarray)):
        values = [_as_float(v) for v in list(value)[:count]]
        return values + [0.0] * (count - len(values))
    return [math.nan] * count


def _coefficients(params: Parameters, cache: dict[tuple[Any, ...], tuple[float, ...]]) -> tuple[float, ...]:
    """``k1..k6`` of ``params``, exactly as :meth:`PDECoefficients.from_parameters`.

    ``k1..k5`` do not depend on ``length`` and ``omega`` (the axes most sweeps vary): they are
    computed once per material and section, and ``k6 = (rho I_p) Omega^2`` per run.
    """
    key = (params.youngs_modulus, params.density, params.poisson_ratio, params.outer_diameter,
           params.inner_diameter, params.k5_variant)
    fixed = cache.get(key)
    if fixed is None:
        k = PDECoefficients.from_parameters(params.replace(omega=0.0))
        fixed = cache[key] = (k.k1, k.k2, k.k3, k.k4, k.k5, k.k1)  # k1 = rho I_p
    return (*fixed[:5], fixed[5] * params.omega**2)


def columns(velocity_columns: int, indices: Sequence[int]) -> list[str]:
    """Column names of a sweep table, in order."""
    names: list[str] = []
    for name in Parameters.field_names():
        if name == "initial_velocities":
            names.extend(f"c{i + 1}" for i in range(velocity_columns))
        else:
            names.append(name)
    return names + ["z", "status", "message", *METRICS] + [f"share_mode_{i}" for i in indices]


def _solve_chunk_raw(task: ChunkTask) -> tuple[pd.DataFrame, Optional[dict[str, Any]]]:
    pd = _require_pandas()
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
    z_column = np.full(n, math.nan)

    material: dict[tuple[Any, ...], tuple[float, ...]] = {}
    valid: list[int] = []
    k_rows: list[tuple[float, ...]] = []
    lengths: list[float] = []
    velocities: list[list[float]] = []
    sections: list[float] = []
    for j, requested in enumerate(task.runs):
        z = task.z
        if z is None and isinstance(requested.get("length"), Real):
            z = 2.0 * float(requested["length"]) / 3.0
        z_column[j] = math.nan if z is None else z
        try:
            params = Parameters(**requested)
        except ValidationError as exc:
            message[j] = str(exc)
            continue
        except TypeError as exc:  # pragma: no cover - keys are checked when the sweep is planned
            message[j] = f"invalid parameters: {exc}"
            continue
        c = params.initial_velocities
        valid.append(j)
        k_rows.append(_coefficients(params, material))
        lengths.append(params.length)
        velocities.append([c[i - 1] if 1 <= i <= len(c) else 0.0 for i in indices])
        sections.append(2.0 * params.length / 3.0 if task.z is None else float(task.z))

    raw: Optional[dict[str, Any]] = None
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
        )
        rows = np.asarray(valid)
        status[rows] = raw["status"]
        message[rows] = raw["message"]
        for name in metrics:
            metrics[name][rows] = raw[name]
        unstable[rows] = raw["unstable_modes"]
        nfev[rows] = raw["nfev"]
        shares[rows] = raw["max_share"]

    data: dict[str, Any] = {}
    for name in Parameters.field_names():
        if name == "initial_velocities":
            block = np.array(
                [_velocity_row(r.get(name), task.velocity_columns) for r in task.runs], dtype=float
            ).reshape(n, task.velocity_columns)
            for i in range(task.velocity_columns):
                data[f"c{i + 1}"] = block[:, i]
        elif name == "k5_variant":
            data[name] = pd.array([str(r.get(name)) for r in task.runs], dtype="str")
        else:
            data[name] = np.array([_as_float(r.get(name)) for r in task.runs], dtype=float)
    data["z"] = z_column
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
    return frame, trajectories


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


class _Progress:
    """A one-line progress bar on stderr (no dependency), updated per chunk."""

    WIDTH = 30

    def __init__(self, total: int, enabled: bool, stream: Any = None) -> None:
        self.total = max(total, 1)
        self.done = 0
        self.enabled = enabled
        self.stream = stream if stream is not None else sys.stderr
        self.start = time.perf_counter()

    def update(self, runs: int) -> None:
        self.done += runs
        if not self.enabled:
            return
        frac = min(self.done / self.total, 1.0)
        filled = int(round(frac * self.WIDTH))
        elapsed = time.perf_counter() - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        eta = (self.total - self.done) / rate if rate > 0 else math.inf
        eta_text = f", {eta:.0f} s left" if math.isfinite(eta) and self.done < self.total else ""
        self.stream.write(
            f"\rsweep [{'#' * filled}{'.' * (self.WIDTH - filled)}] {self.done}/{self.total} runs "
            f"{elapsed:.1f} s ({rate:.0f} runs/s{eta_text})  "
        )
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def _core_build() -> str:
    """A hash of the compiled core (its file), so that chunks of another build are not mixed in."""
    path = getattr(_core, "__file__", None)
    digest = hashlib.sha256(_core.__version__.encode())
    if path and os.path.exists(path):
        with open(path, "rb") as handle:
            for block in iter(lambda: handle.read(1 << 20), b""):
                digest.update(block)
    return digest.hexdigest()[:16]


def _check_count(field: str, value: Any, minimum: int, *, allow_none: bool = False) -> Optional[int]:
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValidationError(field, value, f"an integer >= {minimum}" + (" or None" if allow_none else ""))
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
    base: Parameters, grid: Optional[Mapping[str, Any]], runs: Optional[Iterable[Any]]
) -> tuple[dict[str, list[Any]], list[dict[str, Any]]]:
    if grid is not None and runs is not None:
        raise ValidationError("runs", "both grid and runs", "either a grid or an explicit list of runs")
    if runs is not None:
        if isinstance(runs, (str, bytes, Mapping)) or not isinstance(runs, Iterable):
            raise ValidationError("runs", runs, "a list of Parameters or of mappings {field: value}")
        overrides = [run_overrides(r) for r in runs]
        if not overrides:
            raise ValidationError("runs", [], "at least one run")
        axes: dict[str, list[Any]] = {}
    elif grid is not None:
        axes, overrides = expand_grid(grid)
    else:
        axes, overrides = {}, [{}]
    base_dict = base.to_dict()
    return axes, [apply_overrides(base_dict, o) for o in overrides]


def sweep(
    base_params: Union[Parameters, str, Mapping[str, Any], None] = None,
    grid: Optional[Mapping[str, Any]] = None,
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
    """Solve the Galerkin model for every parameter set of a grid (or list); one row per run.

    Parameters
    ----------
    base_params : Parameters, str or mapping, optional
        The parameters the grid varies (a preset name or a ``{field: value}`` mapping with an
        optional ``"preset"`` key are accepted); default :class:`Parameters()`.
    grid : mapping, optional
        ``{field: values}``; the runs are the Cartesian product (:mod:`drillstring.grid`:
        lists, :func:`linspace`, :func:`logspace`, ``c1``/``c2``/... for single velocities).
    runs : list of Parameters or mappings, optional
        Instead of ``grid``: explicit parameter sets (a mapping overrides fields of
        ``base_params``). An invalid set becomes a row with status ``"invalid"``.
    modes, rigid_mode : int, bool
        The basis, as in :func:`~drillstring.simulate.simulate`.
    t_end, method, rtol, atol, dt, max_steps :
        Solver options, as in :func:`~drillstring.simulate.simulate` (``rtol`` default 1e-8).
        ``max_steps`` applies to each run.
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
        resume a previous, interrupted run of the same sweep (:mod:`drillstring.sweep_store`).
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
        holds the grid axes, ``attrs["solver"]`` the solver options.

    Raises
    ------
    ValidationError
        For bad shared input (solver options, grid keys, a foreign ``out_dir``); a bad
        parameter set is a row, not an error.
    ImportError
        Without pandas (``drillstring[sweep]``), or dask for ``client`` (``drillstring[dask]``).
    """
    pd = _require_pandas()
    base = _base(base_params)
    axes, fulls = _plan(base, grid, runs)
    method, t_end_f, rtol_f, atol_f, dt_f, steps = check_solver_options(method, t_end, rtol, atol, dt, max_steps)
    samples_i = _check_count("samples", samples, 4)
    integrals = dimensionless_integrals(modes, rigid_mode)
    size = _check_count("chunk_size", chunk_size, 1)
    threads_i = _check_count("threads", threads, 1, allow_none=True)
    if z is not None:
        if isinstance(z, bool) or not isinstance(z, Real) or not math.isfinite(z):
            raise ValidationError("z", z, "a finite section position in m, or None for 2l/3")
        z = float(z)
    if not isinstance(trajectories, bool):
        raise ValidationError("trajectories", trajectories, "True or False")
    if trajectories and (out_dir is not None or client is not None):
        raise ValidationError("trajectories", True, "False with out_dir or client (trajectories stay in memory)")
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
    velocity_columns = max(
        [1] + [len(f["initial_velocities"]) for f in fulls if isinstance(f.get("initial_velocities"), (list, tuple))]
    )
    names = columns(velocity_columns, integrals.indices.tolist())
    tasks = [
        ChunkTask(i, start, tuple(fulls[start : start + size]), solver, z, velocity_columns, threads_i, trajectories)
        for i, start in enumerate(range(0, len(fulls), size))
    ]

    store = None
    if out_dir is not None:
        from .sweep_store import SweepStore

        _require_pyarrow()
        identity = {
            "format": _FORMAT,
            "drillstring_version": _core.__version__,
            "core_build": _core_build(),
            "solver": solver,
            "z": z,
            "chunk_size": size,
            "velocity_columns": velocity_columns,
            "runs": len(fulls),
        }
        digest = hashlib.sha256(json.dumps({**identity, "parameters": fulls}, sort_keys=True, default=repr).encode())
        manifest = {**identity, "fingerprint": digest.hexdigest(), "chunks": len(tasks), "axes": list(axes)}
        store = SweepStore.open(out_dir, manifest)

    frames: list[Any] = [None] * len(tasks)
    raws: list[Any] = [None] * len(tasks)
    bar = _Progress(len(fulls), sys.stderr.isatty() if progress is None else bool(progress))
    pending = []
    for task in tasks:
        frame = store.load_chunk(task.index, len(task.runs), names) if store is not None else None
        if frame is None:
            pending.append(task)
        else:
            frames[task.index] = frame
            bar.update(len(task.runs))

    def finished(task: ChunkTask, frame: Any) -> None:
        if store is not None:
            store.save_chunk(task.index, frame)
        frames[task.index] = frame
        bar.update(len(task.runs))

    try:
        if client is not None and pending:
            _run_on_dask(client, pending, finished)
        else:
            for task in pending:  # a Ctrl-C surfaces here, between chunks
                frame, raws[task.index] = _solve_chunk_raw(task)
                finished(task, frame)
    finally:
        bar.close()

    table = pd.concat(frames, ignore_index=True) if len(frames) > 1 else frames[0].reset_index(drop=True)
    if store is not None:
        store.save_results(table)
    table.attrs["axes"] = {key: values for key, values in axes.items()}
    table.attrs["solver"] = dict(solver)
    if not trajectories:
        return table
    y = np.concatenate([r["y"] for r in raws], axis=0)
    m = integrals.indices.size
    traj = SweepTrajectories(
        t=raws[0]["t"],
        theta=np.concatenate([r["theta"] for r in raws], axis=0),
        q=np.ascontiguousarray(y[:, :, :m].transpose(0, 2, 1)),
        qdot=np.ascontiguousarray(y[:, :, m:].transpose(0, 2, 1)),
        indices=integrals.indices,
    )
    return table, traj


def _run_on_dask(client: Any, tasks: list[ChunkTask], finished: Any) -> None:
    """Submit every chunk as a task and hand each result to ``finished`` as it completes."""
    distributed = _require_distributed()
    own = None
    if isinstance(client, str):
        own = client = distributed.Client(client)
    try:
        futures = {}
        for task in tasks:
            futures[client.submit(solve_chunk, task, pure=False)] = task
        try:
            for future in distributed.as_completed(list(futures)):
                finished(futures[future], future.result())
        except BaseException:
            client.cancel(list(futures))
            raise
    finally:
        if own is not None:
            own.close()
