"""Each equation, default and limit in one place: the Python package reads them from the core."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core, coefficients, galerkin, parameters, stability, sweeps
from drillstring.errors import ValidationError

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
