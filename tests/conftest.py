"""Shared fixtures: small hand-made kitchens for rule tests."""

from __future__ import annotations

import pytest

from planner.layout import Layout, parse_layout

# Stations along the top wall (x = 1..7: onion, meat, plate, grill, board, sink, serve), a counter island
# at (4, 3) reachable from both sides, the robot starting at (1, 3), the human at (7, 3).
RULES_KITCHEN = """\
XXXXXXXXX
XOMDPBWSX
X       X
X1  X  2X
X       X
XXXXXXXXX
"""


@pytest.fixture(scope="session")
def kitchen() -> Layout:
    return parse_layout(RULES_KITCHEN, name="rules_kitchen")
