"""Reading a stored knowledge base back (``planner.kb.KnowledgeBase.to_dict`` has no inverse yet).

Needed to resume a trial from its last stored tick with the participant's modelled KB intact, streaks
(consecutive ticks in view) included.
"""

from __future__ import annotations

from typing import Any

from planner.kb import ROBOT_KEY, KnowledgeBase
from planner.objects import OBJECTS
from planner.state import AgentState


def kb_from_dict(data: dict[str, Any]) -> KnowledgeBase:
    """The inverse of ``KnowledgeBase.to_dict``; ``ValueError`` on unknown objects."""
    objects = []
    for item in data["objects"]:
        if item["obj"] not in OBJECTS:
            raise ValueError(f"unknown object {item['obj']!r}")
        objects.append(((int(item["pos"][0]), int(item["pos"][1])), item["obj"]))
    streaks = []
    for key, occupant, count in data.get("streaks", []):
        pos = (int(key[0]), int(key[1]))
        streaks.append((ROBOT_KEY if pos == ROBOT_KEY else pos, occupant, int(count)))
    robot = data.get("robot")
    return KnowledgeBase(
        objects=tuple(sorted(objects)),
        grills=tuple(_count(v) for v in data["grills"]),
        boards=tuple(_count(v) for v in data["boards"]),
        sinks=tuple(_count(v) for v in data["sinks"]),
        robot=None if robot is None else AgentState.from_dict(robot),
        streaks=tuple(streaks),
    )


def _count(value: Any) -> int | None:
    return None if value is None else int(value)
