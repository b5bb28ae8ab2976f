"""Kitchens named by a study: a shipped layout by name, or a layout file by path relative to the study.

Only existence is checked here; the layout's grid is parsed and validated by ``planner`` when a trial
starts. The file's SHA-256 is part of the resolved study, so editing a kitchen changes the study's
config hash (a trial's record says exactly which grid it was played on).
"""

from __future__ import annotations

import hashlib
import re
from pathlib import Path
from typing import Annotated, Any

from pydantic import BeforeValidator, Field, ValidationInfo

from server.study.base import StudyModel

LAYOUT_SUFFIX = ".layout"
_NAME = re.compile(r"^[A-Za-z0-9_-]+$")


def layout_dir() -> Path:
    """The folder of the kitchens shipped with the product (``study_config/layouts``)."""
    try:
        from study_config import LAYOUT_DIR
    except ImportError:
        return Path(__file__).resolve().parents[2] / "study_config" / "layouts"
    return Path(LAYOUT_DIR)


def shipped_kitchens() -> tuple[str, ...]:
    """Names of the shipped kitchens, sorted."""
    return tuple(sorted(p.stem for p in layout_dir().glob(f"*{LAYOUT_SUFFIX}")))


class Kitchen(StudyModel):
    """A kitchen as resolved from the study file."""

    name: str = Field(pattern=_NAME.pattern)
    """The kitchen's name in condition ids and exports: the layout file's stem (``none_3``)."""
    source: str
    """The entry as written in the study: a shipped name or a path relative to the study file."""
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")
    """Digest of the layout file's bytes when the study was loaded."""
    path: Path
    """Absolute path of the layout file; machine-specific, so left out of the config hash."""


def resolve_kitchen(entry: str, base_dir: Path) -> Kitchen:
    """Resolve a study's kitchen entry; ``ValueError`` with a readable reason when it names nothing.

    A bare name (no folder separator, no ``.layout`` suffix) is a shipped kitchen; anything else is a
    path, relative to ``base_dir`` (the study file's folder) unless absolute.
    """
    if not entry.strip():
        raise ValueError("empty kitchen name")
    is_name = "/" not in entry and not entry.endswith(LAYOUT_SUFFIX)
    if is_name:
        path = layout_dir() / f"{entry}{LAYOUT_SUFFIX}"
        if not path.is_file():
            raise ValueError(f"unknown kitchen {entry!r}; shipped kitchens: {', '.join(shipped_kitchens())}")
    else:
        path = (base_dir / entry).resolve()
        if not path.is_file():
            raise ValueError(f"no kitchen file at {path}")
    if not _NAME.match(path.stem):
        raise ValueError(f"kitchen file name {path.name!r} must use only letters, digits, '-' and '_'")
    try:
        digest = hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError as exc:
        raise ValueError(f"cannot read kitchen file {path}: {exc.strerror}") from exc
    return Kitchen(name=path.stem, source=entry, sha256=digest, path=path.resolve())


def _kitchen_before(value: Any, info: ValidationInfo) -> Any:
    if isinstance(value, (Kitchen, dict)):
        return value
    if not isinstance(value, str):
        raise ValueError(f"a kitchen is a name or a path (text), got {value!r}")
    context = info.context if isinstance(info.context, dict) else {}
    base_dir = Path(context.get("base_dir", Path.cwd()))
    return resolve_kitchen(value, base_dir)


KitchenEntry = Annotated[Kitchen, BeforeValidator(_kitchen_before)]
"""A kitchen written as a string in YAML (name or path), resolved against ``context["base_dir"]``."""
