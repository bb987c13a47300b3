"""The paper's figures as data: the runs behind them, their time spans, what each plots and what
the paper claims about it.

:data:`RUNS` holds every simulation (a preset with some fields changed, a basis size, linear or
not), :data:`FIGURES` one :class:`FigureSpec` per figure over those runs, and
:data:`PARAMETER_SETS` the parameter sets of the stability table. All runs use the paper's
Galerkin basis (no rigid mode), DOP853 with ``rtol = 1e-10``, ``atol = 1e-13`` and
:data:`SAMPLES_PER_SECOND` output samples per second.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any, Optional, Union

from ..model.parameters import Parameters, preset

#: Solver settings of every run of the report.
METHOD = "dop853"
RTOL = 1e-10
ATOL = 1e-13
#: Output samples per second of simulated time (full run).
SAMPLES_PER_SECOND = 4000
#: Output samples per second of ``--quick``: 20 a period of the fastest mode of the figures (mode 3
#: of steel, 97.3 Hz; :data:`drillstring.limits.SAMPLES_PER_PERIOD`).
QUICK_SAMPLES_PER_SECOND = 2000
#: Time scale of ``--quick``.
QUICK_T_END_SCALE = 0.1
#: Resolution of the PNGs.
DPI = 120

PathLike = Union[str, "os.PathLike[str]"]

# --------------------------------------------------------------------------- specifications


@dataclass(frozen=True)
class RunSpec:
    """One simulation: a preset with some fields changed, a basis size, linear or not."""

    key: str
    preset: str
    changes: tuple[tuple[str, float], ...]
    modes: int
    t_end: float = 1.0
    nonlinear: bool = True
    description: str = ""

    def params(self) -> Parameters:
        return preset(self.preset).replace(**dict(self.changes))

    def samples(self, scale: float, per_second: int) -> int:
        return int(round(per_second * self.t_end * scale)) + 1

    def kwargs(self, scale: float, per_second: int) -> dict[str, Any]:
        """Keyword arguments of :func:`drillstring.solvers.modal` (besides ``params``)."""
        out: dict[str, Any] = {
            "modes": self.modes,
            "t_end": self.t_end * scale,
            "method": METHOD,
            "rtol": RTOL,
            "atol": ATOL,
            "samples": self.samples(scale, per_second),
        }
        if not self.nonlinear:
            out["nonlinear"] = False
        return out

    def python(self, scale: float, per_second: int) -> str:
        """The exact Python call."""
        p = f'ds.preset("{self.preset}")'
        if self.changes:
            p += ".replace(" + ", ".join(f"{k}={_num(v)}" for k, v in self.changes) + ")"
        kw = self.kwargs(scale, per_second)
        args = ", ".join(f"{k}={_literal(v)}" for k, v in kw.items())
        return f"ds.simulate({p}, {args})"

    def cli(self, scale: float, per_second: int) -> Optional[str]:
        """The equivalent ``drillstring simulate`` command (None for the linearised model)."""
        if not self.nonlinear:
            return None
        kw = self.kwargs(scale, per_second)
        flags = [f"--preset {self.preset}"]
        names = {"length": "--length", "omega": "--omega"}
        flags += [f"{names[k]} {_num(v)}" for k, v in self.changes]
        flags += [f"--modes {kw['modes']}", f"--t-end {_num(kw['t_end'])}", f"--rtol {RTOL:g}",
                  f"--atol {ATOL:g}", f"--samples {kw['samples']}"]
        return "drillstring simulate " + " ".join(flags) + f" --out {self.key}.csv"


def _literal(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return _num(value)
    return repr(value)


def _num(value: float) -> str:
    return repr(float(value)) if not float(value).is_integer() else f"{float(value):.1f}"


#: Omega of Figs. 12 and 13 (rad/s).
OMEGA6 = 2.0 * math.pi * 6.0

#: Every simulation behind the figures and their checks.
RUNS: dict[str, RunSpec] = {
    r.key: r
    for r in (
        RunSpec("one_mode", "aluminum", (), 1, description="one mode, Table 1, C1 = 0.1"),
        RunSpec("linear10", "aluminum", (), 1, t_end=10.0, nonlinear=False,
                description="one mode, linearised, 0 <= t <= 10"),
        RunSpec("nonlinear10", "aluminum", (), 1, t_end=10.0, description="one mode, 0 <= t <= 10"),
        RunSpec("two_mode", "aluminum", (), 2, description="two modes, Table 1, C = (0.1, 0.05)"),
        RunSpec("two_mode_linear", "aluminum", (), 2, nonlinear=False,
                description="two modes, linearised (reference for the claim of Fig. 6)"),
        RunSpec("three_mode", "aluminum", (), 3,
                description="three modes, Table 1 (l = 100 m, Omega = 2 pi 0.5 rad/s, aluminium)"),
        RunSpec("l250", "aluminum", (("length", 250.0),), 3, description="three modes, l = 250 m"),
        RunSpec("l500", "aluminum", (("length", 500.0),), 3, description="three modes, l = 500 m"),
        RunSpec("omega6", "aluminum", (("omega", OMEGA6),), 3,
                description="three modes, Omega = 2 pi 6 rad/s"),
        RunSpec("steel", "steel", (), 3, description="three modes, steel (Table 3)"),
    )
}


@dataclass(frozen=True)
class FigureSpec:
    """One figure of the paper: what it shows, from which runs, and what the paper claims."""

    number: int
    caption: str
    kind: str
    """``modal``, ``modal_phase``, ``linear``, ``linear_phase``, ``section`` or ``section_phase``."""
    runs: tuple[tuple[str, str, str], ...]
    """``(run key, curve label, CSV column tag)`` per curve."""
    claim: str
    """The paper's claim about the figure, one sentence (from its text)."""
    window: tuple[float, float] = (0.0, 1.0)
    name: str = ""
    """Short name for progress lines."""

    @property
    def stem(self) -> str:
        return f"fig{self.number:02d}"


_LEN = (("three_mode", "l = 100 m", "l100"), ("l250", "l = 250 m", "l250"), ("l500", "l = 500 m", "l500"))
_OMEGA = (("three_mode", "Ω = 2π·0.5 rad/s", "omega_2pi0.5"), ("omega6", "Ω = 2π·6 rad/s", "omega_2pi6"))
_MAT = (("three_mode", "aluminium (Table 1)", "aluminium"), ("steel", "steel (Table 3)", "steel"))
_LIN = (("linear10", "linear", "linear"), ("nonlinear10", "nonlinear", "nonlinear"))

#: The fifteen figures of section 3 of the paper.
FIGURES: tuple[FigureSpec, ...] = (
    FigureSpec(1, "Fig. 1: One-mode nonlinear torsional response for the reference parameter set",
               "modal", (("one_mode", "one mode, nonlinear", "one_mode"),),
               "The one-mode response is a bounded, regular oscillation of small amplitude, close to "
               "harmonic: the cubic term only corrects the linear stiffness.", name="one-mode response"),
    FigureSpec(2, "Fig. 2: Phase portrait of the one-mode nonlinear torsional response",
               "modal_phase", (("one_mode", "one mode, nonlinear", "one_mode"),),
               "The trajectory stays bounded around the equilibrium and has a centre-type structure.",
               name="one-mode phase portrait"),
    FigureSpec(3, "Fig. 3: Linear (blue curve) and nonlinear (orange curve) one-mode torsional "
               "responses for 0 ≤ t ≤ 1", "linear", _LIN,
               "Both responses are bounded and their amplitudes remain close, but the nonlinear "
               "response gradually develops a phase shift: the cubic term changes the effective "
               "frequency, not the amplitude level.", name="linear vs nonlinear"),
    FigureSpec(4, "Fig. 4: Phase portraits of the linear (blue curve) and nonlinear (orange curve) "
               "one-mode torsional responses", "linear_phase", _LIN,
               "Both trajectories are bounded, centre-type curves around the equilibrium: the "
               "nonlinearity changes the numbers, not the stability type.",
               name="linear vs nonlinear phase"),
    FigureSpec(5, "Fig. 5: Linear (blue curve) and nonlinear (orange curve) one-mode torsional "
               "responses for 9 ≤ t ≤ 10", "linear", _LIN,
               "On 9 ≤ t ≤ 10 both responses remain bounded and the accumulated phase shift "
               "between them is still visible.", window=(9.0, 10.0), name="linear vs nonlinear, 9-10 s"),
    FigureSpec(6, "Fig. 6: Two-mode nonlinear torsional response at the selected section "
               "z_k = 2l/3 for the reference parameter set in Table 1", "section",
               (("two_mode", "two modes, z_k = 2l/3", "two_mode"),),
               "The two-mode waveform is no longer purely regular: it superposes the first two modal "
               "coordinates, and the amplitude modulation is caused by nonlinear coupling between them.",
               name="two-mode response"),
    FigureSpec(7, "Fig. 7: Phase plane projection of the two-mode nonlinear torsional response",
               "section_phase", (("two_mode", "two modes, z_k = 2l/3", "two_mode"),),
               "The projection is bounded but no longer a simple centre-type curve: it occupies a "
               "wider, more structured region than the one-mode portrait.", name="two-mode phase plane"),
    FigureSpec(8, "Fig. 8: Three-mode nonlinear torsional response at the selected section "
               "z_k = 2l/3 for the reference parameter set in Table 1", "section",
               (("three_mode", "three modes, z_k = 2l/3", "three_mode"),),
               "The third mode adds a higher-frequency component; the waveform becomes more modulated "
               "than with two modes.", name="three-mode response"),
    FigureSpec(9, "Fig. 9: Phase plane projection of the three-mode nonlinear torsional response",
               "section_phase", (("three_mode", "three modes, z_k = 2l/3", "three_mode"),),
               "The projection remains bounded and its structure is more developed than in the "
               "two-mode case.", name="three-mode phase plane"),
    FigureSpec(10, "Fig. 10: Three-mode torsional response at the selected section z_k = 2l/3 for "
               "different drill string lengths", "section", _LEN,
               "Going from l = 100 m to 500 m changes the amplitude level and the modulation pattern; "
               "longer strings show larger variations of θ(z_k, t).", name="lengths"),
    FigureSpec(11, "Fig. 11: Phase-plane projections for different drill string lengths",
               "section_phase", _LEN,
               "As the length increases the occupied region of the phase plane becomes wider and "
               "more structured; all projections remain bounded.", name="lengths, phase plane"),
    FigureSpec(12, "Fig. 12: Three-mode torsional response at the selected section z_k = 2l/3 for "
               "different angular velocities", "section", _OMEGA,
               "The rotation speed changes the modulation structure and the rate of amplitude "
               "development; the response stays bounded in both cases.", name="rotation speeds"),
    FigureSpec(13, "Fig. 13: Phase-plane projections for different angular velocities",
               "section_phase", _OMEGA,
               "Both projections are bounded but clearly differ in the structure of their "
               "trajectories.", name="rotation speeds, phase plane"),
    FigureSpec(14, "Fig. 14: Three-mode torsional response at the selected section z_k = 2l/3 for "
               "the aluminium and steel drill string", "section", _MAT,
               "Steel instead of aluminium noticeably changes the amplitude level and the modulation "
               "envelope; the motion remains bounded.", name="materials"),
    FigureSpec(15, "Fig. 15: Phase-plane projections for aluminium and steel drill string",
               "section_phase", _MAT,
               "The aluminium and steel projections differ in configuration and occupied region.",
               name="materials, phase plane"),
)

#: The parameter sets of the figures, for the stability table: (name, run key, figures).
PARAMETER_SETS: tuple[tuple[str, str, str], ...] = (
    ("aluminium, l = 100 m, Ω = 2π·0.5 rad/s (Table 1)", "three_mode", "1-10, 12, 14"),
    ("aluminium, l = 250 m", "l250", "10, 11"),
    ("aluminium, l = 500 m", "l500", "10, 11"),
    ("aluminium, Ω = 2π·6 rad/s", "omega6", "12, 13"),
    ("steel (Table 3), l = 100 m", "steel", "14, 15"),
)
