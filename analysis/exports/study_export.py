"""``export_study``: a study's tidy CSV files and their data dictionary, written to one folder.

Files (columns in ``data_dictionary.md`` / ``data_dictionary.csv``, written alongside)::

    ticks.csv         one row per stored world step, every trial attempt
    trials.csv        one row per trial attempt (practice and main) with its measures
    cells.csv         participant × condition: the repeated-measures ANOVA input
    wide.csv          one row per participant: a column per between factor, <measure>__<robot>__<kitchen> per
                      within cell (JASP / SPSS)
    wide.sav          the same as an SPSS file, with variable and value labels (analysis.exports.spss)
    answers.csv       questionnaire answers
    participants.csv  every participant with flags and progress
    excluded.csv      participants not in the complete-case analysis, with the reason

The store is read in one transaction on an engine of its own (on SQLite a deferred read: a live server
keeps writing meanwhile).
"""

from __future__ import annotations

import csv
import io
import tempfile
import zipfile
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import pandas as pd
from sqlalchemy import Engine
from sqlalchemy.exc import OperationalError

from analysis.exports.dataset import FILES, Dataset, build_dataset
from analysis.exports.dictionary import render_markdown, rows
from analysis.exports.dictionary_items import spreadsheet_safe
from analysis.exports.spss import SAV_FILE, write_sav
from analysis.source.store_reader import StoreReadError, open_engine

DICTIONARY_FILES = ("data_dictionary.md", "data_dictionary.csv")


@dataclass(frozen=True, slots=True, eq=False)
class ExportResult:
    dataset: Dataset
    out_dir: Path
    files: tuple[Path, ...]


def read_dataset(source: Engine | str, study_id: str, include_invalid: bool = False,
                 include_pilot: bool = False) -> Dataset:
    """Build the export's tables from the store at ``source`` (an engine or a database URL); invalid main
    trials enter ``cells.csv`` only with ``include_invalid``; simulated pilot participants are left out unless
    ``include_pilot``."""
    engine = source if isinstance(source, Engine) else open_engine(source)
    try:
        try:
            conn = engine.connect()
        except OperationalError as exc:
            raise StoreReadError(f"cannot connect to the store: {exc.orig}") from exc
        with conn:
            return build_dataset(conn, study_id, include_invalid, include_pilot)
    finally:
        if engine is not source:
            engine.dispose()


def export_study(source: Engine | str, study_id: str, out_dir: Path | str,
                 include_invalid: bool = False, include_pilot: bool = False) -> ExportResult:
    """Write every file of the export of ``study_id`` into ``out_dir`` (created if needed); invalid main trials
    are listed in ``excluded.csv``, and in ``cells.csv`` only with ``include_invalid``; simulated pilot
    participants only with ``include_pilot``."""
    dataset = read_dataset(source, study_id, include_invalid, include_pilot)
    return write_dataset(dataset, out_dir)


def write_dataset(dataset: Dataset, out_dir: Path | str) -> ExportResult:
    """Write the tables of ``dataset`` and the data dictionary into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files: list[Path] = []
    for name in FILES:
        _csv_safe(dataset.tables[name], name).to_csv(out / name, index=False)
        files.append(out / name)
    stamp = datetime.now(UTC).isoformat(timespec="seconds")
    markdown = render_markdown(dataset.columns, dataset.study_id, stamp, dataset.config)
    (out / DICTIONARY_FILES[0]).write_text(markdown, encoding="utf-8")
    with (out / DICTIONARY_FILES[1]).open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=["file", "column", "type", "unit", "description"])
        writer.writeheader()
        writer.writerows(rows(dataset.columns, dataset.config))
    groups = {f: dataset.design.between_levels(f) for f in dataset.design.between}
    files.insert(files.index(out / "wide.csv") + 1, write_sav(dataset.tables["wide.csv"], dataset.columns["wide.csv"],
                                                               dataset.config, out / SAV_FILE, groups))
    files += [out / name for name in DICTIONARY_FILES]
    return ExportResult(dataset, out, tuple(files))


TEXT_COLUMNS = {"answers.csv": ("text",)}
"""Columns holding what participants typed: written spreadsheet-safe (see ``analysis.exports.dictionary``)."""


def _csv_safe(table: pd.DataFrame, name: str) -> pd.DataFrame:
    """``table`` with its participant-typed text columns made safe to open in a spreadsheet. Quoting of
    commas, quotes and line breaks is the CSV writer's (RFC 4180 style, so every reader gets the text back)."""
    typed = [c for c in TEXT_COLUMNS.get(name, ()) if c in table.columns]
    if not typed:
        return table
    safe = table.copy()
    for column in typed:
        safe[column] = safe[column].map(spreadsheet_safe)
    return safe


def export_zip(source: Engine | str, study_id: str) -> bytes:
    """The export of ``study_id`` as a zip archive, files under the folder ``<study_id>_export/``."""
    with tempfile.TemporaryDirectory(prefix="steakhouse-export-") as tmp:
        result = export_study(source, study_id, Path(tmp) / "export")
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
            for path in result.files:
                archive.write(path, f"{study_id}_export/{path.name}")
    return buffer.getvalue()
