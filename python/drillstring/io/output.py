"""Every output file of drillstring goes through this module: what happens to whatever is at the path.

Each writer renders into a temporary file (:func:`atomic_path`, :func:`atomic_write`,
:func:`write_bytes`, :func:`write_text`), which is then *delivered* to the destination:

* a new path or a regular file: the temporary file lies beside the target, is flushed to disk
  (``fsync``) and renamed over it (``os.replace``, atomic): an interrupted or failed write leaves
  the old file as it was and no temporary file behind. An existing file keeps its permissions;
* a symlink (also a chain of them, also a dangling one whose directory exists): the same, on the
  link's final target; the link itself stays a link, pointing where it pointed;
* a character device or a FIFO: the bytes are streamed into it (opened for writing, never
  created, truncated or renamed over); the temporary file lies in the system's temporary folder;
* ``"-"``, or any path to the file behind this process's standard output (``/dev/stdout``, or
  ``out.csv`` in ``... --out out.csv > out.csv``): the bytes are written to standard output
  (``sys.stdout.buffer``), in order with what the program prints.

Block devices, directories and sockets are refused with a :class:`~drillstring.errors.ValidationError`
naming the field, as is an existing file that is an input of the running command (the same file
under any name: a symlink or a hard link to it) declared with :func:`command_inputs`, and a
regular file reached only through a link to an open descriptor (``/dev/fd/3``: no path to rename over).
:func:`check_destination` makes the same checks, and checks that the directory is writable, before
any work is done. An ``OSError`` of the write itself (disk full, a closed pipe) is re-raised as
:class:`OutputError`, which names the path the caller gave, never the temporary file.

The temporary name keeps the target's extension (or ``suffix``), so writers that infer a format
from it (matplotlib's ``savefig``) or append one (``numpy.savez``) behave as on the target.

An output *folder* (``drill``, ``fit``, ``torque-drag``, ``paper``, ``drill-map``'s tables and
figures) is replaced as a whole (:func:`replaced_folder`): the command writes its complete new
set into a hidden folder beside the target and swaps it in at the end, so that an interruption
(``kill -9``, Ctrl-C, a full disk) at any moment leaves the complete old set or the complete new
one, never a mix.
"""

from __future__ import annotations

import errno
import os
import re
import secrets
import shutil
import signal
import stat
import sys
import tempfile
import threading
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any, Callable, Optional, Union

from ..errors import ValidationError

__all__ = [
    "ASIDE_TAG",
    "BUSY_FOLDER",
    "STAGE_TAG",
    "STDOUT",
    "FolderWrite",
    "OutputError",
    "atomic_path",
    "atomic_write",
    "LOCK",
    "check_destination",
    "check_directory_name",
    "command_inputs",
    "folder_owners",
    "is_path",
    "is_stdout",
    "is_stream",
    "lock_directory",
    "make_directory",
    "read_regular",
    "recover_folder",
    "refuse_foreign_folder",
    "remove_leftovers",
    "replaced_folder",
    "sigint_deferred",
    "unlock_directory",
    "write_bytes",
    "write_text",
    "write_to",
    "writing_folder",
]

PathLike = Union[str, "os.PathLike[str]"]

#: The path that means standard output.
STDOUT = "-"

#: The lock file of an output directory (see :func:`lock_directory`).
LOCK = ".lock"

#: What an output directory may be named (the ``allowed`` text of a refused one).
ALLOWED_DIRECTORY = "a directory path (not empty, and not '-': standard output is not a directory)"

#: What a file destination may be (the ``allowed`` text of a refused one).
ALLOWED_FILE = "a new or regular file (or a symlink to one), a character device, a FIFO or '-' for standard output"

_CHUNK = 1 << 16

#: The errors of a write for want of room: a full disk, a full quota, a read-only file system.
_NO_ROOM = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EIO})


class OutputError(OSError):
    """Writing an output failed (disk full, a closed pipe, a permission error ...).

    ``filename`` is the path as the caller gave it; ``errno`` and ``strerror`` are those of the
    underlying error, which is chained as ``__cause__``.
    """

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"


def is_path(target: Any) -> bool:
    """Whether ``target`` names a file (rather than being an open file object)."""
    return isinstance(target, (str, bytes, os.PathLike))


# --------------------------------------------------------------------------- inputs of the command

_inputs: tuple[str, ...] = ()


@contextmanager
def command_inputs(*paths: Optional[PathLike]) -> Iterator[None]:
    """Declares the input files of the running command (``None`` entries are ignored): inside the
    ``with`` block no output may be written over any of them (:func:`check_destination` and every
    writer refuse it, comparing device and inode, so a symlink or a hard link is caught too)."""
    global _inputs
    saved = _inputs
    _inputs = saved + tuple(os.fsdecode(os.fspath(p)) for p in paths if p is not None)
    try:
        yield
    finally:
        _inputs = saved


# --------------------------------------------------------------------------- classification


@dataclass(frozen=True)
class _Target:
    display: str
    """The path as the caller gave it (what messages name)."""
    real: str
    """The resolved path (symlinks followed); empty for standard output."""
    kind: str
    """``"file"`` (regular or new: rename), ``"stream"`` (character device or FIFO) or ``"stdout"``."""
    mode: Optional[int]
    """Permission bits of an existing regular file."""


def _kind_name(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def _stdout_stat() -> Optional[os.stat_result]:
    """The file behind the process's standard output, if it has a descriptor."""
    try:
        return os.fstat(sys.stdout.fileno()) if sys.stdout is not None else None
    except (OSError, AttributeError, ValueError):  # no descriptor (a test's capture), or closed
        return None


def _resolve(path: PathLike, field: str) -> _Target:
    """Where an output to ``path`` goes and how it is delivered; refuses what may not be written.

    The kind comes from ``os.stat`` of the path as given (every link followed, also the
    ``/proc/self/fd`` links behind ``/dev/stdout``): the file this process's standard output
    writes to is written through standard output; a character device or FIFO is opened by the
    given path; a regular file is renamed over at its resolved path, which must be that same
    file (ordinary symlinks, not a link to an open descriptor)."""
    display = os.fsdecode(os.fspath(path))
    if display == STDOUT:
        return _Target(display, "", "stdout", None)
    if not display:
        raise ValidationError(field, display, ALLOWED_FILE)
    try:
        st: Optional[os.stat_result] = os.stat(display)
    except FileNotFoundError:  # a new file, or a dangling symlink: created at its target
        st = None
    except OSError as exc:  # a symlink loop, a path through a regular file, ...
        raise ValidationError(field, display, f"{ALLOWED_FILE} ({exc.strerror})") from exc
    if st is not None:
        for source in _inputs:
            try:
                same = os.path.samestat(st, os.stat(source))
            except OSError:
                continue
            if same:
                raise ValidationError(
                    field, display, f"a path other than {source}, an input of this command (it would be overwritten)"
                )
        stdout = _stdout_stat()
        if stdout is not None and os.path.samestat(st, stdout):
            return _Target(display, "", "stdout", None)
        if stat.S_ISCHR(st.st_mode) or stat.S_ISFIFO(st.st_mode):
            return _Target(display, display, "stream", None)
        if not stat.S_ISREG(st.st_mode):
            raise ValidationError(field, display, f"{ALLOWED_FILE}, not {_kind_name(st.st_mode)}")
    real = os.path.realpath(display)
    if st is not None:
        try:
            same = os.path.samestat(st, os.stat(real))
        except OSError:
            same = False
        if not same:  # e.g. /dev/fd/3 to an open file: no path to rename over
            raise ValidationError(field, display, f"{ALLOWED_FILE}, reached through ordinary symlinks")
    return _Target(display, real, "file", stat.S_IMODE(st.st_mode) if st is not None else None)


def is_stdout(path: Any) -> bool:
    """Whether output to ``path`` goes to this process's standard output: ``"-"``, or a path
    to the same file (``/dev/stdout``, the file stdout is redirected to)."""
    if not is_path(path):
        return False
    try:
        return _resolve(path, "path").kind == "stdout"
    except ValidationError:
        return False


def is_stream(path: Any) -> bool:
    """Whether output to ``path`` is streamed rather than renamed into place (``"-"``, standard
    output, a character device or a FIFO, symlinks followed): no extension is appended to it."""
    if not is_path(path):
        return False
    try:
        return _resolve(path, "path").kind != "file"
    except ValidationError:
        return False


def _writable_directory(directory: str) -> Optional[str]:
    """Why files cannot be created in ``directory`` (``None`` when they can)."""
    try:
        st = os.stat(directory)
    except OSError as exc:
        return f"{directory}: {exc.strerror}"
    if not stat.S_ISDIR(st.st_mode):
        return f"{directory} is not a directory"
    if not os.access(directory, os.W_OK | os.X_OK):
        return f"{directory} is not writable"
    return None


def check_destination(
    path: PathLike, *, field: str = "path", directory: bool = False, files: Sequence[str] = ()
) -> None:
    """Checks, before any work is done, that an output can be written to ``path``.

    A file destination must be allowed (see the module docstring: not a directory, block device
    or socket, not an input of the command) and, unless it is streamed, lie in an existing,
    writable directory; ``"-"`` needs an open standard output. With ``directory=True``, ``path``
    is an output directory: it must be a writable directory or, if absent, creatable (its
    nearest existing ancestor a writable directory); the existing entries named in ``files``
    (the files the command will write into it) are checked as file destinations.

    Raises :class:`~drillstring.errors.ValidationError` naming ``field`` and ``path`` as given.
    """
    display = os.fsdecode(os.fspath(path))
    if directory:
        check_directory_name(display, field)
        real = os.path.realpath(display)
        probe = real
        while not os.path.lexists(probe) and os.path.dirname(probe) != probe:
            probe = os.path.dirname(probe)
        problem = _writable_directory(probe)
        if problem is not None:
            what = "a writable directory" if probe == real else "a directory that can be created"
            raise ValidationError(field, display, f"{what} ({problem})")
        if probe == real:
            for name in files:
                check_destination(os.path.join(display, name), field=field)
        return
    target = _resolve(display, field)
    if target.kind == "stdout" and sys.stdout is None:
        raise ValidationError(field, display, "an open standard output (it is closed)")
    if target.kind == "stream" and not os.access(target.real, os.W_OK):
        raise ValidationError(field, display, "a writable character device or FIFO (access denied)")
    if target.kind == "file":
        problem = _writable_directory(os.path.dirname(target.real))
        if problem is not None:
            raise ValidationError(field, display, f"a file in an existing, writable directory ({problem})")


def check_directory_name(path: PathLike, field: str) -> None:
    """Refuses (:class:`~drillstring.errors.ValidationError` naming ``field``) an output directory
    named ``""`` (it would be the current folder) or ``"-"`` (standard output, not a folder)."""
    display = os.fsdecode(os.fspath(path))
    if not display or display == STDOUT:
        raise ValidationError(field, display, ALLOWED_DIRECTORY)


def make_directory(path: PathLike) -> Path:
    """Creates the output directory ``path`` (and its parents) unless it exists; a symlink to a
    directory is used as it is, a dangling one gets its target created. Returns ``path``; a
    failure raises :class:`OutputError` naming ``path`` as given; an empty path or ``"-"`` a
    :class:`~drillstring.errors.ValidationError` (:func:`check_directory_name`)."""
    display = os.fsdecode(os.fspath(path))
    check_directory_name(display, "path")
    try:
        os.makedirs(os.path.realpath(display), exist_ok=True)
    except OSError as exc:
        raise _output_error(exc, display) from exc
    return Path(display)


# --------------------------------------------------------------------------- writing


def _fsync_directory(directory: str) -> None:
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _copy_into_fd(source: str, fd: int) -> None:
    with open(source, "rb") as handle:
        while True:
            chunk = handle.read(_CHUNK)
            if not chunk:
                return
            view = memoryview(chunk)
            while view:
                view = view[os.write(fd, view):]


def _deliver(tmp: str, target: _Target) -> None:
    """Moves the finished temporary file to the destination (see the module docstring)."""
    if target.kind == "file":
        with open(tmp, "rb") as handle:
            os.fsync(handle.fileno())
        if target.mode is not None:
            os.chmod(tmp, target.mode)
        os.replace(tmp, target.real)
        _fsync_directory(os.path.dirname(target.real))
    elif target.kind == "stream":
        # no O_CREAT / O_TRUNC: a device or FIFO is written to, never replaced or created
        fd = os.open(target.real, os.O_WRONLY | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0))
        try:
            mode = os.fstat(fd).st_mode
            if not (stat.S_ISCHR(mode) or stat.S_ISFIFO(mode)):  # replaced since it was checked
                raise OSError(errno.EEXIST, "no longer a character device or FIFO")
            _copy_into_fd(tmp, fd)
        finally:
            os.close(fd)
    else:
        stream = sys.stdout
        if stream is None:
            raise OSError(errno.EBADF, "standard output is closed")
        buffer = getattr(stream, "buffer", None)
        if buffer is None:
            raise OSError(errno.EINVAL, "standard output does not accept bytes")
        stream.flush()
        with open(tmp, "rb") as handle:
            shutil.copyfileobj(handle, buffer, _CHUNK)
        buffer.flush()


def _output_error(exc: OSError, display: str) -> OutputError:
    code = exc.errno if exc.errno is not None else errno.EIO
    reason = exc.strerror or str(exc) or type(exc).__name__
    name = "standard output" if display == STDOUT else display
    return OutputError(code, reason, name)


@contextmanager
def atomic_path(path: PathLike, *, field: str = "path", suffix: Optional[str] = None) -> Iterator[str]:
    """Yields a temporary path to write the output into; on a normal exit it is delivered to
    ``path`` (renamed over a regular file, streamed into a device, FIFO or ``"-"``), on an
    exception it is removed and ``path`` is untouched.

    ``suffix`` is the temporary file's extension (default: that of ``path``). Refused
    destinations raise :class:`~drillstring.errors.ValidationError` naming ``field``; an
    ``OSError`` of the body or the delivery becomes :class:`OutputError` naming ``path``.
    """
    target = _resolve(path, field)
    extension = os.path.splitext(target.display)[1] if suffix is None else suffix
    scratch: Optional[str] = None
    if target.kind == "file":
        directory, name = os.path.split(target.real)
        tmp = os.path.join(directory, f".{name}.{secrets.token_hex(6)}.tmp{extension}")
    else:
        scratch = tempfile.mkdtemp(prefix="drillstring-")
        tmp = os.path.join(scratch, f"output{extension}")
    try:
        try:
            yield tmp
            _deliver(tmp, target)
        except OSError as exc:
            if isinstance(exc, OutputError):
                raise
            raise _output_error(exc, target.display) from exc
    finally:
        try:
            os.remove(tmp)
        except OSError:
            pass
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)


def atomic_write(
    path: PathLike, writer: Callable[[str], Any], *, field: str = "path", suffix: Optional[str] = None
) -> Path:
    """Calls ``writer(tmp)`` with a temporary path (a string) and delivers what it wrote to
    ``path`` (see :func:`atomic_path`); returns ``path`` as a :class:`~pathlib.Path`."""
    with atomic_path(path, field=field, suffix=suffix) as tmp:
        writer(tmp)
    return Path(os.fsdecode(os.fspath(path)))


def write_bytes(path: PathLike, data: bytes, *, field: str = "path") -> Path:
    """Writes ``data`` to ``path`` (see :func:`atomic_path`); returns ``path`` as a Path."""

    def writer(tmp: str) -> None:
        with open(tmp, "wb") as handle:
            handle.write(data)

    return atomic_write(path, writer, field=field)


def write_text(path: PathLike, text: str, *, field: str = "path", encoding: str = "utf-8") -> Path:
    """Writes ``text`` to ``path`` in ``encoding`` (see :func:`atomic_path`); returns ``path``."""
    return write_bytes(path, text.encode(encoding), field=field)


def write_to(
    target: Any, writer: Callable[[Any], Any], *, field: str = "path", suffix: Optional[str] = None
) -> Optional[Path]:
    """:func:`atomic_write` for a path; an open file object is passed to ``writer`` directly
    (and ``None`` is returned)."""
    if not is_path(target):
        writer(target)
        return None
    return atomic_write(target, writer, field=field, suffix=suffix)


# --------------------------------------------------------------------------- reading what a command wrote


def read_regular(path: PathLike) -> bytes:
    """The bytes of the regular file ``path`` (symlinks followed). Anything else (a FIFO, a
    device, a directory) raises ``OSError`` without blocking: it is opened non-blocking and
    checked before it is read."""
    fd = os.open(os.fspath(path), os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = "a FIFO" if stat.S_ISFIFO(mode) else _kind_name(mode)
            raise OSError(errno.EINVAL, f"not a regular file ({kind})", os.fsdecode(os.fspath(path)))
        with os.fdopen(fd, "rb", closefd=False) as handle:
            return handle.read()
    finally:
        os.close(fd)


# --------------------------------------------------------------------------- output directories

#: The format of a ``drill-map`` store's manifest (its ``"format"`` entry); any other manifest
#: is a ``sweep``'s.
MAP_FORMAT = "drillstring-drill-map-1"

#: The files that show which command wrote an output directory (command -> names).
FOLDER_SIGNS: dict[str, tuple[str, ...]] = {
    "drill": ("series.parquet", "series.csv", "metrics.json", "fields.npz"),
    "drill-map": ("map.parquet", "map.csv"),
    "sweep": ("results.parquet", "results.csv"),
    "torque-drag": ("torque_drag.json", "broomstick.csv"),
    "fit": ("fit.json",),
    "rig-log": ("states.csv", "events.csv"),
}


def folder_owners(path: PathLike) -> dict[str, list[str]]:
    """The commands whose output the directory ``path`` holds, each with the entries that show
    it (:data:`FOLDER_SIGNS`; a ``manifest.json`` is a ``drill-map``'s when its format is
    :data:`MAP_FORMAT`, else a ``sweep``'s). Empty for a missing or empty directory."""
    display = os.fsdecode(os.fspath(path))
    owners: dict[str, list[str]] = {}
    if not os.path.isdir(display):
        return owners
    for command, names in FOLDER_SIGNS.items():
        for name in names:
            if os.path.lexists(os.path.join(display, name)):
                owners.setdefault(command, []).append(name)
    manifest = os.path.join(display, "manifest.json")
    if os.path.lexists(manifest):
        try:
            import json

            document = json.loads(read_regular(manifest))
        except (OSError, ValueError, RecursionError):
            document = None
        command = "drill-map" if isinstance(document, dict) and document.get("format") == MAP_FORMAT else "sweep"
        owners.setdefault(command, []).append("manifest.json")
    return owners


def refuse_foreign_folder(path: PathLike, command: str, *, field: str) -> None:
    """Refuses (:class:`~drillstring.errors.ValidationError` naming ``field`` and the folder) an
    output directory holding another command's output (:func:`folder_owners`): writing there
    would put this command's files beside the other run's results."""
    display = os.fsdecode(os.fspath(path))
    for other, names in folder_owners(display).items():
        if other != command:
            raise ValidationError(
                field, display, f"a folder for the output of drillstring {command}; it holds the output of "
                f"drillstring {other} ({', '.join(names)}): choose another output directory",
            )


def lock_directory(directory: PathLike, *, field: str, busy: str) -> IO[str]:
    """Takes the exclusive lock of the output directory ``directory`` (POSIX ``flock`` on its
    :data:`LOCK` file, created if needed, released by the system when the process ends, even on
    ``kill -9``) and writes the holder (process, host, time) into it; returns the open lock file
    (close it, or :func:`unlock_directory`, to release).

    A directory locked by another process (or by another open of this one) is refused with a
    :class:`~drillstring.errors.ValidationError` naming ``field`` and the directory; ``busy`` is the
    text of its ``allowed`` part, with ``{holder}`` and ``{path}`` (of the lock file) filled in. A
    lock file that is not a regular file is refused too, without blocking on it. A lock file
    that cannot be created or written for want of room (a full disk or quota, a read-only or
    failing file system) raises :class:`OutputError` naming the lock file's path, and leaves no
    lock file behind."""
    import socket
    import time

    display = os.fsdecode(os.fspath(directory))
    path = os.path.join(display, LOCK)
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0),
                         0o644)
        except OSError as exc:
            if exc.errno in _NO_ROOM:
                raise _output_error(exc, path) from exc
            raise ValidationError(field, display, f"a directory where {LOCK} can be created ({exc})") from exc
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            os.close(fd)
            kind = "a FIFO" if stat.S_ISFIFO(mode) else _kind_name(mode)
            raise ValidationError(field, display, f"a directory whose {LOCK} is a regular file (it is {kind})")
        handle = os.fdopen(fd, "r+", encoding="utf-8")
        try:
            import fcntl
        except ImportError:  # pragma: no cover - Windows: no advisory locks, one writer is on the user
            return handle
        try:
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            holder = handle.read().strip() or "another process"
            handle.close()
            raise ValidationError(field, display, busy.format(holder=holder, path=path)) from exc
        try:  # the holder before us may have removed the file after we opened it: lock the file at the path
            same = os.path.samestat(os.fstat(handle.fileno()), os.stat(path))
        except OSError:
            same = False
        if same:
            break
        handle.close()
    holder = f"process {os.getpid()} on {socket.gethostname()} since {time.strftime('%Y-%m-%d %H:%M:%S')}\n"
    try:  # unbuffered, so that a full disk is seen here and not when the handle is closed
        os.ftruncate(fd, 0)
        data = memoryview(holder.encode("utf-8"))
        while data:
            data = data[os.write(fd, data):]
    except OSError as exc:
        try:  # we hold it: no empty lock file left behind
            os.unlink(path)
        except OSError:
            pass
        handle.close()
        raise _output_error(exc, path) from exc
    return handle


def unlock_directory(handle: IO[str], directory: PathLike) -> None:
    """Removes the :data:`LOCK` file of ``directory`` (while still holding it, and only if it is
    the file ``handle`` holds: a folder replaced meanwhile has a lock file of its own) and
    releases the lock taken by :func:`lock_directory`."""
    path = os.path.join(os.fsdecode(os.fspath(directory)), LOCK)
    try:
        if os.path.samestat(os.fstat(handle.fileno()), os.stat(path)):
            os.unlink(path)
    except (OSError, ValueError):
        pass
    finally:
        handle.close()


# --------------------------------------------------------------------------- output folders written whole

#: What the hidden folders beside an output folder ``NAME`` are called while it is replaced:
#: ``.NAME.drillstring-new-XXXXXXXXXXXX`` holds the set being written (after the swap, the old
#: set being removed); ``.NAME.drillstring-old-XXXXXXXXXXXX`` the old set moved aside where the
#: two cannot be exchanged in one step. Both are left behind only by an interrupted run, and
#: the next run into ``NAME`` removes them (or puts an old set back, see :func:`recover_folder`).
STAGE_TAG = ".drillstring-new-"
ASIDE_TAG = ".drillstring-old-"

#: The temporary files of :func:`atomic_path` (an interrupted write leaves one).
_TEMPORARY = re.compile(r"^\..+\.[0-9a-f]{12}\.tmp(\.[^.]*)?$")


def _hidden(real: str, tag: str, token: Optional[str] = None) -> str:
    parent, name = os.path.split(real)
    return os.path.join(parent, f".{name}{tag}{token or secrets.token_hex(6)}")


def _leftovers(real: str, tag: str) -> list[str]:
    """The hidden folders ``tag`` (:data:`STAGE_TAG`, :data:`ASIDE_TAG`) of the output folder at
    ``real``, newest first (real directories only, never a symlink)."""
    parent, name = os.path.split(real)
    pattern = re.compile(re.escape(f".{name}{tag}") + r"[0-9a-f]{12}$")
    found = []
    try:
        entries = list(os.scandir(parent or "."))
    except OSError:
        return []
    for entry in entries:
        if pattern.match(entry.name) and entry.is_dir(follow_symlinks=False):
            try:
                found.append((entry.stat(follow_symlinks=False).st_mtime, entry.path))
            except OSError:
                continue
    return [path for _, path in sorted(found, reverse=True)]


def recover_folder(path: PathLike) -> None:
    """Puts back the old set of the output folder ``path`` when a swap without an atomic exchange
    (see :class:`FolderWrite`) was interrupted between moving the old folder aside and moving the
    new one in: ``path`` is then missing and its old set lies in ``.NAME.drillstring-old-*``.
    Call it before the folder is created; a present ``path`` is left alone."""
    real = os.path.realpath(os.fsdecode(os.fspath(path)))
    if os.path.lexists(real):
        return
    for aside in _leftovers(real, ASIDE_TAG):
        try:
            os.rename(aside, real)
        except OSError:
            continue
        _fsync_directory(os.path.dirname(real))
        return


def _remove_tree(path: str) -> None:
    shutil.rmtree(path, ignore_errors=True)


def remove_leftovers(path: PathLike) -> None:
    """Removes the hidden folders an interrupted replacement of the output folder ``path`` left
    beside it (:data:`STAGE_TAG`, :data:`ASIDE_TAG`). Call it holding the folder's lock: no live
    run has them then."""
    real = os.path.realpath(os.fsdecode(os.fspath(path)))
    for tag in (STAGE_TAG, ASIDE_TAG):
        for leftover in _leftovers(real, tag):
            _remove_tree(leftover)


_RENAME_EXCHANGE = 2
_AT_FDCWD = -100
_renameat2: Any = None


def _exchange(a: str, b: str) -> bool:
    """Swaps the directories at ``a`` and ``b`` in one step (Linux ``renameat2`` with
    ``RENAME_EXCHANGE``); ``False`` where that is not available (another system, an old kernel
    or C library, a file system without it), an ``OSError`` if it failed otherwise."""
    global _renameat2
    if not sys.platform.startswith("linux"):
        return False
    if _renameat2 is None:
        import ctypes

        try:
            function = ctypes.CDLL(None, use_errno=True).renameat2
        except (OSError, AttributeError):
            _renameat2 = False
            return False
        function.argtypes = (ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint)
        function.restype = ctypes.c_int
        _renameat2 = function
    if _renameat2 is False:
        return False
    import ctypes

    if _renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), b)


def _link_or_copy(source: str, target: str) -> None:
    """``target`` as a hard link to ``source`` (a symlink itself, not followed), or a copy where
    no link can be made."""
    try:
        try:
            os.link(source, target, follow_symlinks=False)
        except NotImplementedError:  # no linkat: a symlink is recreated below, a file linked
            if os.path.islink(source):
                raise OSError(errno.ENOTSUP, "cannot link a symlink", source) from None
            os.link(source, target)
    except OSError as exc:
        if exc.errno not in (errno.EXDEV, errno.EPERM, errno.EMLINK, errno.ENOTSUP, errno.EOPNOTSUPP):
            raise
        if os.path.islink(source):
            os.symlink(os.readlink(source), target)
        else:
            shutil.copy2(source, target, follow_symlinks=False)


@contextmanager
def sigint_deferred() -> Iterator[None]:
    """Holds back SIGINT (Ctrl-C) for the body: a signal received meanwhile is handed to the
    previous handler (normally raising KeyboardInterrupt) when the body ends. Only the main
    thread can change handlers; elsewhere, or when the handler is not a Python callable, the body
    runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.getsignal(signal.SIGINT)
    if not callable(previous):
        yield
        return
    received: list[tuple[int, Any]] = []
    signal.signal(signal.SIGINT, lambda signum, frame: received.append((signum, frame)))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if received:
            previous(*received[0])


class FolderWrite:
    """The replacement of one output folder by a new set of files (see :func:`replaced_folder`).

    ``path`` is the folder as the caller named it; ``directory`` is where the new files are
    written: a fresh hidden folder beside the target (``.NAME.drillstring-new-*``, in the same
    parent directory, so on the same file system), or the folder itself where it cannot be
    swapped (a mount point, or a folder whose parent directory may not be written: ``in_place``;
    the command's files are then replaced one by one). :meth:`shown` turns a path written into ``directory``
    into the path the user sees, :meth:`commit` swaps the new set in, :meth:`discard` drops it.
    """

    def __init__(self, path: PathLike, owned: Callable[[str], bool]) -> None:
        self.path = Path(os.fsdecode(os.fspath(path)))
        self.real = os.path.realpath(os.fspath(self.path))
        self.owned = owned
        self.in_place = os.path.ismount(self.real)
        self.directory = self.path
        self._stage = os.fspath(self.path)
        if self.in_place:
            return
        stage = _hidden(self.real, STAGE_TAG)
        try:
            os.mkdir(stage, 0o700)  # private while written; given the old folder's mode at the swap
        except OSError as exc:
            if exc.errno in (errno.EACCES, errno.EPERM):  # a parent we may not write: in place
                self.in_place = True
                return
            raise _output_error(exc, os.fspath(self.path)) from exc
        self.directory = Path(stage)
        self._stage = stage

    def shown(self, written: PathLike) -> Path:
        """``written`` (a path in :attr:`directory`) as the user sees it: in :attr:`path`."""
        text = os.fsdecode(os.fspath(written))
        base = self._stage
        if text == base or text.startswith(base + os.sep):
            return Path(os.fspath(self.path) + text[len(base):])
        return Path(text)

    def error(self, exc: OSError) -> OutputError:
        """``exc`` as an :class:`OutputError` naming the user's path, never the hidden folder."""
        name = exc.filename if isinstance(exc.filename, str) else os.fspath(self.path)
        shown = os.fspath(self.shown(name))
        if self._stage in shown:
            shown = os.fspath(self.path)
        code = exc.errno if exc.errno is not None else errno.EIO
        return OutputError(code, exc.strerror or str(exc) or type(exc).__name__, shown)

    def _through(self) -> None:
        """The old folder's entries the new set replaces keep what they are, as a single file's
        output does (see the module docstring): a regular file its permissions; a symlink (to a
        file elsewhere), a FIFO or a character device stays in the folder and gets the new
        bytes written through it (those files outside the folder are written at the swap,
        before the exchange, each atomically)."""
        stage = os.fspath(self.directory)
        for name in os.listdir(stage):
            old = os.path.join(self.real, name)
            try:
                st = os.lstat(old)
            except FileNotFoundError:
                continue
            new = os.path.join(stage, name)
            if stat.S_ISDIR(st.st_mode) or os.path.isdir(new):
                continue
            if stat.S_ISREG(st.st_mode):
                if stat.S_IMODE(st.st_mode) != stat.S_IMODE(os.stat(new).st_mode):
                    os.chmod(new, stat.S_IMODE(st.st_mode))
                continue
            with atomic_path(old, field="path") as tmp:
                shutil.copyfile(new, tmp)
            os.unlink(new)
            _link_or_copy(old, new)

    def _carry(self) -> None:
        """Hard links (copies across file systems) into the new folder every entry of the old one
        that is not the command's (:attr:`owned`), the lock file or a leftover temporary file:
        what the user keeps in the folder stays there."""
        stage = os.fspath(self.directory)
        try:
            entries = list(os.scandir(self.real))
        except FileNotFoundError:
            return
        for entry in entries:
            name = entry.name
            if self.owned(name) or name == LOCK or _TEMPORARY.match(name):
                continue
            target = os.path.join(stage, name)
            if os.path.lexists(target):  # written by the command under a name it does not own
                continue
            if entry.is_dir(follow_symlinks=False):
                shutil.copytree(entry.path, target, symlinks=True, copy_function=_link_or_copy)
                for folder, _, _ in os.walk(target):
                    _fsync_directory(folder)
            else:
                _link_or_copy(entry.path, target)

    def commit(self, lock_field: str) -> None:
        """Swaps the new set in: the old folder's other entries are carried over, the new folder
        takes the old one's permissions and a lock of its own (so that the folder's
        :data:`LOCK` is held throughout), is flushed to disk, exchanged with the old folder in one
        step (or, where that is not available, the old folder is renamed aside and the new one
        into place), the parent directory is flushed and the old set removed. Ctrl-C is held
        back from the permissions to the exchange. An exception before the exchange leaves the old
        folder as it was."""
        if self.in_place:
            return
        stage = os.fspath(self.directory)
        self._through()
        self._carry()
        with sigint_deferred():
            try:
                st = os.stat(self.real)
                os.chmod(stage, stat.S_IMODE(st.st_mode))
                if hasattr(os, "chown"):
                    try:
                        os.chown(stage, st.st_uid, st.st_gid)
                    except OSError:
                        pass
            except FileNotFoundError:
                os.chmod(stage, 0o777 & ~_umask())
            lock = lock_directory(stage, field=lock_field, busy="{holder}")
            try:
                _fsync_directory(stage)
                parent = os.path.dirname(self.real)
                if os.path.lexists(self.real):
                    if not _exchange(stage, self.real):
                        aside = _hidden(self.real, ASIDE_TAG, os.path.basename(stage)[-12:])
                        os.rename(self.real, aside)
                        try:
                            os.rename(stage, self.real)
                        except OSError:
                            os.rename(aside, self.real)
                            raise
                        stage = aside
                else:
                    os.rename(stage, self.real)
                    stage = ""
                _fsync_directory(parent)
            except BaseException:
                lock.close()
                raise
            self.directory = self.path
            if stage:
                self._follow_cwd(stage)
            unlock_directory(lock, self.path)
        if stage:
            _remove_tree(stage)  # the old set (holding the old lock file, still held by the caller)

    def _follow_cwd(self, moved: str) -> None:
        """A process whose working directory was the old folder (or inside it), now at ``moved``,
        moves into the new folder at the old path: relative paths keep meaning what they meant."""
        try:
            here = os.getcwd()
        except OSError:
            return
        if here != moved and not here.startswith(moved + os.sep):
            return
        for place in (self.real + here[len(moved):], self.real):
            try:
                os.chdir(place)
                return
            except OSError:
                continue

    def discard(self) -> None:
        """Drops the new set: the old folder stays as it was."""
        if not self.in_place and os.fspath(self.directory) != os.fspath(self.path):
            _remove_tree(os.fspath(self.directory))


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def replaced_folder(path: PathLike, *, owned: Callable[[str], bool], field: str = "path") -> Iterator[FolderWrite]:
    """The output folder ``path`` replaced as a whole by what the ``with`` block writes into the
    yielded :class:`FolderWrite`'s ``directory``: on a normal exit the new set is swapped in
    (:meth:`FolderWrite.commit`), on an exception it is dropped and ``path`` keeps its old set.
    Hold the folder's lock (:func:`lock_directory`) around it. ``owned`` tells the names of the
    command's own files: the old folder's other entries are kept. An ``OSError`` becomes an
    :class:`OutputError` naming the user's path (never the hidden folder)."""
    folder = FolderWrite(path, owned)
    try:
        try:
            yield folder
            folder.commit(field)
        except OSError as exc:
            if isinstance(exc, OutputError) and os.fspath(folder.directory) not in os.fsdecode(exc.filename or ""):
                raise
            raise folder.error(exc) from exc
    finally:
        folder.discard()


#: The ``allowed`` text of an output folder another run is writing to (see :func:`lock_directory`).
BUSY_FOLDER = ("a folder no other run is writing to: it is locked by {holder} ({path}); wait for that run to "
               "finish or choose another output directory")


@contextmanager
def writing_folder(path: PathLike, *, field: str, owned: Callable[[str], bool], command: Optional[str] = None,
                   busy: str = BUSY_FOLDER) -> Iterator[FolderWrite]:
    """An output folder written whole, for the ``with`` block: an old set moved aside by an
    interrupted swap is put back (:func:`recover_folder`), the folder is created if needed and
    locked (:func:`lock_directory`, ``busy`` its refusal), with ``command`` another command's
    output in it is refused (:func:`refuse_foreign_folder`, also once locked), what an
    interrupted run left beside it is removed (:func:`remove_leftovers`) and the new set is
    written and swapped in (:func:`replaced_folder`, ``owned`` the command's own names). At the
    end the lock is released and its file removed, as is the folder if it was created here and
    is still empty. Check the destination first (:func:`check_destination`)."""
    display = os.fsdecode(os.fspath(path))
    check_directory_name(display, field)
    recover_folder(display)
    if command is not None:
        refuse_foreign_folder(display, command, field=field)
    key = os.path.realpath(display)
    created = not os.path.isdir(key)
    directory = make_directory(display)
    try:
        lock = lock_directory(directory, field=field, busy=busy)
        try:
            if command is not None:
                refuse_foreign_folder(display, command, field=field)  # written by another command meanwhile
            remove_leftovers(display)  # of an interrupted run (we hold the lock: no live run has them)
            with replaced_folder(display, owned=owned, field=field) as folder:
                yield folder
        finally:
            unlock_directory(lock, directory)
    finally:
        if created:
            try:
                os.rmdir(key)  # only if empty
            except OSError:
                pass
