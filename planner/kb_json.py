"""The KB rule's memory (:class:`planner.kb_rule.Tracking`) as JSON, for the stored KB of every tick (resuming a
trial reads it back: docs/domain.md §3)."""

from __future__ import annotations

from typing import Any

from planner.kb_rule import RobotSnap, Snap, Tracking
from planner.kb_things import Things
from planner.state import AgentState


def _snap(s: Snap) -> list[Any]:
    return [s.cell[0], s.cell[1], s.kind, s.state]


def _unsnap(data: list[Any]) -> Snap:
    x, y, kind, state = data
    return Snap((int(x), int(y)), str(kind), None if state is None else int(state))


def _robot(r: RobotSnap) -> dict[str, Any]:
    return {"agent": r.state.to_dict(), "held_id": r.held_id, "held": None if r.held is None else _snap(r.held)}


def _unrobot(data: dict[str, Any]) -> RobotSnap:
    held = data.get("held")
    held_id = data.get("held_id")
    return RobotSnap(AgentState.from_dict(data["agent"]), None if held_id is None else int(held_id),
                     None if held is None else _unsnap(held))


def tracking_to_dict(t: Tracking) -> dict[str, Any]:
    return {
        "things": t.things.to_list(),
        "track": [[i, _snap(s), n] for i, s, n in t.track],
        "held": None if t.held is None else [t.held[0], _snap(t.held[1])],
        "robot": None if t.robot is None else [_robot(t.robot[0]), t.robot[1]],
        "untrack": [[i, _snap(s)] for i, s in t.untrack],
        "robot_untrack": None if t.robot_untrack is None else _robot(t.robot_untrack),
        "remove": [[i, _snap(s), n] for i, s, n in t.remove],
        "robot_remove": None if t.robot_remove is None else [_robot(t.robot_remove[0]), t.robot_remove[1]],
        "believed": [[i, _snap(s)] for i, s in t.believed],
    }


def tracking_from_dict(data: dict[str, Any]) -> Tracking:
    """The inverse of :func:`tracking_to_dict`; ``ValueError`` (or ``KeyError``/``TypeError``) on a malformed
    one."""
    held, robot, robot_remove = data.get("held"), data.get("robot"), data.get("robot_remove")
    robot_untrack = data.get("robot_untrack")
    return Tracking(
        things=Things.from_list(list(data["things"])),
        track=tuple((int(i), _unsnap(s), int(n)) for i, s, n in data.get("track", [])),
        held=None if held is None else (int(held[0]), _unsnap(held[1])),
        robot=None if robot is None else (_unrobot(robot[0]), int(robot[1])),
        untrack=tuple((int(i), _unsnap(s)) for i, s in data.get("untrack", [])),
        robot_untrack=None if robot_untrack is None else _unrobot(robot_untrack),
        remove=tuple((int(i), _unsnap(s), int(n)) for i, s, n in data.get("remove", [])),
        robot_remove=None if robot_remove is None else (_unrobot(robot_remove[0]), int(robot_remove[1])),
        believed=tuple((int(i), _unsnap(s)) for i, s in data.get("believed", [])),
    )
