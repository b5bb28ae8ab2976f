"""The docs are a reference: each page says what is true now; measurement history lives in one dated log.

The log is docs/changes.md ("Measurement history"). Everywhere else (README.md and every other docs/*.md page):

- no *dated measurement paragraph*: a paragraph (a run of non-blank lines; a table is one paragraph; a paragraph
  that ends with a colon is read with the one it introduces, e.g. a table) that holds both an ISO date
  (``2026-12-07``) and a measured figure (a number with a unit: %, ms, s, ×, ticks, points, trials, MB, fps …; a p
  value ``p = .03``; an F statistic ``F(1, 27)``; a ``ratio 1.6``). The one allowed date beside figures is a
  section's *measurement marker*, ``Measured 2026-12-07 at `9958083```: the day the section's current figures were
  run and the commit whose code ran (or that recorded them), at most one per section (a heading starts a section),
  and the commit must exist in this repository's history. So a benchmark's current figures carry their date; its
  older runs, each with their own date, belong in the log;
- README.md is at most 150 lines;
- the log's dated entries are newest first;
- every relative link and every ``docs/<page>.md`` named points to a file that exists, and every
  ``docs/domain.md §n`` (or ``§n, "Title"``) cited by a page or the code names a section (and a bold or headed part
  of it) of docs/domain.md.
"""

from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
LOG = REPO / "docs" / "changes.md"
README_MAX_LINES = 150

DATE = re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b")
MARKER = re.compile(r"Measured\s+(20\d\d-[01]\d-[0-3]\d)\s+at\s+`([0-9a-f]{7,40})`")
_NUMBER = r"(?<![\w.§-])[−+-]?\d[\d,]*(?:\.\d+)?"
_UNIT = (
    r"(?:%|‰|×|ms|µs|s|min|minutes?|seconds?|hours?|h|ticks?|points?|trials?|pairs?|runs?|fps|Hz|MB|GB|KB|kB|MiB|GiB"
    r"|req/s|/s)"
)
FIGURE = re.compile(
    rf"{_NUMBER}\s?{_UNIT}(?![\w])"  # 4.3 %, 21.5 ms, 3 s, 1.6×, 107 ticks, 28 trials
    r"|\bp\s?[=<>≤]\s?0?\.\d+"  # p = .005, p < .001
    r"|\bF\(\d+,\s?\d+\)"  # F(1, 27)
    r"|\bratios?\s[−+-]?\d"  # ratio 1.62
)
HEADING = re.compile(r"^#{1,6}\s")
LINK = re.compile(r"\]\(([^)\s]+)\)")
DOC_NAME = re.compile(r"\bdocs/([\w.-]+\.md)\b")
DOMAIN_SECTION = re.compile(r"docs/domain\.md`?\s§\s?(\d+)(?:,\s+\"([^\"\n]+)\")?")


@dataclass(frozen=True)
class Finding:
    """One breach of the rule: the page, the paragraph's first line, and why."""

    path: str
    line: int
    reason: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.reason}"


def paragraphs(text: str) -> list[tuple[int, str, int]]:
    """(first line, text, section number) of each paragraph; a heading is its own paragraph and starts a section."""
    found: list[tuple[int, str, int]] = []
    lines: list[str] = []
    start = 0
    section = 0
    for number, line in enumerate([*text.splitlines(), ""], start=1):
        if HEADING.match(line) or not line.strip():
            if lines:
                found.append((start, "\n".join(lines), section))
                lines = []
            if HEADING.match(line):
                section += 1
            continue
        if not lines:
            start = number
        lines.append(line)
    return found


def dated_measurements(path: str, text: str, commit_exists: object = None) -> list[Finding]:
    """The breaches of the one-log rule in a page that is not the log (see the module's docstring)."""
    findings: list[Finding] = []
    markers_per_section: dict[int, int] = {}
    found = paragraphs(text)
    for index, (line, paragraph, section) in enumerate(found):
        for date, commit in MARKER.findall(paragraph):
            markers_per_section[section] = markers_per_section.get(section, 0) + 1
            if markers_per_section[section] > 1:
                findings.append(Finding(path, line, "a second measurement marker in one section (older runs: the log)"))
            if callable(commit_exists) and not commit_exists(commit):
                findings.append(Finding(path, line, f"measurement marker of {date} names no commit: {commit}"))
        unmarked = MARKER.sub("", paragraph)
        introduced = found[index + 1] if paragraph.rstrip().endswith(":") and index + 1 < len(found) else None
        if introduced and introduced[2] == section:
            unmarked += "\n" + MARKER.sub("", introduced[1])
        date_found = DATE.search(MARKER.sub("", paragraph))
        figure = FIGURE.search(unmarked)
        if date_found and figure:
            findings.append(
                Finding(
                    path,
                    line,
                    f"dated measurement paragraph ({date_found.group()}, {figure.group().strip()!r}): "
                    "move it to docs/changes.md, or mark the current figures 'Measured <date> at `<commit>`'",
                )
            )
    return findings


def commit_in_history(commit: str) -> bool:
    done = subprocess.run(
        ["git", "-C", str(REPO), "cat-file", "-e", f"{commit}^{{commit}}"], capture_output=True, check=False
    )
    return done.returncode == 0


def reference_pages() -> list[Path]:
    return [REPO / "README.md", *sorted(p for p in (REPO / "docs").glob("*.md") if p != LOG)]


def has_full_history() -> bool:
    """A clone with its whole history: an export without ``.git`` or a shallow clone cannot check the commits."""
    if not (REPO / ".git").exists():
        return False
    done = subprocess.run(
        ["git", "-C", str(REPO), "rev-parse", "--is-shallow-repository"], capture_output=True, text=True, check=False
    )
    return done.returncode == 0 and done.stdout.strip() == "false"


@pytest.mark.parametrize("page", reference_pages(), ids=lambda p: p.name)
def test_no_dated_measurement_outside_the_log(page: Path) -> None:
    check = commit_in_history if has_full_history() else None
    findings = dated_measurements(page.relative_to(REPO).as_posix(), page.read_text(encoding="utf-8"), check)
    assert not findings, "\n".join(map(str, findings))


def test_readme_is_at_most_150_lines() -> None:
    lines = len((REPO / "README.md").read_text(encoding="utf-8").splitlines())
    assert lines <= README_MAX_LINES, f"README.md has {lines} lines (at most {README_MAX_LINES})"


def test_the_log_is_dated_newest_first() -> None:
    text = LOG.read_text(encoding="utf-8")
    assert "## Measurement history" in text
    for part in text.split("\n## ")[1:]:
        dates = [m.group(1) for m in re.finditer(r"^### (20\d\d-[01]\d-[0-3]\d)", part, flags=re.M)]
        assert dates == sorted(dates, reverse=True), f"not newest first: {dates}"


def test_links_between_docs_resolve() -> None:
    broken: list[str] = []
    for page in [*reference_pages(), LOG]:
        text = page.read_text(encoding="utf-8")
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue
            if not (page.parent / target.split("#")[0]).exists():
                broken.append(f"{page.name}: ({target})")
        for name in DOC_NAME.findall(text):
            if not (REPO / "docs" / name).exists():
                broken.append(f"{page.name}: docs/{name}")
    assert not broken, "\n".join(broken)


def test_cited_domain_sections_exist() -> None:
    """Every ``docs/domain.md §n`` (and ``§n, "Title"``) cited by a reference page or the code names a section and a
    bold or headed part of it that exist; the log keeps the names of its day."""
    domain = (REPO / "docs" / "domain.md").read_text(encoding="utf-8")
    sections = set(re.findall(r"^## §(\d+)", domain, flags=re.M))
    sources = reference_pages()
    for folder in ("planner", "server", "store", "analysis", "study_config", "pilot", "benchmarks", "static"):
        sources += [*(REPO / folder).rglob("*.py"), *(REPO / folder).rglob("*.js")]
    missing = [
        f"{path.relative_to(REPO)}: §{n} {title}"
        for path in sources
        for n, title in DOMAIN_SECTION.findall(path.read_text(encoding="utf-8"))
        if n not in sections or (title and f"**{title}" not in domain and f"### {title}" not in domain)
    ]
    assert not missing, "\n".join(missing)


# The detector itself, on planted pages: it must catch history and let a marked current figure through.

HISTORY = """# Decision time

**Measured 2026-12-07 at `9958083`**: p99 21.5 ms per kitchen.

On 2026-12-05 the p99 was 13.2 ms; after the KB rule it rose to 21.5 ms.
"""


def test_detector_flags_a_planted_history_paragraph() -> None:
    findings = dated_measurements("planted.md", HISTORY)
    assert [f.line for f in findings] == [5]
    assert "dated measurement paragraph (2026-12-05" in findings[0].reason


def test_detector_allows_one_marker_per_section_but_not_two() -> None:
    current = HISTORY.split("\n\nOn ")[0] + "\n"
    assert dated_measurements("planted.md", current) == []
    twice = current + "\nMeasured 2026-12-05 at `6c8e1b4`: p99 13.2 ms.\n"
    assert [f.reason for f in dated_measurements("planted.md", twice)] == [
        "a second measurement marker in one section (older runs: the log)"
    ]
    next_section = current + "\n## Ticks\n\nMeasured 2026-12-05 at `6c8e1b4`: 102.4 ticks.\n"
    assert dated_measurements("planted.md", next_section) == []


def test_detector_flags_dated_tables_and_statistics_and_ignores_dates_without_figures() -> None:
    table = "| date | p99 |\n|---|---|\n| 2026-12-05 | 13.2 ms |\n"
    assert len(dated_measurements("planted.md", table)) == 1
    statistic = "The pilot of 2026-12-04: robot × kitchen F(1, 27) = 4.53.\n"
    assert len(dated_measurements("planted.md", statistic)) == 1
    rule = "The abstract search ran as an option until 2026-12-07 (docs/changes.md), in §5.\n"
    assert dated_measurements("planted.md", rule) == []
    lead_in = "2026-12-05 06:37 UTC, three runs in a row:\n\n| run | ticks |\n|---|---|\n| 1 | 866 ticks |\n"
    assert [f.line for f in dated_measurements("planted.md", lead_in)] == [1]
    assert dated_measurements("planted.md", lead_in.replace(":\n\n", ".\n\n")) == []


def test_detector_rejects_a_marker_naming_no_commit() -> None:
    page = "Measured 2026-12-07 at `0000000`: 4.3 %.\n"
    findings = dated_measurements("planted.md", page, lambda commit: False)
    assert [f.reason for f in findings] == ["measurement marker of 2026-12-07 names no commit: 0000000"]
