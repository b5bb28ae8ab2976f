"""The participant's control of the avatar: a chosen subtask, or interrupt actions (docs/domain.md §4).

- ``select(subtask)`` replaces the current subtask (and drops queued interrupts). Each tick the avatar walks
  toward the subtask's nearest target by the movement rule of ``planner.avatar`` (one call, ``avatar_move``): a
  shortest path re-planned every tick, targets judged on the participant's **modelled KB**, the robot avoided
  only where the participant can know it is, and walked around once it is known to be parked.
- ``interrupt(up/down/left/right/stay/interact)`` overrides the subtask for one tick, at the next tick, in
  the order pressed (at most ``QUEUE_LIMIT`` waiting); the subtask then continues from the new pose.
  ``interrupt(stop)`` cancels the subtask and the queued interrupts at once.
- A subtask ends when it is done (``planner.subtasks.is_done`` on what the avatar held before and after the
  step and the modelled KB), whoever's action finished it. The participant may choose any subtask that fits
  what the avatar holds (``server.game.needs``); the ones the model of the participant considers available
  (``available``) are a hint for the client.
- A subtask that cannot work is explained, never silent (``server.game.blocked``): one that does not fit what
  the avatar holds is refused when chosen; one whose interaction does nothing gets a notice naming why; and
  one that makes no progress for ``blocked_ticks`` steps ends itself with the last reason. An ``interact``
  key that did nothing gets the same notice, without a subtask (``Blocked.subtask`` ``None``).
- On the paper's clock (``wait_for_participant``) the world steps only for the participant's actions:
  :meth:`ParticipantController.refuse_step`, asked before each step, ends a subtask whose next step would do
  nothing the participant chose (no target known, an interaction that would do nothing, or the way blocked for
  :data:`~server.game.blocked.PATIENCE_STEPS` steps) with its reason, and the world does not step for it
  (``server.game.steps``; docs/protocol.md, "The paper's clock").
"""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np

from planner.avatar import RobotWatch, avatar_move
from planner.events import Event, EventKind
from planner.fov import view
from planner.geometry import Action, Pos, manhattan
from planner.human import HumanModel
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState
from planner.subtasks import Believed, Subtask, available, is_done, targets
from server.game.blocked import (
    PATIENCE_STEPS,
    Blocked,
    Intent,
    Reason,
    Stall,
    explained,
    hands_reason,
    interaction_reason,
    knows_wrongly,
    no_target_reason,
    nothing_left,
    progressed,
)
from server.game.changes import Changes
from server.game.steps import would_act
from server.protocol.interrupts import Interrupt


class Unchecked:
    """The type of :data:`UNCHECKED`: ``select`` was not told what the avatar holds."""


UNCHECKED = Unchecked()

QUEUE_LIMIT = 3


INTERRUPT_ACTION: dict[Interrupt, Action] = {
    Interrupt.UP: Action.NORTH, Interrupt.DOWN: Action.SOUTH, Interrupt.LEFT: Action.WEST,
    Interrupt.RIGHT: Action.EAST, Interrupt.STAY: Action.STAY, Interrupt.INTERACT: Action.INTERACT,
}


class ParticipantController:
    def __init__(self, layout: Layout, rules: Rules, angle: float, subtask: Subtask | None = None,
                 last: Subtask | None = None, blocked_ticks: int | None = None) -> None:
        self.layout, self.rules, self.angle = layout, rules, angle
        self.model = HumanModel(layout, rules)
        self.subtask = subtask
        self.last = last
        self.blocked_ticks = blocked_ticks
        """Steps without progress after which a subtask ends itself (``None``: never)."""
        self.queue: deque[Interrupt] = deque()
        self.robot_watch = RobotWatch()
        self.intent: Intent = "idle"
        self.stall = Stall()
        self.worked = False
        """Whether the avatar did anything (an interaction with an effect) during the current subtask."""
        self.ended: Subtask | None = None
        """The subtask :meth:`observe` ended at the last step, for :meth:`review`."""
        self.key_interact = False
        """Whether the last step's action was an ``interact`` key (an interrupt), for :meth:`review`."""
        self.changes = Changes()
        """Who last changed each cell (``server.game.changes``): a refusal there names what the robot did."""
        self.aims: tuple[Pos, ...] = ()
        """The cells the current subtask was heading for at its last step (its targets on the modelled KB)."""
        self.looking = False
        """The paper's clock: this step looks at a target the participant sees but does not know yet."""

    def select(self, subtask: Subtask, held: str | Unchecked | None = UNCHECKED) -> Blocked | None:
        """Make ``subtask`` the current one (dropping queued interrupts), unless it cannot work with ``held``
        in hand: then nothing changes and the refusal says why. Without ``held`` (scripted players choosing
        from :meth:`available`, which always fits the hands) nothing is checked."""
        reason = None if isinstance(held, Unchecked) else hands_reason(subtask, held)
        if reason is not None:
            return Blocked(subtask, reason, ended=True)
        self.subtask = self.last = subtask
        self.queue.clear()
        self.stall = Stall()
        self.worked = False
        self.aims = ()
        return None

    def interrupt(self, which: Interrupt) -> bool:
        """Queue (or, for ``stop``, apply) an interrupt; ``False`` when the queue is full (nothing changes)."""
        if which is Interrupt.STOP:
            self.subtask = None
            self.queue.clear()
            return True
        if len(self.queue) >= QUEUE_LIMIT:
            return False
        self.queue.append(which)
        return True

    def has_action(self) -> bool:
        """Whether the avatar has something to do (the wait-for-participant clock steps only then)."""
        return bool(self.queue) or self.subtask is not None

    def decide(self, world: WorldState, kb: KnowledgeBase, rng: np.random.Generator) -> tuple[Action, str]:
        """The avatar's action this tick and its source: ``interrupt``, ``subtask`` or ``idle``."""
        self.robot_watch = self.robot_watch.seen(world)
        self.key_interact = False
        if self.queue:
            self.intent = "idle"
            which = self.queue.popleft()
            self.key_interact = which is Interrupt.INTERACT
            return INTERRUPT_ACTION[which], "interrupt"
        if self.subtask is None:
            self.intent = "idle"
            return Action.STAY, "idle"
        action, wants_move = avatar_move(self.model, self.angle, world, kb, self.subtask, self.robot_watch, rng)
        self.aims = targets(self.layout, self.subtask, kb, self.rules) or self.aims
        if self.looking:
            self.intent = "look"
            return Action.STAY, "subtask"
        if action is Action.INTERACT:
            self.intent = "interact"
        elif action is not Action.STAY:
            self.intent = "move"
        else:
            self.intent = "wait" if wants_move else "no_target"
        return action, "subtask"

    def refuse_step(self, world: WorldState, kb: KnowledgeBase, rng: np.random.Generator,
                    look_steps: int = 0) -> Blocked | None:
        """The paper's clock, before a step: when the current subtask's next step (the one :meth:`decide` would
        take with ``rng``, the avatar's generator of this tick) would do nothing the participant chose — no target
        known, an interaction that would do nothing, or a way blocked for :data:`PATIENCE_STEPS` steps — the
        subtask ends here with its reason (``ended``) and the world must not step for it. ``None``: the step
        goes ahead (a key waiting, no subtask, or a step that moves, turns or works).

        One exception keeps the participant's modelled knowledge in step with what they see (it takes a change in
        after ``kb_delay`` steps in view, docs/domain.md §3, and a refusal moves no step): a target they see in view
        but do not know yet, or the cell they face when their knowledge of it is wrong (the onion they went for is
        gone), is looked at for up to ``look_steps`` steps (the study's ``kb_delay``) rather than refused at once —
        else "The grill is busy" while they watch it stand free, or the same walk to the same empty counter again;
        those steps are ``look`` in the record, and the refusal, if still due, follows with its true reason."""
        subtask = self.subtask
        if self.queue or subtask is None:
            return None
        watch = self.robot_watch.seen(world)
        action, wants_move = avatar_move(self.model, self.angle, world, kb, subtask, watch, rng)
        reason: Reason | None = None
        self.looking = False
        if action is Action.INTERACT:
            if not would_act(self.layout, world, self.rules):
                self.looking = self.stall.ticks < look_steps and knows_wrongly(self.layout, self.rules, kb, world,
                                                                               self._faced(world))
                reason = interaction_reason(self.layout, world, self.rules) or Reason("stuck")
                reason = None if self.looking else explained(reason, self.changes, (self._faced(world),))
        elif action is Action.STAY and not wants_move:
            self.looking = self.stall.ticks < look_steps and self._sees_target(world, subtask)
            reason = None if self.looking else explained(no_target_reason(subtask), self.changes, self.aims)
        elif action is Action.STAY and self.stall.ticks >= PATIENCE_STEPS:
            reason = self.stall.reason or self._blocked_way(world)
        if reason is None:
            return None
        self.subtask = None
        self.stall = Stall()
        self.worked = False
        return Blocked(subtask, reason, ended=True)

    def _sees_target(self, world: WorldState, subtask: Subtask) -> bool:
        """Whether a target of ``subtask`` in the world itself is in the participant's view now."""
        human = world.human
        seen = view(self.layout, human.pos, human.facing, self.angle).cells
        return any(cell in seen for cell in targets(self.layout, subtask, world, self.rules))

    def believed(self, world: WorldState, kb: KnowledgeBase) -> Believed:
        return self.model.believed(world, kb)

    def observe(self, before: WorldState, after: WorldState, kb: KnowledgeBase) -> bool:
        """End the subtask if the last step finished it; whether it did."""
        if self.subtask is None:
            return False
        if is_done(self.subtask, before.human.held, after.human.held, self.believed(after, kb), self.rules):
            self.ended, self.subtask = self.subtask, None
            return True
        return False

    def review(self, before: WorldState, after: WorldState, events: tuple[Event, ...],
               kb: KnowledgeBase) -> Blocked | None:
        """After a step of the current subtask (call after :meth:`observe`): a notice when it did not get
        anywhere for a reason the participant should hear, or its end when it made no progress for
        ``blocked_ticks`` steps (the subtask is then dropped). Chopping or washing that ends with nothing done
        (no onion or plate waiting, as far as the participant knows) ends with its reason too."""
        self.changes = self.changes.after(self.layout, events)
        acted = any(e.agent == "human" and e.kind is not EventKind.BLOCKED for e in events)
        self.worked = self.worked or acted
        ended, self.ended = self.ended, None
        if ended is not None:
            idle_end = ended in (Subtask.CHOP_ONION, Subtask.WASH_PLATE) and not self.worked
            self.worked, self.stall = False, Stall()
            return Blocked(ended, nothing_left(ended, kb, self.rules), ended=True) if idle_end else None
        if self.key_interact and not acted:  # an interact key that did nothing: why, as for a task
            reason = interaction_reason(self.layout, before, self.rules)
            if reason is not None:
                reason = explained(reason, self.changes, (self._faced(before),))
                self.stall = Stall()
                return Blocked(None, reason, ended=False)
        subtask = self.subtask
        if subtask is None or self.intent == "idle":
            self.stall = Stall()
            return None
        moved_on = progressed(self.layout, before, after, events)
        reason = self._why(after, moved_on)
        self.stall, tell = self.stall.step(moved_on, reason, self.intent)
        if self.blocked_ticks is not None and self.stall.ticks >= self.blocked_ticks:
            final = explained(self.stall.reason or Reason("stuck"), self.changes, (self._faced(after), *self.aims))
            self.subtask = None
            self.stall = Stall()
            return Blocked(subtask, final, ended=True)
        return Blocked(subtask, reason, ended=False) if tell and reason is not None else None

    def _faced(self, world: WorldState) -> Pos:
        human = world.human
        return human.facing.ahead(human.pos)

    def _why(self, after: WorldState, moved_on: bool) -> Reason | None:
        """Why this step of the subtask did nothing, from what the participant can see now."""
        if self.intent == "look":
            return None
        if self.intent == "interact":
            reason = interaction_reason(self.layout, after, self.rules)
            return None if reason is None else explained(reason, self.changes, (self._faced(after),))
        if self.intent == "no_target":
            return explained(no_target_reason(self.subtask), self.changes, self.aims)
        if moved_on:
            return None
        return self._blocked_way(after)

    def _blocked_way(self, world: WorldState) -> Reason:
        """Why the cook's way is blocked: the robot beside it, when in view; else the way itself."""
        human, robot = world.human, world.robot.pos
        seen = view(self.layout, human.pos, human.facing, self.angle).cells
        return Reason("robot_in_way") if robot in seen and manhattan(human.pos, robot) == 1 else Reason("no_way")

    def available(self, world: WorldState, kb: KnowledgeBase) -> tuple[Subtask, ...]:
        """The subtasks the model of the participant considers available (docs/domain.md §4), judged on the KB."""
        return available(self.believed(world, kb), self.rules, self.subtask or self.last)

    def to_dict(self) -> dict[str, Any]:
        return {"subtask": _value(self.subtask), "last": _value(self.last)}

    @classmethod
    def from_dict(cls, data: dict[str, Any], layout: Layout, rules: Rules, angle: float,
                  blocked_ticks: int | None = None) -> ParticipantController:
        return cls(layout, rules, angle, subtask=_subtask(data.get("subtask")), last=_subtask(data.get("last")),
                   blocked_ticks=blocked_ticks)


def _value(subtask: Subtask | None) -> str | None:
    return None if subtask is None else subtask.value


def _subtask(value: Any) -> Subtask | None:
    return None if value is None else Subtask(value)
