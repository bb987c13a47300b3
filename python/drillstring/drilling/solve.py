"""``drill``: one run of the drilling system in the core."""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, Optional, Union

from .. import _core
from ..errors import SolveError, ValidationError
from ..io.progress import ProgressOption, SolveProgress, check_progress
from .config import DrillConfig, load_drill_config
from .result import DrillProfile, DrillResult, GridCheck, StartCheck
from .units import annotate

__all__ = ["drill", "friction_profile"]

ConfigLike = Union[DrillConfig, Mapping[str, Any], str, "os.PathLike[str]"]


def _config(config: Any) -> DrillConfig:
    if isinstance(config, DrillConfig):
        return config
    if isinstance(config, Mapping):
        return DrillConfig.from_dict(config)
    if isinstance(config, (str, os.PathLike)):
        return load_drill_config(config)
    raise ValidationError("config", type(config).__name__, "a DrillConfig, a mapping or the path of a TOML file")


def friction_profile(config: ConfigLike) -> DrillProfile:
    """The static friction profile of ``config``'s string in its well (``_core.drill_profile``):
    the limit per metre at the cell centres, its integral from the bit up, the break-off torque."""
    return DrillProfile.from_core(_core.drill_profile(_config(config).to_json()))


def drill(config: ConfigLike, *, progress: Optional[ProgressOption] = None, check: bool = True,
          check_grid: bool = False, check_start: bool = False) -> DrillResult:
    """Solves the drilling system ``config`` over ``numerics.duration`` in the core.

    Parameters
    ----------
    config : DrillConfig, mapping or path
        The configuration, a mapping of it (:meth:`DrillConfig.from_dict`) or a TOML file
        (:func:`~drillstring.drilling.load_drill_config`).
    progress : bool or callable, optional
        ``True``: a tqdm bar of the simulated time on stderr; a callable is called as
        ``f(t_reached, duration)`` (about every 20 ms while the core steps, at the start and at
        the end). Never changes the result.
    check : bool
        Raise :class:`~drillstring.errors.SolveError` (with ``.result``) when the solve stops
        early (default); ``False`` returns the partial result with its ``status``.
    check_grid : bool
        Also solve the configuration on twice the cells (about four times the work) and report
        in ``result.grid_check`` how much every metric moved (a coupled run's ROP, weight and
        torque on bit, hook load, MSE and regime too); a move beyond its tolerance
        (:data:`~drillstring.drilling.result.GRID_TOLERANCES`, the core's) is added to
        ``result.warnings``.
    check_start : bool
        A coupled run ([hoist]) only: also solve it from the other start
        (``numerics.initial_state``, ``"rest"`` and ``"steady"``: the bit law's steady drilling)
        and report in ``result.start_check`` where the two disagree (the regime, or a metric
        beyond its tolerance, with the values): a case with more than one attractor, or a window
        still in a transient. The disagreement is added to ``result.warnings``; the result is the
        configuration's own start's.

    Returns
    -------
    DrillResult
        Series, space-time fields, friction profile, metrics and energy balance.

    Raises
    ------
    ValidationError
        A configuration the core refuses (naming the dotted field).
    SolveError
        The solve ended early (``status`` and the partial ``result``), with ``check=True``.
    KeyboardInterrupt
        Ctrl-C (the core stops within a few tens of milliseconds).
    """
    cfg = _config(config)
    for name, flag in (("check", check), ("check_grid", check_grid), ("check_start", check_start)):
        if not isinstance(flag, bool):
            raise ValidationError(name, flag, "True or False")
    option = check_progress(False if progress is None else progress)
    refined_cfg = None
    if check_grid:
        refined_cells = 2 * cfg.numerics.cells
        try:
            refined_cfg = cfg.with_overrides({"numerics.cells": refined_cells}, units="si")
        except ValidationError as exc:
            raise ValidationError(
                "check_grid", f"numerics.cells = {cfg.numerics.cells}",
                f"a grid whose double ({refined_cells} cells) the core accepts: {exc}") from exc
    other_cfg = None
    if check_start:
        if cfg.hoist is None:
            raise ValidationError("check_start", "a configuration without [hoist]",
                                  "a coupled run ([hoist]): the steady start is its steady drilling")
        other = "rest" if cfg.numerics.initial_state == "steady" else "steady"
        other_cfg = cfg.with_overrides({"numerics.initial_state": other})
    result = _solve(cfg, option, check)
    if refined_cfg is not None:
        refined = _solve(refined_cfg, option, check)
        result.grid_check = GridCheck.compare(result, refined, cfg.numerics.cells, refined_cfg.numerics.cells)
        result.warnings = (*result.warnings, *result.grid_check.warnings())
    if other_cfg is not None:
        second = _solve(other_cfg, option, check)
        rest, steady = (result, second) if cfg.numerics.initial_state != "steady" else (second, result)
        result.start_check = StartCheck.compare(rest, steady)
        result.warnings = (*result.warnings, *result.start_check.warnings())
    if cfg.units != "si":  # warnings speak the configuration's units too (the SI value first)
        result.warnings = tuple(annotate(w, cfg.units) for w in result.warnings)
    if isinstance(config, (str, os.PathLike)):
        result.name = os.path.splitext(os.path.basename(os.fsdecode(os.fspath(config))))[0]
    return result


def _solve(cfg: DrillConfig, option: ProgressOption, check: bool) -> DrillResult:
    """One run of ``cfg`` (see :func:`drill`)."""
    text = cfg.to_json()
    profile = DrillProfile.from_core(_core.drill_profile(text))
    duration = cfg.numerics.duration
    with SolveProgress(option, duration, "drill") as bar:
        # the core reports the fraction of the duration done
        report = (lambda fraction: bar.report(fraction * duration)) if bar.enabled else None
        raw = _core.drill_solve(text, report)
        result = DrillResult(cfg, raw, profile)
        bar.finish(result)
    if check and not result.success:
        raise SolveError(result.status, result.message, result)
    return result
