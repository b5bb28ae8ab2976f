"""Rows left out of the analysis by rule, each with its reason, unless the analyst asks to keep them.

A rule reads one column of the participant × condition table: a non-empty value marks the row. Rules:

* ``invalid`` — ``invalid_reason``: the server marked the trial invalid (robot decisions missed past the
  study's threshold; the share is in ``missed_decisions_pct``). Kept with ``--include-invalid``.
* ``low_engagement`` — ``engagement_reason``: the server marked the main trial low-engagement (the participant
  did not take part; their ``idle_pct`` is added). Kept with ``--include-invalid`` too.

Another rule is one more entry in :data:`RULES` (e.g. simulated pilot participants, kept with
``--include-pilot``). A table without a rule's column has nothing to exclude by it (an export made before the
column existed). Excluded rows are listed with their reason in the report and ``exclusions.csv``; a participant
who loses a cell this way is then left out of the measures that need that cell, and the complete-case list says
which cell and why.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

import pandas as pd

from analysis.source.naming import cell_label

EXCLUSION_COLUMNS = ["subject", "cell", "rule", "reason", "included"]


@dataclass(frozen=True, slots=True)
class ExclusionRule:
    name: str
    column: str
    option: str
    """The command-line option that keeps the rows."""
    label: str
    detail_column: str = ""
    """A column whose value is added to the reason (e.g. the share of missed decisions)."""

    def reason(self, row: pd.Series) -> str | None:
        value = row.get(self.column)
        if value is None or pd.isna(value) or str(value).strip() in ("", "0", "False"):
            return None
        text = self.label if str(value).strip() in ("1", "True") else f"{self.label}: {value}"
        detail = row.get(self.detail_column) if self.detail_column else None
        if detail is not None and not pd.isna(detail):
            text += f" ({self.detail_column} = {detail})"
        return text


INVALID = ExclusionRule("invalid", "invalid_reason", "--include-invalid", "invalid robot trial",
                        "missed_decisions_pct")
LOW_ENGAGEMENT = ExclusionRule("low_engagement", "engagement_reason", "--include-invalid", "low-engagement trial",
                               "idle_pct")
RULES: tuple[ExclusionRule, ...] = (INVALID, LOW_ENGAGEMENT)


def apply_exclusions(cells: pd.DataFrame, within: Sequence[str], subject: str,
                     include: Collection[str] = (), rules: Sequence[ExclusionRule] = RULES
                     ) -> tuple[pd.DataFrame, pd.DataFrame]:
    """``(kept, listed)``: the rows no rule excludes (or whose rule is in ``include``), and one row per marked
    row with ``subject, cell, rule, reason, included``."""
    listed = []
    drop = pd.Series(False, index=cells.index)
    for rule in rules:
        if rule.column not in cells.columns:
            continue
        for index, row in cells.iterrows():
            reason = rule.reason(row)
            if reason is None:
                continue
            kept = rule.name in include
            listed.append({"subject": row[subject], "cell": cell_label(within, tuple(row[list(within)])),
                           "rule": rule.name, "reason": reason, "included": int(kept)})
            drop[index] |= not kept
    return cells[~drop].reset_index(drop=True), pd.DataFrame(listed, columns=EXCLUSION_COLUMNS)


def missing_reasons(listed: pd.DataFrame) -> dict[tuple[object, str], str]:
    """``(subject, cell label) → reason`` of the excluded rows, for the complete-case list."""
    return {(r.subject, r.cell): f"excluded: {r.reason}" for r in listed.itertuples() if not r.included}
