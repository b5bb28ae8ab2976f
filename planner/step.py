"""The world's transition: ``step(layout, state, {"human": a, "robot": b}) -> (state, events)`` (DOMAIN §1).

Order inside one step: interacts (robot first, then human) on the faced cell, then moves (a move turns
the agent and steps only onto floor; if both would end on the same cell or swap cells, neither moves,
both still turn), then the world's own effects (each occupied grill cooks one tick, up to ``cook_time``).
"""

from __future__ import annotations

from collections.abc import Mapping

from planner.events import Event, EventKind
from planner.geometry import Action, Pos
from planner.layout import Layout, Terrain
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import AgentState, WorldState

DEFAULT_RULES = Rules()
_DISPENSED = {Terrain.ONION: ONION, Terrain.MEAT: MEAT, Terrain.PLATE: DIRTY_PLATE}


class _Scratch:
    """The mutable working copy of one step; never escapes :func:`step`."""

    __slots__ = ("objects", "grills", "boards", "sinks", "orders_left", "score", "events")

    def __init__(self, state: WorldState) -> None:
        self.objects: dict[Pos, str] = dict(state.objects)
        self.grills = list(state.grills)
        self.boards = list(state.boards)
        self.sinks = list(state.sinks)
        self.orders_left = state.orders_left
        self.score = state.score
        self.events: list[Event] = []


def step(layout: Layout, state: WorldState, joint_action: Mapping[str, Action],
         rules: Rules = DEFAULT_RULES) -> tuple[WorldState, tuple[Event, ...]]:
    """Apply one joint action. Pure: the input state is not changed."""
    w = _Scratch(state)
    agents = {"robot": state.robot, "human": state.human}
    for name in ("robot", "human"):
        if joint_action[name] is Action.INTERACT:
            agents[name] = _interact(layout, rules, w, name, agents[name])
    _move(layout, agents, joint_action, w)
    grills = tuple(g + 1 if g is not None and g < rules.cook_time else g for g in w.grills)
    new_state = WorldState(
        human=agents["human"], robot=agents["robot"],
        objects=tuple(sorted(w.objects.items())) if w.objects else (),
        grills=grills, boards=tuple(w.boards), sinks=tuple(w.sinks),
        orders_left=w.orders_left, tick=state.tick + 1, score=w.score,
    )
    return new_state, tuple(w.events)


def _interact(layout: Layout, rules: Rules, w: _Scratch, name: str, agent: AgentState) -> AgentState:
    target = agent.facing.ahead(agent.pos)
    entry = layout.stations.get(target)
    if entry is None:
        return agent
    kind, i = entry
    held = agent.held
    new_held = held
    event: EventKind | None = None
    obj = held
    if kind is Terrain.COUNTER:
        there = w.objects.get(target)
        if there is None and held is not None:
            w.objects[target] = held
            new_held, event = None, EventKind.PUT_DOWN
        elif there is not None and held is None:
            del w.objects[target]
            new_held, event, obj = there, EventKind.PICK_UP, there
        elif there is not None and held is not None:
            w.objects[target] = held
            new_held, event, obj = there, EventKind.SWAP, there
    elif kind in _DISPENSED:
        if held is None:
            new_held = obj = _DISPENSED[kind]
            event = EventKind.DISPENSE
    elif kind is Terrain.GRILL:
        status = w.grills[i]
        if status is None and held == MEAT:
            w.grills[i], new_held, event = 0, None, EventKind.START_COOKING
        elif status is not None and status >= rules.cook_time and held == CLEAN_PLATE:
            w.grills[i], new_held, event = None, STEAK_PLATE, EventKind.PLATE_STEAK
    elif kind is Terrain.SINK:
        status = w.sinks[i]
        if status is None and held == DIRTY_PLATE:
            w.sinks[i], new_held, event = 0, None, EventKind.LOAD_SINK
        elif status is not None and held is None:
            if status < rules.wash_time:
                w.sinks[i], event, obj = status + 1, EventKind.WASH, DIRTY_PLATE
            else:
                w.sinks[i], new_held, event, obj = None, CLEAN_PLATE, EventKind.TAKE_CLEAN_PLATE, CLEAN_PLATE
    elif kind is Terrain.BOARD:
        status = w.boards[i]
        if status is None and held == ONION:
            w.boards[i], new_held, event = 0, None, EventKind.LOAD_BOARD
        elif status is not None and status < rules.chop_time and held is None:
            w.boards[i], event, obj = status + 1, EventKind.CHOP, ONION
        elif status is not None and status >= rules.chop_time and held == STEAK_PLATE:
            w.boards[i], new_held, event, obj = None, DISH, EventKind.GARNISH, DISH
    elif kind is Terrain.SERVE:
        if held == DISH and w.orders_left > 0:
            w.orders_left -= 1
            w.score += rules.delivery_reward
            new_held, event = None, EventKind.DELIVER
    if event is None:
        return agent
    w.events.append(Event(name, event, target, obj))
    return AgentState(agent.pos, agent.facing, new_held)


def _move(layout: Layout, agents: dict[str, AgentState], joint_action: Mapping[str, Action],
          w: _Scratch) -> None:
    intended: dict[str, AgentState] = {}
    for name, agent in agents.items():
        direction = joint_action[name].direction
        if direction is None:
            intended[name] = agent
            continue
        ahead = direction.ahead(agent.pos)
        pos = ahead if ahead in layout.floor else agent.pos
        intended[name] = AgentState(pos, direction, agent.held)
    r_old, h_old = agents["robot"].pos, agents["human"].pos
    r_new, h_new = intended["robot"].pos, intended["human"].pos
    if r_new == h_new or (r_new == h_old and h_new == r_old):
        for name, agent in agents.items():
            turned = intended[name]
            if turned.pos != agent.pos:
                w.events.append(Event(name, EventKind.BLOCKED, turned.pos))
            agents[name] = AgentState(agent.pos, turned.facing, agent.held)
        return
    agents.update(intended)
