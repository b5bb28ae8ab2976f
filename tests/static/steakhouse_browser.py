"""Helpers of the browser tests: walking a participant through the pages, reading what the kitchen canvas
drew, and playing a round by clicking task buttons like a person would.

Importable from the test files because ``tests/static/conftest.py`` puts this folder on ``sys.path``.
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planner.fov import visible_cells
from planner.geometry import Direction, Pos
from planner.layout import Layout, parse_layout
from study_config import STUDY_DIR

TIMEOUT_MS = 60_000
"""How long a browser test waits for a state before failing: generous, for a machine kept busy by other work
(a passing wait returns as soon as the state is reached)."""
FIRST_FRAME_TIMEOUT_MS = 90_000
"""How long a page may take to draw its first 3D frame: software WebGL compiles its shaders on the CPU, and on a
busy machine the page's thread was seen blocked for ~20 s doing it. A bound on a wait for state, not a delay."""
SCREENSHOTS = Path(os.environ.get("STEAKHOUSE_SCREENSHOTS") or
                   Path(__file__).resolve().parents[2] / "test-output" / "screenshots")
"""Where screenshots go: ``test-output/screenshots/`` (git-ignored), or ``$STEAKHOUSE_SCREENSHOTS``."""
RECRUIT_SITE = "https://recruit.example/"


def screenshot(page: Any, name: str, *, full_page: bool = False) -> Path:
    """Save what the page shows to ``test-output/screenshots/<name>.png`` for a person to look at."""
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    path = SCREENSHOTS / f"{name}.png"
    page.screenshot(path=str(path), full_page=full_page)
    return path

# One dish, start to finish, with a robot that stays put (the order planner.subtasks makes possible).
ONE_DISH = ("pickup_meat", "drop_meat", "pickup_onion", "drop_onion", "chop_onion", "pickup_plate", "drop_plate",
            "wash_plate", "pickup_clean_plate", "pickup_steak", "pickup_garnish", "deliver_dish")


def kitchen(name: str) -> Layout:
    return parse_layout((STUDY_DIR / "layouts" / f"{name}.layout").read_text(encoding="utf-8"), name=name)


@dataclass(frozen=True)
class Drawn:
    """What the kitchen canvas says it drew (its data attributes, set in the same frame as the pixels); the
    first-person canvas has no cells, so ``cell_css`` and ``dpr`` are NaN there."""

    trial: int
    tick: int
    pos: tuple[int, int]
    facing: Direction
    held: str
    robot: str
    grid: tuple[int, int]
    bounds: tuple[int, int, int, int]
    """The part of the grid drawn: left, top, width, height (``hello.bounds``)."""
    cell_css: float
    dpr: float


def drawn(page: Any) -> Drawn:
    data = page.eval_on_selector("#kitchen", "el => ({...el.dataset})")
    x, y, facing = data["you"].split(",")
    width, height = data["grid"].split("x")
    bounds = data.get("bounds") or f"0,0,{width},{height}"  # the first-person view draws no grid
    left, top, shown_w, shown_h = (int(v) for v in bounds.split(","))
    return Drawn(trial=int(data["trial"]), tick=int(data["tick"]), pos=(int(x), int(y)), facing=Direction(facing),
                 held=data["held"], robot=data["robot"], grid=(int(width), int(height)),
                 bounds=(left, top, shown_w, shown_h), cell_css=float(data.get("cell", "nan")),
                 dpr=float(data.get("dpr", "nan")))


def wait_drawn(page: Any, condition: str = "true", timeout: float = TIMEOUT_MS) -> Drawn:
    """Wait until the canvas has drawn a state and ``condition`` (JS over ``d``, its dataset) holds."""
    page.wait_for_function(f"() => {{ const el = document.querySelector('#kitchen');"
                           f" if (!el || !el.dataset.tick) return false; const d = el.dataset; return ({condition}); }}",
                           timeout=timeout)
    return drawn(page)


def press_until_focused(page: Any, selector: str, limit: int = 30) -> None:
    """Press Tab until the element matching ``selector`` has keyboard focus (keyboard-only navigation)."""
    for _ in range(limit):
        if page.evaluate("s => document.activeElement && document.activeElement.matches(s)", selector):
            return
        page.keyboard.press("Tab")
    raise AssertionError(f"{selector} never received keyboard focus")


def start_first_round(page: Any, link: str, *, keyboard: bool = False) -> Drawn:
    """Open the landing link, accept consent, read the instructions and start the first round."""
    page.goto(link)
    for selector in ("#consent-agree", "#instructions-done", "#start-round"):
        page.wait_for_selector(selector)
        if keyboard:
            press_until_focused(page, selector)
            page.keyboard.press("Enter")
        else:
            page.click(selector)
    return wait_drawn(page)


def play_by_clicking(page: Any, script: tuple[str, ...] = ONE_DISH, timeout: float = 20_000) -> list[str]:
    """Click each task button in turn, each once the previous task is done; returns what was clicked."""
    clicked = []
    for subtask in script:
        if page.query_selector("#round-summary"):
            break
        page.wait_for_function("() => document.querySelector('#round-summary') ||"
                               " document.querySelector('#hud-task').parentElement.dataset.subtask === ''",
                               timeout=timeout)
        if page.query_selector("#round-summary"):
            break
        button = f"button[data-subtask='{subtask}']"
        page.click(button)
        clicked.append(subtask)
        # The server's ack clears the pending mark; afterwards the HUD shows the task until it is done.
        page.wait_for_function(f"() => document.querySelector('#round-summary') ||"
                               f" !document.querySelector(\"{button}\").classList.contains('pending')",
                               timeout=timeout)
    page.wait_for_selector("#round-summary", timeout=timeout)
    return clicked


def canvas_image(page: Any) -> tuple[Any, tuple[int, int]]:
    """The page as the browser composited it (a PIL image in device pixels) and the kitchen canvas's
    top-left corner in it, which must lie on a whole device pixel (else the drawing would be blurred)."""
    from PIL import Image

    left, top, dpr = page.eval_on_selector(
        "#kitchen", "el => { const r = el.getBoundingClientRect(); return [r.left, r.top, window.devicePixelRatio]; }")
    image = Image.open(io.BytesIO(page.screenshot())).convert("RGB")
    x, y = left * dpr, top * dpr
    assert abs(x - round(x)) < 0.01 and abs(y - round(y)) < 0.01, f"canvas at a fractional device pixel ({x}, {y})"
    return image, (round(x), round(y))


def cell_pixels(image: Any, origin: tuple[int, int], cell: tuple[int, int], size: int, margin: int = 3,
                step: int = 3, first: tuple[int, int] = (0, 0)) -> list[tuple[int, int, int]]:
    """A grid of pixels inside ``cell`` of a grid drawn at ``origin`` with ``size`` device pixels per cell,
    ``margin`` away from the cell's edges; ``first`` is the grid cell drawn at ``origin`` (the bounds' corner)."""
    x0, y0 = origin[0] + (cell[0] - first[0]) * size, origin[1] + (cell[1] - first[1]) * size
    return [image.getpixel((x, y)) for y in range(y0 + margin, y0 + size - margin, step)
            for x in range(x0 + margin, x0 + size - margin, step)]


def is_black(pixel: tuple[int, int, int]) -> bool:
    """Pure black, as out-of-view cells must be (a little slack for compositing)."""
    return max(pixel) <= 8


def check_mask(page: Any, layout: Layout, angle: float = 120.0) -> tuple[set[Pos], set[Pos]]:
    """Check every cell of the drawn canvas against the FOV of the pose the canvas says it drew."""
    before = drawn(page)
    image, origin = canvas_image(page)
    after = drawn(page)
    assert (before.pos, before.facing) == (after.pos, after.facing), "the avatar moved during the screenshot"
    size = round(before.cell_css * before.dpr)
    seen = visible_cells(layout, before.pos, before.facing, angle)
    left, top, width, height = before.bounds
    black, shown = set(), set()
    for cell in layout.cells():
        if not (left <= cell[0] < left + width and top <= cell[1] < top + height):
            continue  # outside the drawn part of the grid (unreachable counters)
        pixels = cell_pixels(image, origin, cell, size, first=(left, top))
        if cell in seen:
            lit = sum(1 for p in pixels if not is_black(p))
            assert lit / len(pixels) > 0.9, f"in-view cell {cell} is (partly) black"
            shown.add(cell)
        else:
            assert all(is_black(p) for p in pixels), f"out-of-view cell {cell} is not black"
            black.add(cell)
    return black, shown
