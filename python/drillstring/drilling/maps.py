"""Stick-slip maps: the drilling system over a grid of configuration values.

:func:`drill_map` solves every combination of the values of its axes (any dotted field of the
configuration: ``top_drive.rpm``, ``bit.weight_on_bit``, ``friction.static``,
``sections[0].length``, ``top_drive.controller.type``, ...) in the Rust core
(``drillstring_core::drilling::map``) on a thread pool, and returns one row of metrics per run
(no time series: a map's memory does not depend on the duration). Each run is the base
configuration with its axis values set by path, parsed and validated in the core exactly as
:func:`~drillstring.drilling.drill` does, and solved by the same solver (its field snapshots
switched off: they do not change the series or the metrics); its metrics are those of
``metrics.json``. A value the core refuses makes that run's row ``status = "invalid"`` with the
message naming the field; the other runs go on. The base configuration of a map has
``numerics.field_interval = 0`` (a map keeps no snapshots, so their size neither refuses it nor
counts in its memory), and a map whose runs on its threads would not fit the memory budget is
refused by the core before any work (each run's series and grid times the runs solved at once).

With ``out=DIR`` the map is stored as it goes in the chunked, verified, resumable store of the
modal sweeps (:mod:`drillstring.io.sweep_store`: ``manifest.json``, ``chunks/chunk-NNNNN.parquet``
with a SHA-256 record each, one writer at a time); the same call again reuses every verified
chunk, recomputes missing or failed ones and solves only the interrupted runs of a chunk; the
whole table is written as ``map.parquet`` and ``map.csv`` at the end, with the command's
``config.toml`` and figures swapped into the folder as one set (:func:`write_map_files`). Without
``out`` the map is held in memory only.

Figures: :func:`ssi_map` (the stick-slip severity over two axes with the stick-slip boundary,
the contour SSI = 1: the bit-speed oscillation as large as its mean, where the bit starts to
stop), :func:`controller_maps` (one such panel per controller, side by side, on one colour
scale), :func:`ssi_lines` (SSI against one axis, one line per value of another). Each takes
``units="si"`` (the default) or ``"field"``: the axes and the values in the panels' titles in the
field unit of their key (:func:`axis_label`); the table stays SI.

A map of a coupled configuration (a ``[hoist]``: axes such as ``top_drive.rpm`` and
``hoist.weight_on_bit`` with ``hoist.mode = "weight_on_bit"``) also holds the coupled metrics and
the ``regime`` of each run (:data:`COUPLED_COLUMNS`), and :func:`regime_map` draws the regimes,
ROP and MSE over two axes.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import numbers
import os
import re
import warnings
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..limits import INT64_MAX, as_int, check_run_count, memory_budget
from .config import DrillConfig, _load_document, _plain
from .metrics import core_value
from .result import COUPLED_METRICS, COUPLED_REGIMES, METRICS, TEXT_METRICS
from .solve import ConfigLike, _config
from .units import axis_unit, convert, override_to_si, system_of

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = ["CONTROLLER_AXIS", "COUPLED_COLUMNS", "MAP_FILES", "METRIC_COLUMNS", "ControllerScore", "axis_label",
           "boundary_note", "controller_maps", "controller_recommendation", "drill_map", "regime_map", "ssi_lines",
           "ssi_map", "write_map_files"]

#: The axis of the controller type (one panel per controller in :func:`controller_maps`).
CONTROLLER_AXIS = "top_drive.controller.type"

#: The metric columns of a map, in order (those of ``metrics.json``, :data:`~drillstring.drilling.result.METRICS`).
METRIC_COLUMNS: tuple[str, ...] = METRICS

#: The columns a coupled map (a base configuration with a ``[hoist]``) adds after the metrics: the
#: coupled metrics of ``metrics.json`` (:data:`~drillstring.drilling.result.COUPLED_METRICS`; NaN
#: unless the run succeeded) and the ``regime`` (``"undetermined"`` unless it succeeded).
COUPLED_COLUMNS: tuple[str, ...] = COUPLED_METRICS

#: Runs per stored chunk of a map with ``out`` (default).
CHUNK_SIZE = 100

#: Solver columns after the metrics.
STAT_COLUMNS: tuple[str, ...] = ("cells", "steps", "dt", "balance_error", "courant_peak")

MapProgress = Union[bool, Callable[[int, int], Any]]

def _plain_value(value: Any, field: str) -> Any:
    """An axis value as a JSON-ready plain value (numpy scalars unwrapped)."""
    if isinstance(value, np.generic):
        value = value.item()
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        if not math.isfinite(float(value)):
            raise ValidationError(field, value, "finite numbers, strings, true/false or lists of numbers")
        return float(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain_value(v, field) for v in value]
    raise ValidationError(field, value, "numbers, strings, true/false, null or lists of numbers")


def _value_kind(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true/false"
    if isinstance(value, (int, float)):
        return "numbers"
    if isinstance(value, str):
        return "strings"
    return "lists"


def check_axis(key: str, values: Union[Sequence[Any], np.ndarray], field: str,
               config: Optional[DrillConfig] = None) -> list[Any]:
    """The values of the axis ``key`` as JSON-ready plain values, each set in ``config`` (default:
    the core's default configuration) by the core as a run of the map sets it
    (``_core.drill_config_override``, not validated: a value out of range is an ``"invalid"``
    row), so that a key not in the configuration, an index out of range or a value of the wrong
    type (``top_drive.rpm`` takes numbers, ``bit.on_bottom`` true/false, ...) is refused before
    anything is solved; and all of one kind (numbers, strings, true/false or lists, and ``None``:
    one column of the table). A number with a unit (``"5 in"``) is converted to the key's SI unit
    (:mod:`drillstring.drilling.units`), and a plain number is in the unit system of ``config``
    (:attr:`DrillConfig.units`: a field file's axes are in field units). Raises
    :class:`~drillstring.errors.ValidationError` naming ``field`` (the dotted path for a path
    error)."""
    system, chosen = (config.units, config.chosen_units()) if config is not None else ("si", {})
    plain = [_si_value(key, _plain_value(v, field), field, system, chosen) for v in values]
    base = config.to_json() if config is not None else json.dumps(_core.drill_defaults())
    # the path (malformed, an index out of range, a key through a value): the core's message as it is
    _core.drill_config_override(base, json.dumps([[key, plain[0] if plain else None]]), field, parse=False)
    for value in plain:
        try:
            _core.drill_config_override(base, json.dumps([[key, value]]), field, validate=False)
        except ValidationError as exc:
            if exc.value == "an unknown field":
                raise  # a key not in the configuration: named, the allowed keys listed
            raise ValidationError(field, value, f"a value of {key}: {exc.allowed}") from None
    kinds = sorted({_value_kind(v) for v in plain} - {"null"})
    if len(kinds) > 1:
        raise ValidationError(field, f"{key}={', '.join(json.dumps(v) for v in plain)}",
                              f"values of one kind for {key} (one column of the map), not {' and '.join(kinds)}")
    return plain


def _si_value(key: str, value: Any, field: str, system: str, chosen: Mapping[str, tuple[str, str]]) -> Any:
    """An axis value with its quantities in SI, plain numbers in the unit system ``system``; a
    bad unit named as the axis's."""
    try:
        return override_to_si(key, value, system, chosen)
    except ValidationError as exc:
        raise ValidationError(field, value, f"a value of {key}: {exc.allowed}") from None


def _axes(cfg: DrillConfig, axes: Any) -> dict[str, list[Any]]:
    if not isinstance(axes, Mapping) or not axes:
        raise ValidationError("axes", axes, "a non-empty mapping of dotted configuration keys to lists of values "
                              "(e.g. {'top_drive.rpm': [40, 80, 120]})")
    out: dict[str, list[Any]] = {}
    for path, values in axes.items():
        if not isinstance(path, str):
            raise ValidationError("axes", path, "dotted configuration keys (strings)")
        key = path.replace(" ", "")
        if key in out:
            raise ValidationError(f"axes[{path!r}]", path, "each key once")
        if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, np.ndarray)) or len(values) == 0:
            raise ValidationError(f"axes[{path!r}]", values, "a non-empty list of values")
        out[key] = check_axis(key, values, f"axes[{path!r}]", cfg)
    return out


def _map_config(config: ConfigLike) -> DrillConfig:
    """The base configuration of a map with ``numerics.field_interval = 0``: a map keeps no field
    snapshots, so their size must neither refuse it nor count in its memory."""
    if isinstance(config, DrillConfig):
        return config.with_overrides({"numerics.field_interval": 0.0}, units="si")
    source: Optional[str] = None
    if isinstance(config, (str, os.PathLike)):
        source = os.fsdecode(os.fspath(config))
        config = _load_document(source)
    if not isinstance(config, Mapping):
        return _config(config)  # refused there, naming what it is
    data = dict(_plain(dict(config)))
    numerics = data.get("numerics", {})
    if isinstance(numerics, Mapping):
        data["numerics"] = {**numerics, "field_interval": 0.0}
    return DrillConfig.from_dict(data, source=source)


def _progress_hook(
    progress: Any, total: int
) -> tuple[Optional[Callable[[float], None]], Callable[[Optional[int]], None]]:
    """The core's ``progress(finished)`` and ``close(finished)`` (the last report; ``None``: none), for
    ``progress=True`` (a tqdm bar of runs) or a callable ``f(finished, total)``."""
    if progress is None or progress is False:
        return None, lambda done: None
    if progress is True:
        from ..io.progress import bar

        tq = bar(total, "drill map", "runs")

        def report(done: float) -> None:
            tq.n = int(done)
            tq.refresh()

        def close(done: Optional[int]) -> None:
            if done is not None:
                report(done)
            tq.close()

        return report, close
    if callable(progress):
        call = progress
        return (lambda done: call(int(done), total)), (lambda done: None if done is None else call(done, total))
    raise ValidationError("progress", progress, "True, False or a callable f(finished_runs, total_runs)")


def drill_map(
    config: ConfigLike,
    axes: Mapping[str, Sequence[Any]],
    *,
    threads: Optional[int] = None,
    progress: Optional[MapProgress] = None,
    out: Optional[Union[str, os.PathLike[str]]] = None,
    chunk_size: Optional[int] = None,
    client: Any = None,
    name: Optional[str] = None,
    also_write: Optional[Callable[[pd.DataFrame, str], Any]] = None,
) -> pd.DataFrame:
    """Solves ``config`` at every combination of the ``axes`` values; one row per run.

    Parameters
    ----------
    config : DrillConfig, mapping or path of a TOML file
        The base configuration.
    axes : mapping of dotted keys to lists of values
        ``{"top_drive.rpm": [40, 80, 120], "bit.weight_on_bit": [50e3, 100e3]}``; any field of
        the configuration (``sections[1].length``, ``friction.static``,
        ``top_drive.controller.type`` with ``["pi", "soft_torque"]``, ...). The runs are the
        Cartesian product, the first axis varying slowest. ``None`` unsets an optional field;
        one number for ``well.inclination_deg`` (without a ``well.md`` axis) drops the survey
        depths, as :meth:`DrillConfig.with_overrides` does.
    threads : int, optional
        Threads of the map (default: every core), at most ``_core.MAX_THREADS``.
    progress : bool or callable, optional
        ``True``: a tqdm bar of the runs finished on stderr; a callable ``f(finished, total)``
        (about every 20 ms while runs finish). An exception it raises stops the map as Ctrl-C does.
    out : path, optional
        A directory to store the map in as it goes (see the module docstring), resumable by the
        same call; ``map.parquet`` and ``map.csv`` hold the table at the end, swapped in with
        ``also_write``'s files as one set (:func:`write_map_files`: an interruption leaves the
        earlier map's files or the new ones, never a mix). A directory holding another map
        (other configuration, axes, chunk size or core build) is refused.
    chunk_size : int, optional
        Runs per chunk with ``out`` or ``client`` (default :data:`CHUNK_SIZE`).
    client : dask.distributed.Client or str, optional
        Solve the chunks on this Dask cluster, one task per chunk (a str is a scheduler address
        to connect to); each worker solves its chunk on ``threads`` threads (default: all its
        cores). With ``out``, each chunk is stored as it comes back. The table equals the local
        one. Needs ``dask.distributed`` (``pip install '.[dask]'`` in the drillstring checkout).
    name : str, optional
        The well's name in the figures' titles (``frame.attrs["name"]``); default: the stem of
        ``config``'s file name when it is a path, else none.
    also_write : callable, optional
        With ``out``: ``f(table, directory)`` writes more files of the finished map (of
        :data:`MAP_FILES`: ``drillstring drill-map`` its ``config.toml`` and figures) into
        ``directory``, the folder being written beside ``out``; they are swapped in with the
        tables.

    Returns
    -------
    pandas.DataFrame
        Columns: the axis keys (their values), ``status`` (``"success"``, ``"invalid"`` for a
        configuration the core refuses, ``"non_finite"``, ``"interrupted"``, ``"error"``),
        ``message``, the metrics of ``metrics.json`` (:data:`METRIC_COLUMNS`: ``ssi``,
        ``stuck_fraction``, ``period_s``, ``bit_rpm_min`` ... ``breakoff_torque_Nm``; NaN unless
        the run succeeded; ``stick_slip_verdict`` ``"yes"``, ``"no"`` or ``"undetermined"``), for a
        coupled base configuration :data:`COUPLED_COLUMNS` (``rop_mean_m_per_h`` ... ``mse_mean_Pa``
        and ``regime``), and :data:`STAT_COLUMNS`. ``frame.attrs`` holds ``axes``, the base ``config``
        (:meth:`DrillConfig.to_dict`) and the well's ``name`` (or None).

    Raises
    ------
    ValidationError
        A base configuration the core refuses; empty or malformed axes, a key that is not in
        the configuration (naming it), an axis without effect in every run (``top_drive.rpm``
        under ``top_drive.mode = "measured_speed"``: its rows would all be the same; named with
        the reason); a ``client`` that is not a Dask client or address; too many
        runs (:func:`drillstring.limits.check_run_count`)
        or a map over the memory budget.
    KeyboardInterrupt
        Ctrl-C (or the exception of ``progress``): the runs under way stop within milliseconds;
        the exception carries the table so far as its ``frame`` attribute (finished rows kept,
        the others ``"interrupted"``; with ``out``, the chunks solved so far, also stored).
    """
    if threads is not None:
        threads = as_int("threads", threads, 1, _core.MAX_THREADS,
                         f"an integer in 1..={_core.MAX_THREADS} (or None for all cores)")
    if chunk_size is not None:
        chunk_size = as_int("chunk_size", chunk_size, 1, INT64_MAX, "an integer >= 1")
    cfg = _map_config(config)
    named = _axes(cfg, axes)
    runs = 1
    for values in named.values():
        runs *= len(values)
    check_run_count("axes", {k: len(v) for k, v in named.items()}, runs)
    from ..io.cluster import check_client

    check_client(client)
    if name is None and isinstance(config, (str, os.PathLike)):
        name = os.path.splitext(os.path.basename(os.fsdecode(os.fspath(config))))[0]
    report, close = _progress_hook(progress, runs)
    combos = list(itertools.product(*named.values()))
    # an axis without effect in every run refuses the whole map (the core's rule), checked once
    # here for the chunks that solve parts of it
    _core.drill_map_check_axes(cfg.to_json(), _runs_json(named, combos))
    count = None if threads is None else int(threads)
    if report is not None:
        report(0)
    if out is None and client is None:
        frame, interrupt = _solve(cfg, named, combos, count, report, 0)
    else:
        frame, interrupt = _chunked(cfg, named, combos, count, report, out, int(chunk_size or CHUNK_SIZE), client,
                                    name, also_write)
    frame.attrs["name"] = None if name is None else str(name)
    try:
        close(None if interrupt is not None else int((frame["status"] != "interrupted").sum()))
    except BaseException as exc:  # the last report's exception: the map is complete, keep it
        _attach(exc, frame)
        raise
    if interrupt is not None:
        _attach(interrupt, frame)
        raise interrupt
    return frame


def _attach(exc: BaseException, frame: pd.DataFrame) -> None:
    try:
        exc.frame = frame  # type: ignore[attr-defined]
    except AttributeError:  # pragma: no cover - exceptions normally take attributes
        pass


def _solve(cfg: DrillConfig, named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], threads: Optional[int],
           report: Optional[Callable[[float], None]], offset: int) -> tuple[pd.DataFrame, Optional[BaseException]]:
    """Solves the runs ``combos`` in one core call; the table and the exception that stopped it."""
    # no field snapshots in any run, also with a numerics.field_interval axis: the core's
    # drilling::map::run_config drops them
    hook = None if report is None else (lambda done: report(offset + done))
    raw = _core.drill_map(cfg.to_json(), _runs_json(named, combos), threads, memory_budget(), hook, check_axes=False)
    return _frame(named, combos, raw, cfg), raw.get("interrupt")


def _runs_json(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]]) -> str:
    """The runs ``combos`` of the axes ``named`` as the core's JSON list of ``[path, value]`` pairs."""
    return json.dumps([list(zip(named, combo)) for combo in combos], allow_nan=False)


def _digest(value: Any) -> str:
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=repr).encode()).hexdigest()


def _solve_map_chunk(config: dict[str, Any], named: dict[str, list[Any]], combos: list[tuple[Any, ...]],
                     threads: Optional[int]) -> pd.DataFrame:
    """One chunk of a map, solved where it runs (a module-level function: Dask workers import it)."""
    frame, interrupt = _solve(_config(config), named, combos, threads, None, 0)
    if interrupt is not None:
        raise interrupt
    return frame


@dataclasses.dataclass
class _Chunk:
    """A chunk still to solve: its position, its runs, and what the store held of it."""

    index: int
    start: int
    part: list[tuple[Any, ...]]
    plan: str
    parameters: pd.DataFrame
    stored: Optional[pd.DataFrame]
    todo: Optional[np.ndarray]   # rows of ``stored`` to solve (its interrupted runs)

    @property
    def runs(self) -> list[tuple[Any, ...]]:
        return self.part if self.todo is None else [self.part[i] for i in self.todo]

    def merge(self, solved: pd.DataFrame) -> pd.DataFrame:
        import pandas as pd

        if self.stored is None:
            solved.index = self.parameters.index
            frame = solved
        else:
            assert self.todo is not None
            solved.index = self.stored.index[self.todo]
            frame = pd.concat([self.stored.drop(index=solved.index), solved]).sort_index()
        frame.attrs = {}
        return frame


def _chunked(cfg: DrillConfig, named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], threads: Optional[int],
             report: Optional[Callable[[float], None]], out: Any, size: int, client: Any,
             name: Optional[str] = None, also_write: Optional[Callable[[pd.DataFrame, str], Any]] = None,
             ) -> tuple[pd.DataFrame, Optional[BaseException]]:
    """The map in chunks of ``size`` runs: stored in a :class:`~drillstring.io.sweep_store.SweepStore`
    in ``out`` (resumable) if given, solved locally or on the Dask cluster ``client``; a finished
    map's files (the tables, and what ``also_write`` writes) are swapped in as one set
    (:func:`write_map_files`)."""
    import contextlib

    import pandas as pd

    from ..errors import ResumeWarning
    from ..io.output import MAP_FORMAT
    from ..io.sweep_store import SweepStore, core_build

    identity = {"format": MAP_FORMAT, "drillstring_version": _core.__version__,
                "core_build": core_build(), "chunk_size": size, "runs": len(combos)}
    fingerprint = _digest({**identity, "config": cfg.to_dict(), "axes": named})
    chunks = range(0, len(combos), size)
    manifest = {**identity, "fingerprint": fingerprint, "chunks": len(chunks), "axes": list(named)}
    columns = [*named, "status", "message", *METRIC_COLUMNS, *_coupled_columns(cfg), *STAT_COLUMNS]
    frames: dict[int, pd.DataFrame] = {}
    interrupt: Optional[BaseException] = None
    recomputed: dict[int, str] = {}
    done = 0
    opened = SweepStore.open(out, manifest) if out is not None else contextlib.nullcontext()
    with opened as store:
        jobs: list[_Chunk] = []
        for index, start in enumerate(chunks):
            part = combos[start:start + size]
            plan = _digest({"fingerprint": fingerprint, "index": index, "start": start, "runs": part})
            parameters = _axis_frame(named, part, start)
            stored, reason = (None, None) if store is None else store.load_chunk(index, plan, parameters, columns)
            if reason is not None:
                recomputed[index] = reason
            todo = None
            if stored is not None:
                todo = np.flatnonzero((stored["status"] == "interrupted").to_numpy())
                if todo.size == 0:
                    frames[index] = stored
                    done += len(part)
                    continue
                done += len(part) - todo.size
            jobs.append(_Chunk(index, start, part, plan, parameters, stored, todo))
        if report is not None:
            report(done)

        def finished(job: _Chunk, solved: pd.DataFrame) -> None:
            frame = job.merge(solved)
            if store is not None:
                store.save_chunk(job.index, job.plan, frame, not bool((frame["status"] == "interrupted").any()))
            frames[job.index] = frame

        if client is not None and jobs:
            _on_dask(client, cfg, named, jobs, threads, finished, lambda n: report(n) if report is not None else None,
                     done)
        else:
            for job in jobs:
                runs = job.runs
                solved, interrupt = _solve(cfg, named, runs, threads, report, done)
                finished(job, solved)
                done += len(runs)
                if interrupt is not None:
                    break
        ordered = [frames[i] for i in sorted(frames)]
        table = pd.concat(ordered).reset_index(drop=True) if ordered else _frame(named, [], _EMPTY, cfg)
        if recomputed:
            reasons = "; ".join(f"chunk {i}: {why}" for i, why in recomputed.items())
            warnings.warn(f"resuming the drill map in {out}: {len(recomputed)} stored chunk(s) failed verification "
                          f"and are recomputed ({reasons})", ResumeWarning, stacklevel=3)
        table.attrs.update(axes={k: list(v) for k, v in named.items()}, config=cfg.to_dict(),
                           resume={"recomputed": recomputed}, name=None if name is None else str(name))
        if interrupt is None and store is not None:
            write_map_files(table, store.root, also_write)
    return table, interrupt


#: The files of a finished map in its folder (besides the store: ``manifest.json``, ``chunks/``):
#: the tables, the configuration and the figures of ``drillstring drill-map``.
MAP_FILES: tuple[str, ...] = ("map.parquet", "map.csv", "config.toml", "ssi_map.png", "regime_map.png",
                              "controllers.png", "ssi_lines.png")


def _map_owned(name: str) -> bool:
    return name in MAP_FILES


def write_map_files(table: pd.DataFrame, root: Union[str, os.PathLike[str]],
                    also_write: Optional[Callable[[pd.DataFrame, str], Any]] = None) -> None:
    """Writes a finished map's ``map.parquet`` and ``map.csv`` (and what ``also_write(table,
    directory)`` writes into ``directory``) into the map's folder ``root`` as one set: the
    folder, store included (hard links), is written beside it and swapped in
    (:func:`drillstring.io.output.replaced_folder`), so an interruption leaves the earlier map's
    :data:`MAP_FILES` or the new ones, never a mix; the store and its resume are untouched. Call
    it holding the store's lock."""
    from ..io.output import atomic_write, remove_leftovers, replaced_folder

    remove_leftovers(root)  # of an interrupted swap (the store's lock is held)
    with replaced_folder(root, owned=_map_owned, field="out") as folder:
        directory = os.fspath(folder.directory)
        atomic_write(os.path.join(directory, "map.parquet"), lambda tmp: table.to_parquet(tmp, index=False),
                     suffix=".parquet", field="out")
        atomic_write(os.path.join(directory, "map.csv"),
                     lambda tmp: table.to_csv(tmp, index=False, float_format="%.10g"), suffix=".csv", field="out")
        if also_write is not None:
            also_write(table, directory)


def _on_dask(client: Any, cfg: DrillConfig, named: Mapping[str, list[Any]], jobs: list[_Chunk],
             threads: Optional[int], finished: Callable[[_Chunk, pd.DataFrame], None],
             report: Callable[[int], None], done: int) -> None:
    """Submits every chunk as a task and hands each result to ``finished`` as it completes."""
    from ..io.cluster import require_distributed

    distributed = require_distributed()
    own = None
    if isinstance(client, str):
        own = client = distributed.Client(client)
    try:
        config, axes = cfg.to_dict(), {k: list(v) for k, v in named.items()}
        futures = {client.submit(_solve_map_chunk, config, axes, job.runs, threads, pure=False): job for job in jobs}
        try:
            for future in distributed.as_completed(list(futures)):
                job = futures[future]
                finished(job, future.result())
                done += len(job.runs)
                report(done)
        except BaseException:
            client.cancel(list(futures))
            raise
    finally:
        if own is not None:
            own.close()


_EMPTY: dict[str, Any] = {"status": [], "message": [], "metrics": {}, "stats": {}, "coupled": {}}


def _coupled_columns(cfg: DrillConfig) -> tuple[str, ...]:
    """The coupled columns of a map of ``cfg``: :data:`COUPLED_COLUMNS` for a coupled base
    configuration (a ``[hoist]``), none for a torsion-only one (its table as before)."""
    return COUPLED_COLUMNS if cfg.hoist is not None else ()


def _axis_columns(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]]) -> dict[str, Any]:
    import pandas as pd

    columns: dict[str, Any] = {}
    for i, key in enumerate(named):
        values = [combo[i] for combo in combos]
        columns[key] = values if any(isinstance(v, (list, dict)) for v in values) else pd.array(values).to_numpy()
    return columns


def _axis_frame(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], start: int) -> pd.DataFrame:
    import pandas as pd

    return pd.DataFrame(_axis_columns(named, combos), index=pd.RangeIndex(start, start + len(combos)))


def _frame(named: Mapping[str, list[Any]], combos: list[tuple[Any, ...]], raw: Mapping[str, Any],
           cfg: DrillConfig) -> pd.DataFrame:
    import pandas as pd

    columns = _axis_columns(named, combos)
    columns["status"] = list(raw["status"])
    columns["message"] = list(raw["message"])
    metrics = raw["metrics"]
    for name in METRIC_COLUMNS:
        value = core_value(metrics, name)
        if name in TEXT_METRICS:
            columns[name] = np.asarray(list(value or ()), dtype=object)
        else:
            columns[name] = np.asarray([] if value is None else value, dtype=float)
    coupled = raw.get("coupled") or {}
    for name in _coupled_columns(cfg):
        value = coupled.get(name, ())
        columns[name] = np.asarray(list(value), dtype=object) if name == "regime" else np.asarray(value, dtype=float)
    for name in STAT_COLUMNS:
        columns[name] = np.asarray(raw["stats"].get(name, []))
    frame = pd.DataFrame(columns)
    frame.attrs.update(axes={k: list(v) for k, v in named.items()}, config=cfg.to_dict())
    return frame


# --------------------------------------------------------------------------- figures

def _numeric(frame: pd.DataFrame, key: str) -> bool:
    import pandas as pd

    return key in frame.columns and pd.api.types.is_numeric_dtype(frame[key]) and not pd.api.types.is_bool_dtype(
        frame[key])


def numeric_axes(frame: pd.DataFrame) -> list[str]:
    """The axes of a map (``frame.attrs["axes"]``) with numeric values."""
    return [k for k in frame.attrs.get("axes", {}) if _numeric(frame, k)]


#: Most panels a map figure draws (one per combination of the values of the axes it does not plot).
MAX_PANELS = 48

#: Units (the schema's, as pint writes them) a figure writes with the SI prefix that keeps the
#: numbers readable (``N`` -> ``kN``, ``N*m`` -> ``kN m``, ``Pa`` -> ``GPa``): those that start
#: with newtons, pascals, joules or watts; in field units, with foot-pounds force, pounds force
#: or psi (``ft*lbf`` -> ``kft-lbf``, ``psi`` -> ``Mpsi``).
_PREFIXED = r"(N|Pa|J|W|ft\*lbf|lbf|psi)(?=$|[*/ ])"
_PREFIXES = ((1e9, "G"), (1e6, "M"), (1e3, "k"))
_NO_UNIT = ("", "1", "-", "dimensionless")
_SUPERSCRIPTS = str.maketrans({"2": "²", "3": "³", "4": "⁴"})


def _readable_unit(unit: str) -> str:
    """A pint unit as a figure writes it: ``N*m`` -> ``N m``, ``kg*m^2`` -> ``kg m²``,
    ``ft*lbf`` -> ``ft-lbf``."""
    unit = unit.replace("**", "^").replace("ft*lbf", "ft-lbf").replace("*", " ")
    return re.sub(r"\^([234])(?!\d)", lambda m: m.group(1).translate(_SUPERSCRIPTS), unit)


def _schema() -> Mapping[str, Mapping[str, Any]]:
    """The core's configuration schema (``_core.drill_config_schema()``: dotted key, ``sections[]``
    for a section's keys, -> ``type``, ``unit``, ``label``, ``default``, ``description``); empty
    with a core that has none."""
    get = getattr(_core, "drill_config_schema", None)
    return get() if callable(get) else {}


def axis_label(key: str, values: Any = (), units: str = "si") -> tuple[str, float]:
    """The label ``"quantity [unit]"`` of the configuration key ``key`` (its label and unit from
    the core's schema, :func:`_schema`; without one, the key's last name) and the factor its
    SI ``values`` are drawn at: forces, torques, pressures, energies and powers get the SI prefix
    that keeps the largest value below 1000 (``bit.weight_on_bit`` up to 200000 N:
    ``"weight on bit [kN]"``, factor 1e-3). A section's key names its section
    (``sections[1].length``: ``"length, section 2 [m]"``). With ``units="field"`` the quantity
    is in the field unit of its key (:func:`drillstring.drilling.units.field_unit`: lengths in
    ft, diameters in in, weight on bit in klbf, torques in ft-lbf or kft-lbf, psi or Mpsi), the
    factor the conversion's (:func:`drillstring.drilling.units.convert`) times the prefix's."""
    system = system_of(units, "units")
    match = re.fullmatch(r"sections\[(\d+)\]\.(.+)", key)
    generic = f"sections[].{match.group(2)}" if match else key
    entry = _schema().get(generic) or {}
    label = str(entry.get("label") or generic.rsplit(".", 1)[-1].replace("_", " "))
    if match:
        label = f"{label}, section {int(match.group(1)) + 1}"
    unit = str(entry.get("unit") or "")
    factor = 1.0
    if system != "si" and unit and entry.get("type") in ("number", "array"):
        converted, unit = convert(1.0, unit, system, key=generic)
        factor = float(converted if converted is not None else 1.0)
    finite = np.asarray([v for v in values if isinstance(v, numbers.Real) and not isinstance(v, bool)], dtype=float)
    finite = finite[np.isfinite(finite)]
    if re.match(_PREFIXED, unit) and finite.size:
        biggest = float(np.abs(finite).max()) * factor
        for size, prefix in _PREFIXES:
            if biggest >= size:
                factor, unit = factor / size, prefix + unit
                break
    return (label if unit in _NO_UNIT else f"{label} [{_readable_unit(unit)}]"), factor


def _value_text(key: str, value: Any, values: Any, units: str = "si") -> str:
    """``"label = value unit"`` of one value of an axis (the controller: ``"pi controller"``)."""
    if key == CONTROLLER_AXIS:
        return f"{value} controller"
    label, factor = axis_label(key, values, units)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        name, _, unit = label.partition(" [")
        return f"{name} = {float(value) * factor:.4g}" + (f" {unit[:-1]}" if unit else "")
    return f"{label} = {value}"


def _well_name(frame: pd.DataFrame, units: str = "si") -> str:
    """The map's well: its name (``frame.attrs["name"]``: the configuration file's stem or the
    ``name`` given to :func:`drill_map`), else the string's length (in ``units``)."""
    name = frame.attrs.get("name")
    if name:
        return str(name)
    sections = (frame.attrs.get("config") or {}).get("sections") or ()
    length = sum(float(s.get("length", 0.0)) for s in sections if isinstance(s, Mapping))
    scale, unit = axis_unit("m", units)
    return f"{length * scale:.0f} {unit} string" if length > 0 else "drilling system"


def _controller(frame: pd.DataFrame) -> Optional[str]:
    """The base configuration's controller type (None when it is an axis of the map)."""
    if CONTROLLER_AXIS in frame.attrs.get("axes", {}):
        return None
    kind = (((frame.attrs.get("config") or {}).get("top_drive") or {}).get("controller") or {}).get("type")
    return None if kind is None else str(kind)


def _map_title(frame: pd.DataFrame, what: str, units: str = "si") -> str:
    controller = _controller(frame)
    return f"{_well_name(frame, units)}: {what}" + (f", {controller} controller" if controller else "")


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
    parts = [(", ".join(_value_text(k, v, frame[k].tolist(), units) for k, v in zip(keys, values)), part)
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
    if value == "ssi":
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
        if not _numeric(frame, key):
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
    vmax = _vmax(frame["ssi"])
    (xlabel, xscale), (ylabel, yscale) = (axis_label(x, frame[x].tolist(), units),
                                          axis_label(y, frame[y].tolist(), units))
    mesh = None
    for ax, (name, part) in zip(axs, parts):
        mesh = _panel(ax, part, x, y, "ssi", vmax, (xscale, yscale))
        if name:
            ax.set_title(name, fontsize=10)
    for ax in axs[len(parts):]:
        ax.set_visible(False)
    for ax in axs[:len(parts)]:
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
    assert mesh is not None  # at least one panel
    fig.colorbar(mesh, ax=list(axs[:len(parts)]), label="stick-slip severity SSI (cyan: SSI = 1)")
    fig.suptitle(title or _map_title(frame, "stick-slip severity SSI", units))
    return fig


def ssi_map(frame: pd.DataFrame, x: str, y: str, *, title: Optional[str] = None, units: str = "si") -> Figure:
    """The stick-slip severity over the numeric axes ``x`` and ``y`` of a map (a cell per run),
    with the stick-slip boundary SSI = 1 (cyan).

    One panel per combination of the values of the map's other axes (the controller's first), so
    that no cell averages runs of different configurations; a panel without an SSI = 1 boundary
    in its range says so (``"SSI > 1 everywhere in this range"`` or ``"< 1"``). The axes are
    labelled by quantity and unit in readable magnitudes (:func:`axis_label`); the title names
    the well (``frame.attrs["name"]``) and the controller. Failed runs are blank.

    Parameters
    ----------
    frame : pandas.DataFrame
        A map (:func:`drill_map`).
    x, y : str
        Two numeric axes of the map (dotted keys).
    title : str, optional
        The figure's title instead of the default.
    units : {"si", "field"}, optional
        The unit system of the axes and the panels' titles (default ``"si"``; ``"field"``: the
        field unit of each key, :func:`axis_label`).

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
                       title or f"{_well_name(frame, units)}: stick-slip severity SSI by controller", units)


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
        part = part.groupby(x, sort=True)[["ssi", "stuck_fraction"]].mean()  # repeated values: the same run
        label = name or None
        ax1.plot(part.index.to_numpy(dtype=float) * scale, part["ssi"], marker="o", label=label)
        ax2.plot(part.index.to_numpy(dtype=float) * scale, part["stuck_fraction"], marker="o", label=label)
    ax1.axhline(1.0, color="0.5", ls="--", lw=1)
    note = boundary_note(frame["ssi"])
    if note is not None:
        _note(ax1, note)
    ax1.set_ylabel("SSI")
    ax2.set_ylabel("stuck fraction")
    ax2.set_xlabel(xlabel)
    if len(parts) > 1:
        ax1.legend(fontsize="small")
    ax1.set_title(title or _map_title(frame, "stick-slip severity", units))
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
    if "regime" not in frame.columns:
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
    rop_scale, rop_unit = axis_unit("m/h", units)
    mse_scale, mse_unit = (1e-6, "MPa") if system_of(units, "units") == "si" else axis_unit("Pa", units)
    rop_max = float(np.nanmax(frame["rop_mean_m_per_h"].to_numpy(dtype=float), initial=0.0)) * rop_scale
    mse = frame["mse_mean_Pa"].to_numpy(dtype=float) * mse_scale
    mse = mse[np.isfinite(mse)]
    mse_range = (float(mse.min()), float(mse.max())) if mse.size else (0.0, 1.0)
    for row, (name, part) in zip(axs, parts):
        ok = part["status"] == "success"
        codes = part["regime"].map({r: i for i, r in enumerate(COUPLED_REGIMES)}).astype(float).where(ok)
        seen.update(part["regime"][ok])
        xs, ys, z = _grid(part.assign(_regime=codes), x, y, "_regime")
        row[0].pcolormesh(xs * xscale, ys * yscale, z, shading="nearest", cmap=cmap, norm=norm)
        xs, ys, z = _grid(part.assign(_rop=(part["rop_mean_m_per_h"] * rop_scale).where(ok)), x, y, "_rop")
        meshes[0] = row[1].pcolormesh(xs * xscale, ys * yscale, z, shading="nearest", cmap="viridis", vmin=0.0,
                                      vmax=max(rop_max, 1e-9))
        _, _, ssi = _grid(part.assign(_ssi=part["ssi"].where(ok)), x, y, "_ssi")
        if boundary_note(ssi.compressed()) is None and xs.size > 1 and ys.size > 1:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                row[1].contour(xs * xscale, ys * yscale, ssi, levels=[1.0], colors="tab:cyan", linewidths=2.0)
        xs, ys, z = _grid(part.assign(_mse=(part["mse_mean_Pa"] * mse_scale).where(ok)), x, y, "_mse")
        meshes[1] = row[2].pcolormesh(xs * xscale, ys * yscale, np.ma.masked_invalid(z), shading="nearest",
                                      cmap="magma_r", vmin=mse_range[0], vmax=max(mse_range[1], mse_range[0] + 1e-9))
        for ax, what in zip(row, ("regime", "mean ROP", "mechanical specific energy")):
            ax.set_title(f"{what}{', ' + name if name else ''}", fontsize=10)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
    fig.colorbar(meshes[0], ax=list(axs[:, 1]), label=f"mean rate of penetration [{rop_unit}] (cyan: SSI = 1)")
    fig.colorbar(meshes[1], ax=list(axs[:, 2]), label=f"MSE of the means [{mse_unit}]")
    handles = [Patch(facecolor=REGIME_COLOURS[r], edgecolor="0.5", label=r) for r in COUPLED_REGIMES if r in seen]
    if handles:
        axs[0, 0].legend(handles=handles, fontsize="small", loc="upper left", framealpha=0.85)
    fig.suptitle(title or _map_title(frame, "coupled regime, ROP and MSE", units))
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
            if "regime" in frame.columns:
                out["regime_map.png"] = regime_map(frame, x, y, units=units)
            if CONTROLLER_AXIS in axes:
                out["controllers.png"] = controller_maps(frame, x, y, units=units)
        elif len(numeric) == 1:
            others = [k for k in axes if k != numeric[0]]
            out["ssi_lines.png"] = ssi_lines(frame, numeric[0], others[0] if others else None, units=units)
    except ValidationError as exc:
        warnings.warn(f"no map figure: {exc}", stacklevel=2)
    return out


@dataclasses.dataclass(frozen=True)
class ControllerScore:
    """One controller of a map with a ``top_drive.controller.type`` axis, over all its runs
    (every combination of the other axes' values): :func:`controller_recommendation`."""

    controller: str
    runs: int
    #: Runs that did not give a result (invalid, failed, interrupted).
    failed: int
    #: Runs with the stick-slip verdict ``yes`` (the bit stops during part of the window).
    stick_slip: int
    #: Largest and mean SSI over the runs that gave a result (NaN without any).
    worst_ssi: float
    mean_ssi: float

    def line(self) -> str:
        ok = self.runs - self.failed
        failed = f", {self.failed} failed" if self.failed else ""
        return (f"{self.controller}: stick-slip in {self.stick_slip} of {ok} runs{failed}, "
                f"SSI up to {self.worst_ssi:.3g} (mean {self.mean_ssi:.3g})")


def controller_recommendation(frame: pd.DataFrame) -> list[ControllerScore]:
    """The controllers of a map with a ``top_drive.controller.type`` axis, best first: fewest runs
    in stick-slip or without a result, then the lowest mean SSI, then the lowest largest SSI (the
    verdicts and SSI are the core's metrics of each run, counted here). Empty without that axis."""
    if CONTROLLER_AXIS not in frame.columns:
        return []
    scores = []
    for name, part in frame.groupby(CONTROLLER_AXIS, sort=False):
        ok = part[part["status"] == "success"]
        ssi = ok["ssi"].to_numpy(dtype=float)
        ssi = ssi[np.isfinite(ssi)]
        scores.append(ControllerScore(
            controller=str(name), runs=len(part), failed=len(part) - len(ok),
            stick_slip=int((ok["stick_slip_verdict"] == "yes").sum()),
            worst_ssi=float(ssi.max()) if ssi.size else math.nan,
            mean_ssi=float(ssi.mean()) if ssi.size else math.nan))
    inf = math.inf
    return sorted(scores, key=lambda s: (s.stick_slip + s.failed, s.mean_ssi if math.isfinite(s.mean_ssi) else inf,
                                         s.worst_ssi if math.isfinite(s.worst_ssi) else inf))
