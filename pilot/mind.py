"""The simulated participant's choices, one message per ``state`` frame (pure: state in, message and state out).

Each frame, with its KB (:mod:`pilot.perception`) and the subtask the server says is running:

1. **No subtask running**: after ``decision_latency_ticks`` frames it chooses, by the simulated human's rule
   (docs/domain.md §4, paper §IV-A: uniformly at random among the subtasks available in its KB), or, with
   probability ``error_rate``, at random among the subtasks that fit what the cook holds (``hello.needs``). It
   reads the page: a task the page said cannot work (a ``blocked`` that ended it) is not chosen again while it
   believes the same of the places that task needs (until it sees them again, or its knowledge of them changes);
   when its rule offers only that task, it chooses among the others that fit its hands.
2. **A subtask running that what it now sees makes pointless or impossible** (not available in its KB any
   more, or no believed target left): noticed with probability ``notice_probability`` per frame, then handled
   by a stop interrupt, a replacing choice, or a one-step correction (``interact`` to put what it holds on the
   free counter it faces), drawn with the config's weights.
3. **Stuck next to the robot** (the cook has not moved for ``stuck_ticks`` frames with a subtask running and the
   robot in view beside it): with probability ``sidestep_probability`` a move interrupt to a free neighbour.
4. Otherwise a heartbeat, so the pilot's pace knows it has acted.

On the paper's clock (``wait_for_participant``), a task refused because the station it needs is still at work
(:data:`WAIT_REASONS`: the steak is still cooking, the onion not chopped yet) is waited for as the page says: the
simulated participant presses "." (stay) every ``wait_tap_seconds`` while the station it faces is at work
(:func:`faced_station_working`), at most ``wait_taps`` times, and then chooses again (``pilot.client``), asking for
the same task again only if the wait taught it something new of its places (:func:`read_refusal`): an onion
nobody chops does not keep it pressing at the board. The world moves only for those presses; the simulated human
of the paper waited at the station, stepping the world.

Randomness comes from the ``numpy.random.Generator`` passed in (one per trial, from the pilot's seed).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from pilot.config import ParticipantConfig
from pilot.perception import Perception
from planner.geometry import DIRECTIONS, Direction, Pos, manhattan
from planner.kb import KnowledgeBase
from planner.layout import Layout, Terrain
from planner.rules import Rules
from planner.subtasks import Believed, Subtask, available, targets

MOVE_OF: dict[Direction, str] = {Direction.NORTH: "up", Direction.SOUTH: "down", Direction.WEST: "left",
                                  Direction.EAST: "right"}


@dataclass(frozen=True, slots=True)
class Message:
    """One client message: ``type`` and its fields (without ``v`` / ``seq``, added by the connection)."""

    type: str
    fields: tuple[tuple[str, Any], ...] = ()

    def body(self) -> dict[str, Any]:
        return {"type": self.type, **dict(self.fields)}


HEARTBEAT = Message("heartbeat")
STAY = Message("interrupt", (("action", "stay"),))
WAIT_REASONS = frozenset({"steak_cooking", "not_chopped"})
"""Refusals that time answers: the station the task needs is still at work."""
WORKING = frozenset({"cooking", "chopping", "washing"})


@dataclass(frozen=True, slots=True)
class Mind:
    """What the simulated participant carries between frames."""

    idle: int = 0
    last: Subtask | None = None
    still: int = 0
    pose: tuple[Pos, str] | None = None
    interrupts: int = 0
    kb_gap_sum: float = 0.0
    refused: tuple[tuple[Subtask, object], ...] = ()
    """Tasks the page said cannot work (a ``blocked`` that ended them), each with what it believed then of the places
    the task needs (:func:`belief_of`): not chosen again while it still believes the same (it has learnt nothing new
    of those places)."""


def belief_of(layout: Layout, rules: Rules, kb: KnowledgeBase, subtask: Subtask) -> object:
    """What the KB holds of the places ``subtask`` needs: the task's targets, and each station's and counter's
    state there."""
    cells = targets(layout, subtask, kb, rules)
    stations = {Terrain.GRILL: kb.grills, Terrain.BOARD: kb.boards, Terrain.SINK: kb.sinks}
    held = []
    for cell in cells:
        kind, index = layout.stations.get(cell, (None, 0))
        held.append(stations[kind][index] if kind in stations else kb.object_at(cell))
    return cells, tuple(held), kb.grills, kb.boards, kb.sinks


def told_refused(mind: Mind, subtask: Subtask, belief: object) -> Mind:
    """The mind after the page said ``subtask`` cannot work, when it believed ``belief`` (:func:`belief_of`)."""
    kept = tuple(entry for entry in mind.refused if entry[0] is not subtask)
    return replace(mind, refused=(*kept, (subtask, belief)))


def read_refusal(mind: Mind, seen: Perception, subtask: Subtask, reason: str, rules: Rules, *, waits: bool) -> Mind:
    """The mind after a ``blocked`` that ended ``subtask`` for ``reason``. A task refused for what time does not
    answer is noted (:func:`told_refused`). A task refused because its station is still at work (:data:`WAIT_REASONS`)
    is noted too when the participant ``waits`` for it (the paper's clock): once the wait is over, it asks again only
    if it has learnt something new of the places the task needs (the steak cooked on, the onion was chopped), not
    for an onion nobody chops. Otherwise (the world goes on) it is not noted: the world answers it."""
    if seen.kb is None or (reason in WAIT_REASONS and not waits):
        return mind
    return told_refused(mind, subtask, belief_of(seen.layout, rules, seen.kb, subtask))


def fits(subtask: Subtask, held: str | None, needs: Mapping[str, str]) -> bool:
    need = needs.get(subtask.value, "nothing")
    if need == "nothing":
        return held is None
    if need == "something":
        return held is not None
    return held == need


def decide(mind: Mind, seen: Perception, state: Mapping[str, Any], needs: Mapping[str, str], rules: Rules,
           config: ParticipantConfig, rng: np.random.Generator) -> tuple[Message, Mind]:
    """The message answering this frame and the mind after it."""
    you, hud = state["you"], state["hud"]
    pose = ((you["x"], you["y"]), you["facing"])
    running = Subtask(state["subtask"]) if state["subtask"] else None
    still = mind.still + 1 if running is not None and pose == mind.pose else 0
    mind = replace(mind, pose=pose, still=still)
    if hud["orders_left"] == 0 or hud["ticks_left"] == 0 or seen.kb is None:
        return HEARTBEAT, mind
    kb, layout, held = seen.kb, seen.layout, you["held"]
    believed = Believed(kb=kb, held=held, partner_held=kb.robot.held if kb.robot is not None else None,
                        orders_left=int(hud["orders_left"]))
    if mind.refused:
        believed_still = tuple((s, was) for s, was in mind.refused if belief_of(layout, rules, kb, s) == was)
        mind = replace(mind, refused=believed_still) if believed_still != mind.refused else mind
    if running is None:
        if mind.idle + 1 < config.decision_latency_ticks:
            return HEARTBEAT, replace(mind, idle=mind.idle + 1)
        choice = choose(believed, rules, mind.last, held, needs, config, rng, avoid={s for s, _ in mind.refused})
        return Message("select_subtask", (("subtask", choice.value),)), replace(mind, idle=0, last=choice)
    mind = replace(mind, last=running, idle=0)
    if pointless(running, believed, layout, rules) and rng.random() < config.notice_probability:
        return react(mind, running, believed, seen, state, rules, needs, config, rng)
    robot = state["robot"]
    if (still >= config.stuck_ticks and robot is not None
            and manhattan(pose[0], (robot["x"], robot["y"])) == 1 and rng.random() < config.sidestep_probability):
        step = sidestep(layout, pose[0], (robot["x"], robot["y"]), rng)
        if step is not None:
            return interrupt(step), replace(mind, still=0, interrupts=mind.interrupts + 1)
    return HEARTBEAT, mind


def choose(believed: Believed, rules: Rules, last: Subtask | None, held: str | None, needs: Mapping[str, str],
           config: ParticipantConfig, rng: np.random.Generator, avoid: Collection[Subtask] = ()) -> Subtask:
    """The simulated human's rule, or with probability ``error_rate`` any subtask that fits the hands; never one of
    ``avoid`` (a task just refused, or the one being replaced) while another fits the hands."""
    if rng.random() < config.error_rate:
        options = tuple(s for s in Subtask if fits(s, held, needs) and s not in avoid)
    else:
        options = tuple(s for s in available(believed, rules, last) if s not in avoid)
    if not options:
        options = tuple(s for s in Subtask if fits(s, held, needs) and s not in avoid)
    if not options:
        options = available(believed, rules, last)
    return options[int(rng.integers(len(options)))]


def pointless(subtask: Subtask, believed: Believed, layout: Layout, rules: Rules) -> bool:
    """Whether the subtask is no longer available in the KB or has no believed target left."""
    return subtask not in available(believed, rules, subtask) or not targets(layout, subtask, believed.kb, rules)


def react(mind: Mind, running: Subtask, believed: Believed, seen: Perception, state: Mapping[str, Any],
          rules: Rules, needs: Mapping[str, str], config: ParticipantConfig,
          rng: np.random.Generator) -> tuple[Message, Mind]:
    """Stop, replace or correct a subtask noticed to be pointless (weights from the config)."""
    stop, replace_w, _correct = config.reaction_weights()
    draw = rng.random()
    you = state["you"]
    if draw >= stop + replace_w and you["held"] is not None and free_counter_ahead(seen, you):
        return interrupt("interact"), replace(mind, interrupts=mind.interrupts + 1)
    if draw < stop or (draw >= stop + replace_w and rng.random() < 0.5):
        return interrupt("stop"), replace(mind, interrupts=mind.interrupts + 1, last=None, idle=0)
    choice = choose(believed, rules, running, you["held"], needs, config, rng, avoid=(running,))
    return Message("select_subtask", (("subtask", choice.value),)), replace(mind, last=choice)


def free_counter_ahead(seen: Perception, you: Mapping[str, Any]) -> bool:
    """The faced cell is a counter the KB believes empty (it is always in view)."""
    ahead = Direction(you["facing"]).ahead((you["x"], you["y"]))
    layout = seen.layout
    inside = 0 <= ahead[0] < layout.width and 0 <= ahead[1] < layout.height
    return (inside and layout.terrain(ahead) is Terrain.COUNTER and seen.kb is not None
            and seen.kb.object_at(ahead) is None)


def sidestep(layout: Layout, pos: Pos, robot: Pos, rng: np.random.Generator) -> str | None:
    free = [d for d in DIRECTIONS if (cell := d.ahead(pos)) != robot and 0 <= cell[0] < layout.width
            and 0 <= cell[1] < layout.height and layout.is_floor(cell)]
    if not free:
        return None
    return MOVE_OF[free[int(rng.integers(len(free)))]]


def interrupt(action: str) -> Message:
    return Message("interrupt", (("action", action),))


def faced_station_working(state: Mapping[str, Any]) -> bool:
    """Whether the cell the cook faces (always in view) is a station still at work in this frame."""
    you = state["you"]
    x, y = Direction(you["facing"]).ahead((you["x"], you["y"]))
    cell = next((c for c in state["cells"] if (c["x"], c["y"]) == (x, y)), None)
    station = cell.get("station") if cell is not None else None
    return station is not None and station["state"] in WORKING
