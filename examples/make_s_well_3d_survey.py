"""Writes examples/s-well-3d-survey.csv: a 3-D S-shaped well of 4000 m as a survey company
delivers it (stations 25-35 m apart, angles read to 0.01 degree with a small scatter), and
examples/s-well-3d-survey-ft.csv, the same stations with measured depths in feet (to 0.01 ft;
column md_ft) for examples/s-well-3d-field.toml.

The plan, as inclination and azimuth changing at constant rates in measured depth:
vertical to 600 m; build at 2.5 deg/30 m to 35 deg at azimuth 60 deg; hold to 1500 m; turn
right at 1.5 deg/30 m to azimuth 100 deg while holding 35 deg; hold to 2700 m; drop at
2 deg/30 m to 10 deg while turning back to azimuth 80 deg; hold to 4000 m.

    python examples/make_s_well_3d_survey.py    # rewrites the CSV (seeded: the same file)
"""

from pathlib import Path

import numpy as np

# (md at the segment's end, inclination there, azimuth there); linear in md within a segment
PLAN = [
    (0.0, 0.0, 60.0),
    (600.0, 0.0, 60.0),
    (600.0 + 35.0 / 2.5 * 30.0, 35.0, 60.0),
    (1500.0, 35.0, 60.0),
    (1500.0 + 40.0 / 1.5 * 30.0, 35.0, 100.0),
    (2700.0, 35.0, 100.0),
    (2700.0 + 25.0 / 2.0 * 30.0, 10.0, 80.0),
    (4000.0, 10.0, 80.0),
]


def main() -> None:
    rng = np.random.default_rng(20261203)
    md = [0.0]
    while md[-1] < 4000.0 - 35.0:
        md.append(md[-1] + round(float(rng.uniform(25.0, 35.0)), 2))
    md.append(4000.0)
    depth, inc, azi = (np.array(c) for c in zip(*PLAN))
    m = np.array(md)
    i = np.interp(m, depth, inc)
    a = np.interp(m, depth, azi)
    scatter = m > 0.0
    i = np.where(scatter & (i > 0.5), i + rng.normal(0.0, 0.03, m.size), i)
    a = np.where(scatter & (i > 0.5), a + rng.normal(0.0, 0.1, m.size), a)
    rows = ["md_m,inc_deg,azi_deg"] + [f"{x:.2f},{y:.2f},{z % 360.0:.2f}" for x, y, z in zip(m, i, a)]
    Path(__file__).with_name("s-well-3d-survey.csv").write_text("\n".join(rows) + "\n")
    feet = ["md_ft,inc_deg,azi_deg"] + [f"{x / 0.3048:.2f},{y:.2f},{z % 360.0:.2f}" for x, y, z in zip(m, i, a)]
    Path(__file__).with_name("s-well-3d-survey-ft.csv").write_text("\n".join(feet) + "\n")


if __name__ == "__main__":
    main()
