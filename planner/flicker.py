"""No flicker: the robot never undoes its own last interaction while nothing else has changed (docs/domain.md §5,
"No flicker").

A *touch* is an interaction of the robot with a counter: it puts an object down, picks one up, or swaps what it
holds for what lies there. The touch is *undone* by the next touch at the same counter that gives back what it took
and takes back what it gave (put down, then pick up the same object; pick up, then put it back; swap, then swap
back). Undoing pays only when the world has changed since the robot chose the touch: something the choice depends
on besides the robot's own pose, its hands and the counter it touched (:func:`scene_of`: the objects on the other
counters, whether each grill, board and sink is empty, at work or done, the orders left and what the person holds).
A steak cooking on or a chop pressed changes no phase, so a robot cannot flicker "because the grill moved on"; the
person taking the clean plate from the sink in the very step the robot put its dirty plate down is a change.

An undo is a flicker only within ``STALL_TICKS`` ticks of the touch: after that long with nothing changed the team
is stalled (the standoff rules' own threshold, docs/domain.md §5, "Standoffs"), and taking the item back breaks the
stalemate (a simulated participant waiting for the plate the robot had put down in front of itself would otherwise
wait with the robot for the rest of the trial). The robot keeps its last touch (:class:`FlickerWatch`) and never
chooses an interaction that would undo it in an unchanged scene within that time (:func:`undoes`); the same watch,
fed from outside with each step, counts the undone touches of a trial (the ``flickers`` of robot health and of a
headless trial), so one rule both forbids and measures them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from planner.events import Event, EventKind
from planner.geometry import Action, Pos
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState
from planner.step import step

STALL_TICKS = 30
"""Ticks after a touch within which undoing it in an unchanged scene is a flicker (``PlannerConfig.stall_ticks``'s
default: a team quiet this long is stalled)."""
Scene = tuple[object, ...]
"""What an undo is judged against (:func:`scene_of`)."""
COUNTER_KINDS = frozenset({EventKind.PUT_DOWN, EventKind.PICK_UP, EventKind.SWAP})


@dataclass(frozen=True, slots=True)
class Touch:
    """One robot interaction with a counter: at ``cell`` it gave ``gave`` (``None``: nothing) and took ``took``,
    chosen in ``scene`` (:func:`scene_of` the world it was chosen in, without ``cell``) at ``tick``."""

    cell: Pos
    gave: str | None
    took: str | None
    scene: Scene
    tick: int = 0

    def undone_by(self, other: Touch) -> bool:
        """``other`` (a later touch) gives back what this one took and takes back what it gave, at the same cell, in
        the same scene, within :data:`STALL_TICKS` ticks: a flicker."""
        return (other.cell == self.cell and other.gave == self.took and other.took == self.gave
                and other.scene == self.scene and other.tick - self.tick < STALL_TICKS)


def scene_of(world: WorldState, rules: Rules, skip: Pos) -> Scene:
    """The world as the robot's choices depend on it, without the agents' poses, the robot's hands, the counter
    ``skip`` and the counts within a phase: the objects on the other counters, each station's phase, the orders left
    and what the person holds."""
    objects = tuple(item for item in world.objects if item[0] != skip)
    grills = tuple(None if g is None else g >= rules.cook_time for g in world.grills)
    boards = tuple(None if b is None else rules.chopped(b) for b in world.boards)
    sinks = tuple(None if s is None else rules.clean(s) for s in world.sinks)
    return objects, grills, boards, sinks, world.orders_left, world.human.held


def touch_of(before: WorldState, events: Sequence[Event], rules: Rules) -> Touch | None:
    """The robot's counter touch in the step from ``before`` with ``events`` (``None`` when it made none)."""
    for event in events:
        if event.agent == "robot" and event.kind in COUNTER_KINDS:
            took = None if event.kind is EventKind.PUT_DOWN else event.obj
            return Touch(event.pos, before.robot.held if event.kind is not EventKind.PICK_UP else None, took,
                         scene_of(before, rules, event.pos), before.tick)
    return None


def robot_interacted(events: Sequence[Event]) -> bool:
    """The robot changed the world by an interaction in this step (a touch or any other)."""
    return any(e.agent == "robot" and e.kind is not EventKind.BLOCKED for e in events)


@dataclass(frozen=True, slots=True)
class FlickerWatch:
    """The robot's last touch (``None`` after any other interaction, or none yet) and the touches undone so far."""

    last: Touch | None = None
    flickers: int = 0

    def observe(self, before: WorldState, events: Sequence[Event], rules: Rules) -> FlickerWatch:
        """The watch after the step from ``before`` with ``events``; a flicker (:meth:`Touch.undone_by`) counts."""
        if not robot_interacted(events):
            return self
        touch = touch_of(before, events, rules)
        undone = touch is not None and self.last is not None and self.last.undone_by(touch)
        return replace(self, last=touch, flickers=self.flickers + undone)


def undoes(watch: FlickerWatch, layout: Layout, world: WorldState, rules: Rules) -> bool:
    """Whether the robot's interact in ``world`` would be a flicker, undoing its last touch in an unchanged scene
    within :data:`STALL_TICKS` ticks (the robot acts first in a step, so what the person does cannot change the
    robot's effect)."""
    last = watch.last
    if last is None or world.robot.facing.ahead(world.robot.pos) != last.cell:
        return False
    _, events = step(layout, world, {"robot": Action.INTERACT, "human": Action.STAY}, rules)
    touch = touch_of(world, events, rules)
    return touch is not None and last.undone_by(touch)
