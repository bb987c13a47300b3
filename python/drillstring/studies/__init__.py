"""Studies of the paper's model: signal analysis, linear stability, truncation convergence, parameter
sweeps and their axes, Table 2."""
