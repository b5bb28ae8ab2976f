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


def test_a_waiting_participant_sees_the_countdown_and_is_warned_while_they_can_still_act(study_server, new_page):
    page, _ = new_page()
    page.goto(study_server.link("browser_paper_clock_warned", PROLIFIC_PID="paper-clock-warned-1"))
    for selector in ("#consent-agree", "#instructions-done"):
        page.wait_for_selector(selector)
        page.click(selector)
    page.wait_for_selector("#clock-note")
    assert page.inner_text("#clock-note").startswith("The kitchen waits for you")
    page.click("#start-round")
    wait_drawn(page)
    page.wait_for_function("() => !document.querySelector('#hud-countdown').hidden", timeout=TIMEOUT_MS)
    shown = page.inner_text("#hud-countdown")
    assert shown in {f"Round ends in {m}:{s:02d}" for m in (0, 1) for s in range(60) if m * 60 + s <= 60}, shown
    page.wait_for_function("() => (document.querySelector('#task-note').dataset.reason || '')"
                           ".startsWith('would_not_count')", timeout=TIMEOUT_MS)
    assert page.inner_text("#task-note") == "Take part, or this round will not count: choose a task."
    screenshot(page, "paper_clock_warned")


def test_the_end_page_states_each_rule_as_measured_and_nothing_untrue(module_page):
    got = module_page.evaluate("""async () => {
      const { screenedOutText } = await import('/js/pages/finish.js');
      const detail = (rule, value, limit) => ({ reason: 'low_engagement', detail: { rule, value, limit, round: 2 } });
      return {
        none: screenedOutText(detail('no_actions', 0, 1)),
        idle: screenedOutText(detail('idle', 99.6, 95)),
        steps: screenedOutText(detail('task_steps', 3.2, 10)),
        refused: screenedOutText(detail('refused_tasks', 46.7, 35)),
        legacy: screenedOutText({ reason: 'low_engagement' }),
        away: screenedOutText({ reason: 'abandoned_rounds' }),
      };
    }""")
    assert got["none"].startswith("In round 2 you did not choose a task or press a key, so that round cannot count.")
    assert got["idle"].startswith("In round 2 your cook stood with nothing to do for 99.6 % of the round (this study "
                                  "allows at most 95 %)")
    assert got["steps"].startswith("In round 2 the robot did almost all of the work: your cook did 3.2 % of the "
                                   "team's steps (this study asks for at least 10 %)")
    assert got["refused"].startswith("By round 2, 46.7 % of the tasks you chose could not work (this study "
                                     "allows at most 35 %)")
    assert all("completion code" in text for text in got.values())
    assert "no task chosen" not in got["legacy"] and "connection" in got["away"]


def test_every_rule_the_server_can_warn_of_or_screen_out_for_has_words(module_page):
    import typing

    from server.flow.engagement import Rule
    from server.protocol.server import WarningRule

    got = module_page.evaluate("""async () => {
      const { WARNINGS } = await import('/js/game/notes.js');
      const { NOT_TAKING_PART } = await import('/js/pages/finish.js');
      return { warnings: Object.keys(WARNINGS), ends: Object.keys(NOT_TAKING_PART) };
    }""")
    assert sorted(got["warnings"]) == sorted(typing.get_args(WarningRule)) == sorted(typing.get_args(Rule))
    assert sorted(got["ends"]) == sorted(typing.get_args(Rule))
