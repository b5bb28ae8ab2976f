"""Human subtasks and when they are available, judged on the human's KB (docs/domain.md §4, paper §IV-A).

Holding something forces its continuation (onion → board, meat → grill, dirty plate → sink, clean plate →
grill, plated steak → board, dish → serving counter); when the station it needs is believed unusable
(grill/board/sink occupied, nothing cooking, no garnish coming) the human puts the object on a counter.
Empty-handed: keep chopping / washing if it was doing so and the work is unfinished; else every one of
pickup meat (a grill empty, orders left, partner not holding meat), pickup onion (a board empty, partner
not holding an onion), pickup plate (a sink empty, partner not holding a plate), pickup clean plate (a
plate clean, a steak cooking or ready, and a garnish on the board or the partner holding an onion). If
none applies: pickup plate.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from functools import lru_cache
from typing import Protocol

from planner.geometry import Pos
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules


class Subtask(str, Enum):
    PICKUP_MEAT = "pickup_meat"
    PICKUP_ONION = "pickup_onion"
    PICKUP_PLATE = "pickup_plate"
    PICKUP_CLEAN_PLATE = "pickup_clean_plate"
    PICKUP_STEAK = "pickup_steak"
    PICKUP_GARNISH = "pickup_garnish"
    DROP_MEAT = "drop_meat"
    DROP_ONION = "drop_onion"
    DROP_PLATE = "drop_plate"
    CHOP_ONION = "chop_onion"
    WASH_PLATE = "wash_plate"
    DELIVER_DISH = "deliver_dish"
    DROP_ON_COUNTER = "drop_on_counter"


SUBTASKS: tuple[Subtask, ...] = tuple(Subtask)
PLATES = (DIRTY_PLATE, CLEAN_PLATE)


@dataclass(frozen=True, slots=True)
class Believed:
    """The facts availability is judged on: the KB, what the human holds, what it believes the partner holds."""

    kb: KnowledgeBase
    held: str | None
    partner_held: str | None
    orders_left: int


def available(b: Believed, rules: Rules, current: Subtask | None = None) -> tuple[Subtask, ...]:
    """The subtasks the human may choose now (docs/domain.md §4); never empty."""
    kb = b.kb
    if b.held is not None:
        return (forced_continuation(b),)
    if current in (Subtask.CHOP_ONION, Subtask.DROP_ONION) and any(
            rules.chopping(s) for s in kb.boards):
        return (Subtask.CHOP_ONION,)
    if current in (Subtask.WASH_PLATE, Subtask.DROP_PLATE) and any(
            rules.washing(s) for s in kb.sinks):
        return (Subtask.WASH_PLATE,)
    options = []
    if any(g is None for g in kb.grills) and b.orders_left > 0 and b.partner_held != MEAT:
        options.append(Subtask.PICKUP_MEAT)
    if any(s is None for s in kb.boards) and b.partner_held != ONION:
        options.append(Subtask.PICKUP_ONION)
    if any(s is None for s in kb.sinks) and b.partner_held not in PLATES:
        options.append(Subtask.PICKUP_PLATE)
    plate_clean = any(rules.clean(s) for s in kb.sinks)
    steak = any(g is not None for g in kb.grills)
    garnish = any(s is not None for s in kb.boards) or b.partner_held == ONION
    if plate_clean and steak and garnish:
        options.append(Subtask.PICKUP_CLEAN_PLATE)
    return tuple(options) or (Subtask.PICKUP_PLATE,)


def forced_continuation(b: Believed) -> Subtask:
    kb, held = b.kb, b.held
    if held == ONION:
        return Subtask.DROP_ONION if any(s is None for s in kb.boards) else Subtask.DROP_ON_COUNTER
    if held == MEAT:
        return Subtask.DROP_MEAT if any(g is None for g in kb.grills) else Subtask.DROP_ON_COUNTER
    if held == DIRTY_PLATE:
        return Subtask.DROP_PLATE if any(s is None for s in kb.sinks) else Subtask.DROP_ON_COUNTER
    if held == CLEAN_PLATE:
        return Subtask.PICKUP_STEAK if any(g is not None for g in kb.grills) else Subtask.DROP_ON_COUNTER
    if held == STEAK_PLATE:
        garnish = any(s is not None for s in kb.boards) or b.partner_held == ONION
        return Subtask.PICKUP_GARNISH if garnish else Subtask.DROP_ON_COUNTER
    return Subtask.DELIVER_DISH


class Kitchen(Protocol):
    """What :func:`targets` reads: a KB (the kitchen as someone believes it) or the world itself."""

    @property
    def objects(self) -> tuple[tuple[Pos, str], ...]: ...
    @property
    def grills(self) -> tuple[int | None, ...]: ...
    @property
    def boards(self) -> tuple[int | None, ...]: ...
    @property
    def sinks(self) -> tuple[int | None, ...]: ...


def targets(layout: Layout, subtask: Subtask, kb: Kitchen, rules: Rules) -> tuple[Pos, ...]:
    """The cells the human would interact with to do ``subtask``, as its KB sees the kitchen (or, given the
    world, as it is)."""
    return _targets(layout, subtask, kb.objects, kb.grills, kb.boards, kb.sinks, rules)


@lru_cache(maxsize=1 << 15)
def _targets(layout: Layout, subtask: Subtask, objects: tuple[tuple[Pos, str], ...], grills: tuple[int | None, ...],
             boards: tuple[int | None, ...], sinks: tuple[int | None, ...], rules: Rules) -> tuple[Pos, ...]:
    """:func:`targets` from the KB's parts it reads, cached (the same few KBs come back every tick)."""
    def counters_with(obj: str) -> tuple[Pos, ...]:
        return tuple(p for p, o in objects if o == obj)

    def where(cells: tuple[Pos, ...], statuses: tuple[int | None, ...],
              test: Callable[[int | None], bool]) -> tuple[Pos, ...]:
        return tuple(c for c, s in zip(cells, statuses, strict=True) if test(s))

    if subtask is Subtask.PICKUP_MEAT:
        return layout.meats + counters_with(MEAT)
    if subtask is Subtask.PICKUP_ONION:
        return layout.onions + counters_with(ONION)
    if subtask is Subtask.PICKUP_PLATE:
        return layout.plates + counters_with(DIRTY_PLATE)
    if subtask is Subtask.PICKUP_CLEAN_PLATE:
        return where(layout.sinks, sinks, rules.clean) + \
            counters_with(CLEAN_PLATE)
    if subtask is Subtask.PICKUP_STEAK:
        return where(layout.grills, grills, lambda s: s is not None) or layout.grills
    if subtask is Subtask.PICKUP_GARNISH:
        return where(layout.boards, boards, lambda s: s is not None) or layout.boards
    if subtask is Subtask.DROP_MEAT:
        return where(layout.grills, grills, lambda s: s is None)
    if subtask is Subtask.DROP_ONION:
        return where(layout.boards, boards, lambda s: s is None)
    if subtask is Subtask.DROP_PLATE:
        return where(layout.sinks, sinks, lambda s: s is None)
    if subtask is Subtask.CHOP_ONION:
        return where(layout.boards, boards, rules.chopping)
    if subtask is Subtask.WASH_PLATE:
        return where(layout.sinks, sinks, rules.washing)
    if subtask is Subtask.DELIVER_DISH:
        return layout.serves
    occupied = {p for p, _ in objects}
    return tuple(c for c in layout.counters if c not in occupied)


def is_done(subtask: Subtask, held_before: str | None, held: str | None, b: Believed, rules: Rules) -> bool:
    """Whether ``subtask`` finished in the last step, from what the human holds before and after."""
    return finished(subtask, held_before, held, b.kb.boards, b.kb.sinks, rules)


def finished(subtask: Subtask, held_before: str | None, held: str | None, boards: tuple[int | None, ...],
             sinks: tuple[int | None, ...], rules: Rules) -> bool:
    """:func:`is_done` from the only parts of a KB it reads (the boards and sinks), so a caller that judges
    on the world itself needs no KB built for it."""
    picked = _PICKS.get(subtask)
    if picked is not None:
        return held == picked
    if subtask in _DROPS:
        return held_before is not None and held is None
    if subtask is Subtask.CHOP_ONION:
        return not any(rules.chopping(s) for s in boards)
    if subtask is Subtask.WASH_PLATE:
        return not any(rules.washing(s) for s in sinks)
    return False


_DROPS = frozenset((Subtask.DROP_MEAT, Subtask.DROP_ONION, Subtask.DROP_PLATE, Subtask.DROP_ON_COUNTER,
                    Subtask.DELIVER_DISH))
_PICKS = {
    Subtask.PICKUP_MEAT: MEAT, Subtask.PICKUP_ONION: ONION, Subtask.PICKUP_PLATE: DIRTY_PLATE,
    Subtask.PICKUP_CLEAN_PLATE: CLEAN_PLATE, Subtask.PICKUP_STEAK: STEAK_PLATE,
    Subtask.PICKUP_GARNISH: DISH,
}


def beyond_orders(held: str | None, partner_held: str | None, orders_left: int,
                  objects: tuple[tuple[Pos, str], ...], grills: tuple[int | None, ...],
                  boards: tuple[int | None, ...], sinks: tuple[int | None, ...]) -> frozenset[Subtask]:
    """The steps that would start more of a dish than the orders left need (docs/domain.md §5, "Never more
    than the orders need"), counting what is in progress by anyone: meat on a grill or in a hand; onions on a
    board or in a hand; plates in a sink or a hand, clean plates anywhere; plated steaks and dishes anywhere.
    (A raw item lying on a counter is not counted: picking it up starts nothing new.)"""
    hands = (held, partner_held)

    def anywhere(obj: str) -> int:
        return sum(h == obj for h in hands) + sum(o == obj for _, o in objects)

    dishes = anywhere(DISH)
    plated = anywhere(STEAK_PLATE) + dishes
    steaks = sum(g is not None for g in grills) + hands.count(MEAT) + plated
    garnishes = sum(b is not None for b in boards) + hands.count(ONION) + dishes
    plates = sum(s is not None for s in sinks) + hands.count(DIRTY_PLATE) + anywhere(CLEAN_PLATE) + plated
    counts = [(Subtask.PICKUP_MEAT, steaks), (Subtask.PICKUP_ONION, garnishes), (Subtask.PICKUP_PLATE, plates),
              (Subtask.PICKUP_CLEAN_PLATE, hands.count(CLEAN_PLATE) + plated)]
    if held is not None:  # with empty hands these two only resume put-down work (:data:`RESUMED`)
        counts += [(Subtask.PICKUP_STEAK, plated), (Subtask.PICKUP_GARNISH, dishes)]
    return frozenset(s for s, n in counts if n >= orders_left)


NOTHING_NEEDED: tuple[Subtask, ...] = (Subtask.DROP_ON_COUNTER,)
"""The robot's options when no step is needed of it: put its load down; with empty hands it keeps out of the
way (:func:`planner.standoff.out_of_the_way`)."""


def within_orders(options: tuple[Subtask, ...], unneeded: frozenset[Subtask]) -> tuple[Subtask, ...]:
    """``options`` without the ``unneeded`` steps; :data:`NOTHING_NEEDED` when none is left."""
    return tuple(s for s in options if s not in unneeded) or NOTHING_NEEDED


RESUMED: dict[Subtask, str] = {Subtask.PICKUP_STEAK: STEAK_PLATE, Subtask.PICKUP_GARNISH: DISH}
"""For the robot with empty hands: a plated steak or a dish someone put down on a counter is picked up again by
the subtask that makes it (picking it up finishes that subtask), so put-down work is resumed, not made anew."""


def resumable(held: str | None, objects: tuple[tuple[Pos, str], ...], boards: tuple[int | None, ...],
              rules: Rules) -> tuple[Subtask, ...]:
    """The robot's options to resume put-down work (:data:`RESUMED`): with empty hands, a dish on a counter, and a
    plated steak on a counter while a chopped garnish waits on a board (not before: holding the plate, the robot
    could not chop the onion it would wait for)."""
    if held is not None:
        return ()
    lying = {obj for _, obj in objects}
    garnish = any(rules.chopped(b) for b in boards)
    return tuple(s for s, obj in RESUMED.items() if obj in lying and (obj == DISH or garnish))


def resumed_targets(subtask: Subtask, objects: tuple[tuple[Pos, str], ...]) -> tuple[Pos, ...]:
    """The counters with what ``subtask`` resumes (:data:`RESUMED`), for an agent with empty hands."""
    return tuple(p for p, obj in objects if obj == RESUMED.get(subtask))
