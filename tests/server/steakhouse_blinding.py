"""The blinding probe: a participant's browser, recorded byte for byte, searched for anything that names the
study's conditions (``docs/protocol.md`` §1, "Blinding").

:class:`Recorder` keeps every REST answer and websocket frame a participant received; :func:`forbidden_names`
lists what must never appear in them (condition ids, robots, kitchens, planner names, the study's title and
the keys of the condition order); :func:`hits` finds them as whole words. A name that is also a word of the
participant protocol itself (the ``stay`` robot and the ``stay`` interrupt key) cannot be told apart from it
and is reported as exempt instead of searched.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

PLANNER_WORDS = ("qmdp", "QMDP", "QmdpRobot", "no-rollout", "fov-aware")
"""Words naming the planners' machinery beside the robot names themselves (the word "planner" alone is not one:
the client's comments cite ``planner/fov.py`` for the FOV rule every participant is told)."""
ORDER_KEYS = ("condition_order", "order_index", "condition_id")
"""Keys that would carry the participant's condition order or their condition."""


@dataclass
class Recorder:
    """Everything a participant's browser received: ``(where, bytes)`` in arrival order."""

    received: list[tuple[str, bytes]] = field(default_factory=list)

    def add(self, where: str, data: bytes | str) -> None:
        self.received.append((where, data.encode("utf-8") if isinstance(data, str) else data))

    @property
    def messages(self) -> int:
        return len(self.received)

    @property
    def bytes(self) -> int:
        return sum(len(data) for _, data in self.received)


def forbidden_names(study: Any, protocol_words: set[str]) -> tuple[dict[str, str], dict[str, str]]:
    """``(forbidden, exempt)``: name → what it names. ``protocol_words`` are the words the participant
    protocol uses itself (subtasks, interrupt keys, trial kinds …): a name among them is exempt."""
    names: dict[str, str] = {study.title: "the study's title"}
    for condition in study.conditions:
        names[condition.id] = "a condition"
        names[condition.robot] = "a robot"
        names[condition.kitchen] = "a kitchen"
    for practice in study.practice:
        names[practice.robot] = "a robot"
        names[practice.kitchen.name] = "a kitchen"
    for word in PLANNER_WORDS:
        names[word] = "the planner"
    for key in ORDER_KEYS:
        names[key] = "the condition order"
    exempt = {name: what for name, what in names.items() if name in protocol_words}
    return {name: what for name, what in names.items() if name not in exempt}, exempt


def hits(recorder: Recorder, forbidden: dict[str, str]) -> list[str]:
    """Every received message containing a forbidden name as a whole word: ``where: name (what)``."""
    patterns = {name: re.compile(r"(?<![A-Za-z0-9_])" + re.escape(name) + r"(?![A-Za-z0-9_])")
                for name in forbidden}
    found = []
    for where, data in recorder.received:
        text = data.decode("utf-8", errors="replace")
        found += [f"{where}: {name!r} ({forbidden[name]})" for name, pattern in patterns.items()
                  if pattern.search(text)]
    return found
