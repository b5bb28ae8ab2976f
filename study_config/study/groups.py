"""Factors between participants: the study's groups and what cannot be balanced.

A study's ``between`` factors (robot, kitchen, view, fov_angle) are crossed before its within ``factors``
(``study_config/study/design.py``, which also cuts the condition list into groups), so the conditions of one group
(one combination of between levels) form one consecutive block of the condition list, and each group's within
conditions are counterbalanced on their own: the study's orders are group 0's orders, then group
1's, and so on. A participant is assigned to one order, hence to one group (``store/group_assignment.py``
fills the groups in balance, then the orders inside the chosen group).

Designs that cannot balance are refused: a factor both within and between, a between factor with one level, and
a ``fixed`` order (one order cannot hold the conditions of several groups).
"""

from __future__ import annotations

from collections.abc import Sequence

from study_config.study.base import Loc


def between_problems(factors: Sequence[str], between: Sequence[str]) -> list[tuple[Loc, str]]:
    """A factor named both within and between, or twice between."""
    problems: list[tuple[Loc, str]] = [((), f"{f!r} is both a within factor (factors) and a between factor "
                                            "(between); each factor is one or the other") for f in between
                                       if f in factors]
    problems += [((), f"between names {f!r} twice") for i, f in enumerate(between) if f in between[:i]]
    return problems


def scheme_problems(scheme: str, between: Sequence[str]) -> list[tuple[Loc, str]]:
    """A counterbalancing scheme that cannot serve groups."""
    if between and scheme == "fixed":
        return [(("scheme",), "a fixed order cannot serve the groups of a between factor (each group plays other "
                              "conditions); use latin_square or full")]
    return []
