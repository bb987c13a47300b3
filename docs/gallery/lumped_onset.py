"""The lumped two-inertia model: where stick-slip starts

Navarro-Lopez & Cortes's two-inertia model (rotary table and bit joined by a spring and a
damper, the same velocity-weakening bit torque) at a constant motor torque of 6000 N m, over
the weight on bit. The markers are the steady rotations of the linear analysis (filled:
stable); the band and the line are the bit speed of runs from rest (range and mean), and the
lower panel their SSI and stuck fraction. Stick-slip from rest starts at 51.5 kN, while the faster
rotation is still stable (a subcritical onset); from 58 kN the bit ends stuck.
"""

import numpy as np

from drillstring.drilling import lumped_sweep, lumped_sweep_figure

frame = lumped_sweep("wob", np.linspace(40e3, 62e3, 23), duration=150.0)
print(frame[["wob", "ssi", "stuck_fraction"]].iloc[::4].round(3).to_string(index=False))
fig = lumped_sweep_figure(frame)
