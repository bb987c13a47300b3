"""Measurements: the runs of the figures (computed once, on demand), the numbers measured on each
plotted curve, the reference values the checks compare them with, the stability table and the
physics notes.

Every number comes from a shared function: the spectra, envelopes and phase-plane measures from
:mod:`drillstring.studies.analysis`, the modal coefficients from :func:`drillstring.project`, the linear
frequencies, wave speeds and critical speeds from :class:`drillstring.model.coefficients.PDECoefficients`,
the eigenvalues from :func:`drillstring.studies.stability.analyse`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from .. import _core
from ..errors import ValidationError
from ..model.coefficients import PDECoefficients
from ..model.galerkin import project
from ..model.parameters import Parameters, preset
from ..solvers.modal import Simulation, simulate
from ..studies import analysis
from ..studies.stability import analyse
from .specs import OMEGA6, PARAMETER_SETS, RUNS, FigureSpec


@dataclass(frozen=True)
class CurveMetrics:
    """Numbers measured on one plotted curve."""

    label: str
    quantity: str
    window: tuple[float, float]
    amplitude: float
    """max |x| over the window, rad."""
    rate_amplitude: float
    """max |dx/dt| over the window, rad/s."""
    frequencies: tuple[float, ...]
    """Dominant frequencies (Hz) of x over ``record``, strongest first."""
    frequency_amplitudes: tuple[float, ...]
    """Sine amplitudes (rad) of those spectral peaks."""
    record: tuple[float, float]
    """Time span (s) of the FFT record."""
    growth: float
    """max |x| over the second half of the window / over the first half."""
    bounded: bool
    energy_drift: float
    """max |H(t) - H(0)| / |H(0)| of the run."""
    extra: dict[str, float] = field(default_factory=dict)
    """Figure-specific numbers (hull_area, modulation_depth, modal_exchange, quartic_share...)."""


@dataclass(frozen=True)
class StabilityRow:
    parameter_set: str
    material: str
    length: float
    omega: float
    modes: int
    mode: int
    eigenvalue: complex
    """The mode's eigenvalue pair is ``+-eigenvalue`` (Im >= 0)."""
    linear_frequency_hz: float
    critical_speed: float
    mode_classification: str
    classification: str
    figures: str

    @property
    def omega_over_critical(self) -> float:
        """``omega / critical_speed``: how close the mode is to losing stability."""
        return self.omega / self.critical_speed


class Runs:
    """Lazily computed, cached simulations."""

    def __init__(self, scale: float, per_second: int) -> None:
        self.scale = scale
        self.per_second = per_second
        self.cache: dict[str, Simulation] = {}

    def __getitem__(self, key: str) -> Simulation:
        if key not in self.cache:
            spec = RUNS[key]
            self.cache[key] = simulate(spec.params(), **spec.kwargs(self.scale, self.per_second))
        return self.cache[key]


def signal(kind: str, res: Simulation) -> tuple[np.ndarray, np.ndarray, str]:
    if kind.startswith("section"):
        zk = _core.default_section(res.params.length)
        return res.theta(zk), res.theta_dot(zk), "θ(z_k)"
    return res.q[0], res.qdot[0], "θ_1"


def window_mask(t: np.ndarray, window: tuple[float, float]) -> np.ndarray:
    span = window[1] - window[0]
    return (t >= window[0] - 1e-9 * span) & (t <= window[1] + 1e-9 * span)


def safe(func: Callable[..., Any], *args: Any, default: Any = math.nan, **kwargs: Any) -> Any:
    try:
        return func(*args, **kwargs)
    except (ValidationError, ValueError, IndexError, ZeroDivisionError):
        return default


def _modal_exchange(res: Simulation) -> float:
    """max over modes and t of |E_i(t) - E_i(0)| / H(0), E_i = M_i qdot_i^2/2 + K_i q_i^2/2."""
    c = res.coefficients
    e = _core.modal_energies(c.mass, c.stiffness, res.q, res.qdot)
    h0 = float(res.energy[0])
    return float(np.max(np.abs(e - e[:, :1]))) / abs(h0) if h0 else math.nan


def _quartic_share(res: Simulation) -> float:
    """max over t of |V(q)| / |H(0)|: the share of the energy in the quartic (nonlinear)
    potential (computed in the core)."""
    return float(res.coefficients.core_system().quartic_share(res.q, float(res.energy[0])))


def measure(spec: FigureSpec, runs: Runs, window: tuple[float, float]) -> list[CurveMetrics]:
    out = []
    for key, label, _ in spec.runs:
        res = runs[key]
        x, v, quantity = signal(spec.kind, res)
        mask = window_mask(res.t, window)
        xw, vw, tw = x[mask], v[mask], res.t[mask]
        # linear vs nonlinear: the frequency from the whole 10-s record (finer resolution)
        ft, fx = (res.t, x) if spec.kind.startswith("linear") else (tw, xw)
        peaks = safe(analysis.spectral_peaks, ft, fx, 4, default=[])
        extra: dict[str, float] = {
            "modulation_depth": safe(analysis.modulation_depth, xw),
            "hull_area": safe(analysis.hull_area, xw, vw),
            "phase_fill": safe(analysis.phase_fill, xw, vw),
            "quartic_share": _quartic_share(res) if res.coefficients.quartic_coef.size else 0.0,
        }
        if res.q.shape[0] > 1:
            extra["modal_exchange"] = _modal_exchange(res)
        out.append(
            CurveMetrics(
                label=label,
                quantity=quantity,
                window=(float(tw[0]), float(tw[-1])),
                amplitude=float(np.max(np.abs(xw))),
                rate_amplitude=float(np.max(np.abs(vw))),
                frequencies=tuple(p.frequency for p in peaks),
                frequency_amplitudes=tuple(float(p.amplitude) for p in peaks),
                record=(float(ft[0]), float(ft[-1])),
                growth=safe(analysis.amplitude_growth, xw),
                bounded=bool(safe(analysis.is_bounded, xw, default=False)),
                energy_drift=res.energy_drift(),
                extra=extra,
            )
        )
    return out


def _detuning(res: Simulation) -> float:
    """``2 f_1 - f_2`` (Hz) from the FFT of the first two modal coordinates."""
    f1 = safe(lambda: analysis.dominant_frequencies(res.t, res.q[0], 1)[0])
    f2 = safe(lambda: analysis.dominant_frequencies(res.t, res.q[1], 1)[0])
    return 2.0 * f1 - f2


def references(runs: Runs) -> dict[str, Any]:
    """Reference numbers the checks compare the curves with (one-mode exact values, linear
    frequencies, the phase shift, the two-mode measures, the parameter studies' frequencies)."""
    scale = runs.scale
    al = preset("aluminum")
    a1, a2, a3 = project(al, modes=1).duffing()
    w2, beta = a2 / a1, a3 / a1
    c1 = al.initial_velocities[0]
    amplitude = analysis.duffing_amplitude(w2, beta, c1)
    f_exact = analysis.duffing_frequency(w2, beta, amplitude)
    one = runs["one_mode"]
    peaks = safe(analysis.spectral_peaks, one.t, one.q[0], 5, default=[])
    third = None
    if peaks:
        f1 = peaks[0].frequency
        for p in peaks[1:]:
            if abs(p.frequency / (3 * f1) - 1) < 0.02:
                third = (p.frequency, p.amplitude / peaks[0].amplitude)
    st = analyse(al, modes=1)
    lin, nl = runs["linear10"], runs["nonlinear10"]
    times = [1.0 * scale, 10.0 * scale]
    shifts = [(t, float(safe(analysis.phase_shift, lin.t, lin.q[0], nl.q[0], t))) for t in times]
    f_lin = safe(lambda: analysis.dominant_frequencies(lin.t, lin.q[0], 1)[0])
    f_nl = safe(lambda: analysis.dominant_frequencies(nl.t, nl.q[0], 1)[0])
    # multi-mode references
    two, three = runs["two_mode"], runs["three_mode"]
    f2 = safe(analysis.dominant_frequencies, two.t, two.theta(200.0 / 3), 2, default=np.array([]))
    f_linear3 = project(al, modes=3).linear_frequencies / (2 * math.pi)
    detuning_nl = 2 * min(f2) - max(f2) if len(f2) == 2 else math.nan
    detuning_lin = 2 * f_linear3[0] - f_linear3[1]
    peaks3 = safe(analysis.spectral_peaks, three.t, three.theta(200.0 / 3), 4, default=[])
    third_component = None
    for p in peaks3:
        if abs(p.frequency / f_linear3[2] - 1) < 0.05 and peaks3:
            third_component = (p.frequency, p.amplitude, p.amplitude / peaks3[0].amplitude)
    zk = 200.0 / 3
    one_theta = one.theta(zk)
    one_rate = one.theta_dot(zk)
    steel = preset("steel")
    return {
        "one_mode": {
            "f_exact": f_exact,
            "f_linear": math.sqrt(w2) / (2 * math.pi),
            "amplitude": amplitude,
            "third_harmonic": third,
            "eigenvalue": float(st.mode_eigenvalues[0].imag),
            "classification": st.classification,
            "a": (a1, a2, a3),
        },
        "linear": {"f_lin": f_lin, "f_nl": f_nl, "f_exact": f_exact, "shifts": shifts},
        "section": {
            "f_linear3": list(f_linear3),
            "detuning_nl": detuning_nl,
            "detuning_lin": detuning_lin,
            "third_component": third_component,
            "depth2": safe(analysis.modulation_depth, two.theta(zk)),
            "depth2_linear": safe(analysis.modulation_depth, runs["two_mode_linear"].theta(zk)),
            "hull1": safe(analysis.hull_area, one_theta, one_rate),
            "hull2": safe(analysis.hull_area, two.theta(zk), two.theta_dot(zk)),
            "fill1": safe(analysis.phase_fill, one_theta, one_rate),
            "fill2": safe(analysis.phase_fill, two.theta(zk), two.theta_dot(zk)),
            "amp1": float(np.max(np.abs(one_theta))),
            "rate1": float(np.max(np.abs(one_rate))),
        },
        "params": {
            "f1_len": [float(project(al.replace(length=length), modes=1).linear_frequencies[0]) / (2 * math.pi)
                       for length in (100.0, 250.0, 500.0)],
            "f1_omega": [float(project(p, modes=1).linear_frequencies[0]) / (2 * math.pi)
                         for p in (al, al.replace(omega=OMEGA6))],
            "crit_ref": float(PDECoefficients.from_parameters(al).critical_speed(1)),
            "detuning_omega": [_detuning(runs[key]) for key in ("three_mode", "omega6")],
            "wave_ratio": PDECoefficients.from_parameters(steel).wave_speed
            / PDECoefficients.from_parameters(al).wave_speed,
        },
    }


def stability_rows() -> list[StabilityRow]:
    """The stability table: 1, 2, 3 modes on every parameter set of the figures."""
    rows = []
    for name, key, figs in PARAMETER_SETS:
        params = RUNS[key].params()
        material = "steel" if RUNS[key].preset == "steel" else "aluminium"
        for modes in (1, 2, 3):
            st = analyse(params, modes=modes)
            assert st.critical_speeds is not None
            for k, i in enumerate(st.indices.tolist()):
                lam = complex(st.mode_eigenvalues[k])
                rows.append(
                    StabilityRow(
                        parameter_set=name,
                        material=material,
                        length=params.length,
                        omega=params.omega,
                        modes=modes,
                        mode=i,
                        eigenvalue=lam,
                        linear_frequency_hz=float(st.linear_frequencies_hz[k]),
                        critical_speed=float(st.critical_speeds[k]),
                        mode_classification=st.mode_classification[k],
                        classification=st.classification,
                        figures=figs,
                    )
                )
    return rows


#: The models compared in the physics notes.
NOTE_MODELS = ("paper", "consistent")


@dataclass(frozen=True)
class PhysicsNotes:
    """Numbers behind the report's physics notes, per model (``"paper"``, ``"consistent"``)."""

    wave_speed_aluminium: dict[str, float]
    """Linear torsional wave speed sqrt(k2/k1) of Table 1's aluminium, m/s."""
    wave_speed_steel: dict[str, float]
    """The same for Table 3's steel, m/s."""
    bar_speed_aluminium: float
    """Longitudinal bar speed sqrt(E/rho) of the aluminium, m/s."""
    frequencies_hz: dict[str, tuple[float, float, float]]
    """First three free-free frequencies, 100 m aluminium at Omega = 0, Hz."""
    critical_speed_aluminium: dict[str, float]
    """Omega_crit,1 of Table 1 (100 m aluminium), rad/s; ``inf`` where there is none."""
    critical_speed_steel_2000: dict[str, float]
    """Omega_crit,1 of Table 3's steel at l = 2000 m, rad/s; ``inf`` where there is none."""


def physics_notes() -> PhysicsNotes:
    """The numbers of the physics notes, from :class:`drillstring.model.coefficients.PDECoefficients`."""
    al, steel = preset("aluminum"), preset("steel")

    def coef(p: Parameters, model: str) -> PDECoefficients:
        return PDECoefficients.from_parameters(p.replace(model=model))

    def hz(p: Parameters, model: str) -> tuple[float, float, float]:
        w = np.asarray(coef(p, model).linear_frequencies([1, 2, 3]), dtype=float) / (2 * math.pi)
        return (float(w[0]), float(w[1]), float(w[2]))

    return PhysicsNotes(
        wave_speed_aluminium={m: coef(al, m).wave_speed for m in NOTE_MODELS},
        wave_speed_steel={m: coef(steel, m).wave_speed for m in NOTE_MODELS},
        bar_speed_aluminium=_core.bar_speed(al.youngs_modulus, al.density),
        frequencies_hz={m: hz(al.replace(omega=0.0), m) for m in NOTE_MODELS},
        critical_speed_aluminium={m: float(coef(al, m).critical_speed(1)) for m in NOTE_MODELS},
        critical_speed_steel_2000={m: float(coef(steel.replace(length=2000.0), m).critical_speed(1))
                                   for m in NOTE_MODELS},
    )
