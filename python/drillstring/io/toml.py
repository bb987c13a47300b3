"""TOML files: the whole document of a file, and the line of a key (for error messages).

Used by the paper model's parameter files, the sweep and solver tables of the command line and
the drilling configuration alike; ``tomllib`` on Python >= 3.11, else ``tomli``.
"""

from __future__ import annotations

import os
import re
import sys
from typing import Any, Optional, Union

from ..errors import ValidationError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = ["load_toml", "toml_key_line", "with_toml_line"]

PathLike = Union[str, "os.PathLike[str]"]

_TABLE_HEADER = re.compile(r"^\s*\[\s*([^\[\]]+?)\s*\]\s*(#.*)?$")
_KEY = re.compile(r"""^\s*("[^"]*"|'[^']*'|[A-Za-z0-9_.-]+)\s*=""")


def toml_key_line(path: PathLike, table: str, key: str) -> Optional[int]:
    """The 1-based line of ``key = ...`` in ``[table]`` of the TOML file ``path`` (also as the
    dotted key ``table.key`` at the top level), or ``None`` (not found, unreadable)."""
    try:
        with open(path, encoding="utf-8") as handle:
            lines = handle.read().splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    current = ""
    for number, line in enumerate(lines, 1):
        header = _TABLE_HEADER.match(line)
        if header:
            current = re.sub(r"""["'\s]""", "", header.group(1))
            continue
        match = _KEY.match(line)
        if match:
            name = re.sub(r"""["'\s]""", "", match.group(1))
            if (current == table and name == key) or (current == "" and name == f"{table}.{key}"):
                return number
    return None


def with_toml_line(exc: ValidationError, path: PathLike, table: str) -> ValidationError:
    """``exc`` attributed to the file ``path`` and the line of its key in ``[table]``.

    The key is ``exc.field`` without an index suffix (``initial_velocities[1]``) and without a
    ``table.`` prefix (``solver.modes``).
    """
    source = os.fspath(path)
    key = exc.field.split("[", 1)[0]
    if key.startswith(f"{table}."):
        key = key[len(table) + 1 :]
    line = toml_key_line(source, table, key)
    return ValidationError(exc.field, exc.value, exc.allowed, source=source, line=line)


def load_toml(path: PathLike) -> dict[str, Any]:
    """Parse a whole TOML file (``tomllib`` on Python >= 3.11, else ``tomli``).

    Raises
    ------
    ValidationError
        ``field="toml"``: the file cannot be read, or is malformed; the message names the file
        and the parser's line and column. Also for what the parser cannot represent: arrays or
        inline tables nested too deeply for its recursion (``a = [[[[...``), integers beyond
        Python's 4300-digit conversion limit.
    """
    source = os.fspath(path)
    try:
        with open(source, "rb") as handle:
            return tomllib.load(handle)
    except (OSError, UnicodeDecodeError) as exc:
        raise ValidationError(
            "toml", source, f"a readable UTF-8 TOML file ({exc})", source=source
        ) from exc
    except RecursionError as exc:
        raise ValidationError(
            "toml", source, "valid TOML with arrays and inline tables nested at most a few hundred deep",
            source=source,
        ) from exc
    except ValueError as exc:  # tomllib.TOMLDecodeError, or int() of a too-long integer
        found = re.search(r"at line (\d+)", str(exc))
        line = int(found.group(1)) if found else None
        raise ValidationError("toml", source, f"valid TOML ({exc})", source=source, line=line) from exc
