"""Layout parsing and validation: every shipped kitchen loads; bad grids name line, column and reason."""

from __future__ import annotations

import pytest

from planner.layout import LayoutError, Terrain, parse_layout
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


def test_ragged_row():
    error = bad(GOOD.replace("X       X\nX1", "X      X\nX1", 1))
    assert error.line == 3 and "ragged" in str(error)


def test_unclosed_border():
    error = bad(GOOD.replace("XXXXXXXXX\nXOM", "XXXX XXXX\nXOM", 1))
    assert (error.line, error.column) == (1, 5) and "not closed" in str(error)


def test_missing_station():
    error = bad(GOOD.replace("W", "X"))
    assert "missing station" in str(error) and "sink" in str(error)


def test_unknown_character():
    error = bad(GOOD.replace("B", "Q"))
    assert (error.line, error.column) == (2, 6) and "unknown character 'Q'" in str(error)


def test_two_humans():
    error = bad(GOOD.replace("X1  X  2X", "X1 2X  2X"))
    assert (error.line, error.column) == (4, 8) and "second human" in str(error)


def test_missing_start():
    assert "no robot start" in str(bad(GOOD.replace("1", " ")))


def test_unreachable_station():
    walled = "XXXXXXXXX\nXOMDPBWXX\nX   X XSX\nX1  X 2 X\nXXXXXXXXX\n"
    assert "reached" in str(bad(walled))


def test_error_message_names_the_source():
    error = bad(GOOD.replace("B", "Q"))
    assert str(error).startswith("bad.layout:2:6: ")
