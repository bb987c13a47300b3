"""Calibration of the drilling system from measured data.

:mod:`.data` reads a measured time series (CSV or Parquet; the column names of ``drill``'s
``series.csv`` as they are, other names mapped by an option; units from a units row, a header
suffix or an option, converted to the model's SI units), checks it (gaps, non-monotonic time,
NaNs, missing columns) and resamples it onto the model's output times in windows. :mod:`.fit`
fits any numeric configuration values (dotted paths) to it by weighted least squares: a global
quasi-random stage solved in parallel threads, a ``scipy.optimize.least_squares`` refinement,
confidence intervals from the Jacobian (profile likelihood where it is ill-conditioned), the
misfit landscape over each pair of parameters. :mod:`.output` writes a fit's folder
(``drillstring fit --out DIR``).
"""
