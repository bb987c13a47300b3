"""The pseudo-spectral quartic force and potential of the modal model (``evaluation="spectral"``)
against the term sum, and where the core chooses it."""

from __future__ import annotations

import numpy as np
import pytest

import drillstring as ds
from drillstring import _core
from drillstring.errors import ValidationError
from drillstring.model.galerkin import ModalCoefficients, project
from drillstring.model.parameters import preset
from drillstring.solvers.modal import simulate


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.parametrize("model_name", ["paper", "consistent"])
@pytest.mark.parametrize("rigid", [False, True])
@pytest.mark.parametrize("modes", [1, 2, 5, 13, 40])
def test_spectral_equals_the_term_sum_to_rounding(model_name: str, rigid: bool, modes: int) -> None:
    params = preset("aluminum").replace(model=model_name)
    model = project(params, modes, rigid)
    terms = model.core_system(evaluation="terms")
    spectral = model.core_system(evaluation="spectral")
    assert (terms.evaluation, spectral.evaluation) == ("terms", "spectral")
    rng = np.random.default_rng(modes + 100 * rigid)
    m = model.n_modes
    # amplitudes large enough that the quartic force is not negligible against K q
    q = rng.standard_normal((m, 8)) * np.logspace(-2, 0, 8)
    v = rng.standard_normal((m, 8))
    for k in range(q.shape[1]):
        assert _relative(spectral.acceleration(q[:, k]), terms.acceleration(q[:, k])) < 1e-13
    assert _relative(spectral.potential(q), terms.potential(q)) < 1e-13
    assert _relative(spectral.energy(q, v), terms.energy(q, v)) < 1e-13


def test_auto_is_spectral_from_the_crossover() -> None:
    params = preset("aluminum")
    crossover = _core.SPECTRAL_MIN_MODES
    below = project(params, crossover - 2, rigid_mode=True)  # crossover - 1 retained modes
    at = project(params, crossover - 1, rigid_mode=True)
    assert below.core_system().evaluation == "terms"
    assert at.core_system().evaluation == "spectral"
    assert at.core_system(0.5).damping_rate == 0.5
    # a model given by its arrays has no coefficients to evaluate spectrally
    arrays = ModalCoefficients(
        indices=at.indices,
        length=at.length,
        mass=at.mass,
        stiffness=at.stiffness,
        quartic_index=at.quartic_index,
        quartic_coef=at.quartic_coef,
    )
    assert arrays.coefficients is None
    assert arrays.core_system().evaluation == "terms"
    with pytest.raises(ValidationError) as info:
        arrays.core_system(evaluation="spectral")
    assert info.value.field == "evaluation"
    with pytest.raises(ValidationError) as info:
        at.core_system(evaluation="fft")
    assert info.value.field == "evaluation"


def test_spectral_solve_follows_the_term_sum_solve() -> None:
    params = preset("aluminum")
    model = project(params, 20, rigid_mode=True)
    q0, v0 = model.initial_state(params)
    t_eval = np.linspace(0.0, 0.05, 11)
    runs = [
        _core.solve_modal(model.core_system(evaluation=e), q0, v0, 0.05, t_eval, "dop853", 1e-11, 1e-13)
        for e in ("terms", "spectral")
    ]
    assert all(run["status"] == "success" for run in runs)
    np.testing.assert_allclose(runs[1]["y"], runs[0]["y"], rtol=0, atol=1e-9 * np.abs(runs[0]["y"]).max())


def test_spectral_refusals_name_the_field() -> None:
    k = np.array([0.369, 5.4e9, 3.3e8, 1.6e9, -2.2e5, 3.64])
    with pytest.raises(ValidationError) as info:
        _core.ModalSystem.spectral(k, 100.0, np.array([2, 1]))
    assert info.value.field == "indices"
    with pytest.raises(ValidationError) as info:
        _core.ModalSystem.spectral(k, 100.0, np.array([-1, 1]))
    assert info.value.field == "indices[0]"
    with pytest.raises(ValidationError) as info:
        _core.ModalSystem.spectral(k[:5], 100.0, np.array([1]))
    assert info.value.field == "k"
    with pytest.raises(ValidationError) as info:
        _core.ModalSystem.spectral(k, -1.0, np.array([1]))
    assert info.value.field == "length"
    with pytest.raises(ValidationError) as info:
        _core.ModalSystem.spectral(k, 100.0, np.array([1]), damping_rate=-1.0)
    assert info.value.field == "damping_rate"


def test_a_linear_many_mode_run_stays_linear() -> None:
    params = preset("aluminum")
    modes = _core.SPECTRAL_MIN_MODES + 4
    linear = ds.simulate(params, modes=modes, rigid_mode=True, t_end=0.02, nonlinear=False)
    assert linear.coefficients.quartic_coef.size == 0 and linear.coefficients.coefficients is None
    # the exact linear solution: each mode oscillates at its own frequency
    w = linear.coefficients.linear_frequencies
    q0, v0 = linear.coefficients.initial_state(params)
    t = linear.t
    elastic = slice(1, None)
    want = v0[elastic, None] / w[elastic, None] * np.sin(w[elastic, None] * t)
    np.testing.assert_allclose(linear.q[elastic], want, rtol=0, atol=1e-8 * np.abs(want).max())


def test_simulate_takes_the_evaluation() -> None:
    """``simulate(evaluation=...)``: "terms" and "spectral" solves of 10 modes agree to their
    tolerance, "auto" is the spectral one there (from the crossover on), a bad value names the
    argument; below the crossover "auto" is the term sum, bit for bit."""
    params = preset("aluminum")
    t_eval = np.linspace(0.0, 0.05, 11)
    runs = {e: simulate(params, modes=10, t_end=0.05, t_eval=t_eval, rtol=1e-11, atol=1e-13, evaluation=e)
            for e in ("terms", "spectral", "auto")}
    scale = np.abs(runs["terms"].q).max()
    np.testing.assert_allclose(runs["spectral"].q, runs["terms"].q, rtol=0, atol=1e-8 * scale)
    assert np.array_equal(runs["auto"].q, runs["spectral"].q)
    small = [simulate(params, modes=3, t_end=0.05, t_eval=t_eval, evaluation=e).q for e in ("terms", "auto")]
    assert np.array_equal(small[0], small[1])
    with pytest.raises(ValidationError) as info:
        simulate(params, modes=3, t_end=0.05, evaluation="fft")  # type: ignore[arg-type]
    assert info.value.field == "evaluation"
    n = _core.SPECTRAL_MIN_MODES
    assert [_core.resolve_evaluation("auto", m) for m in (n - 1, n)] == ["terms", "spectral"]
    assert _core.resolve_evaluation("terms", 200) == "terms" and _core.resolve_evaluation("spectral", 1) == "spectral"
