"""Layout parsing and validation: every shipped kitchen loads; bad grids name line, column and reason."""

from __future__ import annotations

import pytest

from planner.layout import LayoutError, LayoutProblem, Terrain, parse_layout
from study_config import LAYOUT_DIR, layout_names, load_layout

GOOD = "XXXXXXXXX\nXOMDPBWSX\nX       X\nX1  X  2X\nX       X\nXXXXXXXXX\n"


def test_the_ten_paper_kitchens_ship_and_load():
    assert set(layout_names()) == {"mid_1", "mid_2", "mid_3", "none_1", "none_2", "none_3", "practice",
                                   "side_1", "side_2", "side_3"}
    for name in layout_names():
        layout = load_layout(name)
        assert layout.name == name and layout.grills and layout.serves


def test_load_by_path_equals_load_by_name():
    assert load_layout(LAYOUT_DIR / "mid_2.layout") == load_layout("mid_2")


def test_parse_finds_starts_and_stations():
    layout = parse_layout(GOOD)
    assert layout.start("robot") == (1, 3) and layout.start("human") == (7, 3)
    assert layout.terrain((4, 1)) is Terrain.GRILL and layout.terrain((4, 3)) is Terrain.COUNTER
    assert layout.is_floor((1, 3)) and not layout.is_floor((4, 3))


def test_text_round_trips():
    layout = load_layout("none_3")
    assert parse_layout(layout.text(), name="none_3") == layout


def bad(text: str) -> LayoutError:
    with pytest.raises(LayoutError) as info:
        parse_layout(text, name="bad.layout")
    return info.value


def only(text: str) -> LayoutProblem:
    (problem,) = bad(text).problems
    return problem


def test_ragged_row():
    problem = only(GOOD.replace("X       X\nX1", "X      X\nX1", 1))
    assert problem.line == 3 and "ragged" in problem.reason


def test_unclosed_border():
    problem = only(GOOD.replace("XXXXXXXXX\nXOM", "XXXX XXXX\nXOM", 1))
    assert (problem.line, problem.column) == (1, 5) and "not closed" in problem.reason


def test_missing_station():
    problem = only(GOOD.replace("W", "X"))
    assert "missing station" in problem.reason and "sink" in problem.reason


def test_unknown_character():
    problem = only(GOOD.replace("B", "Q").replace("XXXXXXXXX\nXOM", "XXXXXXXXX\nXBOM", 1).replace("WSX", "WS"))
    assert (problem.line, problem.column) == (2, 7) and "unknown character 'Q'" in problem.reason


def test_two_humans():
    problem = only(GOOD.replace("X1  X  2X", "X1 2X  2X"))
    assert (problem.line, problem.column) == (4, 8) and "second human" in problem.reason


def test_missing_start():
    assert "no robot start" in only(GOOD.replace("1", " ")).reason


def test_unreachable_station():
    walled = "XXXXXXXXX\nXOMDPBWXX\nX   X XSX\nX1  X 2 X\nXXXXXXXXX\n"
    problems = bad(walled).problems  # the two starts share no floor: no station serves both
    assert len(problems) == 7 and all("can be reached by both agents" in p.reason for p in problems)


def test_every_problem_is_reported_at_once_in_reading_order():
    broken = GOOD.replace("B", "Q").replace("X1  X  2X", "X1 2X  2 ").replace("D", "X")
    error = bad(broken)
    assert [(p.line, p.column) for p in error.problems] == [(2, 6), (4, 8), (4, 9), (None, None), (None, None)]
    assert [p.reason.split(";")[0].split(":")[0] for p in error.problems] == [
        "unknown character 'Q'", "a second human start ('2')", "the kitchen is not closed",
        "missing station", "missing station"]
    assert "plate" in error.problems[3].reason and "board" in error.problems[4].reason
    assert str(error).splitlines() == list(error.lines())
    assert error.lines()[0].startswith("bad.layout:2:6: unknown character 'Q'")
    assert error.lines()[3] == "bad.layout: missing station: no plate ('D')"


def test_reachability_waits_for_an_otherwise_valid_grid():
    walled = "XXXXXXXXX\nXOMDPBWXX\nX   X XSX\nX1  X 2 X\nXXXXXXXXX\n"
    problems = bad(walled.replace("XOMDPBWXX", "XOMDPBWXQ")).problems
    assert [p.reason.split(";")[0] for p in problems] == ["unknown character 'Q'"]


def test_error_message_names_the_source():
    error = bad(GOOD.replace("B", "Q"))
    assert str(error).startswith("bad.layout:2:6: ")
