"""What a ``drillstring drill`` output folder holds, checked the same way wherever one is written
(the command, a recording of the live display): its files, ``metrics.json``'s keys and status, the
series' columns, and that ``drill`` of the ``config.toml`` written repeats ``series.csv``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from drillstring.drilling import FILES, drill, load_drill_config
from drillstring.drilling.output import PLOT_FILES
from drillstring.drilling.result import AXIAL_SERIES, SERIES

#: Keys every metrics.json has.
METRIC_KEYS = {"period_s", "ssi", "stuck_fraction", "bit_rpm_min", "bit_rpm_max", "bit_rpm_mean",
               "motor_torque_min_Nm", "motor_torque_max_Nm", "breakoff_torque_Nm", "min_cycle_torque_Nm",
               "window_start", "window_end", "window", "status", "message", "energy"}


def check_drill_folder(folder: Path, *, plots: bool = True, coupled: bool = False) -> pd.DataFrame:
    """Checks the drill output folder ``folder`` and returns its series (``series.csv``)."""
    expected = set(FILES) if plots else set(FILES) - set(PLOT_FILES)
    assert {p.name for p in folder.iterdir()} == expected
    metrics = json.loads((folder / "metrics.json").read_text())
    assert METRIC_KEYS <= set(metrics) and metrics["status"] == "success", metrics.get("message")
    series = pd.read_csv(folder / "series.csv", index_col="t")
    assert list(series.columns) == [*SERIES, *(AXIAL_SERIES if coupled else ())]
    again = drill(load_drill_config(folder / "config.toml"))
    assert again.t.size == series.index.size
    np.testing.assert_allclose(again.t, series.index.to_numpy(), rtol=1e-12)
    for name in SERIES:
        np.testing.assert_allclose(getattr(again, name), series[name].to_numpy(), rtol=1e-9, atol=1e-9)
    return series
