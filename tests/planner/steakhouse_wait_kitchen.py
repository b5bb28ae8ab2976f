"""The kitchen of the dish walk tests (``test_planner_dish_walk.py``, ``test_dish_walk.py``): a robot with a dish at
(1, 2) walks east along the top row to the serving counter (7, 1) while the person stands at (4, 5), below the row."""

from __future__ import annotations

from planner.layout import parse_layout

WAIT_KITCHEN = parse_layout("\n".join([
    "XXXXXXXXX",
    "XMXDXWXSX",
    "X1      X",
    "X       X",
    "X       X",
    "X   2   X",
    "XOXBXXPXX",
    "XXXXXXXXX",
]), name="wait_test")
