"""TOML files: the whole document of a file, the line of a key (for error messages), and the
documents the package writes.

Read by ``tomllib`` (``tomli`` on Python < 3.11), the strict TOML 1.0 parser of the standard
library, for the paper model's parameter files, the sweep and solver tables of the command line
and the drilling configuration alike. A key's line and every document written come from tomlkit:
its documents keep a file's comments, order and layout, so a key's line is where the document
holds it (dotted keys, inline tables, arrays of tables, quoted keys alike) and a document edited
keeps what was not changed.
"""

from __future__ import annotations

import itertools
import os
import re
import sys
import uuid
from collections.abc import Iterator
from typing import Any, Optional, Union

import tomlkit
from tomlkit.container import Container
from tomlkit.items import AoT, Array, InlineTable, String, Table

from ..errors import ValidationError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = ["load_toml", "toml_line", "key_line", "with_toml_line", "toml_string"]

PathLike = Union[str, "os.PathLike[str]"]

#: A dotted field's parts: names and ``[index]`` (``sections[1].length``, ``well.md[2]``).
_FIELD_PART = re.compile(r"([^.\[\]]+)|\[(\d+)\]")



def toml_line(path: PathLike, field: str) -> Optional[int]:
    """The 1-based line of the TOML file ``path`` that sets the dotted ``field``
    (:func:`key_line` of its text), or ``None`` (not found, the file unreadable)."""
    try:
        with open(path, encoding="utf-8") as handle:
            return key_line(handle.read(), field)
    except (OSError, UnicodeDecodeError):
        return None


def key_line(text: str, field: str) -> Optional[int]:
    """The 1-based line of the TOML document ``text`` that sets the dotted ``field``
    (``parameters.length``, ``top_drive.controller.kp``, ``sections[1].length``, ``well.md[2]``),
    or, when the document does not set it, the line of the deepest table (or value) on its path
    that the document writes; ``None`` when there is none or ``text`` is not TOML.

    The line is where tomlkit's document of ``text`` holds the item, however it is written: a key
    of a ``[table]``, a dotted key (``controller.kp = 1`` in ``[top_drive]``), an entry of an
    inline table, a table of an array of tables, an element of a multi-line array, a quoted key.
    """
    target = tuple(int(index) if index else name for name, index in _FIELD_PART.findall(field))
    try:
        paths = [path for path, _, _, _ in _entries(tomlkit.parse(text))]
        for depth in range(len(target), 0, -1):  # the deepest part of the path the document writes
            for number, path in enumerate(paths):
                if path == target[:depth]:
                    line = _marked_line(text, number)
                    if line is not None:
                        return line
    except Exception:  # the line of an error message is best effort, never an error of its own
        return None
    return None


KeyPath = tuple[Union[str, int], ...]


def _entries(node: Any, prefix: KeyPath = ()) -> Iterator[tuple[KeyPath, Any, Union[str, int], Any]]:
    """Every item of a tomlkit document in document order, as written (not merged): its dotted
    path (names and array indices), the container or array holding it, its key there, the item."""
    if isinstance(node, (Array, AoT)):
        for index, item in enumerate(node.body if isinstance(node, AoT) else node):
            yield (*prefix, index), node, index, item
            yield from _entries(item, (*prefix, index))
        return
    if isinstance(node, (Table, InlineTable)):
        node = node.value
    if isinstance(node, Container):
        for key, item in node.body:
            if key is not None:
                yield (*prefix, key.key), node, key.key, item
                yield from _entries(item, (*prefix, key.key))


def _marked_line(text: str, number: int) -> Optional[int]:
    """The line of the ``number``-th item (:func:`_entries`) of a fresh document of ``text``: the
    item is marked (a value replaced by a unique string, a table's header given a unique comment),
    the document rendered and the mark's line counted; ``None`` for an item without a line of its
    own (a table made by dotted keys or by a subtable's header). An array of tables is at its
    first table's header."""
    document = tomlkit.parse(text)
    _, parent, key, item = next(itertools.islice(_entries(document), number, None))
    mark = f"drillstring-line-{uuid.uuid4().hex}"
    if isinstance(item, AoT):
        item = item.body[0] if item.body else None
    if item is None or (isinstance(item, Table) and item.is_super_table()):
        return None
    if isinstance(item, Table):
        item.comment(mark)
    else:
        parent[key] = mark
    rendered = document.as_string()
    at = rendered.find(mark)
    return rendered.count("\n", 0, at) + 1 if at >= 0 else None


def with_toml_line(exc: ValidationError, path: PathLike, table: str) -> ValidationError:
    """``exc`` attributed to the file ``path`` and the line of its field in ``[table]`` (the
    field ``exc.field``, with or without a ``table.`` prefix: ``length``, ``solver.modes``,
    ``initial_velocities[1]``)."""
    source = os.fspath(path)
    field = exc.field if exc.field.startswith(f"{table}.") else f"{table}.{exc.field}"
    line = toml_line(source, field)
    return ValidationError(exc.field, exc.value, exc.allowed, source=source, line=line)


def toml_string(text: str) -> String:
    """``text`` as a TOML basic string item: quotes, backslashes and every control character
    (C0, DEL and C1, which TOML refuses raw or which editors mangle) escaped; other characters
    as they are. A lone surrogate (no Unicode scalar value, so no TOML form) is refused."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise ValidationError("string", text, "text without lone surrogates (it has no TOML form)") from None
    escaped = tomlkit.string(text).as_string()[1:-1]  # C0 and DEL escaped by tomlkit
    escaped = re.sub("[\x80-\x9f]", lambda m: f"\\u{ord(m.group()):04X}", escaped)
    return tomlkit.string(escaped, escape=False)


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
