"""Helpers of the browser tests: walking a participant through the pages, reading what the kitchen canvas
drew, and playing a round by clicking task buttons like a person would.

Importable from the test files because ``tests/static/conftest.py`` puts this folder on ``sys.path``.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planner.geometry import Direction
from planner.layout import Layout, parse_layout
from study_config import STUDY_DIR

TIMEOUT_MS = 15_000
SCREENSHOTS = Path(__file__).resolve().parents[2] / "test-output" / "screenshots"
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
    cell_css: float
    dpr: float


def drawn(page: Any) -> Drawn:
    data = page.eval_on_selector("#kitchen", "el => ({...el.dataset})")
    x, y, facing = data["you"].split(",")
    width, height = data["grid"].split("x")
    return Drawn(trial=int(data["trial"]), tick=int(data["tick"]), pos=(int(x), int(y)), facing=Direction(facing),
                 held=data["held"], robot=data["robot"], grid=(int(width), int(height)),
                 cell_css=float(data.get("cell", "nan")), dpr=float(data.get("dpr", "nan")))


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
                step: int = 3) -> list[tuple[int, int, int]]:
    """A grid of pixels inside ``cell`` of a grid drawn at ``origin`` with ``size`` device pixels per cell,
    ``margin`` away from the cell's edges."""
    x0, y0 = origin[0] + cell[0] * size, origin[1] + cell[1] * size
    return [image.getpixel((x, y)) for y in range(y0 + margin, y0 + size - margin, step)
            for x in range(x0 + margin, x0 + size - margin, step)]
