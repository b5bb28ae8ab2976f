"""The interrupt actions a participant can send (protocol v1, ``interrupt`` messages): the words of the protocol,
which the game's controller turns into moves (:mod:`server.game.controller`)."""

from __future__ import annotations

from enum import Enum


class Interrupt(str, Enum):
    UP = "up"
    DOWN = "down"
    LEFT = "left"
    RIGHT = "right"
    STAY = "stay"
    INTERACT = "interact"
    STOP = "stop"
