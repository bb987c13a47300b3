"""The configuration reference page, generated from the core's schema.

``drillstring._core.drill_config_schema()`` maps every dotted key of a drilling configuration
to ``{type, unit, label, default, description}``. This extension writes one table per
configuration table (``sections``, ``well``, ``top_drive.controller``, ...) with the key, its
unit, its default and its meaning into ``_generated/configuration.md``, which
``reference/configuration.md`` includes. A build against a core without the schema takes the keys
and defaults from ``_core.drill_defaults()`` and says so on the page.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any


def _flatten(value: Any, prefix: str, out: dict[str, Any]) -> None:
    """The dotted keys of the defaults (a list of tables as ``name[]``)."""
    if isinstance(value, dict):
        for key, inner in value.items():
            _flatten(inner, f"{prefix}.{key}" if prefix else key, out)
    elif isinstance(value, list) and value and isinstance(value[0], dict):
        _flatten(value[0], f"{prefix}[]", out)
    else:
        out[prefix] = value


def schema() -> tuple[dict[str, dict[str, Any]], bool]:
    """The schema, and whether it is the core's (False: keys and defaults only)."""
    from drillstring import _core

    if hasattr(_core, "drill_config_schema"):
        return dict(_core.drill_config_schema()), True
    flat: dict[str, Any] = {}
    _flatten(_core.drill_defaults(), "", flat)
    return {key: {"type": type(v).__name__ if v is not None else "", "unit": "", "label": "",
                  "default": v, "description": ""} for key, v in flat.items()}, False


def _table_of(key: str) -> str:
    """The configuration table a dotted key belongs to ('' for the top level)."""
    head, _, _ = key.rpartition(".")
    return head


def _normal(key: str) -> str:
    """``sections[0].length``, ``sections[*].length`` -> ``sections[].length``."""
    return re.sub(r"\[[^\]]*\]", "[]", key)


def _cell(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _default(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, str):
        return f'`"{value}"`'
    return f"`{json.dumps(value)}`"


def _unit(entry: dict[str, Any]) -> str:
    unit = entry.get("unit")
    if unit is None:
        return ""  # not a number
    return _cell(unit) if unit else "–"  # "" is dimensionless


def markdown(entries: dict[str, dict[str, Any]], complete: bool) -> str:
    """One markdown table per configuration table, the top level first, then in the schema's
    order; an entry of type ``table`` gives its table's introduction instead of a row."""
    groups: dict[str, list[str]] = {"": []}  # the top level first
    intros: dict[str, str] = {}
    for key, entry in entries.items():
        if entry.get("type") == "table":
            intros[_normal(key)] = entry.get("description") or entry.get("label") or ""
            groups.setdefault(_normal(key), [])
            continue
        groups.setdefault(_table_of(_normal(key)), []).append(key)
    lines = []
    if not complete:
        lines += ["```{note}", "This build's core has no `drill_config_schema()`: the tables list "
                  "the keys and defaults of `drill_defaults()` only.", "```", ""]
    for table, keys in groups.items():
        if not keys:
            continue
        title = f"`[{table}]`" if table else "top level"
        if table.endswith("[]") and "[]" not in table[:-2]:
            title = f"`[[{table[:-2]}]]`"
        elif "[]" in table:
            title = f"`{table}`"
        lines += [f"## {title}", ""]
        if intros.get(table):
            lines += [intros[table], ""]
        lines += ["| key | unit | default | meaning |", "|---|---|---|---|"]
        for key in keys:
            entry = entries[key]
            name = key.rpartition(".")[2] if table else key
            meaning = entry.get("description") or entry.get("label") or ""
            lines.append(f"| `{name}` | {_unit(entry)} | {_cell(_default(entry.get('default')))} | {_cell(meaning)} |")
        lines.append("")
    return "\n".join(lines)


def _write(app: Any) -> None:
    out = Path(app.srcdir) / "_generated" / "configuration.md"
    out.parent.mkdir(parents=True, exist_ok=True)
    text = markdown(*schema())
    if not out.exists() or out.read_text(encoding="utf-8") != text:  # keep the mtime: no re-read
        out.write_text(text, encoding="utf-8")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
