"""Chunked, resumable, verified storage of a sweep's results in a directory.

Layout of ``DIR``::

    manifest.json               what the sweep is (fingerprint, solver options, run count, ...)
    .lock                       held (``flock``) by the process writing the sweep
    chunks/chunk-00000.parquet  one file per chunk of runs, written as it finishes
    chunks/chunk-00000.json     its record: the chunk's plan digest, row count, SHA-256 of the
                                parquet file, and whether every run in it finished
    results.parquet             the whole table, in run order (written at the end)
    results.csv                 the same as CSV

Guarantees
----------
* **Atomic files.** Every file is written through :mod:`drillstring.io.output`: to a temporary
  name in its final directory, flushed to disk and renamed over its final name, so a reader
  never sees a half-written file: after an interruption a chunk file is either complete or
  absent.
* **One writer.** Opening a store takes an exclusive lock on ``DIR/.lock`` (POSIX ``flock``,
  released by the system when the process ends, even on ``kill -9``). A second process that
  opens the same directory is refused with a message naming the process that holds it; only
  the holder removes temporary files left by interrupted writes.
* **Verified resume.** A re-run with the same directory reuses a chunk only if its record
  exists and matches the plan (the digest of this sweep's fingerprint, the chunk's position and
  its runs' parameters), its file has the recorded SHA-256 and row count, and its parameter
  columns equal the planned runs'. A chunk that fails any check (altered bytes, a file of
  another chunk or sweep, swapped, copied or linked) is recomputed, and the sweep says which
  and why (a :class:`ResumeWarning`). A chunk whose runs were interrupted keeps its finished
  runs; only the interrupted ones are solved again.
* **One sweep per directory.** A different sweep (other runs, solver options, chunking or
  drillstring build) is refused, since mixing chunks of two sweeps would give a table equal to
  neither.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import stat
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, Optional

from .. import _core
from ..errors import ResumeWarning, ValidationError
from .output import (
    LOCK,
    MAP_FORMAT,
    check_directory_name,
    lock_directory,
    read_regular,
    recover_folder,
    refuse_foreign_folder,
    sigint_deferred,
    write_bytes,
)
from .table import frame_to_parquet, read_parquet_frame

if TYPE_CHECKING:
    import pandas as pd

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["SweepStore", "ResumeWarning", "MANIFEST", "RESULTS_PARQUET", "RESULTS_CSV", "LOCK"]

MANIFEST = "manifest.json"
RESULTS_PARQUET = "results.parquet"
RESULTS_CSV = "results.csv"
CHUNKS = "chunks"


def _atomic_write(path: Path, data: bytes) -> None:
    write_bytes(path, data, field="out_dir")


#: Holds back Ctrl-C while a chunk and its record are written (:func:`drillstring.io.output.sigint_deferred`).
_sigint_deferred = sigint_deferred


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _lock(root: Path) -> IO[str]:
    """Takes the exclusive lock of ``root`` (see the module docstring and
    :func:`drillstring.io.output.lock_directory`); returns the open lock file."""
    return lock_directory(
        root, field="out_dir", busy="a directory no other sweep is writing to: it is locked by {holder} ({path}). "
        "Wait for that sweep to finish (then re-run to resume or reuse it) or choose another output directory",
    )


def _read(path: Path) -> bytes:
    """The bytes of a file of the store; a FIFO, device or directory in its place is refused
    (``ValidationError`` naming it) rather than read, which could block for ever (and a chunk
    recomputed over a FIFO would block writing into it)."""
    try:
        return read_regular(path)
    except OSError as exc:
        if exc.errno == errno.EINVAL:
            raise ValidationError(
                "out_dir", str(path), f"a regular file of the store ({exc.strerror}); remove it and run again",
            ) from exc
        raise


def _check_regular(path: Path) -> None:
    """Refuses (as :func:`_read`) an entry of the store at ``path`` that is not a regular file;
    a missing one is fine."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return
    if not stat.S_ISREG(mode):
        _read(path)


class SweepStore:
    """The output directory of one sweep (see the module docstring).

    Open with :meth:`open`, which creates the directory and its manifest or checks that an
    existing manifest describes the same sweep, and takes the directory's lock; :meth:`close`
    releases it (also a ``with`` block).
    """

    def __init__(self, root: Path, manifest: dict[str, Any], lock: Optional[IO[str]] = None) -> None:
        self.root = root
        self.manifest = manifest
        self.chunks = root / CHUNKS
        self._lock = lock

    @classmethod
    def open(cls, out_dir: Any, manifest: dict[str, Any]) -> SweepStore:
        """Create ``out_dir`` for the sweep described by ``manifest`` (which must hold a
        ``"fingerprint"``), or reopen it to resume that same sweep.

        Raises
        ------
        ValidationError
            ``field="out_dir"``: the directory holds another sweep, or another command's output
            (:func:`drillstring.io.output.refuse_foreign_folder`), or files that are not a sweep's,
            or an unreadable manifest, or cannot be created, or another process is
            writing to it.
        """
        check_directory_name(out_dir, "out_dir")
        root = Path(os.fspath(out_dir))
        recover_folder(root)  # a map's folder whose swap (write_map_files) was interrupted midway
        refuse_foreign_folder(root, "drill-map" if manifest.get("format") == MAP_FORMAT else "sweep", field="out_dir")
        try:
            root.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ValidationError("out_dir", str(root), f"a directory that can be created ({exc})") from exc
        lock = _lock(root)
        try:
            cls._check_manifest(root, manifest)
            store = cls(root, manifest, lock)
            store.chunks.mkdir(exist_ok=True)
            for folder in (root, store.chunks):  # temporary files of interrupted writes (we hold the lock)
                for stale in folder.glob(".*.tmp*"):
                    stale.unlink(missing_ok=True)
        except BaseException:
            lock.close()
            raise
        return store

    @staticmethod
    def _check_manifest(root: Path, manifest: dict[str, Any]) -> None:
        path = root / MANIFEST
        if not path.exists():
            strays = sorted(p.name for p in root.iterdir() if p.name in (CHUNKS, RESULTS_PARQUET, RESULTS_CSV))
            if strays:
                raise ValidationError(
                    "out_dir", str(root), f"a directory with a {MANIFEST} for its results "
                    f"(found {', '.join(strays)} without one); choose another output directory"
                )
            _atomic_write(path, (json.dumps(manifest, indent=1, sort_keys=True) + "\n").encode())
            return
        try:
            existing = json.loads(_read(path).decode("utf-8"))
        except ValidationError:
            raise
        except (OSError, ValueError, RecursionError) as exc:
            raise ValidationError("out_dir", str(root), f"a readable {MANIFEST} ({exc})") from exc
        if not isinstance(existing, dict) or not isinstance(existing.get("fingerprint"), str):
            raise ValidationError(
                "out_dir", str(root), f"a {MANIFEST} written by a drillstring sweep (a JSON object with a "
                f"fingerprint; found {type(existing).__name__}); choose another output directory"
            )
        if existing["fingerprint"] != manifest["fingerprint"]:
            raise ValidationError(
                "out_dir",
                str(root),
                "a new directory, or one holding this same sweep to resume; it holds a different "
                f"sweep ({_difference(existing, manifest)}). Choose another output directory or "
                "delete this one",
            )

    def close(self) -> None:
        """Releases the directory's lock."""
        if self._lock is not None:
            self._lock.close()
            self._lock = None

    def __enter__(self) -> SweepStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def chunk_path(self, index: int) -> Path:
        return self.chunks / f"chunk-{index:05d}.parquet"

    def record_path(self, index: int) -> Path:
        return self.chunks / f"chunk-{index:05d}.json"

    def load_chunk(
        self, index: int, plan: str, parameters: pd.DataFrame, columns: list[str]
    ) -> tuple[Optional[pd.DataFrame], Optional[str]]:
        """The stored chunk ``index`` if it passes every check of the module docstring.

        ``plan`` is the chunk's plan digest, ``parameters`` the parameter columns its rows must
        hold, ``columns`` the table's columns. Returns ``(frame, None)`` for a verified chunk,
        ``(None, None)`` when nothing is stored, ``(None, reason)`` when what is stored fails a
        check (it is then recomputed and rewritten).
        """

        path, record_path = self.chunk_path(index), self.record_path(index)
        _check_regular(path)
        _check_regular(record_path)
        if not path.exists() and not record_path.exists():
            return None, None
        try:
            record = json.loads(_read(record_path).decode("utf-8"))
        except FileNotFoundError:
            return None, "it has no record of its checksum"
        except ValidationError:
            raise
        except (OSError, ValueError, RecursionError) as exc:
            return None, f"its record is unreadable ({exc})"
        if not isinstance(record, dict):
            return None, "its record is not a chunk record"
        if record.get("plan") != plan:
            return None, "it was written for other runs (its plan differs: a file of another chunk or sweep)"
        if not path.exists():
            return None, "its file is missing"
        try:
            data = _read(path)
        except ValidationError:
            raise
        except OSError as exc:
            return None, f"its file is unreadable ({exc})"
        if _sha256(data) != record.get("sha256"):
            return None, "its bytes differ from those written (SHA-256 mismatch)"
        try:
            frame = read_parquet_frame(data)
        except Exception as exc:  # a file with the right checksum that parquet refuses: recompute
            return None, f"its file is not a readable table ({exc})"
        if len(frame) != len(parameters) or list(frame.columns) != columns or record.get("rows") != len(frame):
            return None, "its rows or columns differ from the plan"
        frame.index = parameters.index
        mine = frame[list(parameters.columns)]
        if not mine.equals(parameters):
            return None, "its parameter columns differ from the planned runs"
        return frame, None

    def save_chunk(self, index: int, plan: str, frame: pd.DataFrame, complete: bool) -> None:
        """Write chunk ``index`` and then its record, each atomically, as one unit: a Ctrl-C
        arriving in between is raised once both are written (see :func:`_sigint_deferred`)."""
        data = frame_to_parquet(frame)
        record = {"chunk": index, "plan": plan, "rows": len(frame), "sha256": _sha256(data), "complete": complete}
        text = (json.dumps(record, indent=1, sort_keys=True) + "\n").encode()
        with _sigint_deferred():
            _atomic_write(self.chunk_path(index), data)
            _atomic_write(self.record_path(index), text)

    def save_results(self, frame: pd.DataFrame) -> tuple[Path, Path]:
        """Write ``results.parquet`` and ``results.csv`` atomically; returns their paths."""
        parquet, csv = self.root / RESULTS_PARQUET, self.root / RESULTS_CSV
        _atomic_write(parquet, frame_to_parquet(frame))
        _atomic_write(csv, frame.to_csv(index=False).encode("utf-8"))
        return parquet, csv


def _difference(old: dict[str, Any], new: dict[str, Any]) -> str:
    """A short description of how two manifests differ."""
    keys = ("drillstring_version", "core_build", "solver", "z", "chunk_size", "runs", "velocity_columns")
    changed = [key for key in keys if old.get(key) != new.get(key)]
    if not changed:
        changed = ["the parameter sets"]
    return "changed: " + ", ".join(changed)


def core_build() -> str:
    """A hash of the compiled core (its file), so that chunks of another build are not mixed in."""
    path = getattr(_core, "__file__", None)
    digest = hashlib.sha256(_core.__version__.encode())
    if path and os.path.exists(path):
        with open(path, "rb") as handle:
            for block in iter(lambda: handle.read(1 << 20), b""):
                digest.update(block)
    return digest.hexdigest()[:16]
