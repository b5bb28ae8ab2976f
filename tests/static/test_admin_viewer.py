"""The dashboard's live view and replay in real Chromium: a trial played by a scripted participant over the
websocket is watched live (the whole kitchen with the participant's field of view, the knowledge gap, the
robot's belief, tick lateness), and a finished one is replayed: scrubbing, stepping and playing draw each
stored tick, with the cells outside the participant's view dimmed (pixel checks)."""

from __future__ import annotations

import pytest
from steakhouse_admin import admin_page, admin_server, canvas_pixel, login, screenshot  # noqa: F401

pytestmark = pytest.mark.browser

FLOOR = (0xEF, 0xEA, 0xE2)
"""The floor colour of static/js/game/palette.js; outside the field of view it is under a 60 % black mask."""
ROBOT = (0xE6, 0x9F, 0x00)
"""The robot's body colour: drawn above the mask, so the experimenter sees it even when the participant cannot."""
FACING = {"north": (0, -1), "south": (0, 1), "east": (1, 0), "west": (-1, 0)}


def near(pixel, colour, tolerance=6) -> bool:
    return all(abs(a - b) <= tolerance for a, b in zip(pixel, colour, strict=True))


def canvas_data(page) -> dict[str, str]:
    return dict(page.eval_on_selector("#admin-kitchen", "el => ({...el.dataset})"))


def test_a_running_trial_is_watched_live(admin_server, admin_page):  # noqa: F811
    player = admin_server.live_trial("pid-live")
    page = admin_page()
    login(page, admin_server, hash_="#/live")
    row = f"#live-table tr[data-trial='{player.trial_id}']"
    page.wait_for_selector(row)
    assert "pid-live" in page.inner_text(row), "the list names the participant by the recruiting id"
    assert player.participant_id not in page.inner_text(row)
    page.click(f"{row} a.watch")
    page.wait_for_selector("#admin-kitchen[data-tick]")
    first = int(canvas_data(page)["tick"])
    page.wait_for_function(f"() => Number(document.querySelector('#admin-kitchen').dataset.tick) >= {first + 4}")
    page.wait_for_function("() => document.querySelector('#lateness-p99').textContent.endsWith('ms')")

    live = admin_server.get(f"/api/admin/live/{player.trial_id}")
    data = canvas_data(page)
    width, height = live["grid"]["width"], live["grid"]["height"]
    assert data["grid"] == f"{width}x{height}" and int(data["visible"]) == width * height, "the whole kitchen"
    assert 0 < int(data["fov"]) < width * height
    assert page.locator("#gap-panel tbody tr").count() == 4
    assert page.inner_text("#live-meta").startswith("pid-live")
    assert page.get_attribute("#live-meta .who", "title") == f"public id {player.participant_id}"
    if live["decision"] and live["decision"]["belief"]:
        page.wait_for_selector("#belief-list li")
        assert page.locator("#belief-list li").count() >= 1
    assert page.is_visible("#belief-kitchen")
    belief_cell = page.eval_on_selector("#belief-kitchen", "el => Number(el.dataset.cell)")
    assert belief_cell >= 28, f"the participant model's kitchen is drawn at {belief_cell} px a cell: too small to read"
    screenshot(page, "admin_live", full_page=True)

    player.stop()
    page.wait_for_function("() => document.querySelector('#live-meta') &&"
                           " document.querySelector('#live-meta').textContent.includes('away')")


def pick_cells(replay, frame) -> tuple[tuple[int, int], tuple[int, int]]:
    """A floor cell in view and one out of view, both empty (no agent on them)."""
    agents = {(frame["human"]["x"], frame["human"]["y"]), (frame["robot"]["x"], frame["robot"]["y"])}
    fov = {tuple(c) for c in frame["fov"]}
    floor = [(x, y) for y, row in enumerate(replay["grid"]["terrain"]) for x, t in enumerate(row)
             if t == "floor" and (x, y) not in agents]
    return next(c for c in floor if c in fov), next(c for c in floor if c not in fov)


def test_a_finished_trial_is_replayed_tick_by_tick(admin_server, admin_page):  # noqa: F811
    _, trial_id = admin_server.finished_trial("pid-replay")
    replay = admin_server.get(f"/api/admin/trials/{trial_id}/frames")
    frames = replay["frames"]
    last = frames[-1]["tick"]
    page = admin_page()
    login(page, admin_server, hash_="#/trials")
    page.click(f"#trials-table tr[data-trial='{trial_id}'] a.replay-link")
    page.wait_for_selector("#scrubber")
    assert page.inner_text("#tick-label") == f"Tick 0 of {last}"

    hidden = [i for i, f in enumerate(frames) if 0 < i < len(frames) - 5 and not f["robot_in_fov"]]
    assert hidden, "the replayed trial must hide the robot at some tick to test the dimmed view"
    k = hidden[len(hidden) // 2]
    page.fill("#scrubber", str(k))
    page.wait_for_function(f"() => document.querySelector('#admin-kitchen').dataset.tick === '{k}'")
    frame = frames[k]
    data = canvas_data(page)
    assert page.inner_text("#tick-label") == f"Tick {k} of {last}"
    assert data["you"] == f"{frame['human']['x']},{frame['human']['y']},{frame['human']['facing']}"
    assert data["robot"] == f"{frame['robot']['x']},{frame['robot']['y']},{frame['robot']['facing']}"
    assert int(data["fov"]) == len(frame["fov"])
    assert page.inner_text("#replay-tick") == str(k)
    assert page.inner_text("#replay-robot-in-fov") == "no"
    inside, outside = pick_cells(replay, frame)
    assert near(canvas_pixel(page, "#admin-kitchen", inside), FLOOR)
    assert near(canvas_pixel(page, "#admin-kitchen", outside), tuple(round(c * 0.4) for c in FLOOR))
    dx, dy = FACING[frame["robot"]["facing"]]
    body = (0.5 - 0.12 * dx - 0.2 * dy, 0.5 - 0.12 * dy + 0.2 * dx)
    assert near(canvas_pixel(page, "#admin-kitchen", (frame["robot"]["x"], frame["robot"]["y"]), *body), ROBOT)
    screenshot(page, "admin_replay", full_page=True)

    page.focus("#scrubber")
    page.keyboard.press("ArrowRight")
    page.wait_for_function(f"() => document.querySelector('#tick-label').textContent === 'Tick {k + 1} of {last}'")
    page.click("#step-forward")
    page.wait_for_function(f"() => document.querySelector('#admin-kitchen').dataset.tick === '{k + 2}'")
    page.click("#step-back")
    page.wait_for_function(f"() => document.querySelector('#admin-kitchen').dataset.tick === '{k + 1}'")

    page.click("#play")
    page.wait_for_function(f"() => Number(document.querySelector('#admin-kitchen').dataset.tick) >= {k + 4}")
    page.click("#play")
    assert page.get_attribute("#play", "aria-pressed") == "false"
    stopped = page.inner_text("#tick-label")  # the canvas draws on the next animation frame; the label at once
    page.wait_for_timeout(300)
    assert page.inner_text("#tick-label") == stopped, "paused"
    assert f"Tick {canvas_data(page)['tick']} of" in stopped, "the canvas shows the tick the replay paused at"

    page.fill("#scrubber", str(len(frames) - 1))
    page.wait_for_function(f"() => document.querySelector('#tick-label').textContent === 'Tick {last} of {last}'")
    assert page.inner_text("#gap-total") == f"gap {frames[-1]['kb_gap_total']}"
