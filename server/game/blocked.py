"""Why a chosen subtask is not getting anywhere, judged only from what the participant can see.

- :func:`hands_reason`: the subtask cannot work with what the cook holds (``server.game.needs``).
- :func:`interaction_reason`: interacting with the faced cell would do nothing now, and why ("The onion is not
  chopped yet", "The grill is busy"). The faced cell is always in view (it lies straight ahead, at angle 0 of
  the field of view, docs/domain.md §2), so naming its state reveals nothing hidden.
- :func:`progressed`: whether a step moved the subtask on: the cook moved, turned, changed what it holds or
  did something, or the faced cell changed (a steak cooking, the robot chopping).
- :class:`Stall`: counts the subtask's steps without progress; after the study's ``blocked_subtask_seconds``
  the subtask ends itself with the last reason (:mod:`server.game.controller`).
- :func:`explained`: a reason the world's events explain better — the robot took, filled or worked the cell
  (``server.game.changes``).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Literal

from planner.events import Event, EventKind
from planner.geometry import Pos
from planner.kb import KnowledgeBase
from planner.layout import Layout, Terrain
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import WorldState
from planner.subtasks import Subtask
from server.game.changes import Category, Changes
from server.game.needs import NEEDS, NOTHING, SOMETHING, hands_fit
from server.protocol.server import BlockedReason

Intent = Literal["interact", "move", "wait", "no_target", "look", "idle"]
"""What the cook tried this step for its subtask: interact with the target it faces, move toward it, wait for
the way to clear, nothing because no target is known, or (the paper's clock) look at a target the participant
sees but does not know yet (``idle``: no subtask)."""

NOTICE_AFTER_MOVES = 3
"""Steps a move must stay blocked before the participant is told (the robot often steps aside at once)."""
PATIENCE_STEPS = NOTICE_AFTER_MOVES
"""The paper's clock: steps a task's path may wait for the robot to clear the way (the world steps for them, the
robot moving on) before the task ends with the reason (``ParticipantController.refuse_step``)."""


@dataclass(frozen=True, slots=True)
class Reason:
    """Why nothing happened: a reason code, the object it names (needed, held, or what the robot took, put or
    worked on), if any, and for what the robot did the place (``grill``, ``board``, ``sink``, ``counter``)."""

    code: BlockedReason
    item: str | None = None
    place: str | None = None


@dataclass(frozen=True, slots=True)
class Blocked:
    """A subtask that is not getting anywhere: ``ended`` when it ended itself, else a notice while it goes on;
    ``subtask`` ``None``: an ``interact`` key that did nothing (a notice)."""

    subtask: Subtask | None
    reason: Reason
    ended: bool


def hands_reason(subtask: Subtask, held: str | None) -> Reason | None:
    """Why ``subtask`` cannot work with ``held`` in hand (``None``: it can)."""
    if hands_fit(subtask, held):
        return None
    need = NEEDS[subtask]
    if need == NOTHING:
        return Reason("hands_full", held)
    if need == SOMETHING:
        return Reason("hands_empty")
    return Reason("needs_item", need)


def interaction_reason(layout: Layout, world: WorldState, rules: Rules) -> Reason | None:
    """Why the participant's cook interacting with the cell it faces would do nothing (``None``: it would do
    something), from that cell's state in ``world`` and what the cook holds (docs/domain.md §1's table)."""
    human = world.human
    faced = human.facing.ahead(human.pos)
    held = human.held
    entry = layout.stations.get(faced)
    if entry is None:
        return Reason("nothing_there")
    kind, index = entry
    if kind is Terrain.COUNTER:
        return Reason("counter_empty") if held is None and world.object_at(faced) is None else None
    if kind in (Terrain.ONION, Terrain.MEAT, Terrain.PLATE):
        return Reason("hands_full", held) if held is not None else None
    if kind is Terrain.GRILL:
        return _grill(world.grills[index], held, rules)
    if kind is Terrain.BOARD:
        return _board(world.boards[index], held, rules)
    if kind is Terrain.SINK:
        return _sink(world.sinks[index], held)
    if kind is Terrain.SERVE:
        return None if held == DISH and world.orders_left > 0 else Reason("needs_item", DISH)
    return Reason("nothing_there")


def _grill(status: int | None, held: str | None, rules: Rules) -> Reason | None:
    if status is None:
        if held == CLEAN_PLATE:
            return Reason("no_steak")
        return None if held == MEAT else Reason("needs_item", MEAT)
    if held == MEAT:
        return Reason("grill_busy")
    if status < rules.cook_time:
        return Reason("steak_cooking")
    return None if held == CLEAN_PLATE else Reason("needs_item", CLEAN_PLATE)


def _board(status: int | None, held: str | None, rules: Rules) -> Reason | None:
    if status is None:
        if held == ONION:
            return None
        if held == STEAK_PLATE:
            return Reason("no_garnish")
        return Reason("nothing_to_chop") if held is None else Reason("needs_item", ONION)
    if held == ONION:
        return Reason("board_busy")
    if status < rules.chop_time:
        if held is None:
            return None
        return Reason("not_chopped") if held == STEAK_PLATE else Reason("hands_full", held)
    if held == STEAK_PLATE:
        return None
    return Reason("already_chopped") if held is None else Reason("needs_item", STEAK_PLATE)


def _sink(status: int | None, held: str | None) -> Reason | None:
    if status is None:
        if held == DIRTY_PLATE:
            return None
        return Reason("nothing_to_wash") if held is None else Reason("needs_item", DIRTY_PLATE)
    if held is None:
        return None
    return Reason("sink_busy") if held == DIRTY_PLATE else Reason("hands_full", held)


_NO_TARGET: dict[Subtask, Reason] = {
    Subtask.PICKUP_CLEAN_PLATE: Reason("no_clean_plate"), Subtask.DROP_MEAT: Reason("grill_busy"),
    Subtask.DROP_ONION: Reason("board_busy"), Subtask.DROP_PLATE: Reason("sink_busy"),
}


def no_target_reason(subtask: Subtask | None) -> Reason:
    """Why the cook has nowhere to go for ``subtask``: its targets are judged on the participant's modelled
    knowledge (what they have seen), so this is what they know, never hidden state."""
    return _NO_TARGET.get(subtask, Reason("unknown_place")) if subtask is not None else Reason("unknown_place")


def nothing_left(subtask: Subtask, kb: KnowledgeBase, rules: Rules) -> Reason:
    """Why chopping or washing ended with nothing done: the work is already done, or nothing waits for it
    (as the participant knows the boards and sinks)."""
    if subtask is Subtask.WASH_PLATE:
        clean = any(s is not None and s >= rules.wash_time for s in kb.sinks)
        return Reason("already_washed") if clean else Reason("nothing_to_wash")
    chopped = any(s is not None and s >= rules.chop_time for s in kb.boards)
    return Reason("already_chopped") if chopped else Reason("nothing_to_chop")


EXPLAINED_BY: dict[str, Category] = {
    "no_steak": "taken", "no_garnish": "taken", "nothing_to_chop": "taken", "nothing_to_wash": "taken",
    "counter_empty": "taken", "no_clean_plate": "taken", "unknown_place": "taken", "needs_item": "taken",
    "grill_busy": "used", "board_busy": "used", "sink_busy": "used",
    "already_chopped": "done", "already_washed": "done"}
"""The reasons a change the robot made can explain, and the kind of change that explains each: something missing
(taken), a station busy (used), work already done (done). Waits (a steak cooking, an onion not chopped yet) and
the cook's own hands are their own reasons."""
ROBOT_DID: dict[Category, BlockedReason] = {"taken": "taken_by_robot", "used": "filled_by_robot",
                                            "done": "done_by_robot"}


def explained(reason: Reason, changes: Changes, cells: Iterable[Pos]) -> Reason:
    """``reason``, or what the robot changed at one of ``cells`` that is the truer reason: the steak the
    participant went for is gone because the robot took it, the grill is busy because the robot put meat on it
    (``server.game.changes``)."""
    category = EXPLAINED_BY.get(reason.code)
    change = changes.by_robot(cells, category) if category is not None else None
    return reason if change is None else Reason(ROBOT_DID[change.category], change.item, change.place)


def knows_wrongly(layout: Layout, rules: Rules, kb: KnowledgeBase, world: WorldState, cell: Pos) -> bool:
    """Whether the participant's knowledge of ``cell`` (a counter, grill, board or sink) differs from the world:
    another object on a counter, a station empty, working or done in one and not the other."""
    if cell not in layout.stations:
        return False
    return _known_state(layout, rules, kb, cell) != _known_state(layout, rules, world, cell)


def _known_state(layout: Layout, rules: Rules, kitchen: KnowledgeBase | WorldState, cell: Pos) -> object:
    kind, index = layout.stations[cell]
    done_at = {Terrain.GRILL: rules.cook_time, Terrain.BOARD: rules.chop_time, Terrain.SINK: rules.wash_time}.get(kind)
    if done_at is None:
        return kitchen.object_at(cell) if kind is Terrain.COUNTER else None
    value = {Terrain.GRILL: kitchen.grills, Terrain.BOARD: kitchen.boards, Terrain.SINK: kitchen.sinks}[kind][index]
    return "empty" if value is None else "done" if value >= done_at else "working"


def progressed(layout: Layout, before: WorldState, after: WorldState, events: tuple[Event, ...]) -> bool:
    """Whether the step from ``before`` to ``after`` moved the participant's subtask on."""
    h0, h1 = before.human, after.human
    if (h0.pos, h0.facing, h0.held) != (h1.pos, h1.facing, h1.held):
        return True
    if any(e.agent == "human" and e.kind is not EventKind.BLOCKED for e in events):
        return True
    faced = h1.facing.ahead(h1.pos)
    return _cell_state(layout, before, faced) != _cell_state(layout, after, faced)


def _cell_state(layout: Layout, world: WorldState, pos: Pos) -> object:
    entry = layout.stations.get(pos)
    if entry is None:
        return None
    kind, index = entry
    statuses = {Terrain.GRILL: world.grills, Terrain.BOARD: world.boards, Terrain.SINK: world.sinks}.get(kind)
    return statuses[index] if statuses is not None else world.object_at(pos)


@dataclass(frozen=True, slots=True)
class Stall:
    """The current subtask's run of steps without progress, and the reason last told to the participant."""

    ticks: int = 0
    reason: Reason | None = None
    told: Reason | None = None

    def step(self, moved_on: bool, reason: Reason | None, intent: Intent) -> tuple[Stall, bool]:
        """The stall after one step of the subtask, and whether the participant should be told ``reason`` now
        (a new reason; a blocked move only after :data:`NOTICE_AFTER_MOVES` steps)."""
        ticks = 0 if moved_on else self.ticks + 1
        latest = reason if reason is not None else (None if moved_on else self.reason)
        due = intent not in ("move", "wait", "look") or ticks >= NOTICE_AFTER_MOVES
        tell = reason is not None and reason != self.told and due
        return Stall(ticks, latest, reason if tell else self.told), tell
