"""How a participant's avatar walks the subtask they chose (docs/domain.md §4): the movement rule, in one place.

Each tick the avatar takes the first move of a shortest path over (cell, facing) to the nearest target of the
subtask, re-planned every tick, and interacts when it faces the target (``HumanModel.move_toward``, the simulated
human's own rule). Targets are judged on the participant's **modelled KB**, not the world: the avatar walks to
where the participant can know things are (a steak they have not seen is not a target).

The robot's cell is avoided only where the participant can know the robot is: in view now, or where the
participant last acknowledged it (its modelled KB), so the avatar never routes around a robot the participant
cannot know about (if it bumps into one, it is then facing it). A robot known to have stood still for
``STUCK_TICKS`` ticks is walked around (the simulated human's rule, :class:`RobotWatch`); without this the avatar
dithered beside a parked robot that flickered in and out of view as it turned.

The server's controller (``server/game/controller.py``) calls :func:`avatar_move` once per tick of a subtask; the
queue of key presses and the explanations of a subtask that does not get anywhere stay there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from planner.fov import view
from planner.geometry import Action, Pos
from planner.human import STUCK_TICKS, HumanModel
from planner.kb import KnowledgeBase
from planner.state import WorldState
from planner.subtasks import Subtask, targets

OFF_GRID: Pos = (-1, -1)
"""The cell the avatar avoids when the participant cannot know where the robot is (no cell of any kitchen)."""


@dataclass(frozen=True, slots=True)
class RobotWatch:
    """Where the robot was last tick and for how many ticks it has stood on that cell."""

    last: Pos | None = None
    still: int = 0

    def seen(self, world: WorldState) -> RobotWatch:
        """The watch after this tick's world (call once per tick, whatever the avatar does)."""
        robot = world.robot.pos
        return RobotWatch(robot, self.still + 1 if robot == self.last else 0)

    @property
    def parked(self) -> bool:
        """Whether the robot has stood still long enough to be walked around (``STUCK_TICKS``)."""
        return self.still >= STUCK_TICKS


def avatar_move(model: HumanModel, angle: float, world: WorldState, kb: KnowledgeBase, subtask: Subtask,
                watch: RobotWatch, rng: np.random.Generator) -> tuple[Action, bool]:
    """The avatar's action this tick toward ``subtask``'s nearest target on ``kb``, seeing with ``angle``, and
    whether it wants to move (it is not yet at a target); ``watch`` is :meth:`RobotWatch.seen` of this tick.
    Random tie-breaks (waiting or detouring beside the robot) draw from ``rng``."""
    human, robot = world.human, world.robot.pos
    seen = view(model.layout, human.pos, human.facing, angle).cells
    known = robot in seen or (kb.robot is not None and kb.robot.pos == robot)
    cells = targets(model.layout, subtask, kb, model.rules)
    return model.move_toward((human.pos, human.facing), cells, robot if known else OFF_GRID, rng,
                             partner_parked=known and watch.parked)
