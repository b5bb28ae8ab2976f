"""The design a stored study declares, as the statistics need it: within factors with their levels in the study's
order, the horizon, and the after-trial rating items and scales.

Read from the resolved configuration stored with the study (``studies.config``):

* factors and their levels: as the one design reader gives them (:meth:`study_config.study.Design.from_config`,
  which also reads the configuration an older version stored), an angle spelt as
  :func:`study_config.study.fov_angles.angle_level`. A factor named in ``factors`` with a single level is not a
  factor of the analysis (it is reported as such).
* questionnaire items: ``type`` ``rating`` (the default) are analysed, with their ``scale`` range and
  ``reverse: true`` for reverse-coded items; ``choice`` (a nominal index) and ``text`` items are not.
  ``scales: [{id, title, items}]`` of a questionnaire shown after each trial become measures of the cell
  (:mod:`analysis.scales`). End-of-study questionnaires are answered once per participant and are not
  within-subject measures.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from analysis.dictionary_items import item_key as item_column
from analysis.dictionary_items import scale_key
from study_config.study import Design


@dataclass(frozen=True, slots=True)
class RatingItem:
    column: str
    """``<questionnaire>.<item>`` in cells.csv."""
    minimum: int
    maximum: int
    reverse: bool = False


@dataclass(frozen=True, slots=True)
class ScaleSpec:
    column: str
    """``<questionnaire>.<scale id>``: the scale score's column."""
    title: str
    items: tuple[str, ...]
    """Columns of its rating items."""


@dataclass(frozen=True, slots=True)
class StudyDesign:
    factors: tuple[str, ...]
    levels: Mapping[str, tuple[str, ...]]
    single_level: tuple[str, ...] = ()
    """Factors named in ``factors`` that have one level in this study."""
    horizon: int | None = None
    items: tuple[RatingItem, ...] = ()
    scales: tuple[ScaleSpec, ...] = field(default=())
    between: tuple[str, ...] = ()
    """Factors between participants (``between``), with their levels in ``levels`` too."""

    @classmethod
    def from_config(cls, config: Mapping[str, Any]) -> StudyDesign:
        design = Design.from_config(config)
        declared, between = design.factors, design.between
        levels = {f: design.level_names(f) for f in (*declared, *between)}
        factors = tuple(f for f in declared if len(levels[f]) > 1)
        world = config.get("world") or {}
        horizon = world.get("horizon") if isinstance(world, Mapping) else None
        items, scales = rating_specs(config.get("questionnaires") or (), "after_each_trial")
        return cls(factors, {f: levels[f] for f in (*factors, *between)},
                   tuple(f for f in declared if f not in factors), int(horizon) if horizon is not None else None,
                   items, scales, between)

    @property
    def rating_columns(self) -> tuple[str, ...]:
        return tuple(i.column for i in self.items) + tuple(s.column for s in self.scales)


def rating_specs(questionnaires: Any, when: str) -> tuple[tuple[RatingItem, ...], tuple[ScaleSpec, ...]]:
    """The rating items and named scales of the questionnaires shown ``when`` (``after_each_trial`` or
    ``end_of_study``), in study order."""
    items: list[RatingItem] = []
    scales: list[ScaleSpec] = []
    for q in questionnaires:
        if q.get("when", "after_each_trial") != when:
            continue
        qid = str(q["id"])
        mine = {}
        for item in q.get("items", ()):
            scale = item.get("scale") or {}
            if item.get("type", "rating") != "rating" or "min" not in scale or "max" not in scale:
                continue
            rating = RatingItem(item_column(qid, str(item["id"])), int(scale["min"]), int(scale["max"]),
                                bool(item.get("reverse", False)))
            mine[str(item["id"])] = rating
            items.append(rating)
        item_ids = {str(i["id"]) for i in q.get("items", ())}
        for spec in q.get("scales", ()) or ():
            members = tuple(mine[i].column for i in spec.get("items", ()) if i in mine)
            scales.append(ScaleSpec(scale_key(qid, str(spec["id"]), item_ids), str(spec.get("title") or spec["id"]),
                                    members))
    return tuple(items), tuple(scales)
