"""Kitchen layouts: parsing and validation of the plain grids (docs/domain.md §1).

Characters (spelled in ``planner.vocabulary``): ``X`` counter, space floor, ``O`` onion dispenser, ``M`` meat
dispenser, ``D`` plate dispenser, ``P`` grill, ``B`` chopping board, ``W`` sink, ``S`` serving counter, ``1`` the
robot's start, ``2`` the human's start (both start cells are floor). A valid layout is rectangular, closed by
non-floor cells, has at least one of each station and exactly one start per agent. Every station must
be reachable: some floor cell next to it is reachable from both starts.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from planner.geometry import DIRECTIONS, Pos
from planner.vocabulary import START_CHARS, STATIONS, Terrain

__all__ = ["START_CHARS", "STATIONS", "Layout", "LayoutError", "LayoutProblem", "Terrain", "parse_layout"]


@dataclass(frozen=True, slots=True)
class LayoutProblem:
    """One thing wrong with a grid: the reason, and the line and column (1-based) when it is at one cell."""

    reason: str
    line: int | None = None
    column: int | None = None

    def where(self, source: str) -> str:
        """``source:line:column`` (as much of it as is known)."""
        if self.line is None:
            return source
        return f"{source}:{self.line}" + (f":{self.column}" if self.column is not None else "")


class LayoutError(ValueError):
    """A layout that cannot be played: its source and every problem found in it (``problems``: those at a
    cell in reading order, then those of the whole grid); the message has one ``source:line:column: reason``
    line per problem."""

    def __init__(self, source: str, problems: tuple[LayoutProblem, ...]) -> None:
        if not problems:
            raise ValueError("a LayoutError needs at least one problem")
        self.source, self.problems = source, problems
        super().__init__("\n".join(self.lines()))

    def lines(self) -> tuple[str, ...]:
        """One ``source:line:column: reason`` per problem."""
        return tuple(f"{p.where(self.source)}: {p.reason}" for p in self.problems)


@dataclass(frozen=True, slots=True)
class Layout:
    """The fixed part of a kitchen. Station tuples list cells in reading order (row by row)."""

    name: str
    width: int
    height: int
    rows: tuple[str, ...]
    starts: tuple[tuple[str, Pos], ...]
    floor: frozenset[Pos] = field(repr=False)
    counters: tuple[Pos, ...] = field(repr=False)
    onions: tuple[Pos, ...] = field(repr=False)
    meats: tuple[Pos, ...] = field(repr=False)
    plates: tuple[Pos, ...] = field(repr=False)
    grills: tuple[Pos, ...] = field(repr=False)
    boards: tuple[Pos, ...] = field(repr=False)
    sinks: tuple[Pos, ...] = field(repr=False)
    serves: tuple[Pos, ...] = field(repr=False)
    stations: dict[Pos, tuple[Terrain, int]] = field(repr=False, compare=False, hash=False)
    """Every non-floor cell → its terrain and its index among the cells of that terrain."""
    hash_value: int = field(repr=False, compare=False, default=0)

    def __hash__(self) -> int:
        """Precomputed from the grid and starts (what equality compares), so cache lookups stay cheap."""
        return self.hash_value

    def terrain(self, pos: Pos) -> Terrain:
        entry = self.stations.get(pos)
        if entry is not None:
            return entry[0]
        return Terrain.FLOOR if pos in self.floor else Terrain.COUNTER

    def is_floor(self, pos: Pos) -> bool:
        return pos in self.floor

    def start(self, agent: str) -> Pos:
        return dict(self.starts)[agent]

    def cells(self) -> tuple[Pos, ...]:
        return tuple((x, y) for y in range(self.height) for x in range(self.width))

    def text(self) -> str:
        """The layout as its grid text, starts included (round-trips through :func:`parse_layout`)."""
        grid = [list(row) for row in self.rows]
        for agent, (x, y) in self.starts:
            grid[y][x] = _START_CHAR[agent]
        return "\n".join("".join(row) for row in grid) + "\n"


def access_cells(layout: Layout, station: Pos) -> tuple[Pos, ...]:
    """The floor cells from which ``station`` can be used (next to it)."""
    x, y = station
    return tuple((x + d.vector[0], y + d.vector[1]) for d in DIRECTIONS
                 if (x + d.vector[0], y + d.vector[1]) in layout.floor)


def parse_layout(text: str, name: str = "layout", source: str | None = None) -> Layout:
    """Parse and validate a grid. Raises :class:`LayoutError` listing every problem, each with its line,
    column and reason, so a researcher fixing a kitchen file sees them all at once.

    The checks of single cells (unknown characters, a second start, ragged rows, floor on the border) and of
    the whole grid (a missing start or station) are all reported together; an unknown character counts as
    a counter for the others. Reachability is checked only on a grid that passes them all, since a broken
    grid would make it report walls that are typos.
    """
    src = source or name
    lines = text.splitlines()
    while lines and lines[-1].strip() == "":
        lines.pop()
    if not lines:
        raise LayoutError(src, (LayoutProblem("the layout is empty"),))
    rows, starts, found = _read_cells(lines)
    problems = sorted(found + _border_problems(rows), key=lambda p: (p.line or 0, p.column or 0))
    by_kind: dict[Terrain, list[Pos]] = {t: [] for t in Terrain}
    for y, row in enumerate(rows):
        for x, ch in enumerate(row):
            by_kind[Terrain(ch)].append((x, y))
    problems += [LayoutProblem(f"no {agent} start ('{ch}')") for ch, agent in START_CHARS.items()
                 if agent not in starts]
    problems += [LayoutProblem(f"missing station: no {station.name.lower()} ('{station.value}')")
                 for station in STATIONS if not by_kind[station]]
    floor = frozenset(by_kind[Terrain.FLOOR])
    if not problems:
        problems = _unreachable(floor, starts, by_kind)
    if problems:
        raise LayoutError(src, tuple(problems))
    width, height = len(rows[0]), len(rows)
    stations: dict[Pos, tuple[Terrain, int]] = {pos: (kind, i) for kind, found in by_kind.items()
                                                if kind is not Terrain.FLOOR for i, pos in enumerate(found)}
    return Layout(
        name=name, width=width, height=height, rows=tuple(rows),
        starts=tuple(sorted(starts.items())), floor=floor,
        counters=tuple(by_kind[Terrain.COUNTER]), onions=tuple(by_kind[Terrain.ONION]),
        meats=tuple(by_kind[Terrain.MEAT]), plates=tuple(by_kind[Terrain.PLATE]),
        grills=tuple(by_kind[Terrain.GRILL]), boards=tuple(by_kind[Terrain.BOARD]),
        sinks=tuple(by_kind[Terrain.SINK]), serves=tuple(by_kind[Terrain.SERVE]),
        stations=stations, hash_value=hash((name, tuple(rows), tuple(sorted(starts.items())))),
    )


_TERRAIN_CHARS = {t.value for t in Terrain}
_ALLOWED = ", ".join([Terrain.COUNTER.value, "space", *(t.value for t in STATIONS), *START_CHARS])
_START_CHAR = {agent: ch for ch, agent in START_CHARS.items()}


def _read_cells(lines: list[str]) -> tuple[list[str], dict[str, Pos], list[LayoutProblem]]:
    """The rows with starts as floor and unknown characters as counters, the starts, and the problems of
    single cells and rows (ragged rows, unknown characters, a second start)."""
    width = len(lines[0])
    starts: dict[str, Pos] = {}
    rows: list[str] = []
    problems: list[LayoutProblem] = []
    for y, line in enumerate(lines):
        if len(line) != width:
            problems.append(LayoutProblem(f"ragged row: {len(line)} characters where the first row has {width}",
                                          y + 1, min(len(line), width) + 1))
        cells: list[str] = []
        for x, ch in enumerate(line):
            if ch in START_CHARS:
                agent = START_CHARS[ch]
                if agent in starts:
                    first = starts[agent]
                    problems.append(LayoutProblem(f"a second {agent} start ('{ch}'); the first is at line "
                                                  f"{first[1] + 1}, column {first[0] + 1}", y + 1, x + 1))
                else:
                    starts[agent] = (x, y)
                ch = Terrain.FLOOR.value
            elif ch not in _TERRAIN_CHARS:
                problems.append(LayoutProblem(f"unknown character {ch!r}; allowed: {_ALLOWED}", y + 1, x + 1))
                ch = Terrain.COUNTER.value
            cells.append(ch)
        rows.append("".join(cells))
    return rows, starts, problems


def _border_problems(rows: list[str]) -> list[LayoutProblem]:
    """Every floor cell on the grid's edge (a ragged row's edge is its own last cell)."""
    height = len(rows)
    return [LayoutProblem("the kitchen is not closed: floor on the border", y + 1, x + 1)
            for y, row in enumerate(rows) for x, ch in enumerate(row)
            if ch == Terrain.FLOOR.value and (x in (0, len(row) - 1) or y in (0, height - 1))]


def _unreachable(floor: frozenset[Pos], starts: dict[str, Pos],
                 by_kind: dict[Terrain, list[Pos]]) -> list[LayoutProblem]:
    """Every kind of station no cell of which has a floor neighbour reachable from both starts."""
    regions = {agent: _flood(floor, pos) for agent, pos in starts.items()}
    shared = regions["human"] & regions["robot"]
    problems = []
    for station in STATIONS:
        reachable = any(
            (x + dx, y + dy) in shared
            for (x, y) in by_kind[station]
            for (dx, dy) in (d.vector for d in DIRECTIONS)
        )
        if not reachable:
            x, y = by_kind[station][0]
            problems.append(LayoutProblem(f"no {station.name.lower()} ('{station.value}') can be reached by "
                                          "both agents", y + 1, x + 1))
    return problems


def _flood(floor: frozenset[Pos], start: Pos) -> frozenset[Pos]:
    seen = {start}
    todo = [start]
    while todo:
        x, y = todo.pop()
        for dx, dy in ((0, 1), (0, -1), (1, 0), (-1, 0)):
            nxt = (x + dx, y + dy)
            if nxt in floor and nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return frozenset(seen)
