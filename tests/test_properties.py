"""Property-based tests (hypothesis) of the Python API on random realistic drill strings.

For random valid parameters (lengths 50-1000 m, steel-to-aluminium materials, annular sections,
rotation below the first critical speed, initial modal velocities up to 1 rad/s) and 1-4 modes:

* the results are finite and the solve succeeds;
* the conserved energy drifts by less than 1e-7 at rtol = 1e-10;
* the output sampling does not change the solution: adaptive steps are not tied to the output
  times, so the samples at the times two requests share agree (to 1e-12 relative; in fact
  bit for bit) and so do the step counts.
"""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.model.coefficients import PDECoefficients

SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def drill_strings(draw: st.DrawFn) -> ds.Parameters:
    length = draw(st.floats(50.0, 1000.0))
    youngs_modulus = draw(st.floats(5e10, 2.2e11))
    density = draw(st.floats(2000.0, 8000.0))
    poisson_ratio = draw(st.floats(0.2, 0.4))
    outer = draw(st.floats(0.1, 0.3))
    inner = outer * draw(st.floats(0.0, 0.9))
    count = draw(st.integers(1, 4))
    magnitudes = draw(st.lists(st.floats(0.01, 1.0), min_size=count, max_size=count))
    signs = draw(st.lists(st.sampled_from([-1.0, 1.0]), min_size=count, max_size=count))
    params = ds.Parameters(
        length=length,
        youngs_modulus=youngs_modulus,
        density=density,
        poisson_ratio=poisson_ratio,
        outer_diameter=outer,
        inner_diameter=inner,
        omega=0.0,
        initial_velocities=tuple(m * s for m, s in zip(magnitudes, signs)),
        k5_variant=draw(st.sampled_from(["paper", "energy"])),
    )
    critical = float(PDECoefficients.from_parameters(params).critical_speed(1))
    return params.replace(omega=critical * draw(st.floats(0.0, 0.9)))


@SETTINGS
@given(params=drill_strings(), modes=st.integers(1, 4), t_end=st.floats(0.05, 0.3))
def test_random_drill_strings_give_finite_results_that_conserve_energy(
    params: ds.Parameters, modes: int, t_end: float
) -> None:
    res = ds.simulate(params, modes=modes, t_end=t_end, rtol=1e-10, atol=1e-14, samples=201)
    assert res.status == "success"
    assert np.all(np.isfinite(res.q)) and np.all(np.isfinite(res.qdot))
    assert np.all(np.isfinite(res.energy)) and res.energy[0] > 0
    drift = res.energy_drift()
    assert drift < 1e-7, f"energy drift {drift:.2e}"
    theta = res.theta(2 * params.length / 3)
    assert np.all(np.isfinite(theta))
    # The motion stays near the initial kinetic energy's amplitude scale (no blow-up).
    assert np.max(np.abs(res.qdot)) <= 10 * max(abs(c) for c in params.initial_velocities) + 1e-12


@SETTINGS
@given(
    params=drill_strings(),
    modes=st.integers(1, 4),
    rigid_mode=st.booleans(),
    t_end=st.floats(0.05, 0.3),
    method=st.sampled_from(["dop853", "dopri5"]),
)
def test_results_do_not_depend_on_the_output_sampling(
    params: ds.Parameters, modes: int, rigid_mode: bool, t_end: float, method: str
) -> None:
    fine = np.linspace(0.0, t_end, 101)
    coarse = fine[::10]
    kwargs = {"modes": modes, "rigid_mode": rigid_mode, "t_end": t_end, "method": method, "rtol": 1e-10}
    a = ds.simulate(params, t_eval=coarse, **kwargs)
    b = ds.simulate(params, t_eval=fine, **kwargs)
    np.testing.assert_allclose(a.q, b.q[:, ::10], rtol=1e-12, atol=1e-12 * float(np.max(np.abs(b.q))))
    np.testing.assert_allclose(a.qdot, b.qdot[:, ::10], rtol=1e-12, atol=1e-12 * float(np.max(np.abs(b.qdot))))
    assert (a.stats.naccept, a.stats.nreject) == (b.stats.naccept, b.stats.nreject)
    # Every step's end point is the same: the sampled values are in fact bit-identical.
    assert np.array_equal(a.q, b.q[:, ::10])


@SETTINGS
@given(params=drill_strings(), nodes=st.integers(5, 60), t_end=st.floats(0.01, 0.05))
def test_random_pde_solves_are_finite_and_conserve_the_discrete_energy(
    params: ds.Parameters, nodes: int, t_end: float
) -> None:
    res = ds.solve_pde(params, nodes=nodes, t_end=t_end, rtol=1e-10, atol=1e-14, samples=51)
    assert res.status == "success"
    assert np.all(np.isfinite(res.q)) and np.all(np.isfinite(res.qdot))
    assert res.energy_drift() < 1e-7


def test_omega_is_capped_at_the_first_critical_speed() -> None:
    """The cap used by the strategy: at Omega = Omega_1 the first elastic mode loses stiffness."""
    params = ds.preset("aluminum")
    k = PDECoefficients.from_parameters(params)
    critical = float(k.critical_speed(1))
    at_critical = PDECoefficients.from_parameters(params.replace(omega=critical))
    assert abs(float(at_critical.frequency_squared(1))) < 1e-9 * float(k.frequency_squared(1))
    below = PDECoefficients.from_parameters(params.replace(omega=0.9 * critical))
    assert float(below.frequency_squared(1)) > 0
