"""The participant's field of view as a factor: the study's ``fov_angles`` (the levels of the ``fov_angle``
factor, within or between participants) or, without them, the one ``world.fov_angle`` of every trial.

Each trial plays at one angle, stored on its row (``trials.fov_angle``): the server masks the participant's
view with it (docs/domain.md §2), the robot's model of the person uses it (docs/domain.md §5), and the admin's
live view and replay draw it. A level is written in condition ids, cells and exports as :func:`angle_level`
(``90``, ``112.5``), so the same angle has one spelling everywhere.
"""

from __future__ import annotations


def angle_level(angle: float) -> str:
    """The level name of ``angle`` degrees: the shortest spelling of the number (``90``, not ``90.0``)."""
    return f"{float(angle):g}"


def angle_value(angle: float | None) -> int | float | None:
    """``angle`` as the export writes it: an integral angle as an int (so ``90`` reads back as :func:`angle_level`
    spells it), else the float; ``None`` (a trial stored before angles were recorded) stays ``None``."""
    if angle is None:
        return None
    return int(angle) if float(angle).is_integer() else float(angle)
