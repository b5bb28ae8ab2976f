"""Who does the work in a trial (docs/domain.md §6, "Who does the work"): the person's and the robot's deliveries and
task steps, counted from a trial's events (or, for the reference's VR logs, from what each agent held step by step:
``benchmarks/planner/vr_logs.py``).

A *task step* is an interaction that changed what the agent holds: taking from a crate, a counter or the sink,
putting down, loading a grill, board or sink, plating a steak, adding the garnish, delivering. Chopping and washing
presses change the world too but not the agent's hands; they are counted apart (``presses``), because the
reference's logs, sampled at the planner's decision steps, do not show them reliably. Since those logs end at the
first delivery, the steps up to it are also kept (``steps_to_first``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from planner.events import Event, EventKind

PRESSES = frozenset({EventKind.CHOP, EventKind.WASH})
AGENTS = ("human", "robot")


@dataclass(frozen=True, slots=True)
class Tally:
    """A count for the person and one for the robot."""

    person: int = 0
    robot: int = 0

    def plus(self, agent: str, n: int = 1) -> Tally:
        return replace(self, person=self.person + n) if agent == "human" else replace(self, robot=self.robot + n)

    def __add__(self, other: Tally) -> Tally:
        return Tally(self.person + other.person, self.robot + other.robot)

    @property
    def total(self) -> int:
        return self.person + self.robot

    @property
    def person_share(self) -> float | None:
        """The person's share of the count (``None`` when there is none)."""
        return self.person / self.total if self.total else None


@dataclass(frozen=True, slots=True)
class WorkShare:
    """The work of one trial (or a sum of trials); ``first``: who delivered the first dish, per trial with one."""

    deliveries: Tally = field(default_factory=Tally)
    steps: Tally = field(default_factory=Tally)
    presses: Tally = field(default_factory=Tally)
    steps_to_first: Tally = field(default_factory=Tally)
    first: Tally = field(default_factory=Tally)

    def observe(self, events: Sequence[Event]) -> WorkShare:
        """The work after one step's ``events``."""
        work = self
        for event in events:
            if event.kind is EventKind.BLOCKED or event.agent not in AGENTS:
                continue
            if event.kind in PRESSES:
                work = replace(work, presses=work.presses.plus(event.agent))
                continue
            work = replace(work, steps=work.steps.plus(event.agent))
            if not work.first.total:
                work = replace(work, steps_to_first=work.steps_to_first.plus(event.agent))
            if event.kind is EventKind.DELIVER:
                work = replace(work, deliveries=work.deliveries.plus(event.agent),
                               first=work.first if work.first.total else work.first.plus(event.agent))
        return work

    def __add__(self, other: WorkShare) -> WorkShare:
        return WorkShare(self.deliveries + other.deliveries, self.steps + other.steps, self.presses + other.presses,
                         self.steps_to_first + other.steps_to_first, self.first + other.first)
