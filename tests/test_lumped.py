"""The lumped two-inertia model of Navarro-Lopez & Cortes (2007), ``drillstring.drilling.lumped``
(``drillstring_core::drilling::lumped``), against oracles written here: the steady-rotation
balance solved with scipy's brentq, the Jacobian's eigenvalues with numpy, the energy balance
from the sampled series, and the slipping phase integrated with scipy's DOP853."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from drillstring.drilling import lumped, lumped_defaults, lumped_equilibria
from drillstring.errors import ValidationError

# The published parameters, written out here (Navarro-Lopez & Cortes 2007, J. Sound Vib. 307).
PUBLISHED = {"jr": 2122.0, "jb": 471.9698, "kt": 861.5336, "ct": 172.3067, "cr": 425.0, "cb": 50.0,
             "rb": 0.155575, "mu_cb": 0.5, "mu_sb": 0.8, "gamma_b": 0.9, "v_f": 1.0, "d_v": 1e-6,
             "tm": 6000.0}
P = PUBLISHED


def mu(w: float) -> float:
    return P["mu_cb"] + (P["mu_sb"] - P["mu_cb"]) * np.exp(-P["gamma_b"] * abs(w) / P["v_f"])


def steady(w: float, wob: float) -> float:
    """Tm = (cr + cb) w + Wob Rb mu(w) at a steady rotation."""
    return (P["cr"] + P["cb"]) * w + wob * P["rb"] * mu(w) - P["tm"]


def fold_wob() -> float:
    """The weight where the two steady rotations merge: min_w steady(w) = 0."""
    def minimum(wob: float) -> float:
        drop = wob * P["rb"] * (P["mu_sb"] - P["mu_cb"]) * P["gamma_b"] / P["v_f"]
        w = np.log(drop / (P["cr"] + P["cb"])) / (P["gamma_b"] / P["v_f"])
        return steady(w, wob)
    return float(brentq(minimum, 50e3, 70e3, xtol=1e-9))


def upper_root(wob: float) -> float:
    """The faster steady rotation (brentq on the falling-then-rising balance)."""
    hi = (P["tm"] - wob * P["rb"] * P["mu_cb"]) / (P["cr"] + P["cb"])
    a = P["gamma_b"] / P["v_f"]
    drop = wob * P["rb"] * (P["mu_sb"] - P["mu_cb"]) * a
    lo = max(0.0, np.log(drop / (P["cr"] + P["cb"])) / a) if drop > P["cr"] + P["cb"] else 0.0
    return float(brentq(steady, lo, hi, args=(wob,), xtol=1e-15, rtol=1e-15))


def jacobian(w: float, wob: float) -> np.ndarray:
    """d(wr', phi', wb')/d(wr, phi, wb) of the slipping bit at speed w > 0."""
    a = P["gamma_b"] / P["v_f"]
    dmu = -(P["mu_sb"] - P["mu_cb"]) * a * np.exp(-a * w)
    jr, jb, kt, ct = P["jr"], P["jb"], P["kt"], P["ct"]
    return np.array([[-(P["cr"] + ct) / jr, -kt / jr, ct / jr],
                     [1.0, 0.0, -1.0],
                     [ct / jb, kt / jb, -(ct + P["cb"] + wob * P["rb"] * dmu) / jb]])


def growth(wob: float) -> float:
    """The largest real part of the Jacobian's eigenvalues at the faster rotation."""
    return float(np.linalg.eigvals(jacobian(upper_root(wob), wob)).real.max())


def hopf_wob() -> float:
    return float(brentq(growth, 50e3, fold_wob() - 1.0, xtol=1e-6))


def rhs_slip(_t: float, y: np.ndarray, wob: float) -> list[float]:
    wr, phi, wb = y
    tb = wob * P["rb"] * mu(wb) * np.sign(wb)
    return [(P["tm"] - P["cr"] * wr - P["kt"] * phi - P["ct"] * (wr - wb)) / P["jr"],
            wr - wb,
            (P["kt"] * phi + P["ct"] * (wr - wb) - P["cb"] * wb - tb) / P["jb"]]


def near(wob: float, scale: float) -> tuple[float, float, float]:
    """The faster steady rotation, its bit speed perturbed by ``scale`` (relative)."""
    w = upper_root(wob)
    return (w, (P["tm"] - P["cr"] * w) / P["kt"], w * (1.0 + scale))


# --------------------------------------------------------------------------- parameters


def test_defaults_are_the_published_parameters() -> None:
    d = lumped_defaults()
    assert {k: d[k] for k in PUBLISHED} == PUBLISHED
    assert d["wob"] == 50e3


# --------------------------------------------------------------------------- steady speed against Wob


@pytest.mark.parametrize("wob", [0.0, 10e3, 20e3, 30e3, 40e3, 48e3])
def test_long_time_bit_speed_is_the_steady_root(wob: float) -> None:
    root = upper_root(wob)
    assert growth(wob) < -0.1  # stable, well inside
    eq = lumped_equilibria({"wob": wob})
    assert eq.equilibrium == "stable_rotation"
    assert eq.rotations[-1].speed == pytest.approx(root, rel=1e-12)
    res = lumped({"wob": wob}, duration=250.0, output_interval=0.05)
    # from rest: the slowest mode decays at >= 0.17 1/s, 250 s are e^-40
    assert res.bit_speed[-1] == pytest.approx(root, rel=1e-6)
    assert res.top_speed[-1] == pytest.approx(root, rel=1e-6)
    assert res.spring_torque[-1] == pytest.approx(P["tm"] - P["cr"] * root, rel=1e-6)
    assert res.metrics.ssi < 1e-6 and res.metrics.stuck_fraction == 0.0


def test_equilibria_count_and_stability_match_numpy() -> None:
    fold = fold_wob()
    for wob in (20e3, 49e3, 55e3, 58e3, 58.9e3, fold - 10.0, fold + 10.0, 70e3):
        eq = lumped_equilibria({"wob": wob})
        roots = []
        grid = np.linspace(1e-9, (P["tm"] - wob * P["rb"] * P["mu_cb"]) / (P["cr"] + P["cb"]) + 1.0, 20001)
        values = np.array([steady(w, wob) for w in grid])
        for k in np.nonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0]:
            roots.append(brentq(steady, grid[k], grid[k + 1], args=(wob,), xtol=1e-15, rtol=1e-15))
        assert [r.speed for r in eq.rotations] == pytest.approx(roots, rel=1e-10), wob
        for r in eq.rotations:
            want = np.sort_complex(np.linalg.eigvals(jacobian(r.speed, wob)))
            got = np.sort_complex(r.eigenvalues)
            assert np.max(np.abs(got - want)) < 1e-9 * max(1.0, np.max(np.abs(want)))
            assert r.stable == bool(np.all(want.real < 0))
        assert eq.stuck_possible == (P["tm"] <= wob * P["rb"] * P["mu_sb"])
        if not roots:
            assert eq.equilibrium == "stuck"


# --------------------------------------------------------------------------- onset of stick-slip


def test_onset_linear_boundary_and_subcritical_coexistence() -> None:
    """At Tm = 6000 N m the faster rotation loses stability in a Hopf bifurcation at
    Wob_H ~ 58.7 kN, just before it merges with the slower (unstable) one at Wob_F ~ 59.1 kN.
    Near the equilibrium the solver follows the linear analysis (settles below Wob_H, an
    oscillation growing into sticking above). From rest it stick-slips from ~51.4 kN on, with the
    rotation still stable: stick-slip coexists with it (a subcritical onset) up to ~57.7 kN,
    above which the bit ends stuck."""
    hopf, fold = hopf_wob(), fold_wob()
    assert 58e3 < hopf < fold < 60e3
    assert lumped_equilibria({"wob": hopf - 20.0}).equilibrium == "stable_rotation"
    assert lumped_equilibria({"wob": hopf + 20.0}).equilibrium == "unstable"
    assert lumped_equilibria({"wob": fold + 20.0}).equilibrium == "stuck"

    # below Wob_H, started near the rotation: settles
    below = lumped({"wob": hopf - 700.0}, duration=300.0, initial=near(hopf - 700.0, 1e-2))
    assert below.metrics.ssi < 1e-6 and below.metrics.stuck_fraction == 0.0
    # above Wob_H (below the fold), started near the rotation: grows into stick-slip
    mid = 0.5 * (hopf + fold)
    above = lumped({"wob": mid}, duration=400.0, initial=near(mid, 1e-3))
    assert above.stats["sticks"] >= 1 and above.metrics.stuck_fraction > 0.0
    first_stick = above.t[np.argmax(above.bit_speed == 0.0)]
    assert first_stick > 50.0  # grown from 1e-3 at the linear rate (~0.03 1/s), not kicked
    # ... and, as with every weight above ~57.7 kN (Tm < Wob Rb mu_sb), ends stuck for good
    assert above.metrics.stuck_fraction == 1.0
    # subcritical: below Wob_H but from rest, stick-slip; well below, from rest, steady
    coexist = lumped({"wob": 55e3}, duration=200.0)
    assert coexist.metrics.stuck_fraction > 0.1 and coexist.metrics.ssi >= 1.0
    assert growth(55e3) < 0
    settled = lumped({"wob": 50e3}, duration=200.0)
    assert settled.metrics.ssi < 1e-6
    # the stick-slip cycle at 55 kN: period from the spring torque, bit speed from 0 up
    assert coexist.metrics.bit_rpm_min == 0.0 and 4.0 < coexist.metrics.period_s < 5.5


def test_stick_phase_holds_within_the_static_limit_and_breaks_at_it() -> None:
    wob = 55e3
    res = lumped({"wob": wob}, duration=60.0, output_interval=0.001)
    limit = wob * P["rb"] * P["mu_sb"]
    applied = res.spring_torque + P["ct"] * res.top_speed
    stuck = res.bit_speed == 0.0
    assert stuck.sum() > 1000 and res.stats["sticks"] > 5
    assert np.all(np.abs(applied[stuck]) <= limit * (1 + 1e-12))
    assert np.allclose(res.bit_torque[stuck], applied[stuck], rtol=1e-12)
    # the last stuck sample before each slip: within one sample's change of the limit
    starts = np.nonzero(stuck[:-1] & ~stuck[1:])[0]
    assert starts.size > 5
    step = np.max(np.abs(np.diff(applied)))
    assert np.all(limit - applied[starts] <= step)
    # slipping forwards only (no reversal with these parameters)
    assert res.bit_speed.min() == 0.0


# --------------------------------------------------------------------------- energy and an independent integration


def test_energy_balance_of_a_stick_slip_run() -> None:
    wob = 55e3
    res = lumped({"wob": wob}, duration=60.0, output_interval=0.001)
    e = res.energy
    assert abs(e["balance_error"]) < 1e-9
    # the same balance from the sampled series (trapezoidal rule): an independent estimate
    t, wr, wb = res.t, res.top_speed, res.bit_speed
    motor = np.trapezoid(P["tm"] * wr, t)
    viscous = np.trapezoid(P["cr"] * wr**2 + P["ct"] * (wr - wb) ** 2 + P["cb"] * wb**2, t)
    friction = np.trapezoid(res.bit_torque * wb, t)
    phi = res.spring_torque / P["kt"]
    energy = 0.5 * P["jr"] * wr**2 + 0.5 * P["jb"] * wb**2 + 0.5 * P["kt"] * phi**2
    assert motor == pytest.approx(e["motor_work"], rel=1e-6)
    assert viscous == pytest.approx(e["viscous_loss"], rel=1e-6)
    assert friction == pytest.approx(e["friction_loss"], rel=1e-5)
    assert energy[-1] == pytest.approx(e["kinetic_top"] + e["kinetic_bit"] + e["spring"], rel=1e-12)
    assert abs(motor - (energy[-1] - energy[0]) - viscous - friction) < 1e-5 * motor


def test_slipping_phase_matches_scipy() -> None:
    wob = 55e3
    res = lumped({"wob": wob}, duration=40.0, output_interval=0.01)
    wb = res.bit_speed
    # a slip interval: from the first sample after a stick ends to the last before the next
    moving = wb > 0.0
    start = int(np.nonzero(~moving[:-1] & moving[1:])[0][1]) + 5
    end = start + int(np.nonzero(~moving[start:])[0][0]) - 2
    assert end - start > 100
    y0 = [res.top_speed[start], res.spring_torque[start] / P["kt"], wb[start]]
    t = res.t[start:end + 1]
    sol = solve_ivp(rhs_slip, (t[0], t[-1]), y0, method="DOP853", t_eval=t, rtol=1e-12, atol=1e-12, args=(wob,))
    assert sol.success
    assert np.max(np.abs(sol.y[0] - res.top_speed[start:end + 1])) < 1e-7
    assert np.max(np.abs(sol.y[2] - wb[start:end + 1])) < 1e-7
    assert np.max(np.abs(sol.y[1] * P["kt"] - res.spring_torque[start:end + 1])) < 1e-5

    # and a whole run that never sticks, from a perturbed rotation
    res = lumped({"wob": 30e3}, duration=20.0, output_interval=0.08, initial=(8.0, 2.0, 6.0))
    sol = solve_ivp(rhs_slip, (0.0, 20.0), [8.0, 2.0, 6.0], method="DOP853", t_eval=res.t, rtol=1e-13,
                    atol=1e-13, args=(30e3,))
    assert np.max(np.abs(sol.y[2] - res.bit_speed)) < 1e-9
    # fourth order: halving the step divides the error by ~16
    errors = []
    for dt in (0.04, 0.02):
        r = lumped({"wob": 30e3}, duration=20.0, dt=dt, output_interval=0.08, initial=(8.0, 2.0, 6.0))
        errors.append(np.max(np.abs(sol.y[2] - r.bit_speed)))
    assert 12.0 < errors[0] / errors[1] < 20.0, errors


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(("params", "kwargs", "field"), [
    ({"jb": 0.0}, {}, "jb"),
    ({"mu_cb": 0.9}, {}, "mu_cb"),
    ({"wob": -1.0}, {}, "wob"),
    ({"weight": 1.0}, {}, "weight"),
    ({"tm": "6000"}, {}, "tm"),
    ({"tm": float("nan")}, {}, "tm"),
    ({}, {"dt": 0.0}, "dt"),
    ({}, {"duration": -1.0}, "duration"),
    ({}, {"window": (5.0, 1.0)}, "window"),
    ({}, {"initial": (1.0, 2.0)}, "initial"),
    ({}, {"output_interval": 1e-9}, "output_interval"),
])
def test_bad_input_names_the_field(params: dict[str, object], kwargs: dict[str, object], field: str) -> None:
    with pytest.raises(ValidationError) as err:
        lumped(params, **kwargs)  # type: ignore[arg-type]
    assert err.value.field == field


def test_the_readme_example_says_what_it_prints() -> None:
    from _docs import blocks

    (block,) = [b for b in blocks("python") if "lumped_equilibria" in b]
    names: dict[str, object] = {}
    exec(compile(block, "the documentation's lumped example", "exec"), names)
    eq, m = names["eq"], names["m"]
    assert eq.equilibrium == "stable_rotation"  # type: ignore[attr-defined]
    assert [round(r.speed, 2) for r in eq.rotations] == [0.67, 3.36]  # type: ignore[attr-defined]
    assert [r.stable for r in eq.rotations] == [False, True]  # type: ignore[attr-defined]
    assert (round(m.ssi, 2), round(m.stuck_fraction, 2), round(m.period_s, 2)) == (1.22, 0.28, 4.63)  # type: ignore[attr-defined]
    # the boundaries the documentation gives at tm = 6000 N m
    assert P["tm"] / (P["rb"] * P["mu_sb"]) == pytest.approx(48.2e3, rel=1e-3)
    assert round(hopf_wob() / 1e3, 1) == 58.7 and round(fold_wob() / 1e3, 1) == 59.1


def test_progress_is_reported_and_its_exception_stops_the_run() -> None:
    seen: list[float] = []
    lumped({"wob": 30e3}, duration=50.0, progress=seen.append)
    assert seen[0] == 0.0 and seen[-1] == 1.0 and seen == sorted(seen)

    def stop(fraction: float) -> None:
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        lumped({"wob": 30e3}, duration=1e4, progress=stop)


def test_command_line(capsys: pytest.CaptureFixture[str]) -> None:
    from _cli import one_line_error, run_cli

    code, out, err = run_cli(capsys, "lumped", "--set", "wob=55e3", "--duration", "100")
    assert code == 0, err
    assert "steady rotation 0.67144 rad/s: unstable" in out and "steady rotation 3.36252 rad/s: stable" in out
    assert "equilibrium: stable_rotation" in out and "SSI 1.2" in out
    code, out, err = run_cli(capsys, "lumped", "--set", "weight=1")
    assert code == 2
    one_line_error(err, "weight")


def test_sweep_rows_are_the_single_runs_and_equilibria() -> None:
    """Each row of ``lumped_sweep`` is what ``lumped`` and ``lumped_equilibria`` give for its
    value (exactly); across the onset the rows show it: steady below, stick-slip coexisting with
    the stable rotation above ~51.4 kN, no rotation past the fold."""
    from drillstring.drilling import lumped_figure, lumped_sweep, lumped_sweep_figure

    values = [48e3, 55e3, 60e3]
    frame = lumped_sweep("wob", values, {"tm": 6000.0}, duration=150.0)
    assert list(frame["wob"]) == values and frame.attrs["parameter"] == "wob"
    for _, row in frame.iterrows():
        p = {"tm": 6000.0, "wob": row["wob"]}
        eq, res = lumped_equilibria(p), lumped(p, duration=150.0)
        assert row["equilibrium"] == eq.equilibrium and row["stuck_possible"] == eq.stuck_possible
        assert row["static_limit_Nm"] == eq.static_limit
        speeds = [r.speed for r in eq.rotations]
        got = [row[f"rotation_{k}"] for k in (1, 2) if row[f"stable_{k}"] is not None]
        assert got == speeds and [row[f"stable_{k}"] for k in (1, 2)][:len(speeds)] == [r.stable for r in eq.rotations]
        for column, value in [("ssi", res.metrics.ssi), ("stuck_fraction", res.metrics.stuck_fraction),
                              ("bit_rpm_max", res.metrics.bit_rpm_max), ("period_s", res.metrics.period_s)]:
            assert row[column] == value or (np.isnan(row[column]) and np.isnan(value)), column
    assert list(frame["equilibrium"]) == ["stable_rotation", "stable_rotation", "stuck"]
    assert frame["stuck_fraction"][0] == 0.0 and 0.1 < frame["stuck_fraction"][1] < 1.0
    assert frame["stuck_fraction"][2] == 1.0 and np.isnan(frame["rotation_1"][2])
    assert len(lumped_sweep_figure(frame).axes) == 2
    assert len(lumped_figure(lumped({"wob": 55e3}, duration=20.0)).axes) == 2


@pytest.mark.parametrize(("name", "values", "field"), [
    ("weight", [1.0], "name"), ("wob", [], "values"), ("wob", 5e4, "values"),
    ("wob", [float("nan")], "wob"), ("wob", [-1.0], "wob"),
])
def test_sweep_bad_input_names_the_field(name: str, values: object, field: str) -> None:
    from drillstring.drilling import lumped_sweep

    with pytest.raises(ValidationError) as info:
        lumped_sweep(name, values, duration=10.0)
    assert info.value.field == field


def test_sweep_and_output_on_the_command_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    import pandas as pd
    from _cli import one_line_error, run_cli

    out_dir = tmp_path / "sweep"
    code, out, err = run_cli(capsys, "lumped", "--sweep", "wob=48e3,55e3", "--duration", "100", "--out", str(out_dir))
    assert code == 0, err
    assert "wob = 48000: steady rotations" in out and "wob = 55000:" in out and "SSI 1.2" in out
    table = pd.read_csv(out_dir / "lumped_sweep.csv")
    assert list(table["wob"]) == [48e3, 55e3] and table["stuck_fraction"][1] > 0.1
    assert (out_dir / "lumped_sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    single = tmp_path / "single"
    code, out, err = run_cli(capsys, "lumped", "--set", "wob=55e3", "--duration", "20", "--out", str(single))
    assert code == 0, err
    series = pd.read_csv(single / "lumped.csv")
    res = lumped({"wob": 55e3}, duration=20.0)
    assert list(series.columns) == ["t_s", "top_speed_rad_s", "bit_speed_rad_s", "spring_torque_Nm", "bit_torque_Nm"]
    np.testing.assert_allclose(series["bit_speed_rad_s"], res.bit_speed, rtol=1e-15, atol=0)
    assert (single / "lumped.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for args, needle in [(["--sweep", "weight=1:2:3"], "--sweep"), (["--sweep", "wob=1:2:x"], "--sweep"),
                         (["--sweep", "wob=1:2:1000000000000"], "--sweep")]:
        code, out, err = run_cli(capsys, "lumped", *args)
        assert code == 2
        one_line_error(err, needle)


def test_lumped_params_are_typed_with_the_cores_defaults_and_validation() -> None:
    from drillstring import _core
    from drillstring.drilling import LumpedParams

    assert LumpedParams().to_dict() == _core.lumped_defaults()[0] == lumped_defaults()
    p = LumpedParams(wob=60e3)
    # a LumpedParams and the mapping of the same values give the same run
    a = lumped(p, duration=20.0)
    b = lumped({"wob": 60e3}, duration=20.0)
    assert a.params == b.params and np.array_equal(a.bit_speed, b.bit_speed)
    with pytest.raises(ValidationError) as info:
        LumpedParams(kt=-1.0)
    assert info.value.field == "kt"
