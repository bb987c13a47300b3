"""A stick-slip map: speed against weight on bit, two controllers

`examples/on-bottom-3000m.toml` (3000 m of 5-in pipe, 200 m of collars, an 8.5-in bit on
bottom) over seven top-drive speeds, five weights on bit and two controllers: 70 runs of 60 s,
solved in parallel by the core. The contour SSI = 1 is the stick-slip boundary (the bit-speed
oscillation as large as its mean: the bit just reaches standstill). Under the stiff PI
controller the bit sticks at low speed; the soft-torque controller, which presents a damper
matched to the pipe's impedance at the string's first natural frequency, removes most of it.
"""

import numpy as np

import drillstring as ds

cfg = ds.load_drill_config("examples/on-bottom-3000m.toml")
df = ds.drill_map(cfg, {"top_drive.rpm": np.linspace(40, 160, 7),
                        "bit.weight_on_bit": np.linspace(40e3, 120e3, 5),
                        "top_drive.controller.type": ["pi", "soft_torque"]})
print(df.pivot_table(index=["top_drive.controller.type", "bit.weight_on_bit"], columns="top_drive.rpm",
                     values="ssi").round(2).to_string())
fig = ds.drilling.controller_maps(df, "top_drive.rpm", "bit.weight_on_bit")
