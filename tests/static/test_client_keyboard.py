"""Playing from the keyboard in real Chromium: the number row chooses tasks (its key shown on each task
button), a whole round is played with those keys and the arrows alone, a key that does nothing says why in the
HUD's note, and the HUD keeps its height when a note appears (static/js/game/keys.js, controls.js, notes.js)."""

from __future__ import annotations

import json

import pytest
from steakhouse_browser import ONE_DISH, TIMEOUT_MS, screenshot, start_first_round, wait_drawn

pytestmark = pytest.mark.browser

# The task keys in the order the buttons are shown (static/js/labels.js SUBTASK_GROUPS without "Put on counter").
KEY_OF = {"pickup_meat": "1", "pickup_onion": "2", "pickup_plate": "3", "pickup_clean_plate": "4",
          "pickup_steak": "5", "pickup_garnish": "6", "drop_meat": "7", "drop_onion": "8", "drop_plate": "9",
          "chop_onion": "0", "wash_plate": "-", "deliver_dish": "="}


def sent_choices(page) -> list[str]:
    """The subtasks the page's websocket chooses, in order (appended as they are sent)."""
    chosen: list[str] = []

    def on_socket(ws) -> None:
        def on_frame(payload) -> None:
            message = json.loads(payload)
            if message.get("type") == "select_subtask":
                chosen.append(message["subtask"])

        ws.on("framesent", on_frame)

    page.on("websocket", on_socket)
    return chosen


def hud_height(page) -> float:
    height: float = page.eval_on_selector(".hud", "el => el.getBoundingClientRect().height")
    return height


def wait_idle(page) -> None:
    page.wait_for_function("() => document.querySelector('#round-summary') ||"
                           " document.querySelector('#hud-task').parentElement.dataset.subtask === ''",
                           timeout=TIMEOUT_MS)


def test_task_keys_are_shown_and_a_round_is_played_with_the_keyboard_alone(study_server, new_page):
    page, _ = new_page()
    sent = sent_choices(page)
    start_first_round(page, study_server.link(PROLIFIC_PID="keys-round-1"), keyboard=True)
    shown = page.eval_on_selector_all(".task-button", "els => els.map(b => [b.dataset.subtask, b.dataset.key])")
    assert {task: key for task, key in shown if key} == KEY_OF
    assert dict(shown)["drop_on_counter"] == ""
    screenshot(page, "keyboard_task_keys")
    for subtask in ONE_DISH:
        wait_idle(page)
        if page.query_selector("#round-summary"):
            break
        button = f"button[data-subtask='{subtask}']"
        page.keyboard.press(KEY_OF[subtask])
        # The server's ack clears the pending mark; afterwards the HUD shows the task until it is done.
        page.wait_for_function(f"() => document.querySelector('#round-summary') ||"
                               f" !document.querySelector(\"{button}\").classList.contains('pending')",
                               timeout=TIMEOUT_MS)
    page.wait_for_selector("#round-summary", timeout=TIMEOUT_MS)
    assert "All orders delivered" in page.inner_text("#summary-text")
    assert sent == list(ONE_DISH), "each key chose its own task, and only the keys did"


def test_a_key_that_does_nothing_says_why_and_the_hud_keeps_its_height(study_server, new_page):
    page, _ = new_page(viewport=(1280, 720))
    start_first_round(page, study_server.link(PROLIFIC_PID="keys-note-1"))
    wait_drawn(page)
    before = hud_height(page)
    assert page.eval_on_selector("#task-note", "el => el.hidden")
    page.keyboard.press("q")
    page.wait_for_function("() => !document.querySelector('#task-note').hidden")
    assert page.inner_text("#task-note").startswith("Q is not a game key")
    assert hud_height(page) == before, "the note appears inside the HUD's own height"
    screenshot(page, "keyboard_other_key_note")
    page.keyboard.press("Space")  # the cook faces floor: the server says the key did nothing, and why
    page.wait_for_function("() => document.querySelector('#task-note').textContent.startsWith('There is nothing')")
    assert hud_height(page) == before
    page.keyboard.press("=")  # deliver dish with empty hands: refused with its reason, like a click
    page.wait_for_function("() => document.querySelector('#task-note').textContent.startsWith('Deliver dish')")
    assert hud_height(page) == before
    long_text = "A long note " * 20
    page.evaluate("(t) => { const n = document.querySelector('#task-note'); n.hidden = false;"
                  " n.querySelector('.task-note-text').textContent = t; }", long_text)
    assert hud_height(page) == before, "even a note too long for two lines does not grow the HUD"
