"""Resource limits of a solve, checked before any work is done.

* The **output memory budget**: the arrays a solve returns (times, the state at every sample
  and the ``q``/``qdot`` copies made from it, 8 bytes a value) must fit :data:`MEMORY_BUDGET`
  bytes, 2 GiB by default. Set ``drillstring.limits.MEMORY_BUDGET`` or the environment variable
  ``DRILLSTRING_MEMORY_BUDGET`` (bytes, optionally with a K, M, G or T suffix, powers of 1024;
  the variable wins) to change it. A request beyond it raises
  :class:`~drillstring.errors.ValidationError` naming the field that sets the size (``samples``,
  ``t_eval``, ``dt`` for every-step output, ``nodes``) and the bytes it would need.
* **Step limits** (``max_steps``): :data:`ADAPTIVE_MAX_STEPS` step attempts for the adaptive
  methods, :data:`FIXED_MAX_STEPS` steps for the fixed-step ones. A fixed-step solve's step
  count ``ceil(t_end / dt)`` is known up front, so one needing more is refused at once (field
  ``dt``) unless ``max_steps`` is given; an adaptive solve that reaches its limit ends with status
  ``"max_steps"`` (:class:`~drillstring.errors.SolveError`).
* **Number conversion**: every number a user gives (Python API, command line, TOML) is converted
  by :func:`as_float` or :func:`as_int`. A value that is not a real number, not finite, or too
  large for a float (``10**400``) or outside an integer range (``2**63``) raises
  :class:`~drillstring.errors.ValidationError` naming the field and the allowed range, never
  ``OverflowError``.
* **Output sampling** (:func:`default_samples`, :func:`check_sampling`): the default output
  times resolve the fastest retained linear mode with :data:`SAMPLES_PER_PERIOD` samples per
  period (at least :data:`MIN_DEFAULT_SAMPLES` samples, at most :data:`DEFAULT_OUTPUT_SHARE` of
  the memory budget); an explicit request, or a default cut by that cap, that gives fewer
  samples per period issues a :class:`~drillstring.errors.SamplingWarning` saying by how much.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any, Optional

import numpy as np

from . import _core
from .errors import SamplingWarning, ValidationError

__all__ = [
    "ADAPTIVE_MAX_STEPS",
    "FIXED_MAX_STEPS",
    "INT64_MAX",
    "MEMORY_BUDGET",
    "MEMORY_BUDGET_ENV",
    "MIN_DEFAULT_SAMPLES",
    "SAMPLES_PER_PERIOD",
    "as_float",
    "as_int",
    "check_output_size",
    "check_sampling",
    "default_samples",
    "fixed_steps",
    "memory_budget",
    "output_bytes",
    "samples_to_resolve",
]

#: Default budget, in bytes, for the output arrays of one solve (2 GiB). A request whose output
#: would need more is refused before any work, naming the field that sets its size. The
#: environment variable ``DRILLSTRING_MEMORY_BUDGET`` (bytes, optionally with a K, M, G or T
#: suffix: powers of 1024) overrides it; so does assigning this constant.
MEMORY_BUDGET = 2 * 1024**3
MEMORY_BUDGET_ENV = "DRILLSTRING_MEMORY_BUDGET"
#: Default step limit of the adaptive methods (accepted + rejected steps; the core's
#: ``options::ADAPTIVE_MAX_STEPS``).
ADAPTIVE_MAX_STEPS: int = _core.ADAPTIVE_MAX_STEPS
#: Default step limit of the fixed-step methods (the core's ``options::FIXED_MAX_STEPS``). Their
#: step count (:func:`fixed_steps`) is known up front: a request needing more is refused before
#: any work unless ``max_steps`` is given.
FIXED_MAX_STEPS: int = _core.FIXED_MAX_STEPS

#: Largest integer option (a count of samples, nodes, steps, ...): what the core's 64-bit
#: integers hold.
INT64_MAX = 2**63 - 1

#: Integers with more digits than this are shown in error messages by their digit count only
#: (``repr`` of an integer beyond 4300 digits raises ``ValueError``).
_SHOWN_DIGITS = 40

_UNITS = {"": 1, "B": 1, "K": 1024, "KB": 1024, "KIB": 1024, "M": 1024**2, "MB": 1024**2, "MIB": 1024**2,
          "G": 1024**3, "GB": 1024**3, "GIB": 1024**3, "T": 1024**4, "TB": 1024**4, "TIB": 1024**4}


def _shown(value: Any) -> Any:
    """``value`` for an error message: an integer too long to print becomes a short description."""
    if isinstance(value, Integral) and not isinstance(value, bool) and abs(int(value)) >= 10**_SHOWN_DIGITS:
        magnitude = abs(int(value))
        digits = int(math.log10(magnitude)) + 1
        if 10 ** (digits - 1) > magnitude:  # log10 rounded up at a power of ten
            digits -= 1
        elif 10**digits <= magnitude:
            digits += 1
        return f"an integer of {digits} digits"
    return value


def json_ready(value: Any) -> Any:
    """A plain value (numbers, strings, booleans, None, mappings, lists, tuples) as JSON can carry
    it to the core, which checks it and names the field: numpy and other numbers as int or float;
    a non-finite float, an integer too large for a float (which JSON has no form for) and any
    other object as text (``"nan"``, ``"inf"``, its ``repr``), which the core refuses."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, Integral):
        number = int(value)
        if abs(number) < 2**63:
            return number
        try:
            return float(number)
        except OverflowError:  # too large for a float
            return "inf" if number > 0 else "-inf"
    if isinstance(value, Real):
        real = float(value)
        return real if math.isfinite(real) else repr(real)
    if isinstance(value, Mapping):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    return repr(value)


def as_float(field: str, value: Any, allowed: str) -> float:
    """``value`` as a finite float, or :class:`~drillstring.errors.ValidationError` naming
    ``field`` with ``allowed`` (bools, strings, NaN, infinities and integers too large for a float
    such as ``10**400`` are refused)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ValidationError(field, _shown(value), allowed)
    try:
        result = float(value)
    except (OverflowError, ValueError, TypeError):
        raise ValidationError(field, _shown(value), allowed) from None
    if not math.isfinite(result):
        raise ValidationError(field, value, allowed)
    return result


def as_int(field: str, value: Any, minimum: int, maximum: int = INT64_MAX, allowed: str = "") -> int:
    """``value`` as an int with ``minimum <= value <= maximum``, or
    :class:`~drillstring.errors.ValidationError` naming ``field`` (default message: "an integer,
    minimum <= field <= maximum"; bools and floats are refused)."""
    if isinstance(value, bool) or not isinstance(value, Integral) or not minimum <= int(value) <= maximum:
        top = "2**63 - 1" if maximum == INT64_MAX else str(maximum)
        raise ValidationError(field, _shown(value), allowed or f"an integer, {minimum} <= {field} <= {top}")
    return int(value)


def memory_budget() -> int:
    """The output memory budget in bytes: ``$DRILLSTRING_MEMORY_BUDGET`` if set, else
    :data:`MEMORY_BUDGET`."""
    text = os.environ.get(MEMORY_BUDGET_ENV, "").strip()
    if not text:
        return int(MEMORY_BUDGET)
    number = text.rstrip("kKmMgGtTiIbB").strip()
    unit = text[len(text.rstrip("kKmMgGtTiIbB")):].upper()
    try:
        value = float(number) * _UNITS[unit]
    except (ValueError, KeyError):
        value = float("nan")
    if not (math.isfinite(value) and value > 0):
        raise ValidationError(
            MEMORY_BUDGET_ENV, text, "a number of bytes > 0, optionally with a K, M, G or T suffix (e.g. 512M)"
        )
    return int(value)


def _human_bytes(n: float) -> str:
    for unit in ("bytes", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if n < 1024 or unit == "PiB":
            return f"{n:.0f} {unit}" if unit == "bytes" else f"{n:.4g} {unit}"
        n /= 1024
    return f"{n:.3g} PiB"  # pragma: no cover


def output_bytes(samples: int, state_dim: int) -> int:
    """Peak memory of a solve's output: the times, the core's state samples and the ``q``,
    ``qdot`` arrays made from them, 8 bytes a value."""
    return 8 * samples * (1 + 2 * state_dim)


def check_output_size(field: str, value: Any, samples: int, state_dim: int, what: str) -> None:
    """Refuses (``ValidationError`` naming ``field``) an output larger than :func:`memory_budget`."""
    need = output_bytes(samples, state_dim)
    budget = memory_budget()
    if need > budget:
        raise ValidationError(
            field,
            value,
            f"an output within the memory budget of {_human_bytes(budget)} ({MEMORY_BUDGET_ENV}): {what} "
            f"= {samples} samples of {state_dim} values would need {_human_bytes(need)} ({need} bytes)",
        )


def fixed_steps(t_end: float, dt: float) -> int:
    """The number of steps of a fixed-step method: ``ceil(t_end / dt - 1e-9)`` (at least 1;
    saturating at ``_core.MAX_STEP_COUNT``, 2^62), the core's count (``options::fixed_steps``)."""
    return _core.fixed_steps(float(t_end), float(dt))


#: Memory a planned sweep run takes before it is solved, bytes: its parameter dict, its task
#: entry and its table row (measured: ``benchmarks/sweep_throughput.py`` prints it).
PLAN_BYTES_PER_RUN = 2048


def check_run_count(field: str, value: Any, runs: int) -> None:
    """Refuses (``ValidationError`` naming ``field``) a sweep of ``runs`` runs whose plan alone,
    :data:`PLAN_BYTES_PER_RUN` bytes a run, would not fit :func:`memory_budget`; checked before
    the runs are listed."""
    need = runs * PLAN_BYTES_PER_RUN
    budget = memory_budget()
    if need > budget:
        raise ValidationError(
            field,
            value,
            f"a sweep whose {runs} runs fit the memory budget of {_human_bytes(budget)} ({MEMORY_BUDGET_ENV}): "
            f"planning them would need {_human_bytes(need)} ({PLAN_BYTES_PER_RUN} bytes a run); "
            f"at most {budget // PLAN_BYTES_PER_RUN} runs",
        )


def check_table_size(runs: int, columns: int, velocity_columns: int) -> None:
    """Refuses a sweep table of ``runs`` rows and ``columns`` columns (16 bytes a cell with
    pandas' overhead) over :func:`memory_budget`, naming ``initial_velocities`` when its
    ``velocity_columns`` are most of the columns."""
    need = 16 * runs * columns
    budget = memory_budget()
    if need > budget:
        field = "initial_velocities" if 2 * velocity_columns > columns else "grid"
        raise ValidationError(
            field,
            f"{runs} runs x {columns} columns",
            f"a table within the memory budget of {_human_bytes(budget)} ({MEMORY_BUDGET_ENV}): it would need "
            f"{_human_bytes(need)}",
        )


# --------------------------------------------------------------------------- output sampling

#: Output samples per period of the fastest retained linear mode that the default output times
#: give, and below which an explicit request is warned about (:func:`check_sampling`): a sampled
#: sinusoid then shows its peaks to within 1 - cos(pi / 20) = 1.2 % and its phase portrait is
#: smooth; an FFT of it finds the true frequency (the Nyquist limit is 2).
SAMPLES_PER_PERIOD = 20
#: The fewest output times the default gives (short runs keep smooth plots).
MIN_DEFAULT_SAMPLES = 1001
#: Share of :func:`memory_budget` the default output may take (the rest leaves room for copies
#: such as ``to_pandas``); a request beyond it must be explicit.
DEFAULT_OUTPUT_SHARE = 0.25


def samples_to_resolve(t_end: float, frequency_hz: float) -> int:
    """Uniform output times over ``0 <= t <= t_end`` giving :data:`SAMPLES_PER_PERIOD` samples
    per period of ``frequency_hz``: ``ceil(SAMPLES_PER_PERIOD * t_end * f) + 1`` (at least 2;
    saturating at 2^62)."""
    intervals = SAMPLES_PER_PERIOD * t_end * frequency_hz
    if not intervals < 2.0**62:
        return 2**62
    return max(math.ceil(intervals - 1e-9), 1) + 1


def default_samples(t_end: float, frequency_hz: float, state_dim: int) -> int:
    """The default number of uniform output times of a solve whose fastest retained linear mode
    has ``frequency_hz``: :func:`samples_to_resolve`, at least :data:`MIN_DEFAULT_SAMPLES`, and
    at most what fits :data:`DEFAULT_OUTPUT_SHARE` of :func:`memory_budget` (never fewer than
    :data:`MIN_DEFAULT_SAMPLES` for that cap: those are checked against the whole budget by the
    caller)."""
    wanted = max(MIN_DEFAULT_SAMPLES, samples_to_resolve(t_end, frequency_hz))
    cap = int(DEFAULT_OUTPUT_SHARE * memory_budget()) // output_bytes(1, state_dim)
    return min(wanted, max(cap, MIN_DEFAULT_SAMPLES))


def check_sampling(
    times: np.ndarray, t_end: float, frequency_hz: float, mode: str, request: Optional[str], *, stacklevel: int = 4
) -> None:
    """Warns (:class:`~drillstring.errors.SamplingWarning`) when the output ``times`` give fewer
    than :data:`SAMPLES_PER_PERIOD` samples per period of ``frequency_hz`` (the fastest retained
    mode, described by ``mode``) over their largest spacing. ``request`` names what set them
    (``"samples = 1001"``, ``"t_eval"``) or is ``None`` for the default cut by the memory cap.
    One or two output times ask for states, not a time history, and are never warned about."""
    if times.size < 3 or not frequency_hz > 0.0:
        return
    spacing = float(np.max(np.diff(times)))
    if spacing <= 0.0:
        return
    per_period = 1.0 / (frequency_hz * spacing)
    if per_period >= SAMPLES_PER_PERIOD:
        return
    needed = samples_to_resolve(t_end, frequency_hz)
    period = f"{SAMPLES_PER_PERIOD} samples per period"
    if request is None:
        what = (f"the default output ({times.size} samples over t_end = {t_end:g} s, the most that fit "
                f"{DEFAULT_OUTPUT_SHARE:g} of the memory budget, {MEMORY_BUDGET_ENV})")
        fix = f"pass samples = {needed} (or t_eval) or shorten t_end"
    elif request == "t_eval":
        what = f"t_eval (largest spacing {spacing:.4g} s)"
        fix = f"a spacing of at most {1.0 / (SAMPLES_PER_PERIOD * frequency_hz):.4g} s (samples >= {needed} over t_end)"
    else:
        what = f"{request} over t_end = {t_end:g} s"
        fix = f"samples >= {needed} (the default, with samples and t_eval unset, resolves it)"
    warnings.warn(
        f"under-resolved output: {what} gives {per_period:.3g} samples per period of the fastest retained "
        f"mode ({mode}, {frequency_hz:.4g} Hz); resolving it takes {period}: {fix}",
        SamplingWarning,
        stacklevel=stacklevel,
    )
