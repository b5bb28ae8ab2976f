"""The participant's words for a task that cannot work agree with the server's rules, checked inside Chromium
on the modules the pages import: a task button is disabled exactly when ``server.game.needs`` says the hands do
not fit, every reason the protocol can send has words, and the recipe strip's step follows what is held."""

from __future__ import annotations

import typing

import pytest

from planner.objects import OBJECTS
from planner.subtasks import SUBTASKS
from server.game.needs import NEEDS, hands_fit
from server.protocol.server import BlockedReason

pytestmark = pytest.mark.browser


def test_a_task_is_disabled_exactly_when_the_hands_do_not_fit(module_page):
    needs = {s.value: NEEDS[s] for s in SUBTASKS}
    held = [None, *OBJECTS]
    got = module_page.evaluate("""async ([needs, held]) => {
      const { handsReason } = await import('/js/game/reasons.js');
      const out = {};
      for (const [task, need] of Object.entries(needs)) out[task] = held.map((h) => handsReason(need, h));
      return out;
    }""", [needs, held])
    for subtask in SUBTASKS:
        for h, reason in zip(held, got[subtask.value], strict=True):
            assert (reason is None) is hands_fit(subtask, h), (subtask, h, reason)
    assert got["deliver_dish"][0] == "You need a finished dish in your hands"
    assert got["pickup_meat"][1 + OBJECTS.index("onion")] == "Your hands are full (an onion): put it down first"


def test_every_reason_the_server_can_send_has_words(module_page):
    got = module_page.evaluate("""async (reasons) => {
      const { BLOCKED_REASONS, blockedText } = await import('/js/game/reasons.js');
      return { known: BLOCKED_REASONS, texts: reasons.map((r) => blockedText({ reason: r, item: 'clean_plate' })) };
    }""", list(typing.get_args(BlockedReason)))
    assert sorted(got["known"]) == sorted(typing.get_args(BlockedReason))
    assert all(text and text != "That did not work" for text in got["texts"])
    assert "You need a clean plate in your hands" in got["texts"]


def test_the_recipe_step_follows_what_is_held(module_page):
    got = module_page.evaluate("""async (held) => {
      const { currentStep, RecipeStrip } = await import('/js/game/recipe.js');
      const strip = new RecipeStrip();
      strip.update('onion', null);
      return { steps: held.map((h) => currentStep(h, null)), chop: currentStep(null, 'chop_onion'),
               idle: currentStep(null, null), shown: strip.node.querySelector('[aria-current=step]').dataset.step };
    }""", list(OBJECTS))
    assert dict(zip(OBJECTS, got["steps"], strict=True)) == {
        "onion": "garnish.board", "meat": "steak.grill", "dirty_plate": "plate.sink", "clean_plate": "serve.steak",
        "steak_plate": "serve.garnish", "dish": "serve.serve"}
    assert (got["chop"], got["idle"], got["shown"]) == ("garnish.chop", None, "garnish.board")
