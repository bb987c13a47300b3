"""A drilling session (``ds.DrillSession``) against the batch run ``ds.drill``: the same series bit
for bit whatever the chunks, a change by ``set`` equal to a ``top_drive.steps`` entry and to a
``[[changes]]`` entry at the same time, a snapshot that continues bit for bit, refusals naming the
key, a diverging session's status, Ctrl-C during a long step."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _children import python_child
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import drillstring as ds
from drillstring.drilling.result import SERIES

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _torsional(duration: float = 12.0) -> ds.DrillConfig:
    """The torsion-only example on bottom, shortened."""
    return ds.load_drill_config(EXAMPLES / "on-bottom-3000m.toml").with_overrides(
        {"numerics.duration": duration, "numerics.cells": 100, "numerics.field_interval": 0.5})


def _coupled(duration: float = 12.0) -> ds.DrillConfig:
    """The coupled example (a [hoist] holding the weight on bit), shortened."""
    return ds.load_drill_config(EXAMPLES / "coupled-deviated-3200m.toml").with_overrides(
        {"numerics.duration": duration, "numerics.cells": 100, "numerics.field_interval": 0.5,
         "metrics.window": None})


CONFIGS = {"torsional": _torsional, "coupled": _coupled}


def _columns(result: ds.DrillResult) -> dict[str, np.ndarray]:
    return {"t": result.t, **result.series_columns()}


def _same_bits(a: ds.DrillResult, b: ds.DrillResult) -> None:
    ca, cb = _columns(a), _columns(b)
    assert ca.keys() == cb.keys()
    for name in ca:
        assert ca[name].tobytes() == cb[name].tobytes(), name


def _through(session: ds.DrillSession, chunks: list[float]) -> None:
    """Steps ``session`` by each chunk, then to its configuration's duration."""
    for c in chunks:
        session.step(c)
    session.step(max(session.config.numerics.duration - session.t, 0.0))


@pytest.mark.parametrize("kind", list(CONFIGS))
def test_a_session_stepped_through_the_duration_is_drill_bit_for_bit(kind: str) -> None:
    cfg = CONFIGS[kind]()
    batch = ds.drill(cfg)
    session = ds.DrillSession(cfg, keep_fields=True)
    _through(session, [0.011, 3.2, 0.0, 2.49])
    result = session.result()
    _same_bits(result, batch)
    assert result.omega_field.tobytes() == batch.omega_field.tobytes()
    assert result.metrics.to_dict() == batch.metrics.to_dict()
    assert result.energy == batch.energy
    assert result.warnings == batch.warnings
    if kind == "coupled":
        assert result.coupled_metrics == batch.coupled_metrics and result.coupled_regime == batch.coupled_regime
    # the cheap reads agree with the result
    rows = session.rows(len(session) - 5)
    assert rows["bit_rpm"].tobytes() == batch.bit_rpm[-5:].tobytes()
    assert list(session.series().columns) == list(batch.to_pandas().columns)
    assert result.config == cfg  # stepped to the duration: the configuration that repeats it is the one given


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.floats(min_value=0.0, max_value=4.0, allow_nan=False), max_size=4))
def test_the_chunks_do_not_change_the_series(chunks: list[float]) -> None:
    cfg = _torsional(6.0)
    batch = _BATCH.setdefault("t6", ds.drill(cfg))
    session = ds.DrillSession(cfg)
    for c in chunks:
        if session.t + c < cfg.numerics.duration:
            session.step(c)
    _through(session, [])
    _same_bits(session.result(), batch)


_BATCH: dict[str, ds.DrillResult] = {}


@pytest.mark.parametrize("kind", list(CONFIGS))
def test_set_at_20_s_is_a_steps_entry_and_a_changes_entry_at_20_s(kind: str) -> None:
    cfg = CONFIGS[kind](26.0)
    by_steps = ds.drill(cfg.with_overrides({"top_drive.steps": [[20.0, 80.0]]}))
    by_changes = ds.drill(cfg.with_overrides({"changes": [{"time": 20.0, "key": "top_drive.rpm", "value": 80.0}]}))
    session = ds.DrillSession(cfg)
    session.step(20.0)
    session.set("top_drive.rpm", 80.0)
    _through(session, [])
    by_set = session.result()
    _same_bits(by_steps, by_set)
    _same_bits(by_steps, by_changes)
    assert session.changes == [(pytest.approx(20.0, abs=session.dt), "top_drive.rpm", 80.0)]
    # the change did something: the top drive ends near 80 rpm
    assert by_set.surface_rpm[-1] > 60.0


def test_a_hoist_set_is_a_hoist_steps_entry() -> None:
    cfg = _coupled(12.0)
    by_steps = ds.drill(cfg.with_overrides({"hoist.steps": [[8.0, 100e3]]}))
    session = ds.DrillSession(cfg)
    session.step(8.0)
    session.set("hoist.weight_on_bit", 100e3)
    _through(session, [])
    _same_bits(by_steps, session.result())
    # the driller's lower weight reaches the bit: less weight on bit than without the change
    held = ds.drill(cfg)
    assert by_steps.axial["weight_on_bit"][-200:].mean() < held.axial["weight_on_bit"][-200:].mean()


def test_a_snapshot_continues_bit_for_bit() -> None:
    session = ds.DrillSession(_coupled())
    session.step(3.0)
    snap = session.snapshot()
    session.set("hoist.weight_on_bit", 100e3)
    session.step(2.0)
    for _ in range(2):  # restored twice from the same snapshot: the same run
        again = ds.DrillSession.restore(snap)
        assert again.t == snap.t
        again.set("hoist.weight_on_bit", 100e3)
        again.step(2.0)
        _same_bits(again.result(), session.result())
        assert again.state()["axial_force_N"].tobytes() == session.state()["axial_force_N"].tobytes()


def test_a_pickled_snapshot_continues_bit_for_bit() -> None:
    import pickle

    session = ds.DrillSession(_torsional(), keep_fields=True)
    session.step(2.0)
    session.set("top_drive.rpm", 70.0)
    session.step(1.3)
    session.set("friction.kinetic_ratio", 0.7)
    session.step(0.4)
    restored = ds.DrillSession.restore(pickle.loads(pickle.dumps(session.snapshot())))
    assert restored.t == session.t and restored.changes == session.changes
    for s in (session, restored):
        s.set("top_drive.rpm", 90.0)
        s.step(2.0)
    _same_bits(restored.result(), session.result())
    assert restored.result().omega_field.tobytes() == session.result().omega_field.tobytes()


def test_a_key_that_cannot_change_is_refused_naming_the_key() -> None:
    session = ds.DrillSession(_torsional())
    with pytest.raises(ds.ValidationError, match="cannot change during a run") as err:
        session.set("numerics.cells", 300)
    assert err.value.field == "numerics.cells"
    with pytest.raises(ds.ValidationError) as err:
        session.set("hoist.speed", 0.01)
    assert err.value.field == "hoist.speed"
    assert session.changes == []


def test_an_invalid_value_names_the_allowed_range() -> None:
    session = ds.DrillSession(_torsional())
    with pytest.raises(ds.ValidationError, match=">= 0") as err:
        session.set("friction.static", -0.2)
    assert err.value.field == "friction.static"
    with pytest.raises(ds.ValidationError) as err:
        session.set("top_drive.controller.type", "fuzzy")
    assert err.value.field.startswith("top_drive.controller")


def test_the_state_holds_the_fields_of_the_string() -> None:
    session = ds.DrillSession(_coupled())
    session.step(2.0)
    state = session.state()
    n = state["z_m"].size
    for name in ("omega_rpm", "torque_Nm", "contact_N_per_m", "stuck"):
        assert state[name].shape == (n,), name
    assert state["stuck"].dtype == bool
    assert state["axial_z_m"].shape == state["axial_force_N"].shape
    assert state["t_s"] == session.t
    # the top cell turns with the top drive (its speed within the cell's travel of the surface's)
    assert state["surface_rpm"] == pytest.approx(session.rows(len(session) - 1)["surface_rpm"][0], rel=0.05, abs=1.0)


def test_a_gain_the_sampled_loop_cannot_hold_is_refused_and_the_session_runs_on() -> None:
    # (a run that diverges ends with a status, never a panic: the core's session tests step a
    # state beyond the runaway bound)
    session = ds.DrillSession(_torsional())
    session.step(0.5)
    with pytest.raises(ds.ValidationError) as err:
        session.set("top_drive.controller.kp", 1e12)
    assert err.value.field in ("top_drive.controller.kp", "numerics.cells")
    assert session.status == "success"
    session.step(0.5)
    assert session.changes == []


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_stops_a_long_step_and_the_session_stays_usable(tmp_path: Path) -> None:
    script = f"""
        import time
        import drillstring as ds
        cfg = ds.load_drill_config({str(EXAMPLES / "on-bottom-3000m.toml")!r}).with_overrides(
            {{"numerics.duration": 86000.0, "numerics.field_interval": 0.0, "numerics.output_interval": 10.0}})
        s = ds.DrillSession(cfg)
        print("ready", flush=True)
        try:
            s.step(86000.0)
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), s.t > 0.0, s.status, flush=True)
        s.step(0.1)
        print("usable", s.status, flush=True)
    """
    with python_child(script, cwd=tmp_path) as child:
        time.sleep(1.0)
        sent = child.interrupt()
        out, err = child.communicate(timeout=120)
    lines = out.splitlines()
    assert any(line.startswith("interrupted") and line.endswith("True success") for line in lines), (out, err)
    latency = float(next(line for line in lines if line.startswith("interrupted")).split()[1]) - sent
    print(f"Ctrl-C latency {1e3 * latency:.1f} ms")
    assert "usable success" in lines, (out, err)


def test_result_save_writes_a_config_that_repeats_the_run(tmp_path: Path) -> None:
    session = ds.DrillSession(_torsional(10.0))
    session.step(4.0)
    session.set("top_drive.rpm", 70.0)
    session.step(3.0)
    session.set("friction.static", 0.3)
    session.step(1.5)
    result = session.result()
    result.save(tmp_path / "run", plots=False)
    again = ds.drill(tmp_path / "run" / "config.toml")
    _same_bits(again, result)
    assert len(again.config.changes) == 2
    assert again.metrics.to_dict() == result.metrics.to_dict()


def test_series_columns_are_the_results() -> None:
    session = ds.DrillSession(_torsional(4.0))
    session.step(1.0)
    frame = session.series()
    assert list(frame.columns) == list(SERIES)
    assert len(frame) == len(session)


def test_the_guides_example_prints_what_the_guide_says(monkeypatch: pytest.MonkeyPatch,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    """docs/guide/session.md's controller loop, run as written, prints its output block."""
    import re

    page = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "session.md").read_text(encoding="utf-8")
    (block,) = re.findall(r"^```python\n(.*?)^```", page, flags=re.S | re.M)
    printed = re.findall(r"^```text\n(.*?)^```", page, flags=re.S | re.M)[-1]
    monkeypatch.chdir(EXAMPLES.parent)
    exec(compile(block, "docs/guide/session.md", "exec"), {"__name__": "__example__"})
    assert capsys.readouterr().out == printed


def test_a_field_configurations_set_reads_plain_numbers_in_field_units() -> None:
    session = ds.DrillSession(EXAMPLES / "on-bottom-3000m-field.toml")
    session.set("bit.weight_on_bit", 18.0)        # klbf, as --set reads it in this file
    session.set("bit.weight_on_bit", "80 kN")     # a quantity in its own unit
    (_, _, first), (_, _, second) = [c for c in session.changes]
    assert first == pytest.approx(18.0 * 4448.2216152605, rel=1e-12)
    assert second == pytest.approx(80e3, rel=1e-12)
    reference = ds.load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml").with_overrides(["bit.weight_on_bit=18"])
    assert reference.bit.weight_on_bit == pytest.approx(first, rel=1e-12)


def test_a_field_files_changes_read_their_values_in_the_keys_field_units(tmp_path: Path) -> None:
    """A ``[[changes]]`` value in a ``units = "field"`` file is in the field unit of the key it
    changes (klbf for the weight on bit, as the key itself is read), or a quantity with a unit."""
    text = (EXAMPLES / "on-bottom-3000m-field.toml").read_text(encoding="utf-8")
    changes = ('\n[[changes]]\ntime = 4.0\nkey = "bit.weight_on_bit"\nvalue = 18.0\n'
               '\n[[changes]]\ntime = 6.0\nkey = "top_drive.rpm"\nvalue = "7 rad/s"\n')
    path = tmp_path / "field.toml"
    path.write_text(text + changes, encoding="utf-8")
    cfg = ds.load_drill_config(path)
    assert [c.value for c in cfg.changes] == pytest.approx([18.0 * 4448.2216152605, 7.0 * 60.0 / (2.0 * np.pi)],
                                                          rel=1e-12)
    short = {"numerics.duration": 8.0, "numerics.cells": 100}
    session = ds.DrillSession(ds.load_drill_config(EXAMPLES / "on-bottom-3000m-field.toml").with_overrides(short))
    session.step(4.0)
    session.set("bit.weight_on_bit", 18.0)
    session.step(2.0)
    session.set("top_drive.rpm", 7.0 * 60.0 / (2.0 * np.pi))
    session.step(2.0)
    _same_bits(session.result(), ds.drill(cfg.with_overrides(short), progress=False))
