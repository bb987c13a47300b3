"""Chunked, resumable, atomic storage of a sweep's results in a directory.

Layout of ``DIR``::

    manifest.json              what the sweep is (fingerprint, solver options, run count, ...)
    chunks/chunk-00000.parquet one file per finished chunk of runs
    results.parquet            the whole table, in run order (written at the end)
    results.csv                the same as CSV

Every file is written to a temporary name in its final directory, flushed to disk and then
renamed over its final name (``os.replace``, atomic on POSIX and Windows), so a reader never
sees a half-written file: after an interruption a chunk file is either complete or absent.
A re-run with the same directory skips the chunks whose files exist; a different sweep (other
runs, solver options, chunking or drillstring build) is refused, since mixing chunks of two
sweeps would give a table equal to neither.
"""

from __future__ import annotations

import json
import os
import uuid
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional

from .errors import ValidationError

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["SweepStore", "MANIFEST", "RESULTS_PARQUET", "RESULTS_CSV"]

MANIFEST = "manifest.json"
RESULTS_PARQUET = "results.parquet"
RESULTS_CSV = "results.csv"
CHUNKS = "chunks"


def _atomic_write(path: Path, data: bytes) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    try:
        with open(tmp, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


class SweepStore:
    """The output directory of one sweep (see the module docstring).

    Open with :meth:`open`, which creates the directory and its manifest or checks that an
    existing manifest describes the same sweep.
    """

    def __init__(self, root: Path, manifest: dict[str, Any]) -> None:
        self.root = root
        self.manifest = manifest
        self.chunks = root / CHUNKS

    @classmethod
    def open(cls, out_dir: Any, manifest: dict[str, Any]) -> SweepStore:
        """Create ``out_dir`` for the sweep described by ``manifest`` (which must hold a
        ``"fingerprint"``), or reopen it to resume that same sweep.

        Raises
        ------
        ValidationError
            ``field="out_dir"``: the directory holds another sweep, or files that are not a
            sweep's, or cannot be created.
        """
        root = Path(os.fspath(out_dir))
        try:
            root.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ValidationError("out_dir", str(root), f"a directory that can be created ({exc})") from exc
        path = root / MANIFEST
        if path.exists():
            try:
                existing = json.loads(path.read_text(encoding="utf-8"))
            except (OSError, ValueError) as exc:
                raise ValidationError("out_dir", str(root), f"a readable {MANIFEST} ({exc})") from exc
            if existing.get("fingerprint") != manifest["fingerprint"]:
                raise ValidationError(
                    "out_dir",
                    str(root),
                    "a new directory, or one holding this same sweep to resume; it holds a different "
                    f"sweep ({_difference(existing, manifest)}). Choose another output directory or "
                    "delete this one",
                )
        else:
            strays = sorted(p.name for p in root.iterdir() if p.name in (CHUNKS, RESULTS_PARQUET, RESULTS_CSV))
            if strays:
                raise ValidationError(
                    "out_dir", str(root), f"a directory with a {MANIFEST} for its results "
                    f"(found {', '.join(strays)} without one); choose another output directory"
                )
            _atomic_write(path, (json.dumps(manifest, indent=1, sort_keys=True) + "\n").encode())
        store = cls(root, manifest)
        store.chunks.mkdir(exist_ok=True)
        for stale in store.chunks.glob(".*.tmp"):  # left by an interrupted write
            stale.unlink(missing_ok=True)
        return store

    def chunk_path(self, index: int) -> Path:
        return self.chunks / f"chunk-{index:05d}.parquet"

    def load_chunk(self, index: int, rows: int, columns: list[str]) -> Optional[pd.DataFrame]:
        """The finished chunk ``index`` if its file exists and has ``rows`` rows and exactly
        ``columns``; ``None`` otherwise (then it is recomputed and rewritten)."""
        import pandas as pd

        path = self.chunk_path(index)
        if not path.exists():
            return None
        try:
            frame = pd.read_parquet(path)
        except Exception:  # unreadable: recompute it (atomic writes make this unexpected)
            return None
        if len(frame) != rows or list(frame.columns) != columns:
            return None
        return frame

    def save_chunk(self, index: int, frame: pd.DataFrame) -> None:
        """Write chunk ``index`` atomically."""
        _atomic_write(self.chunk_path(index), frame.to_parquet())

    def save_results(self, frame: pd.DataFrame) -> tuple[Path, Path]:
        """Write ``results.parquet`` and ``results.csv`` atomically; returns their paths."""
        parquet, csv = self.root / RESULTS_PARQUET, self.root / RESULTS_CSV
        _atomic_write(parquet, frame.to_parquet())
        _atomic_write(csv, frame.to_csv(index=False).encode("utf-8"))
        return parquet, csv


def _difference(old: dict[str, Any], new: dict[str, Any]) -> str:
    """A short description of how two manifests differ."""
    keys = ("drillstring_version", "core_build", "solver", "z", "chunk_size", "runs", "velocity_columns")
    changed = [key for key in keys if old.get(key) != new.get(key)]
    if not changed:
        changed = ["the parameter sets"]
    return "changed: " + ", ".join(changed)
