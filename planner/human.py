"""The simulated human (paper §IV-A; docs/domain.md §4): used in simulation and as the robot's model of the person.

It commits to a subtask until the subtask is done or becomes unavailable in its KB, then picks uniformly
at random (from the generator passed in) among the available subtasks. It walks a shortest path over
(cell, facing), re-planned every tick around its partner, and interacts when it faces its target. When it
has been stuck for two ticks it takes a random free move: it wanted to move but did not, or, as the reference's
human model has it (``auto_unstuck``), it interacted and nothing changed (the same pose, the same hands, the same
content of the cell it faces), e.g. waiting at a station its KB believes busy while it is not; or it interacted
twice and undid the first (it put down what it held and took it up again, where its KB offers it nothing else).

The same model drives either agent: ``me`` names the avatar it controls. For the human the partner's held
object comes from its KB (what it last acknowledged the robot holding); for a simulated partner in the
robot's place, from the world.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from planner.geometry import DIRECTIONS, MOVES, Action, Pos, manhattan, move_action
from planner.kb import KnowledgeBase
from planner.layout import Layout, Terrain
from planner.paths import UNREACHABLE, Pose, best_moves, detour_moves, distances_to, next_pose
from planner.rules import Rules
from planner.state import WorldState
from planner.subtasks import Believed, Subtask, available, is_done, targets

STUCK_TICKS = 2
"""Ticks a cook (or its partner) stands still before it is taken as stuck or parked; the participant's avatar
walks around a robot parked this long by the same rule (``planner.avatar``)."""
WAIT_WHEN_BLOCKED = 0.5
YIELD_TICKS = 4
_DIRECTION_OF = {move_action(d): d for d in DIRECTIONS}


@dataclass(frozen=True, slots=True)
class HumanMemory:
    """What the model carries between ticks: its subtask, what it held, and how long it has been stuck."""

    subtask: Subtask | None = None
    held: str | None = None
    last_pose: Pose | None = None
    wants_move: bool = False
    still: int = 0
    partner_pos: Pos | None = None
    partner_still: int = 0
    yielding: int = 0
    interacted: bool = False
    faced: object = None
    """What the cell it faced held when it last acted (a counter's object or a station's count)."""
    before: tuple[str | None, object] | None = None
    """What it held and faced the tick before, when it interacted from the same pose then too."""

    def to_dict(self) -> dict[str, object]:
        return {"subtask": None if self.subtask is None else self.subtask.value, "held": self.held,
                "still": self.still}


@dataclass(frozen=True, slots=True)
class HumanModel:
    layout: Layout
    rules: Rules
    me: str = "human"

    @property
    def partner(self) -> str:
        return "robot" if self.me == "human" else "human"

    def believed(self, world: WorldState, kb: KnowledgeBase) -> Believed:
        partner_held = ((kb.robot.held if kb.robot is not None else None) if self.me == "human"
                        else world.human.held)
        return Believed(kb=kb, held=world.agent(self.me).held, partner_held=partner_held,
                        orders_left=world.orders_left)

    def commit(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
               rng: np.random.Generator) -> Subtask:
        """The subtask after this tick's observation: keep the current one or choose anew (uniformly among
        the available subtasks, drawn from ``rng`` only when there is a choice)."""
        b = self.believed(world, kb)
        kept, options = _choice(self.layout, self.rules, kb.objects, kb.grills, kb.boards, kb.sinks, b.held,
                                b.partner_held, b.orders_left, memory.subtask, memory.held)
        if kept is not None:
            return kept
        return options[int(rng.integers(len(options)))] if len(options) > 1 else options[0]

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]:
        """One tick of the model: the action to take and the memory to carry."""
        subtask = self.commit(world, kb, memory, rng)
        agent = world.agent(self.me)
        pose: Pose = (agent.pos, agent.facing)
        partner_pos = world.agent(self.partner).pos
        faced = _content(self.layout, world, agent.facing.ahead(agent.pos))
        here = memory.interacted and memory.last_pose == pose
        now = (agent.held, faced)
        fruitless = here and ((memory.held, memory.faced) == now or memory.before == now)
        still = memory.still + 1 if (memory.wants_move or fruitless) and memory.last_pose == pose else 0
        partner_still = memory.partner_still + 1 if memory.partner_pos == partner_pos else 0
        action, wants_move = self.move_toward(pose, targets(self.layout, subtask, kb, self.rules), partner_pos,
                                              rng, partner_parked=partner_still >= STUCK_TICKS)
        yielding = max(memory.yielding - 1, 0)
        if yielding and action is not Action.INTERACT:
            action, wants_move = Action.STAY, False
        elif (wants_move or action is Action.INTERACT) and still >= STUCK_TICKS:
            action, still = self.random_free_move(pose, partner_pos, rng), 0
        elif (action is Action.INTERACT and self.waiting(subtask, kb) and partner_still >= STUCK_TICKS
              and manhattan(pose[0], partner_pos) == 1):
            action, yielding = self.random_free_move(pose, partner_pos, rng), YIELD_TICKS
        return action, HumanMemory(subtask=subtask, held=agent.held, last_pose=pose, wants_move=wants_move,
                                   still=still, partner_pos=partner_pos, partner_still=partner_still,
                                   yielding=yielding, interacted=action is Action.INTERACT, faced=faced,
                                   before=(memory.held, memory.faced) if here else None)

    def waiting(self, subtask: Subtask, kb: KnowledgeBase) -> bool:
        """Whether interacting now only waits (steak not ready, garnish not chopped): then it yields the
        spot to a partner that has been standing still next to it, stepping aside and holding still for
        ``YIELD_TICKS`` ticks (unless its target comes within reach)."""
        if subtask is Subtask.PICKUP_STEAK:
            return not any(g is not None and g >= self.rules.cook_time for g in kb.grills)
        if subtask is Subtask.PICKUP_GARNISH:
            return not any(self.rules.chopped(b) for b in kb.boards)
        return False

    def move_toward(self, pose: Pose, cells: tuple[Pos, ...], blocked: Pos,
                    rng: np.random.Generator | None = None, partner_parked: bool = False) -> tuple[Action, bool]:
        """Interact if facing the nearest target; else the first move along a shortest path to it.

        When the partner stands on every shortest path: wait with probability ``WAIT_WHEN_BLOCKED``, else a
        shortest detour around it, chosen at random among equals (randomness breaks the symmetric dance of two
        agents dodging the same way at the same time). A partner that has not moved for two ticks
        (``partner_parked``) is walked around: the path avoids its cell all the way. Also answers whether
        the model wants to move (it is not yet at its target).
        """
        fixed, detours = _route(self.layout, pose, cells, blocked, partner_parked)
        if fixed is not None:
            return fixed
        if not detours or (rng is not None and rng.random() < WAIT_WHEN_BLOCKED):
            return Action.STAY, True
        if len(detours) == 1 or rng is None:
            return detours[0], True
        return detours[int(rng.integers(len(detours)))], True

    def random_free_move(self, pose: Pose, blocked: Pos, rng: np.random.Generator) -> Action:
        free = [m for m in MOVES if _free(self.layout, pose, m, blocked)]
        if not free:
            return Action.STAY
        return free[int(rng.integers(len(free)))]


@lru_cache(maxsize=1 << 16)
def _choice(layout: Layout, rules: Rules, objects: tuple[tuple[Pos, str], ...], grills: tuple[int | None, ...],
            boards: tuple[int | None, ...], sinks: tuple[int | None, ...], held: str | None,
            partner_held: str | None, orders_left: int, current: Subtask | None,
            held_before: str | None) -> tuple[Subtask | None, tuple[Subtask, ...]]:
    """The deterministic part of :meth:`HumanModel.commit`, from the parts of the KB it reads, cached (every
    rollout tick asks it, mostly about the same few kitchens): the current subtask when it is kept, else
    ``None`` and the options to choose among."""
    kb = KnowledgeBase(objects=objects, grills=grills, boards=boards, sinks=sinks, robot=None)
    b = Believed(kb=kb, held=held, partner_held=partner_held, orders_left=orders_left)
    if current is not None and is_done(current, held_before, held, b, rules):
        return None, available(b, rules, current)
    options = available(b, rules, current)
    if current is not None and current in options and targets(layout, current, kb, rules):
        return current, options
    return None, options


@lru_cache(maxsize=1 << 17)
def _route(layout: Layout, pose: Pose, cells: tuple[Pos, ...], blocked: Pos,
           partner_parked: bool) -> tuple[tuple[Action, bool] | None, tuple[Action, ...]]:
    """The deterministic part of :meth:`HumanModel.move_toward`, cached: the paths between the same poses
    and targets come back every tick and in every rollout. Either the answer, or (``None``, the detours
    around a partner on every shortest path) for the random choice among them."""
    best, best_d = None, UNREACHABLE
    for cell in cells:
        d = distances_to(layout, cell).get(pose, UNREACHABLE)
        if d < best_d:
            best, best_d = cell, d
    if best is None:
        return (Action.STAY, False), ()
    if best_d == 0:
        return (Action.INTERACT, False), ()
    if partner_parked:
        around = detour_moves(layout, pose, best, blocked)
        if around:
            return (around[0], True), ()
    moves = best_moves(layout, pose, best, blocked)
    if moves:
        return (moves[0], True), ()
    return None, detour_moves(layout, pose, best, blocked)


def _free(layout: Layout, pose: Pose, move: Action, blocked: Pos) -> bool:
    target = next_pose(layout, pose, _DIRECTION_OF[move])[0]
    return target != pose[0] and target != blocked


def _content(layout: Layout, world: WorldState, cell: Pos) -> object:
    """What ``cell`` holds: a counter's object, or a grill's, board's or sink's count (``None`` for nothing)."""
    entry = layout.stations.get(cell)
    if entry is None:
        return None
    kind, i = entry
    if kind is Terrain.GRILL:
        return world.grills[i]
    if kind is Terrain.BOARD:
        return world.boards[i]
    if kind is Terrain.SINK:
        return world.sinks[i]
    return world.object_at(cell)
