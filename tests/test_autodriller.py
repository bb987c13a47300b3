"""The autodriller (hoist.mode = "autodriller", [hoist.autodriller], hoist.steps) from Python, a
coupled run's outputs (series.csv columns, fields.npz, the axial figures, --units field) and the
warning of a bit that never touches bottom. The steady states are the Detournay law's closed
form (Richard, Germay & Detournay 2007), not the code's."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

from drillstring.cli import main
from drillstring.drilling import DrillConfig, drill
from drillstring.drilling.config import Autodriller
from drillstring.errors import ValidationError

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

# The rate form at 120 rpm with a = 0.108 m, eps = sigma = 60 MPa, zeta = 0.6, l = 11 mm:
# W = a zeta eps d + a l sigma with d = 2 pi V / Omega = V / (2 rev/s).
CUTTING = 0.108 * 0.6 * 60e6  # N per m of depth of cut per revolution
CONTACT = 0.108 * 0.011 * 60e6  # 71 280 N


def steady_rop_m_per_h(wob: float) -> float:
    return (wob - CONTACT) / CUTTING * 2.0 * 3600.0


def config(hoist: dict[str, Any], window: tuple[float, float] = (50.0, 60.0), **numerics: Any) -> DrillConfig:
    """A 200 m vertical pipe at 120 rpm, strongly damped (it settles), friction off."""
    return DrillConfig.from_dict({
        "damping_rate": 10.0,
        "sections": [{"length": 200.0, "outer_diameter": 0.127, "inner_diameter": 0.108,
                      "shear_modulus": 200e9 / 2.6, "density": 8000.0, "poisson_ratio": 0.3}],
        "well": {"inclination_deg": 0.0, "mud_density": 0.0},
        "friction": {"static": 0.0},
        "top_drive": {"rpm": 120.0, "ramp_time": 2.0, "controller": {"type": "speed"}},
        "bit": {"radius": 0.108, "law": "detournay"},
        "hoist": hoist,
        "numerics": {"cells": 100, "duration": 60.0, "output_interval": 0.01, **numerics},
        "metrics": {"window": list(window)},
    })


AUTODRILLER = {"mode": "autodriller", "ramp_time": 2.0,
               "autodriller": {"setpoint": 90e3, "kp": 5e-7, "ki": 1e-6, "max_speed": 100 / 3600}}


def test_the_configuration_reads_and_refuses_the_autodriller() -> None:
    cfg = config({**AUTODRILLER, "steps": [[30.0, 80e3]]})
    assert cfg.hoist is not None and cfg.hoist.mode == "autodriller"
    assert cfg.hoist.autodriller == Autodriller(target="weight_on_bit", setpoint=90e3, kp=5e-7, ki=1e-6,
                                                min_speed=0.0, max_speed=100 / 3600)
    assert cfg.hoist.steps == ((30.0, 80e3),)
    # A string with a unit is converted to the target's SI unit: 18 klbf = 18 000 x 4.4482216152605 N.
    cfg = config({**AUTODRILLER, "autodriller": {**AUTODRILLER["autodriller"], "setpoint": "18 klbf"}})
    assert cfg.hoist is not None and cfg.hoist.autodriller.setpoint == pytest.approx(80_067.989, rel=1e-9)
    cfg = config({**AUTODRILLER, "autodriller": {**AUTODRILLER["autodriller"], "target": "rop",
                                                 "setpoint": "60 ft/h"}})
    assert cfg.hoist is not None and cfg.hoist.autodriller.setpoint == pytest.approx(60 * 0.3048 / 3600, rel=1e-12)
    with pytest.raises(ValidationError, match="hoist.autodriller.setpoint"):
        config({**AUTODRILLER, "autodriller": {"setpoint": "3 m", "kp": 1e-7}})
    # No gain: refused, naming the field and what it takes.
    with pytest.raises(ValidationError) as err:
        config({**AUTODRILLER, "autodriller": {"setpoint": 90e3}})
    assert err.value.field == "hoist.autodriller.kp" and "kp > 0 or ki > 0" in str(err.value)
    with pytest.raises(ValidationError) as err:
        config({**AUTODRILLER, "autodriller": {**AUTODRILLER["autodriller"], "min_speed": 0.01, "max_speed": 0.001}})
    assert err.value.field == "hoist.autodriller.max_speed"
    with pytest.raises(ValidationError) as err:
        config({**AUTODRILLER, "steps": [[30.0, 80e3], [20.0, 70e3]]})
    assert err.value.field == "hoist.steps[1]"
    with pytest.raises(ValidationError, match="hoist.mode"):
        config({"mode": "weight"})


def test_the_autodriller_settles_at_its_weight_and_follows_a_step(tmp_path: Path) -> None:
    result = drill(config({**AUTODRILLER, "steps": [[30.0, 80e3]]}, field_interval=1.0))
    assert result.success, result.message
    wob, rop = result.axial["weight_on_bit"], result.axial["rop"]
    before = np.abs(result.t - 29.0).argmin()
    assert wob[before] == pytest.approx(90e3, rel=1e-4)
    assert rop[before] == pytest.approx(steady_rop_m_per_h(90e3), rel=1e-3)
    window = result.t >= 50.0
    assert np.abs(wob[window] / 80e3 - 1).max() < 1e-4
    c = result.coupled_metrics
    assert c is not None and c["rop_mean_m_per_h"] == pytest.approx(steady_rop_m_per_h(80e3), rel=1e-3)
    assert not [w for w in result.warnings if "never touched" in w]
    # The block's limit: 90 kN needs 34.7 m/h; held to 20 m/h the bit drills at 20 m/h.
    limited = drill(config({**AUTODRILLER, "autodriller": {**AUTODRILLER["autodriller"], "max_speed": 20 / 3600}}))
    c = limited.coupled_metrics
    assert c is not None and c["rop_mean_m_per_h"] == pytest.approx(20.0, rel=1e-3)
    assert c["wob_mean_N"] == pytest.approx(CONTACT + CUTTING * 20 / 3600 / 2, rel=1e-3)
    assert limited.axial["rop"].max() < 20.0 * 1.5  # the bit catches up with the block only briefly
    # The outputs: series.csv has the core's axial series after the torsional columns, fields.npz
    # the axial field, and the axial figures are drawn.
    paths = result.save(tmp_path / "run")
    names = {p.name for p in paths}
    assert {"axial_time.png", "axial_space_time.png"} <= names
    frame = pd.read_csv(tmp_path / "run" / "series.csv", index_col="t")
    assert list(frame.columns) == ["surface_rpm", "bit_rpm", "motor_torque", "bit_torque", "bit_axial_speed",
                                   "rop", "weight_on_bit", "hook_load", "bit_depth", "depth_of_cut", "block_position"]
    np.testing.assert_allclose(frame["weight_on_bit"], wob, rtol=1e-9)
    fields = np.load(tmp_path / "run" / "fields.npz")
    assert fields["axial_speed_m_s"].shape == (result.field_t.size, result.axial_z.size) == (61, fields["axial_z"].size)
    # at the end every cell moves down at the rate of penetration (within 0.5 %, the splitting)
    np.testing.assert_allclose(fields["axial_speed_m_s"][-1], steady_rop_m_per_h(80e3) / 3600, rtol=5e-3)
    assert "axial_time.png" in (tmp_path / "run" / "report.md").read_text()


def test_the_autodriller_on_rop() -> None:
    hoist = {"mode": "autodriller", "ramp_time": 2.0,
             "autodriller": {"target": "rop", "setpoint": 20 / 3600, "kp": 0.5, "ki": 2.0}}
    result = drill(config(hoist))
    c = result.coupled_metrics
    assert c is not None and c["rop_mean_m_per_h"] == pytest.approx(20.0, rel=1e-3)
    assert c["wob_mean_N"] == pytest.approx(CONTACT + CUTTING * 20 / 3600 / 2, rel=1e-3)


def test_a_bit_lifted_off_bottom_is_warned_about() -> None:
    result = drill(config({"speed": -0.01}, (5.0, 10.0), duration=10.0))
    c = result.coupled_metrics
    assert c is not None and c["bounce_fraction"] == 1.0 and c["rop_mean_m_per_h"] == 0.0
    [warning] = [w for w in result.warnings if "never touched bottom" in w]
    assert "[5, 10] s" in warning and "hoist.speed" in warning


def test_torsion_only_series_csv_is_unchanged_and_field_units_convert(tmp_path: Path,
                                                                      capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plain"
    assert main(["drill", str(EXAMPLES / "on-bottom-3000m.toml"), "--out", str(out), "--no-plots",
                 "--set", "numerics.duration=2", "--set", "numerics.cells=100"]) == 0
    header = (out / "series.csv").read_text().splitlines()[0]
    assert header == "t,surface_rpm,bit_rpm,motor_torque,bit_torque"
    assert "axial_z" not in np.load(out / "fields.npz").files
    assert not (out / "axial_time.png").exists()
    # a coupled run in field units: the console's ROP in ft/h, WOB in klbf; the data stay SI
    out = tmp_path / "coupled"
    capsys.readouterr()
    assert main(["drill", str(EXAMPLES / "aarsnes-van-de-wouw-2019.toml"), "--out", str(out), "--units", "field",
                 "--set", "numerics.duration=20", "--set", "numerics.cells=200", "--set", "numerics.field_interval=1",
                 "--set", "metrics.window=[10.0, 20.0]"]) == 0
    c = json.loads((out / "metrics.json").read_text())["coupled"]
    [line] = [x for x in capsys.readouterr().out.splitlines() if x.startswith("on bottom:")]
    assert f"ROP {c['rop_mean_m_per_h'] / 0.3048:.4g} ft/h" in line
    assert f"weight on bit {c['wob_mean_N'] / 4448.2216152605:.4g} klbf" in line
    assert (out / "axial_space_time.png").exists() and (out / "axial_time.png").exists()
    # series.csv stays SI (m, N) in field units too
    frame = pd.read_csv(out / "series.csv", index_col="t")
    window = frame.index >= 10.0
    assert math.isclose(frame["weight_on_bit"][window].mean(), c["wob_mean_N"], rel_tol=1e-6)
