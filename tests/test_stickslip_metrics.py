"""Stick-slip metrics of bit-speed and motor-torque series (``drillstring.drilling.metrics``
``stick_slip_metrics``, ``break_off_torque``; computed by ``drillstring_core::metrics::stickslip``)
against analytic values, and the refusal of bad input naming the argument."""

from __future__ import annotations

import math
from typing import Callable

import _docs
import numpy as np
import pytest

from drillstring import _core
from drillstring.drilling import metrics as metrics_module
from drillstring.errors import ValidationError

RPM = 60.0 / (2.0 * math.pi)


def test_sinusoidal_speed_has_severity_a_and_is_never_stuck() -> None:
    w0, a, f = 12.0, 0.7, 1.5
    t = np.linspace(0.0, 4.0, 24001)  # 6 whole periods
    omega = w0 * (1.0 + a * np.sin(2 * np.pi * f * t))
    m = metrics_module.stick_slip_metrics(t, omega)
    assert m.ssi == pytest.approx(a, abs=1e-6)
    assert m.stuck_fraction == 0.0
    assert m.bit_rpm_mean == pytest.approx(w0 * RPM, rel=1e-9)
    assert m.bit_rpm_min == pytest.approx(w0 * (1 - a) * RPM, rel=1e-6)
    assert m.bit_rpm_max == pytest.approx(w0 * (1 + a) * RPM, rel=1e-6)
    assert math.isnan(m.motor_torque_min_Nm) and math.isnan(m.motor_torque_max_Nm) and math.isnan(m.period_s)
    assert (m.window_start, m.window_end) == (0.0, 4.0)


@pytest.mark.parametrize("a", [1.5, 2.0, 4.0])
def test_clipped_speed_is_stuck_for_the_arccos_fraction(a: float) -> None:
    w0, f = 8.0, 0.5
    # non-uniform samples over 5 periods
    t = 10.0 * np.linspace(0.0, 1.0, 50001) ** 1.2
    omega = np.maximum(0.0, w0 * (1.0 + a * np.sin(2 * np.pi * f * t)))
    m = metrics_module.stick_slip_metrics(t, omega, stick_speed=0.0)
    assert m.stuck_fraction == pytest.approx(math.acos(1.0 / a) / math.pi, abs=3e-4)
    mean = w0 * (math.sqrt(a * a - 1.0) + math.pi - math.acos(1.0 / a)) / math.pi
    assert m.bit_rpm_mean == pytest.approx(mean * RPM, rel=1e-4)
    assert m.bit_rpm_min == 0.0
    assert m.ssi == pytest.approx(w0 * (1.0 + a) / (2.0 * mean), rel=1e-4)


def test_square_wave_and_its_period() -> None:
    # stuck for 0.3 of each 2 s period, 5 rad/s otherwise; the motor torque follows it
    t = np.linspace(0.0, 8.0, 80001)
    stuck = (t % 2.0) < 0.6
    omega = np.where(stuck, 0.0, 5.0)
    torque = np.where(stuck, 900.0, 300.0)
    m = metrics_module.stick_slip_metrics(t, omega, torque, window=(0.0, 7.99))
    assert m.stuck_fraction == pytest.approx(0.3, abs=1e-3)
    assert m.ssi == pytest.approx(5.0 / (2 * 3.5), rel=1e-3)
    assert (m.motor_torque_min_Nm, m.motor_torque_max_Nm) == (300.0, 900.0)
    # the period from the similarity of the torque with itself shifted, resampled to 16384
    # samples over the window: exact to a fraction of a resampled step (4.9e-4 s)
    assert m.period_s == pytest.approx(2.0, abs=1e-4)


def test_motor_torque_period_of_a_sine_and_fewer_than_two_cycles() -> None:
    t = np.sort(np.random.default_rng(3).uniform(0.0, 3.0, 30000))
    torque = 2e3 + 5e2 * np.sin(2 * np.pi * 1.25 * t + 0.4)
    omega = np.full(t.size, 10.0)
    m = metrics_module.stick_slip_metrics(t, omega, torque)
    assert m.period_s == pytest.approx(0.8, rel=1e-4)
    assert m.motor_torque_min_Nm == pytest.approx(1.5e3, rel=1e-5)
    assert m.motor_torque_max_Nm == pytest.approx(2.5e3, rel=1e-5)
    assert m.ssi == 0.0
    # 1.25 cycles in the window: no period
    assert math.isnan(metrics_module.stick_slip_metrics(t, omega, torque, window=(0.0, 1.0)).period_s)


def test_zero_mean_speed_gives_nan_severity_and_the_threshold_counts() -> None:
    t = np.linspace(0.0, 1.0, 101)
    m = metrics_module.stick_slip_metrics(t, np.zeros(t.size))
    assert math.isnan(m.ssi) and m.stuck_fraction == 1.0
    # |omega| = 0.1 |t - 0.5| * 2 <= 0.05 for |t - 0.5| <= 0.25: half the time
    half = metrics_module.stick_slip_metrics(t, 0.2 * np.abs(t - 0.5), stick_speed=0.05)
    assert half.stuck_fraction == pytest.approx(0.5, abs=1e-12)
    assert metrics_module.STICK_SPEED == _core.STICK_SPEED > 0


def test_break_off_torque_of_constant_and_linear_limits() -> None:
    depth = np.linspace(0.0, 3500.0, 36)
    assert metrics_module.break_off_torque(depth, np.full(depth.size, 6.5)) == pytest.approx(6.5 * 3500.0, rel=1e-12)
    assert metrics_module.break_off_torque(depth, 0.002 * depth) == pytest.approx(0.001 * 3500.0**2, rel=1e-12)


T = np.linspace(0.0, 1.0, 11)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: metrics_module.stick_slip_metrics(np.r_[0.0, 1.0, 1.0], np.ones(3)), "t"),
        (lambda: metrics_module.stick_slip_metrics(np.r_[0.0, 2.0, 1.0], np.ones(3)), "t"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones(10)), "omega_bit"),
        (lambda: metrics_module.stick_slip_metrics(T, np.full(11, np.nan)), "omega_bit"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones(11), np.ones(12)), "motor_torque"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones(11), window=(0.42, 0.48)), "window"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones(11), window=(0.8, 0.2)), "window"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones(11), stick_speed=-1e-3), "stick_speed"),
        (lambda: metrics_module.stick_slip_metrics(T, np.ones((11, 1))), "omega_bit"),
        (lambda: metrics_module.break_off_torque([0.0, 0.0], [1.0, 1.0]), "depth"),
        (lambda: metrics_module.break_off_torque([0.0, 1.0], [1.0]), "limit"),
        (lambda: metrics_module.break_off_torque([0.0, 1.0], [1.0, -2.0]), "limit"),
    ],
)
def test_bad_input_names_the_argument(call: Callable[[], object], field: str) -> None:
    with pytest.raises(ValidationError) as err:
        call()
    assert err.value.field == field
    assert "expected" in str(err.value)


def test_readme_example(capsys: pytest.CaptureFixture[str]) -> None:
    (code,) = [c for c in _docs.blocks("python") if "stick_slip_metrics" in c]
    exec(compile(code, "the documentation's stick-slip example", "exec"), {})
    assert capsys.readouterr().out.splitlines() == ["SSI 1.23, stuck 0.334, period 4.00 s", "15000.0"]
