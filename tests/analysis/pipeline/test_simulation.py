"""The paper's tests on a simulation (:func:`analysis.pipeline.simulation.robot_effects`): seeds as participants, robot
× kitchen on the KB gap, then the robot within each kitchen."""

from __future__ import annotations

import numpy as np

from analysis.pipeline.simulation import robot_effects


def rows(seeds: int = 8, effect_in_a: float = 0.3):
    """Two robots × two kitchens; the FOV-aware robot's KB gap is ``effect_in_a`` lower in kitchen ``a`` only."""
    rng = np.random.default_rng(3)
    out = []
    for seed in range(seeds):
        person = rng.normal(1.0, 0.2)
        for kitchen in ("a", "b"):
            for robot in ("fov_aware", "baseline"):
                gap = person + rng.normal(0, 0.02) - (effect_in_a if robot == "fov_aware" and kitchen == "a" else 0)
                out.append({"layout": kitchen, "robot": robot, "seed": seed, "kb_gap_mean": round(gap, 4)})
    return out


def test_the_interaction_and_the_robot_in_each_kitchen_are_reported():
    lines = robot_effects(rows(), "kb_gap_mean", ["fov_aware", "baseline"])
    assert lines[0] == "kb_gap_mean, 8 seeds as participants (repeated-measures ANOVA):"
    interaction = next(line for line in lines if line.startswith("  robot * kitchen: "))
    assert interaction.startswith("  robot * kitchen: F(1, 7) = ") and "p < .001" in interaction
    in_a = next(line for line in lines if line.startswith("  robot in a: "))
    in_b = next(line for line in lines if line.startswith("  robot in b: "))
    assert "fov_aware − baseline -0.3" in in_a and "p < .001" in in_a
    assert "fov_aware − baseline" in in_b and "p < .001" not in in_b


def test_one_kitchen_is_the_robots_effect_alone():
    lines = robot_effects([r for r in rows() if r["layout"] == "a"], "kb_gap_mean", ["fov_aware", "baseline"])
    assert [line.split(":")[0] for line in lines[1:]] == ["  robot"]


def test_a_seed_missing_a_cell_is_left_out_and_too_few_seeds_report_nothing():
    some = rows()[1:]  # seed 0 has no FOV-aware trial in kitchen a
    assert robot_effects(some, "kb_gap_mean", ["fov_aware", "baseline"])[0].startswith("kb_gap_mean, 7 seeds")
    assert robot_effects(rows(seeds=2), "kb_gap_mean", ["fov_aware", "baseline"]) == []
    assert robot_effects(rows(), "kb_gap_mean", ["fov_aware"]) == []
