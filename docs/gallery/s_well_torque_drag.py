"""Torque and drag in a 3-D S well

`examples/s-well-3d.toml`: a 4000 m S-shaped 3-D well of 135 survey stations. The static
soft-string model (Johancsik et al. 1984) gives the tension, torque and normal force along the
string for pick-up, slack-off and rotation off and on bottom, the hook load against bit depth
for several friction factors (the broomstick plot), and the well's path. These numbers agree with
welleng run on the same well to 7e-5 once two defects of its torque and drag are corrected
({doc}`../../models/verification`).
"""

import drillstring as ds
from drillstring.drilling.torque_drag import broomstick_figure, profiles_figure, well_path_figure

td = ds.torque_drag("examples/s-well-3d.toml")
s = td.summary
print(f"hook load: pick-up {s['hook_load_pickup_N'] / 1e3:.1f} kN, slack-off {s['hook_load_slackoff_N'] / 1e3:.1f} kN, "
      f"rotating {s['hook_load_rotating_N'] / 1e3:.1f} kN")
print(f"surface torque: off bottom {s['surface_torque_off_bottom_Nm'] / 1e3:.2f} kN m, "
      f"on bottom {s['surface_torque_on_bottom_Nm'] / 1e3:.2f} kN m")
profiles = profiles_figure(td)
broomstick = broomstick_figure(td)
path = well_path_figure(td)
