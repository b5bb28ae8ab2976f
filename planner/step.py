"""The world's transition: ``step(layout, state, {"human": a, "robot": b}) -> (state, events)`` (docs/domain.md §1).

Order inside one step: interacts (robot first, then human) on the faced cell, then moves (a move turns
the agent and steps only onto floor; if both would end on the same cell or swap cells, neither moves,
both still turn), then the world's own effects (each occupied grill cooks one tick, up to ``cook_time``).
"""

from __future__ import annotations

from collections.abc import Mapping

from planner.events import Event, EventKind
from planner.geometry import Action, Direction, Pos
from planner.layout import Layout, Terrain
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import AgentState, WorldState

DEFAULT_RULES = Rules()
_DISPENSED = {Terrain.ONION: ONION, Terrain.MEAT: MEAT, Terrain.PLATE: DIRTY_PLATE}


class _Scratch:
    """The mutable working copy of one step, made only when someone interacts; never escapes :func:`step`."""

    __slots__ = ("boards", "events", "grills", "objects", "orders_left", "score", "sinks")

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
    robot, human = state.robot, state.human
    r_action, h_action = joint_action["robot"], joint_action["human"]
    w: _Scratch | None = None
    if r_action is Action.INTERACT or h_action is Action.INTERACT:
        w = _Scratch(state)
        if r_action is Action.INTERACT:
            robot = _interact(layout, rules, w, "robot", robot)
        if h_action is Action.INTERACT:
            human = _interact(layout, rules, w, "human", human)
    robot, human, blocked = _move(layout, robot, human, r_action, h_action)
    if w is None:
        objects, grills, boards, sinks = state.objects, state.grills, state.boards, state.sinks
        orders_left, score, events = state.orders_left, state.score, blocked
    else:
        objects = tuple(sorted(w.objects.items())) if w.objects else ()
        grills, boards, sinks = tuple(w.grills), tuple(w.boards), tuple(w.sinks)
        orders_left, score, events = w.orders_left, w.score, tuple(w.events) + blocked
    cook = rules.cook_time
    if any(g is not None and g < cook for g in grills):
        grills = tuple(g + 1 if g is not None and g < cook else g for g in grills)
    new_state = WorldState(human=human, robot=robot, objects=objects, grills=grills, boards=boards,
                           sinks=sinks, orders_left=orders_left, tick=state.tick + 1, score=score)
    return new_state, events


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
    elif kind is Terrain.SERVE and held == DISH and w.orders_left > 0:
        w.orders_left -= 1
        w.score += rules.delivery_reward
        new_held, event = None, EventKind.DELIVER
    if event is None:
        return agent
    w.events.append(Event(name, event, target, obj))
    return AgentState(agent.pos, agent.facing, new_held)


def _move(layout: Layout, robot: AgentState, human: AgentState, r_action: Action,
          h_action: Action) -> tuple[AgentState, AgentState, tuple[Event, ...]]:
    r_dir, h_dir = r_action.direction, h_action.direction
    if r_dir is None and h_dir is None:
        return robot, human, ()
    r_new = _turn_and_step(layout, robot, r_dir)
    h_new = _turn_and_step(layout, human, h_dir)
    if r_new.pos == h_new.pos or (r_new.pos == human.pos and h_new.pos == robot.pos):
        blocked = tuple(Event(name, EventKind.BLOCKED, new.pos)
                        for name, old, new in (("robot", robot, r_new), ("human", human, h_new))
                        if new.pos != old.pos)
        return (AgentState(robot.pos, r_new.facing, robot.held),
                AgentState(human.pos, h_new.facing, human.held), blocked)
    return r_new, h_new, ()


def _turn_and_step(layout: Layout, agent: AgentState, direction: Direction | None) -> AgentState:
    if direction is None:
        return agent
    ahead = direction.ahead(agent.pos)
    return AgentState(ahead if ahead in layout.floor else agent.pos, direction, agent.held)
