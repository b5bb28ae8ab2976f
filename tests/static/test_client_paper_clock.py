"""The paper's clock in real Chromium: a task whose next step would do nothing is refused, the page says the true
reason and shows no task, and the world does not move (the server's tick and its robot stay where they were while
the participant waits); a held key is one press, one step; on the fixed clock a held key still repeats."""

from __future__ import annotations

import json
import time

import pytest
from steakhouse_browser import TIMEOUT_MS, screenshot, start_first_round, wait_drawn

pytestmark = pytest.mark.browser

WAIT_S = 1.5
"""How long the test lets the participant stand after the refusal: at 10 ticks a second the world would have
stepped 15 times on the fixed clock."""


def sent_interrupts(page) -> list[str]:
    """The interrupt actions the page's websocket sends, in order."""
    sent: list[str] = []

    def on_socket(ws) -> None:
        ws.on("framesent", lambda payload: sent.append(json.loads(payload)["action"])
              if '"interrupt"' in payload else None)

    page.on("websocket", on_socket)
    return sent


def trial_id(page) -> int:
    return int(page.eval_on_selector("#kitchen", "el => el.dataset.trial"))


def hold(page, key: str, repeats: int) -> None:
    """Hold ``key`` down: one press, then ``repeats`` auto-repeat keydowns (``event.repeat``), then release."""
    for _ in range(repeats + 1):
        page.keyboard.down(key)
        page.wait_for_timeout(60)
    page.keyboard.up(key)


def test_a_refused_step_moves_nothing_and_says_why_and_a_held_key_is_one_step(study_server, new_page):
    page, _ = new_page()
    sent = sent_interrupts(page)
    start_first_round(page, study_server.link("browser_paper_clock", PROLIFIC_PID="paper-clock-1"))
    trial = trial_id(page)
    before = study_server.live(trial)
    assert before["tick"] == 0
    moves_left = page.inner_text("#hud-time")
    page.click("button[data-subtask='pickup_clean_plate']")  # no clean plate seen yet: nothing to walk to
    page.wait_for_function("() => !document.querySelector('#task-note').hidden", timeout=TIMEOUT_MS)
    assert page.inner_text("#task-note") == "Pick up clean plate stopped: You have not seen a clean plate yet."
    page.wait_for_function("() => document.querySelector('#hud-task').textContent === 'none'", timeout=TIMEOUT_MS)
    screenshot(page, "paper_clock_refused_step")
    time.sleep(WAIT_S)
    after = study_server.live(trial)
    assert after["tick"] == 0 and after["world"]["robot"] == before["world"]["robot"], "the robot waited too"
    assert page.inner_text("#hud-time") == moves_left
    events = study_server.events(trial, until=lambda kinds: "subtask_blocked" in kinds)
    assert [e["payload"] for e in events if e["kind"] == "subtask_blocked"] == [
        {"subtask": "pickup_clean_plate", "reason": "no_clean_plate", "item": None}]

    hold(page, ".", repeats=8)
    page.wait_for_function("n => document.querySelector('#hud-time').textContent !== n", arg=moves_left,
                           timeout=TIMEOUT_MS)
    time.sleep(0.5)
    assert sent == ["stay"], "a held key is one press"
    assert study_server.live(trial)["tick"] == 1, "and one step of the world"


def test_on_the_fixed_clock_a_held_key_repeats(study_server, new_page):
    page, _ = new_page()
    sent = sent_interrupts(page)
    start_first_round(page, study_server.link("browser_keys", PROLIFIC_PID="paper-clock-fixed-1"))
    wait_drawn(page)
    hold(page, ".", repeats=8)
    page.wait_for_function("() => true")
    time.sleep(0.3)
    assert len(sent) > 1 and set(sent) == {"stay"}, sent
