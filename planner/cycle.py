"""Joint cycles: the robot and the person stepping back and forth in step for ever (docs/domain.md §5, "Joint
cycles").

Two agents can each keep moving, each re-planning around the other every tick, and come back again and
again to the same joint situation while the team gets nothing done: the robot holding an onion and the
person stepping aside into each other's way in a 4-tick cycle. The standoff rules (:mod:`planner.standoff`)
do not fire, because somebody always moves. The rule here is keyed on the joint situation itself: the
**joint key** of a tick is both agents' poses and held objects and the kitchen's state (objects on counters,
stations, orders; not the tick). A tick at which the robot moved or turned, or tried to move and was blocked
(the two pushing against each other into one cell, tick after tick, is a cycle of one tick), and whose key
equals one of the last ``cycle_window`` keys, is a **return**. Returns are counted while the team's shaping potential Φ
(:func:`planner.rollout.potential`) stays the same; when they reach ``cycle_returns`` the pair is in a
joint cycle, and the robot breaks it by yielding: it steps to a free neighbouring cell off the person's way
(:func:`planner.standoff.step_aside`) and holds still for ``cycle_hold`` ticks, so the person can pass.
When the cycle comes back before Φ moves (the second break of the same quiet stretch, and every one after
it), the robot also gives up its current subtask for ``2 × cycle_hold`` ticks and takes another one.
A robot that waits in place makes no returns (at a grill while the steak cooks; holding still while the
person alone goes round in circles, shuttling a plate between a counter and its hands: that is the team-stall
rule's case, :mod:`planner.standoff`), nor does a kitchen that changes.

State is an immutable :class:`CycleWatch`, advanced once per observed tick by :func:`watch`.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, replace

from planner.state import WorldState
from planner.subtasks import Subtask


@dataclass(frozen=True, slots=True)
class CycleWatch:
    phi: float | None = None
    """The team's shaping potential Φ at the last observed tick."""
    seen: tuple[Hashable, ...] = ()
    """The joint keys of the last ticks since Φ last changed (at most ``cycle_window``), newest last."""
    returns: int = 0
    """Returns to a recent joint key since Φ last changed or the last break."""
    broken: int = 0
    """Cycles broken in this trial."""
    streak: int = 0
    """Cycles broken since Φ last changed."""
    hold_until: int = -1
    """After a break the robot holds still until this tick."""
    avoid: Subtask | None = None
    """The subtask given up in a repeated cycle, avoided until ``avoid_until``."""
    avoid_until: int = -1

    def cycling(self, returns: int) -> bool:
        """Whether the pair is in a joint cycle (``returns`` returns without progress)."""
        return self.returns >= returns

    def avoided(self, tick: int) -> Subtask | None:
        return self.avoid if tick < self.avoid_until else None


def joint_key(world: WorldState) -> Hashable:
    """Both agents' poses and held objects and the kitchen's state, without the tick and the score."""
    return (world.robot, world.human, world.objects, world.grills, world.boards, world.sinks, world.orders_left)


def watch(state: CycleWatch, world: WorldState, phi: float, window: int, robot_moved: bool) -> CycleWatch:
    """The watch after observing ``world`` (``phi``: its shaping potential; ``robot_moved``: the robot moved,
    turned, or tried to move and was blocked in the last step)."""
    key = joint_key(world)
    if state.phi is None or phi != state.phi:
        return replace(state, phi=phi, seen=(key,), returns=0, streak=0)
    back = robot_moved and key in state.seen
    return replace(state, seen=(state.seen + (key,))[-window:], returns=state.returns + back)


def broken(state: CycleWatch, current: Subtask | None, tick: int, hold: int) -> CycleWatch:
    """The watch after the robot yields at ``tick``: it holds still ``hold`` ticks; from the second break of
    one quiet stretch on it also avoids ``current`` for ``2 × hold`` ticks. The returns count again."""
    streak = state.streak + 1
    avoid, until = (current, tick + 2 * hold) if streak >= 2 and current is not None else (state.avoid,
                                                                                             state.avoid_until)
    return replace(state, seen=state.seen[-1:], returns=0, broken=state.broken + 1, streak=streak,
                   hold_until=tick + hold, avoid=avoid, avoid_until=until)


def without_avoided(options: tuple[Subtask, ...], state: CycleWatch, tick: int) -> tuple[Subtask, ...]:
    """``options`` without the subtask given up in a repeated cycle (unless it is the only one)."""
    avoided = state.avoided(tick)
    rest = tuple(s for s in options if s is not avoided)
    return rest or options
