"""A study's design: its factors, their levels, and the conditions and groups they cross into — the one definition,
used by the typed study (hence the server), the analysis and the pilot — and what is measured in them (the
questionnaires' items and named scales, the horizon of a round).

:meth:`Design.from_config` reads it from a study's configuration as any of them holds it, and tolerates what an
older version of the platform left out:

* the JSON the store keeps with a study (``studies.config``, ``store/studies.py``), written by whichever version
  served the study: a study stored before views, fields of view or between factors existed has no ``views``,
  ``fov_angles`` or ``between``;
* the typed study's fields (:class:`study_config.study.Study`), also while it is being validated.

The levels of each factor, in the study's order:

* ``robot``: ``robots``; ``kitchen``: the names in ``kitchens`` (a name, a ``{name: ...}`` mapping as stored, or
  a resolved kitchen);
* ``view``: ``views``, else the one ``view``, else the default (``top_down``, the view of every study stored before
  views existed);
* ``fov_angle``: ``fov_angles``, else the one ``world.fov_angle``, else the paper's angle.

The within factors are ``factors`` (``robot`` and ``kitchen`` when not written), the between factors ``between``
(none when not written). Conditions cross the between factors, then the within factors, the first varying slowest;
a dimension that is not a factor has one level and comes last. So the conditions of one group (one combination of
between levels) form one consecutive block (``study_config/study/groups.py``).

Questionnaires are read with their defaults (``when`` ``after_each_trial``, an item's ``type`` ``rating``,
``reverse`` false, a scale's ``title`` its id); a rating item's scale range is ``scale.min`` to ``scale.max``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, cast

from planner.perception import FOV_ANGLE
from study_config.study.conditions import FACTORS, Condition, Factor
from study_config.study.fov_angles import angle_level
from study_config.study.views import DEFAULT_VIEW, ViewName

DEFAULT_FACTORS: tuple[Factor, ...] = ("robot", "kitchen")
"""The within factors of a study that names none."""


@dataclass(frozen=True, slots=True)
class Design:
    """The factors of a study and their levels (:attr:`conditions` is their cross), and what is measured."""

    robots: tuple[str, ...]
    kitchens: tuple[str, ...]
    """Kitchen names."""
    views: tuple[ViewName, ...]
    fov_angles: tuple[float, ...]
    """Degrees."""
    factors: tuple[Factor, ...] = DEFAULT_FACTORS
    """Within-subject factors, as the study declares them (a declared factor may have one level)."""
    between: tuple[Factor, ...] = ()
    """Between-participants factors."""
    questionnaires: tuple[QuestionnaireDesign, ...] = ()
    horizon: int | None = None
    """Ticks of a round (``world.horizon``), when the configuration gives it."""

    @classmethod
    def from_config(cls, config: Mapping[str, Any]) -> Design:
        """The design of ``config``: a stored study's JSON (of any version), or the typed study's fields."""
        horizon = _get(config.get("world"), "horizon")
        return cls(robots=tuple(str(r) for r in config.get("robots") or ()),
                   kitchens=tuple(str(_get(k, "name", k)) for k in config.get("kitchens") or ()),
                   views=view_levels(config), fov_angles=fov_angle_levels(config),
                   factors=_factors(config.get("factors")) or DEFAULT_FACTORS,
                   between=_factors(config.get("between")),
                   questionnaires=tuple(_questionnaire(q) for q in config.get("questionnaires") or ()),
                   horizon=int(horizon) if horizon is not None else None)

    def questionnaires_shown(self, when: str) -> tuple[QuestionnaireDesign, ...]:
        """The questionnaires shown ``when`` (``after_each_trial`` or ``end_of_study``), in study order."""
        return tuple(q for q in self.questionnaires if q.when == when)

    @property
    def crossed(self) -> tuple[Factor, ...]:
        """The factors in the order they are crossed: between, then within."""
        return (*self.between, *self.factors)

    def levels(self, factor: Factor) -> tuple[str, ...] | tuple[float, ...]:
        """The levels of ``factor`` in the study's order (angles in degrees)."""
        if factor == "robot":
            return self.robots
        if factor == "kitchen":
            return self.kitchens
        return self.views if factor == "view" else self.fov_angles

    def level_names(self, factor: Factor) -> tuple[str, ...]:
        """The levels of ``factor`` as condition ids, cells and exports spell them (an angle as
        :func:`study_config.study.fov_angles.angle_level`)."""
        if factor == "fov_angle":
            return tuple(angle_level(a) for a in self.fov_angles)
        return tuple(str(level) for level in self.levels(factor))

    @property
    def conditions(self) -> tuple[Condition, ...]:
        """Every condition, in study order: the factors in :attr:`crossed` order, the first varying slowest; a
        dimension that is not a factor has one level (the study's checks see to it) and comes last."""
        crossed = self.crossed
        order = [*crossed, *(f for f in FACTORS if f not in crossed)]
        flags = {"view_is_factor": "view" in crossed, "fov_angle_is_factor": "fov_angle" in crossed}
        return tuple(
            Condition.model_validate({**dict(zip(order, combination, strict=True)), **flags})
            for combination in itertools.product(*(self.levels(f) for f in order))
        )

    def groups(self) -> list[list[str]]:
        """The condition ids of each between-participants group, in study order (one group holding every id
        without between factors)."""
        ids = [c.id for c in self.conditions]
        n_groups = math.prod(len(self.levels(f)) for f in self.between)
        if n_groups < 1 or len(ids) % n_groups:
            return [ids]
        size = len(ids) // n_groups
        return [ids[g * size:(g + 1) * size] for g in range(n_groups)]


@dataclass(frozen=True, slots=True)
class ItemDesign:
    id: str
    text: str = ""
    type: str = "rating"
    """``rating``, ``choice`` or ``text``."""
    scale: tuple[int, int] | None = None
    """``(min, max)`` of a rating item's scale."""
    reverse: bool = False


@dataclass(frozen=True, slots=True)
class ScaleDesign:
    """A named scale: the mean of some of its questionnaire's rating items."""

    id: str
    title: str
    items: tuple[str, ...]
    """Item ids."""


@dataclass(frozen=True, slots=True)
class QuestionnaireDesign:
    id: str
    when: str = "after_each_trial"
    """``after_each_trial`` or ``end_of_study``."""
    items: tuple[ItemDesign, ...] = ()
    scales: tuple[ScaleDesign, ...] = ()


def view_levels(config: Mapping[str, Any]) -> tuple[ViewName, ...]:
    """The view levels of ``config``: ``views``, else ``(view,)``, else the default (top-down)."""
    views: Sequence[ViewName] | None = config.get("views")
    if views:
        return tuple(views)
    view: ViewName | None = config.get("view")
    return (view or DEFAULT_VIEW,)


def fov_angle_levels(config: Mapping[str, Any]) -> tuple[float, ...]:
    """The field-of-view levels of ``config`` in degrees: ``fov_angles``, else ``(world.fov_angle,)``, else the
    paper's angle (a stored study without a world, or a typed study whose world is not validated yet)."""
    angles = config.get("fov_angles")
    if angles:
        return tuple(float(a) for a in angles)
    single = _get(config.get("world"), "fov_angle")
    return (float(single) if single is not None else FOV_ANGLE,)


def _get(entry: Any, name: str, default: Any = None) -> Any:
    """Field ``name`` of a stored (JSON) entry or of a typed one; ``default`` when it has none."""
    if isinstance(entry, Mapping):
        return entry.get(name, default)
    return getattr(entry, name, default)


def _questionnaire(entry: Any) -> QuestionnaireDesign:
    return QuestionnaireDesign(
        id=str(_get(entry, "id")), when=str(_get(entry, "when") or "after_each_trial"),
        items=tuple(_item(i) for i in _get(entry, "items") or ()),
        scales=tuple(ScaleDesign(id=str(_get(s, "id")), title=str(_get(s, "title") or _get(s, "id")),
                                 items=tuple(str(i) for i in _get(s, "items") or ()))
                     for s in _get(entry, "scales") or ()))


def _item(entry: Any) -> ItemDesign:
    scale = _get(entry, "scale")
    low, high = _get(scale, "min"), _get(scale, "max")
    return ItemDesign(id=str(_get(entry, "id")), text=str(_get(entry, "text") or ""),
                      type=str(_get(entry, "type") or "rating"),
                      scale=(int(low), int(high)) if low is not None and high is not None else None,
                      reverse=bool(_get(entry, "reverse", False)))


def _factors(names: Any) -> tuple[Factor, ...]:
    """The factors named in ``names`` (a factor this version does not know is left out)."""
    return tuple(cast(Factor, str(f)) for f in names or () if f in FACTORS)
