"""Study definitions (YAML), the kitchens shipped with the product, and questionnaires.

Kitchens are found by name (``none_3`` → ``study_config/layouts/none_3.layout``) or by path.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from planner.layout import Layout, LayoutError, LayoutProblem, parse_layout

STUDY_DIR = Path(__file__).resolve().parent
LAYOUT_DIR = STUDY_DIR / "layouts"


def layout_names() -> tuple[str, ...]:
    """The names of the shipped kitchens, sorted."""
    return tuple(sorted(p.stem for p in LAYOUT_DIR.glob("*.layout")))


def resolve_layout_path(name_or_path: str | Path, base: Path | None = None) -> Path:
    """A shipped kitchen's file for a bare name, else the path (relative to ``base`` if given)."""
    text = str(name_or_path)
    if "/" not in text and not text.endswith(".layout"):
        return LAYOUT_DIR / f"{text}.layout"
    path = Path(text)
    if not path.is_absolute() and base is not None:
        path = base / path
    return path


def load_layout(name_or_path: str | Path, base: Path | None = None) -> Layout:
    """Load a kitchen by shipped name or file path. Raises :class:`LayoutError` (file and every problem)."""
    path = resolve_layout_path(name_or_path, base)
    return _load_path(str(path.resolve()) if path.exists() else str(path))


@lru_cache(maxsize=64)
def _load_path(path_text: str) -> Layout:
    path = Path(path_text)
    if not path.is_file():
        known = ", ".join(layout_names())
        raise LayoutError(str(path), (LayoutProblem(f"no such layout file (shipped kitchens: {known})"),))
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise LayoutError(str(path), (LayoutProblem(f"not a UTF-8 text file ({exc.reason})"),)) from exc
    return parse_layout(text, name=path.stem, source=str(path))
