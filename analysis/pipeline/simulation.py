"""The paper's tests on a simulation (``steakhouse simulate``): each seed is one simulated participant, who plays
every robot × kitchen with the same simulated person's random stream, so the trials of a seed are repeated
measures. The test is the one the study's analysis runs on people (docs/analysis.md): a repeated-measures ANOVA of
robot (× kitchen, with two kitchens or more) on a measure, then the robot's simple effect within each kitchen
(Holm-adjusted as a family), with the mean difference of the first two robots named.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import pandas as pd

from analysis.followups.simple_effects import simple_effects
from analysis.preparation.cells import complete_cases
from analysis.statistics.anova import rm_anova
from analysis.statistics.apa import apa_f_sentence, p_clause

MIN_SEEDS = 3
"""Fewer seeds leave the ANOVA's error term with under two degrees of freedom: not reported."""


def robot_effects(rows: Sequence[Mapping[str, object]], measure: str, robots: Sequence[str]) -> list[str]:
    """One line per test of ``measure`` (a column of the simulation's ``trials.csv``) over the seeds that have a
    trial in every robot × kitchen cell; ``robots`` in the order to compare (first − second). Empty when fewer than
    two robots or :data:`MIN_SEEDS` complete seeds."""
    if len(robots) < 2 or not rows:
        return []
    df = pd.DataFrame([{"seed": r["seed"], "robot": r["robot"], "kitchen": r["layout"], measure: r[measure]}
                       for r in rows if r["robot"] in robots])
    df[measure] = pd.to_numeric(df[measure], errors="coerce")
    df["robot"] = pd.Categorical(df["robot"], categories=list(robots))
    kitchens = list(pd.unique(df["kitchen"]))
    df["kitchen"] = pd.Categorical(df["kitchen"], categories=kitchens)
    within = ["robot", "kitchen"] if len(kitchens) > 1 else ["robot"]
    clean, _ = complete_cases(df, measure, within, "seed")
    seeds = clean["seed"].nunique()
    if seeds < MIN_SEEDS:
        return []
    lines = [f"{measure}, {seeds} seeds as participants (repeated-measures ANOVA):"]
    for row in rm_anova(clean, measure, within, "seed").to_dict("records"):
        lines.append(f"  {row['effect']}: {apa_f_sentence(row)}")
    effects = simple_effects(clean, measure, within, "seed")
    for row in effects[effects["factor"] == "robot"].to_dict("records"):
        difference = (f", {row['level_1']} − {row['level_2']} {float(row['mean_diff']):+.3f}"
                      if isinstance(row.get("level_1"), str) else "")
        lines.append(f"  robot in {str(row['at']).removeprefix('kitchen=')}: {apa_f_sentence(row)}"
                     f"{difference} (Holm-adjusted {p_clause(float(row['p_holm']))})")
    return lines
