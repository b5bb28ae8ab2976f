"""``wide.sav``: the wide table for SPSS users, written beside ``wide.csv`` with pyreadstat.

Same rows and columns as ``wide.csv``, ready for SPSS's GLM Repeated Measures (one variable per within cell) with the
between factors as between-subjects factors. Each variable carries its data-dictionary description as its label; a
variable whose name SPSS cannot take (longer than 64 bytes, or not starting with a letter) is renamed ``v<n>`` and
keeps its export name at the start of its label.

From the data dictionary (:mod:`analysis.exports.dictionary`, the questionnaire items of the study's configuration):

* measurement level: a rating item (per cell or at the end of the study) is ordinal; a choice item, a 0/1 flag,
  text, the participant, the counterbalancing order and a between factor are nominal; every other number is scale;
* format: whole numbers (integers, flags, ratings, choices, codes) ``F<w>.0``; other numbers with the decimals
  their values need, up to 3 (``F<w>.<d>``); text ``A<w>``; w the widest value;
* value labels: a rating item's anchor labels (``scale.labels``), a choice item's options (0-based, as exported),
  no / yes for 0/1 flags, and the levels of a between factor, which is written as the codes 1, 2, … of its levels
  in study order (SPSS's factors are codes with labels; ``wide.csv`` has the level's name).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from analysis.exports.dictionary import FLAG, INT, TEXT, WIDE_SEPARATOR, Column
from analysis.source.naming import item_key

SAV_FILE = "wide.sav"
MAX_NAME = 64
MAX_LABEL = 256
MAX_DECIMALS = 3
FLAG_LABELS = {0.0: "no", 1.0: "yes"}
NOMINAL_NUMBERS = ("order_index",)
"""Numbers that name something rather than measure it: the counterbalancing order's index."""
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


def item_kinds(config: Mapping[str, Any]) -> dict[str, str]:
    """``<questionnaire>.<item>`` → ``rating``, ``choice`` or ``text``."""
    return {item_key(str(q["id"]), str(i["id"])): str(i.get("type", "rating"))
            for q in config.get("questionnaires") or () for i in q.get("items", ())}


def spss_names(names: Sequence[str]) -> dict[str, str]:
    """Export column name → an SPSS variable name (unchanged when valid; else ``v<position>``)."""
    out = {}
    for position, name in enumerate(names, start=1):
        valid = _VALID.match(name) and len(name.encode()) <= MAX_NAME and not name.endswith(".")
        out[name] = name if valid else f"v{position}"
    return out


def measurement_level(column: Column, kinds: Mapping[str, str], between: Mapping[str, Sequence[str]]) -> str:
    """SPSS's measurement level of a documented column (see the module docstring)."""
    kind = kinds.get(column.name.split(WIDE_SEPARATOR)[0])
    if kind == "rating":
        return "ordinal"
    if kind is not None or column.name in between or column.name in NOMINAL_NUMBERS or column.type in (FLAG, TEXT):
        return "nominal"
    return "scale"


def write_sav(wide: pd.DataFrame, columns: Sequence[Column], config: Mapping[str, Any], path: Path,
              between: Mapping[str, Sequence[str]] | None = None) -> Path:
    """Write ``wide`` (the ``wide.csv`` table, documented by ``columns``) to ``path`` as an SPSS ``.sav`` file;
    ``between`` maps each factor between participants to its levels in study order."""
    import pyreadstat

    between = between or {}
    names = spss_names(list(wide.columns))
    described = {c.name: c for c in columns}
    items, kinds = item_value_labels(config), item_kinds(config)
    data = pd.DataFrame({names[c]: _codes(wide[c], between[c]) if c in between else _spss_values(wide[c])
                         for c in wide.columns})
    labels: list[str | None] = []
    value_labels: dict[str, dict[float, str]] = {}
    measures: dict[str, str] = {}
    formats: dict[str, str] = {}
    for column in wide.columns:
        name = names[column]
        info = described.get(column) or Column(column, TEXT, "")
        labels.append((info.description if name == column else f"{column}: {info.description}")[:MAX_LABEL])
        base = column.split(WIDE_SEPARATOR)[0]
        if column in between:
            value_labels[name] = {float(i): str(level) for i, level in enumerate(between[column], start=1)}
        elif base in items:
            value_labels[name] = items[base]
        elif info.type == FLAG:
            value_labels[name] = FLAG_LABELS
        measures[name] = measurement_level(info, kinds, between)
        whole = info.type in (INT, FLAG) or base in kinds or column in between
        formats[name] = _format(data[name], whole)
    pyreadstat.write_sav(data, str(path), column_labels=labels, variable_value_labels=value_labels,
                         variable_measure=measures, variable_format=formats)
    return path


def _codes(column: pd.Series, levels: Sequence[str]) -> pd.Series:
    """A between factor's levels as the codes 1, 2, … of ``levels`` (missing: system-missing)."""
    position = {str(level): float(i) for i, level in enumerate(levels, start=1)}
    return column.map(lambda v: math.nan if pd.isna(v) else position.get(str(v), math.nan)).astype(float)


def _spss_values(column: pd.Series) -> pd.Series:
    """Numbers as float64 (missing: system-missing), everything else as text (missing: empty)."""
    if pd.api.types.is_numeric_dtype(column) or pd.api.types.is_bool_dtype(column):
        return column.astype("Float64").astype(float)
    return column.astype(object).where(column.notna(), "").astype(str)


def _format(values: pd.Series, whole: bool) -> str:
    """``A<w>`` for text; ``F<w>.<d>`` for numbers, d = 0 for ``whole`` columns, else the fewest decimals (at most
    :data:`MAX_DECIMALS`) that write every value exactly."""
    if not pd.api.types.is_numeric_dtype(values):
        return f"A{max([1, *(len(str(v).encode()) for v in values)])}"
    finite = values[np.isfinite(values)].to_numpy(dtype=float)
    decimals = 0 if whole else next((d for d in range(MAX_DECIMALS + 1)
                                     if np.allclose(finite, np.round(finite, d), rtol=0, atol=1e-9)), MAX_DECIMALS)
    digits = len(str(int(np.abs(finite).max()))) if finite.size else 1
    width = digits + (1 if finite.size and finite.min() < 0 else 0) + (decimals + 1 if decimals else 0)
    return f"F{max(width, decimals + 2 if decimals else 1)}.{decimals}"
