"""The live display's server without a browser: a WebSocket client (aiohttp) gets the frames, the
answers to its commands, the error message of a key that cannot change; the decimation of the
series; the command line's errors and its Ctrl-C."""

from __future__ import annotations

import asyncio
import json
import math
import sys
import time
from collections.abc import Awaitable
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest
from _children import python_child
from _cli import one_line_error, run_cli
from _drill_folder import check_drill_folder
from hypothesis import given, settings
from hypothesis import strategies as st

from drillstring.drilling import DrillSession, drill, load_drill_config
from drillstring.drilling.metrics import OUTPUTS
from drillstring.drilling.units import axis_unit, metric_texts
from drillstring.live.display import controls, decimate
from drillstring.live.driver import Driver
from drillstring.live.server import Background, LiveApp

aiohttp = pytest.importorskip("aiohttp")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "on-bottom-3000m.toml"


def _config() -> Any:
    return load_drill_config(EXAMPLE).with_overrides(["numerics.cells=100"])


Client = Callable[[Any], Awaitable[Any]]


def _talk(tmp_path: Path, body: Client, *, speed: float = 1.0, config: Any = None) -> Any:
    """Runs ``body(ws)`` against a display of ``config`` (default: the example on 100 cells) served
    on a free port."""
    driver = Driver(config or _config(), speed=speed, record_dir=tmp_path)

    async def client(url: str) -> Any:
        async with aiohttp.ClientSession() as http, http.ws_connect(url + "ws") as ws:
            return await body(ws)

    with Background(LiveApp(driver, name="on-bottom")) as server:
        return asyncio.run(asyncio.wait_for(client(server.url), 60))


async def _next(ws: Any, kind: str) -> dict[str, Any]:
    while True:
        message = json.loads((await ws.receive()).data)
        if message["type"] == kind:
            return message  # type: ignore[no-any-return]


async def _reply(ws: Any, command: dict[str, Any], events: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    """Sends ``command`` and returns its reply; the events of the frames passed on the way are
    added to ``events``."""
    await ws.send_str(json.dumps(command))
    while True:
        message = json.loads((await ws.receive()).data)
        if events is not None:
            events += message.get("events", [])
        if message["type"] == "reply" and message["id"] == command["id"]:
            return message  # type: ignore[no-any-return]


def test_frames_arrive_with_the_tracks_of_the_run_and_time_advances(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        hello = await _next(ws, "hello")
        frames = [await _next(ws, "frame") for _ in range(30)]
        return hello, frames

    hello, frames = _talk(tmp_path, body)
    names = [c["name"] for c in hello["tracks"]]
    assert names == ["surface_rpm", "motor_torque", "bit_rpm", "bit_torque"]  # torsion only: no hook load
    assert {c["key"] for c in hello["controls"]} >= {"top_drive.rpm"}
    times = [f["status"]["t"] for f in frames]
    assert times[-1] > times[0] and all(b >= a for a, b in zip(times, times[1:]))
    rows = [f["rows"] for f in frames if "rows" in f]
    t = np.concatenate([r["t"] for r in rows])
    assert np.all(np.diff(t) > 0)  # each row drawn once, in order
    # at 1x, 30 frames of 50 ms are about 1.5 s of the run
    assert 0.5 < times[-1] - times[0] < 3.0
    state = next(f["state"] for f in frames if "state" in f)
    # every cell of the grid (about the 100 asked for: the sections are split into whole cells)
    assert len(state["z_m"]) == len(state["omega_rpm"]) == len(state["contact_N_per_m"]) >= 90
    assert state["z_m"][-1] < 3200.0 < state["z_m"][-1] + 3200.0 / 90 and state["bit_stuck"] in (True, False)


def test_a_coupled_run_shows_the_hoist_and_the_axial_field(tmp_path: Path) -> None:
    config = load_drill_config(ROOT / "examples" / "coupled-deviated-3200m.toml").with_overrides(
        ["numerics.cells=100"])

    async def body(ws: Any) -> Any:
        hello = await _next(ws, "hello")
        frames = [await _next(ws, "frame") for _ in range(20)]
        wob = await _reply(ws, {"type": "set", "id": 1, "key": "hoist.weight_on_bit", "value": 100e3})
        return hello, frames, wob

    hello, frames, wob = _talk(tmp_path, body, config=config, speed=4.0)
    assert [c["name"] for c in hello["tracks"]] == ["surface_rpm", "motor_torque", "hook_load", "block_position",
                                                    "bit_depth", "weight_on_bit", "rop", "bit_rpm", "bit_torque"]
    assert "hoist.weight_on_bit" in {c["key"] for c in hello["controls"]}
    rows = [f["rows"] for f in frames if "rows" in f]
    assert rows and all(set(r) == {"t", *(c["name"] for c in hello["tracks"])} for r in rows)
    state = next(f["state"] for f in frames if "state" in f)
    assert len(state["axial_z_m"]) == len(state["axial_force_N"]) > 0
    assert wob["ok"], wob


def test_the_verdict_of_the_last_window_is_the_batch_runs_over_that_window(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        while True:
            frame = await _next(ws, "frame")
            if "verdict" in frame:
                return frame["verdict"]

    shown = _talk(tmp_path, body, speed=4.0)
    start, end = shown["window"]
    assert end - start == pytest.approx(15.0) or start == 0.0
    # the same run by drill to the window's end, its metrics over the window, as drill's console says them
    batch = drill(_config().with_overrides([f"numerics.duration={end!r}", f"metrics.window=[{start!r}, {end!r}]"]))
    names = [n for n, o in OUTPUTS.items() if o.console and "torsional" in o.runs]
    assert shown["texts"] == metric_texts(batch.metrics.values, names, "si")
    assert shown["verdict"] == batch.metrics.stick_slip_verdict and "SSI" in shown["texts"][0]


def test_a_page_connecting_while_the_run_steps_flat_out_gets_its_hello_and_frames(tmp_path: Path) -> None:
    # at --speed max the stepping thread is (almost) always inside a step: the server must not
    # touch the session from its own thread
    async def body(ws: Any) -> Any:
        hello = await _next(ws, "hello")
        frames = [await _next(ws, "frame") for _ in range(10)]
        return hello, frames

    time.sleep(0.3)
    hello, frames = _talk(tmp_path, body, speed=math.inf)
    assert hello["dt"] > 0 and frames[-1]["status"]["speed"] == "max"
    assert frames[-1]["status"]["t"] > frames[0]["status"]["t"]


def test_a_set_is_answered_and_a_key_that_cannot_change_gets_its_message(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        await _next(ws, "frame")
        events: list[dict[str, Any]] = []
        good = await _reply(ws, {"type": "set", "id": 1, "key": "top_drive.rpm", "value": 80.0}, events)
        bad_key = await _reply(ws, {"type": "set", "id": 2, "key": "numerics.cells", "value": 80}, events)
        bad_value = await _reply(ws, {"type": "set", "id": 3, "key": "top_drive.rpm", "value": "fast"}, events)
        unknown = await _reply(ws, {"type": "jump", "id": 4}, events)
        while not events:
            events += (await _next(ws, "frame")).get("events", [])
        return good, bad_key, bad_value, unknown, events

    good, bad_key, bad_value, unknown, events = _talk(tmp_path, body)
    assert good["ok"] is True
    assert bad_key["ok"] is False and "numerics.cells" in bad_key["message"]
    assert bad_value["ok"] is False and "top_drive.rpm" in bad_value["message"]
    assert unknown["ok"] is False and "jump" in unknown["message"]
    assert events[0]["key"] == "top_drive.rpm" and events[0]["value"] == 80.0


def test_pause_stops_the_clock_and_resume_starts_it(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        await _next(ws, "frame")
        assert (await _reply(ws, {"type": "pause", "id": 1}))["ok"]
        paused = [(await _next(ws, "frame"))["status"] for _ in range(10)]
        assert (await _reply(ws, {"type": "resume", "id": 2}))["ok"]
        running = [(await _next(ws, "frame"))["status"] for _ in range(10)]
        return paused, running

    paused, running = _talk(tmp_path, body)
    assert all(s["paused"] for s in paused) and len({s["t"] for s in paused}) == 1
    assert not running[-1]["paused"] and running[-1]["t"] > paused[-1]["t"]


def test_a_page_opened_later_shows_the_setpoints_changed_and_another_site_is_refused(tmp_path: Path) -> None:
    driver = Driver(_config(), record_dir=tmp_path)

    async def pages(url: str) -> tuple[dict[str, Any], int]:
        async with aiohttp.ClientSession() as http:
            async with http.ws_connect(url + "ws") as first:
                assert (await _reply(first, {"type": "set", "id": 1, "key": "top_drive.rpm", "value": 70.0}))["ok"]
            async with http.ws_connect(url + "ws") as second:
                hello = await _next(second, "hello")
            try:
                async with http.ws_connect(url + "ws", origin="http://elsewhere.example"):
                    status = 101
            except aiohttp.WSServerHandshakeError as exc:
                status = exc.status
        return hello, status

    with Background(LiveApp(driver)) as server:
        hello, status = asyncio.run(asyncio.wait_for(pages(server.url), 60))
    assert next(c for c in hello["controls"] if c["key"] == "top_drive.rpm")["value"] == 70.0
    assert status == 403


def test_reset_starts_the_run_again_and_tells_the_page(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        before = await _next(ws, "frame")
        while before["status"]["t"] < 1.0:
            before = await _next(ws, "frame")
        assert (await _reply(ws, {"type": "set", "id": 1, "key": "top_drive.rpm", "value": 60.0}))["ok"]
        await ws.send_str(json.dumps({"type": "reset", "id": 2}))
        seen: dict[str, Any] = {}
        while not {"reply", "reset"} <= set(seen):  # the reply and the reset's message, in either order
            message = json.loads((await ws.receive()).data)
            seen.setdefault(message["type"], message)
        assert seen["reply"]["ok"]
        reset = seen["reset"]
        after = await _next(ws, "frame")
        return before, reset, after

    before, reset, after = _talk(tmp_path, body)
    assert after["status"]["t"] < 0.5 < before["status"]["t"]
    rpm = next(c for c in reset["controls"] if c["key"] == "top_drive.rpm")
    assert rpm["value"] == 40.0  # the configuration's setpoint again: the changes are dropped


def test_a_preset_sets_the_controller_type_and_gains_of_this_string(tmp_path: Path) -> None:
    async def body(ws: Any) -> Any:
        await _next(ws, "frame")
        await ws.send_str(json.dumps({"type": "preset", "id": 1, "value": "soft_torque"}))
        await ws.send_str(json.dumps({"type": "preset", "id": 2, "value": "gentle"}))
        replies: dict[int, Any] = {}
        events: list[dict[str, Any]] = []
        while len(replies) < 2 or len(events) < 4:  # replies and frames in any order
            message = json.loads((await ws.receive()).data)
            if message["type"] == "reply":
                replies[message["id"]] = message
            events += message.get("events", [])
        return replies[1], replies[2], events

    done, bad, events = _talk(tmp_path, body)
    assert done["ok"] and done["result"] == [f"top_drive.controller.{k}" for k in ("type", "kp", "ki", "z_factor")]
    assert not bad["ok"] and "gentle" in bad["message"] and "soft_torque" in bad["message"]
    changed = {e["key"].rsplit(".", 1)[1]: e["value"] for e in events}
    # soft torque for this string (ARCHITECTURE.md, tuning.rs): kp = z_factor Z, ki = (2 pi f1)^2 I_TD
    from drillstring.drilling import recommend_controllers

    numbers = recommend_controllers(_config()).string
    assert changed["type"] == "soft_torque"
    assert changed["kp"] == pytest.approx(changed["z_factor"] * numbers.impedance, rel=1e-12)
    assert changed["ki"] == pytest.approx((2 * np.pi * numbers.first_mode_hz) ** 2 * numbers.top_drive_inertia,
                                          rel=1e-12)


def test_the_controls_are_the_setpoints_of_the_run() -> None:
    settable = DrillSession(EXAMPLE).settable
    torsion = {c["key"] for c in controls(settable, load_drill_config(EXAMPLE), "si")}
    assert torsion == {"top_drive.rpm", "bit.weight_on_bit", "top_drive.controller.type", "top_drive.controller.preset"}
    coupled = load_drill_config(ROOT / "examples" / "coupled-deviated-3200m.toml")
    assert coupled.hoist is not None and coupled.hoist.mode == "weight_on_bit"
    keys = {c["key"] for c in controls(settable, coupled, "si")}
    assert keys == {"top_drive.rpm", "hoist.weight_on_bit", "top_drive.controller.type", "top_drive.controller.preset"}


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 0.2), min_size=1, max_size=200), st.lists(st.integers(1, 40), max_size=10),
       st.sampled_from([0.01, 0.05, 0.3]))
def test_decimation_does_not_depend_on_how_the_rows_arrive(gaps: list[float], cuts: list[int], step: float) -> None:
    # rows arriving in any chunks keep the same rows as all at once: one per interval of `step`
    t = np.cumsum(np.asarray(gaps) + 1e-3)
    whole = t[decimate(t, step, -np.inf)]
    kept, last, start = [], -np.inf, 0
    for end in [*np.cumsum(cuts), t.size]:
        chunk = t[start:min(end, t.size)]
        start = min(end, t.size)
        picked = chunk[decimate(chunk, step, last)]
        if picked.size:
            last = float(picked[-1])
        kept.append(picked)
    np.testing.assert_array_equal(np.concatenate(kept), whole)
    assert np.unique(np.floor(whole / step)).size == whole.size == np.unique(np.floor(t / step)).size


def test_a_field_configuration_gets_the_pages_si_values_as_they_are(tmp_path: Path) -> None:
    # the page sends SI (its factor undone); a field file's session reads plain numbers in klbf
    config = load_drill_config(ROOT / "examples" / "on-bottom-3000m-field.toml").with_overrides(
        ["numerics.cells=60"], units="si")
    assert config.units == "field"
    driver = Driver(config, record_dir=tmp_path)
    driver.start()
    try:
        driver.submit("set", ("bit.weight_on_bit", 100e3)).result(timeout=30)
        driver.submit("set", ("top_drive.rpm", 80.0)).result(timeout=30)
        driver.submit("pause").result(timeout=30)
        changes = [(key, value) for _, key, value in driver.session.changes]
    finally:
        driver.stop()
    assert changes == [("bit.weight_on_bit", pytest.approx(100e3, rel=1e-12)), ("top_drive.rpm", 80.0)]


def test_a_recording_of_a_field_configuration_repeats_with_drill(tmp_path: Path) -> None:
    config = load_drill_config(ROOT / "examples" / "on-bottom-3000m-field.toml").with_overrides(
        ["numerics.cells=60"], units="si")
    driver = Driver(config, speed=4.0, record_dir=tmp_path)
    driver.start()
    try:
        time.sleep(0.5)
        driver.submit("set", ("bit.weight_on_bit", 100e3)).result(timeout=30)
        time.sleep(0.5)
        folder = Path(driver.submit("record").result(timeout=120))
    finally:
        driver.stop()
    check_drill_folder(folder)
    (change,) = load_drill_config(folder / "config.toml").changes
    assert change.key == "bit.weight_on_bit" and change.value == pytest.approx(100e3, rel=1e-12)


def test_field_units_show_the_setpoints_in_klbf() -> None:
    config = load_drill_config(EXAMPLE)
    shown = {c["key"]: c for c in controls(("top_drive.rpm", "bit.weight_on_bit"), config, "field")}
    wob = shown["bit.weight_on_bit"]
    assert wob["unit"] == "klbf" and wob["value"] * wob["factor"] == pytest.approx(80e3 / 4448.2216152605)
    assert shown["top_drive.rpm"]["factor"] == 1.0 and shown["top_drive.rpm"]["unit"] == "rpm"
    assert axis_unit("N", "si", kilo=True) == (1e-3, "kN")


@pytest.mark.parametrize(("args", "needles"), [(["--speed", "0"], ["--speed", "max"]),
                                               (["--port", "70000"], ["--port", "65535"])])
def test_bad_options_are_one_line_usage_errors(args: list[str], needles: list[str],
                                               capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        run_cli(capsys, "live", str(EXAMPLE), "--no-browser", *args)
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and len(err.strip().splitlines()) == 1 and all(n in err for n in needles), err


def test_a_bad_value_is_one_line_with_exit_status_2(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_cli(capsys, "live", str(EXAMPLE), "--no-browser", "--set", "top_drive.rpm=fast")
    assert code == 2
    one_line_error(err, "top_drive.rpm")


def test_without_the_extra_the_command_names_it(capsys: pytest.CaptureFixture[str],
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "aiohttp", None)  # as if not installed: its import fails
    code, _, err = run_cli(capsys, "live", str(EXAMPLE), "--no-browser")
    assert code == 2
    one_line_error(err, "live", "aiohttp")


def test_the_command_prints_its_address_serves_the_page_and_stops_on_ctrl_c(tmp_path: Path) -> None:
    script = f"""
        import sys
        from drillstring.cli import main
        sys.exit(main(["live", {str(EXAMPLE)!r}, "--no-browser", "--port", "0", "--set", "numerics.cells=60",
                       "--record-dir", {str(tmp_path)!r}]))
    """
    with python_child(script, cwd=tmp_path, ready=None) as child:
        line = child.read_line()
        assert line.startswith("drillstring live: http://127.0.0.1:"), line
        url = line.split()[2]

        async def get() -> tuple[int, str, int]:
            async with aiohttp.ClientSession() as http:
                async with http.get(url) as page:
                    text = await page.text()
                async with http.get(url + "static/vendor/dygraph.min.js") as script:
                    return page.status, text, len(await script.read())

        status, text, size = asyncio.run(get())
        assert status == 200 and "dygraph.min.js" in text and size > 100_000
        child.wait_cpu(0.2)  # the run under way
        child.interrupt()
        out, err = child.communicate(timeout=60)
        assert child.proc.returncode == 0, err
    assert "drillstring live: stopped" in out and "Traceback" not in err
