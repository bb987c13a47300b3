"""One number in one place: the defaults and limits the core holds are what Python uses, and no
Python source re-derives them."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core, limits
from drillstring.errors import ValidationError
from drillstring.model import coefficients, galerkin, parameters
from drillstring.solvers import pde
from drillstring.solvers.modal import _default_dt
from drillstring.solvers.trajectory import default_section
from drillstring.studies import analysis, stability, sweeps

PACKAGE = Path(ds.__file__).parent
CORE = Path(__file__).resolve().parents[1] / "rust" / "core" / "src"


def _source(module: Any) -> str:
    return Path(module.__file__).read_text(encoding="utf-8")


def _spy(monkeypatch: pytest.MonkeyPatch, names: tuple[str, ...]) -> list[str]:
    """Wraps the ``_core`` functions ``names`` so that each call is recorded."""
    calls: list[str] = []

    def wrap(name: str, real: Callable[..., Any]) -> Callable[..., Any]:
        def recorded(*args: Any, **kwargs: Any) -> Any:
            calls.append(name)
            return real(*args, **kwargs)

        return recorded

    for name in names:
        monkeypatch.setattr(_core, name, wrap(name, getattr(_core, name)))
    return calls


def test_paper_model_linear_numbers_are_computed_by_the_core(monkeypatch: pytest.MonkeyPatch) -> None:
    params = ds.preset("aluminum")
    k = ds.PDECoefficients.from_parameters(params)
    model = ds.project(params, modes=1)
    names = ("frequency_squared", "linear_frequencies", "wave_speed", "critical_speeds", "modal_rates",
             "duffing", "modal_jacobian", "modal_stability", "mode_shapes", "check_damping_rate")
    calls = _spy(monkeypatch, names)
    k.frequency_squared(1)
    assert calls == ["frequency_squared"]
    k.linear_frequencies([1, 2])
    assert calls[-1] == "linear_frequencies"
    _ = k.wave_speed
    k.critical_speed(1)
    _ = model.linear_frequencies
    model.duffing()
    model.basis(1.0)
    stability.analyse(params, modes=1)
    assert set(calls) == set(names)


def test_paper_model_force_and_acceleration_are_the_core_systems() -> None:
    model = ds.project(ds.preset("steel"), modes=3, rigid_mode=True)
    q = np.array([0.01, -0.02, 0.03, 0.005])
    system = model.core_system()
    assert np.array_equal(model.cubic_force(q), system.quartic_gradient(q))
    assert np.array_equal(model.acceleration(q), system.acceleration(q))


def test_paper_model_k6_and_damping_rule_are_the_cores() -> None:
    for name in ("aluminum", "steel"):
        for model in ("paper", "consistent"):
            p = ds.preset(name).replace(model=model, omega=7.25)
            k = ds.PDECoefficients.from_parameters(p)
            rate = k.k6_per_omega_squared
            assert rate is not None and _core.k6(rate, p.omega) == k.k6
            # the sweep's per-run k6 (coefficients cached without omega) is the same number
            assert sweeps._coefficients(p, {}) == k.as_tuple()
    assert _core.k6(0.0, 1e200) == 0.0 and math.isinf(_core.k6(1.0, 1e200))
    with pytest.raises(ValidationError) as core_error:
        _core.check_damping_rate(-1.0)
    for bad in (-1.0, math.nan, "1", True):
        with pytest.raises(ValidationError) as info:
            parameters.check_damping_rate(bad)
        assert info.value.field == "damping_rate" and info.value.allowed == core_error.value.allowed


def test_paper_model_re_derivations_are_gone() -> None:
    galerkin_src, coefficients_src = _source(galerkin), _source(coefficients)
    stability_src, sweeps_src = _source(stability), _source(sweeps)
    # the basis, the force, the frequencies and the Duffing coefficients: no numpy formula left
    for text in ("np.cos(", "np.sin(", "bincount", "np.sqrt(", "self.length / 2.0", "stiffness / self.mass"):
        assert text not in galerkin_src, text
    for text in ("math.sqrt", "np.sqrt", "math.pi", "** 2"):
        assert text not in coefficients_src, text
    for text in ("np.linalg", "np.sqrt", "0.25 * c", "1e-12 * scale", "np.mean", "np.eye"):
        assert text not in stability_src, text
    assert not re.search(r"omega\s*\*\*\s*2", sweeps_src)
    assert "_core.k6(" in sweeps_src
    # the core: one mode shape, one unstable-mode rule, one k6
    batch = (CORE / "sweep" / "batch.rs").read_text(encoding="utf-8")
    integrals = (CORE / "sweep" / "integrals.rs").read_text(encoding="utf-8")
    model = (CORE / "model.rs").read_text(encoding="utf-8")
    assert "stability::unstable_modes" in batch and "k < 0.0" not in batch
    assert "PI / length * z).cos()" not in integrals and "map(|&i| mode_shape(i, z, length))" in integrals
    assert model.count("omega.powf(2.0)") == 1 and "k6(k1, p.omega)" in model
    # the stub names what the package calls
    stub = (PACKAGE / "_core.pyi").read_text(encoding="utf-8")
    for name in ("frequency_squared", "critical_speeds", "modal_stability", "mode_shapes", "duffing", "k6",
                 "check_damping_rate", "quartic_gradient"):
        assert f"def {name}(" in stub, name


#: (Python name, the core's constant, the value the documentation states).
CONSTANTS = [
    (limits.ADAPTIVE_MAX_STEPS, "ADAPTIVE_MAX_STEPS", 10_000_000),
    (limits.FIXED_MAX_STEPS, "FIXED_MAX_STEPS", 100_000_000),
    (pde.MAX_NODES, "PDE_MAX_NODES", 10_000_000),
    (pde.MIN_RESOLVED_MODES, "PDE_MIN_RESOLVED_MODES", 3),
    (pde.MODE_CONTENT_SHARE, "PDE_MODE_CONTENT_SHARE", 1e-3),
    (analysis.BOUNDED_GROWTH, "BOUNDED_GROWTH", 1.5),
    (analysis.PHASE_FILL_BINS, "PHASE_FILL_BINS", 32),
    (analysis.DEFAULT_PAD, "SPECTRAL_PAD", 8),
    (analysis.DEFAULT_THRESHOLD, "PEAK_THRESHOLD", 1e-3),
]


@pytest.mark.parametrize(("python", "core", "documented"), CONSTANTS, ids=[c[1] for c in CONSTANTS])
def test_constants_are_the_cores(python, core, documented):
    assert python == getattr(_core, core) == documented
    assert type(python) is type(documented)


def test_constants_defaults_of_the_signal_functions_are_the_cores():
    import inspect

    assert inspect.signature(analysis.is_bounded).parameters["factor"].default == _core.BOUNDED_GROWTH
    assert inspect.signature(analysis.phase_fill).parameters["bins"].default == _core.PHASE_FILL_BINS


def test_constants_default_section_is_two_thirds_of_the_length():
    for length in (100.0, 200.0, 1000.0, 3.0, 7.5):
        assert default_section(length) == _core.default_section(length) == 2.0 * length / 3.0
    res = ds.simulate(ds.preset("aluminum"), modes=1, t_end=0.01)
    assert ds.plots._section(res, None) == _core.default_section(res.params.length)
    assert ds.studies.sweeps._default_z({"length": 150.0}, None) == 100.0
    assert math.isnan(ds.studies.sweeps._default_z({"length": "x"}, None))


def test_constants_step_counts_and_default_steps_are_the_cores():
    assert limits.fixed_steps(1.0, 0.1) == _core.fixed_steps(1.0, 0.1) == 10
    assert limits.fixed_steps(1.0, 0.3) == 4 and limits.fixed_steps(1.0, 2.0) == 1
    assert limits.fixed_steps(1.0, 1e-300) == _core.MAX_STEP_COUNT == 2**62
    # the modal default step: 1e-4 s, or 1/100 of the shortest period (independent arithmetic)
    coefficients = ds.project(ds.preset("aluminum"), modes=12)
    w_max = max(math.sqrt(abs(k / m)) for k, m in zip(coefficients.stiffness, coefficients.mass))
    assert _default_dt(coefficients) == min(_core.DEFAULT_FIXED_DT, 2 * math.pi / w_max / 100)
    assert _default_dt(coefficients) < _core.DEFAULT_FIXED_DT == 1e-4
    slow = ds.project(ds.preset("aluminum"), modes=1)
    assert _default_dt(slow) == 1e-4
    # the PDE: half the CFL limit h / c
    params = ds.preset("aluminum")
    system = pde.pde_system(params, 101)
    k1, k2 = system.coefficients[:2]
    assert system.default_dt() == 0.5 * (params.length / 100) / math.sqrt(k2 / k1)


def test_constants_a_fixed_step_solve_uses_the_cores_default_step():
    params = ds.preset("aluminum")
    res = ds.simulate(params, modes=3, t_end=0.01, method="rk4", samples=None, t_eval=None)
    dt = _core.default_fixed_dt(np.asarray(res.coefficients.mass), np.asarray(res.coefficients.stiffness))
    assert res.t.size == _core.fixed_steps(0.01, dt) + 1
    sol = ds.solve_pde(params, nodes=41, t_end=2e-3, method="verlet")
    assert sol.t.size == _core.fixed_steps(2e-3, pde.pde_system(params, 41).default_dt()) + 1


def test_constants_the_pde_default_output_resolves_the_cores_mode():
    params = ds.preset("aluminum")
    system = pde.pde_system(params, 81)
    z = np.asarray(system.z)
    velocity = np.cos(5 * np.pi * z / params.length) + 0.1 * np.cos(9 * np.pi * z / params.length)
    hz, mode = pde.fastest_mode(params, np.zeros(z.size), velocity)
    assert mode == "mode 9"
    k = ds.model.coefficients.PDECoefficients.from_parameters(params)
    assert hz == pytest.approx(float(k.linear_frequencies(9)) / (2 * math.pi), rel=1e-15)
    assert pde.fastest_mode(params, np.zeros(z.size), np.zeros(z.size))[1] == f"mode {_core.PDE_MIN_RESOLVED_MODES}"


#: Re-derivations of the core's numbers that must not appear in the package's Python source.
FORBIDDEN = {
    "the section rule 2 l / 3": re.compile(r"\b2(\.0)?\s*\*\s*[\w.()\"\[\]\s]*?\blength\b[\w.()\"\[\]\s]*?/\s*3"),
    "a step limit": re.compile(r"\b10_000_000\b|\b100_000_000\b|\b1e7\b|\b1e8\b"),
    "the CFL share": re.compile(r"0\.5\s*\*\s*h\b"),
    "a DCT of the initial state": re.compile(r"np\.fft\."),
}


def _code(path: Path) -> str:
    """The source without comments and docstrings (prose may quote the rules)."""
    import ast
    import io
    import tokenize

    text = path.read_text()
    docstrings = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            value = first.value if isinstance(first, ast.Expr) else None
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                docstrings.add(first.lineno)
    kept = []
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT or (tok.type == tokenize.STRING and tok.start[0] in docstrings):
            continue
        kept.append(tok.string)
    return " ".join(kept)


def test_constants_no_python_source_re_derives_them():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        code = _code(path)
        for what, pattern in FORBIDDEN.items():
            for match in pattern.finditer(code):
                found.append(f"{path.relative_to(PACKAGE)}: {what}: {match.group(0)!r}")
    assert not found, "\n".join(found)


def test_constants_the_forbidden_patterns_find_what_they_look_for():
    samples = {
        "the section rule 2 l / 3": ["2 * params.length / 3", "2.0 * res.params.length / 3.0", "2 * length / 3"],
        "a step limit": ["ADAPTIVE_MAX_STEPS = 10_000_000"],
        "the CFL share": ["0.5 * h / math.sqrt(k2 / k1)"],
        "a DCT of the initial state": ["np.fft.rfft(even)"],
    }
    for what, texts in samples.items():
        for text in texts:
            assert FORBIDDEN[what].search(text), (what, text)
