"""The study design as the export needs it, read from the resolved configuration stored with the study.

Conditions are the server's, read by the one design reader (:meth:`study_config.study.Design.from_config`, which
also reads the configuration an older version stored): the robot × kitchen (× view, × fov_angle, when these are
factors) cross in study order (the first factor varies slowest; condition ids are ``robot@kitchen``,
``robot@kitchen@view``, ``robot@kitchen@angle`` or ``robot@kitchen@view@angle``). A condition's cell is the tuple of
its levels in :attr:`ExportDesign.fields` order: ``(robot, kitchen)``, ``(robot, kitchen, view)``,
``(robot, kitchen, fov_angle)`` or all four, an angle spelt as :func:`study_config.study.fov_angles.angle_level`
(``90``). Questionnaire items are split into those
answered after each main trial (one value per condition: measures of the cell) and those answered once at
the end of the study (one value per participant).

The columns of ``cells.csv`` and ``wide.csv`` that come from the questionnaires are defined here once
(:attr:`ExportDesign.trial_value_columns`, :attr:`ExportDesign.end_value_columns`): the export fills exactly these
columns and the data dictionary documents exactly these, so a study that validates always exports. Free-text items
are not among them (their answers are in ``answers.csv``); rating and choice items are, and so is every named
scale's score (:mod:`analysis.measures.scale_scores`), for questionnaires after each trial and at the end of the study
alike.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from analysis.exports.dictionary import NUM, Column, item_columns
from analysis.source.naming import item_key as item_column
from analysis.source.study_design import RatingItem, ScaleSpec, rating_specs
from study_config.study import Condition, Design
from study_config.study.fov_angles import angle_level

CELL_FIELDS = ("robot", "kitchen", "view", "fov_angle")
"""The fields a cell tuple may have, in order (robot and kitchen always; view and fov_angle when factors)."""


@dataclass(frozen=True, slots=True)
class ExportDesign:
    robots: tuple[str, ...]
    kitchens: tuple[str, ...]
    conditions: tuple[tuple[str, ...], ...]
    """Cells in study order: their levels of :attr:`fields`."""
    trial_items: tuple[tuple[str, str, str], ...]
    """(questionnaire, item, text) answered after each main trial."""
    end_items: tuple[tuple[str, str, str], ...]
    """(questionnaire, item, text) answered once at the end of the study."""
    ratings: tuple[RatingItem, ...] = ()
    """Every rating item, both positions (the scales' reversal reads them)."""
    trial_scales: tuple[ScaleSpec, ...] = ()
    """Named scales of the questionnaires after each trial (a score per cell)."""
    end_scales: tuple[ScaleSpec, ...] = ()
    """Named scales of the end-of-study questionnaires (a score per participant)."""
    between: tuple[str, ...] = ()
    """Factors between participants: a participant is expected in the conditions of their group only."""
    fields: tuple[str, ...] = ("robot", "kitchen")
    """The fields of a cell: robot, kitchen, then view and fov_angle when they are factors (within or between)."""

    @classmethod
    def from_config(cls, config: Mapping[str, Any]) -> ExportDesign:
        design = Design.from_config(config)
        fields = tuple(f for f in CELL_FIELDS if f in ("robot", "kitchen") or f in design.crossed)
        conditions = tuple(_cell(c, fields) for c in design.conditions)
        trial_ratings, trial_scales = rating_specs(design, "after_each_trial")
        end_ratings, end_scales = rating_specs(design, "end_of_study")
        return cls(design.robots, design.kitchens, conditions, _valued_items(design, "after_each_trial"),
                   _valued_items(design, "end_of_study"), trial_ratings + end_ratings, trial_scales, end_scales,
                   design.between, fields)

    def condition_of(self, condition_id: str) -> tuple[str, str] | None:
        """``(robot, kitchen)`` of a condition id (``robot@kitchen``, or ``robot@kitchen@view`` in a study with
        a view factor), or ``None`` when the id is malformed."""
        robot, sep, rest = condition_id.partition("@")
        return (robot, rest.partition("@")[0]) if sep else None

    def expected_cells(self, condition_order: Sequence[str]) -> tuple[tuple[str, ...], ...]:
        """The cells a participant assigned ``condition_order`` should have: every condition, or with between
        factors those of the participant's group (the between levels of their first assigned condition)."""
        if not self.between or not condition_order:
            return self.conditions
        group = {self.fields.index(f): level for f, level in self.group_of(condition_order).items()}
        return tuple(c for c in self.conditions if all(c[i] == level for i, level in group.items()))

    def group_of(self, condition_order: Sequence[str]) -> dict[str, str]:
        """The participant's level of each between factor (from their first assigned condition; empty without
        between factors or an order)."""
        if not self.between or not condition_order:
            return {}
        first = condition_order[0].split("@")
        return {f: first[self.fields.index(f)] for f in self.between
                if f in self.fields and self.fields.index(f) < len(first)}

    @property
    def within_fields(self) -> tuple[str, ...]:
        """The fields of a cell that vary within participants: :attr:`fields` without the between factors."""
        return tuple(f for f in self.fields if f not in self.between)

    def within_cell(self, cell: Sequence[str]) -> tuple[str, ...]:
        """The levels of :attr:`within_fields` of a cell (a member of :attr:`conditions`)."""
        return tuple(level for f, level in zip(self.fields, cell, strict=True) if f not in self.between)

    @property
    def within_cells(self) -> tuple[tuple[str, ...], ...]:
        """The cells every participant plays, whatever their group (:meth:`within_cell` of each condition, in study
        order): ``wide.csv`` has one column per measure and such a cell."""
        return tuple(dict.fromkeys(self.within_cell(c) for c in self.conditions))

    def between_levels(self, factor: str) -> tuple[str, ...]:
        """The levels of a between factor in study order."""
        i = self.fields.index(factor)
        return tuple(dict.fromkeys(c[i] for c in self.conditions))

    def cell_of(self, robot: str, kitchen: str, view: str, fov_angle: float | None = None) -> tuple[str, ...]:
        """The cell (a member of ``conditions``) a trial with these levels belongs to."""
        levels = {"robot": robot, "kitchen": kitchen, "view": view,
                  "fov_angle": angle_level(fov_angle) if fov_angle is not None else ""}
        return tuple(levels[f] for f in self.fields)

    @property
    def trial_value_columns(self) -> list[Column]:
        """Questionnaire columns of ``cells.csv`` (and per condition of ``wide.csv``): the rating and choice
        items answered after each trial, then their scales' scores."""
        return item_columns(self.trial_items) + scale_columns(self.trial_scales)

    @property
    def end_value_columns(self) -> list[Column]:
        """Questionnaire columns of ``wide.csv`` answered once: end-of-study rating and choice items, then their
        scales' scores."""
        return item_columns(self.end_items) + scale_columns(self.end_scales)

    def item_names(self, items: tuple[tuple[str, str, str], ...]) -> list[str]:
        return [item_column(q, i) for q, i, _ in items]


def _valued_items(design: Design, when: str) -> tuple[tuple[str, str, str], ...]:
    """(questionnaire, item, text) of the items with a value (not free text: it is exported in answers.csv only)
    of the questionnaires shown ``when``."""
    return tuple((q.id, i.id, i.text) for q in design.questionnaires_shown(when) for i in q.items if i.type != "text")


def _cell(condition: Condition, fields: tuple[str, ...]) -> tuple[str, ...]:
    levels = {"robot": condition.robot, "kitchen": condition.kitchen, "view": condition.view,
              "fov_angle": angle_level(condition.fov_angle)}
    return tuple(levels[f] for f in fields)


def scale_columns(scales: tuple[ScaleSpec, ...]) -> list[Column]:
    """One column per named scale: its score (see :mod:`analysis.measures.scale_scores`)."""
    return [Column(s.column, NUM, f"scale score “{s.title}”: mean of {', '.join(s.items)} after reversing "
                                  "reverse-coded items (min + max − value); empty when an item is missing")
            for s in scales]
