"""What the user guide states about controller presets, the stick-slip verdict, the warnings and
calibration, checked against the runs and commands it names: the numbers are read from the pages
(docs/guide/*.md), so a page and the code cannot drift apart unnoticed.

The oracles are independent of the code under test where one exists (the calibration example's
truth is the configuration that made its data); elsewhere the page's numbers are the recorded
measurement and the test is what keeps them true.
"""

from __future__ import annotations

import contextlib
import io
import math
import re
import shutil
from pathlib import Path

import _docs
import pytest
from _cli import run_cli

import drillstring as ds

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "guide"
ON_BOTTOM = ROOT / "examples" / "on-bottom-3000m.toml"


def _page(name: str) -> str:
    return (GUIDE / name).read_text(encoding="utf-8")


def _comment_lines(block: str) -> list[str]:
    """The ``# ...`` lines of a block after its last line of code (the output the page shows)."""
    lines = block.rstrip("\n").splitlines()
    out: list[str] = []
    for line in reversed(lines):
        if not line.startswith("# "):
            break
        out.insert(0, line[2:])
    return out


def test_the_preset_table_of_the_controllers_page_is_what_the_presets_give() -> None:
    rows = re.findall(r"^\| (?:preset `(\w+)`|the example's PI) \| ([\d.]+) \| ([\d.]+) \| stick-slip: (\w+); "
                      r"(settled|not settled)", _page("controllers.md"), flags=re.M)
    assert len(rows) == 4, rows
    base = ds.load_drill_config(ON_BOTTOM).with_overrides(["top_drive.rpm=40"])
    for preset, ssi, stuck, verdict, settled in rows:
        cfg = base.with_overrides([f"top_drive.controller.preset={preset}"]) if preset else base
        m = ds.drill(cfg, progress=False).metrics
        decimals = len(ssi.partition(".")[2])
        assert round(m.ssi, decimals) == float(ssi), (preset, m.ssi, ssi)
        places = len(stuck.partition(".")[2])
        assert round(m.stuck_fraction, places) == float(stuck), (preset, m.stuck_fraction, stuck)
        assert m.stick_slip_verdict == verdict and m.settled == (settled == "settled"), (preset, m)


def test_the_tune_output_on_the_controllers_page_is_the_commands(capsys: pytest.CaptureFixture[str]) -> None:
    (block,) = [b for b in _docs.blocks("bash", [GUIDE / "controllers.md"]) if "drillstring tune" in b]
    code, out, _ = run_cli(capsys, "tune", str(ON_BOTTOM))
    assert code == 0
    assert out.strip().splitlines() == _comment_lines(block)


def test_the_verdict_lines_of_the_metrics_page_are_the_consoles(tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    page = _page("metrics.md")
    (block,) = re.findall(r"^```text\n(stick-slip:.*?)^```", page, flags=re.S | re.M)
    shown = block.strip().splitlines()
    runs = ([], ["--set", "top_drive.controller.preset=soft_torque"],
            ["--set", "top_drive.rpm=0", "--set", "numerics.duration=4"])
    assert len(shown) == len(runs)
    for k, (line, extra) in enumerate(zip(shown, runs)):
        code, out, err = run_cli(capsys, "drill", str(ON_BOTTOM), "--no-plots", "--out", str(tmp_path / f"r{k}"),
                                 *extra)
        assert code == 0
        printed = [s for s in (out + err).splitlines() if s.startswith("stick-slip:")]
        assert printed == [line], (extra, printed)
    # the run of a bit that never turns is flagged as the page says
    assert "(success, but metrics not finite: not a result)" in page and "(success, but metrics not finite: " \
        "not a result)" in out + err


@pytest.mark.parametrize(("override", "words"), [
    (["sections[0].outer_diameter=1.5", "sections[0].inner_diameter=1.4"], "sections[0].outer_diameter = 1.5 m"),
    (["bit.radius=0.3"], "bit.radius = 0.3 m is a bit over 0.5 m across"),
    (["top_drive.rpm=450"], "a top-drive speed of 450 rpm is over the 400 rpm"),
    (["sections[0].length=15000", "well.extend=true"], "over the 15000 m of the deepest wells"),
])
def test_each_value_warning_the_metrics_page_lists_fires_beyond_its_threshold(override: list[str],
                                                                              words: str) -> None:
    page = _page("metrics.md")
    for threshold in ("over 1 m", "over 0.25 m", "longer than 15 000 m", "over 400 rpm"):
        assert threshold in page
    cfg = ds.load_drill_config(ON_BOTTOM).with_overrides(["numerics.duration=1", "numerics.cells=100"])
    assert not any(words.split(" is ")[0] in w for w in ds.drill(cfg, progress=False, check=False).warnings)
    run = ds.drill(cfg.with_overrides(override), progress=False, check=False)
    assert any(words in w for w in run.warnings), run.warnings


def test_the_calibration_example_recovers_the_truth_and_prints_what_the_page_shows(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (block,) = [b for b in _docs.blocks("python", [GUIDE / "calibration.md"]) if "ds.fit(" in b and "top=" not in b]
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    printed = io.StringIO()
    scope: dict[str, object] = {"__name__": "__example__"}
    with contextlib.redirect_stdout(printed):
        exec(compile(block, "the calibration example", "exec"), scope)
    assert printed.getvalue().strip().splitlines() == _comment_lines(block)
    res = scope["res"]
    assert isinstance(res, ds.FitResult)
    # the oracle: the values of the example file that made the data
    truth = ds.load_drill_config(ROOT / "examples" / "aarsnes-shor-well-b-corrected.toml").friction
    assert (truth.static, truth.kinetic_ratio) == (0.3, 0.65)
    for key, true in (("friction.static", truth.static), ("friction.kinetic_ratio", truth.kinetic_ratio)):
        p = res.parameters[key]
        assert p.ci_low <= true <= p.ci_high and p.identifiable, (key, p)
        assert p.ci_high - p.ci_low < 0.025 * true  # "1-2.5 % of them wide"
    assert res.rms[0]["motor_torque"] == pytest.approx(500.0, rel=0.1)  # the sensor noise
    assert math.isfinite(res.condition) and res.warnings == []


def test_the_verdict_count_of_the_maps_page_is_the_quick_start_maps(tmp_path: Path,
                                                                     capsys: pytest.CaptureFixture[str]) -> None:
    (line,) = re.findall(r"`(stick-slip: yes in \d+ runs .*?)`", _page("maps.md").replace("\n", " "))
    code, out, err = run_cli(capsys, "drill-map", str(ON_BOTTOM), "--axis", "top_drive.rpm=40:120:5", "--axis",
                             "bit.weight_on_bit=40e3:120e3:3", "--no-plots", "--out", str(tmp_path / "m"))
    assert code == 0
    assert line in (out + err).replace("\n", " "), (line, out + err)
