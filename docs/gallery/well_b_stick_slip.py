"""Well B: one stick-slip run

Aarsnes & Shor's Well B (2500 m of drill pipe and collars, 60° tangent, bit off bottom, 40 rpm
under a stiff PI controller) with the quirks of their published code corrected
(`examples/aarsnes-shor-well-b-corrected.toml`; `examples/aarsnes-shor-well-b.toml` is the
set-up of their code, which {doc}`../../models/verification` compares with its Octave run): 60 s
on 1000 cells. The wall friction holds the string until the top drive has wound up the
break-off torque; then the string slips, the bit runs up to about four times the setpoint and
sticks again, about every 7.2 s. The figures are those `drillstring drill` writes: the time
histories (bit and surface speed, motor torque), the speed and torque along the string over
time, and the torque against depth inside the break-off envelope.
"""

import drillstring as ds
from drillstring.drilling import plots

res = ds.drill("examples/aarsnes-shor-well-b-corrected.toml")
m = res.metrics
print(f"SSI {m.ssi:.2f}, stuck fraction {m.stuck_fraction:.2f}, period {m.period_s:.2f} s")
print(f"bit {m.bit_rpm_min:.0f}..{m.bit_rpm_max:.0f} rpm, motor torque "
      f"{m.motor_torque_min_Nm / 1e3:.1f}..{m.motor_torque_max_Nm / 1e3:.1f} kN m, "
      f"break-off {m.breakoff_torque_Nm / 1e3:.2f} kN m")
print(f"stick-slip: {m.stick_slip}, settled: {m.settled}, warnings: {res.warnings}")
histories = plots.time_histories(res)
space_time = plots.space_time_maps(res)
depth = plots.torque_depth(res)
