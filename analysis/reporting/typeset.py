"""The report's typography, applied once to every block before it is rendered (:func:`typeset`).

* A negative number gets a real minus sign (U+2212), in prose and tables: ``−0.37``, ``[−0.65, −0.09]``.
* In prose (paragraphs and bullet points), a factor's level reads as words: ``kitchen=none_3`` becomes
  ``kitchen none_3`` (tables keep the ``factor=level`` labels of the CSV files they mirror).
* Parentheses inside parentheses become square brackets (APA 7, §6.10): ``(main trial 3 abandoned (grace
  expired))`` becomes ``(main trial 3 abandoned [grace expired])``.
"""

from __future__ import annotations

import re

from analysis.reporting.document import Block, BulletList, Paragraph, Table

MINUS = "\u2212"
_NEGATIVE = re.compile(r"(?<![\w.\-\u2212)\]])-(?=\.?\d)")
_LEVEL = re.compile(r"(?<![\w.])([A-Za-z_][A-Za-z0-9_.]*)=(?=[^\s=])")


def minus(text: str) -> str:
    """``text`` with the hyphen of each negative number replaced by a minus sign (not in ``2026-12-07``,
    ``P-03`` or ``n-1``: only a hyphen after a space, an opening bracket or the start)."""
    return _NEGATIVE.sub(MINUS, text)


def levels_in_words(text: str) -> str:
    """``robot=baseline, kitchen=mid_2`` → ``robot baseline, kitchen mid_2``."""
    return _LEVEL.sub(r"\1 ", text)


def nested_brackets(text: str) -> str:
    """Parentheses at depth two and more written as square brackets."""
    out, depth = [], 0
    for char in text:
        if char == "(":
            out.append("(" if depth == 0 else "[")
            depth += 1
        elif char == ")" and depth > 0:
            depth -= 1
            out.append(")" if depth == 0 else "]")
        else:
            out.append(char)
    return "".join(out)


def prose(text: str) -> str:
    return minus(nested_brackets(levels_in_words(text)))


def typeset(blocks: list[Block]) -> list[Block]:
    """Every block with the module's typography (headings and images as they are)."""
    out: list[Block] = []
    for block in blocks:
        match block:
            case Paragraph(text):
                out.append(Paragraph(prose(text)))
            case BulletList(items):
                out.append(BulletList(tuple(prose(item) for item in items)))
            case Table(columns, rows):
                out.append(Table(columns, tuple(tuple(minus(cell) for cell in row) for row in rows)))
            case _:
                out.append(block)
    return out
