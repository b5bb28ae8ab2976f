"""The choices an analysis run takes besides the table and the roles of its columns (one home for each default)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from analysis.preparation.levels import LevelOrder
from analysis.source.study_design import RatingItem, ScaleSpec

POOLED, PER_GROUP = "pooled", "per-group"
"""The error of a mixed design's within-group follow-ups (:mod:`analysis.followups.mixed_followups`): the within-group
covariance pooled over the groups (the default, as ``emmeans`` on an ``afex`` model) or each group's own."""
FOLLOW_UP_ERRORS = (POOLED, PER_GROUP)


@dataclass(frozen=True, slots=True)
class AnalysisOptions:
    levels: LevelOrder | None = None
    """Level order per factor (see :mod:`analysis.preparation.levels`); first appearance for a factor not given."""
    strict_levels: bool = True
    """Whether a present level missing from ``levels`` is an error (``--levels``) or appended (a stored study)."""
    ratings: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    """Rating columns (rank tests beside the ANOVA) and their scale's (min, max)."""
    items: tuple[RatingItem, ...] = ()
    scales: tuple[ScaleSpec, ...] = ()
    """Questionnaire scales to score (:mod:`analysis.measures.scale_scores`)."""
    include: frozenset[str] = frozenset()
    """Exclusion rules whose rows are kept (:mod:`analysis.preparation.exclusions`), e.g. ``{"invalid"}``."""
    horizon: int | None = None
    """The study's horizon: ``ticks``' upper bound."""
    position: str = "position"
    """Column of the trial's position in the participant's sequence (the order check)."""
    finished: str = "finished"
    """Column of the 0/1 outcome 'every order delivered' (censoring of ``ticks``)."""
    plots: bool = True
    """Whether to draw the plots (the slowest part of a run)."""
    seed: int = 0
    """Seed of the bootstrap of η²G's interval and of the plots' jitter."""
    title: str = "Repeated-measures analysis"
    lmm: bool = False
    """Also fit the linear mixed model of every measure (:mod:`analysis.statistics.lmm_count_models`)."""
    between: str | None = None
    """A factor between participants (one level per participant): the analysis is the mixed ANOVA
    (:mod:`analysis.pipeline.mixed_run`)."""
    ss_type: int = 3
    """Sums of squares of the mixed ANOVA: 3 (as ``afex``) or 2 (as ``pingouin``);
    :mod:`analysis.statistics.mixed_anova`."""
    follow_up_error: str = POOLED
    """The error of a mixed design's within-group follow-ups, one of :data:`FOLLOW_UP_ERRORS`."""
