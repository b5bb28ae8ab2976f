"""Reading a study's YAML safely, remembering where each field was written.

``yaml.SafeLoader`` only (no Python objects, never ``eval``). Besides the data, the reader returns the
line of every key and list item, so a problem found later can point at its line, and it reports
repeated keys in one mapping, which plain YAML loading would silently resolve to the last one.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import yaml

Loc = tuple[str | int, ...]

_MERGE_TAG = "tag:yaml.org,2002:merge"
_INT_TAG = "tag:yaml.org,2002:int"


class YamlSyntaxError(Exception):
    """The text is not valid YAML; ``line`` and ``column`` are 1-based."""

    def __init__(self, message: str, line: int | None, column: int | None) -> None:
        super().__init__(message)
        self.message = message
        self.line = line
        self.column = column


@dataclass(frozen=True)
class ParsedYaml:
    """The loaded data, the line of each location in it, and repeated keys (location, line)."""

    data: Any
    lines: dict[Loc, int] = field(default_factory=dict)
    repeated_keys: list[tuple[Loc, int]] = field(default_factory=list)

    def line_of(self, loc: Loc) -> int | None:
        """Line of ``loc``, or of its nearest written ancestor (a missing field points at its parent)."""
        for end in range(len(loc), 0, -1):
            if loc[:end] in self.lines:
                return self.lines[loc[:end]]
        return None


def parse_yaml(text: str) -> ParsedYaml:
    """Parse one YAML document; raise :class:`YamlSyntaxError` with its position when it is invalid."""
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return ParsedYaml(data=None)
        parsed = ParsedYaml(data=None)
        _walk(node, (), parsed, set())
        data = loader.construct_document(node)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        reason = "; ".join(part for part in (exc.context, exc.problem) if part) or "invalid YAML"
        if mark is None:
            raise YamlSyntaxError(reason, None, None) from exc
        raise YamlSyntaxError(reason, mark.line + 1, mark.column + 1) from exc
    except yaml.YAMLError as exc:
        raise YamlSyntaxError(str(exc), None, None) from exc
    finally:
        loader.dispose()
    return replace(parsed, data=data)


def _key(node: yaml.Node) -> str | int | None:
    if not isinstance(node, yaml.ScalarNode):
        return None
    text = str(node.value)
    if node.tag == _INT_TAG:
        try:
            return int(text.replace("_", ""), 0)
        except ValueError:
            return text
    return text


def _walk(node: yaml.Node, loc: Loc, parsed: ParsedYaml, seen: set[int]) -> None:
    if id(node) in seen:
        return
    seen.add(id(node))
    if isinstance(node, yaml.MappingNode):
        keys: set[str | int] = set()
        for key_node, value_node in node.value:
            key = _key(key_node)
            if key_node.tag == _MERGE_TAG or key is None:
                continue
            line = key_node.start_mark.line + 1
            if key in keys:
                parsed.repeated_keys.append(((*loc, key), line))
            keys.add(key)
            parsed.lines.setdefault((*loc, key), line)
            _walk(value_node, (*loc, key), parsed, seen)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            parsed.lines.setdefault((*loc, index), item.start_mark.line + 1)
            _walk(item, (*loc, index), parsed, seen)
