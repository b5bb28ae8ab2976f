"""A minimal document model rendered to both Markdown and HTML.

The report is assembled once as a sequence of blocks (headings, paragraphs, bullet lists, tables,
images) and each renderer writes its own syntax, so the HTML needs no Markdown converter and the
two files cannot drift apart. Text is plain: Markdown-significant ``|`` in table cells and all of
``<>&"'`` in HTML are escaped; nothing else is interpreted.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Heading:
    level: int
    text: str


@dataclass(frozen=True, slots=True)
class Paragraph:
    text: str


@dataclass(frozen=True, slots=True)
class BulletList:
    items: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Table:
    columns: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]


@dataclass(frozen=True, slots=True)
class Image:
    path: str
    alt: str


Block = Heading | Paragraph | BulletList | Table | Image


def table(columns: Sequence[str], rows: Iterable[Sequence[str]]) -> Table:
    """A ``Table`` from any sequences of already formatted cell strings."""
    return Table(tuple(columns), tuple(tuple(row) for row in rows))


def render_markdown(blocks: Iterable[Block]) -> str:
    """CommonMark with GitHub tables; blocks separated by a blank line."""
    parts: list[str] = []
    for block in blocks:
        match block:
            case Heading(level, text):
                parts.append(f"{'#' * level} {text}")
            case Paragraph(text):
                parts.append(text)
            case BulletList(items):
                parts.append("\n".join(f"- {item}" for item in items))
            case Table(columns, rows):
                lines = [_md_row(columns), "|" + "---|" * len(columns)]
                lines += [_md_row(row) for row in rows]
                parts.append("\n".join(lines))
            case Image(path, alt):
                parts.append(f"![{alt}]({path})")
    return "\n\n".join(parts) + "\n"


def render_html(blocks: Iterable[Block], title: str) -> str:
    """A standalone HTML5 page with a little inline CSS."""
    body: list[str] = []
    for block in blocks:
        match block:
            case Heading(level, text):
                body.append(f"<h{level}>{_e(text)}</h{level}>")
            case Paragraph(text):
                body.append(f"<p>{_e(text)}</p>")
            case BulletList(items):
                body.append("<ul>" + "".join(f"<li>{_e(item)}</li>" for item in items) + "</ul>")
            case Table(columns, rows):
                head = "".join(f"<th>{_e(c)}</th>" for c in columns)
                lines = "".join(
                    "<tr>" + "".join(f"<td>{_e(c)}</td>" for c in row) + "</tr>" for row in rows
                )
                body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{lines}</tbody></table>")
            case Image(path, alt):
                body.append(f'<figure><img src="{_e(path)}" alt="{_e(alt)}"></figure>')
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{_e(title)}</title>\n<style>{_CSS}</style>\n</head>\n<body>\n"
        + "\n".join(body)
        + "\n</body>\n</html>\n"
    )


_CSS = (
    "body{font-family:sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;line-height:1.4}"
    "table{border-collapse:collapse;margin:0.5rem 0}"
    "th,td{border:1px solid #bbb;padding:0.2rem 0.5rem;text-align:right}"
    "th{background:#eee}img{max-width:100%}"
)


def _md_row(cells: Sequence[str]) -> str:
    return "| " + " | ".join(cell.replace("|", "\\|") for cell in cells) + " |"


def _e(text: str) -> str:
    return html.escape(text, quote=True)
