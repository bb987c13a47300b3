"""The report document rendered as Markdown and as one self-contained HTML page, through Jinja2
templates. Inline markup inside the text (```code```, ``**bold**``, ``*italic*``, ``[link](target)``) is
Markdown; the HTML template converts it with :func:`inline_html`."""

from __future__ import annotations

import base64
import functools
import re
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from markupsafe import Markup, escape

from .document import Block

if TYPE_CHECKING:  # pragma: no cover - Jinja2 is loaded when a report is rendered, not on import
    import jinja2

_INLINE = re.compile(r"`([^`]+)`|\*\*([^*]+)\*\*|\[([^\]]+)\]\(([^)\s]+)\)|\*([^*\s][^*]*)\*")


def inline_html(text: Any) -> Markup:
    """Inline Markdown (code, bold, italic, links) as escaped HTML."""
    text = str(text)
    out, pos = [], 0
    for m in _INLINE.finditer(text):
        out.append(escape(text[pos:m.start()]))
        if m.group(1) is not None:
            out.append(Markup("<code>%s</code>") % m.group(1))
        elif m.group(2) is not None:
            out.append(Markup("<strong>%s</strong>") % m.group(2))
        elif m.group(3) is not None:
            out.append(Markup('<a href="%s">%s</a>') % (m.group(4), m.group(3)))
        else:
            out.append(Markup("<em>%s</em>") % m.group(5))
        pos = m.end()
    out.append(escape(text[pos:]))
    return Markup("").join(out)


def _cell(value: Any) -> str:
    """A Markdown table cell: ``|`` escaped."""
    return str(value).replace("|", "\\|")


_MARKDOWN = """\
{% for b in blocks %}
{% if b.kind == "h1" %}
# {{ b.text }}
{% elif b.kind == "h2" %}
## {{ b.text }}
{% elif b.kind == "p" %}
{{ b.text }}
{% elif b.kind == "ul" %}
{% for item in b.items %}
- {{ item }}
{% endfor %}
{% elif b.kind == "ol" %}
{% for item in b.items %}
{{ loop.index }}. {{ item }}
{% endfor %}
{% elif b.kind == "img" %}
![{{ b.alt }}]({{ b.text }})
{% elif b.kind == "code" %}
```
{{ b.text }}
```
{% elif b.kind == "table" %}
| {{ b.items | map("cell") | join(" | ") }} |
|{% for _ in b.items %}---{{ "|" if not loop.last }}{% endfor %}|
{% for row in b.rows %}
| {{ row | map("cell") | join(" | ") }} |
{% endfor %}
{% endif %}

{% endfor %}
"""

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; max-width: 1100px;
       margin: 2em auto; padding: 0 1em; line-height: 1.45; color: #222; }
h1 { font-size: 1.6em; } h2 { font-size: 1.25em; margin-top: 2em; border-bottom: 1px solid #ddd; }
img { max-width: 100%; border: 1px solid #eee; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
th { background: #f3f3f3; }
code, pre { font-family: ui-monospace, Menlo, Consolas, monospace; font-size: 0.88em; }
pre { background: #f6f6f6; padding: 0.7em; overflow-x: auto; }
"""

_HTML = """\
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{{ title }}</title>
<style>{{ css }}</style></head><body>
{% for b in blocks %}
{% if b.kind in ("h1", "h2") %}
<{{ b.kind }}>{{ b.text | inline }}</{{ b.kind }}>
{% elif b.kind == "p" %}
<p>{{ b.text | inline }}</p>
{% elif b.kind in ("ul", "ol") %}
<{{ b.kind }}>{% for item in b.items %}<li>{{ item | inline }}</li>{% endfor %}</{{ b.kind }}>
{% elif b.kind == "img" %}
<figure><img src="data:image/png;base64,{{ images[b.text] }}" alt="{{ b.alt }}"></figure>
{% elif b.kind == "code" %}
<pre><code>{{ b.text }}</code></pre>
{% elif b.kind == "table" %}
<table><thead><tr>{% for h in b.items %}<th>{{ h | inline }}</th>{% endfor %}</tr></thead><tbody>
{%- for row in b.rows %}<tr>{% for c in row %}<td>{{ c | inline }}</td>{% endfor %}</tr>{% endfor -%}
</tbody></table>
{% endif %}
{% endfor %}
</body></html>"""


def _environment(autoescape: bool) -> jinja2.Environment:
    import jinja2

    env = jinja2.Environment(autoescape=autoescape, trim_blocks=True, lstrip_blocks=True,
                             keep_trailing_newline=True, undefined=jinja2.StrictUndefined)
    env.filters["cell"] = _cell
    env.filters["inline"] = inline_html
    return env


@functools.cache
def _template(kind: str) -> jinja2.Template:
    """The compiled ``"markdown"`` or ``"html"`` template (compiled once, on first use)."""
    if kind == "html":
        return _environment(True).from_string(_HTML)
    return _environment(False).from_string(_MARKDOWN)


def markdown(doc: Sequence[Block]) -> str:
    """The report as Markdown."""
    return _template("markdown").render(blocks=doc).rstrip("\n") + "\n"


def html(doc: Sequence[Block], images: Mapping[str, bytes]) -> str:
    """The report as one self-contained HTML page; ``images`` holds the PNG of each image block
    (kept in memory rather than read back: an output may be a FIFO or a device)."""
    encoded = {name: base64.b64encode(data).decode("ascii") for name, data in images.items()}
    return _template("html").render(blocks=doc, images=encoded, title=doc[0].text, css=Markup(_CSS))
