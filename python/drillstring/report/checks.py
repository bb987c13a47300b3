"""The paper's claims checked against the measurements: one checker per group of figures.

Each :class:`Check` states its criterion (the sentence the report prints after the verdict) and
returns the findings (sentences with the numbers) and the verdict, ``"supported"``,
``"partly supported"`` or ``"contradicted"``. Every check starts from boundedness: a figure with an
unbounded curve is contradicted whatever else holds.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Callable

from .fmt import hz, pct, sci
from .measure import CurveMetrics
from .specs import OMEGA6

Verdict = str
Findings = tuple[list[str], Verdict]

_BOUNDED = "every curve is bounded (see the settings above; otherwise contradicted)"
_CHANGED = "changes by at least 10 % of its value"


@dataclass(frozen=True)
class Check:
    """A checker of a group of figures and the criterion it applies to each."""

    criteria: Mapping[int, str]
    """Figure number to criterion."""
    assess: Callable[[int, list[CurveMetrics], dict[str, Any]], Findings]
    """``(figure number, curves, reference values) -> (findings, verdict)``."""


def _start(curves: Sequence[CurveMetrics]) -> Verdict:
    return "supported" if all(c.bounded for c in curves) else "contradicted"


def _partly(verdict: Verdict) -> Verdict:
    return "partly supported" if verdict == "supported" else verdict


def _changed(a: float, b: float, threshold: float = 0.10) -> bool:
    """Whether ``b`` differs from ``a`` by at least ``threshold`` (relative)."""
    return bool(abs(b / a - 1.0) >= threshold) if a else bool(b)


def _bounded(curves: Sequence[CurveMetrics]) -> str:
    if len(curves) == 1:
        c = curves[0]
        return (f"Bounded: {'yes' if c.bounded else 'NO'} (max |x| over the second half of the window "
                f"/ first half = {c.growth:.3f}); energy drift {sci(c.energy_drift, 1)}.")
    verdict = "bounded" if all(c.bounded for c in curves) else "NOT all bounded"
    parts = [f"{c.label}: growth {c.growth:.2f}, energy drift {sci(c.energy_drift, 1)}" for c in curves]
    return (f"The curves are {verdict} (growth = max |x| over the second half of the window / "
            "first half; " + "; ".join(parts) + ").")


# --------------------------------------------------------------------------- Figs. 1-2


def one_mode(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """The one-mode response and its phase portrait: bounded, and the equilibrium is a centre."""
    verdict = _start(curves)
    c0, one = curves[0], ref["one_mode"]
    found = [f"Amplitude max |θ_1| = {sci(c0.amplitude, 4)} rad (Table 2 reference 5.061e-4 rad), "
             f"max |dθ_1/dt| = {c0.rate_amplitude:.4f} rad/s (= C_1, energy conservation)."]
    if n == 1:
        harm = one["third_harmonic"]
        found.append(
            f"Dominant frequency {c0.frequencies[0]:.3f} Hz (FFT over {c0.record[1] - c0.record[0]:g} s; "
            f"exact Duffing value {one['f_exact']:.3f} Hz, linear {one['f_linear']:.3f} Hz); "
            + (f"third harmonic at {harm[0]:.1f} Hz with {harm[1] * 100:.2f} % of the fundamental's "
               "amplitude: close to harmonic." if harm else
               "no harmonic above 0.1 % of the fundamental: close to harmonic.")
        )
    else:
        found.append(
            f"Jacobian eigenvalues ±{one['eigenvalue']:.2f}i rad/s (= ±i sqrt(a2/a1), eq. 29): "
            f"a {one['classification']}; the orbit is one closed curve retraced "
            f"{c0.frequencies[0] * (c0.window[1] - c0.window[0]):.1f} times (energy drift "
            f"{sci(c0.energy_drift, 1)})."
        )
    found.append(_bounded(curves))
    if one["classification"] != "centre":
        verdict = "contradicted"
    return found, verdict


# --------------------------------------------------------------------------- Figs. 3-5


def linear_vs_nonlinear(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Linear against nonlinear: bounded, amplitudes within 10 %, the phase shift reported."""
    verdict = _start(curves)
    lin, nl = curves
    cmp = ref["linear"]
    found = [
        f"Amplitudes: linear {sci(lin.amplitude, 4)} rad, nonlinear {sci(nl.amplitude, 4)} rad "
        f"({pct(nl.amplitude, lin.amplitude)}): close.",
        f"Frequencies (FFT over {lin.record[1] - lin.record[0]:g} s): linear {cmp['f_lin']:.4f} Hz, "
        f"nonlinear {cmp['f_nl']:.4f} Hz ({pct(cmp['f_nl'], cmp['f_lin'])}; exact Duffing "
        f"{cmp['f_exact']:.4f} Hz).",
    ]
    shifts = cmp["shifts"]
    found.append(
        "Accumulated phase shift of the nonlinear response (zero crossings): "
        + ", ".join(f"{math.degrees(s):.0f}° ({s / (2 * math.pi):.2f} cycles) at t = {t:g} s"
                    for t, s in shifts)
        + "; it grows linearly with t (constant frequency offset)."
    )
    if n == 3 and shifts and abs(shifts[0][1]) > 0.75 * math.pi:
        found.append(
            f"Note: at t = {shifts[0][0]:g} s the two curves are already "
            f"{math.degrees(abs(shifts[0][1])):.0f}° apart (nearly in antiphase), so 'gradually' "
            f"means over the {cmp['f_nl'] * shifts[0][0]:.0f} cycles of the window, not a small offset."
        )
    if n == 4:
        found.append(
            f"Both have the same linearisation: eigenvalues ±{ref['one_mode']['eigenvalue']:.2f}i "
            "rad/s, a centre; max |dθ_1/dt| = "
            f"{lin.rate_amplitude:.4f} (linear) and {nl.rate_amplitude:.4f} rad/s (nonlinear)."
        )
    found.append(_bounded(curves))
    if abs(nl.amplitude / lin.amplitude - 1) > 0.1:
        found.append("Contradicts the claim: the amplitudes differ by more than 10 %.")
        verdict = "contradicted"
    return found, verdict


# --------------------------------------------------------------------------- Figs. 6-9


def _section_amplitude(c0: CurveMetrics, sec: dict[str, Any]) -> str:
    return (f"Amplitude max |θ(z_k)| = {sci(c0.amplitude, 4)} rad, max |θ_dot(z_k)| = "
            f"{c0.rate_amplitude:.4f} rad/s; dominant frequencies {hz(c0.frequencies)} "
            f"(linear modes {hz(sec['f_linear3'])}).")


def two_mode_response(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Fig. 6: the modulation is a nonlinear effect (deeper than the linearised model's)."""
    verdict = _start(curves)
    c0, sec = curves[0], ref["section"]
    found = [_section_amplitude(c0, sec)]
    det_nl, det_lin = sec["detuning_nl"], sec["detuning_lin"]
    depth, depth_lin = c0.extra["modulation_depth"], sec["depth2_linear"]
    found.append(
        f"Modulation depth of the half-cycle peaks {depth:.2f}, against {depth_lin:.3f} for the "
        "linearised two-mode model with the same initial velocities: the modulation is a "
        "nonlinear effect. Mechanism: the modal energies M_i q̇_i²/2 + K_i q_i²/2 change by "
        f"at most {c0.extra['modal_exchange'] * 100:.1f} % of the total over the window, so "
        "the modes exchange little energy; the nonlinear frequency shifts detune the near 1:2 "
        f"ratio of the two modes, 2 f_1 - f_2 = {det_nl:+.3f} Hz measured (beat period "
        f"{1 / abs(det_nl):.2f} s) against {det_lin:+.4f} Hz for the linear frequencies, and "
        "the shape of the superposition drifts with that beat."
    )
    if not depth > 5 * depth_lin:
        found.append("Contradicts the claim: the linearised model is as modulated as the nonlinear one.")
        verdict = "contradicted"
    found.append(_bounded(curves))
    return found, verdict


def three_mode_response(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Fig. 8: a component at mode 3's frequency, and at least the two-mode modulation."""
    verdict = _start(curves)
    c0, sec = curves[0], ref["section"]
    found = [_section_amplitude(c0, sec)]
    third = sec["third_component"]
    depth, depth2 = c0.extra["modulation_depth"], sec["depth2"]
    found.append(
        (f"Component at {third[0]:.2f} Hz (mode 3) with amplitude {sci(third[1], 2)} rad, "
         f"{third[2] * 100:.0f} % of the fundamental: the added higher-frequency component is "
         "there (the ripples on each cycle). " if third else
         "Contradicts the claim: no component near the third mode's frequency was found. ")
        + f"Modulation depth {depth:.2f} against {depth2:.2f} with two modes; modal energy "
        f"exchange {c0.extra['modal_exchange'] * 100:.1f} % of the total."
    )
    if not third:
        verdict = "contradicted"
    elif depth < depth2:
        found.append(
            f"Only partly supported: by the envelope of the half-cycle peaks the three-mode "
            f"waveform is less modulated than the two-mode one ({depth:.2f} vs {depth2:.2f}); "
            "it is more complex in shape (ripples), not in its envelope."
        )
        verdict = _partly(verdict)
    found.append(_bounded(curves))
    return found, verdict


def phase_region(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Figs. 7 and 9: the projection occupies a wider region than the portrait with one mode fewer,
    and fills more of it."""
    verdict = _start(curves)
    c0, sec = curves[0], ref["section"]
    found = [_section_amplitude(c0, sec)]
    ref_area, ref_fill, ref_name = (sec["hull2"], sec["fill2"], "two-mode") if n == 9 else (
        sec["hull1"], sec["fill1"], "one-mode")
    found.append(
        f"Occupied region (convex hull of the projection) {sci(c0.extra['hull_area'], 3)} rad²/s "
        f"against {sci(ref_area, 3)} rad²/s for the {ref_name} portrait at the same section; "
        f"the trajectory passes through {c0.extra['phase_fill'] * 100:.0f} % of it (fill "
        f"fraction; {ref_name}: {ref_fill * 100:.0f} %). Extents |θ| ≤ {sci(c0.amplitude, 3)} rad, "
        f"|θ_dot| ≤ {c0.rate_amplitude:.4f} rad/s (one mode at z_k: {sci(sec['amp1'], 3)} rad, "
        f"{sec['rate1']:.4f} rad/s)."
    )
    if not c0.extra["hull_area"] > ref_area:
        found.append(f"Contradicts the claim: the occupied region is not wider than the {ref_name} one.")
        verdict = "contradicted"
    elif not c0.extra["phase_fill"] > ref_fill:
        found.append(f"Only partly supported: the projection is wider but fills less of its "
                     f"region than the {ref_name} one.")
        verdict = _partly(verdict)
    found.append(_bounded(curves))
    return found, verdict


# --------------------------------------------------------------------------- Figs. 10-15


def _measured(curves: Sequence[CurveMetrics]) -> str:
    lines = [
        f"{c.label}: max |θ(z_k)| = {sci(c.amplitude, 3)} rad, max |θ_dot| = {c.rate_amplitude:.4f} rad/s, "
        f"dominant {hz(c.frequencies, 2)}, modulation depth {c.extra['modulation_depth']:.2f}, "
        f"hull area {sci(c.extra['hull_area'], 2)} rad²/s, fill {c.extra['phase_fill'] * 100:.0f} %, "
        f"quartic energy share {c.extra['quartic_share'] * 100:.1f} %"
        for c in curves
    ]
    return "Measured: " + "; ".join(lines) + "."


def lengths(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Figs. 10 and 11: the amplitude (Fig. 10) or the occupied region (Fig. 11) grows with l."""
    verdict = _start(curves)
    found = [_measured(curves)]
    par = ref["params"]
    series = [c.amplitude for c in curves] if n == 10 else [c.extra["hull_area"] for c in curves]
    what = "amplitude" if n == 10 else "occupied region"
    if all(b > a for a, b in zip(series, series[1:])):
        found.append(
            f"The {what} grows with the length ({series[-1] / series[0]:.1f}x from 100 to 500 m), "
            "as claimed. The linear frequencies fall as 1/l "
            f"({hz(par['f1_len'])} for mode 1), so the same initial velocities C_i give larger "
            "angles, and the quartic energy share rises: at l = 500 m the motion is strongly "
            f"nonlinear (dominant {curves[-1].frequencies[0]:.1f} Hz against a linear "
            f"{par['f1_len'][-1]:.1f} Hz)."
        )
    else:
        found.append(f"Contradicts the claim: the {what} does not increase monotonically with the "
                     f"length ({', '.join(sci(a, 3) for a in series)}).")
        verdict = "contradicted"
    fills = [c.extra["phase_fill"] for c in curves]
    if n == 11 and not all(b > a for a, b in zip(fills, fills[1:])):
        found.append(
            "'More structured' has no single measure; by the fill fraction (share of the occupied "
            "region the trajectory passes through) the longer strings' projections are not denser: "
            + " → ".join(f"{f * 100:.0f} %" for f in fills) + "."
        )
    found.append(_bounded(curves))
    return found, verdict


def rotation(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Figs. 12 and 13: the faster rotation changes the response (Fig. 12: modulation depth or
    amplitude) or the projection (Fig. 13: occupied region or fill fraction) by 10 % or more."""
    verdict = _start(curves)
    found = [_measured(curves)]
    par = ref["params"]
    a, b = curves
    found.append(
        f"Ω = 2π·6 rad/s lowers the linear first-mode frequency from {par['f1_omega'][0]:.2f} to "
        f"{par['f1_omega'][1]:.2f} Hz (k6 = ρ I_p Ω² softens every mode; critical speed "
        f"{par['crit_ref']:.1f} rad/s, Ω/Ω_crit = {OMEGA6 / par['crit_ref']:.2f}); dominant "
        f"frequency {pct(b.frequencies[0], a.frequencies[0])}, amplitude "
        f"{pct(b.amplitude, a.amplitude)}, modulation depth {a.extra['modulation_depth']:.2f} → "
        f"{b.extra['modulation_depth']:.2f}, occupied region "
        f"{pct(b.extra['hull_area'], a.extra['hull_area'])}."
    )
    if n == 12:
        changed = _changed(a.extra["modulation_depth"], b.extra["modulation_depth"]) or _changed(
            a.amplitude, b.amplitude)
        what = "the modulation structure and amplitude change"
    else:
        changed = any(_changed(a.extra[k], b.extra[k]) for k in ("hull_area", "phase_fill"))
        what = "the projections differ in occupied region and fill fraction"
        found.append(
            f"Fill fraction {a.extra['phase_fill'] * 100:.0f} % → {b.extra['phase_fill'] * 100:.0f} %: "
            "at Ω = 2π·6 rad/s the projection is a narrow band (2 f_1 - f_2 = "
            f"{par['detuning_omega'][1]:+.2f} Hz against {par['detuning_omega'][0]:+.2f} Hz, so the "
            "superposition drifts much more slowly) instead of a precessing orbit filling the disc."
        )
    if not changed:
        found.append(f"Only partly supported: {what} by less than 10 %.")
        verdict = _partly(verdict)
    found.append(_bounded(curves))
    return found, verdict


def materials(n: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Figs. 14 and 15: steel changes the response (Fig. 14: modulation depth or amplitude) or the
    projection (Fig. 15: occupied region or fill fraction) by 10 % or more."""
    verdict = _start(curves)
    found = [_measured(curves)]
    par = ref["params"]
    a, b = curves
    found.append(
        f"Steel vs aluminium: amplitude {pct(b.amplitude, a.amplitude)}, dominant frequency "
        f"{pct(b.frequencies[0], a.frequencies[0])}, modulation depth "
        f"{a.extra['modulation_depth']:.2f} → {b.extra['modulation_depth']:.2f}, occupied region "
        f"{pct(b.extra['hull_area'], a.extra['hull_area'])}, fill fraction "
        f"{a.extra['phase_fill'] * 100:.0f} % → {b.extra['phase_fill'] * 100:.0f} %. "
        "The linear frequencies scale with sqrt(G/ρ), which differs by only "
        f"{par['wave_ratio'] * 100 - 100:+.1f} % between the two metals: the 3x higher Young's "
        "modulus is almost cancelled by the 2.9x higher density."
    )
    keys = ("modulation_depth",) if n == 14 else ("hull_area", "phase_fill")
    metrics = [(a.extra[k], b.extra[k]) for k in keys]
    if n == 14:
        metrics.append((a.amplitude, b.amplitude))
    if not any(_changed(x, y) for x, y in metrics):
        found.append(
            "Only partly supported: "
            + ("the amplitude level and the modulation envelope change" if n == 14 else
               "the occupied region and its fill fraction change")
            + " by less than 10 %; the curves look distinct mainly because the frequency "
            f"difference ({b.frequencies[0] - a.frequencies[0]:.2f} Hz) dephases them over the window."
        )
        verdict = _partly(verdict)
    found.append(_bounded(curves))
    return found, verdict


#: Every figure's checker and criterion.
CHECKS: tuple[Check, ...] = (
    Check({n: f"supported if {_BOUNDED} and the one-mode equilibrium is a centre." for n in (1, 2)}, one_mode),
    Check({n: f"supported if {_BOUNDED} and the linear and nonlinear amplitudes are within 10 % of each "
              "other (otherwise contradicted)." for n in (3, 4, 5)}, linear_vs_nonlinear),
    Check({6: f"supported if {_BOUNDED} and the modulation depth is more than 5x that of the linearised "
              "two-mode model (otherwise contradicted)."}, two_mode_response),
    Check({n: f"supported if {_BOUNDED}, the occupied region (convex hull) is larger than the {ref} "
              "portrait's (otherwise contradicted) and the fill fraction is higher (otherwise partly)."
           for n, ref in ((7, "one-mode"), (9, "two-mode"))}, phase_region),
    Check({8: f"supported if {_BOUNDED}, a spectral component lies within 5 % of mode 3's linear frequency "
              "(otherwise contradicted) and the modulation depth is at least the two-mode one's "
              "(otherwise partly)."}, three_mode_response),
    Check({10: f"supported if {_BOUNDED} and the amplitude grows with the length (otherwise contradicted).",
           11: f"supported if {_BOUNDED} and the occupied region grows with the length (otherwise "
               "contradicted)."}, lengths),
    Check({12: f"supported if {_BOUNDED} and the modulation depth or the amplitude {_CHANGED} (otherwise "
               "partly).",
           13: f"supported if {_BOUNDED} and the occupied region or the fill fraction {_CHANGED} "
               "(otherwise partly)."}, rotation),
    Check({14: f"supported if {_BOUNDED} and the modulation depth or the amplitude {_CHANGED} (otherwise "
               "partly).",
           15: f"supported if {_BOUNDED} and the occupied region or the fill fraction {_CHANGED} "
               "(otherwise partly)."}, materials),
)

#: How each figure's verdict is decided from the numbers measured on it.
CRITERIA: dict[int, str] = dict(sorted((n, text) for check in CHECKS for n, text in check.criteria.items()))

_BY_FIGURE: dict[int, Check] = {n: check for check in CHECKS for n in check.criteria}


def assess(number: int, curves: list[CurveMetrics], ref: dict[str, Any]) -> Findings:
    """Findings (sentences with the numbers) and the verdict for figure ``number``."""
    return _BY_FIGURE[number].assess(number, curves, ref)
