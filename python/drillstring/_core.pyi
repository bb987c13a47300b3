"""Type stubs of the compiled module ``drillstring._core`` (Rust, PyO3)."""

from typing import Any, Callable, Literal, Optional, TypedDict, Union, final

import numpy as np
from numpy.typing import NDArray

__version__: str

def simd_path() -> str:
    """``"avx512+fma"``, ``"avx2+fma"`` or ``"baseline"``: the code path of the core's hot loops
    here (``DRILLSTRING_SIMD=avx2`` or ``=baseline`` pins a narrower one)."""

class SolveOutput(TypedDict):
    t: NDArray[np.float64]
    y: NDArray[np.float64]
    status: str
    message: str
    nfev: int
    naccept: int
    nreject: int
    ndense: int
    #: Energy taken out by the damping up to each sample; None without damping.
    dissipated: Optional[NDArray[np.float64]]

@final
class ModalSystem:
    """``M q'' + c M q' + K q + grad V(q) = 0`` with diagonal M, K, quartic potential terms
    and the viscous damping rate ``c >= 0`` (1/s)."""

    def __new__(
        cls,
        mass: NDArray[np.float64],
        stiffness: NDArray[np.float64],
        quartic_index: NDArray[np.int64],
        quartic_coef: NDArray[np.float64],
        damping_rate: float = 0.0,
    ) -> ModalSystem: ...
    @staticmethod
    def spectral(
        k: NDArray[np.float64],
        length: float,
        indices: NDArray[np.int64],
        damping_rate: float = 0.0,
    ) -> ModalSystem:
        """Eq. 18 with ``k = (k1, ..., k6)`` on the basis ``cos(i pi z / length)``, ``i`` in
        ``indices``, its quartic force and potential evaluated pseudo-spectrally (exact
        quadrature, O(n log n); no quartic coefficients)."""
    @property
    def evaluation(self) -> str:
        """``"terms"`` (merged monomials of the quartic coefficients) or ``"spectral"``."""
    @property
    def modes(self) -> int: ...
    @property
    def damping_rate(self) -> float: ...
    @property
    def velocity_dependent(self) -> bool:
        """Whether the forces depend on the velocity (damping); see :func:`resolve_method`."""
    def acceleration(self, q: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def quartic_gradient(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """The cubic force ``grad V(q)`` at one state ``q`` (m,)."""
    def energy(self, q: NDArray[np.float64], qdot: NDArray[np.float64]) -> NDArray[np.float64]:
        """``H = q'^T M q' / 2 + q^T K q / 2 + V(q)`` of each sample: ``q``, ``qdot`` (m, samples)."""
    def potential(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """The quartic potential ``V(q)`` of each sample: ``q`` of shape (m, samples)."""
    def quartic_share(self, q: NDArray[np.float64], energy0: float) -> float:
        """``max_t |V(q_t)| / |H(0)|`` of the samples ``q`` (m, samples) of a run whose first
        sample has the energy ``energy0``; ``nan`` when ``energy0 == 0``."""

def solve_modal(
    system: ModalSystem,
    q0: NDArray[np.float64],
    v0: NDArray[np.float64],
    t_end: float,
    t_eval: Optional[NDArray[np.float64]],
    method: str,
    rtol: float,
    atol: float,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    first_step: Optional[float] = None,
    max_step: float = ...,
    progress: Optional[Callable[[float], object]] = None,
) -> SolveOutput: ...

class SectionProperties(TypedDict):
    area: float
    polar_moment: float
    i_r: float
    i_x2y2: float
    j4: float

def section(outer_diameter: float, inner_diameter: float) -> SectionProperties:
    """Annulus ``D > 0``, ``0 <= d < D`` (m): ``A``, ``I_p``, ``I_r``, ``I_x2y2`` (eq. 8) and
    ``J4 = int r^4 dA``; ``ValidationError`` naming the diameter otherwise."""

def shear_modulus(youngs_modulus: float, poisson_ratio: float) -> float:
    """``G = E / (2 (1 + nu))``, Pa."""

def p_wave_modulus(youngs_modulus: float, poisson_ratio: float) -> float:
    """``lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu))``, Pa."""

def bar_speed(youngs_modulus: float, density: float) -> float:
    """Longitudinal bar speed ``sqrt(E / rho)``, m/s."""

class Coefficients(TypedDict):
    k1: float
    k2: float
    k3: float
    k4: float
    k5: float
    k6: float
    k6_per_omega_squared: float

def coefficients(
    youngs_modulus: float,
    density: float,
    poisson_ratio: float,
    outer_diameter: float,
    inner_diameter: float,
    omega: float,
    k5_variant: str,
    model: str,
) -> Coefficients:
    """``k1..k6`` of ``model`` (``"paper"``: eq. 17 with ``k5_variant`` ``"paper"`` or
    ``"energy"``; ``"consistent"``: ``rho I_p, G I_p, 0, 0, M J4 / 2, 0``) and ``k6 / Omega^2``;
    ``ValidationError`` naming the input, or ``parameters`` when a coefficient is not finite
    (or ``k1``, ``k2`` not ``> 0``)."""

def k6(k6_per_omega_squared: float, omega: float) -> float:
    """The rotation term ``k6 = (k6 / Omega^2) Omega^2`` (N); exactly 0 when
    ``k6_per_omega_squared == 0``."""

def check_damping_rate(damping_rate: float) -> float:
    """``damping_rate`` (1/s) if finite and ``>= 0``, else ``ValidationError`` naming it."""

def frequency_squared(
    k1: float, k2: float, k6: float, length: float, indices: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``w_i^2 = (k2 (i pi / l)^2 - k6) / k1`` (rad^2/s^2) of each mode number ``i``."""

def linear_frequencies(frequency_squared: NDArray[np.float64]) -> NDArray[np.float64]:
    """``sqrt(w^2)`` (rad/s) of each ``w^2 >= 0``, ``nan`` for a negative one."""

def wave_speed(k1: float, k2: float) -> float:
    """``sqrt(k2 / k1)`` (m/s), ``nan`` for ``k2 < 0``."""

def critical_speeds(
    k2: float, k6_per_omega_squared: float, length: float, indices: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``(i pi / l) sqrt(k2 / (k6 / Omega^2))`` (rad/s) of each mode number ``i``; ``inf`` when
    ``k6_per_omega_squared == 0``, ``nan`` for ``k2 < 0``."""

def wave_speed_squared_of_rates(
    rates: NDArray[np.float64], indices: NDArray[np.int64], length: float, omega: float
) -> float:
    """``k2 / k1`` that the rates ``K_ii / M_ii`` of a modal model with ``k6 = k1 Omega^2``
    imply (the mean over its elastic modes); ``nan`` without one."""

def modal_rates(mass: NDArray[np.float64], stiffness: NDArray[np.float64]) -> NDArray[np.float64]:
    """``K_ii / M_ii`` (1/s^2); ``ValidationError`` for a mass not finite and ``> 0`` or a
    stiffness not finite."""

def duffing(
    indices: NDArray[np.int64],
    mass: NDArray[np.float64],
    stiffness: NDArray[np.float64],
    quartic_coef: NDArray[np.float64],
    length: float,
) -> tuple[float, float, float]:
    """``(a1, a2, a3)`` of eq. 19 / corrected eq. 20 of the single-mode (``i = 1``) model;
    ``ValidationError`` naming ``modes`` for another basis."""

def modal_jacobian(
    mass: NDArray[np.float64], stiffness: NDArray[np.float64], damping_rate: float
) -> NDArray[np.float64]:
    """``[[0, I], [-M^-1 K, -c I]]`` (2m, 2m) at ``q = qdot = 0``."""

class ModalStabilityDict(TypedDict):
    rates: NDArray[np.float64]
    mode_eigenvalues_real: NDArray[np.float64]
    mode_eigenvalues_imag: NDArray[np.float64]
    eigenvalues_real: NDArray[np.float64]
    eigenvalues_imag: NDArray[np.float64]
    mode_classification: list[str]
    classification: str

def modal_stability(
    mass: NDArray[np.float64], stiffness: NDArray[np.float64], damping_rate: float
) -> ModalStabilityDict:
    """Rates, eigenvalues (per mode the root ``-c/2 + sqrt(c^2/4 - mu)``; all ``2m`` sorted by
    imaginary then real part) and classification (``"centre"``, ``"stable focus"``,
    ``"stable node"``, ``"degenerate"``, ``"saddle"``) of the equilibrium."""

def mode_shapes(
    indices: NDArray[np.int64], length: float, z: NDArray[np.float64], slope: bool = False
) -> NDArray[np.float64]:
    """``cos(i pi z / l)`` (or with ``slope`` its ``z``-derivative) as a (len(z), len(indices))
    array."""

PDE_MAX_NODES: int
"""Largest grid of :class:`PdeSystem`, nodes."""

@final
class PdeSystem:
    """The torsion PDE on ``nodes`` grid points ``z_j = j l / (nodes - 1)`` (lumped-mass linear
    finite elements; the discrete energy ``H_h`` is conserved by the semi-discrete system)."""

    def __new__(
        cls,
        k1: float,
        k2: float,
        k3: float,
        k4: float,
        k5: float,
        k6: float,
        length: float,
        nodes: int,
        damping_rate: float = 0.0,
    ) -> PdeSystem: ...
    @property
    def nodes(self) -> int: ...
    @property
    def damping_rate(self) -> float: ...
    @property
    def velocity_dependent(self) -> bool:
        """Whether the forces depend on the velocity (damping); see :func:`resolve_method`."""
    @property
    def length(self) -> float: ...
    @property
    def spacing(self) -> float: ...
    @property
    def coefficients(self) -> tuple[float, float, float, float, float, float]: ...
    @property
    def z(self) -> NDArray[np.float64]: ...
    @property
    def weights(self) -> NDArray[np.float64]: ...
    def acceleration(self, q: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def energy(self, q: NDArray[np.float64], qdot: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def initial_velocity_from_modes(self, c: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def linear_frequencies_squared(self, count: int) -> NDArray[np.float64]: ...
    def default_dt(self) -> float:
        """The default step of the fixed-step methods: :data:`PDE_CFL_SHARE` of the CFL limit
        ``h / c``, ``c = sqrt(k2 / k1)``, s."""
    def fastest_mode(self, twist: NDArray[np.float64], velocity: NDArray[np.float64]) -> tuple[int, float]:
        """``(i, w_i in rad/s)``: the highest cosine mode of the nodal ``twist`` and ``velocity``
        (twist amplitude times ``w_i``, or velocity amplitude, at least
        :data:`PDE_MODE_CONTENT_SHARE` of the largest), at least :data:`PDE_MIN_RESOLVED_MODES`
        and at most ``nodes - 1``; ``w_i`` the continuum rate ``sqrt(|(k2 (i pi/l)^2 - k6)/k1|)``.
        ``ValidationError`` for fields of another length than ``nodes``."""

PDE_CFL_SHARE: float
"""The default fixed step of a PDE solve is this share of the CFL limit ``h / c``."""
PDE_MIN_RESOLVED_MODES: int
"""The default output times of a PDE solve resolve at least this many modes."""
PDE_MODE_CONTENT_SHARE: float
"""A cosine mode of the initial state counts when its amplitude is this share of the largest."""

def solve_pde(
    system: PdeSystem,
    q0: NDArray[np.float64],
    v0: NDArray[np.float64],
    t_end: float,
    t_eval: Optional[NDArray[np.float64]],
    method: str,
    rtol: float,
    atol: float,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    first_step: Optional[float] = None,
    max_step: float = ...,
    progress: Optional[Callable[[float], object]] = None,
) -> SolveOutput: ...

class BatchOutput(TypedDict, total=False):
    status: list[str]
    message: list[str]
    max_theta: NDArray[np.float64]
    rms_theta: NDArray[np.float64]
    dominant_frequency_hz: NDArray[np.float64]
    energy_drift: NDArray[np.float64]
    unstable_modes: NDArray[np.int64]
    nfev: NDArray[np.int64]
    max_share: NDArray[np.float64]
    interrupt: Optional[BaseException]
    t: NDArray[np.float64]
    y: NDArray[np.float64]
    theta: NDArray[np.float64]

def batch_solve(
    k: NDArray[np.float64],
    length: NDArray[np.float64],
    initial_velocities: NDArray[np.float64],
    z: NDArray[np.float64],
    indices: NDArray[np.int64],
    quartic_index: NDArray[np.int64],
    cos4: NDArray[np.float64],
    mixed: NDArray[np.float64],
    sin4: NDArray[np.float64],
    t_end: float,
    samples: int,
    method: str,
    rtol: float,
    atol: float,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    first_step: Optional[float] = None,
    max_step: float = ...,
    keep_trajectories: bool = False,
    threads: Optional[int] = None,
    memory_budget: Optional[int] = None,
    damping_rate: Optional[NDArray[np.float64]] = None,
) -> BatchOutput:
    """Solve R runs of one Galerkin basis in parallel (GIL released) on a thread pool made for
    this call; one entry per run in every column (``unstable_modes`` -1 for an invalid run;
    ``t``, ``y`` (R, S, 2m), ``theta`` (R, S) only with ``keep_trajectories``).
    ``damping_rate`` (R,): each run's viscous damping rate (None: undamped); with damping
    ``energy_drift`` is the error of the energy balance ``H + dissipated - H(0)``.

    Ctrl-C stops the runs under way within tens of ms: the result is still returned, the runs
    that did not finish have status ``"interrupted"``, and ``interrupt`` holds the exception to
    raise (None otherwise).

    Raises
    ------
    ValidationError
        ``threads`` outside ``1..=MAX_THREADS``, a batch whose memory estimate exceeds
        ``memory_budget`` bytes (field ``samples``), or other bad shared options.
    """
    ...

#: Largest ``threads`` of a batch solve.
MAX_THREADS: int

class BatchPlan(TypedDict):
    threads: int
    bytes: int

def batch_plan(
    modes: int,
    samples: int,
    runs: int,
    threads: Optional[int] = None,
    keep_trajectories: bool = False,
    memory_budget: Optional[int] = None,
) -> BatchPlan:
    """Check a planned batch before any work: the thread count it would use (every core for
    None) and its peak memory estimate in bytes.

    Raises
    ------
    ValidationError
        ``threads`` outside ``1..=MAX_THREADS``; ``samples`` when the estimate exceeds
        ``memory_budget`` bytes (or ``samples`` is not an integer the core can hold).
    """
    ...

class IntegralArrays(TypedDict):
    indices: NDArray[np.int64]
    quartic_index: NDArray[np.int64]
    cos4: NDArray[np.float64]
    mixed: NDArray[np.float64]
    sin4: NDArray[np.float64]

def galerkin_integrals(modes: int, rigid_mode: bool) -> IntegralArrays:
    """The exact dimensionless quartic integrals of the free-end basis ``cos(i pi s)``
    (``drillstring.model.galerkin.GalerkinIntegrals``), generated in the core.

    Raises
    ------
    ValidationError
        ``modes`` outside ``1..=GALERKIN_MAX_MODES``.
    """

GALERKIN_MAX_MODES: int
SPECTRAL_MIN_MODES: int

def resolve_evaluation(evaluation: str, modes: int) -> Literal["terms", "spectral"]:
    """The quartic evaluation that ``evaluation`` (``"auto"``, ``"terms"`` or ``"spectral"``)
    means for ``modes`` retained modes: ``"auto"`` is ``"spectral"`` from
    :data:`SPECTRAL_MIN_MODES` on, else ``"terms"``.

    Raises
    ------
    ValidationError
        For another name (field ``evaluation``).
    """

AUTO_RKN12_MAX_RTOL: float

def resolve_method(
    method: str, velocity_dependent: bool, rtol: float
) -> Literal["dop853", "dopri5", "rkn12", "rk4", "central", "verlet"]:
    """The integration method ``method`` selects: a method name as given, or for ``"auto"``
    ``"rkn12"`` when the forces do not depend on the velocity and
    ``rtol <= AUTO_RKN12_MAX_RTOL``, else ``"dop853"``.

    >>> from drillstring import _core
    >>> _core.resolve_method("auto", False, 1e-12), _core.resolve_method("auto", True, 1e-12)
    ('rkn12', 'dop853')

    Raises
    ------
    ValidationError
        For another name (field ``method``).
    """

class ScaledSystem(TypedDict):
    mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    quartic_coef: NDArray[np.float64]

def scale_integrals(
    k: NDArray[np.float64],
    length: float,
    indices: NDArray[np.int64],
    quartic_index: NDArray[np.int64],
    cos4: NDArray[np.float64],
    mixed: NDArray[np.float64],
    sin4: NDArray[np.float64],
) -> ScaledSystem:
    """The modal system of a Galerkin model (a sweep run, or :func:`drillstring.model.galerkin.project`):
    the dimensionless integrals scaled by k1..k6 and l.

    Raises
    ------
    ValidationError
        Bad integrals, ``k`` not finite, ``k1 <= 0``, ``length <= 0``, or a mass, stiffness
        or quartic coefficient of the result not finite.
    """
    ...

SPECTRAL_PAD: int
"""Default zero-padding factor of :func:`spectral_peaks`."""
PEAK_THRESHOLD: float
"""Default relative threshold of :func:`spectral_peaks`."""

def spectral_peaks(
    x: NDArray[np.float64], dt: float, count: int, pad: int, threshold: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``count`` strongest peaks of the Hann-windowed, ``pad``-times zero-padded spectrum of
    the record ``x`` sampled every ``dt`` s, strongest first: ``(frequencies in Hz, sine
    amplitudes)``. Empty for fewer than 4 samples, a non-finite record or ``dt``, or a spectrum
    without a peak (the same peaks as a sweep's ``dominant_frequency_hz``, the first one).

    Raises
    ------
    ValidationError
        ``count`` or ``pad`` not an integer >= 1, or ``len(x) * pad`` too large.
    """
    ...

def energy_drift(energy: NDArray[np.float64], dissipated: Optional[NDArray[np.float64]] = None) -> float:
    """``max |H + D - H(0)| / |H(0)|`` of the energies of the samples and the energies the damping
    took out up to each (None undamped); 0 when ``H(0) = 0`` or without samples, NaN when a term
    is NaN (a sweep's ``energy_drift``).

    Raises
    ------
    ValidationError
        ``dissipated`` not of the length of ``energy``.
    """
    ...

def modal_energies(
    mass: NDArray[np.float64], stiffness: NDArray[np.float64], q: NDArray[np.float64], qdot: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The quadratic energy ``(M_i qdot_i^2 + K_i q_i^2) / 2`` of each mode (rows) at each sample
    (columns), shape (m, samples) like ``q`` and ``qdot`` (the terms of a sweep's modal shares).

    Raises
    ------
    ValidationError
        ``q`` and ``qdot`` not of equal shape (m, samples), ``stiffness`` not of length m.
    """
    ...

STICK_SPEED: float
"""Default stick threshold speed of :func:`stick_slip_metrics`, rad/s."""

STICK_SLIP_CRITERION: str
"""The criterion of the three-way stick-slip verdict (``verdict``: yes, no, undetermined)."""

COUPLED_REGIME_CRITERION: str
"""The criterion of a coupled run's regime (``drilling::axial::regime``)."""

COUPLED_REGIMES: list[str]
"""The coupled regimes' names: smooth drilling, stick-slip, bit bounce, stick-slip and bit bounce,
off bottom, undetermined."""

StickSlipDict = dict[str, Any]
"""Stick-slip metrics by the names of :func:`drill_outputs` (those with ``stick_slip``: float, bool,
int or str as their ``kind``; NaN where undefined) and ``warnings`` (list of str)."""

def stick_slip_metrics(
    t: NDArray[np.float64],
    omega_bit: NDArray[np.float64],
    motor_torque: Optional[NDArray[np.float64]] = None,
    *,
    window: Optional[tuple[float, float]] = None,
    stick_speed: float = ...,
) -> StickSlipDict:
    """Stick-slip metrics of the bit speed ``omega_bit`` (rad/s) and optionally the motor torque
    sampled at the strictly increasing times ``t`` over the samples with
    ``t_start <= t <= t_end`` (``window``; None: all): severity ``(max - min) / (2 |mean|)``
    (NaN for a zero mean), the time fraction with ``|omega_bit| <= stick_speed``, bit rpm
    min / max / time-weighted mean, motor torque min / max and cycle period (mean interval
    between upward crossings of its time-weighted mean, one per cycle: a crossing within 0.6
    periods of the strongest spectral peak after the last one counted does not count; NaN with
    fewer than two cycles or without a torque series).

    Raises
    ------
    ValidationError
        ``t`` not finite and strictly increasing (or fewer than 2 samples), ``omega_bit`` or
        ``motor_torque`` not finite or of another length, ``window`` not ``t_start < t_end`` or
        holding fewer than 2 samples, ``stick_speed`` not finite and >= 0.
    """
    ...

def break_off_torque(depth: NDArray[np.float64], limit: NDArray[np.float64]) -> float:
    """The static break-off torque of a well, N m: the trapezoidal integral of the friction
    limit per metre ``limit`` (N m/m) over the strictly increasing measured depths ``depth`` (m).

    Raises
    ------
    ValidationError
        ``depth`` not finite and strictly increasing (or fewer than 2 samples), ``limit`` not
        finite and >= 0 or of another length.
    """
    ...

# --- Signal metrics of a response (drillstring_core::metrics::signal) ---

BOUNDED_GROWTH: float
"""Default largest :func:`amplitude_growth` that :func:`is_bounded` accepts."""
PHASE_FILL_BINS: int
"""Default cells per axis of the grid of :func:`phase_fill`."""

def crossing_phase(t: NDArray[np.float64], x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(times, phases)`` of the zero crossings of ``x(t)`` (``k pi`` at the ``k``-th, linear
    between samples), each led by ``t[0]`` and the phase extrapolated there from the first half
    period. ``ValidationError`` (field ``x``): fewer than two crossings, another length than ``t``."""

def phase_shift(
    t: NDArray[np.float64], x_ref: NDArray[np.float64], x: NDArray[np.float64], at: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The accumulated phase (rad) of ``x`` minus that of ``x_ref`` at each time of ``at``
    (:func:`crossing_phase`, linear between crossings, the last half period beyond them)."""

def amplitude_growth(x: NDArray[np.float64]) -> float:
    """``max |x|`` over the last half of the record over that of the first half (``inf`` with a
    non-finite sample or a zero first half, NaN when both are zero). ``ValidationError``: fewer
    than 2 samples."""

def is_bounded(x: NDArray[np.float64], factor: float = ..., limit: Optional[float] = None) -> bool:
    """Finite, :func:`amplitude_growth` ``<= factor`` (default :data:`BOUNDED_GROWTH`) and
    ``max |x| <= limit`` when given."""

def modulation_depth(x: NDArray[np.float64]) -> float:
    """``1 - min/max`` of the half-cycle peaks of each sign (the larger of the two); NaN with
    fewer than two complete half cycles of each sign."""

def hull_area(x: NDArray[np.float64], y: NDArray[np.float64]) -> float:
    """Area of the convex hull of the points ``(x_k, y_k)``. ``ValidationError``: other lengths."""

def phase_fill(x: NDArray[np.float64], y: NDArray[np.float64], bins: Optional[int] = None) -> float:
    """Share of the cells of a ``bins x bins`` grid (None: :data:`PHASE_FILL_BINS`) over the
    trajectory's convex hull that it passes through. ``ValidationError``: fewer than 3 samples
    or other lengths (field ``x``), ``bins`` not an integer >= 1."""

def ellipk(m: float) -> float:
    """The complete elliptic integral of the first kind ``K(m)``. ``ValidationError``: ``m >= 1``."""

def duffing_amplitude(omega2: float, beta: float, velocity: float) -> float:
    """The turning point of ``x'' + omega2 x + beta x^3 = 0`` started at ``x = 0``,
    ``x' = velocity``. ``ValidationError``: above the separatrix of a softening oscillator."""

def duffing_frequency(omega2: float, beta: float, amplitude: float) -> float:
    """The exact frequency (Hz) of ``x'' + omega2 x + beta x^3 = 0`` at amplitude ``amplitude``.
    ``ValidationError``: ``omega2 + beta A^2 <= 0``."""

# --- Defaults and limits of a solve (drillstring_core::options, model::default_section) ---

ADAPTIVE_MAX_STEPS: int
"""Default step limit of the adaptive methods (accepted + rejected steps)."""
FIXED_MAX_STEPS: int
"""Default step limit of the fixed-step methods."""
MAX_STEP_COUNT: int
"""The largest step count :func:`fixed_steps` reports (2^62)."""
DEFAULT_FIXED_DT: float
"""Default step of the fixed-step methods on a modal system, s (unless the fastest mode asks
for a shorter one)."""
STEPS_PER_PERIOD: float
"""Steps per period of the fastest linear mode that the default fixed step gives at least."""

def fixed_steps(span: float, dt: float) -> int:
    """Steps of a fixed-step method over ``span``: ``ceil(span / dt - 1e-9)``, at least 1,
    saturating at :data:`MAX_STEP_COUNT`."""

def fastest_mode(mass: NDArray[np.float64], stiffness: NDArray[np.float64]) -> Optional[tuple[int, float]]:
    """``(index, sqrt(|K_i / M_i|))`` of the fastest linear mode (the first of equals); None
    without modes."""

def default_fixed_dt(mass: NDArray[np.float64], stiffness: NDArray[np.float64]) -> float:
    """:data:`DEFAULT_FIXED_DT`, or ``1 /`` :data:`STEPS_PER_PERIOD` of the shortest linear
    period ``2 pi / max sqrt(|K_i / M_i|)`` if that is shorter, s."""

def default_section(length: float) -> float:
    """The section the paper reports its twist at, ``z_k = 2 l / 3`` (m)."""

# --- The drilling system (issue #13): configuration as JSON, see /work/drill-contract.md ---

def drill_defaults() -> dict[str, Any]:
    """The default drilling configuration as a new dict of JSON values (what ``json.loads`` of
    its JSON gives; ``sections`` holds one template section; ``length``, ``outer_diameter`` and
    ``inner_diameter`` of each section are required)."""

def drill_config_override(
    config_json: str, overrides_json: str, field: str = "overrides", validate: bool = True, parse: bool = True
) -> dict[str, Any]:
    """The configuration ``config_json`` with ``overrides_json`` (a JSON list of
    ``[dotted path, value]`` pairs: ``top_drive.rpm``, ``sections[1].length``, a table such as
    ``top_drive.controller`` merged into it, ``null`` for None) set in order, parsed and (with
    ``validate``) validated, as JSON with every default filled in. One number for
    ``well.inclination_deg`` without a ``well.md`` override drops the survey depths. Without
    ``parse``: the configuration with the values set, as JSON (only the paths checked).

    Raises
    ------
    ValidationError
        ``field`` for a malformed path or list; otherwise naming the dotted field: an index out
        of range, a key through a value that is not a table, an unknown key (the allowed ones
        listed), a wrong type, a value out of range (with ``validate``).
    """

class ConfigKeyDoc(TypedDict):
    #: "number", "integer", "string", "boolean", "array" or "table".
    type: str
    #: The SI unit as pint parses it ("m", "N*m", "kg/m^3", "deg/(30 m)", "" dimensionless; a list
    #: of numbers: its entries' unit); None for what is not a number.
    unit: Optional[str]
    #: A short name of the quantity, for axes ("weight on bit").
    label: str
    #: The default as a JSON value; None when required, computed (see the description) or a table.
    default: Any
    #: What the key means, its allowed range in words, what null means.
    description: str

def drill_config_schema() -> dict[str, ConfigKeyDoc]:
    """The reference of the drilling configuration: every key by dotted path
    (``sections[].outer_diameter``, ``top_drive.controller.kp``; ``[]`` any index of a list,
    ``top_drive.steps[][0]`` an entry of each pair), sorted, each with exactly ``type``, ``unit``,
    ``label``, ``default`` and ``description`` (derived from the configuration structs, their doc
    comments and unit attributes)."""

def parameters_defaults() -> dict[str, Any]:
    """The paper model's default parameters as JSON (Table 1 of the paper, aluminium reference,
    ``initial_velocities`` ``[0.1, 0.05, 0.02]``): the fields of :class:`drillstring.Parameters`."""

def parameters_validate(params_json: str) -> dict[str, Any]:
    """The paper model's parameters ``params_json`` (a JSON object of some of the fields)
    validated, every default filled in, as JSON.

    Raises
    ------
    ValidationError
        naming the field (``length``, ``initial_velocities[2]``) of an unknown key, a value of the
        wrong type or out of range.
    """

def drill_validate(config_json: str) -> dict[str, Any]:
    """The configuration with every default filled in, as a dict of JSON values.

    Raises
    ------
    ValidationError
        naming the dotted field (``sections[1].outer_diameter``, ``top_drive.controller.kp``)
        of an unknown key, a wrong type, a missing required value or a value out of range,
        or ``numerics.output_interval`` / ``numerics.field_interval`` when the outputs would
        exceed the memory limit (512 MiB).
    """

def well_trajectory(config_json: str) -> dict[str, NDArray[np.float64]]:
    """The survey stations of a drilling configuration and their minimum-curvature trajectory:
    ``md`` (m), ``inc_deg``, ``azi_deg``, ``north``, ``east``, ``tvd`` (m) and
    ``dls_deg_per_30m`` (of the interval ending at each station).

    Raises
    ------
    ValidationError
        naming the field of an invalid configuration or survey (a survey file: its row and column).
    """

def well_torque_drag(config_json: str) -> dict[str, Any]:
    """The static soft-string torque and drag of a drilling configuration's string in its well:
    ``hook_load_pickup_N``, ``hook_load_slackoff_N``, ``hook_load_rotating_N``,
    ``hook_load_rotating_on_bottom_N``, ``surface_torque_off_bottom_Nm``,
    ``surface_torque_on_bottom_Nm``, ``max_normal_force_N_per_m``, ``max_normal_force_md``,
    ``max_normal_force_operation``, ``hook_load_sliding_N``, the buckling, lock-up and limits
    (``buckling_evaluated``, ``first_buckling``, ``lockup``, ``max_set_down_N``,
    ``max_weight_on_bit_N``, ``max_utilisation``, ..., ``closest_limit``); ``profiles`` (per
    operation ``pickup``, ``slackoff``, ``rotating``, ``rotating_on_bottom``, ``sliding``:
    ``md``, ``tension_N``, ``torque_Nm``, ``normal_force_N_per_m``, ``side_force_per_joint_N``,
    ``sinusoidal_buckling_load_N``, ``helical_buckling_load_N``, ``buckling``, ``utilisation``)
    and ``broomstick`` (``depth_m``, ``friction_factors``, and the hook loads ``pickup``,
    ``slackoff``, ``rotating`` (N) and the surface torque ``torque_rotating`` (N m) as arrays
    ``[factor, depth]``).

    Raises
    ------
    ValidationError
        naming the field of an invalid configuration or survey.
    """

def well_implied_friction(config_json: str, depths: list[float], operations: list[str], hook_loads: list[float],
                          torques: list[float]) -> dict[str, Any]:
    """For each measured point (bit depth m, operation name of the profiles, hook load N and
    surface torque N m, NaN where not measured), the uniform friction factor in [0, 1] that
    reproduces it: ``friction_factor`` (array, NaN where none does) and ``reason`` (list of
    str, empty where one does).

    Raises
    ------
    ValidationError
        naming the field of an invalid configuration or an unknown operation.
    """

class DrillProfile(TypedDict):
    #: Cell centres (measured depth from the top), m.
    z: NDArray[np.float64]
    #: Static friction limit per metre at the cell centres, N m/m.
    limit_per_m: NDArray[np.float64]
    #: Static friction torque of the string below each cell centre (from the bit up), N m.
    cumulative: NDArray[np.float64]
    #: Integral of the limit over the string (refined quadrature), N m.
    breakoff_torque: float
    #: The bit's static torque W r mu_s on bottom (0 off bottom), N m.
    bit_static_torque: float
    #: breakoff_torque + bit_static_torque: the torque the motor must exceed to break free, N m.
    static_torque: float
    #: cumulative + bit_static_torque: the static torque the string holds at each cell centre, N m.
    holding: NDArray[np.float64]
    #: The well at the cell centres: inclination, azimuth (degrees), TVD (m), dogleg severity
    #: (degrees per 30 m), and the static friction factor there.
    inclination_deg: NDArray[np.float64]
    azimuth_deg: NDArray[np.float64]
    tvd: NDArray[np.float64]
    dls_deg_per_30m: NDArray[np.float64]
    friction_factor: NDArray[np.float64]

def drill_profile(config_json: str) -> DrillProfile:
    """The friction profile and static break-off torque of a configuration.

    Raises
    ------
    ValidationError
        as :func:`drill_validate`.
    """

class StringNumbersDict(TypedDict):
    #: Characteristic impedance of the top section J sqrt(G rho), N m s.
    impedance: float
    #: First natural frequency of the string (top fixed, bit free or with the BHA), Hz.
    first_mode_hz: float
    #: Top-drive inertia, kg m^2.
    top_drive_inertia: float
    #: Static torsional stiffness of the string 1 / sum L / (G J), N m/rad.
    stiffness: float

class PresetRecommendationDict(TypedDict):
    #: "stiff", "soft_torque" or "z_torque".
    preset: str
    #: The controller table the preset sets (type, preset, kp, ki, tuning_frequency, z_factor,
    #: torque_highpass_time).
    controller: dict[str, Any]
    #: The damping the top drive presents to torque waves, N m s.
    damping: float
    #: The reflection coefficient of a torque wave at the top, (c - Z) / (c + Z).
    reflection: float
    #: stiff, soft_torque: kp / (2 pi I_TD), Hz (NaN for z_torque).
    speed_bandwidth_hz: float
    #: z_torque: the fraction of the setpoint the top turns at while the string winds up (NaN
    #: otherwise).
    windup_speed_ratio: float
    #: The rule with its numbers.
    rule: str

class ControllerRecommendationsDict(TypedDict):
    string: StringNumbersDict
    presets: list[PresetRecommendationDict]

def recommend_controllers(config_json: str) -> ControllerRecommendationsDict:
    """The recommended settings of every controller preset for the configuration's string and
    the numbers they were computed from (``drilling::tuning::recommend``).

    Raises
    ------
    ValidationError
        as :func:`drill_validate`.
    """

DrillMetrics = dict[str, Any]
"""A drilling run's metrics: the torsional metrics of :func:`drill_outputs` by name (the window
asked for, default the last half of the run, as ``window_start``, ``window_end``), and ``warnings``."""

class DrillEnergy(TypedDict):
    #: J, from the start to the end reached: motor work = (final - initial) + losses.
    motor_work: float
    initial: float
    #: At the end: string kinetic, string elastic, top-drive and BHA kinetic energy.
    kinetic: float
    elastic: float
    top_drive: float
    bha: float
    #: The wall friction's work on the string (both fields in a coupled run), and the axial
    #: field's part of it (coupled runs with friction.coupling = "axial_torsional"; else 0).
    friction_loss: float
    axial_friction_loss: float
    damping_loss: float
    bit_loss: float
    #: upwind_loss + inertia_loss.
    numerical_loss: float
    #: Dissipation of the first-order transport (linear: 0 at Courant number 1; consistent:
    #: the energy the Godunov face fluxes bring in less the cells' energy change).
    upwind_loss: float
    #: Dissipation of the implicit Euler steps of the top-drive and BHA inertias.
    inertia_loss: float
    #: A coupled run ([hoist]): the hoist's and the buoyed weight's work on the axial field
    #: (inputs of the balance) and the axial field's energies at the end, J (0 without a hoist).
    hoist_work: float
    gravity_work: float
    axial_kinetic: float
    axial_elastic: float
    #: Relative residual of the balance.
    balance_error: float

class DrillStats(TypedDict):
    cells: int
    steps: int
    dt: float
    #: Courant numbers of the sections at the speed the step is made for (consistent: the
    #: tangent speed at numerics.max_shear_strain).
    courant_min: float
    courant_max: float
    #: The largest Courant number of the local (tangent) wave speed met in the run.
    courant_peak: float
    #: Controller gains used (soft_torque: the tuned ones).
    kp: float
    ki: float
    #: First natural frequency (fixed top, bit free or with the BHA), Hz.
    first_mode_hz: float

class DrillCoupledOutput(TypedDict, total=False):
    """What a coupled run ([hoist]) adds to its :class:`DrillOutput` (absent without a hoist)."""

    #: Series at the times t: bit axial speed m/s (down positive), ROP m/h, weight on bit N,
    #: hook load N, bit depth m, depth of cut per revolution m, block position m (down positive).
    bit_axial_speed: NDArray[np.float64]
    rop: NDArray[np.float64]
    weight_on_bit: NDArray[np.float64]
    hook_load: NDArray[np.float64]
    bit_depth: NDArray[np.float64]
    depth_of_cut: NDArray[np.float64]
    block_position: NDArray[np.float64]
    #: The coupled metrics over the window (rop_mean_m_per_h, wob_mean_N, tob_mean_Nm,
    #: bounce_fraction, hook_load_mean_N, mse_mean_Pa).
    coupled: dict[str, float]
    #: Axial cell centres, m; at field_t, (len(field_t), len(axial_z)): axial speed m/s (down
    #: positive) and axial force N (compression positive); absent without snapshots.
    axial_z: NDArray[np.float64]
    axial_speed_field: NDArray[np.float64]
    axial_force_field: NDArray[np.float64]

class DrillOutput(DrillCoupledOutput):
    #: Series at k * output_interval.
    t: NDArray[np.float64]
    surface_rpm: NDArray[np.float64]
    bit_rpm: NDArray[np.float64]
    motor_torque: NDArray[np.float64]
    bit_torque: NDArray[np.float64]
    #: Snapshot times (nearest step to k * field_interval), s.
    field_t: NDArray[np.float64]
    #: Cell centres, m.
    z: NDArray[np.float64]
    #: (len(field_t), len(z)): speed rpm and torque N m.
    omega_field: NDArray[np.float64]
    torque_field: NDArray[np.float64]
    #: "success", "interrupted", "non_finite" or "out_of_memory".
    status: str
    message: str
    #: What the configuration makes doubtful (a torque limit below the static torque, a value
    #: likely a unit mistake, a transient still decaying in the window, metrics not finite).
    warnings: list[str]
    #: False when a headline metric (ssi, stuck fraction, bit speed, motor torque) is not
    #: finite or the window has none: not a result, whatever ``status`` says.
    metrics_finite: bool
    #: Whether the top drive was asked to turn (a pick-up without rotation: False).
    rotating: bool
    metrics: DrillMetrics
    energy: DrillEnergy
    stats: DrillStats

@final
class DrillSession:
    """A drilling run stepped in chunks (the core's ``Session``); ``drill_solve`` is one stepped
    to ``numerics.duration``."""

    def __new__(cls, config_json: str, keep_fields: bool = False) -> DrillSession: ...
    @staticmethod
    def resume(config_json: str, changes_json: str, steps: int, keep_fields: bool = False) -> DrillSession:
        """The session that ``steps`` steps of ``config_json`` with the changes ``changes_json``
        (``[{"time", "key", "value"}, ...]``) reach, stepped there without the GIL."""
    @property
    def steps(self) -> int: ...
    def step(self, seconds: float, progress: Optional[Callable[[float], object]] = None) -> None:
        """Advances to the step end nearest ``t + seconds`` (at least one step) without the GIL;
        ``progress(t)`` every ~20 ms. Raises ``KeyboardInterrupt`` on Ctrl-C (the session stays
        usable at the step reached)."""
    def set(self, key: str, value_json: str) -> None:
        """Sets ``key`` to the JSON value from the next step; ``ValidationError`` naming the key."""
    @property
    def t(self) -> float: ...
    @property
    def dt(self) -> float: ...
    @property
    def replay_duration(self) -> float:
        """The ``numerics.duration`` of the configuration that repeats what was stepped, s."""
    @property
    def status(self) -> str: ...
    @property
    def message(self) -> str: ...
    @staticmethod
    def settable() -> list[str]: ...
    def changes(self) -> list[tuple[float, str, str]]:
        """``(time, key, value as JSON text)`` of every change made."""
    def config(self) -> dict[str, Any]: ...
    def state(self) -> dict[str, Any]: ...
    def rows(self, start: int = 0) -> dict[str, NDArray[np.float64]]: ...
    def __len__(self) -> int: ...
    def result(self, window: Optional[tuple[float, float]] = None) -> DrillOutput: ...
    def copy(self) -> DrillSession: ...

def drill_solve(config_json: str, progress: Optional[Callable[[float], object]] = None) -> DrillOutput:
    """Runs the drilling system from ``numerics.initial_state`` (rest, or a coupled run's steady
    drilling); ``progress(fraction)`` is called every ~20 ms.
    Runs without the GIL.

    Raises
    ------
    ValidationError
        as :func:`drill_validate`, or ``damping_rate`` above ``1 / dt``.
    KeyboardInterrupt
        Ctrl-C during the solve (or any exception raised by ``progress``).
    """


def drill_compare(metrics: dict[str, Union[float, str, None]],
                  other: dict[str, Union[float, str, None]]) -> list[dict[str, Any]]:
    """Two runs' metrics (names to numbers, texts or None) compared with the core's tolerances
    (``drilling::compare``): one dict per metric both give, ``metric``, ``value``, ``other``,
    ``change``, ``kind``, ``tolerance``, ``within``.

    Raises
    ------
    ValidationError
        a value that is not a number, a text or None.
    """

class OutputDict(TypedDict):
    """One output of a run in the core's registry (``drillstring_core::outputs``)."""

    name: str
    #: The few words the console, report.md and the figures name it by, without its unit.
    label: str
    #: SI unit as pint parses it ("" dimensionless); None for a verdict, a count or a text.
    unit: Optional[str]
    definition: str
    #: Of "torsional", "coupled", "lumped".
    runs: list[str]
    map_column: bool
    #: "number", "verdict", "count", "text" or "series".
    kind: str
    #: (kind, tolerance, floor) of the grid and start checks, or None.
    tolerance: Optional[tuple[str, float, float]]
    headline: bool
    #: On the console's summary of a run (drillstring drill), by its label, in this order.
    console: bool
    #: A metric of stick_slip_metrics (of any series).
    of_any_series: bool

def drill_outputs() -> list[OutputDict]:
    """Every metric and series channel of a run, declared once in the core, in order."""

def drill_compare_tolerances() -> list[tuple[str, str, float, float]]:
    """The tolerances of :func:`drill_compare`: ``(metric, kind, tolerance, floor)``, kind
    ``"rel"``, ``"abs"`` or ``"equal"``."""


class DrillMapOutput(TypedDict):
    """What :func:`drill_map` returns: one entry per run, in the order of the runs."""

    status: list[str]
    message: list[str]
    metrics: dict[str, Any]
    """The metrics of :func:`drill_outputs` with ``map_column`` of a torsional run: float arrays, NaN
    unless successful (verdicts 1 or 0); texts as lists of str (``undetermined`` unless successful)."""
    stats: dict[str, NDArray[np.generic]]
    """``cells``, ``steps`` (uint64), ``dt``, ``balance_error``, ``courant_peak`` (the largest
    Courant number a run reached: above 1 only with ``nonlinearity = "consistent"`` past
    ``numerics.max_shear_strain``)."""
    coupled: dict[str, Any]
    """A coupled run's metrics (``rop_mean_m_per_h``, ``wob_mean_N``, ``tob_mean_Nm``,
    ``bounce_fraction``, ``hook_load_mean_N``, ``mse_mean_Pa``: float arrays, NaN without them) and
    ``regime`` (a list of str, ``undetermined`` without them)."""
    interrupt: Optional[BaseException]
    """The exception that stopped the map (Ctrl-C or raised by ``progress``), or None."""


def drill_map(
    config_json: str,
    runs_json: str,
    threads: Optional[int] = None,
    memory_budget: Optional[int] = None,
    progress: Optional[Callable[[float], object]] = None,
    check_axes: bool = True,
) -> DrillMapOutput:
    """A stick-slip map: ``config_json`` with each run's overrides (``runs_json``: a list of runs,
    each a list of ``[dotted key, value]`` pairs; null unsets a field) solved in parallel without
    the GIL; ``progress(finished_runs)`` about every 20 ms. A refused run is a row with status
    ``"invalid"``; the exception that stopped the map is returned under ``interrupt``.

    Raises
    ------
    ValidationError
        ``config_json`` or ``runs_json`` not JSON of the right shape, ``threads``, a map
        over ``memory_budget`` bytes (``threads``), or with ``check_axes`` an axis without
        effect in every run (``drill_map_check_axes``).
    """


def drill_map_check_axes(config_json: str, runs_json: str) -> None:
    """Refuses a map (``config_json`` with the runs ``runs_json``, as :func:`drill_map`) with an
    axis that changes nothing in any run (``top_drive.rpm`` under ``top_drive.mode =
    "measured_speed"``, a hoist key of another ``hoist.mode``, ...): the core's rule
    ``drilling::effect::no_effect``.

    Raises
    ------
    ValidationError
        Naming ``axis KEY`` and why it has no effect.
    """


# ----------------------------------------------------------------- the lumped two-inertia model

def lumped_defaults() -> tuple[dict[str, Any], dict[str, Any]]:
    """The default parameters and numerics of the lumped model as dicts of JSON values:
    parameters ``jr``, ``jb``, ``kt``, ``ct``, ``cr``, ``cb``, ``rb``, ``mu_cb``, ``mu_sb``,
    ``gamma_b``, ``v_f``, ``d_v``, ``tm``, ``wob`` (Navarro-Lopez & Cortes 2007);
    numerics ``duration``, ``dt``, ``output_interval``, ``initial`` ([wr, phi, wb]),
    ``window`` (null or [t_start, t_end]), ``stick_speed``."""

LumpedMetrics = dict[str, Any]
"""The lumped metrics of :func:`drill_outputs` by name (of ``metrics::stick_slip`` with the spring
torque as the torque series), and ``warnings``."""

class LumpedEnergy(TypedDict):
    #: J: motor_work = (kinetic_top + kinetic_bit + spring - initial) + viscous_loss + friction_loss.
    motor_work: float
    initial: float
    kinetic_top: float
    kinetic_bit: float
    spring: float
    viscous_loss: float
    friction_loss: float
    #: The residual over the largest term.
    balance_error: float

class LumpedOutput(TypedDict):
    #: Samples at k * output_interval: s, rad/s, rad/s, N m (kt phi), N m.
    t: NDArray[np.float64]
    top_speed: NDArray[np.float64]
    bit_speed: NDArray[np.float64]
    spring_torque: NDArray[np.float64]
    bit_torque: NDArray[np.float64]
    #: "success", "interrupted", "non_finite" or "out_of_memory".
    status: str
    message: str
    window: tuple[float, float]
    metrics: LumpedMetrics
    energy: LumpedEnergy
    #: steps, sticks, slips.
    stats: dict[str, int]

def lumped_solve(
    params_json: str, numerics_json: str, progress: Optional[Callable[[float], object]] = None
) -> LumpedOutput:
    """Runs the lumped model (fourth-order Runge-Kutta, stick and slip switches located in the
    step) without the GIL.

    Raises
    ------
    ValidationError
        An unknown field or a value out of range, naming it.
    KeyboardInterrupt
        Ctrl-C during the run (or any exception raised by ``progress``).
    """

class LumpedRotationDict(TypedDict):
    #: rad/s, rad.
    speed: float
    twist: float
    #: (re, im) of the Jacobian's eigenvalues, by increasing real part.
    eigenvalues: list[tuple[float, float]]
    stable: bool

class LumpedEquilibriaDict(TypedDict):
    rotations: list[LumpedRotationDict]
    #: Tm <= Wob Rb mu_sb.
    stuck_possible: bool
    #: "stable_rotation", "unstable" or "stuck".
    equilibrium: str
    #: Wob Rb mu_sb, N m.
    static_limit: float

def lumped_equilibria(params_json: str) -> LumpedEquilibriaDict:
    """The steady rotations of the lumped model, their stability and the regime.

    Raises
    ------
    ValidationError
        As :func:`lumped_solve`.
    """

def min_cycle_torque(
    breakoff_torque: float, kinetic_ratio: float, bit_static: float = 0.0, bit_kinetic: float = 0.0
) -> float:
    """The minimum motor torque of a stick-slip cycle implied by break-off, ``2 K - S`` with
    ``S = breakoff_torque + bit_static`` and ``K = kinetic_ratio breakoff_torque + bit_kinetic``
    (``drilling::grid::min_cycle_torque_from``), N m."""
