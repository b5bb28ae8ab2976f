"""``wide.sav``: the wide table for SPSS users, written beside ``wide.csv`` with pyreadstat.

Same rows and values as ``wide.csv``. Each variable carries its data-dictionary description as its label; a
variable whose name SPSS cannot take (longer than 64 bytes, or not starting with a letter) is renamed ``v<n>`` and
keeps its export name at the start of its label. Value labels: a rating item's anchor labels (``scale.labels``),
a choice item's options (0-based, as exported), and no / yes for 0/1 flags.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from analysis.dictionary import FLAG, WIDE_SEPARATOR, Column
from analysis.dictionary_items import item_key

SAV_FILE = "wide.sav"
MAX_NAME = 64
MAX_LABEL = 256
FLAG_LABELS = {0.0: "no", 1.0: "yes"}
_VALID = re.compile(r"^[A-Za-z][A-Za-z0-9._@#$]*$")


def item_value_labels(config: Mapping[str, Any]) -> dict[str, dict[float, str]]:
    """``<questionnaire>.<item>`` → value → label, for rating items with anchor labels and for choice items."""
    out: dict[str, dict[float, str]] = {}
    for questionnaire in config.get("questionnaires") or ():
        for item in questionnaire.get("items", ()):
            key = item_key(str(questionnaire["id"]), str(item["id"]))
            if item.get("type") == "choice":
                out[key] = {float(i): str(option) for i, option in enumerate(item.get("options", ()))}
            elif (item.get("scale") or {}).get("labels"):
                out[key] = {float(v): str(text) for v, text in item["scale"]["labels"].items()}
    return out


def spss_names(names: Sequence[str]) -> dict[str, str]:
    """Export column name → an SPSS variable name (unchanged when valid; else ``v<position>``)."""
    out = {}
    for position, name in enumerate(names, start=1):
        valid = _VALID.match(name) and len(name.encode()) <= MAX_NAME and not name.endswith(".")
        out[name] = name if valid else f"v{position}"
    return out


def write_sav(wide: pd.DataFrame, columns: Sequence[Column], config: Mapping[str, Any], path: Path) -> Path:
    """Write ``wide`` (the ``wide.csv`` table, documented by ``columns``) to ``path`` as an SPSS ``.sav`` file."""
    import pyreadstat

    names = spss_names(list(wide.columns))
    described = {c.name: c for c in columns}
    items = item_value_labels(config)
    data = pd.DataFrame({names[c]: _spss_values(wide[c]) for c in wide.columns})
    labels: list[str | None] = []
    value_labels: dict[str, dict[float, str]] = {}
    for column in wide.columns:
        info = described.get(column)
        text = info.description if info else ""
        labels.append((text if names[column] == column else f"{column}: {text}")[:MAX_LABEL])
        base = column.split(WIDE_SEPARATOR)[0]
        if base in items:
            value_labels[names[column]] = items[base]
        elif info is not None and info.type == FLAG:
            value_labels[names[column]] = FLAG_LABELS
    pyreadstat.write_sav(data, str(path), column_labels=labels, variable_value_labels=value_labels)
    return path


def _spss_values(column: pd.Series) -> pd.Series:
    """Numbers as float64 (missing: system-missing), everything else as text (missing: empty)."""
    if pd.api.types.is_numeric_dtype(column) or pd.api.types.is_bool_dtype(column):
        return column.astype("Float64").astype(float)
    return column.astype(object).where(column.notna(), "").astype(str)
