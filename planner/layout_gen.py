"""Kitchens on demand: seeded random layouts in the paper's style (docs/domain.md §1–§2).

``generate_kitchen(rng, style, size)`` builds one kitchen from the ``numpy.random.Generator`` passed in
(same generator state, same kitchen). A kitchen is a closed room of counters with one of each station on
its counters, in one of four shapes:

* ``island``    – an open room around a counter block that has floor on every side (the paper's ``mid``);
* ``peninsula`` – a counter strip reaching from one wall into the room (the paper's ``side``);
* ``corridor``  – a passage two cells wide, straight, L- or U-shaped; stations line its walls;
* ``split``     – a counter wall across the room with one doorway 2–3 cells wide, a start on each side.

Every kitchen returned satisfies :func:`kitchen_problems` (it returns no problem): it parses as a valid
layout (closed, every station, one start each, every station class reachable by both agents), its floor is
one connected region (so all work is shared), no floor pose of a person with the study's default 120° view
sees every station (so some work always happens out of the other's sight), and the two starts are at least
three steps apart. Drawing retries with the same generator until the kitchen qualifies.
Solvability by a simulated team is tested over many seeds (``tests/planner/test_layout_gen.py``).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from planner.fov import in_view
from planner.geometry import DIRECTIONS, Pos, manhattan
from planner.layout import START_CHARS, STATIONS, Layout, LayoutError, Terrain, parse_layout

STYLES: tuple[str, ...] = ("island", "peninsula", "corridor", "split")
SIZE_RANGES: dict[str, tuple[tuple[int, int], tuple[int, int]]] = {
    "island": ((11, 15), (8, 11)),
    "peninsula": ((10, 15), (8, 11)),
    "corridor": ((10, 15), (7, 10)),
    "split": ((11, 15), (7, 10)),
}
"""Per style, the (min, max) width and height drawn when no size is given (the paper's are 15 × 10–11)."""
MIN_SIZE: dict[str, tuple[int, int]] = {"island": (9, 7), "peninsula": (8, 7), "corridor": (8, 6),
                                        "split": (9, 6)}
"""The smallest grid (walls included) each style fits in."""
MAX_SIDE = 40
VIEW_ANGLE = 120.0
MIN_START_DISTANCE = 3
MIN_DOOR = 2
"""A split kitchen's doorway is 2–3 cells wide: in a one-cell doorway two simulated humans (docs/domain.md §4)
facing each other deadlock (measured on generator seeds 0–99: 10 of 300 simulated-team trials unfinished)."""
ATTEMPTS = 200


class GenerationError(ValueError):
    """A request no kitchen can satisfy (unknown style, too small a size), naming the reason."""


@dataclass(frozen=True, slots=True)
class KitchenRequest:
    """What to draw: a style (``None`` = drawn) and a size ``(width, height)`` with walls (``None`` = drawn)."""

    style: str | None = None
    size: tuple[int, int] | None = None

    def __post_init__(self) -> None:
        if self.style is not None and self.style not in STYLES:
            raise GenerationError(f"unknown style {self.style!r}; known: {', '.join(STYLES)}")
        if self.size is not None:
            width, height = self.size
            for style in (self.style,) if self.style else STYLES:
                min_w, min_h = MIN_SIZE[style]
                if width < min_w or height < min_h:
                    raise GenerationError(f"size {width}x{height} is too small for style {style!r} "
                                          f"(at least {min_w}x{min_h})")
            if width > MAX_SIDE or height > MAX_SIDE:
                raise GenerationError(f"size {width}x{height} is too large (at most {MAX_SIDE} per side)")


def parse_size(text: str) -> tuple[int, int]:
    """``"13x9"`` → ``(13, 9)``; raises :class:`GenerationError` naming the expected form."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.isdigit() for p in parts):
        raise GenerationError(f"size {text!r} is not WIDTHxHEIGHT (e.g. 15x11)")
    return int(parts[0]), int(parts[1])


def generate_kitchen(rng: np.random.Generator, request: KitchenRequest = KitchenRequest(),
                     name: str = "kitchen") -> Layout:
    """One kitchen drawn from ``rng`` (see the module docstring for what every kitchen satisfies)."""
    style = request.style or STYLES[int(rng.integers(len(STYLES)))]
    for _ in range(ATTEMPTS):
        width, height = request.size or _draw_size(rng, style)
        floor, divider = _SHAPES[style](rng, width, height)
        grid = _place(rng, width, height, floor, divider)
        if grid is None:
            continue
        try:
            layout = parse_layout(grid, name=name)
        except LayoutError:
            continue
        if not kitchen_problems(layout):
            return layout
    raise GenerationError(f"no {style} kitchen of size {request.size} qualified after {ATTEMPTS} attempts")


def style_of(layout: Layout) -> str | None:
    """The style a generated kitchen's name carries (``gen_1000_island`` → ``island``), else ``None``."""
    tail = layout.name.rsplit("_", 1)[-1]
    return tail if tail in STYLES else None


def kitchen_problems(layout: Layout, angle: float = VIEW_ANGLE) -> list[str]:
    """What keeps ``layout`` from being a kitchen in the paper's style; empty when it is one.

    Beyond :func:`planner.layout.parse_layout`'s validity: one connected floor, some station out of view
    from every floor pose (at ``angle``), starts at least ``MIN_START_DISTANCE`` apart.
    """
    problems = []
    region = _flood(layout.floor, layout.start("human"))
    if region != layout.floor:
        problems.append(f"{len(layout.floor) - len(region)} floor cells cannot be reached")
    stations = [pos for kind in STATIONS for pos in _cells(layout, kind)]
    seen_all = next(((pos, facing) for pos in sorted(layout.floor) for facing in DIRECTIONS
                     if all(in_view(pos, facing, s, angle) for s in stations)), None)
    if seen_all is not None:
        problems.append(f"every station is in view from {seen_all[0]} facing {seen_all[1].value}")
    if manhattan(layout.start("human"), layout.start("robot")) < MIN_START_DISTANCE:
        problems.append("the starts are closer than 3 steps")
    return problems


def _cells(layout: Layout, kind: Terrain) -> tuple[Pos, ...]:
    return {Terrain.ONION: layout.onions, Terrain.MEAT: layout.meats, Terrain.PLATE: layout.plates,
            Terrain.GRILL: layout.grills, Terrain.BOARD: layout.boards, Terrain.SINK: layout.sinks,
            Terrain.SERVE: layout.serves}[kind]


def _draw_size(rng: np.random.Generator, style: str) -> tuple[int, int]:
    (w0, w1), (h0, h1) = SIZE_RANGES[style]
    return int(rng.integers(w0, w1 + 1)), int(rng.integers(h0, h1 + 1))


Room = tuple[set[Pos], int | None]
"""A shape's floor cells and, for a split kitchen, the column of its dividing counter wall."""


def _rect(x0: int, y0: int, x1: int, y1: int) -> set[Pos]:
    """Cells with ``x0 <= x <= x1`` and ``y0 <= y <= y1``."""
    return {(x, y) for x in range(x0, x1 + 1) for y in range(y0, y1 + 1)}


def _island(rng: np.random.Generator, w: int, h: int) -> Room:
    floor = _rect(1, 1, w - 2, h - 2)
    iw = int(rng.integers(2, w - 2 - 4 + 1))
    ih = int(rng.integers(1, min(h - 2 - 4, 3) + 1))
    x0 = int(rng.integers(3, w - 3 - iw + 1))
    y0 = int(rng.integers(3, h - 3 - ih + 1))
    return floor - _rect(x0, y0, x0 + iw - 1, y0 + ih - 1), None


def _peninsula(rng: np.random.Generator, w: int, h: int) -> Room:
    floor = _rect(1, 1, w - 2, h - 2)
    side = int(rng.integers(4))
    thick = int(rng.integers(1, 3))
    if side < 2:  # from the north or south wall, reaching down or up
        reach = int(rng.integers(max((h - 2) * 2 // 5, 1), max((h - 2) - 2, 1) + 1))
        x0 = int(rng.integers(3, w - 3 - thick + 1))
        ys = (1, reach) if side == 0 else (h - 1 - reach, h - 2)
        return floor - _rect(x0, ys[0], x0 + thick - 1, ys[1]), None
    reach = int(rng.integers(max((w - 2) * 2 // 5, 1), max((w - 2) - 2, 1) + 1))
    y0 = int(rng.integers(3, h - 3 - thick + 1))
    xs = (1, reach) if side == 2 else (w - 1 - reach, w - 2)
    return floor - _rect(xs[0], y0, xs[1], y0 + thick - 1), None


def _corridor(rng: np.random.Generator, w: int, h: int) -> Room:
    shape = int(rng.integers(3))
    if shape == 0:  # straight, somewhere across the room
        y0 = int(rng.integers(1, h - 3 + 1))
        return _rect(1, y0, w - 2, y0 + 1), None
    top = _rect(1, 1, w - 2, 2)
    right = _rect(w - 3, 1, w - 2, h - 2)
    if shape == 1:  # L: along the top, down one side
        return (top | right if rng.random() < 0.5 else top | _rect(1, 1, 2, h - 2)), None
    return top | right | _rect(1, 1, 2, h - 2), None  # U, open side down


def _split(rng: np.random.Generator, w: int, h: int) -> Room:
    floor = _rect(1, 1, w - 2, h - 2)
    wall_x = int(rng.integers(4, w - 5 + 1))
    door = int(rng.integers(MIN_DOOR, MIN_DOOR + 2))
    door_y = int(rng.integers(1, h - 1 - door + 1))
    return floor - (_rect(wall_x, 1, wall_x, h - 2) - _rect(wall_x, door_y, wall_x, door_y + door - 1)), wall_x


_SHAPES = {"island": _island, "peninsula": _peninsula, "corridor": _corridor, "split": _split}


def _place(rng: np.random.Generator, w: int, h: int, floor: set[Pos], divider: int | None) -> str | None:
    """The grid text: stations on counters next to the floor, spread apart, and the two starts."""
    around = [(x, y) for y in range(h) for x in range(w) if (x, y) not in floor
              and any((x + d.vector[0], y + d.vector[1]) in floor for d in DIRECTIONS)]
    if len(around) < len(STATIONS) or len(floor) < 6:
        return None
    order = rng.permutation(len(STATIONS))
    chosen: dict[Pos, Terrain] = {}
    for spacing in (3, 2, 1):
        chosen = {}
        for k in order:
            free = [c for c in around if all(manhattan(c, o) >= spacing for o in chosen)]
            if not free:
                break
            chosen[free[int(rng.integers(len(free)))]] = STATIONS[int(k)]
        if len(chosen) == len(STATIONS):
            break
    if len(chosen) < len(STATIONS):
        return None
    starts = _starts(rng, floor, divider)
    if starts is None:
        return None
    grid = [[Terrain.COUNTER.value] * w for _ in range(h)]
    for x, y in floor:
        grid[y][x] = Terrain.FLOOR.value
    for (x, y), kind in chosen.items():
        grid[y][x] = kind.value
    for (x, y), ch in zip(starts, START_CHARS, strict=True):
        grid[y][x] = ch
    return "\n".join("".join(row) for row in grid) + "\n"


def _starts(rng: np.random.Generator, floor: set[Pos], divider: int | None) -> tuple[Pos, Pos] | None:
    """Robot and human starts, at least ``MIN_START_DISTANCE`` apart (in a split kitchen, one each side)."""
    cells = sorted(floor)
    for _ in range(50):
        robot = cells[int(rng.integers(len(cells)))]
        pool = [c for c in cells if manhattan(c, robot) >= MIN_START_DISTANCE]
        if divider is not None:
            pool = [c for c in pool if c[0] != divider and robot[0] != divider
                    and (c[0] < divider) != (robot[0] < divider)]
        if pool:
            return robot, pool[int(rng.integers(len(pool)))]
    return None


def _flood(floor: Iterable[Pos], start: Pos) -> frozenset[Pos]:
    cells = set(floor)
    seen = {start}
    todo = [start]
    while todo:
        x, y = todo.pop()
        for d in DIRECTIONS:
            nxt = (x + d.vector[0], y + d.vector[1])
            if nxt in cells and nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return frozenset(seen)


def generate_named(seed: int, request: KitchenRequest = KitchenRequest()) -> Layout:
    """The kitchen of generator seed ``seed``, named ``gen_<seed>_<style>`` (what ``steakhouse layout
    generate`` writes; :func:`style_of` reads the style back)."""
    rng = np.random.default_rng(seed)
    style = request.style or STYLES[int(rng.integers(len(STYLES)))]
    return generate_kitchen(rng, KitchenRequest(style, request.size), name=f"gen_{seed}_{style}")
