"""Numpy implementations of numbers the core computes, kept only as test oracles.

The package calls the core (``drillstring._core``) for each of these; the tests check that the
core gives the same numbers to rounding.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import NDArray

#: Hann main-lobe half width in unpadded bins (the core's ``HANN_HALF_WIDTH``).
HANN_HALF_WIDTH = 2


def _hann_leakage(distance: float) -> float:
    """Envelope of the Hann window's side lobes relative to its peak, ``distance`` in bins."""
    with np.errstate(divide="ignore"):
        return float(np.float64(1.0) / (math.pi * distance * abs(distance * distance - 1.0)))


def spectral_peaks(x: NDArray[np.float64], dt: float, count: int, pad: int = 8,
                   threshold: float = 1e-3) -> list[tuple[float, float]]:
    """``(frequency Hz, sine amplitude)`` of the ``count`` strongest peaks of the Hann-windowed,
    zero-padded spectrum, strongest first (side lobes and unresolved peaks dropped)."""
    xa = np.asarray(x, dtype=float)
    n = xa.size
    window = np.hanning(n)
    signal = (xa - np.dot(window, xa) / window.sum()) * window
    nfft = 1 << int(math.ceil(math.log2(n * pad)))
    magnitude = np.abs(np.fft.rfft(signal, nfft))
    top = float(magnitude.max()) if magnitude.size else 0.0
    if top <= 0.0:
        return []
    inner = magnitude[1:-1]
    is_peak = (inner > magnitude[:-2]) & (inner >= magnitude[2:]) & (inner >= threshold * top)
    candidates = np.nonzero(is_peak)[0] + 1
    candidates = candidates[np.argsort(magnitude[candidates])[::-1]]
    bin_hz = 1.0 / (nfft * dt)
    gain = window.sum() / 2.0
    chosen: list[int] = []
    peaks: list[tuple[float, float]] = []
    for k in candidates.tolist():
        distances = [abs(k - j) / (nfft / n) for j in chosen]
        if any(d < HANN_HALF_WIDTH for d in distances):
            continue
        leakage = sum(
            magnitude[j] * (_hann_leakage(d) + _hann_leakage((k + j) / (nfft / n)))
            for j, d in zip(chosen, distances)
        )
        if magnitude[k] <= 2.0 * leakage:
            continue
        chosen.append(k)
        a, b, c = (math.log(max(v, 1e-300)) for v in magnitude[k - 1 : k + 2])
        denom = a - 2.0 * b + c
        delta = 0.5 * (a - c) / denom if denom < 0 else 0.0
        log_peak = b - 0.25 * (a - c) * delta
        peaks.append(((k + delta) * bin_hz, math.exp(log_peak) / gain))
        if len(peaks) == count:
            break
    return peaks


def energy_drift(energy: NDArray[np.float64], dissipated: NDArray[np.float64] | None = None) -> float:
    """``max |H + D - H(0)| / |H(0)|`` (0 when ``H(0) = 0`` or without samples)."""
    h = np.asarray(energy, dtype=float)
    if dissipated is not None:
        h = h + dissipated
    if h.size == 0 or h[0] == 0:
        return 0.0
    return float(np.max(np.abs(h - h[0])) / abs(h[0]))


def modal_energies(mass: NDArray[np.float64], stiffness: NDArray[np.float64], q: NDArray[np.float64],
                   qdot: NDArray[np.float64]) -> NDArray[np.float64]:
    """``E_i = (M_i qdot_i^2 + K_i q_i^2) / 2`` of each mode (rows) at each sample (columns)."""
    return 0.5 * (mass[:, None] * qdot**2 + stiffness[:, None] * q**2)


def max_modal_shares(mass: NDArray[np.float64], stiffness: NDArray[np.float64], q: NDArray[np.float64],
                     qdot: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest ``E_i / sum_j E_j`` of each mode over the samples with a positive total."""
    e = modal_energies(mass, stiffness, q, qdot)
    total = e.sum(axis=0)
    keep = total > 0
    if not keep.any():
        return np.full(mass.size, math.nan)
    return np.max(e[:, keep] / total[keep], axis=1)


def modal_potential(quartic_index: NDArray[np.int64], quartic_coef: NDArray[np.float64],
                    q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Quartic potential ``V(q) = sum_t C_t q_a q_b q_c q_d``: ``q`` (m,) -> (), (m, S) -> (S,)."""
    factors = np.asarray(q, dtype=float)[quartic_index]  # (T, 4) or (T, 4, S)
    return np.asarray(np.tensordot(quartic_coef, factors.prod(axis=1), axes=(0, 0)))


def modal_energy(mass: NDArray[np.float64], stiffness: NDArray[np.float64],
                 quartic_index: NDArray[np.int64], quartic_coef: NDArray[np.float64],
                 q: NDArray[np.float64], qdot: NDArray[np.float64]) -> NDArray[np.float64]:
    """``H = 1/2 q'^T M q' + 1/2 q^T K q + V(q)``: ``q``, ``qdot`` (m,) -> (), (m, S) -> (S,)."""
    qa, va = np.asarray(q, dtype=float), np.asarray(qdot, dtype=float)
    shape = (-1,) + (1,) * (qa.ndim - 1)
    quadratic = 0.5 * np.sum(mass.reshape(shape) * va**2 + stiffness.reshape(shape) * qa**2, axis=0)
    return np.asarray(quadratic + modal_potential(quartic_index, quartic_coef, qa))


def galerkin_scaling(k: tuple[float, float, float, float, float, float], length: float,
                     indices: NDArray[np.int64], cos4: NDArray[np.float64], mixed: NDArray[np.float64],
                     sin4: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """``(mass, stiffness, quartic_coef)`` of the modal system: the dimensionless integrals
    scaled by ``k1..k6`` and ``l`` (``drillstring.model.galerkin`` module docstring)."""
    k1, k2, k3, k4, k5, k6 = k
    i = indices.astype(float)
    norm = np.where(indices == 0, length, length / 2.0)  # int_0^l phi_i^2 dz
    mass = k1 * norm
    stiffness = k2 * (i * math.pi / length) ** 2 * norm - k6 * norm
    coef = (
        (k3 * length / 4.0) * cos4
        + (k4 * math.pi**2 / (2.0 * length)) * mixed
        + (k5 * math.pi**4 / (4.0 * length**3)) * sin4
    )
    return mass, stiffness, coef


# --------------------------------------------------------------------------- Galerkin integrals
# The former generator of ``drillstring.model.galerkin.dimensionless_integrals`` (now in the core,
# ``drillstring_core::galerkin``): integer arithmetic over the sign patterns, exact.

# distinct-ordering count of a sorted quadruple, indexed by (a==b)*4 + (b==c)*2 + (c==d)
_MULTIPLICITY = np.array([24, 12, 12, 4, 12, 6, 4, 1], dtype=np.int64)
_SIGNS = np.array(
    [(1, *rest) for rest in itertools.product((1, -1), repeat=3)], dtype=np.int64
)  # (8, 4), e_a = +1
_PAIRS = tuple(itertools.combinations(range(4), 2))


def _integer_integrals(quad: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """``8 x (cos4, mixed, sin4)`` for sorted mode-number quadruples ``quad`` (K, 4)."""
    hit = (quad @ _SIGNS.T == 0).astype(np.int64)  # (K, 8): N(e)
    eq = (quad[:, :-1] == quad[:, 1:]).astype(np.int64)
    mult = _MULTIPLICITY[eq[:, 0] * 4 + eq[:, 1] * 2 + eq[:, 2]]
    cos4 = mult * hit.sum(axis=1)
    pair_sum = np.zeros(quad.shape[0], dtype=np.int64)
    for i, j in _PAIRS:
        # sine pair at (i, j), cosines at the other two
        pair_sum += quad[:, i] * quad[:, j] * (hit @ (-_SIGNS[:, i] * _SIGNS[:, j]))
    # sum over the 24 permutations = 4 * pair_sum; distinct orderings = mult/24 of that
    numerator = mult * pair_sum
    assert not np.any(numerator % 6), "mixed quartic integral is not a multiple of 1/8"
    mixed = numerator // 6
    sin4 = mult * quad.prod(axis=1) * (hit @ _SIGNS.prod(axis=1))
    return cos4, mixed, sin4


def galerkin_integrals(modes: int, rigid_mode: bool) -> tuple[NDArray[np.int64], NDArray[np.int64],
                                                             NDArray[np.float64], NDArray[np.float64],
                                                             NDArray[np.float64]]:
    """``(indices, quartic_index, cos4, mixed, sin4)`` of the ``cos(i pi s)`` basis."""
    indices = np.arange(0 if rigid_mode else 1, modes + 1, dtype=np.int64)
    first = int(indices[0])
    top = modes
    base = top + 1
    keys: list[NDArray[np.int64]] = []
    for a in range(first, top + 1):
        # b = a + u, c = a + v with 0 <= u <= v <= top - a
        u, v = np.triu_indices(top - a + 1)
        b = a + u.astype(np.int64)
        c = a + v.astype(np.int64)
        # candidates d = +-a +- b +- c with c <= d <= top
        cand = a * _SIGNS[:, 1, None] + b * _SIGNS[:, 2, None] + c * _SIGNS[:, 3, None]
        ok = (cand >= c) & (cand <= top)
        (rows,) = np.nonzero(ok.ravel())
        col = rows % b.size
        d = cand.ravel()[rows]
        key = ((a * base + b[col]) * base + c[col]) * base + d
        keys.append(np.unique(key))
    key = np.concatenate(keys) if keys else np.zeros(0, dtype=np.int64)
    quad = np.empty((key.size, 4), dtype=np.int64)
    rest = key
    for col in (3, 2, 1, 0):
        quad[:, col] = rest % base
        rest = rest // base
    cos4, mixed, sin4 = _integer_integrals(quad)
    return indices, quad - first, cos4 / 8.0, mixed / 8.0, sin4 / 8.0


# --------------------------------------------------------------------------- stick-slip metrics
# A numpy port of the definitions of ``drillstring_core::metrics::stickslip`` (its module
# documentation), computed directly: the similarity by explicit differences, not the FFT.

RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def time_within(t: NDArray[np.float64], x: NDArray[np.float64], s: float) -> float:
    """Time during which the linear interpolant of ``x`` has ``|x| <= s``."""
    total = 0.0
    for t0, t1, u, v in zip(t[:-1], t[1:], x[:-1], x[1:]):
        if u == v:
            total += (t1 - t0) if abs(u) <= s else 0.0
            continue
        a, b = (-s - u) / (v - u), (s - u) / (v - u)
        total += max(0.0, min(max(a, b), 1.0) - max(min(a, b), 0.0)) * (t1 - t0)
    return total


def similarity_period(x: NDArray[np.float64], dt: float) -> float:
    """Period of the uniformly sampled ``x``: the first local maximum of the similarity
    ``s[k] = 1 - mean((y_j - y_{j+k})^2) / (2 var)`` after ``s`` first falls below 0 and within
    80 % of the highest up to half the series, refined by a parabola; NaN without one."""
    y = np.asarray(x, dtype=float) - np.mean(x)
    m = y.size
    var = float(np.mean(y * y))
    half = m // 2
    s = np.array([1.0 - np.mean((y[: m - k] - y[k:]) ** 2) / (2.0 * var) for k in range(half + 1)])
    below = np.nonzero(s < 0.0)[0]
    if below.size == 0:
        return math.nan
    k0 = int(below[0])
    top = float(s[k0:half].max())
    for k in range(max(k0, 1), half):
        if s[k] >= 0.8 * top and s[k] >= s[k - 1] and s[k] >= s[k + 1]:
            a, b, c = s[k - 1], s[k], s[k + 1]
            curvature = a - 2.0 * b + c
            delta = min(0.5, max(-0.5, 0.5 * (a - c) / curvature)) if curvature < 0 else 0.0
            return float((k + delta) * dt)
    return math.nan


def stick_slip(t: NDArray[np.float64], omega: NDArray[np.float64], torque: NDArray[np.float64],
               window: tuple[float, float], stick_speed: float) -> dict[str, float]:
    """The stick-slip metrics of the samples in ``window`` (bit speed ``omega`` rad/s, motor
    torque N m on uniform times ``t``), named as the drilling metrics are."""
    keep = (t >= window[0]) & (t <= window[1])
    tw, w, q = t[keep], omega[keep], torque[keep]
    mean = float(np.trapezoid(w, tw) / (tw[-1] - tw[0]))
    return {
        "ssi": float((w.max() - w.min()) / (2.0 * abs(mean))),
        "stuck_fraction": min(1.0, time_within(tw, w, stick_speed) / (tw[-1] - tw[0])),
        "period_s": similarity_period(q, float(np.mean(np.diff(tw)))),
        "bit_rpm_min": float(w.min()) * RPM_PER_RAD_S,
        "bit_rpm_max": float(w.max()) * RPM_PER_RAD_S,
        "bit_rpm_mean": mean * RPM_PER_RAD_S,
        "motor_torque_min_Nm": float(q.min()),
        "motor_torque_max_Nm": float(q.max()),
    }
# --------------------------------------------------------------------------- the modal model
# The former numpy evaluations of ``drillstring.model.galerkin.ModalCoefficients`` (force, dense
# tensor, acceleration, basis) and of ``drillstring.studies.stability`` (Jacobian, its eigenvalues by
# LAPACK, the classification from eigenvalues); the package now asks the core for each.


def cubic_force(quartic_index: NDArray[np.int64], quartic_coef: NDArray[np.float64],
                q: NDArray[np.float64]) -> NDArray[np.float64]:
    """``grad V(q)`` of ``V = sum_t C_t q_a q_b q_c q_d`` by scattering the four partial
    derivatives of every term: ``q`` (m,) -> (m,), (m, S) -> (m, S)."""
    qa = np.asarray(q, dtype=float)
    m = qa.shape[0]
    f = qa[quartic_index]  # (T, 4) or (T, 4, S)
    one = np.ones_like(f[:, 0])
    left = [one, f[:, 0], f[:, 0] * f[:, 1], f[:, 0] * f[:, 1] * f[:, 2]]
    right = [f[:, 1] * f[:, 2] * f[:, 3], f[:, 2] * f[:, 3], f[:, 3], one]
    coef = quartic_coef if qa.ndim == 1 else quartic_coef[:, None]
    weights = np.concatenate([coef * left[k] * right[k] for k in range(4)])
    target = quartic_index.T.ravel()  # position k of every term, k-major
    if qa.ndim == 1:
        return np.bincount(target, weights=weights, minlength=m).astype(float, copy=False)
    samples = qa.shape[1]
    flat = (target[:, None] * samples + np.arange(samples)).ravel()
    force = np.bincount(flat, weights=weights.ravel(), minlength=m * samples)
    return force.astype(float, copy=False).reshape(m, samples)


def cubic_tensor(quartic_index: NDArray[np.int64], quartic_coef: NDArray[np.float64], m: int) -> NDArray[np.float64]:
    """Dense symmetric ``T`` (m, m, m, m) with ``grad V_j = sum T_jbcd q_b q_c q_d`` and
    ``V = 1/4 sum T_abcd q_a q_b q_c q_d``."""
    tensor = np.zeros((m, m, m, m))
    # each distinct ordering of term t is visited 24/mult_t times: 4 C_t / 24 each time
    # gives 4 C_t / mult_t = 4 S_t per ordering, where V = sum_ordered S q q q q
    value = quartic_coef / 6.0
    for perm in itertools.permutations(range(4)):
        np.add.at(tensor, tuple(quartic_index[:, p] for p in perm), value)
    return tensor


def modal_acceleration(mass: NDArray[np.float64], stiffness: NDArray[np.float64],
                       quartic_index: NDArray[np.int64], quartic_coef: NDArray[np.float64],
                       q: NDArray[np.float64]) -> NDArray[np.float64]:
    """``q'' = -M^-1 (K q + grad V(q))``: ``q`` (m,) -> (m,), (m, S) -> (m, S)."""
    qa = np.asarray(q, dtype=float)
    shape = (-1,) + (1,) * (qa.ndim - 1)
    force = cubic_force(quartic_index, quartic_coef, qa)
    return -(stiffness.reshape(shape) * qa + force) / mass.reshape(shape)


def mode_shapes(indices: NDArray[np.int64], length: float, z: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """``(cos(i pi z / l), -(i pi / l) sin(i pi z / l))`` as (len(z), m) arrays."""
    wave = np.asarray(indices) * (math.pi / length)
    arg = np.outer(np.atleast_1d(np.asarray(z, dtype=float)), wave)
    return np.cos(arg), -wave * np.sin(arg)


def jacobian(mass: NDArray[np.float64], stiffness: NDArray[np.float64], damping_rate: float) -> NDArray[np.float64]:
    """``J = [[0, I], [-M^-1 K, -c I]]`` (2m, 2m) by a linear solve."""
    m = mass.size
    jac = np.zeros((2 * m, 2 * m))
    jac[:m, m:] = np.eye(m)
    jac[m:, :m] = -np.linalg.solve(np.diag(mass), np.diag(stiffness))
    jac[m:, m:] = -damping_rate * np.eye(m)
    return jac


def jacobian_eigenvalues(jac: NDArray[np.float64]) -> NDArray[np.complex128]:
    """The eigenvalues of ``jac`` by LAPACK, sorted by imaginary then real part."""
    eig = np.linalg.eigvals(jac)
    return eig[np.lexsort((eig.real, eig.imag))]


def classify_eigenvalues(eigenvalues: NDArray[np.complex128], rtol: float = 1e-9) -> str:
    """The type of an equilibrium from the eigenvalues of its Jacobian (real parts within
    ``rtol max |lambda|`` count as zero): ``"saddle"``, ``"degenerate"``, ``"stable focus"``,
    ``"stable node"`` or ``"centre"``."""
    lam = np.asarray(eigenvalues, dtype=complex)
    scale = float(np.max(np.abs(lam))) if lam.size else 0.0
    tol = rtol * scale
    if np.any(lam.real > tol):
        return "saddle"
    if np.any(np.abs(lam) <= tol):
        return "degenerate"
    if lam.size and np.all(lam.real < -tol):
        return "stable focus" if np.any(np.abs(lam.imag) > tol) else "stable node"
    return "centre"
# --------------------------------------------------------------------------- signal metrics
# The numpy versions of drillstring.studies.analysis's signal metrics (the core computes them:
# drillstring_core::metrics::signal); kept as oracles for tests/test_analysis.py.

from numpy.typing import ArrayLike  # noqa: E402


def crossing_phase(t: ArrayLike, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Zero-crossing times of ``x(t)`` (led by ``t[0]``) and the phase there: ``k pi`` at the ``k``-th."""
    ta, xa = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    sign = xa >= 0.0
    idx = np.nonzero(sign[1:] != sign[:-1])[0]
    if idx.size < 2:
        raise ValueError("x", f"{idx.size} zero crossings", "at least two zero crossings")
    x0, x1 = xa[idx], xa[idx + 1]
    times = ta[idx] + (ta[idx + 1] - ta[idx]) * (x0 / (x0 - x1))
    start = math.pi * (1.0 - (times[0] - ta[0]) / (times[1] - times[0]))
    phases = start + math.pi * np.arange(1, times.size + 1)
    return np.concatenate([[ta[0]], times]), np.concatenate([[start], phases])


def _phase_at(times: NDArray[np.float64], phases: NDArray[np.float64], at: NDArray[np.float64]) -> NDArray[np.float64]:
    out = np.interp(at, times, phases)
    # beyond the last crossing: extrapolate with the last half period
    slope = (phases[-1] - phases[-2]) / (times[-1] - times[-2])
    late = at > times[-1]
    out[late] = phases[-1] + slope * (at[late] - times[-1])
    return out


def phase_shift(t: ArrayLike, x_ref: ArrayLike, x: ArrayLike, at: ArrayLike | float | None = None
                ) -> float | NDArray[np.float64]:
    """Accumulated phase of ``x`` minus that of ``x_ref`` at ``at`` (default ``t[-1]``), by ``np.interp``."""
    times_ref, phase_ref = crossing_phase(t, x_ref)
    times_x, phase_x = crossing_phase(t, x)
    ta = np.asarray(t, dtype=float)
    when = np.atleast_1d(np.asarray(ta[-1] if at is None else at, dtype=float))
    shift = _phase_at(times_x, phase_x, when) - _phase_at(times_ref, phase_ref, when)
    return float(shift[0]) if np.ndim(ta[-1] if at is None else at) == 0 else shift


def amplitude_growth(x: ArrayLike) -> float:
    """``max |x|`` over the last half over that of the first half (inf when not finite)."""
    xa = np.asarray(x, dtype=float).ravel()
    if xa.size < 2:
        raise ValueError("x", f"{xa.size} samples", "at least 2 samples")
    if not np.all(np.isfinite(xa)):
        return math.inf
    half = xa.size // 2
    first = float(np.max(np.abs(xa[:half])))
    last = float(np.max(np.abs(xa[half:])))
    if first == 0.0:
        return math.nan if last == 0.0 else math.inf
    return last / first


def is_bounded(x: ArrayLike, factor: float = 1.5, *, limit: float | None = None) -> bool:
    """Finite, growth ``<= factor`` and ``max |x| <= limit``."""
    growth = amplitude_growth(x)
    if not math.isfinite(growth) or growth > factor:
        return False
    return limit is None or float(np.max(np.abs(np.asarray(x, dtype=float)))) <= limit



def modulation_depth(x: ArrayLike) -> float:
    """``1 - min/max`` of the half-cycle peaks of each sign (``np.maximum.reduceat``), the larger."""
    xa = np.asarray(x, dtype=float).ravel()
    sign = xa >= 0.0
    cuts = np.nonzero(sign[1:] != sign[:-1])[0] + 1
    if cuts.size < 5:
        return math.nan
    peaks = np.maximum.reduceat(np.abs(xa), cuts)[:-1]  # complete half cycles between crossings
    positive = sign[cuts[:-1]]
    depths = []
    for part in (peaks[positive], peaks[~positive]):
        if part.size < 2 or part.max() <= 0:
            return math.nan
        depths.append(1.0 - float(part.min()) / float(part.max()))
    return max(depths)


def hull_area(x: ArrayLike, y: ArrayLike) -> float:
    """Area of the convex hull of the points (``np.unique`` rows, monotone chain, shoelace by ``np.dot``)."""
    pts = np.unique(np.column_stack([np.asarray(x, float).ravel(), np.asarray(y, float).ravel()]), axis=0)
    if pts.shape[0] < 3:
        return 0.0

    def half(points: NDArray[np.float64]) -> list[tuple[float, float]]:
        chain: list[tuple[float, float]] = []
        for px, py in points.tolist():
            while len(chain) >= 2:
                (ax, ay), (bx, by) = chain[-2], chain[-1]
                if (bx - ax) * (py - ay) - (by - ay) * (px - ax) > 0:
                    break
                chain.pop()
            chain.append((px, py))
        return chain

    lower, upper = half(pts), half(pts[::-1])
    hull = np.array(lower[:-1] + upper[:-1])
    hx, hy = hull[:, 0], hull[:, 1]
    return 0.5 * abs(float(np.dot(hx, np.roll(hy, -1)) - np.dot(hy, np.roll(hx, -1))))


def phase_fill(x: ArrayLike, y: ArrayLike, bins: int = 32) -> float:
    """Share of the cells of a ``bins x bins`` grid over the hull that the trajectory passes through."""
    xa = np.asarray(x, dtype=float).ravel()
    ya = np.asarray(y, dtype=float).ravel()
    if xa.size < 3 or xa.shape != ya.shape:
        raise ValueError("x", f"{xa.size} samples", "x and y of equal length >= 3")
    span_x, span_y = float(np.ptp(xa)), float(np.ptp(ya))
    if span_x == 0.0 or span_y == 0.0:
        return 0.0
    u = (xa - xa.min()) / span_x * bins * (1 - 1e-12)
    v = (ya - ya.min()) / span_y * bins * (1 - 1e-12)
    # subdivide every segment so that consecutive points are < 1/2 cell apart
    steps = int(np.ceil(2.0 * max(np.max(np.abs(np.diff(u))), np.max(np.abs(np.diff(v)))))) + 1
    frac = np.linspace(0.0, 1.0, steps, endpoint=False)
    uu = (u[:-1, None] + np.diff(u)[:, None] * frac).ravel()
    vv = (v[:-1, None] + np.diff(v)[:, None] * frac).ravel()
    visited = np.zeros((bins, bins), dtype=bool)
    visited[uu.astype(int), vv.astype(int)] = True
    visited[int(u[-1]), int(v[-1])] = True
    # cells whose centre lies inside the hull: the hull's area in cells, approximately
    hull_cells = max(1.0, hull_area(u, v))
    return min(1.0, float(visited.sum()) / hull_cells)


def ellipk(m: float) -> float:
    """``K(m)`` by the arithmetic-geometric mean."""
    if not m < 1.0:
        raise ValueError("m", m, "m < 1")
    a, b = 1.0, math.sqrt(1.0 - m)
    for _ in range(60):
        if abs(a - b) <= 1e-16 * a:
            break
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def duffing_amplitude(omega2: float, beta: float, velocity: float) -> float:
    """Turning point of ``x'' + omega2 x + beta x^3 = 0`` from ``x = 0``, ``x' = v``."""
    if beta == 0.0:
        return abs(velocity) / math.sqrt(omega2)
    disc = omega2 * omega2 + 2.0 * beta * velocity * velocity
    if disc < 0.0:
        raise ValueError("velocity", velocity, "below the separatrix of the softening oscillator")
    # A^2 = (-omega2 + sqrt(disc)) / beta, written without cancellation
    return math.sqrt(2.0 * velocity * velocity / (omega2 + math.sqrt(disc)))


def duffing_frequency(omega2: float, beta: float, amplitude: float) -> float:
    """Exact frequency (Hz) of ``x'' + omega2 x + beta x^3 = 0`` at amplitude ``A``."""
    stiff = omega2 + beta * amplitude * amplitude
    if not stiff > 0.0:
        raise ValueError("amplitude", amplitude, "omega2 + beta A^2 > 0")
    m = beta * amplitude * amplitude / (2.0 * stiff)
    return math.sqrt(stiff) / (4.0 * ellipk(m))
