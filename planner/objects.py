"""The objects an agent can hold or a counter can carry: their names live in :mod:`planner.vocabulary` (the
kitchen's words, spelled once); this module keeps them where the world's code has always imported them from.
"""

from __future__ import annotations

from planner.vocabulary import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, OBJECTS, ONION, STEAK_PLATE

__all__ = ["CLEAN_PLATE", "DIRTY_PLATE", "DISH", "MEAT", "OBJECTS", "ONION", "STEAK_PLATE"]
