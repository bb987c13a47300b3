"""The optional outputs and the extras of the package that bring their modules
(``[project.optional-dependencies]`` of ``pyproject.toml``): each extra's modules, written once."""

from __future__ import annotations

import importlib

from ..errors import MissingExtraError

__all__ = ["EXTRAS", "require"]

#: Each extra of an optional output -> the modules it brings (the distributions of the same names).
EXTRAS: dict[str, tuple[str, ...]] = {
    # TrajectoryResult.to_xarray / save, `simulate --out run.nc` (h5netcdf 1.8 leaves its HDF5
    # backend, h5py, to an extra of its own)
    "netcdf": ("xarray", "h5netcdf", "h5py"),
    "las": ("lasio",),  # LAS 2.0 rig logs of `drillstring rig-log` (calibration/rig_log.py)
    "live": ("aiohttp",),  # the display of `drillstring live` (live/server.py)
}


def require(extra: str, purpose: str) -> None:
    """Checks that the modules of ``extra`` import; else raises :class:`MissingExtraError`
    naming the extra and ``purpose`` (what was asked for: ``"writing netCDF"``)."""
    missing = []
    for module in EXTRAS[extra]:
        try:
            importlib.import_module(module)
        except ImportError:
            missing.append(module)
    if missing:
        raise MissingExtraError(extra, purpose, tuple(missing))
