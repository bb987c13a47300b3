"""Time integration of the n-mode Galerkin model: :func:`simulate` and :class:`Simulation`.

The twist is expanded as ``theta(z, t) = sum_i q_i(t) cos(i pi z / l)`` (paper eq. 15) and the
modal system ``M q'' + K q + grad V(q) = 0`` (eq. 19 for one mode) is integrated in the Rust
core with the GIL released.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Callable, Literal, Optional, get_args

import numpy as np

from .. import _core, limits
from ..errors import SolveError, ValidationError
from ..io.progress import ProgressOption, SolveProgress, check_progress
from ..model.galerkin import Evaluation, ModalCoefficients, project
from ..model.parameters import Parameters
from .trajectory import SolverStats, TrajectoryResult

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import ArrayLike, NDArray

__all__ = ["METHODS", "Method", "SolverStats", "Simulation", "simulate", "check_solver_options"]

#: Integration methods: adaptive Dormand-Prince 8(5,3) and 5(4), the adaptive
#: Runge-Kutta-Nystrom pair RKN12(10) for undamped models, fixed-step classical RK4, the
#: explicit central-difference scheme of the paper's Table 2 and symplectic Stormer-Verlet;
#: ``"auto"`` lets the core choose (:func:`drillstring._core.resolve_method`).
Method = Literal["dop853", "dopri5", "rkn12", "rk4", "central", "verlet", "auto"]
METHODS: tuple[Method, ...] = get_args(Method)
FIXED_STEP_METHODS = ("rk4", "central", "verlet")
#: Methods of a sweep: a named method for every run (``"auto"`` would differ between damped
#: and undamped runs).
SWEEP_METHODS: tuple[Method, ...] = tuple(m for m in METHODS if m != "auto")
#: Methods of the PDE solver (every method applies to both).
PDE_METHODS = METHODS

#: rtol below 100 machine epsilons cannot be met by the step-size controller.
MIN_RTOL = 100 * float(np.finfo(float).eps)

def _positive(field: str, value: Any, *, allow_none: bool = False) -> Optional[float]:
    if value is None and allow_none:
        return None
    result = limits.as_float(field, value, "a finite number > 0")
    if not result > 0:
        raise ValidationError(field, value, "a finite number > 0")
    return result


def _count(field: str, value: Any, minimum: int, maximum: int = limits.INT64_MAX) -> int:
    """An integer option ``minimum <= value <= maximum`` (at most 2**63 - 1, the core's limit)."""
    return limits.as_int(field, value, minimum, maximum)


def check_solver_options(
    method: Any,
    t_end: Any,
    rtol: Any,
    atol: Any,
    dt: Any,
    max_steps: Any = None,
    methods: Sequence[Method] = METHODS,
) -> tuple[Method, float, float, float, Optional[float], Optional[int]]:
    """Validates the solver options shared by every solver; returns them normalised.

    Raises :class:`~drillstring.errors.ValidationError` naming the option and its range.
    """
    if method not in methods:
        raise ValidationError("method", method, "one of " + ", ".join(repr(m) for m in methods))
    name: Method = method
    t_end_f = _positive("t_end", t_end)
    rtol_f = _positive("rtol", rtol)
    assert t_end_f is not None and rtol_f is not None
    if rtol_f < MIN_RTOL or rtol_f >= 1.0:
        raise ValidationError("rtol", rtol, f"{MIN_RTOL:.3g} <= rtol < 1")
    atol_f = _positive("atol", atol)
    assert atol_f is not None
    dt_f = _positive("dt", dt, allow_none=True)
    if dt_f is not None and dt_f > t_end_f:
        raise ValidationError("dt", dt, f"0 < dt <= t_end = {t_end_f}")
    steps = None if max_steps is None else _count("max_steps", max_steps, 1)
    return name, t_end_f, rtol_f, atol_f, dt_f, steps


def _output_times(
    t_eval: Any,
    samples: Any,
    t_end: float,
    method: str,
    *,
    state_dim: int,
    dt: Optional[float],
    max_steps: Optional[int],
    fastest: Callable[[], tuple[float, str]],
    default_field: str = "samples",
    default_value: Any = None,
) -> Optional[NDArray[np.float64]]:
    """The output times (``None``: every step), after the resource guards.

    Before anything is allocated: a fixed-step method needing more than
    :data:`~drillstring.limits.FIXED_MAX_STEPS`
    steps without an explicit ``max_steps`` is refused (field ``dt``), and so is an output larger
    than :func:`~drillstring.limits.memory_budget` (field ``t_eval``, ``samples``, ``dt`` for every-step output, or
    ``default_field`` for the default samples, e.g. ``nodes`` for the PDE). ``fastest()`` gives
    the frequency (Hz) of the fastest mode to resolve and its description: the default samples
    resolve it (:func:`~drillstring.limits.default_samples`) and output times too sparse for it
    are warned about (:func:`~drillstring.limits.check_sampling`). It is called only once the
    output is known to fit (it is a pass over the whole state: on a huge grid the refusal comes
    first).
    """
    if method in FIXED_STEP_METHODS:
        assert dt is not None
        steps = limits.fixed_steps(t_end, dt)
        if max_steps is None and steps > limits.FIXED_MAX_STEPS:
            raise ValidationError(
                "dt",
                dt,
                f"a step giving at most max_steps = {limits.FIXED_MAX_STEPS} steps over t_end = {t_end:g} "
                f"({steps} needed; pass max_steps to allow more)",
            )
        if t_eval is None and samples is None:
            count = min(steps, limits.FIXED_MAX_STEPS if max_steps is None else max_steps) + 1
            limits.check_output_size("dt", dt, count, state_dim, f"every step of dt = {dt:g} over t_end = {t_end:g}")
            return None  # every step
    if t_eval is None:
        if samples is None:
            # never fewer than MIN_DEFAULT_SAMPLES: refused at once if even those do not fit
            limits.check_output_size(default_field, default_value, limits.MIN_DEFAULT_SAMPLES, state_dim,
                                     f"the default {limits.MIN_DEFAULT_SAMPLES} samples")
            frequency_hz, mode = fastest()
            n = limits.default_samples(t_end, frequency_hz, state_dim)
            limits.check_output_size(default_field, default_value, n, state_dim, f"the default {n} samples")
            request = None
        else:
            n = _count("samples", samples, 2)
            limits.check_output_size("samples", samples, n, state_dim, "samples")
            request = f"samples = {n}"
            frequency_hz, mode = fastest()
        uniform = np.linspace(0.0, t_end, n)
        limits.check_sampling(uniform, t_end, frequency_hz, mode, request)
        return uniform
    if isinstance(t_eval, (str, bytes)):
        raise ValidationError("t_eval", t_eval, "a 1-D array of floats")
    try:
        times = np.asarray(t_eval, dtype=np.float64)
    except OverflowError as exc:  # an int like 10**400 (its repr may be too long to print)
        raise ValidationError("t_eval", "a number too large for a float", "a 1-D array of finite floats") from exc
    except (TypeError, ValueError) as exc:
        raise ValidationError("t_eval", t_eval, "a 1-D array of floats") from exc
    if times.ndim != 1:
        raise ValidationError("t_eval", f"an array of shape {times.shape}", "a 1-D array")
    if times.size == 0:
        raise ValidationError("t_eval", "an empty array", "at least one output time")
    limits.check_output_size("t_eval", f"{times.size} times", times.size, state_dim, "len(t_eval)")
    if times.size >= 3 and np.all(np.isfinite(times)) and np.all(np.diff(times) >= 0.0):  # else refused later
        limits.check_sampling(times, t_end, *fastest(), "t_eval")
    return np.ascontiguousarray(times)


def fastest_mode(coefficients: ModalCoefficients) -> tuple[float, str]:
    """The fastest retained linear mode of a Galerkin system: ``max sqrt(|K_ii / M_ii|) / 2 pi``
    (Hz; the growth rate of a mode beyond its critical speed counts as its frequency) and
    ``"mode i"``. The default output times resolve it (:func:`~drillstring.limits.default_samples`)."""
    fastest = _core.fastest_mode(*_mass_stiffness(coefficients))
    if fastest is None:
        raise ValidationError("modes", 0, "at least one retained mode")
    k, rate = fastest
    return rate / (2 * math.pi), f"mode {int(coefficients.indices[k])}"


def _mass_stiffness(coefficients: ModalCoefficients) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return (np.ascontiguousarray(coefficients.mass, dtype=float),
            np.ascontiguousarray(coefficients.stiffness, dtype=float))


def _default_dt(coefficients: ModalCoefficients) -> float:
    """The core's default fixed step (``options::default_fixed_dt``): ``_core.DEFAULT_FIXED_DT``
    (1e-4 s), or 1/100 of the shortest linear period if that is shorter."""
    return _core.default_fixed_dt(*_mass_stiffness(coefficients))


class Simulation(TrajectoryResult):
    """The result of :func:`simulate`.

    Attributes
    ----------
    t : ndarray, shape (samples,)
        Output times, s.
    q, qdot : ndarray, shape (m, samples)
        Modal coordinates ``q_i`` (rad) and their rates (rad/s), one row per mode in
        ``indices`` order (the rigid mode i = 0 first when included).
    indices : ndarray of int
        Mode numbers ``i`` of the rows.
    params : Parameters
    coefficients : ModalCoefficients
        The Galerkin system that was integrated.
    method : str
    status : str
        ``"success"``, ``"max_steps"``, ``"step_size_underflow"`` or ``"non_finite"``
        (``"interrupted"`` exists in the core for cancelled sweeps; Ctrl-C during
        :func:`simulate` raises ``KeyboardInterrupt`` instead).
    message : str
        Explanation of a non-success status ("" on success).
    stats : SolverStats
    """

    def __init__(
        self,
        params: Parameters,
        coefficients: ModalCoefficients,
        system: Any,
        method: str,
        raw: Mapping[str, Any],
    ) -> None:
        self.coefficients = coefficients
        super().__init__(params, system, method, raw)

    @property
    def indices(self) -> NDArray[np.int64]:
        return self.coefficients.indices

    def _section_matrix(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.coefficients.basis(z)

    def _state_columns(self) -> list[str]:
        return [f"q{i}" for i in self.indices]

    def _state_dimension(self) -> tuple[str, NDArray[Any], dict[str, str], str, str]:
        attrs = {"long_name": "mode number i of the basis cos(i pi z / l)"}
        return "mode", self.indices, attrs, "q", "qdot"

    def __repr__(self) -> str:
        return (
            f"Simulation(method={self.method!r}, modes={list(self.indices)}, "
            f"samples={self.t.size}, status={self.status!r}, nfev={self.stats.nfev})"
        )


def simulate(
    params: Parameters,
    modes: int = 3,
    rigid_mode: bool = False,
    t_end: float = 1.0,
    method: Method = "dop853",
    rtol: float = 1e-9,
    atol: float = 1e-12,
    dt: Optional[float] = None,
    t_eval: Optional[ArrayLike] = None,
    *,
    samples: Optional[int] = None,
    max_steps: Optional[int] = None,
    nonlinear: bool = True,
    evaluation: Evaluation = "auto",
    check: bool = True,
    progress: ProgressOption = False,
) -> Simulation:
    """Integrates the ``modes``-mode Galerkin model of ``params`` over ``0 <= t <= t_end``.

    Parameters
    ----------
    params : Parameters
        Drill string, rotation speed ``omega`` and initial modal velocities ``C_i``.
    modes : int
        Number of elastic modes ``n`` (basis ``cos(i pi z / l)``, i = 1..n).
    rigid_mode : bool
        Also keep the uniform twist i = 0 (needed for convergence to the PDE, model notes).
    t_end : float
        End time, s.
    method : {"dop853", "dopri5", "rkn12", "rk4", "central", "verlet", "auto"}
        Adaptive DOP853 (default) or Dormand-Prince 5(4) with dense output; the adaptive
        Runge-Kutta-Nystrom pair RKN12(10) of Dormand, El-Mikkawy and Prince (1987, order 12,
        output through a degree-17 Hermite-Birkhoff interpolant of the step ends: about a
        third of DOP853's evaluations at rtol = 1e-12); fixed-step classical RK4,
        the explicit central-difference scheme of Table 2 or symplectic Stormer-Verlet.
        ``"auto"``: ``"rkn12"`` for an undamped model at ``rtol <=``
        ``drillstring._core.AUTO_RKN12_MAX_RTOL`` (a measured crossover), else ``"dop853"``;
        the result's ``method`` is the one chosen. With ``params.damping_rate > 0`` only
        "dop853", "dopri5", "rk4" (and "auto") apply ("central", "verlet" and "rkn12" advance
        ``q'' = a(q)`` only and raise ValidationError naming ``method``).
    rtol, atol : float
        Tolerances of the adaptive methods (Hairer's scaled RMS error norm).
    dt : float, optional
        Step of the fixed-step methods (shrunk to divide ``t_end`` evenly). Default: 1e-4 s, or
        1/100 of the shortest linear period if shorter.
    t_eval : array_like, optional
        Output times in ``[0, t_end]``, non-decreasing. Default: ``samples`` uniform times for
        adaptive methods, every step for fixed-step methods.
    samples : int, optional
        Number of uniform output times when ``t_eval`` is None. Default: 20 samples per period of
        the fastest retained linear mode (:func:`fastest_mode`), at least 1001, at most a quarter
        of the memory budget (:func:`~drillstring.limits.default_samples`): 1868 for 3 modes of
        the aluminium preset over 1 s. Output times giving fewer than 20 samples per period of
        that mode (three or more of them) issue a :class:`~drillstring.errors.SamplingWarning`.
    max_steps : int, optional
        Step limit: accepted + rejected steps of the adaptive methods (default 10^7), steps of the
        fixed-step ones (default 10^8; their step count is known up front and a request needing
        more is refused unless ``max_steps`` is given). A solve that reaches it ends with
        status ``"max_steps"``.
    nonlinear : bool
        ``False`` drops the cubic terms: the linearised model ``M q'' + K q = 0`` (sec. 3.3).
    evaluation : {"auto", "terms", "spectral"}
        How the core evaluates the quartic force: ``"terms"`` sums the quartic terms one by one,
        ``"spectral"`` evaluates them pseudo-spectrally (O(n log n), equal to the term sum to
        rounding), ``"auto"`` (default) takes the spectral evaluation from
        ``drillstring._core.SPECTRAL_MIN_MODES`` retained modes on, where it is faster. The two
        agree to rounding, so adaptive solves agree to their tolerance, not bit for bit.
    check : bool
        Raise :class:`~drillstring.errors.SolveError` when the solve stops early (default);
        with ``check=False`` the partial result is returned with its ``status``.
    progress : bool or callable
        ``True``: a tqdm bar of the solve time reached, on stderr; a callable is called as
        ``f(t_reached, t_end)``. The Rust core reports the time reached about every 20 ms while
        it steps, and at ``t = 0`` and when the solve ends. Never changes the result; an
        exception the callable raises stops the solve and is raised.

    Examples
    --------
    >>> import drillstring as ds
    >>> res = ds.simulate(ds.preset("aluminum"), modes=3, t_end=1.0)
    >>> theta_k = res.theta(2 * 100.0 / 3)      # twist at z_k = 2l/3
    >>> float(abs(res.q[0]).max())               # doctest: +ELLIPSIS
    0.000...
    """
    if not isinstance(params, Parameters):
        raise ValidationError("params", type(params).__name__, "a drillstring.Parameters")
    method, t_end_f, rtol_f, atol_f, dt_f, steps = check_solver_options(
        method, t_end, rtol, atol, dt, max_steps
    )
    if not isinstance(nonlinear, bool):
        raise ValidationError("nonlinear", nonlinear, "True or False")
    if not isinstance(check, bool):
        raise ValidationError("check", check, "True or False")
    progress = check_progress(progress)
    coefficients = project(params, modes=modes, rigid_mode=rigid_mode)
    if not nonlinear:
        # without its k1..k6 the model is its arrays alone (no quartic terms), evaluated as such
        coefficients = dataclasses.replace(
            coefficients,
            quartic_index=np.zeros((0, 4), dtype=np.int64),
            quartic_coef=np.zeros(0),
            coefficients=None,
        )
    if method in FIXED_STEP_METHODS and dt_f is None:
        dt_f = _default_dt(coefficients)
    times = _output_times(
        t_eval, samples, t_end_f, method, state_dim=2 * coefficients.n_modes, dt=dt_f, max_steps=steps,
        fastest=lambda: fastest_mode(coefficients),
    )
    system = coefficients.core_system(params.damping_rate, evaluation)
    method = _core.resolve_method(method, system.velocity_dependent, rtol_f)
    q0, v0 = coefficients.initial_state(params)
    with SolveProgress(progress, t_end_f, "simulate") as bar:
        raw = _core.solve_modal(
            system, q0, v0, t_end_f, times, method, rtol_f, atol_f, dt=dt_f, max_steps=steps,
            **bar.core_kwargs(),
        )
        result = Simulation(params, coefficients, system, method, raw)
        bar.finish(result)
    if check and not result.success:
        raise SolveError(result.status, result.message, result)
    return result
