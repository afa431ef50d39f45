"""One page model, two renderings: the Markdown and the HTML of a page say the same things."""

from __future__ import annotations

import html
import re
from pathlib import Path

import pytest

from planshape.results import render
from planshape.results.page import Bullets, Figure, Heading, Page, Paragraph
from planshape.results.tables import Cell, Table

TABLE = Table(
    ("Entry", "IQM"),
    ((Cell("plan/grid", code=True), Cell("0.500", 0.5)), (Cell("a|b"), Cell("n/a"))),
    sortable=True,
)


@pytest.fixture
def page(tmp_path: Path) -> Page:
    (tmp_path / "plots").mkdir()
    (tmp_path / "plots" / "a.png").write_bytes(b"\x89PNG")
    return Page(
        "board",
        (
            Heading(2, "Reach & push", anchor="reach"),
            Paragraph("**Packages**: numpy <2>"),
            Bullets(("one", "**two**")),
            TABLE,
            Paragraph("only on the page", only="html"),
            Heading(2, "Only in Markdown", only="markdown"),
            Figure("a plot", "plots/a.png"),
        ),
    )


def test_markdown(page):
    text = render.markdown(page)
    assert text.startswith("# board\n\n## Reach & push\n\n**Packages**: numpy <2>\n\n- one\n")
    assert "| Entry | IQM |\n|---|---|\n| `plan/grid` | 0.500 |\n| a\\|b | n/a |" in text
    assert "![a plot](plots/a.png)\n" in text and "Only in Markdown" in text
    assert "only on the page" not in text


def test_html_is_self_contained_and_escaped(page, tmp_path):
    text = render.html(page, tmp_path)
    assert '<h2 id="reach">Reach &amp; push</h2>' in text
    assert "<p><strong>Packages</strong>: numpy &lt;2&gt;</p>" in text
    assert '<table class="sortable">' in text and "<td><code>plan/grid</code></td>" in text
    assert '<td class="num" data-value="0.5">0.500</td>' in text
    assert '<td class="num" data-value="">n/a</td>' in text
    assert 'src="data:image/png;base64,iVBORw=="' in text
    assert "only on the page" in text and "Only in Markdown" not in text
    assert "table.sortable th" in text and "querySelectorAll" in text  # style.css, sort.js
    assert not re.search(r"<(link|script) [^>]*(href|src)=", text)  # nothing fetched


def test_both_show_every_shared_block(page, tmp_path):
    """Every heading, paragraph, item, cell and caption not marked for one medium is in both."""
    md, page_html = render.markdown(page), html.unescape(render.html(page, tmp_path))
    texts = []
    for block in page.blocks:
        if block.only is None:
            texts += {
                "heading": lambda b: [b.text],
                "paragraph": lambda b: [b.text.replace("**", "")],
                "bullets": lambda b: [i.replace("**", "") for i in b.items],
                "table": lambda b: [*b.headings, *(c.text for row in b.rows for c in row)],
                "figure": lambda b: [b.caption],
            }[block.kind](block)
    plain_md = md.replace("**", "").replace("\\|", "|")
    assert [t for t in texts if t not in plain_md] == []
    assert [
        t for t in texts if t not in page_html.replace("<strong>", "").replace("</strong>", "")
    ] == []
