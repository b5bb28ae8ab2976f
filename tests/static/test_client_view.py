"""The kitchen view in real Chromium: black out-of-view cells (pixel checks against the planner's FOV
function), interrupt keys moving the avatar, refresh and dropped connections resuming the same trial."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

import pytest
from steakhouse_browser import check_mask, drawn, kitchen, press_until_focused, start_first_round, wait_drawn

from steakhouse_browser import screenshot
from server.game.view import drawn_bounds

if TYPE_CHECKING:
    from playwright.sync_api import WebSocketRoute

pytestmark = pytest.mark.browser

PRACTICE = kitchen("practice")


def test_out_of_view_cells_are_black_and_nothing_is_remembered(study_server, new_page):
    page, _ = new_page(scale=2)
    first = start_first_round(page, study_server.link(PROLIFIC_PID="view-1"), keyboard=True)
    assert first.grid == (PRACTICE.width, PRACTICE.height) and first.dpr == 2
    assert first.bounds == drawn_bounds(PRACTICE), "only floor, stations and one ring around them are drawn"
    canvas = page.eval_on_selector("#kitchen", "el => [el.width, el.height, el.getBoundingClientRect().width]")
    assert canvas[0] == round(first.cell_css * 2) * first.bounds[2] and canvas[0] == 2 * canvas[2]
    black, shown = check_mask(page, PRACTICE)
    assert black and shown and first.pos in shown

    page.keyboard.press("ArrowLeft")
    turned = wait_drawn(page, "d.you.endsWith('west')")
    assert turned.pos == (first.pos[0] - 1, first.pos[1])
    black_after, shown_after = check_mask(page, PRACTICE)
    forgotten = shown - shown_after
    assert forgotten and forgotten <= black_after, "cells seen before the turn must be black now"
    assert turned.robot, "the robot (standing west of the avatar) is drawn once it is in view"


def test_interrupt_keys_move_the_avatar_and_stop_cancels_the_task(study_server, new_page):
    # browser_keys: the robot stands between the cook and every station, so a chosen task is still running
    # when its stop key arrives, however busy the machine (the test waits on state, never on the clock).
    page, _ = new_page()
    start = start_first_round(page, study_server.link("browser_keys", PROLIFIC_PID="keys-1"))
    trial = start.trial
    assert (start.pos, start.facing.value) == ((9, 2), "south")

    def server_human():
        human = study_server.live(trial)["world"]["human"]
        return tuple(human["pos"]), human["facing"]

    page.keyboard.press("ArrowLeft")
    assert wait_drawn(page, "d.you === '8,2,west'")
    assert server_human() == ((8, 2), "west")
    page.keyboard.press("d")
    assert wait_drawn(page, "d.you === '9,2,east'")
    page.keyboard.press("w")  # a counter is north: the avatar only turns
    assert wait_drawn(page, "d.you === '9,2,north'")
    assert server_human() == ((9, 2), "north")
    page.keyboard.press(".")
    page.keyboard.press("Space")

    meat = page.locator("button[data-subtask='pickup_meat']")
    meat.click()
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'Pick up meat'")
    assert meat.get_attribute("aria-pressed") == "true"
    page.keyboard.press("Space")  # the focused button must not be clicked again: Space is "interact"
    page.keyboard.press("Escape")
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'none'")
    assert meat.get_attribute("aria-pressed") == "false"
    page.locator("button[data-subtask='pickup_onion']").click()
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'Pick up onion'")
    page.keyboard.press("Shift+S")
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'none'")
    assert study_server.live(trial)["subtask"] is None
    press_until_focused(page, "button[data-subtask='pickup_plate']")  # tasks can be chosen with the keyboard too
    page.keyboard.press("Enter")
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'Pick up plate'")
    page.keyboard.press("Escape")

    page.evaluate("() => { window.dispatchEvent(new Event('blur')); }")
    page.evaluate("() => { window.dispatchEvent(new Event('focus')); }")
    wanted = ["interrupt:left", "interrupt:right", "interrupt:up", "interrupt:stay", "interrupt:interact",
              "select_subtask:pickup_meat", "interrupt:interact", "interrupt:stop", "select_subtask:pickup_onion",
              "interrupt:stop", "select_subtask:pickup_plate", "interrupt:stop", "blur", "focus"]
    deadline = time.monotonic() + 5
    while True:
        events = study_server.events(trial)
        logged = [f"{e['kind']}:{e['payload'].get('action') or e['payload'].get('subtask')}"
                  if e["kind"] in ("interrupt", "select_subtask") else e["kind"]
                  for e in events if e["kind"] in ("interrupt", "select_subtask", "blur", "focus")]
        if logged == wanted or time.monotonic() > deadline:
            break
        time.sleep(0.1)
    assert logged == wanted
    stops = [e["payload"]["subtask"] for e in events if e["kind"] == "interrupt" and e["payload"]["action"] == "stop"]
    assert stops == ["pickup_meat", "pickup_onion", "pickup_plate"], "each stop cancelled a running task"


def test_refresh_resumes_the_same_trial_at_a_later_tick(study_server, new_page):
    page, _ = new_page()
    link = study_server.link(PROLIFIC_PID="refresh-1")
    first = start_first_round(page, link)
    page.click("button[data-subtask='pickup_onion']")
    before = wait_drawn(page, "Number(d.tick) >= 10")
    screenshot(page, "practice_round")
    page.reload()
    after = wait_drawn(page, f"Number(d.tick) > {before.tick}")
    assert after.trial == first.trial == before.trial
    assert page.query_selector("#start-round") is None, "a started round resumes without its intro card"
    participant = study_server.participant(page.evaluate(
        "() => JSON.parse(localStorage.getItem('steakhouse.session.browser_flow')).participant"))
    rows = study_server.trials(participant["participant_id"])
    assert [(r["trial_id"], r["kind"], r["status"]) for r in rows] == [(first.trial, "practice", "running")]
    kinds = [e["kind"] for e in study_server.events(first.trial, until=lambda k: k.count("connect") == 2)]
    assert kinds.count("connect") == 2 and "disconnect" in kinds and kinds.count("trial_start") == 1


def test_a_dropped_connection_reconnects_with_backoff(study_server, new_page):
    page, _ = new_page()
    attempts: list[float] = []
    routes: list[tuple[WebSocketRoute, WebSocketRoute]] = []  # (page side, server side)

    def handle(ws):
        attempts.append(time.monotonic())
        if len(attempts) == 2:
            ws.close(code=1011, reason="still down")
            return
        routes.append((ws, ws.connect_to_server()))

    page.route_web_socket("**/ws/play**", handle)
    first = start_first_round(page, study_server.link(PROLIFIC_PID="drop-1"))
    before = wait_drawn(page, "Number(d.tick) >= 5")
    dropped_at = time.monotonic()
    page_side, server_side = routes[0]
    page_side.close(code=1012, reason="network gone")
    server_side.close(code=1001, reason="network gone")
    page.wait_for_selector("#link-status[data-link='reconnecting']", timeout=3000)
    assert page.locator("#stage-cover").is_visible()
    page.wait_for_selector("#link-status[data-link='open']", timeout=10_000)
    after = wait_drawn(page, f"Number(d.tick) > {before.tick}")
    assert after.trial == first.trial
    assert len(attempts) == 3
    first_wait, second_wait = attempts[1] - dropped_at, attempts[2] - attempts[1]
    assert 0.1 < first_wait < second_wait, (first_wait, second_wait)
    assert page.locator("#latency").get_attribute("data-ms").isdigit()


def test_a_second_window_takes_the_round_over_and_the_first_can_take_it_back(study_server, new_page):
    page, _ = new_page()
    first = start_first_round(page, study_server.link(PROLIFIC_PID="two-windows"))
    other = page.context.new_page()
    other.goto(page.url)
    other.click("#start-round")
    assert wait_drawn(other).trial == first.trial
    page.wait_for_selector("#link-status[data-link='replaced']")
    assert "another window" in page.inner_text("#stage-cover")
    press_until_focused(page, "#stage-cover button")
    page.keyboard.press("Enter")
    again = wait_drawn(page, f"Number(d.tick) > {first.tick} && document.querySelector('#link-status').dataset.link === 'open'")
    assert again.trial == first.trial
    other.wait_for_selector("#link-status[data-link='replaced']")
    other.close()
