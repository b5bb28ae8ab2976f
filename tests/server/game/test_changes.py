"""Who last changed each cell (``server.game.changes``): a task refused because the world changed under the
participant is explained by the robot's last change of that cell, when it was the robot's and answers the refusal
(taken, used, done); the person's own changes, moves and deliveries explain nothing."""

from __future__ import annotations

from planner.events import Event, EventKind
from planner.objects import CLEAN_PLATE, MEAT, ONION
from server.game.changes import Change, Changes
from study_config import load_layout

KITCHEN = load_layout("practice")  # grill (8,4), board (5,1), sink (7,1); (1,0) a counter
GRILL, BOARD, COUNTER = (8, 4), (5, 1), (1, 0)


def test_the_robots_last_change_of_a_cell_explains_a_refusal_of_its_kind() -> None:
    changes = Changes().after(KITCHEN, [Event("robot", EventKind.PLATE_STEAK, GRILL, CLEAN_PLATE),
                                        Event("robot", EventKind.CHOP, BOARD)])
    assert changes.by_robot([GRILL], "taken") == Change("robot", "taken", "steak", "grill")
    assert changes.by_robot([BOARD], "done") == Change("robot", "done", "onion", "board")
    assert changes.by_robot([GRILL], "used") is None, "a take does not explain a busy grill"
    assert changes.by_robot([BOARD, GRILL], "taken") == Change("robot", "taken", "steak", "grill"), \
        "the first cell in order whose last change answers"


def test_a_later_change_by_the_person_replaces_the_robots() -> None:
    changes = Changes().after(KITCHEN, [Event("robot", EventKind.START_COOKING, GRILL, MEAT)])
    assert changes.by_robot([GRILL], "used") == Change("robot", "used", MEAT, "grill")
    changes = changes.after(KITCHEN, [Event("human", EventKind.PLATE_STEAK, GRILL, CLEAN_PLATE)])
    assert changes.by_robot([GRILL], "used") is None and changes.by_robot([GRILL], "taken") is None


def test_events_that_change_no_holder_are_not_remembered() -> None:
    start = Changes()
    after = start.after(KITCHEN, [Event("robot", EventKind.BLOCKED, (3, 2)), Event("robot", EventKind.DELIVER, (1, 3)),
                                  Event("robot", EventKind.DISPENSE, (6, 1), ONION)])
    assert after is start and dict(after.last) == {}
    counter = start.after(KITCHEN, [Event("robot", EventKind.PICK_UP, COUNTER, ONION)])
    assert counter.by_robot([COUNTER], "taken") == Change("robot", "taken", ONION, "counter")
