"""Kitchens named by a study: a shipped layout by name, or a layout file by path relative to the study.

The layout's grid is parsed here with the same checker ``serve`` and the game use
(:func:`planner.layout.parse_layout`), so ``steakhouse study validate`` refuses every kitchen ``serve`` would
refuse, naming the file, line and column of every problem (:class:`KitchenFileError`). The file's SHA-256
is part of the resolved study, so editing a kitchen changes the study's config hash (a trial's record says
exactly which grid it was played on).
"""

from __future__ import annotations

import hashlib
import re
from pathlib import Path
from typing import Annotated, Any

from pydantic import BeforeValidator, Field, ValidationInfo

from planner.layout import LayoutError, parse_layout
from study_config.study.base import Loc, StudyModel, duplicate_problems, raise_problems

LAYOUT_SUFFIX = ".layout"
_NAME = re.compile(r"^[A-Za-z0-9_-]+$")
MAX_KITCHEN_NAME = 64
"""The longest kitchen name (a layout file's stem): the store keeps it with every trial (``trials.kitchen``)."""


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

    name: str = Field(pattern=_NAME.pattern, max_length=MAX_KITCHEN_NAME)
    """The kitchen's name in condition ids and exports: the layout file's stem (``none_3``)."""
    source: str
    """The entry as written in the study: a shipped name or a path relative to the study file."""
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")
    """Digest of the layout file's bytes when the study was loaded."""
    path: Path
    """Absolute path of the layout file; machine-specific, so left out of the config hash."""


class KitchenFileError(ValueError):
    """A kitchen file whose grid cannot be played: ``problems`` lists every problem as ``(where, reason)``,
    ``where`` the entry as written with the line and column (``my/kitchen.layout:3:7``)."""

    def __init__(self, problems: tuple[tuple[str, str], ...]) -> None:
        super().__init__("; ".join(f"({where}): {reason}" for where, reason in problems))
        self.problems = problems


def resolve_kitchen(entry: str, base_dir: Path) -> Kitchen:
    """Resolve a study's kitchen entry and check its grid; ``ValueError`` with a readable reason when it names
    nothing, :class:`KitchenFileError` when its grid is invalid.

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
    if len(path.stem) > MAX_KITCHEN_NAME:
        raise ValueError(f"kitchen file name {path.name!r}: at most {MAX_KITCHEN_NAME} characters before "
                         f"{LAYOUT_SUFFIX} (the name is stored with every trial)")
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ValueError(f"cannot read kitchen file {path}: {exc.strerror}") from exc
    shown = entry if not is_name else f"{entry}{LAYOUT_SUFFIX}"
    try:
        parse_layout(data.decode("utf-8"), name=path.stem, source=shown)
    except UnicodeDecodeError as exc:
        raise KitchenFileError(((shown, f"not a UTF-8 text file ({exc.reason})"),)) from exc
    except LayoutError as exc:
        raise KitchenFileError(tuple((p.where(shown), p.reason) for p in exc.problems)) from exc
    return Kitchen(name=path.stem, source=entry, sha256=hashlib.sha256(data).hexdigest(), path=path.resolve())


def resolve_kitchens(entries: list[Any] | tuple[Any, ...], base_dir: Path,
                     ) -> tuple[tuple[Any, ...] | None, list[tuple[Loc, str, str | None]]]:
    """Resolve every entry of a study's ``kitchens``: the kitchens, or ``None`` and every problem at once
    (``(location, reason, where)``: an unknown name, a missing file, each problem of an invalid grid, a
    duplicate), so one bad entry never hides another's problem."""
    resolved: list[Any] = []
    problems: list[tuple[Loc, str, str | None]] = []
    for index, entry in enumerate(entries):
        try:
            resolved.append(_kitchen_before(entry, base_dir))
        except KitchenFileError as exc:
            problems += [((index,), reason, where) for where, reason in exc.problems]
            resolved.append(None)
        except ValueError as exc:
            problems.append(((index,), str(exc), None))
            resolved.append(None)
    names = [k.name if isinstance(k, Kitchen) else entry_name(entries[i]) for i, k in enumerate(resolved)]
    problems += [(loc, reason, None) for loc, reason in duplicate_problems(names, "kitchen")
                 if names[int(loc[0])] is not None]
    problems.sort(key=lambda p: p[0])
    return (None if problems else tuple(resolved)), problems


def entry_name(entry: Any) -> str | None:
    """The kitchen name an entry would have (its file stem), for duplicates among entries that failed."""
    if isinstance(entry, str) and entry.strip():
        return Path(entry).stem if entry.endswith(LAYOUT_SUFFIX) or "/" in entry else entry
    if isinstance(entry, dict) and isinstance(entry.get("name"), str):
        return str(entry["name"])
    return None


def base_dir_of(info: ValidationInfo) -> Path:
    """The study file's folder, from the validation context (the working directory without one)."""
    context = info.context if isinstance(info.context, dict) else {}
    return Path(context.get("base_dir", Path.cwd()))


def _kitchen_before(value: Any, base_dir: Path) -> Any:
    if isinstance(value, (Kitchen, dict)):
        return value
    if not isinstance(value, str):
        raise ValueError(f"a kitchen is a name or a path (text), got {value!r}")
    return resolve_kitchen(value, base_dir)


def _kitchen_entry(value: Any, info: ValidationInfo) -> Any:
    """One kitchen field: every problem of an invalid grid reported at the field, each with its place."""
    try:
        return _kitchen_before(value, base_dir_of(info))
    except KitchenFileError as exc:
        raise_problems([((), reason) for _, reason in exc.problems], value, [where for where, _ in exc.problems])
        raise


KitchenEntry = Annotated[Kitchen, BeforeValidator(_kitchen_entry)]
"""A kitchen written as a string in YAML (name or path), resolved against ``context["base_dir"]``."""
