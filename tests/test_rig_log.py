"""``drillstring rig-log`` / ``ds.rig_log``: a made-up rig log whose states, depths, rate of
penetration and events are known by construction; the same log in other units and layouts; the
LAS null and gaps; bad input; the real shared log (read from ``../shared/data/rig-logs`` beside
the repository, skipped where absent)."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from _cli import one_line_error, run_cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.calibration.rig_log import RigStateRules, estimate_block_weight
from drillstring.errors import MissingExtraError, ValidationError

SHARED_LOG = Path(__file__).resolve().parents[2] / "shared" / "data" / "rig-logs" / "sample-data-1.csv"

BLOCK = 150e3  # N, the block and top drive
KLBF = 4448.2216152605
FT = 0.3048
FT_LBF = FT * 4.4482216152605
PSI = 6894.757293168361


@dataclass
class Segment:
    """Rows of the made-up log: the block's rise per row (m/s at 1 Hz), the hook load, the
    surface speed and torque, the pumps, whether the string hangs in the slips, the true state."""

    rows: int
    rise: float
    hook: float
    state: int
    rpm: Any = 0.0
    torque: Any = 0.0
    pumps: bool = False
    slips: bool = False


def _segments(drill_rows: int) -> list[Segment]:
    """Drilling a stand, its connection, a pick-up, a slack-off, a start-up off bottom, a trip out."""
    k = np.arange(drill_rows + 1)
    return [
        # drilling at 36 m/h, 120 rpm, surface torque 10 +- 3 kN m with a 4 s period
        Segment(drill_rows + 1, -0.01, 350e3, 2, 120.0, 10e3 + 3e3 * np.sin(np.pi / 2 * k), pumps=True),
        Segment(10, 0.0, 360e3, 0),  # on bottom, pumps off, not rotating
        Segment(300, 0.0, BLOCK, 3, slips=True),  # connection: block up 28 m with the string in slips
        Segment(10, 0.0, 400e3, 0),  # picked up weight, still on bottom
        Segment(60, 0.2, 420e3, 9),  # pick-up: 12 m at 0.2 m/s
        Segment(30, 0.0, 400e3, 0),
        Segment(30, -0.2, 380e3, 8),  # slack-off: 6 m down
        Segment(30, 0.0, 400e3, 7, pumps=True),  # circulating at rest
        Segment(65, 0.0, 400e3, 7, np.r_[20.0, 40, 60, 80, np.full(61, 100.0)],
                np.r_[3e3, 6e3, 9e3, 12e3, 15e3, np.full(60, 8e3)], pumps=True),  # start-up
        Segment(20, 0.0, 400e3, 0),
        Segment(60, 0.5, 430e3, 9),  # trip out 30 m
        Segment(30, 0.0, BLOCK, 3, slips=True),
    ]


def synthetic(drill_rows: int = 2800, start_depth: float = 1000.0) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The made-up log in SI (``t``, ``block_height``, ``hook_load``, ``surface_rpm``,
    ``surface_torque``, ``standpipe_pressure``, ``flow_out``) and its truth (state, bit and hole
    depth per row, the rows next to a change of segment)."""
    segments = _segments(drill_rows)
    rise, hook, rpm, torque, pumps, state, hanging, edge = ([] for _ in range(8))
    for seg in segments:
        rise.append(np.full(seg.rows, seg.rise))
        hook.append(np.full(seg.rows, seg.hook))
        rpm.append(np.broadcast_to(seg.rpm, seg.rows))
        torque.append(np.broadcast_to(seg.torque, seg.rows))
        pumps.append(np.full(seg.rows, seg.pumps))
        state.append(np.full(seg.rows, seg.state))
        hanging.append(np.full(seg.rows, not seg.slips))
        e = np.zeros(seg.rows, bool)
        e[:4] = e[-4:] = True
        edge.append(e)
    cat = np.concatenate
    rise_, hanging_ = cat(rise), cat(hanging)
    rise_[0] = 0.0
    slips_rows = ~hanging_
    rise_[slips_rows] = 0.0
    # the block climbs 28 m in slips over the connection's middle rows (a new stand picked up)
    conn = np.flatnonzero(slips_rows)[:300]
    rise_[conn[10:290]] = 0.1
    block = 30.0 + np.cumsum(rise_)
    bit = start_depth + np.cumsum(np.where(hanging_, -rise_, 0.0))  # the bit moves with the hanging string
    n = block.size
    frame = pd.DataFrame({
        "t": 100.0 + np.arange(n, dtype=float), "block_height": block, "hook_load": cat(hook),
        "surface_rpm": cat(rpm), "surface_torque": cat(torque),
        "standpipe_pressure": np.where(cat(pumps), 15e6, 0.2e6), "flow_out": np.where(cat(pumps), 30.0, 0.0),
    })
    truth = {"state": cat(state), "bit": bit, "hole": np.maximum.accumulate(bit), "edge": cat(edge),
             "segments": segments}
    return frame, truth


@pytest.fixture(scope="module")
def made_up() -> tuple[pd.DataFrame, dict[str, Any], Any]:
    frame, truth = synthetic()
    return frame, truth, ds.rig_log(frame, start_depth=1000.0)


def test_depths_of_the_made_up_log_are_its_true_depths(made_up: Any) -> None:
    _, truth, result = made_up
    s = result.states
    np.testing.assert_allclose(s["bit_depth_m"], truth["bit"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(s["hole_depth_m"], truth["hole"], rtol=0, atol=1e-9)
    assert result.summary["depth_range_m"]["drilled"] == pytest.approx(28.0, abs=1e-9)


def test_the_states_of_the_made_up_log_are_its_true_states(made_up: Any) -> None:
    """Every row but the few at a change of segment (the bit speed is a 5 s centred difference;
    the bit within 0.3 m of the bottom is on bottom) has its true state."""
    _, truth, result = made_up
    state = result.states["rig_state"].to_numpy()
    inside = ~truth["edge"]
    wrong = np.flatnonzero(inside & (state != truth["state"]))
    assert wrong.size == 0, [(int(i), int(state[i]), int(truth["state"][i])) for i in wrong[:10]]
    assert set(np.unique(state)) >= {0, 2, 3, 7, 8, 9}
    per_state = result.summary["time_per_state_s"]
    assert per_state["drilling"] == pytest.approx(2800.0, abs=1.0)
    assert per_state["connection"] == pytest.approx(329.0 + 1, abs=2.0)


def test_rop_and_the_drilled_interval_of_the_made_up_log(made_up: Any) -> None:
    """36 m/h everywhere in the drilling (the hole's advance per drilling time), one interval of
    28 m, and the torque's (max - min) / (2 mean) of 10 +- 3 kN m: 0.3."""
    _, truth, result = made_up
    s = result.states
    drilling = s["rig_state"].to_numpy() == 2
    np.testing.assert_allclose(s["rop_m_per_h"][drilling], 36.0, rtol=1e-9)
    assert (s["rop_m_per_h"][~drilling] == 0).all()
    (interval,) = result.intervals.to_dict("records")
    assert interval["drilled [m]"] == pytest.approx(28.0, abs=1e-9)
    assert interval["rop [m/h]"] == pytest.approx(36.0, rel=1e-9)
    assert interval["stick_slip_severity [1]"] == pytest.approx(0.3, abs=0.01)
    assert result.summary["rules"]["thresholds"]["block_weight"] == pytest.approx(BLOCK)


def test_events_of_the_made_up_log(made_up: Any) -> None:
    _, truth, result = made_up
    e = result.events
    assert list(e["event"]) == ["pick_up", "slack_off", "start_up", "rotating_off_bottom", "pick_up"]
    assert list(e["operation"]) == ["pick_up", "slack_off", "", "rotating_off_bottom", "pick_up"]
    np.testing.assert_allclose(e["hook_load [N]"], [420e3, 380e3, 400e3, 400e3, 430e3])
    pick, slack, start, rotating, trip = e.to_dict("records")
    assert 1016.0 <= pick["depth [m]"] <= 1028.0 and 1016.0 <= slack["depth [m]"] <= 1022.0
    assert 992.0 <= trip["depth [m]"] <= 1022.0
    assert start["depth [m]"] == rotating["depth [m]"] == pytest.approx(1022.0)
    assert start["peak_torque [N m]"] == 15e3
    assert rotating["surface_torque [N m]"] == 8e3 and rotating["surface_rpm [rpm]"] == 100.0
    series = result.series[start["series"]]
    assert series["t [s]"].iloc[0] == 0.0 and series["surface_rpm [rpm]"].iloc[0] == 0.0
    assert series["surface_rpm [rpm]"].iloc[-1] == 100.0 and series["motor_torque [N m]"].max() == 15e3


def _in_units(frame: pd.DataFrame, chosen: dict[str, tuple[str, float]], layout: str) -> str:
    """The SI ``frame`` as CSV text with each column in its chosen unit (name -> (unit, SI value
    of one unit)), the units as header suffixes or a units row."""
    out = pd.DataFrame({name: frame[name] / chosen[name][1] if name in chosen else frame[name] for name in frame})
    if layout == "suffix":
        out.columns = [f"{c} [{chosen[c][0]}]" if c in chosen else c for c in out.columns]
        return out.to_csv(index=False, float_format="%.17g")
    units = ",".join(chosen[c][0] if c in chosen else ("s" if c == "t" else "") for c in out.columns)
    text = out.to_csv(index=False, float_format="%.17g")
    header, rest = text.split("\n", 1)
    return f"{header}\n{units}\n{rest}"


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(length=st.sampled_from([("m", 1.0), ("ft", FT)]),
       force=st.sampled_from([("N", 1.0), ("kN", 1e3), ("klbf", KLBF), ("lbf", KLBF / 1e3)]),
       torque=st.sampled_from([("N m", 1.0), ("kN m", 1e3), ("ft lbf", FT_LBF), ("kft-lbf", 1e3 * FT_LBF)]),
       pressure=st.sampled_from([("Pa", 1.0), ("psi", PSI), ("bar", 1e5)]),
       layout=st.sampled_from(["suffix", "row"]))
def test_the_same_log_in_any_units_gives_the_same_si_result(tmp_path: Path, length: Any, force: Any, torque: Any,
                                                           pressure: Any, layout: str) -> None:
    """The made-up log written in ft, klbf, kft-lbf, psi, ... as header suffixes or a units row
    gives the states, depths and events of the SI log."""
    frame, _ = synthetic(drill_rows=300)
    reference = ds.rig_log(frame, start_depth=1000.0)
    chosen = {"block_height": length, "hook_load": force, "surface_torque": torque, "standpipe_pressure": pressure}
    path = tmp_path / f"log-{layout}.csv"
    path.write_text(_in_units(frame, chosen, layout), encoding="utf-8")
    start = "3280.839895013123 ft" if length[0] == "ft" else "1000 m"
    result = ds.rig_log(path, start_depth=start)
    assert (result.states["rig_state"] == reference.states["rig_state"]).all()
    np.testing.assert_allclose(result.states["bit_depth_m"], reference.states["bit_depth_m"], rtol=0, atol=1e-6)
    np.testing.assert_allclose(result.states["hook_load_N"], reference.states["hook_load_N"], rtol=1e-12)
    np.testing.assert_allclose(result.states["surface_torque_Nm"], reference.states["surface_torque_Nm"], rtol=1e-12)
    assert list(result.events["event"]) == list(reference.events["event"])
    np.testing.assert_allclose(result.events["hook_load [N]"], reference.events["hook_load [N]"], rtol=1e-12)


def _with_gaps(frame: pd.DataFrame, null_row: int = 1000) -> tuple[pd.DataFrame, int, int]:
    """The log with the hook load missing (-999.25) in 7 rows of the drilling from ``null_row``
    and 50 rows of the connection's middle cut out (a time jump of 51 s)."""
    out = frame.copy()
    out.loc[null_row:null_row + 6, "hook_load"] = -999.25
    connection = int(np.flatnonzero(frame["hook_load"] == BLOCK)[100])
    return out.drop(index=range(connection, connection + 50)).reset_index(drop=True), null_row, connection


def test_the_las_null_and_gaps_are_found_and_reported(tmp_path: Path) -> None:
    frame, truth = synthetic(drill_rows=2000)
    gappy, null_row, cut = _with_gaps(frame)
    result = ds.rig_log(gappy, start_depth=1000.0)
    s = result.summary
    assert s["null_values"]["hook_load"] == 7 and s["missing_values"]["hook_load"] == 7
    assert s["gap_count"] == {"time_jump": 1, "missing_values": 1}
    jump = next(g for g in s["gaps"] if g["kind"] == "time_jump")
    assert jump["duration_s"] == 51.0 and jump["t_start"] == frame["t"][cut - 1]
    missing = next(g for g in s["gaps"] if g["kind"] == "missing_values")
    assert missing["rows"] == 7 and missing["t_start"] == frame["t"][null_row]
    assert (result.states["rig_state"][null_row:null_row + 7] == 0).all()
    # the bit is held across the missing rows: the block's fall over them is not counted
    bit = result.states["bit_depth_m"].to_numpy()
    assert bit[null_row + 6] == bit[null_row - 1]
    assert bit[-1] == pytest.approx(truth["bit"][-1] - 8 * 0.01, abs=1e-9)
    assert len(result.states) == len(gappy)


def test_an_las_file_reads_as_its_csv(tmp_path: Path) -> None:
    lasio = pytest.importorskip("lasio")
    frame, _ = synthetic(drill_rows=300)
    gappy, _, _ = _with_gaps(frame, null_row=100)
    las = lasio.LASFile()
    las.well.NULL.value = -999.25
    for header, name, unit, scale in (("TIME", "t", "s", 1.0), ("BPOS", "block_height", "ft", FT),
                                      ("HKLD", "hook_load", "klbf", KLBF), ("RPM", "surface_rpm", "rpm", 1.0),
                                      ("TQA", "surface_torque", "kN.m", 1e3),
                                      ("SPPA", "standpipe_pressure", "kPa", 1e3), ("MFOP", "flow_out", "%", 1.0)):
        values = gappy[name].to_numpy() / scale
        las.append_curve(header, np.where(gappy[name] == -999.25, np.nan, values), unit=unit)
    path = tmp_path / "log.las"
    with open(path, "w", encoding="utf-8") as handle:
        las.write(handle, version=2.0, fmt="%.15g")
    assert "-999.25" in path.read_text(encoding="utf-8")
    from_las = ds.rig_log(path, start_depth=1000.0)
    from_frame = ds.rig_log(gappy, start_depth=1000.0)
    assert (from_las.states["rig_state"] == from_frame.states["rig_state"]).all()
    np.testing.assert_allclose(from_las.states["bit_depth_m"], from_frame.states["bit_depth_m"], atol=1e-6)
    assert from_las.summary["channels"]["hook_load"] == {"header": "HKLD", "unit": "klbf"}
    assert from_las.summary["missing_values"]["hook_load"] == 7


def test_las_without_lasio_names_the_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    path = tmp_path / "log.las"
    path.write_text("~Version\n", encoding="utf-8")
    monkeypatch.setitem(sys.modules, "lasio", None)
    with pytest.raises(MissingExtraError, match=r"extra 'las' \(lasio not installed\)"):
        ds.rig_log(path)


def test_block_weight_is_the_lowest_frequent_hook_load() -> None:
    """Drawn loads: a cluster at 140 kN (10 %), a few lower outliers, most rows at 300-400 kN."""
    rng = np.random.default_rng(1)
    loads = np.r_[rng.normal(140e3, 1e3, 1000), rng.uniform(60e3, 100e3, 200), rng.uniform(300e3, 400e3, 8800)]
    assert estimate_block_weight(loads) == pytest.approx(140e3, abs=500)


@pytest.mark.parametrize(("argv", "needles"), [
    (["--column", "hookload=HKLD"], ["--column", "hookload"]),
    (["--column", "hook_load"], ["--column", "NAME=HEADER"]),
    (["--unit", "hook_load=furlong"], ["units[hook_load]", "furlong"]),
    (["--start-depth", "3000 kg"], ["--start-depth", "3000 kg"]),
    (["--start-depth", "deep"], ["--start-depth"]),
    (["--hole-depth", "10 m", "--start-depth", "20 m"], ["--hole-depth"]),
    (["--rule", "speed=3"], ["--rule", "speed"]),
    (["--rule", "slips_margin=-5 klbf"], ["slips_margin"]),
])
def test_bad_options_are_one_line_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str],
                                         needles: list[str]) -> None:
    frame, _ = synthetic(drill_rows=100)
    path = tmp_path / "log.csv"
    frame.to_csv(path, index=False)
    code, _, err = run_cli(capsys, "rig-log", str(path), "--out", str(tmp_path / "out"), *argv)
    assert code == 2
    one_line_error(err, *needles)
    assert not (tmp_path / "out").exists()


def test_a_missing_channel_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    frame, _ = synthetic(drill_rows=100)
    path = tmp_path / "log.csv"
    frame.drop(columns="hook_load").to_csv(path, index=False)
    code, _, err = run_cli(capsys, "rig-log", str(path), "--out", str(tmp_path / "out"))
    assert code == 2
    one_line_error(err, "hook_load", "--column")
    with pytest.raises(ValidationError, match="block_height"):
        ds.rig_log(frame.drop(columns="block_height"))
    with pytest.raises(ValidationError, match="start_depth"):
        ds.rig_log(frame, start_depth="3 kg")


def test_mnemonics_and_mapped_headers_are_found(tmp_path: Path) -> None:
    """WITS mnemonics need no mapping; another header is mapped with columns=; both give the
    canonical log's result."""
    frame, _ = synthetic(drill_rows=200)
    reference = ds.rig_log(frame)
    wits = frame.rename(columns={"t": "TIME", "block_height": "BPOS", "hook_load": "HKLD", "surface_rpm": "RPM",
                                 "surface_torque": "TQA", "standpipe_pressure": "SPPA", "flow_out": "MFOP"})
    assert (ds.rig_log(wits).states["rig_state"] == reference.states["rig_state"]).all()
    odd = frame.rename(columns={"hook_load": "Load on the hook"})
    mapped = ds.rig_log(odd, columns={"hook_load": "Load on the hook"})
    assert (mapped.states["rig_state"] == reference.states["rig_state"]).all()


def test_the_cli_writes_the_folder_and_prints_the_next_commands(tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    frame, _ = synthetic(drill_rows=600)
    path = tmp_path / "log.csv"
    frame.to_csv(path, index=False)
    out = tmp_path / "states"
    code, text, err = run_cli(capsys, "rig-log", str(path), "--out", str(out), "--start-depth", "1000 m",
                              "--rule", "block_weight=150 kN")
    assert code == 0, err
    names = {p.name for p in out.iterdir()}
    assert {"states.csv", "events.csv", "intervals.csv", "summary.json", "report.md", "rig_log.png", "events.png",
            "start_up_01.csv"} <= names
    states = pd.read_csv(out / "states.csv")
    assert list(states.columns[:5]) == ["t", "rig_state", "bit_depth_m", "hole_depth_m", "rop_m_per_h"]
    assert {"hook_load_N", "surface_torque_Nm", "block_height_m", "standpipe_pressure_Pa"} <= set(states.columns)
    events = pd.read_csv(out / "events.csv", keep_default_na=False)
    assert list(events.columns[:8]) == ["event", "t_start", "t_end", "operation", "depth [m]", "hole_depth [m]",
                                        "hook_load [N]", "surface_torque [N m]"]
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["events"] == {"start_up": 1, "pick_up": 2, "slack_off": 1, "rotating_off_bottom": 1}
    assert f"--data {out / 'start_up_01.csv'}" in text and f"--measured {out / 'events.csv'}" in text
    # the start-up's file is what drillstring fit reads
    from drillstring.calibration.data import read_measured

    data = read_measured(out / "start_up_01.csv")
    assert set(data.series) == {"surface_rpm", "motor_torque", "hook_load"} and data.t[0] == 0.0


def test_rules_are_validated_and_read_with_units() -> None:
    rules = RigStateRules.from_pairs({"block_weight": "32 klbf", "moving_speed": "300 ft/h"})
    assert rules.block_weight == pytest.approx(32 * KLBF) and rules.moving_speed == pytest.approx(300 * FT / 3600)
    with pytest.raises(ValidationError, match="rules.on_bottom"):
        RigStateRules(on_bottom=-1.0)
    with pytest.raises(ValidationError, match="gap_factor"):
        RigStateRules(gap_factor=1.0)


needs_shared_log = pytest.mark.skipif(not SHARED_LOG.is_file(),
                                      reason=f"the shared rig log is not here ({SHARED_LOG})")


@needs_shared_log
def test_the_shared_rig_log(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The real 1 Hz log (50,000 rows): every row in states.csv, the hole deepening only, drilling
    and connections found, a plausible rate of penetration, a handful of events of each kind."""
    out = tmp_path / "rig"
    code, text, err = run_cli(capsys, "rig-log", str(SHARED_LOG), "--start-depth", "3000 ft", "--out", str(out),
                              "--no-plots")
    assert code == 0, err
    states = pd.read_csv(out / "states.csv")
    assert len(states) == 50_000
    assert (np.diff(states["hole_depth_m"]) >= 0).all()
    assert states["bit_depth_m"].iloc[0] == pytest.approx(3000 * FT)
    drilling = states[states["rig_state"] == 2]
    codes = set(states["rig_state"])
    assert {2, 3} <= codes and codes <= {0, 2, 3, 4, 7, 8, 9}
    assert drilling["rop_m_per_h"].between(0, 200).all()
    assert (drilling["bit_depth_m"] >= drilling["hole_depth_m"] - RigStateRules().on_bottom).all()
    intervals = pd.read_csv(out / "intervals.csv")
    assert (intervals["depth_to [m]"] > intervals["depth_from [m]"]).all()
    assert intervals["rop [m/h]"].between(1, 200).all()
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["missing_values"]["hook_load"] == 1458 and summary["gap_count"]["missing_values"] == 2
    assert all(3 <= n <= 100 for n in summary["events"].values()), summary["events"]
    assert summary["time_per_state_s"]["drilling"] > 3 * 3600
    assert math.isfinite(summary["rop_mean_m_per_h"]) and 5 < summary["rop_mean_m_per_h"] < 100
    assert "drillstring fit" in text and "drillstring torque-drag" in text


@needs_shared_log
def test_the_guides_python_example_prints_what_it_says(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    """The Python example of docs/guide/rig-logs.md, run beside the shared log, prints the line
    its comment gives; the numbers of the guide's command output are those of the summary."""
    import _docs

    page = Path(__file__).resolve().parents[1] / "docs" / "guide" / "rig-logs.md"
    (block,) = [b for b in _docs.blocks("python", [page]) if "ds.rig_log(" in b]
    (tmp_path / "sample-data-1.csv").symlink_to(SHARED_LOG)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(block, "rig-logs example", "exec"), {"__name__": "__example__"})
    printed = capsys.readouterr().out.splitlines()
    expected = [line[2:] for line in block.splitlines() if line.startswith("# ")]
    assert printed[0] == expected[0]
    summary = json.loads((tmp_path / "rig-states" / "summary.json").read_text(encoding="utf-8"))
    text = page.read_text(encoding="utf-8")
    hours = ", ".join(f"{name.replace('_', ' ')} {seconds / 3600:.2f} h"
                      for name, seconds in summary["time_per_state_s"].items())
    assert f"# states: {hours}\n" in text
    d = summary["depth_range_m"]
    assert (f"hole depth {d['hole_start']:.1f} m -> {d['hole_end']:.1f} m ({d['drilled']:.1f} m in "
            f"{summary['drilled_intervals']} intervals, mean ROP {summary['rop_mean_m_per_h']:.3g} m/h)") in text
    assert f"block weight of {summary['rules']['thresholds']['block_weight'] / 1e3:.0f} kN" in text


def test_a_parquet_log_with_units_in_its_headers_reads_as_the_si_log(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    frame, _ = synthetic(drill_rows=300)
    reference = ds.rig_log(frame, start_depth=1000.0)
    field = pd.DataFrame({"t [s]": frame["t"], "block_height [ft]": frame["block_height"] / FT,
                          "hook_load [klbf]": frame["hook_load"] / KLBF, "surface_rpm [rpm]": frame["surface_rpm"],
                          "surface_torque [kft lbf]": frame["surface_torque"] / (1e3 * FT_LBF),
                          "standpipe_pressure [psi]": frame["standpipe_pressure"] / PSI,
                          "flow_out [%]": frame["flow_out"]})
    path = tmp_path / "log.parquet"
    field.to_parquet(path)
    result = ds.rig_log(path, start_depth="3280.839895013123 ft")
    assert (result.states["rig_state"] == reference.states["rig_state"]).all()
    np.testing.assert_allclose(result.states["bit_depth_m"], reference.states["bit_depth_m"], atol=1e-6)
    np.testing.assert_allclose(result.events["hook_load [N]"], reference.events["hook_load [N]"], rtol=1e-12)


def test_the_guide_names_every_rule() -> None:
    """Every threshold of RigStateRules is described in the guide, with its default."""
    from dataclasses import fields

    text = " ".join((Path(__file__).resolve().parents[1] / "docs" / "guide" / "rig-logs.md").read_text(
        encoding="utf-8").split())
    defaults = {"gap_factor": "5",
                "slips_margin": "5 klbf", "on_bottom": "0.3 m", "moving_speed": "0.03 m/s", "rotating_rpm": "5 rpm",
                "rest_rpm": "1 rpm", "flow_out_min": "5 %", "standpipe_min": "100 psi", "speed_window": "5 s",
                "rop_window": "60 s", "severity_window": "60 s", "event_min": "15 s", "settle": "5 s",
                "startup_rest": "10 s", "startup_length": "60 s"}
    rules = RigStateRules()
    for f in fields(RigStateRules):
        assert f"`{f.name}`" in text, f.name
        if f.name in defaults:
            assert RigStateRules.from_pairs({f.name: defaults[f.name]}) == rules, f.name
            number = defaults[f.name].split()[0]
            assert f"`{f.name}` ({number}" in text or f"`{f.name}`, {number}" in text, f.name


def test_a_time_column_of_dates_reads_as_seconds_from_the_first(tmp_path: Path) -> None:
    frame, _ = synthetic(drill_rows=300)
    reference = ds.rig_log(frame, start_depth=1000.0)
    dated = frame.copy()
    dated["t"] = (pd.Timestamp("2016-03-01 06:00:00") + pd.to_timedelta(frame["t"] - frame["t"][0], unit="s")
                  ).dt.strftime("%Y-%m-%d %H:%M:%S")
    path = tmp_path / "dated.csv"
    dated.to_csv(path, index=False)
    result = ds.rig_log(path, start_depth=1000.0)
    assert result.summary["t_origin"] == "2016-03-01T06:00:00+00:00"
    np.testing.assert_array_equal(result.states["t"], frame["t"] - frame["t"][0])
    assert (result.states["rig_state"] == reference.states["rig_state"]).all()
