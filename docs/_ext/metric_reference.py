"""The table of a run's outputs, generated from the core's registry.

``drillstring._core.drill_outputs()`` lists every metric and series channel of a run once, with
its unit, definition and the runs that have it. This extension writes the table into
``_generated/metrics.md``, which ``guide/metrics.md`` includes, so that the page lists exactly the
outputs of the version it documents.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

#: The runs in the table's column, by the registry's names.
RUNS = {"torsional": "drilling", "coupled": "coupled", "lumped": "lumped"}


def _cell(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _unit(entry: dict[str, Any]) -> str:
    unit = entry.get("unit")
    if unit is None:
        return ""  # a verdict, a count or a text
    return _cell(unit.replace("*", " ")) if unit else "–"  # "" is dimensionless


def markdown(entries: list[dict[str, Any]]) -> str:
    """Two tables: the metrics (in the order of ``metrics.json``), then the series channels."""
    lines = ["| metric | unit | kind | runs | map column | definition |", "|---|---|---|---|---|---|"]
    for e in entries:
        if e["kind"] == "series":
            continue
        runs = ", ".join(RUNS[r] for r in e["runs"])
        lines.append(f"| `{e['name']}` | {_unit(e)} | {e['kind']} | {runs} | {'yes' if e['map_column'] else 'no'} "
                     f"| {_cell(e['definition'])} |")
    lines += ["", "| series | unit | runs | definition |", "|---|---|---|---|"]
    for e in entries:
        if e["kind"] == "series":
            runs = ", ".join(RUNS[r] for r in e["runs"])
            lines.append(f"| `{e['name']}` | {_unit(e)} | {runs} | {_cell(e['definition'])} |")
    return "\n".join(lines) + "\n"


def table() -> str:
    """The tables of this build's core."""
    from drillstring import _core

    return markdown([dict(e) for e in _core.drill_outputs()])


def _write(app: Any) -> None:
    out = Path(app.srcdir) / "_generated" / "metrics.md"
    out.parent.mkdir(parents=True, exist_ok=True)
    text = table()
    if not out.exists() or out.read_text(encoding="utf-8") != text:  # keep the mtime: no re-read
        out.write_text(text, encoding="utf-8")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
