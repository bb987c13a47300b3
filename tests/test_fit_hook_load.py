"""The wall friction from the hook load of a pick-up (examples/pickup-3200m.toml): a coupled run
pulled up off bottom without rotation.

Oracles: the soft-string torque-and-drag pick-up load (`ds.torque_drag`, Johancsik 1984, checked
against welleng in tests/test_torque_drag*.py), which the coupled run's steady hook load must
equal in a straight hole with one friction factor; the known friction factor of synthetic data.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import drillstring as ds
from drillstring.cli import main
from drillstring.errors import ValidationError

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "pickup-3200m.toml"


@pytest.fixture(scope="module")
def pickup() -> ds.DrillResult:
    return ds.drill(ds.load_drill_config(EXAMPLE), progress=False)


def test_the_pickup_load_is_the_torque_and_drag_pickup_load(pickup: ds.DrillResult) -> None:
    cfg = ds.load_drill_config(EXAMPLE)
    td = ds.torque_drag(cfg)
    hanging = ds.torque_drag(cfg.with_overrides({"friction.static": 0.0}))
    # at rest: the hanging string's static hook load
    assert pickup.axial["hook_load"][0] == pytest.approx(hanging.hook_load_pickup_N, rel=1e-9)
    # pulled at 0.05 m/s: the static load plus the drag mu N L (the mean over the axial waves)
    c = pickup.coupled_metrics
    assert c is not None and pickup.coupled_regime == "off bottom"
    # a pick-up without rotation: one note says why there are no torsional metrics, no warning
    # that the bit never touched bottom (the hoist lifts it on purpose)
    assert not pickup.rotating and not pickup.metrics_finite
    assert len(pickup.warnings) == 1 and pickup.warnings[0].startswith("no rotation: top_drive.rpm is 0"), \
        pickup.warnings
    drag = td.hook_load_pickup_N - hanging.hook_load_pickup_N
    assert drag > 80e3
    assert c["hook_load_mean_N"] == pytest.approx(td.hook_load_pickup_N, abs=0.005 * drag)
    assert c["hook_load_mean_N"] == pytest.approx(863.4e3, abs=0.05e3)  # the example's header
    # without friction the hook load stays the static one
    free = ds.drill(ds.load_drill_config(EXAMPLE).with_overrides({"friction.static": 0.0}), progress=False)
    assert free.coupled_metrics is not None
    assert free.coupled_metrics["hook_load_mean_N"] == pytest.approx(hanging.hook_load_pickup_N, abs=0.01 * drag)


def test_the_slackoff_load_is_the_torque_and_drag_slackoff_load() -> None:
    """Picked up for 25 s, then lowered at 0.02 m/s (the friction reverses along the string over
    some 20 s): the mean hook load over 60-75 s is the soft-string slack-off load."""
    cfg = ds.load_drill_config(EXAMPLE).with_overrides(
        {"hoist.steps": [[25.0, 0.02]], "numerics.duration": 75.0, "metrics.window": [60.0, 75.0]})
    run = ds.drill(cfg, progress=False)
    td = ds.torque_drag(cfg)
    hanging = ds.torque_drag(cfg.with_overrides({"friction.static": 0.0})).hook_load_pickup_N
    drag = hanging - td.hook_load_slackoff_N
    assert drag > 80e3
    c = run.coupled_metrics
    assert c is not None and run.coupled_regime == "off bottom"  # lowered, not yet on the rock
    assert c["hook_load_mean_N"] == pytest.approx(td.hook_load_slackoff_N, abs=0.005 * drag)


@pytest.fixture(scope="module")
def measured(pickup: ds.DrillResult) -> pd.DataFrame:
    """The pick-up's hook load at 10 Hz with 2 kN of sensor noise, in kN."""
    rng = np.random.default_rng(3)
    t = pickup.t[::10]
    return pd.DataFrame({"t": t, "hook_load": (pickup.axial["hook_load"][::10] + rng.normal(0.0, 2e3, t.size)) / 1e3})


def test_the_friction_factor_from_the_hook_load(measured: pd.DataFrame, tmp_path: Path) -> None:
    data = tmp_path / "pickup.csv"
    measured.rename(columns={"hook_load": "hook_load [kN]"}).to_csv(data, index=False)
    res = ds.fit(EXAMPLE, str(data), {"friction.static": (0.05, 0.5)}, targets="hook_load", windows=[(10.0, 30.0)],
                 landscape=False, threads=2, samples=16, starts=1)
    p = res.parameters["friction.static"]
    assert p.ci_low <= 0.2 <= p.ci_high and p.identifiable, p
    assert p.ci_high - p.ci_low < 0.01, p
    # the residual is the sensor noise, not a model error
    assert res.rms[0]["hook_load"] == pytest.approx(2e3, rel=0.1)


@pytest.mark.slow
def test_the_command_fits_the_hook_load(measured: pd.DataFrame, tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    data = tmp_path / "pickup.csv"
    measured.rename(columns={"hook_load": "HKLD [kN]"}).to_csv(data, index=False)
    out = tmp_path / "fit"
    assert main(["fit", str(EXAMPLE), "--data", str(data), "--column", "hook_load=HKLD", "--target", "hook_load",
                 "--param", "friction.static=0.05:0.5", "--window", "10:30", "--out", str(out),
                 "--no-landscape", "--samples", "16"]) == 0
    text = capsys.readouterr().out
    assert "friction.static" in text and (out / "fit.json").exists()
    # next: the torque and drag of the calibrated well, which runs
    assert "next, the torque and drag of the calibrated well" in text
    (command,) = [line.strip() for line in text.splitlines() if line.strip().startswith("drillstring torque-drag")]
    assert main(command.split()[1:]) == 0


def test_the_console_of_a_pickup(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["drill", str(EXAMPLE), "--out", str(tmp_path / "run"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    assert "(success; no rotation: no torsional metrics)" in out
    assert "off bottom: hook load 863.4 kN (mean over the window); regime: off bottom" in out
    # lowered onto the rock (the same string turning), the run is on bottom and rotating again
    assert main(["drill", str(EXAMPLE), "--out", str(tmp_path / "down"), "--no-plots", "--set", "hoist.speed=0.01",
                 "--set", "top_drive.rpm=60"]) == 0
    out = capsys.readouterr().out
    assert "(success)" in out and "on bottom: ROP" in out and "no rotation" not in out


def test_axial_targets_need_a_coupled_run(measured: pd.DataFrame) -> None:
    torsion_only = ds.load_drill_config(Path(__file__).resolve().parents[1] / "examples" / "on-bottom-3000m.toml")
    with pytest.raises(ValidationError, match="hook_load and weight_on_bit need a coupled run"):
        ds.fit(torsion_only, measured, {"friction.static": (0.05, 0.5)}, targets="hook_load")
    with pytest.raises(ValidationError, match="series the model computes"):
        ds.fit(EXAMPLE, measured, {"friction.static": (0.05, 0.5)}, targets="block_position")
