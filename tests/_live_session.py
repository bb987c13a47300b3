"""A stand-in of ``DrillSession`` for the live display's tests: the session's interface with a
cheap made-up motion (the top drive follows its setpoint with a lag of ``TAU`` s, the bit swings
about it), its keys checked by the configuration's own overrides, and ``result()`` a real
``drill`` run of the same changes, so a recording is a real output folder."""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from drillstring.drilling import DrillConfig, drill
from drillstring.errors import ValidationError

#: The lag of the stand-in's top drive behind its setpoint, s.
TAU = 0.5
SETTABLE = ("top_drive.rpm", "top_drive.torque_limit", "top_drive.controller.type", "top_drive.controller.kp",
            "top_drive.controller.ki", "top_drive.controller.z_factor", "bit.weight_on_bit", "friction.static",
            "friction.kinetic_ratio", "hoist.mode", "hoist.speed", "hoist.hook_load", "hoist.weight_on_bit",
            "hoist.autodriller.setpoint", "hoist.autodriller.kp", "hoist.autodriller.ki")


class StandInSession:
    def __init__(self, config: DrillConfig) -> None:
        self.config = self._base = config
        self.dt = 0.002
        self.t = 0.0
        self.status, self.message = "success", ""
        self.settable = SETTABLE
        self.changes: list[tuple[float, str, Any]] = []
        self._rpm = 0.0
        self._every = float(config.numerics.output_interval)
        self._rows: dict[str, list[float]] = {k: [] for k in ("t", "surface_rpm", "bit_rpm", "motor_torque",
                                                              "bit_torque")}
        self._record()

    def __len__(self) -> int:
        return len(self._rows["t"])

    def _setpoint(self) -> float:
        return float(self.config.top_drive.rpm)

    def _record(self) -> None:
        swing = 0.8 * math.sin(2 * math.pi * self.t / 6.6)
        self._rows["t"].append(self.t)
        self._rows["surface_rpm"].append(self._rpm)
        self._rows["bit_rpm"].append(max(self._rpm * (1 + swing), 0.0))
        self._rows["motor_torque"].append(8e3 + 4e3 * swing)
        self._rows["bit_torque"].append(6e3 - 1e3 * swing)

    def step(self, seconds: float) -> None:
        steps = max(1, round(seconds / self.dt))
        for _ in range(steps):
            self._rpm += (self._setpoint() - self._rpm) * self.dt / TAU
            self.t = round(self.t + self.dt, 9)
            if self.t + 1e-9 >= len(self) * self._every:
                self._record()

    def set(self, key: str, value: Any) -> None:
        if key not in self.settable or (key.startswith("hoist.") and self.config.hoist is None):
            raise ValidationError(key, value, f"a key that can change during a run: {', '.join(self.settable)}")
        self.config = self.config.with_overrides([f"{key}={value!r}" if isinstance(value, str) else f"{key}={value}"])
        self.changes.append((self.t + self.dt, key, value))

    def state(self) -> dict[str, Any]:
        cells = int(self.config.numerics.cells)
        length = sum(s.length for s in self.config.sections)
        z = (np.arange(cells) + 0.5) * length / cells
        phase = 2 * np.pi * (z / length - self.t / 6.6)
        return {
            "z_m": z, "omega_rpm": self._rpm * (1 + 0.5 * np.sin(phase)), "torque_Nm": 8e3 * (1 - z / length),
            "contact_N_per_m": np.where(z > 800, 300.0, 0.0), "stuck": np.zeros(cells, dtype=bool),
            "t_s": self.t, "surface_rpm": self._rpm, "bit_rpm": self._rows["bit_rpm"][-1],
            "motor_torque_Nm": self._rows["motor_torque"][-1], "bit_torque_Nm": self._rows["bit_torque"][-1],
        }

    def rows(self, start: int = 0) -> dict[str, np.ndarray]:
        return {k: np.asarray(v[start:]) for k, v in self._rows.items()}

    def metrics(self, window: Optional[tuple[float, float]] = None) -> dict[str, Any]:
        return {"stick_slip_verdict": "yes", "ssi": 1.6, "stuck_fraction": 0.2, "period_s": 6.6,
                "bit_rpm_min": 0.0, "bit_rpm_max": 2.6 * self._setpoint()}

    def result(self, window: Optional[tuple[float, float]] = None) -> Any:
        steps = [[t, v] for t, key, v in self.changes if key == "top_drive.rpm"]
        overrides = [f"numerics.duration={self.t}"] + ([f"top_drive.steps={steps}"] if steps else [])
        return drill(self._base.with_overrides(overrides, units="si"))


def session_class() -> Any:
    """The session the live display's tests drive: ``DrillSession`` once the package has it, else
    the stand-in."""
    try:
        from drillstring.drilling.session import DrillSession  # type: ignore[import-not-found]
    except ImportError:
        return StandInSession
    return DrillSession
