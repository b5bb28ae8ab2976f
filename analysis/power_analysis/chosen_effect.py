"""Power for a chosen effect size (``steakhouse power --effect eta2g=0.1``), beside the pilot's own.

For an omnibus effect E the pilot's data are changed so that E's generalized η² equals the chosen value and
nothing else changes: with L_E the effect's orthonormal contrasts (:mod:`analysis.statistics.sphericity`) and z̄ the
mean of the participants' contrast scores, every participant's values get (c − 1) · L_E z̄ added. That multiplies SS_E
by c² and leaves every error term, the participants' sum of squares and every other effect as they were (the
contrasts of different effects are orthogonal), so with

    η²G = SS_E / (SS_E + SS_subjects + Σ SS_error)        (:mod:`analysis.statistics.anova`)

c = √(η²G* / (1 − η²G*) · (SS_subjects + Σ SS_error) / SS_E). The pattern of the cell means (which levels differ
in which direction) stays the pilot's; only its size is set. An effect the pilot does not show at all (SS_E = 0)
has no pattern to scale and gets no power at the chosen size.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analysis.source.input_errors import AnalysisInputError
from analysis.statistics.anova import effect_sums, effects_of

SIZE_NAMES = ("eta2g",)


@dataclass(frozen=True, slots=True)
class EffectSize:
    """A chosen generalized η² (``eta2g=0.1``)."""

    eta2g: float

    @property
    def label(self) -> str:
        return f"eta2g={self.eta2g:g}"

    @classmethod
    def parse(cls, text: str) -> EffectSize:
        name, sep, value = text.partition("=")
        if not sep or name.strip() not in SIZE_NAMES:
            raise AnalysisInputError(f"--effect {text!r}: expected eta2g=VALUE, e.g. eta2g=0.1")
        try:
            size = float(value)
        except ValueError:
            raise AnalysisInputError(f"--effect {text!r}: {value!r} is not a number") from None
        if not 0 < size < 1:
            raise AnalysisInputError(f"--effect {text!r}: η²G must be between 0 and 1")
        return cls(size)


def with_effect_size(values: np.ndarray, levels: Sequence[int], within: Sequence[str], effect: Sequence[int],
                     contrast: np.ndarray, eta2g: float) -> np.ndarray | None:
    """The participants × cells ``values`` with effect ``effect`` (contrasts ``contrast``) scaled to ``eta2g``;
    ``None`` when the values show no such effect to scale."""
    n = len(values)
    ss = effect_sums(values, levels, effect)[0]
    error_total = effect_sums(values, levels, ())[1] + sum(effect_sums(values, levels, e)[1]
                                                           for e in effects_of(within))
    if ss <= 1e-12 * max(error_total, 1.0) or n < 2:
        return None
    c = math.sqrt(eta2g / (1 - eta2g) * error_total / ss)
    mean_scores = (values @ contrast).mean(axis=0)
    return np.asarray(values + (c - 1) * (contrast @ mean_scores)[None, :])
