"""How the analysis names what a study declares: a cell of the within design, a questionnaire item's column and a
named scale's column. The exports, the statistics and the report all spell them this one way."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import Any


def cell_label(within: Sequence[str], cell: Sequence[Any]) -> str:
    """``robot=baseline, kitchen=mid_2`` for ``within=("robot", "kitchen")``."""
    return ", ".join(f"{factor}={level}" for factor, level in zip(within, cell, strict=True))


def item_key(questionnaire: str, item: str) -> str:
    """``<questionnaire id>.<item id>``: an item's (or a scale's) column name in the exports."""
    return f"{questionnaire}.{item}"


def scale_key(questionnaire: str, scale: str, item_ids: Collection[str]) -> str:
    """A named scale's column: ``<questionnaire id>.<scale id>``, with ``_scale`` appended when an item of the
    questionnaire has the scale's id."""
    return item_key(questionnaire, scale) + ("_scale" if scale in item_ids else "")
