"""What each world step was for the participant's cook, and the paper's clock's rule of which steps happen
(docs/protocol.md, "The paper's clock").

Every stored tick says what the participant's cook did in it (``ticks.controller.step``):

- ``key``: one action of a key press or interrupt button (a move, a turn, ``stay``, ``interact``);
- ``walk``: a step along the chosen task's path (a move or a turn);
- ``work``: an interaction of the task that changed the world (picked up, put down, chopped, …);
- ``wait``: the task's path waited for the robot to clear the way (or bumped into it);
- ``look``: the paper's clock: the task looked at a target the participant sees but does not know yet, or at the
  cell they face when their knowledge of it is wrong (their modelled KB takes a change in after the study's
  ``kb_delay`` steps in view), at most ``kb_delay`` steps;
- ``stand``: the task did nothing the participant chose: no target known, or an interaction that did nothing;
- ``idle``: no task and no key (only the fixed clock steps then).

``stand`` and ``idle`` are the ticks in which the participant had no executable action. On the paper's clock
(``timing.mode: wait_for_participant``) :func:`server.game.controller.ParticipantController.refuse_step` ends a
task before such a step, so the world does not move for it; ``wait`` steps are bounded by
:data:`server.game.blocked.PATIENCE_STEPS`.
"""

from __future__ import annotations

from planner.events import Event, EventKind
from planner.geometry import Action
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState
from planner.step import step
from store.activity import NOT_EXECUTABLE, StepKind

__all__ = ["NOT_EXECUTABLE", "StepKind", "acted", "step_kind", "would_act"]



def acted(events: tuple[Event, ...], agent: str = "human") -> bool:
    """Whether ``agent`` changed the world in a step (any event of theirs but a blocked move)."""
    return any(e.agent == agent and e.kind is not EventKind.BLOCKED for e in events)


def would_act(layout: Layout, world: WorldState, rules: Rules) -> bool:
    """Whether the participant's cook interacting now would change the world (the robot standing still)."""
    _, events = step(layout, world, {"human": Action.INTERACT, "robot": Action.STAY}, rules)
    return acted(events)


def step_kind(source: str, action: Action, before: WorldState, after: WorldState,
              events: tuple[Event, ...], intent: str) -> StepKind:
    """What the participant's cook did in the step from ``before`` to ``after`` (``source``: ``interrupt``,
    ``subtask`` or ``idle``; ``intent``: what the task tried, ``server.game.blocked.Intent``)."""
    if source == "interrupt":
        return "key"
    if source != "subtask":
        return "idle"
    if action is Action.INTERACT:
        return "work" if acted(events) else "stand"
    if action is Action.STAY:
        return "wait" if intent == "wait" else "look" if intent == "look" else "stand"
    h0, h1 = before.human, after.human
    return "walk" if (h0.pos, h0.facing) != (h1.pos, h1.facing) else "wait"
