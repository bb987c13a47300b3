"""The paper's model: three modes of the aluminium string

Table 1 of the paper (100 m aluminium string, Ω = π rad/s) with the three-mode initial
condition C = (0.1, 0.05, 0.02) rad/s: the Galerkin model integrated by DOP853 over one second,
the twist at the paper's section z_k = 2l/3 and its phase portrait. The energy of the
conservative model is kept to the solver's tolerance.
"""

import drillstring as ds

params = ds.preset("aluminum")
res = ds.simulate(params, modes=3, t_end=1.0)
print(f"max |theta(z_k)| = {abs(res.theta(2 * params.length / 3)).max():.3e} rad, "
      f"energy drift {res.energy_drift():.1e}")
fig = ds.plots.time_history_and_phase(res)
