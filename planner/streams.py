"""The random streams of one trial, written once: every draw of a trial comes from its seed and the tick.

A live trial (``server/game``) has one seed (62 random bits, drawn when the attempt starts and stored with it).
At tick ``t`` the participant's avatar breaks its ties with ``default_rng([seed, t, AVATAR])`` and the robot's
planner decides with ``default_rng([seed, t, ROBOT])``: each stream is a pure function of the seed and the tick,
so a trial resumed at tick t (in any process, after a restart) draws what it would have drawn, and the avatar's
draws never shift the robot's.
"""

from __future__ import annotations

import numpy as np

AVATAR = 0
"""The stream of the participant's avatar (its random tie-breaks, ``planner.avatar``)."""
ROBOT = 1
"""The stream of the robot's planner (``planner.decision.Robot.decide``)."""


def tick_rng(seed: int, tick: int, stream: int) -> np.random.Generator:
    """The generator of ``stream`` (:data:`AVATAR` or :data:`ROBOT`) for the decision at ``tick`` of the trial
    with ``seed``."""
    return np.random.default_rng([seed, tick, stream])


def avatar_rng(seed: int, tick: int) -> np.random.Generator:
    """The avatar's stream at ``tick`` of the trial with ``seed``."""
    return tick_rng(seed, tick, AVATAR)


def robot_rng(seed: int, tick: int) -> np.random.Generator:
    """The robot planner's stream at ``tick`` of the trial with ``seed``."""
    return tick_rng(seed, tick, ROBOT)
