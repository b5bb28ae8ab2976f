"""The design a stored study declares, as the statistics need it: within factors with their levels in the study's
order, the horizon, and the after-trial rating items and scales.

Read from the resolved configuration stored with the study (``studies.config``) by the one design reader
(:meth:`study_config.study.Design.from_config`, which also reads the configuration an older version stored):

* factors and their levels, an angle spelt as :func:`study_config.study.fov_angles.angle_level`. A factor named in
  ``factors`` with a single level is not a factor of the analysis (it is reported as such).
* questionnaire items: ``type`` ``rating`` (the default) are analysed, with their ``scale`` range and
  ``reverse: true`` for reverse-coded items; ``choice`` (a nominal index) and ``text`` items are not.
  ``scales: [{id, title, items}]`` of a questionnaire shown after each trial become measures of the cell
  (:mod:`analysis.measures.scale_scores`). End-of-study questionnaires are answered once per participant and are not
  within-subject measures.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from analysis.source.naming import item_key as item_column
from analysis.source.naming import scale_key
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
        items, scales = rating_specs(design, "after_each_trial")
        return cls(factors, {f: levels[f] for f in (*factors, *between)},
                   tuple(f for f in declared if f not in factors), design.horizon, items, scales, between)

    @property
    def rating_columns(self) -> tuple[str, ...]:
        return tuple(i.column for i in self.items) + tuple(s.column for s in self.scales)


def rating_specs(design: Design, when: str) -> tuple[tuple[RatingItem, ...], tuple[ScaleSpec, ...]]:
    """The rating items and named scales of the questionnaires shown ``when`` (``after_each_trial`` or
    ``end_of_study``), in study order, as analysis columns."""
    items: list[RatingItem] = []
    scales: list[ScaleSpec] = []
    for q in design.questionnaires_shown(when):
        mine = {i.id: RatingItem(item_column(q.id, i.id), *i.scale, reverse=i.reverse)
                for i in q.items if i.type == "rating" and i.scale is not None}
        items.extend(mine.values())
        item_ids = {i.id for i in q.items}
        scales.extend(ScaleSpec(scale_key(q.id, spec.id, item_ids), spec.title,
                                tuple(mine[i].column for i in spec.items if i in mine)) for spec in q.scales)
    return tuple(items), tuple(scales)
