"""The examples gallery: every ``gallery/*.py`` runs at build time.

Each script's docstring is its page's text (first line the title), its code is shown, what it
prints is shown, and every matplotlib ``Figure`` it leaves in its namespace is saved as a PNG and
shown in order. The pages go into ``_generated/gallery/`` (``gallery.md`` lists them). A script
that raises fails the build. Scripts run with the checkout as the working directory, so that
``examples/...`` paths work as in the README.
"""

from __future__ import annotations

import ast
import contextlib
import io
import os
import time
from pathlib import Path
from typing import Any

from sphinx.util import logging

LOG = logging.getLogger(__name__)


def _run(script: Path, out: Path, root: Path) -> str:
    """Run one script; write its figures; return its page."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    source = script.read_text(encoding="utf-8")
    tree = ast.parse(source)
    doc = ast.get_docstring(tree) or script.stem
    first_code = tree.body[0].end_lineno + 1 if ast.get_docstring(tree) else 1
    title, _, text = doc.partition("\n")
    namespace: dict[str, Any] = {"__name__": "__gallery__"}
    printed = io.StringIO()
    here = os.getcwd()
    start = time.perf_counter()
    try:
        os.chdir(root)
        with contextlib.redirect_stdout(printed):
            exec(compile(source, str(script), "exec"), namespace)
    finally:
        os.chdir(here)
    seconds = time.perf_counter() - start
    figures = [v for v in namespace.values() if isinstance(v, Figure)]
    lines = [f"# {title.strip()}", "", text.strip(), "",
             f"```{{literalinclude}} ../../gallery/{script.name}", ":language: python",
             f":lines: {first_code}-", "```", ""]
    if printed.getvalue().strip():
        lines += ["It prints:", "", "```text", printed.getvalue().rstrip(), "```", ""]
    for k, fig in enumerate(figures):
        name = f"{script.stem}_{k + 1}.png"
        fig.savefig(out / name, dpi=90)
        lines += [f"![{title.strip()}, figure {k + 1}]({name})", ""]
    lines.append("*The documentation build ran this script and made these figures.*")
    LOG.info(f"gallery: {script.name} in {seconds:.1f} s, {len(figures)} figures")
    return "\n".join(lines) + "\n"


def _build(app: Any) -> None:
    src = Path(app.srcdir)
    out = src / "_generated" / "gallery"
    out.mkdir(parents=True, exist_ok=True)
    scripts = sorted((src / "gallery").glob("*.py"))
    for stale in out.iterdir():  # pages and figures of scripts that are gone
        if not any(stale.name == f"{s.stem}.md" or stale.name.startswith(f"{s.stem}_") for s in scripts):
            stale.unlink()
    for script in scripts:
        page = _run(script, out, src.parent)
        target = out / f"{script.stem}.md"
        if not target.exists() or target.read_text(encoding="utf-8") != page:
            target.write_text(page, encoding="utf-8")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _build)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
