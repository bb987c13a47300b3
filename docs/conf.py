"""Sphinx configuration of the drillstring documentation.

Build (from the checkout, with the package and the ``docs`` extra installed)::

    python3 -m sphinx -W --keep-going -b html docs docs/_build/html

The configuration reference (``drillstring._core.drill_config_schema()``) and the gallery's
figures (``docs/gallery/*.py`` run at build time) are generated into ``docs/_generated/``.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
if importlib.util.find_spec("drillstring") is None:  # a checkout without an installed package
    sys.path.insert(0, str(HERE.parent / "python"))

import drillstring  # noqa: E402

project = "drillstring"
author = "drillstring maintainers"
copyright = "drillstring maintainers"
release = drillstring.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "config_reference",
    "metric_reference",
    "gallery",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_generated/configuration.md", "_generated/metrics.md", "gallery/*.py", "Thumbs.db",
                    ".DS_Store"]

myst_enable_extensions = ["colon_fence", "dollarmath"]
myst_heading_anchors = 3

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_ivar = True  # "Attributes" as fields: no second description of a dataclass field

html_theme = "alabaster"
html_title = f"drillstring {release}"
html_static_path: list[str] = []


def _listed(index: str) -> set[str]:
    """The documents the toctrees of the index name (one per line)."""
    return {line.strip() for line in index.splitlines() if line.strip() and not line.startswith((":", "`", "#"))}


def _more_pages(app, docname, source):  # type: ignore[no-untyped-def]
    """Any page another change adds under docs/ (``docs/units.md``, ...) goes into a "More"
    toctree of the index, so that nothing needs registering and no page is left out."""
    if docname != "index":
        return
    src = Path(app.srcdir)
    listed = _listed(source[0])
    pages = sorted(
        str(path.relative_to(src).with_suffix("")).replace("\\", "/")
        for path in src.rglob("*.md")
        if not path.relative_to(src).parts[0].startswith("_") and path.stem != "index"
    )
    more = [page for page in pages if page not in listed]
    if more:
        source[0] += "\n```{toctree}\n:maxdepth: 1\n:caption: More\n\n" + "\n".join(more) + "\n```\n"


def setup(app):  # type: ignore[no-untyped-def]
    app.connect("source-read", _more_pages)
