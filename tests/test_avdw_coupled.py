"""examples/aarsnes-van-de-wouw-2019.toml against the Octave run of Aarsnes & van de Wouw's
published code at 30 rpm / 30 m/h (tests/reference/aarsnes-van-de-wouw-2019, the 120 s run,
whose last 5 s are settled at the bit law's steady state: WOB spread 1e-4), and its twin with the
exact delay, examples/aarsnes-van-de-wouw-2019-converged.toml (against the numpy oracle:
tests/test_avdw_converged.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from avdw_reference import reference

from drillstring.drilling import DrillResult, drill, load_drill_config

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-van-de-wouw-2019.toml"
CONVERGED = EXAMPLE.with_name("aarsnes-van-de-wouw-2019-converged.toml")


def _octave() -> dict:
    return reference()["cases"]["rpm30_rop30"]["long_120s"]["metrics"]


def _at_their_steady_state(result: DrillResult, ref: dict) -> None:
    """ROP, WOB, TOB and MSE within 0.5 % of their run's, no bounce, no stick."""
    assert result.success, result.message
    m = result.coupled_metrics
    assert m is not None
    assert m["rop_mean_m_per_h"] == pytest.approx(ref["rop_mean_m_per_h"], rel=5e-3)
    assert m["wob_mean_N"] == pytest.approx(ref["wob_N"]["mean"], rel=5e-3)
    assert m["tob_mean_Nm"] == pytest.approx(ref["tob_Nm"]["mean"], rel=5e-3)
    assert m["mse_mean_Pa"] == pytest.approx(ref["mse_mean_Pa"], rel=5e-3)
    assert m["bounce_fraction"] == 0.0 and result.metrics.stuck_fraction == 0.0


def test_the_rate_form_settles_where_the_published_code_does() -> None:
    # Both runs sit at the Detournay law's steady state (d = 2 pi V / Omega = 1/60 m, their contact
    # torque: geometry = 2); what is left is their first-order cut surface (depth of cut 0.07 %
    # below nominal, ROP 0.16 % below the hoist's) and how the ends are discretised: 0.5 %.
    ref = _octave()
    result = drill(load_drill_config(EXAMPLE).with_overrides({"bit.law": "detournay"}))
    _at_their_steady_state(result, ref)
    assert abs(result.energy["balance_error"]) < 1e-12


def test_the_published_example_settles_where_the_published_code_does() -> None:
    # The example as written: their upwind cut surface on 169 cells (bit.detournay.cut_surface =
    # "upwind"), whose numerical diffusion damps the regenerative instability: the run settles at
    # the law's steady state as theirs does, ROP, WOB, TOB and MSE within 0.5 % of their 120 s run.
    ref = _octave()
    cfg = load_drill_config(EXAMPLE)
    assert (cfg.bit.law, cfg.bit.detournay.cut_surface, cfg.bit.detournay.cut_surface_cells) == ("rgd", "upwind", 169)
    result = drill(cfg)
    _at_their_steady_state(result, ref)
    late = result.t >= 180.0
    wob, rpm = result.axial["weight_on_bit"][late], result.bit_rpm[late]
    assert wob.max() - wob.min() < 1e-3 * ref["wob_N"]["mean"]  # settled, as theirs (1e-4)
    assert rpm.max() - rpm.min() < 0.01 * 30.0
    assert abs(result.energy["balance_error"]) < 1e-12


def test_the_exact_delay_cycles_about_the_same_steady_state() -> None:
    # The converged twin (bit.law = "rgd" with the exact delay): the regenerative instability
    # their diffusive cut surface damps grows into a coupled limit cycle (WOB ~123 to ~141 kN,
    # the bit stopping for ~1 % of the time);
    # it drills at the hoist's speed and its mean weight and torque stay within 3 % of the
    # settled run's.
    ref = _octave()
    result = drill(load_drill_config(CONVERGED))
    assert result.success, result.message
    m = result.coupled_metrics
    assert m is not None
    assert m["rop_mean_m_per_h"] == pytest.approx(30.0, rel=5e-3)
    assert m["wob_mean_N"] == pytest.approx(ref["wob_N"]["mean"], rel=0.03)
    assert m["tob_mean_Nm"] == pytest.approx(ref["tob_Nm"]["mean"], rel=0.03)
    wob = result.axial["weight_on_bit"][result.t >= 180.0]
    assert wob.max() - wob.min() > 0.05 * ref["wob_N"]["mean"]  # not settled: the limit cycle
    assert abs(result.energy["balance_error"]) < 1e-12


def test_the_console_names_the_on_bottom_numbers(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """`drillstring drill` of a coupled run prints ROP, WOB, TOB, bounce and MSE, the numbers of
    metrics.json's `coupled` (SI: m/h, kN, kN m, MPa)."""
    import json

    from drillstring.cli import main

    example = Path(__file__).resolve().parents[1] / "examples" / "aarsnes-van-de-wouw-2019.toml"
    assert main(["drill", str(example), "--out", str(tmp_path / "run"), "--no-plots",
                 "--set", "numerics.duration=20", "--set", "numerics.cells=200",
                 "--set", "metrics.window=[10.0, 20.0]"]) == 0
    line = [x for x in capsys.readouterr().out.splitlines() if x.startswith("on bottom:")]
    c = json.loads((tmp_path / "run" / "metrics.json").read_text())["coupled"]
    # the registry's coupled metrics in its order, each by its label
    assert line == [f"on bottom: ROP {c['rop_mean_m_per_h']:.4g} m/h, weight on bit {c['wob_mean_N'] / 1e3:.4g} kN, "
                    f"torque on bit {c['tob_mean_Nm'] / 1e3:.4g} kN m, bit bounce {c['bounce_fraction']:.3g}, "
                    f"hook load {c['hook_load_mean_N'] / 1e3:.4g} kN, MSE {c['mse_mean_Pa'] / 1e6:.4g} MPa; "
                    f"regime: {c['regime']}"]
