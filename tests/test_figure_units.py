"""Figures and console lines in the user's unit system (``units="field"``, ``--units field``):
the single-run figures, the map figures and the torque-and-drag figures label their axes in the
field unit and draw the SI data times the exact factor of the unit's definition (1 ft = 0.3048 m,
1 in = 0.0254 m, 1 lbf = 4.4482216152605 N; deg/100 ft = deg/30 m * 30 / (100 * 0.3048)), while
every data file stays SI, byte for byte."""

from __future__ import annotations

import json
from decimal import Decimal
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from _cli import run_cli

import drillstring as ds
from drillstring.drilling import DrillConfig, DrillResult, drill
from drillstring.drilling.map_labels import axis_label
from drillstring.drilling.map_plots import map_figures, ssi_lines, ssi_map
from drillstring.drilling.plots import space_time_maps, time_histories, torque_depth
from drillstring.drilling.torque_drag import broomstick_figure, profiles_figure, well_path_figure
from drillstring.drilling.units import axis_unit
from drillstring.errors import ValidationError

pytest.importorskip("pint")

ROOT = Path(__file__).resolve().parents[1]
ON_BOTTOM = ROOT / "examples" / "on-bottom-3000m.toml"
S_WELL = ROOT / "examples" / "s-well-3d.toml"
FT, INCH, LBF = 0.3048, 0.0254, 4.4482216152605
FT_LBF = FT * LBF
#: Within a few roundings of the exact product (the factor is the correctly rounded float of the
#: exact one, and kilo a second factor).
RTOL = 1e-15


def _close(actual: Any, expected: Any) -> None:
    np.testing.assert_allclose(np.asarray(actual, dtype=float), np.asarray(expected, dtype=float), rtol=RTOL,
                               atol=0.0)


@pytest.fixture(scope="module")
def run() -> DrillResult:
    cfg = DrillConfig.from_dict({
        "sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "well": {"inclination_deg": 30.0},
        "bit": {"on_bottom": True},
        "numerics": {"cells": 40, "duration": 4.0, "field_interval": 0.5},
    })
    return drill(cfg)


@pytest.fixture(scope="module")
def td() -> ds.TorqueDragResult:
    return ds.torque_drag(S_WELL)


# --------------------------------------------------------------------------- the factors


def test_axis_unit_gives_the_exact_factor_and_the_unit_text() -> None:
    assert axis_unit("N*m", "si", kilo=True) == (1e-3, "kN m")
    assert axis_unit("m", "si") == (1.0, "m")
    assert axis_unit("rpm", "field") == (1.0, "rpm")
    factor, unit = axis_unit("m", "field")
    assert unit == "ft" and factor == float(Decimal(1) / Decimal("0.3048"))  # the exact factor, rounded once
    factor, unit = axis_unit("N*m", "field", kilo=True)
    assert unit == "kft-lbf"
    _close(factor, 1e-3 / FT_LBF)
    factor, unit = axis_unit("N", "field", kilo=True)  # klbf is a thousand already
    assert unit == "klbf"
    _close(factor, 1e-3 / LBF)
    assert axis_unit("N", "si", kilo=True) == (1e-3, "kN")
    factor, unit = axis_unit("N/m", "field")
    assert unit == "lbf/ft"
    _close(factor, FT / LBF)
    factor, unit = axis_unit("N*m/m", "field")
    assert unit == "ft-lbf/ft"
    _close(factor, 1 / LBF)
    factor, unit = axis_unit("deg/(30 m)", "field")
    assert unit == "deg/100 ft"
    _close(factor, 100 * FT / 30)


@pytest.mark.parametrize("call", [
    lambda: axis_unit("m", "imperial"),
    lambda: axis_label("bit.weight_on_bit", [1.0], "imperial"),
])
def test_an_unknown_system_is_refused_naming_units(call: Any) -> None:
    with pytest.raises(ValidationError, match="one of si .* field") as info:
        call()
    assert info.value.field == "units"


# --------------------------------------------------------------------------- a run's figures


def test_time_histories_in_field_units(run: DrillResult) -> None:
    si = time_histories(run)
    field = time_histories(run, units="field")
    assert si.axes[1].get_ylabel() == "torque, kN m"
    assert field.axes[1].get_ylabel() == "torque, kft-lbf"
    assert field.axes[0].get_ylabel() == si.axes[0].get_ylabel() == "speed, rpm"  # rpm in both systems
    motor, bit = field.axes[1].get_lines()[:2]
    _close(motor.get_ydata(), run.motor_torque / FT_LBF / 1e3)
    _close(bit.get_ydata(), run.bit_torque / FT_LBF / 1e3)
    np.testing.assert_array_equal(field.axes[0].get_lines()[0].get_ydata(), run.surface_rpm)
    np.testing.assert_array_equal(motor.get_xdata(), run.t)
    title = field._suptitle.get_text()  # type: ignore[attr-defined]
    assert f"{run.config.length / FT:.0f} ft string" in title and " m string" not in title


def test_torque_depth_in_field_units(run: DrillResult) -> None:
    fig = torque_depth(run, units="field")
    ax, ax_limit = fig.axes[:2]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("torque, kft-lbf", "measured depth, ft")
    assert ax_limit.get_xlabel() == "static friction limit, ft-lbf/ft"
    envelope = run.profile.holding if run.profile.holding.size == run.profile.z.size else run.profile.cumulative
    line = ax.get_lines()[0]  # the envelope's right edge
    _close(line.get_xdata(), envelope / FT_LBF / 1e3)
    _close(line.get_ydata(), run.profile.z / FT)
    last = ax.get_lines()[2]  # the last snapshot
    _close(last.get_xdata(), run.torque_field[-1] / FT_LBF / 1e3)
    _close(last.get_ydata(), run.z / FT)
    (limit,) = ax_limit.get_lines()
    _close(limit.get_xdata(), run.profile.limit_per_m / LBF)  # N m/m = N: ft-lbf/ft = lbf
    title = fig._suptitle.get_text()  # type: ignore[attr-defined]
    assert f"break-off torque {run.profile.static_torque / FT_LBF / 1e3:.4g} kft-lbf" in title


def test_space_time_maps_in_field_units(run: DrillResult) -> None:
    si = space_time_maps(run)
    field = space_time_maps(run, units="field")
    panels = [ax for ax in field.axes if ax.get_label() != "<colorbar>"]
    assert [ax.get_ylabel() for ax in panels] == ["measured depth, ft"] * 2
    bars = [ax for ax in field.axes if ax.get_label() == "<colorbar>"]
    assert [ax.get_ylabel() for ax in bars] == ["speed, rpm", "torque, kft-lbf"]
    si_panels = [ax for ax in si.axes if ax.get_label() != "<colorbar>"]
    speed_si, torque_si = (ax.collections[0] for ax in si_panels)
    speed, torque = (ax.collections[0] for ax in panels)
    np.testing.assert_array_equal(speed.get_array(), speed_si.get_array())
    # the SI panel holds kN m: the field one the same torques in kft-lbf
    _close(torque.get_array(), np.asarray(torque_si.get_array()) * 1e3 / FT_LBF / 1e3)
    depth_si, depth = speed_si.get_coordinates()[..., 1], speed.get_coordinates()[..., 1]
    # the cell edges matplotlib puts half-way between the depths (the top one 0 to rounding)
    np.testing.assert_allclose(depth, depth_si / FT, rtol=RTOL, atol=1e-12)
    _close(np.unique(depth)[1:3], np.unique(depth_si)[1:3] / FT)


def test_drill_result_plot_takes_units(run: DrillResult, tmp_path: Path) -> None:
    fig = run.plot("torque_depth", units="field", path=tmp_path / "td.png")
    assert fig.axes[0].get_ylabel() == "measured depth, ft" and (tmp_path / "td.png").stat().st_size > 0
    assert run.plot("time").axes[1].get_ylabel() == "torque, kN m"
    with pytest.raises(ValidationError) as info:
        run.plot("time", units="imperial")
    assert info.value.field == "units"


# --------------------------------------------------------------------------- map figures


def _map_frame(axes: dict[str, list[float]]) -> pd.DataFrame:
    keys = list(axes)
    rows = []
    ssi = iter(np.linspace(0.2, 2.0, int(np.prod([len(v) for v in axes.values()]))))
    for a in axes[keys[0]]:
        for b in axes[keys[1]] if len(keys) > 1 else [None]:
            row = {keys[0]: a, "ssi": next(ssi), "stuck_fraction": 0.0, "status": "success"}
            if b is not None:
                row[keys[1]] = b
            rows.append(row)
    frame = pd.DataFrame(rows)
    frame.attrs.update(axes=axes, name=None, config={"sections": [{"length": 3048.0}]})
    return frame


def test_map_axis_labels_in_field_units() -> None:
    label, factor = axis_label("bit.weight_on_bit", [40e3, 80e3], "field")
    assert label == "weight on bit [klbf]"
    _close(factor, 1e-3 / LBF)
    label, factor = axis_label("sections[0].outer_diameter", [0.127, 0.1397], "field")
    assert label.endswith("section 1 [in]")  # a diameter in inches, not ft
    _close(factor, 1 / INCH)
    label, factor = axis_label("top_drive.torque_limit", [20e3, 60e3], "field")
    assert label.endswith("[kft-lbf]")
    _close(factor, 1e-3 / FT_LBF)
    label, factor = axis_label("sections[1].length", [1000.0, 3000.0], "field")
    assert label.endswith("section 2 [ft]")
    _close(factor, 1 / FT)
    assert axis_label("top_drive.rpm", [40.0, 120.0], "field") == axis_label("top_drive.rpm", [40.0, 120.0])
    assert axis_label("bit.weight_on_bit", [40e3, 80e3]) == ("weight on bit [kN]", 1e-3)  # SI as before


def test_ssi_map_in_field_units() -> None:
    wob = [40e3, 80e3, 120e3]
    frame = _map_frame({"top_drive.rpm": [60.0, 120.0], "bit.weight_on_bit": wob})
    fig = ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit", units="field")
    ax = fig.axes[0]
    assert ax.get_ylabel() == "weight on bit [klbf]" and ax.get_xlabel().endswith("[rpm]")
    centres = np.unique(ax.collections[0].get_coordinates()[..., 1])
    # "nearest" shading: the edges lie half-way between the cell centres, the weights in klbf
    klbf = np.asarray(wob) / LBF / 1e3
    _close(centres[1:-1], (klbf[1:] + klbf[:-1]) / 2)
    assert fig._suptitle.get_text().startswith("10000 ft string")  # type: ignore[attr-defined]


def test_ssi_lines_and_panel_titles_in_field_units() -> None:
    frame = _map_frame({"sections[0].length": [1524.0, 3048.0], "bit.weight_on_bit": [44482.216152605]})
    fig = ssi_lines(frame, "sections[0].length", units="field")
    ax = fig.axes[1]
    assert ax.get_xlabel().endswith("[ft]")
    _close(fig.axes[0].get_lines()[0].get_xdata(), [5000.0, 10000.0])
    frame = _map_frame({"sections[0].length": [1524.0, 3048.0], "bit.weight_on_bit": [44482.216152605, 88964.43230521]})
    frame.attrs["axes"]["top_drive.rpm"] = [60.0]
    lines = ssi_lines(frame, "sections[0].length", "bit.weight_on_bit", units="field").axes[0].get_lines()
    assert [line.get_label() for line in lines[:2]] == ["weight on bit = 10 klbf", "weight on bit = 20 klbf"]
    assert set(map_figures(frame, "field")) == {"ssi_map.png"}


# --------------------------------------------------------------------------- torque and drag figures


def test_torque_drag_figures_in_field_units(td: ds.TorqueDragResult) -> None:
    fig = profiles_figure(td, units="field")
    tension, torque, normal, side = fig.axes
    assert [ax.get_xlabel() for ax in fig.axes] == ["effective tension, klbf", "torque, kft-lbf",
                                                    "normal force, lbf/ft", "side force per joint, klbf"]
    assert tension.get_ylabel() == "measured depth, ft"
    p = td.profiles["pickup"]
    line = tension.get_lines()[0]
    _close(line.get_xdata(), np.asarray(p["tension_N"]) / LBF / 1e3)
    _close(line.get_ydata(), np.asarray(p["md"]) / FT)
    _close(torque.get_lines()[0].get_xdata(), np.asarray(td.profiles["rotating"]["torque_Nm"]) / FT_LBF / 1e3)
    _close(normal.get_lines()[0].get_xdata(), np.asarray(p["normal_force_N_per_m"]) * FT / LBF)
    _close(side.get_lines()[0].get_xdata(), np.asarray(p["side_force_per_joint_N"]) / LBF / 1e3)
    assert f"pick-up {td.hook_load_pickup_N / LBF / 1e3:.0f} klbf" in fig._suptitle.get_text()  # type: ignore

    fig = broomstick_figure(td, units="field")
    ax, ax_torque = fig.axes
    assert ax.get_xlabel() == "hook load, klbf (with the block weight)"
    assert ax_torque.get_xlabel() == "surface torque, kft-lbf"
    _close(ax_torque.get_lines()[0].get_xdata(), np.asarray(td.broomstick["torque_rotating"][0]) / FT_LBF / 1e3)
    assert ax.get_ylabel() == "bit depth, ft (measured)"
    rotating = ax.get_lines()[0]
    _close(rotating.get_xdata(), np.asarray(td.broomstick["rotating"][0]) / LBF / 1e3)
    _close(rotating.get_ydata(), np.asarray(td.broomstick["depth_m"]) / FT)

    fig = well_path_figure(td, units="field")
    plan, section, dls = fig.axes
    assert (plan.get_xlabel(), plan.get_ylabel(), section.get_ylabel()) == ("east, ft", "north, ft", "TVD, ft")
    assert (dls.get_xlabel(), dls.get_ylabel()) == ("measured depth, ft", "dogleg severity, deg/100 ft")
    _close(plan.get_lines()[0].get_xdata(), np.asarray(td.trajectory["east"]) / FT)
    _close(dls.get_lines()[0].get_ydata(), np.asarray(td.trajectory["dls_deg_per_30m"]) * 100 * FT / 30)

    si = profiles_figure(td)
    assert [ax.get_xlabel() for ax in si.axes] == ["effective tension, kN", "torque, kN m", "normal force, N/m",
                                                   "side force per joint, kN"]


# --------------------------------------------------------------------------- the command line


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.is_file() and p.name != ".lock"}


def test_drill_units_field_writes_field_figures_and_si_data(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    short = ["--set", "numerics.duration=6", "--set", "numerics.cells=60"]
    runs = {}
    for name, extra in (("default", []), ("si", ["--units", "si"]), ("field", ["--units", "field"])):
        code, out, _ = run_cli(capsys, "drill", str(ON_BOTTOM), "--out", str(tmp_path / name), *short, *extra)
        assert code == 0
        runs[name] = _files(tmp_path / name)
    assert "kft-lbf" in out and "kN m" not in out
    assert runs["default"] == runs["si"]  # --units si is the default, byte for byte
    field, default = runs["field"], runs["default"]
    assert set(field) == set(default)
    for name in ("series.csv", "series.parquet", "fields.npz", "config.toml"):
        assert field[name] == default[name], name  # the data files stay SI
    assert b"| section | length, ft | OD, in |" in field["report.md"]  # the report follows --units
    assert b"| section | length, m | OD, m |" in default["report.md"]
    metrics = json.loads(field["metrics.json"])
    metrics.pop("output_units")
    assert metrics == json.loads(default["metrics.json"])
    for name in ("time_histories.png", "space_time.png", "torque_depth.png"):
        assert field[name] != default[name] and field[name].startswith(b"\x89PNG"), name


def test_torque_drag_units_field(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out_si, _ = run_cli(capsys, "torque-drag", str(S_WELL), "--out", str(tmp_path / "si"))
    assert code == 0 and "kN" in out_si and "klbf" not in out_si
    code, out, _ = run_cli(capsys, "torque-drag", str(S_WELL), "--out", str(tmp_path / "field"), "--units", "field")
    assert code == 0
    td = json.loads((tmp_path / "si" / "torque_drag.json").read_text())
    assert f"pick-up {td['hook_load_pickup_N'] / LBF / 1e3:.1f} klbf" in out
    assert f"off bottom {td['surface_torque_off_bottom_Nm'] / FT_LBF / 1e3:.2f} kft-lbf" in out
    assert " ft string" in out and "kN" not in out and " m " not in out
    si, field = _files(tmp_path / "si"), _files(tmp_path / "field")
    assert set(si) == set(field)
    for name in ("torque_drag.json", "profiles.csv", "broomstick.csv", "survey.csv", "config.toml"):
        assert si[name] == field[name], name
    for name in ("torque_drag.png", "broomstick.png", "well_path.png"):
        assert si[name] != field[name], name


def test_drill_map_units_field(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = ["drill-map", str(ON_BOTTOM), "--axis", "top_drive.rpm=60,120", "--axis", "bit.weight_on_bit=40e3,80e3",
            "--set", "numerics.duration=3", "--set", "numerics.cells=40", "--threads", "1"]
    assert run_cli(capsys, *args, "--out", str(tmp_path / "si"))[0] == 0
    assert run_cli(capsys, *args, "--out", str(tmp_path / "field"), "--units", "field")[0] == 0
    si, field = _files(tmp_path / "si"), _files(tmp_path / "field")
    for name in ("map.csv", "config.toml"):
        assert si[name] == field[name], name  # the table stays SI
    assert si["ssi_map.png"] != field["ssi_map.png"]


@pytest.mark.parametrize("command", [
    ["drill", str(ON_BOTTOM)],
    ["torque-drag", str(S_WELL)],
    ["drill-map", str(ON_BOTTOM), "--axis", "top_drive.rpm=60,120"],
])
def test_a_bad_unit_system_is_one_line_exit_2(command: list[str], tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        run_cli(capsys, *command, "--out", str(tmp_path / "out"), "--units", "imperial")
    assert info.value.code == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "--units" in lines[0] and "'imperial'" in lines[0] and "field" in lines[0], err
    assert lines[0].startswith(f"drillstring {command[0]}: error:")  # argparse's usage line, before any work
    assert not (tmp_path / "out").exists()
