"""``DrillSession``: a drilling run stepped in chunks, with values changed between them.

The core's session (``_core.DrillSession``) holds the run; ``ds.drill`` is the same session stepped
to ``numerics.duration`` in one go, so stepping a session through the duration in any chunks gives
``ds.drill``'s series bit for bit. A change made by :meth:`DrillSession.set` takes effect from the
next step and is recorded in :attr:`DrillSession.changes`; the result's ``config.toml`` carries them
as ``[[changes]]``, so ``drillstring drill`` on it repeats the run.
"""

from __future__ import annotations

import json
import math
import os
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .. import _core
from ..errors import SolveError, ValidationError
from ..limits import json_ready
from . import units as _units
from .config import DrillConfig, _plain
from .metrics import REGIME
from .result import DrillProfile, DrillResult

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    from numpy.typing import NDArray

    from .solve import ConfigLike

__all__ = ["DrillSession", "DrillSnapshot"]


class DrillSnapshot:
    """A copy of a session's whole state (:meth:`DrillSession.snapshot`); :meth:`DrillSession.restore`
    continues from it bit for bit, as often as asked. It pickles as its description (the
    configuration, the changes made and the steps taken): unpickling steps a session there again."""

    def __init__(self, core: Any, config: DrillConfig, name: Optional[str], keep_fields: bool) -> None:
        self._core = core
        self._config = config
        self._name = name
        self._keep_fields = keep_fields

    def __reduce__(self) -> tuple[Any, ...]:
        changes = [{"time": t, "key": key, "value": json.loads(value)} for t, key, value in self._core.changes()]
        return (_resumed, (self._config, json.dumps(changes, allow_nan=False), int(self._core.steps),
                           self._keep_fields, self._name))

    @property
    def t(self) -> float:
        """The time of the snapshot, s."""
        return float(self._core.t)

    def __repr__(self) -> str:
        return f"<DrillSnapshot at t = {self.t:g} s>"


def _resumed(config: DrillConfig, changes_json: str, steps: int, keep_fields: bool,
             name: Optional[str]) -> DrillSnapshot:
    """A pickled snapshot: its session stepped there again (the core's ``Session::resume``)."""
    core = _core.DrillSession.resume(config.to_json(), changes_json, steps, keep_fields)
    return DrillSnapshot(core, config, name, keep_fields)


class DrillSession:
    """A drilling run stepped in chunks, with values changed between them.

    Parameters
    ----------
    config : DrillConfig, mapping or path
        What :func:`~drillstring.drill` accepts.
    keep_fields : bool
        Record the space-time snapshots every ``numerics.field_interval`` (for
        :meth:`result`'s fields); off by default, :meth:`state` gives the fields at any time.

    Examples
    --------
    >>> s = ds.DrillSession("examples/on-bottom-3000m.toml")      # doctest: +SKIP
    >>> s.step(20.0)                                              # doctest: +SKIP
    >>> s.set("top_drive.rpm", 80.0)                              # doctest: +SKIP
    >>> s.step(40.0)                                              # doctest: +SKIP
    >>> s.result().save("out")                                    # doctest: +SKIP
    """

    def __init__(self, config: ConfigLike, *, keep_fields: bool = False) -> None:
        from .solve import _config

        if not isinstance(keep_fields, bool):
            raise ValidationError("keep_fields", keep_fields, "True or False")
        cfg = _config(config)
        self._config = cfg
        self._core = _core.DrillSession(cfg.to_json(), keep_fields)
        self._keep_fields = keep_fields
        self._name: Optional[str] = (os.path.splitext(os.path.basename(os.fsdecode(os.fspath(config))))[0]
                                     if isinstance(config, (str, os.PathLike)) else None)

    # ------------------------------------------------------------------ where it stands

    @property
    def config(self) -> DrillConfig:
        """The configuration the session started from (its changes are :attr:`changes`)."""
        return self._config

    @property
    def t(self) -> float:
        """The simulated time reached, s."""
        return float(self._core.t)

    @property
    def dt(self) -> float:
        """The time step, s."""
        return float(self._core.dt)

    @property
    def status(self) -> str:
        """``"success"`` while the session can be stepped; after a divergence or a non-finite
        state the status (``"non_finite"``, ``"out_of_memory"``) and :attr:`message`."""
        return str(self._core.status)

    @property
    def message(self) -> str:
        return str(self._core.message)

    @property
    def settable(self) -> tuple[str, ...]:
        """The keys :meth:`set` accepts (the core's list)."""
        return tuple(_core.DrillSession.settable())

    @property
    def changes(self) -> list[tuple[float, str, Any]]:
        """Every change made, ``(time it took effect from, key, value)``, in order: those of
        :meth:`set` and the configuration's ``[[changes]]`` reached."""
        return [(float(t), str(key), json.loads(value)) for t, key, value in self._core.changes()]

    def __len__(self) -> int:
        """The number of series rows so far."""
        return len(self._core)

    def __repr__(self) -> str:
        return f"<DrillSession at t = {self.t:g} s, {len(self)} rows, {self.status}>"

    # ------------------------------------------------------------------ stepping and changing

    def step(self, seconds: float) -> None:
        """Advances by whole steps to the step end nearest ``t + seconds`` (at least one step; a
        time whose nearest step end is ``numerics.duration``'s ends where :func:`~drillstring.drill`
        does). The core steps without the GIL; Ctrl-C stops it within tens of milliseconds at the
        step reached (``KeyboardInterrupt``; the session stays usable).

        Raises
        ------
        ValidationError
            ``seconds`` not a finite number >= 0.
        SolveError
            The run diverged or became non-finite (:attr:`status`, :attr:`message`), now or before.
        """
        if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not (
                math.isfinite(seconds) and seconds >= 0):
            raise ValidationError("seconds", seconds, "a finite number >= 0 (s)")
        self._check()
        self._core.step(float(seconds))
        self._check()

    def _check(self) -> None:
        if self.status != "success":
            raise SolveError(self.status, self.message, None)

    def set(self, key: str, value: Any) -> None:
        """Sets the dotted ``key`` (one of :attr:`settable`) to ``value`` from the next step,
        validated as ``--set`` validates it (in the configuration's unit system; ``"80 rpm"``
        with a unit).

        Raises
        ------
        ValidationError
            A key that cannot change during a run (naming it), or a value out of its range
            (naming the key and the range).
        """
        if not isinstance(key, str):
            raise ValidationError("key", key, "a dotted key: one of " + ", ".join(self.settable))
        key = key.strip()
        system = self._config.units
        current = self._config if system == "si" else DrillConfig._from_core(self._core.config())
        chosen = current.chosen_units([(key, value)])
        si = json_ready(_units.override_to_si(key, _plain(value), system, chosen))
        try:
            self._core.set(key, json.dumps(si, allow_nan=False))
        except ValidationError as exc:
            error = _units.field_error(exc, system)
            if error is exc:
                raise
            raise error from None

    # ------------------------------------------------------------------ reading

    def state(self) -> dict[str, Any]:
        """The state at :attr:`t` (SI): the along-string fields as arrays, ``z_m``, ``omega_rpm``,
        ``torque_Nm``, ``contact_N_per_m`` (the wall's normal force per metre), ``stuck`` (bool per
        cell), for a coupled run also ``axial_z_m``, ``axial_speed_m_per_s`` (down positive) and
        ``axial_force_N`` (compression positive); and the scalars ``t_s``, ``surface_rpm``,
        ``bit_rpm``, ``motor_torque_Nm``, ``bit_torque_Nm`` (of the last step)."""
        raw = dict(self._core.state())
        out: dict[str, Any] = {}
        for name, value in raw.items():
            if name == "stuck":
                out[name] = np.asarray(value, dtype=bool)
            elif isinstance(value, (float, int)):
                out[name] = float(value)
            else:
                out[name] = np.asarray(value, dtype=np.float64)
        return out

    def rows(self, start: int = 0) -> dict[str, NDArray[np.float64]]:
        """The series rows from index ``start`` on (``series.csv``'s columns and ``t``), cheap:
        for a display that polls the new samples (``len(session)`` rows so far)."""
        if isinstance(start, bool) or not isinstance(start, int) or start < 0:
            raise ValidationError("start", start, "an index >= 0")
        return {str(k): np.asarray(v, dtype=np.float64) for k, v in dict(self._core.rows(start)).items()}

    def result(self, window: Optional[tuple[float, float]] = None) -> DrillResult:
        """A :class:`~drillstring.drilling.DrillResult` of what was stepped: the series, the
        energy balance, the metrics over ``window`` (s; default ``metrics.window``, else the last
        half of what was stepped) and the warnings. Its :attr:`~DrillResult.config` is the
        configuration that repeats the run: ``numerics.duration`` the time reached, the changes
        as ``[[changes]]`` (and ``metrics.window`` the window asked for), so ``.save(folder)``
        writes what ``drillstring drill`` on its ``config.toml`` writes."""
        span = None
        if window is not None:
            try:
                a, b = (float(x) for x in window)
            except (TypeError, ValueError):
                raise ValidationError("window", window, "two times (start, end), s") from None
            span = (a, b)
        raw = self._core.result(span)
        profile = DrillProfile.from_core(_core.drill_profile(self._config.to_json()))
        result = DrillResult(self._replay_config(span), raw, profile)
        result.name = self._name
        return result

    def _replay_config(self, window: Optional[tuple[float, float]]) -> DrillConfig:
        """The configuration whose batch run is this session's run so far."""
        cfg = self._config
        overrides: dict[str, Any] = {
            "changes": [{"time": t, "key": key, "value": value} for t, key, value in self.changes]}
        duration = float(self._core.replay_duration)
        if duration != cfg.numerics.duration:
            overrides["numerics.duration"] = duration
        if window is not None:
            overrides["metrics.window"] = list(window)
        elif cfg.metrics.window is not None and cfg.metrics.window[1] > duration:
            overrides["metrics.window"] = None
        return cfg.with_overrides(overrides, units="si")

    def series(self) -> pd.DataFrame:
        """Everything stepped so far as :meth:`DrillResult.to_pandas` gives it: ``series.csv``'s
        columns indexed by ``t``."""
        return self.result().to_pandas()

    def metrics(self, window: Optional[tuple[float, float]] = None) -> dict[str, Any]:
        """The metrics over ``window`` as ``metrics.json`` holds them (NaN as None): the
        stick-slip metrics and, for a coupled run, under ``coupled`` its metrics and regime."""
        result = self.result(window)
        out: dict[str, Any] = result.metrics.to_dict()
        if result.coupled_metrics is not None:
            out["coupled"] = {**result.coupled_metrics, REGIME: result.coupled_regime}
        return out

    # ------------------------------------------------------------------ snapshots

    def snapshot(self) -> DrillSnapshot:
        """The whole state now (the run, its series, its changes): :meth:`restore` continues
        from it bit for bit (also after pickling, which stores how the state was reached and
        steps there again when unpickled)."""
        return DrillSnapshot(self._core.copy(), self._config, self._name, self._keep_fields)

    @classmethod
    def restore(cls, snapshot: DrillSnapshot) -> DrillSession:
        """A new session continuing from ``snapshot`` (which stays as it is)."""
        if not isinstance(snapshot, DrillSnapshot):
            raise ValidationError("snapshot", type(snapshot).__name__, "a DrillSnapshot of DrillSession.snapshot()")
        session = cls.__new__(cls)
        session._config = snapshot._config
        session._core = snapshot._core.copy()
        session._name = snapshot._name
        session._keep_fields = snapshot._keep_fields
        return session
