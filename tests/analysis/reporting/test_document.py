"""The report's document model and its two renderers."""

from __future__ import annotations

from analysis.reporting.document import (
    Block,
    BulletList,
    Heading,
    Image,
    Paragraph,
    render_html,
    render_markdown,
    table,
)

BLOCKS: list[Block] = [
    Heading(2, "ticks"),
    Paragraph("n used = 3 <of> 4 & more"),
    BulletList(("one", "two")),
    table(["a", "b|c"], [["1", "x|y"]]),
    Image("plots/t.png", "alt text"),
]


def test_markdown() -> None:
    assert render_markdown(BLOCKS) == (
        "## ticks\n\n"
        "n used = 3 <of> 4 & more\n\n"
        "- one\n- two\n\n"
        "| a | b\\|c |\n|---|---|\n| 1 | x\\|y |\n\n"
        "![alt text](plots/t.png)\n"
    )


def test_html_escapes_text_and_keeps_structure() -> None:
    page = render_html(BLOCKS, "T & T")
    assert page.startswith("<!DOCTYPE html>")
    assert "<title>T &amp; T</title>" in page
    assert "<h2>ticks</h2>" in page
    assert "<p>n used = 3 &lt;of&gt; 4 &amp; more</p>" in page
    assert "<ul><li>one</li><li>two</li></ul>" in page
    assert "<th>b|c</th>" in page and "<td>x|y</td>" in page
    assert '<img src="plots/t.png" alt="alt text">' in page
