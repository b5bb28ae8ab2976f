"""Who did which work, tick by tick: subtask switches, redundant actions and the share of the prep and
plating work each agent did (docs/domain.md §6, "Who does the work").

Switches and redundant actions are judged from the stored ticks alone (``subtask`` and ``controller`` columns, and
the world state after each step), so they can be recomputed from an export of the store.

**Subtask switch.** At tick t the avatar runs subtask B, at tick t − 1 it ran a different subtask A, and
the controller state stored after tick t − 1 still held A: the participant replaced a subtask that was
neither finished nor cancelled. Choosing a subtask after the previous one finished, re-choosing the running
one, or choosing after a ``stop`` that took effect at an earlier tick is not a switch. (A ``stop`` and a new
choice sent between the same two ticks is a switch: the avatar went straight from A to B.)

**Redundant action** (work the participant started that the robot had already done). At tick t the
participant's avatar goes from empty-handed to holding a raw item, meat, onion or dirty plate (from a
dispenser or a counter), while in the world *before* that step every station that item goes to (grills for
meat, boards for an onion, sinks for a dirty plate) was occupied and at least one of them had been loaded by
the robot. A station is loaded by the agent whose held item of that kind disappears in the step that fills
the station without the item appearing on the counter it faces (which would be a put-down). Items the robot
loads in the same step as the participant's pickup do not count (the participant could not have known).
With several orders open, a pickup that prepares the next order while the robot's item still occupies the
station counts as well: the item cannot be used until the station is free again.

**Work shares** come from the world events each tick stored (``ticks.world_events``, the typed events of
``planner.events``): *prep* = putting meat on a grill, an onion on a board or a dirty plate in a sink,
and every chop and wash press; *plating* = a clean plate taking the steak, the plated steak taking the
garnish, and delivering the dish. ``human_prep_pct`` = 100 · the participant's prep events / all prep
events (both agents), likewise ``human_plating_pct``; ``collisions`` = steps in which a move was cancelled
because the two agents would have met. Empty when no tick of the trial kept its events (ticks stored
before the store's revision 0002) or, for a share, when nobody did such work.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from planner.geometry import Direction
from planner.vocabulary import DIRTY_PLATE, MEAT, ONION

STATION_OF_ITEM: dict[str, str] = {MEAT: "grills", ONION: "boards", DIRTY_PLATE: "sinks"}
PREP_EVENTS = frozenset({"start_cooking", "load_board", "load_sink", "chop", "wash"})
PLATING_EVENTS = frozenset({"plate_steak", "garnish", "deliver"})
COLLISION_EVENT = "blocked"
"""Raw item → the world-state list of the stations it is loaded into."""

World = Mapping[str, Any]
NAN = float("nan")


def subtask_switch_flags(subtasks: Sequence[str | None], controllers: Sequence[Mapping[str, Any]]) -> list[int]:
    """1 at each tick where the participant switched subtask (see the module docstring), else 0.

    ``subtasks[i]`` is the ``subtask`` column of the i-th stored tick, ``controllers[i]`` its ``controller``
    column (the participant's controller state after that tick).
    """
    flags = [0] * len(subtasks)
    for i in range(1, len(subtasks)):
        before, now = subtasks[i - 1], subtasks[i]
        if before and now and before != now and controllers[i - 1].get("subtask") == before:
            flags[i] = 1
    return flags


def redundant_action_flags(initial: World, worlds: Sequence[World]) -> list[int]:
    """1 at each tick where the participant started work the robot had already done, else 0.

    ``initial`` is the trial's initial world state, ``worlds[i]`` the world state stored after the i-th tick.
    """
    loaded_by: dict[str, list[str | None]] = {kind: [None] * len(initial.get(kind, ()))
                                              for kind in STATION_OF_ITEM.values()}
    flags = []
    before = initial
    for after in worlds:
        flags.append(int(_redundant_pickup(before, after, loaded_by)))
        _update_loaders(before, after, loaded_by)
        before = after
    return flags


def _held(world: World, agent: str) -> str | None:
    held = world[agent].get("held")
    return None if held is None else str(held)


def _redundant_pickup(before: World, after: World, loaded_by: dict[str, list[str | None]]) -> bool:
    item = _held(after, "human")
    if _held(before, "human") is not None or item not in STATION_OF_ITEM:
        return False
    kind = STATION_OF_ITEM[item]
    stations = before.get(kind, ())
    return bool(stations) and all(s is not None for s in stations) and "robot" in loaded_by[kind]


def _update_loaders(before: World, after: World, loaded_by: dict[str, list[str | None]]) -> None:
    for item, kind in STATION_OF_ITEM.items():
        filled = []
        for i, (old, new) in enumerate(zip(before.get(kind, ()), after.get(kind, ()), strict=True)):
            if new is None:
                loaded_by[kind][i] = None
            elif old is None or new < old:
                filled.append(i)
        if not filled:
            continue
        loaders = [agent for agent in ("robot", "human") if _loaded(before, after, agent, item)]
        for i, station in enumerate(filled):
            loaded_by[kind][station] = loaders[i] if i < len(loaders) else "unknown"


def _loaded(before: World, after: World, agent: str, item: str) -> bool:
    """Whether ``agent`` let go of ``item`` in this step other than by putting it on the counter it faces."""
    if _held(before, agent) != item or _held(after, agent) is not None:
        return False
    state = after[agent]
    x, y = state["pos"]
    faced = Direction(state["facing"]).ahead((int(x), int(y)))
    on_counter = any(tuple(o["pos"]) == faced and o["obj"] == item for o in after.get("objects", ()))
    return not on_counter


def work_shares(steps: Sequence[Sequence[Mapping[str, Any]] | None]) -> dict[str, float]:
    """``human_prep_pct``, ``human_plating_pct`` and ``collisions`` from each tick's world events (see the
    module docstring); ``steps[i]`` is the ``world_events`` of the i-th stored tick (``None``: not kept)."""
    kept = [events for events in steps if events is not None]
    if not kept:
        return {"human_prep_pct": NAN, "human_plating_pct": NAN, "collisions": NAN}
    counts = {(agent, group): 0 for agent in ("human", "robot") for group in ("prep", "plating")}
    collisions = 0
    for events in kept:
        collisions += any(e.get("kind") == COLLISION_EVENT for e in events)
        for e in events:
            group = "prep" if e.get("kind") in PREP_EVENTS else "plating" if e.get("kind") in PLATING_EVENTS else None
            if group is not None and (e.get("agent"), group) in counts:
                counts[(str(e["agent"]), group)] += 1
    return {"human_prep_pct": _share(counts[("human", "prep")], counts[("robot", "prep")]),
            "human_plating_pct": _share(counts[("human", "plating")], counts[("robot", "plating")]),
            "collisions": float(collisions)}


def _share(human: int, robot: int) -> float:
    return 100.0 * human / (human + robot) if human + robot else NAN
