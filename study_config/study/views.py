"""How the participant sees the kitchen: the study's ``view`` (one for every trial) or ``views`` (the levels
of the ``view`` factor).

- ``top_down``: the 2D kitchen from above, cells out of view black (docs/client.md, "The game").
- ``first_person``: the same world in 3D through the cook's eyes, the camera's horizontal field of view the
  study's ``world.fov_angle`` (docs/client.md, "The first-person view"), as in the paper's VR setting.

The server's masking is the same for both (docs/domain.md §2): the view changes only how the browser draws
the cells it is sent, so the view is the one setting the participant's browser may be told.
"""

from __future__ import annotations

from typing import Literal

ViewName = Literal["top_down", "first_person"]

VIEW_NAMES: tuple[ViewName, ...] = ("top_down", "first_person")

DEFAULT_VIEW: ViewName = "top_down"
"""The view of a study that names none, and of trials stored before views existed."""
