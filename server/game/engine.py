"""One live trial's world, step by step: no clock, no I/O (the loop in :mod:`server.game.loop` drives it).

Each tick: the participant's action comes from the controller (interrupt, subtask path, or stay), the
robot's from its planner; the world steps; the participant's modelled KB is updated with the study's FOV
angle and KB delay and the participant's own events (docs/domain.md §3); the KB-gap components (paper §VII) and
whether the robot is in the participant's FOV are computed for the tick record; and whether the participant's
subtask got anywhere (a notice, or its end after ``blocked_ticks`` steps without progress: ``server.game.blocked``).

Randomness: the avatar's tie-breaks draw from the trial's avatar stream at the tick, the robot's planner (in its
pool) from its robot stream, both by the one rule of ``planner.streams``, so a trial resumed at tick t draws what
it would have drawn.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planner.events import Event
from planner.fov import View, view
from planner.geometry import Action
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState, initial_state, is_done
from planner.step import step
from planner.streams import avatar_rng
from planner.subtasks import Subtask
from planner.summary import gap_components, summarize
from server.game.blocked import Blocked
from server.game.controller import ParticipantController
from server.game.steps import StepKind, step_kind


@dataclass(frozen=True, slots=True)
class TickOutcome:
    """What one step did and what is logged for it (``world`` and ``kb`` after the step)."""

    tick: int
    human_action: Action
    robot_action: Action
    source: str
    subtask: Subtask | None
    events: tuple[Event, ...]
    world: WorldState
    kb: KnowledgeBase
    kb_summary: dict[str, Any]
    world_summary: dict[str, Any]
    gap: dict[str, int]
    robot_in_fov: bool
    subtask_finished: bool
    blocked: Blocked | None = None
    """A notice that the subtask did not get anywhere, or its end (``blocked.ended``)."""
    step: StepKind = "idle"
    """What the participant's cook did in this step (``server.game.steps``)."""


class TrialEngine:
    def __init__(self, layout: Layout, rules: Rules, *, angle: float, kb_delay: int, seed: int,
                 world: WorldState | None = None, kb: KnowledgeBase | None = None,
                 controller: ParticipantController | None = None, blocked_ticks: int | None = None) -> None:
        self.layout, self.rules, self.angle, self.kb_delay, self.seed = layout, rules, angle, kb_delay, seed
        self.world = world if world is not None else initial_state(layout, rules)
        self.kb = kb if kb is not None else initial_kb(self.world)
        self.controller = controller or ParticipantController(layout, rules, angle, blocked_ticks=blocked_ticks)
        self.last_events: tuple[Event, ...] = ()

    @property
    def done(self) -> bool:
        return is_done(self.world, self.rules)

    @property
    def tick(self) -> int:
        return self.world.tick

    def fov(self) -> View:
        """The participant's view now (the one FOV function, ``planner.fov.view``)."""
        human = self.world.human
        return view(self.layout, human.pos, human.facing, self.angle)

    def refused_step(self) -> Blocked | None:
        """The paper's clock, before a step: the participant's subtask ended because its next step would do
        nothing they chose (``ParticipantController.refuse_step``); the world must then not step."""
        if self.done:
            return None
        return self.controller.refuse_step(self.world, self.kb, avatar_rng(self.seed, self.world.tick),
                                           look_steps=self.kb_delay)

    def advance(self, robot_action: Action) -> TickOutcome:
        """Step the world once with the participant's action and ``robot_action``."""
        if self.done:
            raise RuntimeError("the trial is over")
        before = self.world
        rng = avatar_rng(self.seed, before.tick)
        subtask = self.controller.subtask
        human_action, source = self.controller.decide(before, self.kb, rng)
        world, events = step(self.layout, before, {"human": human_action, "robot": robot_action}, self.rules)
        kb = update_kb(self.kb, self.layout, world, angle=self.angle, kb_delay=self.kb_delay,
                       own_events=[e for e in events if e.agent == "human"])
        kind = step_kind(source, human_action, before, world, events, self.controller.intent)
        finished = self.controller.observe(before, world, kb)
        blocked = self.controller.review(before, world, events, kb)
        self.world, self.kb, self.last_events = world, kb, events
        kb_sum, world_sum = summarize(kb, self.rules), summarize(world, self.rules)
        return TickOutcome(
            tick=world.tick, human_action=human_action, robot_action=robot_action, source=source,
            subtask=subtask, events=events, world=world, kb=kb, kb_summary=kb_sum.to_dict(),
            world_summary=world_sum.to_dict(), gap=gap_components(kb_sum, world_sum),
            robot_in_fov=world.robot.pos in self.fov().cells, subtask_finished=finished, blocked=blocked,
            step=kind,
        )
