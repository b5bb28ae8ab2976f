"""What the admin work changed in the participant's client, checked in Chromium: the instructions picture
follows the study's field-of-view angle (``session.fov_angle``) with the planner's own rule, and rounds are
numbered per kind ("Practice 1 of 1", "Round 1 of 2")."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from steakhouse_admin import PRACTICE_STUDY, REPLAY_FOV, REPLAY_STUDY, admin_page, admin_server  # noqa: F401

from planner.fov import in_view
from planner.geometry import Direction

pytestmark = pytest.mark.browser

EXAMPLE = json.loads((Path(__file__).resolve().parents[2] / "static" / "data" / "example_view.json").read_text())
ANGLES = [30, 60, 89.9, 90, 100, 120, 135, 179, 180, 200, 270, 359, 360]


def test_the_pictures_fov_rule_is_the_planners(admin_server, admin_page):  # noqa: F811
    page = admin_page()
    page.goto(f"{admin_server.url}/data/example_view.json")
    width, height = len(EXAMPLE["rows"][0]), len(EXAMPLE["rows"])
    got = page.evaluate("""async ([width, height, angles]) => {
      const { inView } = await import('/js/game/picture.js');
      const out = {};
      for (const facing of ['north', 'south', 'east', 'west'])
        for (const angle of angles)
          for (let oy = 0; oy < height; oy += 1)
            for (let ox = 0; ox < width; ox += 1) {
              const seen = [];
              for (let y = 0; y < height; y += 1)
                for (let x = 0; x < width; x += 1) if (inView([ox, oy], facing, [x, y], angle)) seen.push(`${x},${y}`);
              out[`${facing}|${angle}|${ox},${oy}`] = seen;
            }
      return out;
    }""", [width, height, ANGLES])
    for facing in Direction:
        for angle in ANGLES:
            for oy in range(height):
                for ox in range(width):
                    expected = [f"{x},{y}" for y in range(height) for x in range(width)
                                if in_view((ox, oy), facing, (x, y), angle)]
                    assert got[f"{facing.value}|{angle}|{ox},{oy}"] == expected, (facing, angle, ox, oy)


def test_the_instructions_draw_the_studys_angle_and_main_rounds_count_alone(admin_server, admin_page):  # noqa: F811
    page = admin_page()
    page.goto(f"{admin_server.url}/?study={REPLAY_STUDY}&PROLIFIC_PID=pid-instructions")
    page.click("#consent-agree")
    page.wait_for_selector("#instructions .picture-pair canvas")
    assert f"cone of {REPLAY_FOV}°" in page.inner_text("#fov-text")
    labels = page.eval_on_selector_all(".picture-pair canvas", "els => els.map(e => e.getAttribute('aria-label'))")
    assert f"{REPLAY_FOV}° field of view" in labels[1]
    cells = page.evaluate("""async (angle) => {
      const { exampleScenes, loadExample } = await import('/js/game/picture.js');
      return exampleScenes(await loadExample(), angle).view.cells.map((c) => [c.x, c.y]);
    }""", REPLAY_FOV)
    you = EXAMPLE["you"]
    expected = [[x, y] for y, row in enumerate(EXAMPLE["rows"]) for x in range(len(row))
                if in_view((you["x"], you["y"]), Direction(you["facing"]), (x, y), REPLAY_FOV)]
    assert cells == expected and len(cells) < len(EXAMPLE["visible"])

    page.click("#instructions-done")
    page.wait_for_selector("#start-round")
    assert page.inner_text("#round-title") == "Round 1 of 2"
    page.click("#start-round")
    page.wait_for_function("() => document.querySelector('#hud-round').textContent === 'Round 1 of 2'")


def test_a_practice_round_says_practice_1_of_1(admin_server, admin_page):  # noqa: F811
    page = admin_page()
    page.goto(f"{admin_server.url}/?study={PRACTICE_STUDY}&PROLIFIC_PID=pid-practice")
    page.click("#consent-agree")
    page.click("#instructions-done")
    page.wait_for_selector("#start-round")
    assert page.inner_text("#round-title") == "Practice round"
    assert page.inner_text("#round-number") == "Practice 1 of 1"
    page.click("#start-round")
    page.wait_for_function("() => document.querySelector('#hud-round').textContent === 'Practice 1 of 1'")
