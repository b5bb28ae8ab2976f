"""The robot's model of the person (docs/domain.md §5, steps 1 and the person the study shows).

What the robot tracks of its partner from tick to tick, and nothing of its own choice: the person's KB as the
robot models it (:func:`planner.kb.update_kb` with the modelled angle and delay; the baseline's person sees
everything, so its KB is the world), the belief over the person's subtask (:mod:`planner.belief`), and how long
the person has stood in one cell (``human_still``, for the standoff rules and the simulated person's parking) or
done nothing at all (``partner_still``, :mod:`planner.alone`).
"""

from __future__ import annotations

from collections.abc import Sequence

from planner.alone import still_for
from planner.belief import Belief, update_belief
from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.state import AgentState, WorldState


class PersonModel:
    """The person as the robot models them, updated once per tick by :meth:`observe`."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig) -> None:
        self.layout, self.rules, self.cfg = layout, rules, config
        self.kb: KnowledgeBase | None = None
        self.kb_tick: int | None = None
        self.belief: Belief | None = None
        self.last: AgentState | None = None
        self.human_still = 0
        self.partner_still = 0

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        """Start on ``world``: the modelled KB is ``kb`` (a resumed trial's restored KB) or, at a trial's start
        or for a model that sees everything at once (the baseline's: its KB is the world), :func:`initial_kb`."""
        self.kb = kb if kb is not None and not self.cfg.human_sees_everything else initial_kb(world)
        self.kb_tick = world.tick
        self.belief = None
        self.last = None
        self.human_still = 0
        self.partner_still = 0

    def observe(self, world: WorldState, events: Sequence[Event]) -> bool:
        """Take in the world after a step and the step's events; whether the person moved to another cell."""
        assert self.kb is not None
        human_events = [e for e in events if e.agent == "human"]
        if world.tick != self.kb_tick:
            # The person's KB takes each world once, after it steps (planner.play, server.game.engine): the
            # world the robot was reset with is already in ``initial_kb``, and seeing it again is no new tick.
            self.kb = update_kb(self.kb, self.layout, world, angle=self.cfg.human_angle,
                                kb_delay=self.cfg.human_delay, own_events=human_events)
            self.kb_tick = world.tick
        action = _infer_action(self.last, world.human, bool(human_events))
        partner_held = self.kb.robot.held if self.kb.robot is not None else None
        self.belief = update_belief(self.belief, self.layout, self.rules, self.kb, self.last, world.human,
                                    action, partner_held, world.orders_left, weight=self.cfg.progress_weight,
                                    floor=self.cfg.belief_floor)
        moved = self.last is not None and self.last.pos != world.human.pos
        self.human_still = 0 if moved else self.human_still + 1
        self.partner_still = still_for(self.partner_still, self.last, world.human, human_events)
        self.last = world.human
        return moved

    @property
    def alone(self) -> bool:
        """Whether the person has stopped (:mod:`planner.alone`): the robot plans as if it were alone."""
        return self.partner_still >= self.cfg.alone_ticks


def _infer_action(before: AgentState | None, now: AgentState, interacted: bool) -> Action | None:
    if before is None:
        return None
    if interacted:
        return Action.INTERACT
    if before.pos != now.pos or before.facing != now.facing:
        return Action(now.facing.value)
    return Action.STAY
