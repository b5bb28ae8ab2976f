"""The objects an agent can hold or a counter can carry (docs/domain.md §1).

A dish is made as: meat → grill; onion → board, chopped; dirty plate → sink, washed, taken out clean;
clean plate takes the steak from the grill (``steak_plate``); the plated steak takes the garnish from
the board (``dish``); the dish is delivered at the serving counter.
"""

from __future__ import annotations

ONION = "onion"
MEAT = "meat"
DIRTY_PLATE = "dirty_plate"
CLEAN_PLATE = "clean_plate"
STEAK_PLATE = "steak_plate"
DISH = "dish"

OBJECTS: tuple[str, ...] = (ONION, MEAT, DIRTY_PLATE, CLEAN_PLATE, STEAK_PLATE, DISH)
