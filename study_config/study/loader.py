"""Loading a study file: YAML → :class:`Study`, or every problem found, each naming file, field and reason."""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from os import PathLike
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from study_config.study.base import STUDY_ERROR, Loc, StudyModel
from study_config.study.models import Study
from study_config.study.yaml_source import ParsedYaml, YamlSyntaxError, parse_yaml

_BOOL_HINT = "; YAML reads yes/no/on/off as true/false, so quote such text"
_PLAIN_MESSAGES = {
    "missing": "required field is missing",
    "tuple_type": "should be a list",
    "list_type": "should be a list",
    "model_type": "should be a mapping of fields",
    "model_attributes_type": "should be a mapping of fields",
    "dict_type": "should be a mapping",
}


@dataclass(frozen=True)
class StudyProblem:
    """One thing wrong with a study file."""

    file: str
    """The file as it was named to the loader."""
    path: str
    """Field path (``robots[1]``, ``questionnaires[0].items[2].scale``); empty for the file as a whole."""
    reason: str
    """What is wrong, in words."""
    line: int | None = None
    """1-based line of the field (or its nearest written parent) when known."""
    source: str | None = None
    """The place in another file the problem is in, e.g. a kitchen layout's ``my/kitchen.layout:3:7``."""

    def __str__(self) -> str:
        where = f" (line {self.line})" if self.line is not None and self.path else ""
        if not self.path:
            return f"{self.file}: {self.reason}"
        source = f" ({self.source})" if self.source else ""
        return f"{self.file}: {self.path}{source}: {self.reason}{where}"


class StudyConfigError(Exception):
    """A study file that cannot be used; ``problems`` lists every problem found."""

    def __init__(self, problems: list[StudyProblem]) -> None:
        super().__init__("\n".join(str(p) for p in problems))
        self.problems = tuple(problems)


def load_study(path: str | PathLike[str]) -> Study:
    """The study in ``path``; :class:`StudyConfigError` listing every problem when it is invalid."""
    study, problems = _load(Path(path), str(path))
    if problems or study is None:
        raise StudyConfigError(problems)
    return study


def validate_study_file(path: str | PathLike[str]) -> list[StudyProblem]:
    """Every problem in the study file at ``path`` (an empty list when it is valid)."""
    return _load(Path(path), str(path))[1]


def _load(path: Path, file: str) -> tuple[Study | None, list[StudyProblem]]:
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        return None, [StudyProblem(file, "", f"cannot read the file: {exc}")]
    try:
        parsed = parse_yaml(text)
    except YamlSyntaxError as exc:
        where = f" at line {exc.line}, column {exc.column}" if exc.line is not None else ""
        return None, [StudyProblem(file, "", f"invalid YAML{where}: {exc.message}", exc.line)]
    if not isinstance(parsed.data, dict):
        found = "the file is empty" if parsed.data is None else f"found a {type(parsed.data).__name__}"
        return None, [StudyProblem(file, "", f"a study file must be a mapping of fields; {found}", 1)]
    problems = [
        StudyProblem(file, render_path(loc), "key written more than once (only the last would count)", line)
        for loc, line in parsed.repeated_keys
    ]
    try:
        study = Study.model_validate(parsed.data, context={"base_dir": path.parent.resolve()})
    except ValidationError as exc:
        problems += _problems(exc, file, parsed)
        return None, sorted(problems, key=lambda p: p.line or 0)
    return (None if problems else study), problems


def _problems(exc: ValidationError, file: str, parsed: ParsedYaml) -> list[StudyProblem]:
    problems = []
    for error in exc.errors():
        loc: Loc = tuple(error["loc"])
        reason, source = _reason(error), _source(error)
        if loc[-1:] == ("[key]",):
            loc, reason = loc[:-1], f"key: {reason}"
        problems.append(StudyProblem(file, render_path(loc), reason, parsed.line_of(loc), source))
    return problems


def render_path(loc: Loc) -> str:
    """``("questionnaires", 0, "items", 2, "scale")`` → ``questionnaires[0].items[2].scale``."""
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _source(error: Any) -> str | None:
    """Where in another file (a kitchen layout) the problem is, when it is there."""
    ctx = error.get("ctx") or {}
    where = ctx.get("where") if error["type"] == STUDY_ERROR else None
    return str(where) if where else None


def _reason(error: Any) -> str:
    kind = error["type"]
    if kind == "value_error":
        return str(error["ctx"]["error"])
    if kind == STUDY_ERROR:
        return str(error["msg"])
    if kind == "extra_forbidden":
        name = str(error["loc"][-1])
        close = difflib.get_close_matches(name, sorted(_field_names()), n=1)
        return "unknown field" + (f"; did you mean {close[0]!r}?" if close else "")
    message = _PLAIN_MESSAGES.get(kind) or str(error["msg"]).replace("Input should", "should", 1)
    value = error.get("input")
    if kind != "missing" and (value is None or isinstance(value, (str, int, float, bool))):
        hint = _BOOL_HINT if isinstance(value, bool) else ""
        message += f" (got {value!r}{hint})"
    return message


def _field_names() -> set[str]:
    names: set[str] = set()
    pending: list[type[BaseModel]] = [Study]
    while pending:
        model = pending.pop()
        for name, info in model.model_fields.items():
            names.add(name)
            for arg in _classes(info.annotation):
                if issubclass(arg, StudyModel) and not set(arg.model_fields) <= names:
                    pending.append(arg)
    return names


def _classes(annotation: Any) -> list[type]:
    if isinstance(annotation, type):
        return [annotation]
    return [c for arg in getattr(annotation, "__args__", ()) for c in _classes(arg)]
