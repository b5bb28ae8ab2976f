"""Standoffs: the robot's target is blocked by the person and nothing moves (docs/domain.md §5, "Standoffs").

A person may stand in the only access cell of a station, or in the only way to it, for a long time (an
idle or adversarial participant; two agents each waiting for the other). The planner's rollouts value
waiting there (the person is predicted to move on), so without this rule a robot can wait behind such a
person for the rest of the trial. The rule: when the robot has made **no progress** (same cell, same
held object) for ``standoff_ticks`` consecutive ticks **while every way to its target passes through the
person's cell**, it re-plans around the person, in this order:

1. **take over the blocked work**: the person's own subtask (the robot's most likely hypothesis) when the
   person has stood still as long, the robot can do it and can reach it without passing the person (two
   agents stuck in a corridor, each needing the other's side: the robot does the person's errand);
2. **step aside** when the robot is in the person's way too (the person faces the robot, and every way
   from the person to the targets of its most likely subtask passes the robot's cell): the robot moves to a
   free neighbouring cell off the person's way;
3. **another useful subtask**: the best of the robot's other options it can reach without passing the
   person; holding something, putting it down on a free counter is one (then the robot's hands are free
   for other work);
4. **step aside** when nothing else is reachable.

The blocked subtask is then avoided until the person moves or ``2 × standoff_ticks`` ticks pass; after a step
aside the robot also holds still for ``2 × standoff_ticks`` ticks (else it steps back into the way as soon as
the person comes closer).

**Team stalls.** The person can also stall the team without blocking anyone: the simulated person whose
out-of-date KB says the sink is busy shuttles its dirty plate between a counter and its hands for the rest of
the trial, and the robot, which counts on that plate reaching the sink, has no option left that it keeps
(fetching a plate is not offered while the person holds one, so the robot's options flicker with the
person's hands and it steps back and forth between two subtasks). So, whether or not its target is blocked:
when the **team** has made no progress, i.e. the shaping potential Φ (orders, steaks on grills, boards and
sinks in use, clean plates, plated steaks and dishes: :func:`planner.rollout.potential`) has not changed for
``stall_ticks`` consecutive ticks, the robot **takes the person's stalled work over**: it judges its options
as if the person's hands were empty (:func:`unaided`: what the person carries and has not brought is no
longer counted on, so the robot fetches and washes its own plate, brings its own meat or onion) and keeps
the subtask it chooses until it is done (:func:`committed`), heading only for the targets it can reach
without passing the person (:func:`within_reach`: a plate the person keeps putting down on a counter that
only the person's cell gives on to is not one; heading for it whenever it lies there turned the robot back
and forth as well); ordinary planning resumes as soon as Φ changes.
The blocked-target rule above comes first.

**Still person.** Where the plates and the person's counter are reached only from the person's own cell
(generated kitchen ``gen_1048_corridor``), the shuttling person stalls the team beyond the robot's reach: it
changes its mind only on what it sees, and it faces its counter. So, whatever else holds, once the person
has stood in one cell for ``visit_ticks`` ticks the robot walks to a cell beside the person (around it) and
holds there ``standoff_ticks`` ticks, once until the person moves again (:func:`beside`, :func:`arrive`,
:func:`visit_done`). This models nothing of what the person sees (for the baseline, whose person sees
everything, it is only a pause); it is a last resort that gives a person who looks about, and the simulated
person, whose view always takes in the cells to its left and right (docs/domain.md §2), the chance to see the
robot and what it carries. It comes after the blocked-target rule and before the team-stall rule.

State is an immutable :class:`Standoff`, advanced once per observed tick by :func:`advance`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from planner.geometry import DIRECTIONS, Action, Pos, manhattan, move_action
from planner.layout import Layout
from planner.paths import UNREACHABLE, detour_moves, distance
from planner.state import AgentState, WorldState
from planner.subtasks import Subtask

Targets = Callable[[Subtask, WorldState], tuple[Pos, ...]]


@dataclass(frozen=True, slots=True)
class Standoff:
    stuck: int = 0
    """Consecutive ticks without progress while the target was blocked."""
    avoid: Subtask | None = None
    """The subtask given up in the last standoff, avoided until ``avoid_until`` or until the person moves."""
    avoid_until: int = -1
    hold_until: int = -1
    """After a step aside the robot holds still until this tick, so the person can pass."""
    phi: float | None = None
    """The team's shaping potential Φ at the last observed tick."""
    quiet: int = 0
    """Consecutive ticks without team progress (Φ unchanged)."""
    visited: bool = False
    """The robot has stood beside the person since the person last moved (a still person is visited once)."""
    beside_until: int = -1
    """While visiting a still person: the robot holds beside the person until this tick."""

    def avoided(self, tick: int) -> Subtask | None:
        return self.avoid if tick < self.avoid_until else None

    def stalled(self, ticks: int) -> bool:
        """Whether the team has made no progress for ``ticks`` ticks (a team stall)."""
        return self.quiet >= ticks


def blocked(layout: Layout, world: WorldState, cells: tuple[Pos, ...]) -> bool:
    """Whether every way from the robot to every reachable target cell passes through the person's cell (the
    robot is not already at one of them)."""
    return _blocked(layout, world.robot, world.human.pos, cells)


def in_the_way(layout: Layout, world: WorldState, human_cells: tuple[Pos, ...]) -> bool:
    """Whether the person is trying to get past the robot: it faces the robot's cell (its last move was
    toward it) and every way from it to ``human_cells`` passes through that cell. (A person standing idle
    at a station faces the station, not the robot.)"""
    if world.human.facing.ahead(world.human.pos) != world.robot.pos:
        return False
    return _blocked(layout, world.human, world.robot.pos, human_cells)


def _blocked(layout: Layout, agent: AgentState, other: Pos, cells: tuple[Pos, ...]) -> bool:
    pose = (agent.pos, agent.facing)
    known = [c for c in cells if distance(layout, pose, c) < UNREACHABLE]
    if not known or any(distance(layout, pose, c) == 0 for c in known):
        return False
    return not any(detour_moves(layout, pose, c, other) for c in known)


def reachable(layout: Layout, world: WorldState, cells: tuple[Pos, ...]) -> bool:
    """Whether one of ``cells`` can be reached (or is reached) without passing the person's cell."""
    return any(_clear(layout, world, c) for c in cells)


def within_reach(layout: Layout, world: WorldState, cells: tuple[Pos, ...]) -> tuple[Pos, ...]:
    """The ``cells`` the robot can reach (or has reached) without passing the person's cell."""
    return tuple(c for c in cells if _clear(layout, world, c))


def _clear(layout: Layout, world: WorldState, cell: Pos) -> bool:
    pose = (world.robot.pos, world.robot.facing)
    return distance(layout, pose, cell) == 0 or bool(detour_moves(layout, pose, cell, world.human.pos))


def advance(state: Standoff, layout: Layout, before: AgentState | None, world: WorldState,
            target: tuple[Pos, ...], human_moved: bool, phi: float) -> Standoff:
    """The standoff after the robot observed ``world`` (``before``: the robot one tick earlier; ``target``:
    the cells of the robot's current subtask; ``phi``: the shaping potential of ``world``)."""
    quiet = state.quiet + 1 if state.phi is not None and phi == state.phi else 0
    state = replace(state, phi=phi, quiet=quiet)
    if human_moved:
        state = replace(state, avoid=None, avoid_until=-1, visited=False, beside_until=-1)
    progressed = before is None or before.pos != world.robot.pos or before.held != world.robot.held
    if progressed or not target or not blocked(layout, world, target):
        return replace(state, stuck=0)
    return replace(state, stuck=state.stuck + 1)


def give_up(state: Standoff, subtask: Subtask | None, tick: int, ticks: int) -> Standoff:
    """Avoid ``subtask`` for ``2 × ticks`` ticks; the count starts again."""
    return replace(state, stuck=0, avoid=subtask, avoid_until=tick + 2 * ticks, hold_until=-1)


def hold_aside(state: Standoff, tick: int, ticks: int) -> Standoff:
    """After stepping aside: hold still for ``2 × ticks`` ticks."""
    return replace(state, hold_until=tick + 2 * ticks)


def alternatives(layout: Layout, world: WorldState, options: tuple[Subtask, ...], blocked_subtask: Subtask | None,
                 targets: Targets) -> tuple[Subtask, ...]:
    """The options other than ``blocked_subtask`` the robot can reach without passing the person, and, when
    the robot holds something, putting it down on a free counter."""
    extra = (Subtask.DROP_ON_COUNTER,) if world.robot.held is not None and Subtask.DROP_ON_COUNTER not in options \
        else ()
    return tuple(s for s in options + extra
                 if s is not blocked_subtask and reachable(layout, world, targets(s, world)))


def beside(world: WorldState) -> bool:
    """Whether the robot stands on a cell next to the person's."""
    return manhattan(world.robot.pos, world.human.pos) == 1


def arrive(state: Standoff, tick: int, ticks: int) -> Standoff:
    """Beside the still person: hold there ``ticks`` ticks (from the first tick beside it)."""
    return state if state.beside_until >= 0 else replace(state, beside_until=tick + ticks)


def visit_done(state: Standoff) -> Standoff:
    """The visit is over (held its ticks, or no cell beside the person can be reached)."""
    return replace(state, visited=True, beside_until=-1)


def unaided(world: WorldState) -> WorldState:
    """``world`` as the robot judges its options in a team stall: the person's hands empty, so nothing the
    person carries is counted on."""
    return replace(world, human=replace(world.human, held=None))


def committed(options: tuple[Subtask, ...], current: Subtask | None) -> tuple[Subtask, ...]:
    """In a team stall: the robot's current subtask alone while it is among ``options``, else ``options``."""
    return (current,) if current in options else options


def take_over(human_subtask: Subtask | None, choices: tuple[Subtask, ...]) -> Subtask | None:
    """The person's stalled subtask, when the robot can do it (it is among ``choices``)."""
    return human_subtask if human_subtask in choices else None


def out_of_the_way(layout: Layout, world: WorldState, human_cells: tuple[Pos, ...], person_still: bool) -> Action:
    """With nothing to do (:data:`planner.subtasks.NOTHING_NEEDED`): stay, or step aside when every way from the
    person to ``human_cells`` (the targets of its most likely subtask) passes the robot's cell, or when the
    robot stands next to a person who stands still (``person_still``: e.g. waiting at the grill). An idle robot
    parked beside a waiting person reads as wanting the spot: the simulated person yields it
    (:meth:`planner.human.HumanModel.act`), comes back once the robot is still, and yields again, for as long as
    the robot idles there (docs/domain.md §5, "Never more than the orders need"). A person walking past is let pass."""
    crowding = person_still and manhattan(world.robot.pos, world.human.pos) == 1
    if crowding or _blocked(layout, world.human, world.robot.pos, human_cells):
        return step_aside(layout, world, human_cells)
    return Action.STAY


def step_aside(layout: Layout, world: WorldState, human_cells: tuple[Pos, ...]) -> Action:
    """The move to a free neighbouring floor cell that is off the person's way to ``human_cells`` (the
    targets of its most likely subtask: from there the person can still reach one), farther from the person
    on ties; ``STAY`` when the robot cannot move."""
    robot, human = world.robot.pos, world.human.pos
    pose = (human, world.human.facing)

    def clear(cell: Pos) -> bool:
        return any(distance(layout, pose, c) == 0 or detour_moves(layout, pose, c, cell) for c in human_cells)

    moves = [(clear(d.ahead(robot)), manhattan(d.ahead(robot), human), -i, d) for i, d in enumerate(DIRECTIONS)
             if d.ahead(robot) in layout.floor and d.ahead(robot) != human]
    if not moves:
        return Action.STAY
    return move_action(max(moves)[3])
