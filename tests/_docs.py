"""The documentation as the tests read it: the README and every markdown page under docs/
(the pages of the documentation site; generated pages and the build are left out)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def pages() -> list[Path]:
    """The README, then the site's markdown pages in path order."""
    docs = ROOT / "docs"
    found = sorted(p for p in docs.rglob("*.md") if not any(part.startswith("_") for part in p.relative_to(docs).parts))
    return [README, *found]


def text() -> str:
    """Every page, one after the other."""
    return "\n".join(p.read_text(encoding="utf-8") for p in pages())


def blocks(language: str, paths: list[Path] | None = None) -> list[str]:
    """The fenced code blocks of one language, in page order."""
    found: list[str] = []
    for path in pages() if paths is None else paths:
        found += re.findall(rf"^```{language}\n(.*?)^```", path.read_text(encoding="utf-8"), flags=re.S | re.M)
    return found
