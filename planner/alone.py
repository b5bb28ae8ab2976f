"""Working alone: when the partner stops, the robot plans as if it were alone (docs/domain.md §5, "Working
alone").

A participant who stops (walks away from the keyboard, gives up, waits to see what the robot does) is no
partner to plan with: the robot's rollouts would still predict that the person picks up what is next, and
a robot that leaves that work to them can wait for the rest of the trial. So once the person has not moved,
turned or interacted for ``alone_ticks`` ticks (:func:`still_for`), the robot plans for one agent, until the
person does something again:

* its options are judged as if the person's hands were empty (:func:`planner.standoff.unaided`: nothing the
  person carries is counted on, and the person's load counts for nothing in what the orders still need);
* its rollouts simulate a person who stays where they stand (:class:`planner.partner.StillHuman`), walked around as a
  parked agent, under one hypothesis.

The default (20 ticks) lies above the longest wait of a working person (a steak cooks for 10 ticks; the
simulated person presses interact while it waits, which does not count as doing something only because the
grill does not change).
"""

from __future__ import annotations

from collections.abc import Sequence

from planner.events import Event
from planner.layout import Layout
from planner.partner import StillHuman
from planner.planner_config import PlannerConfig
from planner.rollout import Rollout
from planner.rules import Rules
from planner.standoff import reachable
from planner.state import AgentState, WorldState


def solo_rollout(layout: Layout, rules: Rules, cfg: PlannerConfig) -> Rollout:
    """Rollouts of the robot alone beside a person who stays where they stand."""
    rollout = Rollout(layout, rules, cfg)
    rollout.human = StillHuman(layout, rules)
    return rollout


def still_for(ticks: int, before: AgentState | None, now: AgentState, events: Sequence[Event]) -> int:
    """Ticks the person has not moved, turned, tried to move or interacted with anything (pressing interact
    where it changes nothing is no sign of life), given the count at the tick before."""
    acted = any(e.agent == "human" for e in events)
    return ticks + 1 if before == now and not acted else 0


def solo_possible(layout: Layout, world: WorldState) -> bool:
    """Whether one agent, the robot, can do every step of a dish with the person standing where they stand in
    ``world``: some station of every kind can be reached without passing the person's cell."""
    kinds = (layout.onions, layout.meats, layout.plates, layout.grills, layout.boards, layout.sinks, layout.serves)
    return all(reachable(layout, world, cells) for cells in kinds)
