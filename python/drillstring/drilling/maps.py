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

A map of a coupled configuration (a ``[hoist]``: axes such as ``top_drive.rpm`` and
``hoist.weight_on_bit`` with ``hoist.mode = "weight_on_bit"``) also holds the coupled metrics and
the ``regime`` of each run (:data:`~drillstring.drilling.map_table.COUPLED_COLUMNS`).

The map's table is assembled by :mod:`~drillstring.drilling.map_table`, its figures are drawn by
:mod:`~drillstring.drilling.map_plots` with the labels of :mod:`~drillstring.drilling.map_labels`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import numbers
import os
import warnings
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..limits import INT64_MAX, as_int, check_run_count, memory_budget
from .config import DrillConfig, _load_document, _plain
from .map_table import METRIC_COLUMNS, STAT_COLUMNS, axis_frame, coupled_columns, map_frame
from .solve import ConfigLike, _config
from .units import override_to_si

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["CHUNK_SIZE", "MAP_FILES", "check_axis", "drill_map", "write_map_files"]

#: Runs per stored chunk of a map with ``out`` (default).
CHUNK_SIZE = 100

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
        ``message``, the metrics of ``metrics.json``
        (:data:`~drillstring.drilling.map_table.METRIC_COLUMNS`: ``ssi``, ``stuck_fraction``,
        ``period_s``, ``bit_rpm_min`` ... ``breakoff_torque_Nm``; NaN unless the run succeeded;
        ``stick_slip_verdict`` ``"yes"``, ``"no"`` or ``"undetermined"``), for a coupled base
        configuration :data:`~drillstring.drilling.map_table.COUPLED_COLUMNS`
        (``rop_mean_m_per_h`` ... ``mse_mean_Pa`` and ``regime``), and
        :data:`~drillstring.drilling.map_table.STAT_COLUMNS`. ``frame.attrs`` holds ``axes``, the
        base ``config`` (:meth:`DrillConfig.to_dict`) and the well's ``name`` (or None).

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
    return map_frame(named, combos, raw, cfg), raw.get("interrupt")


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
    columns = [*named, "status", "message", *METRIC_COLUMNS, *coupled_columns(cfg), *STAT_COLUMNS]
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
            parameters = axis_frame(named, part, start)
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
        table = pd.concat(ordered).reset_index(drop=True) if ordered else map_frame(named, [], _EMPTY, cfg)
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
    from ..io.table import frame_to_parquet

    remove_leftovers(root)  # of an interrupted swap (the store's lock is held)
    with replaced_folder(root, owned=_map_owned, field="out") as folder:
        directory = os.fspath(folder.directory)
        atomic_write(os.path.join(directory, "map.parquet"), lambda tmp: frame_to_parquet(table, tmp, index=False),
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


