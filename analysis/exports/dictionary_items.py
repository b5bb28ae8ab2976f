"""The data dictionary's questionnaire section: every item of the study (type, range, reversal, options,
wording) and every named scale (its items, which are reversed, how it is scored), read from the resolved
study configuration stored with the study; and how participant-typed text is written to CSV safely."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from analysis.source.naming import item_key, scale_key


def md_cell(text: str) -> str:
    """Text for a Markdown table cell."""
    return text.replace("|", "\\|")


@dataclass(frozen=True, slots=True)
class ItemInfo:
    """A questionnaire item as the data dictionary describes it."""

    column: str
    """``<questionnaire>.<item>``."""
    kind: str
    """``rating min..max`` (``, reversed``), ``choice`` or ``text``."""
    description: str


@dataclass(frozen=True, slots=True)
class ScaleInfo:
    """A named scale: the mean of its items after reversal (docs/analysis.md)."""

    column: str
    """``<questionnaire>.<scale>``."""
    title: str
    items: tuple[str, ...]
    reversed: tuple[str, ...]
    description: str


def questionnaire_items(config: Mapping[str, Any]) -> list[ItemInfo]:
    """Every questionnaire item of a stored study configuration: its type, range, reversal and wording."""
    out = []
    for questionnaire in config.get("questionnaires", ()):
        when = "end of study" if questionnaire.get("when") == "end_of_study" else "after each main trial"
        for item in questionnaire.get("items", ()):
            kind = item.get("type", "rating")
            text = f"“{item.get('text', '')}” ({when}{'' if item.get('required', True) else ', optional'})"
            if kind == "rating" and item.get("scale"):
                low, high = item["scale"]["min"], item["scale"]["max"]
                labels = "; ".join(f"{k} = {v}" for k, v in sorted(item["scale"].get("labels", {}).items(),
                                                                     key=lambda kv: int(kv[0])))
                reverse = bool(item.get("reverse"))
                kind = f"rating {low}..{high}{', reversed' if reverse else ''}"
                text += f"; {labels}" if labels else ""
                text += f"; reverse-coded: scored as {low + high} − value in scales" if reverse else ""
            elif kind == "choice":
                text += "; options: " + "; ".join(f"{i} = {o}" for i, o in enumerate(item.get("options", ())))
            elif kind == "text":
                text += f"; at most {item.get('max_length')} characters (answers.csv, column text)"
            out.append(ItemInfo(item_key(str(questionnaire["id"]), str(item["id"])), kind, text))
    return out


def questionnaire_scales(config: Mapping[str, Any]) -> list[ScaleInfo]:
    """Every named scale of a stored study configuration, with its items and which of them are reversed."""
    out = []
    for questionnaire in config.get("questionnaires", ()):
        qid = str(questionnaire["id"])
        reversed_items = {str(i["id"]) for i in questionnaire.get("items", ()) if i.get("reverse")}
        item_ids = {str(i["id"]) for i in questionnaire.get("items", ())}
        for scale in questionnaire.get("scales", ()):
            items = tuple(str(i) for i in scale.get("items", ()))
            flipped = tuple(i for i in items if i in reversed_items)
            description = (f"{scale.get('title') or scale['id']}: mean of {', '.join(items)}"
                           + (f" after reversing {', '.join(flipped)} (min + max − value)" if flipped else ""))
            out.append(ScaleInfo(scale_key(qid, str(scale["id"]), item_ids), str(scale.get("title", "")), items,
                                 flipped, description))
    return out


def questionnaire_markdown(config: Mapping[str, Any]) -> list[str]:
    """The data dictionary's section on questionnaire items and named scales (none: no lines)."""
    items, scales = questionnaire_items(config), questionnaire_scales(config)
    if not items:
        return []
    lines = ["## Questionnaire items and scales", "",
             "Every item as the participant saw it. answers.csv has one row per answer; cells.csv (after each "
             "trial) and wide.csv (per condition, and once for the end of study) a column per rating or choice "
             "item and per named scale (its score); free-text answers are in answers.csv only. Ratings are exported "
             "as given: reverse them (min + max − value) before combining them.", "",
             "| item | type | wording and coding |", "|---|---|---|"]
    lines += [f"| {i.column} | {i.kind} | {md_cell(i.description)} |" for i in items]
    lines.append("")
    if scales:
        lines += ["Named scales (scored by the analysis as the mean of their items, reversed items first reversed):",
                  "", "| scale | items | scoring |", "|---|---|---|"]
        lines += [f"| {sc.column} | {', '.join(sc.items)} | {md_cell(sc.description)} |" for sc in scales]
        lines.append("")
    return lines


FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def spreadsheet_safe(text: Any) -> Any:
    """``text`` as written to a CSV file a spreadsheet may open: a leading ``'`` before text that a spreadsheet
    would otherwise run as a formula (OWASP's advice on CSV injection); anything else unchanged."""
    if isinstance(text, str) and text.startswith(FORMULA_STARTS):
        return "'" + text
    return text
