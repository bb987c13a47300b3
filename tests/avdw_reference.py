"""Reference numbers from Aarsnes & van de Wouw's (2019) coupled axial-torsional code, run in GNU Octave.

Produced from their published MATLAB code (see tests/reference/aarsnes-van-de-wouw-2019/README.md).

    from avdw_reference import reference, parameters, window, full, stability
    ref = reference()                     # reference.json: per case scheme constants and metrics
    par = parameters()                    # parameters.json: the SI parameters of Coupled/parameters.m
    w = window("rpm30_rop30")             # dict of arrays, every 0.003 s step of the 20..25 s window
    w = window("rpm30_rop30", long=True)  # the 115..120 s window of the 120 s run
    f = full("rpm30_rop30")               # the whole run, every 10th (120 s run: 50th) step
    s = stability()                       # the torsional stability map and the dimensional loop gains
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parent / "reference" / "aarsnes-van-de-wouw-2019"
CASES = ("rpm30_rop30", "rpm30_rop60", "rpm60_rop30", "rpm60_rop60", "rpm120_rop30", "rpm120_rop60")
LONG_CASES = ("rpm30_rop30", "rpm30_rop60")  # also run to 120 s


def reference() -> dict:
    """reference.json as a dict."""
    return json.loads((DATA / "reference.json").read_text())


def parameters() -> dict:
    """parameters.json as a dict."""
    return json.loads((DATA / "parameters.json").read_text())


@lru_cache(maxsize=1)
def _npz() -> dict[str, np.ndarray]:
    with np.load(DATA / "reference.npz") as z:
        return {k: z[k] for k in z.files}


def _group(prefix: str) -> dict[str, np.ndarray]:
    out = {k[len(prefix):]: v for k, v in _npz().items() if k.startswith(prefix)}
    if not out:
        raise KeyError(f"no stored series under {prefix!r}")
    return out


def window(case: str, long: bool = False) -> dict[str, np.ndarray]:
    """Series of the metrics window of ``case`` (float64 copies of the stored float32), keyed by column."""
    return {k: v.astype(np.float64) for k, v in _group(f"{'long_' if long else ''}{case}.window.").items()}


def full(case: str, long: bool = False) -> dict[str, np.ndarray]:
    """Decimated series of the whole run of ``case``."""
    return {k: v.astype(np.float64) for k, v in _group(f"{'long_' if long else ''}{case}.full.").items()}


def final_cut_surface(case: str, long: bool = False) -> np.ndarray:
    """The cut-surface state l (Pl values, m per blade) at the end of the run."""
    return _npz()[f"{'long_' if long else ''}{case}.final_cut_surface_m"]


def stability() -> dict[str, np.ndarray]:
    """``nondim.V0``, ``nondim.Om``, ``nondim.Z`` (rows V0, columns Om), ``nondim.OmLine``;
    ``dimensional.rop30.rpm``, ``dimensional.rop30.MT_2k``, ... (see reference.json ``stability``)."""
    return _group("stability.")
