"""Figures of runs and maps (labels, titles, panels, notes, the break-off line), ``DrillResult.plot``
and the three-way stick-slip verdict (core, ``metrics.json``, ``report.md``, the console, maps)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from _cli import run_cli

from drillstring import _core
from drillstring.drilling import DrillConfig, drill, drill_map, load_drill_config, map_labels
from drillstring.drilling.map_labels import axis_label
from drillstring.drilling.map_plots import boundary_note, controller_maps, map_figures, ssi_lines, ssi_map
from drillstring.errors import ValidationError

ROOT = Path(__file__).resolve().parents[1]
ON_BOTTOM = ROOT / "examples" / "on-bottom-3000m.toml"
WELL_B = ROOT / "examples" / "aarsnes-shor-well-b-corrected.toml"

def _key(unit: Any, label: str) -> dict[str, Any]:
    """An entry of ``_core.drill_config_schema()``."""
    return {"type": "number", "unit": unit, "label": label, "default": None, "description": label}


#: A schema in the format of ``_core.drill_config_schema()`` (dotted key -> its description).
FAKE_SCHEMA = {
    "bit.weight_on_bit": _key("N", "weight on bit"),
    "top_drive.rpm": _key("rpm", "top-drive speed"),
    "friction.static": _key("", "wall friction factor"),
    "sections[].length": _key("m", "section length"),
    "sections[].shear_modulus": _key("Pa", "shear modulus"),
    "top_drive.torque_limit": _key("N*m", "torque limit"),
    "top_drive.inertia": _key("kg*m^2", "top-drive inertia"),
    "numerics.cells": _key(None, "cells"),
}


@pytest.fixture
def schema(monkeypatch: pytest.MonkeyPatch) -> dict[str, Any]:
    monkeypatch.setattr(map_labels, "_schema", lambda: FAKE_SCHEMA)
    return FAKE_SCHEMA


def _texts(fig: Any) -> list[str]:
    out = [t.get_text() for t in fig.texts]
    for ax in fig.axes:
        out += [t.get_text() for t in ax.texts]
    return out


def _panels(fig: Any) -> list[Any]:
    """The visible axes with a colour mesh (not the colour bar)."""
    return [ax for ax in fig.axes if ax.get_visible() and ax.collections and ax.get_label() != "<colorbar>"]


# --------------------------------------------------------------------------- axis labels


def test_axis_labels_have_quantity_and_unit_in_readable_magnitudes(schema: dict[str, Any]) -> None:
    assert axis_label("bit.weight_on_bit", [0.0, 100e3, 200e3]) == ("weight on bit [kN]", 1e-3)
    assert axis_label("bit.weight_on_bit", [50.0, 500.0]) == ("weight on bit [N]", 1.0)
    assert axis_label("top_drive.rpm", [40.0, 400.0]) == ("top-drive speed [rpm]", 1.0)
    assert axis_label("friction.static", [0.1, 0.5]) == ("wall friction factor", 1.0)
    assert axis_label("sections[1].length", [100.0, 3000.0]) == ("section length, section 2 [m]", 1.0)
    assert axis_label("sections[0].shear_modulus", [79e9]) == ("shear modulus, section 1 [GPa]", 1e-9)
    # pint's products written with spaces and powers as superscripts; prefixes on newton metres
    assert axis_label("top_drive.torque_limit", [20e3, 60e3]) == ("torque limit [kN m]", 1e-3)
    assert axis_label("top_drive.inertia", [2900.0]) == ("top-drive inertia [kg m²]", 1.0)
    # no unit (None), and a key the schema does not know: its last name, no unit
    assert axis_label("numerics.cells", [10, 20]) == ("cells", 1.0)
    assert axis_label("numerics.duration", [10, 20]) == ("duration", 1.0)


@pytest.mark.skipif(not hasattr(_core, "drill_config_schema"), reason="a core without the configuration schema")
def test_axis_labels_from_the_cores_schema() -> None:
    label, factor = axis_label("bit.weight_on_bit", [0.0, 200e3])
    assert label.endswith("[kN]") and factor == 1e-3 and "weight" in label
    assert axis_label("top_drive.rpm", [40.0, 120.0])[0].endswith("[rpm]")


# --------------------------------------------------------------------------- map figures


def _synthetic(ssi: list[float], controllers: tuple[str, ...] = ("pi",), name: str = "Well X") -> pd.DataFrame:
    """A map table of 2 x 3 runs per controller with the given SSI values (runs in order)."""
    rows = []
    k = 0
    axes: dict[str, list[Any]] = {"top_drive.rpm": [40.0, 80.0, 120.0], "bit.weight_on_bit": [50e3, 200e3]}
    if len(controllers) > 1:
        axes["top_drive.controller.type"] = list(controllers)
    for kind in controllers:
        for wob in axes["bit.weight_on_bit"]:
            for rpm in axes["top_drive.rpm"]:
                row = {"top_drive.rpm": rpm, "bit.weight_on_bit": wob, "ssi": ssi[k], "stuck_fraction": 0.0,
                       "status": "success"}
                if len(controllers) > 1:
                    row["top_drive.controller.type"] = kind
                rows.append(row)
                k += 1
    frame = pd.DataFrame(rows)
    frame.attrs.update(axes=axes, name=name, config={"top_drive": {"controller": {"type": "soft_torque"}},
                                                      "sections": [{"length": 3000.0}]})
    return frame


def test_map_axes_title_and_boundary(schema: dict[str, Any]) -> None:
    frame = _synthetic([0.2, 0.5, 0.8, 1.2, 1.6, 2.0])
    fig = ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit")
    (ax,) = _panels(fig)
    assert ax.get_xlabel() == "top-drive speed [rpm]" and ax.get_ylabel() == "weight on bit [kN]"
    assert fig._suptitle is not None
    assert fig._suptitle.get_text() == "Well X: stick-slip severity SSI, soft_torque controller"
    # the weights are drawn in kN: the cell centres are 50 and 200
    mesh = ax.collections[0]
    assert np.allclose(np.unique(mesh.get_coordinates()[..., 1]).min(), 50.0 - 75.0)
    assert len(ax.collections) == 2  # the mesh and the SSI = 1 contour
    assert not [t for t in _texts(fig) if "everywhere" in t]


@pytest.mark.parametrize(("ssi", "note"), [
    ([1.2, 1.5, 2.0, 3.0, 1.1, 4.0], "SSI > 1 everywhere in this range"),
    ([0.2, 0.5, 0.1, 0.3, 0.9, 0.0], "SSI < 1 everywhere in this range"),
    ([float("nan")] * 6, "no successful run"),
])
def test_a_map_without_a_boundary_says_so(schema: dict[str, Any], ssi: list[float], note: str) -> None:
    frame = _synthetic(ssi)
    assert boundary_note(frame["ssi"]) == note
    fig = ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit")
    (ax,) = _panels(fig)
    assert note in [t.get_text() for t in ax.texts]
    assert len(ax.collections) == 1  # no contour
    assert note in _texts(ssi_lines(frame, "top_drive.rpm"))


def test_one_panel_per_controller_never_an_average(schema: dict[str, Any]) -> None:
    pi = [0.2, 0.5, 0.8, 1.2, 1.6, 2.0]
    soft = [1.1, 1.2, 1.3, 1.4, 1.5, 1.6]
    frame = _synthetic(pi + soft, controllers=("pi", "soft_torque"))
    for fig in (ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit"),
                controller_maps(frame, "top_drive.rpm", "bit.weight_on_bit")):
        panels = _panels(fig)
        assert [ax.get_title() for ax in panels] == ["pi controller", "soft_torque controller"]
        for ax, values in zip(panels, (pi, soft)):
            cells = np.ma.filled(ax.collections[0].get_array(), np.nan).ravel()
            np.testing.assert_array_equal(cells, values)  # the panel's own runs, not a mean over controllers
        assert "SSI > 1 everywhere in this range" in [t.get_text() for t in panels[1].texts]
        assert not panels[0].texts
    assert set(map_figures(frame)) == {"ssi_map.png", "controllers.png"}
    # lines: one per controller and per weight, each the runs' own values
    lines = ssi_lines(frame, "top_drive.rpm").axes[0].get_lines()
    labelled = [line for line in lines if not line.get_label().startswith("_")]
    assert len(labelled) == 4
    assert labelled[0].get_label() == "pi controller, weight on bit = 50 kN"
    np.testing.assert_array_equal(labelled[0].get_ydata(), pi[:3])
    np.testing.assert_array_equal(labelled[3].get_ydata(), soft[3:])


def test_too_many_panels_are_refused(schema: dict[str, Any]) -> None:
    frame = _synthetic([1.0] * 6)
    big = pd.concat([frame.assign(**{"friction.static": float(k)}) for k in range(50)], ignore_index=True)
    big.attrs.update(frame.attrs)
    big.attrs["axes"] = {**frame.attrs["axes"], "friction.static": [float(k) for k in range(50)]}
    with pytest.raises(ValidationError, match="at most 48 panels"):
        ssi_map(big, "top_drive.rpm", "bit.weight_on_bit")
    with pytest.warns(UserWarning, match="no map figure"):
        assert map_figures(big) == {}


def _small_on_bottom() -> DrillConfig:
    return DrillConfig.from_dict({
        "sections": [{"length": 1000.0, "outer_diameter": 0.127, "inner_diameter": 0.108}],
        "well": {"inclination_deg": 30.0},
        "bit": {"on_bottom": True, "weight_on_bit": 40e3},
        "numerics": {"cells": 40, "duration": 4.0, "field_interval": 0.5},
    })


def test_solved_map_has_the_verdict_column_and_the_name(tmp_path: Path) -> None:
    path = tmp_path / "small-well.toml"
    _small_on_bottom().save(path)
    frame = drill_map(path, {"top_drive.rpm": [10.0, 120.0], "bit.weight_on_bit": [20e3, 60e3]}, threads=2)
    assert frame.attrs["name"] == "small-well"
    assert set(frame["stick_slip_verdict"]) <= {"yes", "no", "undetermined"}
    assert ((frame["stick_slip_verdict"] == "yes") == (frame["stick_slip"] == 1)).all()
    fig = ssi_map(frame, "top_drive.rpm", "bit.weight_on_bit")
    assert fig._suptitle is not None and fig._suptitle.get_text().startswith("small-well: ")
    assert _panels(fig)[0].get_ylabel().endswith("[kN]") or not hasattr(_core, "drill_config_schema")
    # an invalid run has no metrics: undetermined
    bad = drill_map(_small_on_bottom(), {"top_drive.inertia": [2900.0, -1.0]}, threads=1, name="W")
    assert list(bad["stick_slip_verdict"]) == [bad["stick_slip_verdict"][0], "undetermined"]
    assert bad.attrs["name"] == "W"


# --------------------------------------------------------------------------- single runs


def test_on_bottom_breakoff_line_includes_the_bits_static_torque() -> None:
    cfg = _small_on_bottom()
    result = drill(cfg)
    bit = cfg.bit
    bit_static = bit.weight_on_bit * bit.radius * bit.mu_static  # W r mu_s, from the configuration
    p = result.profile
    assert p.bit_static_torque == pytest.approx(bit_static, rel=1e-15)
    assert p.static_torque == pytest.approx(p.breakoff_torque + bit_static, rel=1e-15)
    np.testing.assert_allclose(p.holding, p.cumulative + bit_static, rtol=1e-15)
    fig = result.plot("time")
    torque_ax = fig.axes[1]
    (line,) = [ln for ln in torque_ax.get_lines() if ln.get_label().startswith("break-off torque")]
    assert line.get_label() == "break-off torque (wall friction + bit static torque)"
    assert line.get_ydata()[0] == pytest.approx((p.breakoff_torque + bit_static) / 1e3, rel=1e-12)
    # the envelope of the torque-depth figure at the top is the same static torque
    fig = result.plot("torque_depth")
    envelope = [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() == ":"][0]
    assert envelope.get_xdata()[0] == pytest.approx((p.cumulative[0] + bit_static) / 1e3, rel=1e-12)
    # off bottom: the wall's alone
    off = drill(cfg.with_overrides(["bit.on_bottom=false"]))
    assert off.profile.bit_static_torque == 0.0 and off.profile.static_torque == off.profile.breakoff_torque
    (line,) = [ln for ln in off.plot().axes[1].get_lines() if ln.get_label().startswith("break-off torque")]
    assert line.get_label() == "break-off torque (wall friction)"


def test_result_plot(tmp_path: Path) -> None:
    from matplotlib.figure import Figure

    result = drill(_small_on_bottom())
    for kind, count in (("time", 2), ("space_time", 4), ("torque_depth", 2)):
        fig = result.plot(kind)
        assert isinstance(fig, Figure) and len(fig.axes) == count, kind
    fig = result.plot("time", title="my title")
    assert fig._suptitle is not None and fig._suptitle.get_text() == "my title"
    with pytest.raises(ValidationError, match="one of time, space_time, torque_depth"):
        result.plot("nope")
    with pytest.raises(ValidationError, match="path"):
        result.plot("time", path=tmp_path / "x.nope")
    written = tmp_path / "t.png"
    result.plot("time", path=written)
    assert written.read_bytes()[:4] == b"\x89PNG"
    # into a subfigure of a larger figure
    outer = Figure(figsize=(12, 10))
    left, right = outer.subfigures(1, 2)
    assert result.plot("time", fig=left) is outer
    assert result.plot("torque_depth", fig=right) is outer
    assert len(outer.axes) == 4


# --------------------------------------------------------------------------- the verdict


@pytest.mark.skipif(not WELL_B.exists(), reason="examples/aarsnes-shor-well-b-corrected.toml")
def test_corrected_well_b_sticks() -> None:
    result = drill(WELL_B)
    m = result.metrics
    assert m.stick_slip_verdict == "yes" and m.stick_slip
    assert 0.0 < m.stuck_fraction < 1.0
    summary = result.summary()
    assert summary["stick_slip_verdict"] == "yes" and summary["stick_slip"] is True
    assert summary["stick_slip_reason"] == "the bit stops during part of the window"
    assert summary["stick_slip_criterion"] == _core.STICK_SLIP_CRITERION
    assert result.name == "aarsnes-shor-well-b-corrected"
    assert "aarsnes-shor-well-b-corrected" in result.plot()._suptitle.get_text()  # type: ignore[union-attr]
    assert "stick-slip: yes" in result.plot()._suptitle.get_text()  # type: ignore[union-attr]


@pytest.mark.skipif(not ON_BOTTOM.exists(), reason="examples/on-bottom-3000m.toml")
def test_a_soft_case_does_not_stick() -> None:
    cfg = load_drill_config(ON_BOTTOM)
    soft = drill(cfg.with_overrides(["top_drive.rpm=120", "numerics.duration=120"])).metrics
    assert soft.stuck_fraction == 0.0 and soft.ssi < 0.1 and soft.settled
    assert soft.stick_slip_verdict == "no" and not soft.stick_slip
    low = drill(cfg.with_overrides(["top_drive.rpm=40", "numerics.duration=30"])).metrics
    assert low.stick_slip_verdict == "yes"


def test_the_verdict_of_series() -> None:
    from drillstring.drilling.metrics import stick_slip_metrics

    t = np.linspace(0.0, 10.0, 20001)
    clipped = np.maximum(0.0, 10.0 * (1.0 + 2.0 * np.sin(2 * np.pi * t)))
    assert stick_slip_metrics(t, clipped, clipped).stick_slip_verdict == "yes"
    soft = 10.0 * (1.0 + 0.5 * np.sin(2 * np.pi * t))
    m = stick_slip_metrics(t, soft, soft)
    assert (m.stick_slip_verdict, m.ssi < 1, m.stuck_fraction) == ("no", True, 0.0)
    growing = 10.0 * (1.0 + 0.06 * t * np.sin(2 * np.pi * t))
    m = stick_slip_metrics(t, growing, growing)
    assert m.stick_slip_verdict == "undetermined" and "grows" in m.stick_slip_reason
    m = stick_slip_metrics(t, np.zeros_like(t))
    assert m.stick_slip_verdict == "undetermined" and "stuck throughout" in m.stick_slip_reason


@pytest.mark.skipif(not ON_BOTTOM.exists(), reason="examples/on-bottom-3000m.toml")
def test_console_metrics_json_and_report_state_the_verdict(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    code, stdout, err = run_cli(capsys, "drill", str(ON_BOTTOM), "--out", str(out), "--set", "numerics.duration=20",
                                "--set", "top_drive.rpm=40", "--no-progress")
    assert code == 0, err
    assert "stick-slip: yes (the bit stops during part of the window)" in stdout
    assert "static torque to break free" in stdout
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["stick_slip_verdict"] == "yes" and metrics["stick_slip"] is True
    assert metrics["stick_slip_criterion"].startswith("yes: the bit stops")
    assert "stick_slip_verdict" in metrics["definitions"]
    report = (out / "report.md").read_text()
    assert "**Stick-slip: yes**" in report and "Criterion: yes: the bit stops" in report
