"""Rendering: one :class:`~planshape.results.page.Page` written as Markdown and as HTML, and
numbers written as strict JSON.

* :func:`markdown` — ``LEADERBOARD.md``: the blocks in order, a blank line between them;
* :func:`html` — ``index.html`` through the jinja2 template ``templates/index.html``, with the
  style (``templates/style.css``) and the table-sorting script (``templates/sort.js``) inlined
  and every figure inlined as a base64 data URI, so the page is one file that works offline;
* :func:`json_ready` — NaN as ``null``, numpy scalars as Python numbers, for ``summary.json``.

Example:
    >>> from planshape.results.page import Bullets, Heading, Page, Paragraph
    >>> page = Page("results", (Heading(2, "Setup"), Paragraph("**Seeds**: 5"), Bullets(("a",))))
    >>> print(markdown(page))
    # results
    <BLANKLINE>
    ## Setup
    <BLANKLINE>
    **Seeds**: 5
    <BLANKLINE>
    - a
    <BLANKLINE>
    >>> "<p><strong>Seeds</strong>: 5</p>" in html(page, Path("."))
    True
"""

from __future__ import annotations

import base64
import functools
import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from planshape.results.page import Block, Page
from planshape.results.tables import Table

__all__ = ["html", "json_ready", "markdown"]


# --------------------------------------------------------------------------------------------
# Markdown
# --------------------------------------------------------------------------------------------


def _md_escape(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _md_row(cells: list[str]) -> str:
    return "| " + " | ".join(_md_escape(c) for c in cells) + " |"


def _md_table(table: Table) -> str:
    lines = [_md_row(list(table.headings)), "|" + "|".join("---" for _ in table.headings) + "|"]
    lines += [_md_row([f"`{c.text}`" if c.code else c.text for c in row]) for row in table.rows]
    return "\n".join(lines)


def _md_block(block: Block) -> str:
    match block.kind:
        case "heading":
            return "#" * block.level + " " + block.text
        case "paragraph":
            return block.text
        case "bullets":
            return "\n".join(f"- {item}" for item in block.items)
        case "table":
            return _md_table(block)
        case "figure":
            return f"![{block.caption}]({block.src})"
    raise TypeError(f"not a block of a page: {block!r}")


def markdown(page: Page) -> str:
    """``page`` as Markdown: its title as ``#``, then every block shown there."""
    blocks = [f"# {page.title}", *map(_md_block, page.blocks_for("markdown"))]
    return "\n\n".join(blocks) + "\n"


# --------------------------------------------------------------------------------------------
# HTML
# --------------------------------------------------------------------------------------------


@functools.cache
def _environment() -> Any:
    import jinja2
    import markupsafe

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("planshape.results", "templates"),
        autoescape=True,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
    )

    def inline(text: str) -> Any:
        """Escaped text with ``**bold**`` as ``<strong>``."""
        escaped = str(markupsafe.escape(text))
        return markupsafe.Markup(re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", escaped))

    env.filters["inline"] = inline
    return env


def _asset(name: str) -> Any:
    """A file of ``templates/`` as trusted markup, to inline."""
    import markupsafe

    source, _, _ = _environment().loader.get_source(_environment(), name)
    return markupsafe.Markup(source)


def _data_uri(path: Path) -> str:
    kind = "gif" if path.suffix == ".gif" else "png"
    return f"data:image/{kind};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def html(page: Page, root: Path) -> str:
    """``page`` as one self-contained HTML file; figures are read from ``root / src``."""
    template = _environment().get_template("index.html")
    return template.render(
        page=page,
        blocks=page.blocks_for("html"),
        css=_asset("style.css"),
        js=_asset("sort.js"),
        data_uri=lambda src: _data_uri(root / src),
    )


# --------------------------------------------------------------------------------------------
# JSON
# --------------------------------------------------------------------------------------------


def json_ready(value: Any) -> Any:
    """``value`` with NaN and infinities as ``None`` (JSON ``null``), numpy scalars as Python
    numbers and tuples as lists, so that ``json.dumps(..., allow_nan=False)`` accepts it.

    Example:
        >>> import json
        >>> json.dumps(json_ready({"iqm": float("nan"), "ci": (np.float64(0.5), 1.0)}))
        '{"iqm": null, "ci": [0.5, 1.0]}'
    """
    if isinstance(value, Mapping):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_ready(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
