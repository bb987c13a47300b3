"""Calibration from measured data (``ds.fit``, ``drillstring fit``).

Oracles: the known configuration that made the synthetic data (Well B of Aarsnes & Shor, its
friction mu = 0.3, fRat = 0.65), the Octave run of their published code (tests/data/aarsnes_shor/,
made by a code this project did not write), and, for the ridge, the regularised friction law in
which only the kinetic limit mu * fRat acts, so that the misfit's valley must follow
mu * fRat = 0.195 exactly.

The grids are 250 cells (time step 0.01/3 s, so that the controller's 0.01 s is a whole number of
steps; with 200 cells it is not, the controller's sample times jitter with the step and the misfit
jumps at the scale of the intervals) and 1000 for the Octave series (their grid).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from aarsnes_shor_reference import series as octave_series

import drillstring as ds
from drillstring.calibration.data import MeasuredData, read_measured
from drillstring.cli import main
from drillstring.errors import ValidationError

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-shor-well-b.toml"
TRUTH = {"friction.static": 0.3, "friction.kinetic_ratio": 0.65}
BOUNDS = {"friction.static": (0.1, 0.6), "friction.kinetic_ratio": (0.3, 0.95)}


@pytest.fixture(scope="module")
def short_config():
    return ds.load_drill_config(EXAMPLE).with_overrides(
        {"numerics.cells": 250, "numerics.duration": 12.0, "numerics.field_interval": 0.0})


@pytest.fixture(scope="module")
def synthetic(short_config):
    """The truth's surface torque and speed at 20 Hz with sensor noise (500 N m, 0.3 rpm): the
    motor torque, which includes the top drive's inertia torque."""
    run = ds.drill(short_config)
    rng = np.random.default_rng(0)
    t = run.t[::5]
    return pd.DataFrame({
        "t": t,
        "surface_rpm": run.surface_rpm[::5] + rng.normal(0.0, 0.3, t.size),
        "motor_torque": run.motor_torque[::5] + rng.normal(0.0, 500.0, t.size),
    })


def test_synthetic_start_up_recovered_within_the_intervals(short_config, synthetic):
    res = ds.fit(short_config, synthetic, BOUNDS, landscape=False, threads=2)
    for key, true in TRUTH.items():
        p = res.parameters[key]
        assert p.ci_low <= true <= p.ci_high, (key, p)
        assert p.identifiable
        # informative: the interval is a few per cent of the value at most, far inside the bounds
        assert p.ci_high - p.ci_low < 0.03 * true, (key, p)
    assert res.warnings == []
    # the residual RMS is the sensor noise (500 N m), not a model error
    assert res.rms[0]["motor_torque"] == pytest.approx(500.0, rel=0.15)
    assert res.refinement["ssr"] <= res.global_stage["best_ssr"]


def test_octave_surface_series_recovers_their_friction():
    """A model difference, measured: their surface torque and top-drive speed (rad/s, mapped and
    converted) over the start-up, fitted with the example's set-up of their scheme but the
    solver's default `numerics.source_speed = "after_transport"` (their code evaluates the
    friction threshold before transport, tests/test_well_b_published.py). The friction comes out
    within a few per cent, the intervals miss the published values by that scheme difference;
    with the option the fit recovers them (test_octave_series_with_noise_by_the_command)."""
    s = octave_series()
    frame = pd.DataFrame({"time": s["t_s"], "torque": s["motor_torque_Nm"] / 1e3,
                          "omega": s["top_drive_speed_rad_s"]})
    data = read_measured(frame.iloc[::2], columns={"t": "time", "motor_torque": "torque", "surface_rpm": "omega"},
                         units={"motor_torque": "kN m", "surface_rpm": "rad/s"})
    cfg = ds.load_drill_config(EXAMPLE).with_overrides({"numerics.duration": 8.0, "numerics.field_interval": 0.0})
    res = ds.fit(cfg, data, {"friction.static": (0.2, 0.4), "friction.kinetic_ratio": (0.5, 0.8)},
                 windows=[(0.0, 8.0)], samples=32, starts=2, landscape=False, threads=2)
    est = res.parameters
    mu, ratio = est["friction.static"].value, est["friction.kinetic_ratio"].value
    # measured 2026-12-03: mu 0.3083 (0.3005..0.3129), fRat 0.6351 (0.6309..0.6393), RMS 116 N m.
    # The kinetic friction mu fRat is theirs to 0.3 %; mu and fRat each to 3 %: the scheme
    # difference (their threshold before transport) is worth that much friction, more than the
    # intervals of a noiseless series (so they do not hold the published values).
    assert mu * ratio == pytest.approx(0.3 * 0.65, rel=0.01)
    assert mu == pytest.approx(0.3, rel=0.04)
    assert ratio == pytest.approx(0.65, rel=0.04)
    # their scheme and this one differ by up to 2 kN m over 0..10 s; the fit's RMS error is far below
    assert res.rms[0]["motor_torque"] < 250.0


def test_the_ridge_of_static_friction_and_kinetic_ratio(short_config, synthetic):
    """With a regularised wall law only mu * fRat acts: the landscape's valley follows the
    hyperbola mu * fRat = 0.195, the fit warns that the two are not identifiable alone and the
    near-singular Jacobian names both."""
    cfg = short_config.with_overrides({"friction.model": "regularised", "numerics.duration": 6.0})
    run = ds.drill(cfg)
    data = MeasuredData(run.t, {"motor_torque": run.motor_torque
                                + np.random.default_rng(1).normal(0.0, 300.0, run.t.size)})
    res = ds.fit(cfg, data, BOUNDS, samples=8, starts=1, profile=False, landscape_points=11, threads=2)
    land = res.landscapes[0]
    assert (land.x_key, land.y_key) == ("friction.static", "friction.kinetic_ratio")
    product = []
    for col, mu in enumerate(land.x):
        k = int(np.argmin(land.ssr[:, col]))
        if 0 < k < land.y.size - 1:  # a minimum inside the grid of ratios
            product.append(mu * land.y[k])
            # across the valley the misfit rises by far more than along it
            assert land.ssr[:, col].max() > 20 * land.ssr[k, col]
    assert len(product) >= 4
    step = land.y[1] - land.y[0]
    assert np.all(np.abs(np.array(product) - 0.195) < 0.6 * step * land.x.max())
    assert any("near-singular Jacobian" in w and "friction.static" in w and "friction.kinetic_ratio" in w
               for w in res.warnings)
    fitted = res.parameters["friction.static"].value * res.parameters["friction.kinetic_ratio"].value
    assert fitted == pytest.approx(0.195, rel=0.01)
    # on the ridge the Jacobian's intervals reach past the box: reported up to its bounds, and
    # each parameter flagged as not identifiable alone
    for est in res.parameters.values():
        assert est.lower <= est.ci_low <= est.value <= est.ci_high <= est.upper, est
    assert not any(est.identifiable for est in res.parameters.values())


def test_two_start_ups_with_a_shared_and_a_per_event_parameter(short_config):
    """Two start-ups (40 and 60 rpm) of one well: the static friction shared, the kinetic ratio
    one per event (0.65 and 0.55: e.g. a mud change between them)."""
    configs = [short_config.with_overrides({"numerics.duration": 6.0}),
               short_config.with_overrides({"numerics.duration": 6.0, "top_drive.rpm": 60.0})]
    ratios = (0.65, 0.55)
    data = []
    for e, (cfg, ratio) in enumerate(zip(configs, ratios)):
        run = ds.drill(cfg.with_overrides({"friction.kinetic_ratio": ratio}))
        noise = np.random.default_rng(10 + e).normal(0.0, 500.0, run.t[::5].size)
        data.append(MeasuredData(run.t[::5], {"motor_torque": run.motor_torque[::5] + noise}, source=f"event {e}"))
    res = ds.fit(configs, data, BOUNDS, per_event=["friction.kinetic_ratio"], landscape=False, threads=2)
    assert list(res.parameters) == ["friction.static", "events[0].friction.kinetic_ratio",
                                    "events[1].friction.kinetic_ratio"]
    truth = {"friction.static": 0.3, "events[0].friction.kinetic_ratio": 0.65,
             "events[1].friction.kinetic_ratio": 0.55}
    for key, true in truth.items():
        p = res.parameters[key]
        assert p.ci_low <= true <= p.ci_high, (key, p)
        assert p.ci_high - p.ci_low < 0.1 * true, (key, p)
    assert [c.friction.kinetic_ratio for c in res.configs] == pytest.approx(
        [res.parameters[f"events[{e}].friction.kinetic_ratio"].value for e in range(2)])
    assert [c.top_drive.rpm for c in res.configs] == [40.0, 60.0]


# --------------------------------------------------------------------------- data


def test_series_csv_of_drill_read_as_is_and_units(tmp_path, short_config):
    res = ds.drill(short_config.with_overrides({"numerics.duration": 1.0}))
    res.save(tmp_path / "run", plots=False)
    data = read_measured(tmp_path / "run" / "series.csv")
    assert set(data.series) == {"surface_rpm", "bit_rpm", "motor_torque", "bit_torque"}
    np.testing.assert_allclose(data.series["motor_torque"], res.motor_torque, rtol=1e-9)
    parquet = read_measured(tmp_path / "run" / "series.parquet")
    np.testing.assert_array_equal(parquet.t, res.t)
    # a units row and a header suffix: kN m and rad/s to N m and rpm
    path = tmp_path / "units.csv"
    path.write_text("t,motor_torque,surface_rpm [rad/s]\ns,kN.m,\n0,1.5,6.283185307179586\n0.1,2,0\n")
    d = read_measured(path)
    np.testing.assert_allclose(d.series["motor_torque"], [1500.0, 2000.0])
    np.testing.assert_allclose(d.series["surface_rpm"], [60.0, 0.0])
    d = read_measured(path, units={"motor_torque": "kft lbf"})
    assert d.series["motor_torque"][0] == pytest.approx(1.5 * 1355.8179483314004)


@pytest.mark.parametrize(("text", "field", "words"), [
    ("t,motor_torque\n0,1\n0.2,2\n0.1,3\n", "t", "strictly increasing"),
    ("t,surface_rpm\n0,1\n0.1,2\n", "columns", "motor_torque missing"),
    ("time,motor_torque\n0,1\n0.1,2\n", "columns", "time column"),
    ("t,motor_torque\n0,1\n0.1,nan\n0.2,3\n", "column motor_torque", "NaN"),
    ("t,motor_torque\n0,1\n0.1,2\n0.2,3\n5,3\n5.1,2\n", "t", "gap"),
    ("t,motor_torque [furlong]\n0,1\n0.1,2\n", "units[motor_torque]", "torque unit"),
])
def test_bad_data_named(tmp_path, short_config, text, field, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValidationError) as err:
        ds.fit(short_config, path, {"friction.static": (0.1, 0.5)}, samples=2, landscape=False)
    assert field in err.value.field and words in str(err.value)


def test_nan_drop_and_bad_parameters(tmp_path, short_config):
    path = tmp_path / "d.csv"
    path.write_text("t,motor_torque\n0,1\n0.1,nan\n0.2,3\n")
    assert read_measured(path, nan="drop").t.tolist() == [0.0, 0.2]
    data = read_measured(path, nan="drop")
    for params, field in (({"numerics.cells": (10, 20)}, "numerics.cells"),
                          ({"well.inclination_deg": (10, 20)}, "parameters[well.inclination_deg]"),
                          ({"friction.static": (-1, 0.5)}, "friction.static"),
                          ({"friction.static": (0.5, 0.1)}, "parameters[friction.static]"),
                          ({"friction.model": (0, 1)}, "friction.model")):
        with pytest.raises(ValidationError) as err:
            ds.fit(short_config, data, params)
        assert err.value.field == field


# --------------------------------------------------------------------------- the command


def test_fit_command_end_to_end(tmp_path, synthetic, short_config, capsys):
    data = synthetic.rename(columns={"t": "TIME", "motor_torque": "TQ [kN m]"})
    data["TQ [kN m]"] /= 1e3
    data.to_csv(tmp_path / "field.csv", index=False)
    short_config.save(tmp_path / "well.toml")
    out = tmp_path / "calibrated"
    (out).mkdir()
    (out / "landscape.png").write_text("an earlier fit's figure")
    argv = ["fit", str(tmp_path / "well.toml"), "--data", str(tmp_path / "field.csv"), "--column", "t=TIME",
            "--column", "motor_torque=TQ", "--param", "friction.static=0.1:0.6", "--param",
            "friction.kinetic_ratio=0.3:0.95", "--samples", "8", "--no-landscape", "--threads", "2",
            "--out", str(out)]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    doc = json.loads((out / "fit.json").read_text())
    for key, true in TRUTH.items():
        p = doc["parameters"][key]
        assert p["ci_low"] <= true <= p["ci_high"]
    assert doc["evaluations"] > 8 and doc["time_s"] > 0 and doc["misfit"]["ssr"] > 0
    fitted = ds.load_drill_config(out / "config.toml")
    assert fitted.friction.static == pytest.approx(doc["parameters"]["friction.static"]["value"], rel=1e-12)
    assert not (out / "landscape.png").exists()  # never a mix with an earlier fit
    assert {p.name for p in out.iterdir()} == {"config.toml", "fit.json", "fit_series.csv", "fit_series.png",
                                               "report.md"}
    assert f"drillstring drill-map {out}/config.toml" in printed and "top_drive.controller.type=" in printed
    # a drill folder is refused
    run = tmp_path / "run"
    ds.drill(short_config.with_overrides({"numerics.duration": 0.5})).save(run, plots=False)
    assert main([*argv[:-1], str(run)]) == 2
    assert "holds the output of drillstring drill" in capsys.readouterr().err


def test_profile_interval_of_a_quadratic_profile_and_a_flat_one():
    from drillstring.calibration.fit import _profile_interval

    values = np.linspace(0.1, 0.6, 9)
    excess = ((values - 0.3) / 0.01) ** 2  # a quadratic profile: the interval is 0.3 -+ 0.01 sqrt(3.84)
    low, high, flat = _profile_interval(values, excess, 3.84, 0.3)
    assert (low, high) == pytest.approx((0.3 - 0.01 * np.sqrt(3.84), 0.3 + 0.01 * np.sqrt(3.84)), rel=1e-12)
    assert not flat
    low, high, flat = _profile_interval(values, np.full(9, 0.1), 3.84, 0.3)
    assert (low, high, flat) == (0.1, 0.6, True)


# --------------------------------------------------------------------------- a model the project did not write


def _octave_csv(path: Path, seed: int = 2026) -> None:
    """Their Octave surface series as a rig would log them: 20 Hz, torque in kN m, speed in rpm,
    with sensor noise of 500 N m and 0.3 rpm (seeded). Their motor torque y(k) is the one set at
    t_k and held over the next 0.01 s; a log sampling at t_k + 0.01 s before the next update reads
    it there (drillstring's series hold at t the torque of the step ending at t)."""
    s = octave_series()
    rng = np.random.default_rng(seed)
    k = np.arange(5, s["t_s"].size, 5)
    t = s["t_s"][k]
    rpm = s["top_drive_speed_rad_s"][k] * 60.0 / (2.0 * np.pi) + rng.normal(0.0, 0.3, t.size)
    torque = s["motor_torque_Nm"][k - 1] + rng.normal(0.0, 500.0, t.size)
    pd.DataFrame({"TIME [s]": t, "RPM_TD [rpm]": rpm, "TQ_TD [kN m]": torque / 1e3}).to_csv(
        path, index=False, float_format="%.5f")


@pytest.mark.slow
def test_octave_series_with_noise_by_the_command(tmp_path, capsys):
    """The calibration's done-when: `drillstring fit` on a surface-data CSV made by a model the
    project did not write (the Octave run of Aarsnes & Shor's code, tests/data/aarsnes_shor), with
    noise, recovers its friction within the intervals it reports, and the next command it prints
    gives the stick-slip map and the controller recommendation of the calibrated well."""
    import shlex
    import time

    _octave_csv(tmp_path / "rig.csv")
    out = tmp_path / "well-b-fit"
    start = time.perf_counter()
    assert main(["fit", str(EXAMPLE), "--set", "numerics.source_speed=before_transport",
                 "--data", str(tmp_path / "rig.csv"), "--column", "t=TIME", "--column", "motor_torque=TQ_TD",
                 "--column", "surface_rpm=RPM_TD", "--target", "motor_torque", "--target", "surface_rpm",
                 "--param", "friction.static=0.2:0.4", "--param", "friction.kinetic_ratio=0.5:0.8",
                 "--window", "0.05:30", "--samples", "32", "--no-landscape", "--threads", "2",
                 "--out", str(out)]) == 0
    fit_seconds = time.perf_counter() - start
    printed = capsys.readouterr().out
    doc = json.loads((out / "fit.json").read_text())
    for key, true in TRUTH.items():
        p = doc["parameters"][key]
        assert p["ci_low"] <= true <= p["ci_high"], (key, p)
        assert p["identifiable"]
        assert p["ci_high"] - p["ci_low"] < 0.03 * true, (key, p)  # informative
    # the residuals are the sensor noise: the model is theirs
    assert doc["misfit"]["rms"][0]["motor_torque"] == pytest.approx(500.0, rel=0.1)
    assert doc["misfit"]["rms"][0]["surface_rpm"] == pytest.approx(0.3, rel=0.1)
    fitted = ds.load_drill_config(out / "config.toml")
    assert fitted.numerics.source_speed == "before_transport"
    assert fitted.numerics.duration == 60.0  # the example's, not the windows'
    # one more command: the one the fit prints
    lines = printed.splitlines()
    command = lines[lines.index(next(x for x in lines if x.startswith("next, "))) + 1].strip()
    argv = shlex.split(command)
    assert argv[:2] == ["drillstring", "drill-map"] and "top_drive.controller.type=pi,soft_torque,z_torque" in command
    start = time.perf_counter()
    assert main(argv[1:]) == 0
    map_seconds = time.perf_counter() - start
    printed = capsys.readouterr().out
    table = pd.read_csv(tmp_path / "well-b-fit-map" / "map.csv")
    assert (table["status"] == "success").all() and len(table) == 81
    assert (tmp_path / "well-b-fit-map" / "controllers.png").exists()
    best = next(x for x in printed.splitlines() if x.startswith("controller recommendation: "))
    name = best.split()[2]
    assert name in ("pi", "soft_torque", "z_torque")
    # the recommended controller has the fewest runs in stick-slip
    counts = table[table["stick_slip_verdict"] == "yes"].groupby("top_drive.controller.type").size()
    assert counts.get(name, 0) == min(counts.get(c, 0) for c in ("pi", "soft_torque", "z_torque"))
    print(f"fit {fit_seconds:.1f} s, drill-map {map_seconds:.1f} s")


def test_controller_recommendation_of_a_map():
    """The ranking drill-map prints: fewest runs in stick-slip or without a result, then the
    lowest mean SSI (a table written by hand)."""
    from drillstring.drilling.map_table import controller_recommendation

    frame = pd.DataFrame({
        "top_drive.controller.type": ["pi"] * 3 + ["soft_torque"] * 3 + ["z_torque"] * 3,
        "status": ["success"] * 8 + ["failed"],
        "stick_slip_verdict": ["yes", "yes", "no", "no", "no", "undetermined", "no", "no", None],
        "ssi": [1.4, 1.2, 0.3, 0.2, 0.4, 0.9, 0.1, 0.1, np.nan],
    })
    ranking = controller_recommendation(frame)
    assert [r.controller for r in ranking] == ["soft_torque", "z_torque", "pi"]
    assert (ranking[0].stick_slip_runs, ranking[0].failed, ranking[0].runs) == (0, 0, 3)
    assert ranking[0].worst_ssi == 0.9 and ranking[0].mean_ssi == pytest.approx(0.5)
    assert (ranking[1].failed, ranking[1].mean_ssi) == (1, pytest.approx(0.1))
    assert ranking[2].line() == "pi: stick-slip in 2 of 3 runs, SSI up to 1.4 (mean 0.967)"
    assert controller_recommendation(frame.drop(columns="top_drive.controller.type")) == []
