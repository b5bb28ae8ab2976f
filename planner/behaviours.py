"""The paper's two robot behaviours (paper §VI-C), measured from outside a trial (docs/domain.md §6, "Behaviours").

A trial is read as one :class:`Frame` per tick, the state after the tick's step: what the robot holds, whether
the robot stands in the person's view (:mod:`planner.fov`) and whether the robot delivered a dish in that tick.

* **Behaviour 1, showing a pickup:** every tick at which the robot comes to hold an object it did not hold the
  tick before (taken from a crate, a counter or the sink, or made by plating a steak or adding the garnish)
  starts a *holding*, which lasts until what it holds changes again (put down, used, or the trial ends). The
  holding *is shown* when, at some tick within it, the robot stands in the person's view and has stood there at
  least ``kb_delay`` consecutive ticks (counted from before the holding began, whatever its hands did): the
  tick the person acknowledges what it holds (docs/domain.md §3). Rate: shown / holdings.
* **Behaviour 2, a delivery in view:** a *dish trip* runs from the tick the robot comes to hold a dish to the
  tick before it delivers it (a trip that ends otherwise is not counted). Its share is the fraction of the
  trip's ticks with the robot in the person's view. Rate: the mean share over trips.

The robot component of the KB gap (ticks at which the person's KB is wrong about what the robot holds) is split
by why (:func:`hands_gap`): *lag*, the ticks it would be wrong even if the person watched the robot every tick
(a person who watched it from the start knows every change of hands from the ``kb_delay``-th tick on); *unseen*,
the robot holds
something the person has not acknowledged; *stale*, the robot's hands are empty but the person still believes it
holds what it last showed them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from planner.events import Event, EventKind
from planner.fov import view
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.objects import DISH
from planner.state import WorldState


@dataclass(frozen=True, slots=True)
class Frame:
    """One tick of a trial, as the behaviours read it; ``believed`` is what the person's KB says the robot holds,
    when the trial kept the KB (``(held,)``; ``None`` when it did not, e.g. a log)."""

    held: str | None
    seen: bool
    delivered: bool = False
    believed: tuple[str | None] | None = None


@dataclass(frozen=True, slots=True)
class Behaviours:
    """Counts of one trial (or a sum of trials): holdings and those shown; dish trips and their summed share."""

    holdings: int = 0
    shown: int = 0
    trips: int = 0
    trip_share_sum: float = 0.0

    @property
    def shown_rate(self) -> float | None:
        return self.shown / self.holdings if self.holdings else None

    @property
    def trip_share(self) -> float | None:
        return self.trip_share_sum / self.trips if self.trips else None

    def __add__(self, other: Behaviours) -> Behaviours:
        return Behaviours(self.holdings + other.holdings, self.shown + other.shown, self.trips + other.trips,
                          self.trip_share_sum + other.trip_share_sum)


@dataclass(frozen=True, slots=True)
class HandsGap:
    """Ticks of one trial (or a sum of trials) at which the person's KB is wrong about the robot's hands, by why
    (module docstring); ``ticks`` is all ticks."""

    ticks: int = 0
    lag: int = 0
    unseen: int = 0
    stale: int = 0

    @property
    def wrong(self) -> int:
        return self.lag + self.unseen + self.stale

    def __add__(self, other: HandsGap) -> HandsGap:
        return HandsGap(self.ticks + other.ticks, self.lag + other.lag, self.unseen + other.unseen,
                        self.stale + other.stale)


def frame_of(layout: Layout, world: WorldState, events: Sequence[Event], angle: float,
             kb: KnowledgeBase | None = None) -> Frame:
    """The frame of one tick of our own trials: ``world`` after the step, ``events`` the step's events, ``kb`` the
    person's KB after it (if kept)."""
    seen = world.robot.pos in view(layout, world.human.pos, world.human.facing, angle).cells
    delivered = any(e.agent == "robot" and e.kind is EventKind.DELIVER for e in events)
    believed = None if kb is None else (None if kb.robot is None else kb.robot.held,)
    return Frame(world.robot.held, seen, delivered, believed)


def holdings(frames: Sequence[Frame]) -> list[tuple[int, int]]:
    """``(start, end)`` index ranges (end exclusive) of every holding (behaviour 1)."""
    spans, start = [], None
    for t, frame in enumerate(frames):
        before = frames[t - 1].held if t else None
        if frame.held != before:
            if start is not None:
                spans.append((start, t))
            start = t if frame.held is not None else None
    if start is not None:
        spans.append((start, len(frames)))
    return spans


def in_view_runs(frames: Sequence[Frame]) -> list[int]:
    """At each tick, the robot's consecutive ticks in view up to it (0 when out of view)."""
    runs, run = [], 0
    for frame in frames:
        run = run + 1 if frame.seen else 0
        runs.append(run)
    return runs


def measure(frames: Sequence[Frame], kb_delay: int) -> Behaviours:
    """Behaviours 1 and 2 of one trial (module docstring)."""
    spans = holdings(frames)
    runs = in_view_runs(frames)
    shown = sum(any(r >= max(kb_delay, 1) for r in runs[a:b]) for a, b in spans)
    trips, share = 0, 0.0
    for a, b in spans:
        if frames[a].held == DISH and b < len(frames) and frames[b].delivered:
            trips += 1
            share += sum(f.seen for f in frames[a:b]) / (b - a)
    return Behaviours(len(spans), shown, trips, share)


def hands_gap(frames: Sequence[Frame], kb_delay: int) -> HandsGap:
    """The person's KB about what the robot holds, tick by tick (the frames' ``believed`` when they carry it, else
    by the KB's rule for the robot, docs/domain.md §3: it takes what the robot holds at every tick the robot stands
    in view and has stood there ``kb_delay`` consecutive ticks, whatever its hands did meanwhile; at the start it
    knows the robot's empty hands), and the ticks it is wrong, split into lag, unseen and stale."""
    believed = watched = None  # the KB's belief, and a person's who watched the robot every tick
    lag = unseen = stale = 0
    for t, (frame, run) in enumerate(zip(frames, in_view_runs(frames), strict=True)):
        if frame.believed is not None:
            believed = frame.believed[0]
        elif frame.seen and run >= kb_delay:
            believed = frame.held
        if t + 1 >= kb_delay:
            watched = frame.held
        if believed == frame.held:
            continue
        if watched != frame.held:
            lag += 1
        elif frame.held is None:
            stale += 1
        else:
            unseen += 1
    return HandsGap(len(frames), lag, unseen, stale)
