"""The order and carry-over check (analysis.statistics.order_check): a linear mixed model with position as a
covariate."""

from __future__ import annotations

import numpy as np
import pandas as pd

from analysis.statistics.order_check import order_check


def sequenced(seed: int, drift: float, carryover: float = 0.0) -> pd.DataFrame:
    """12 participants, robot × kitchen in a balanced Latin square of positions, a robot effect, and ``drift``
    per later position (``carryover``: the robot effect grows with position)."""
    rng = np.random.default_rng(seed)
    orders = [[0, 1, 2, 3], [1, 3, 0, 2], [2, 0, 3, 1], [3, 2, 1, 0]]
    cells = [("a", "k1"), ("a", "k2"), ("b", "k1"), ("b", "k2")]
    rows = []
    for s in range(12):
        person = rng.normal(0, 5)
        for position, c in enumerate(orders[s % 4], start=1):
            robot, kitchen = cells[c]
            effect = (3 + carryover * position) if robot == "b" else 0.0
            rows.append({"p": s, "robot": robot, "kitchen": kitchen, "position": position,
                         "y": 50 + person + effect + drift * position + rng.normal(0, 1)})
    return pd.DataFrame(rows)


def test_a_drift_with_position_is_found_and_said_in_plain_words() -> None:
    check = order_check(sequenced(1, drift=2.0), "y", ["robot", "kitchen"], "p")
    assert check.order_effect is True and abs(check.slope - 2.0) < 0.5
    assert check.sentence.startswith("An order effect was found for y: each later position changed it by")


def test_no_drift_no_order_effect_and_carryover_shows_as_an_interaction() -> None:
    check = order_check(sequenced(2, drift=0.0), "y", ["robot", "kitchen"], "p")
    assert check.order_effect is False and "No order effect was found for y" in check.sentence
    carried = order_check(sequenced(2, drift=0.0, carryover=2.0), "y", ["robot", "kitchen"], "p")
    assert carried.carryover_p < 0.05 and "possible carry-over" in carried.sentence


def test_what_cannot_be_checked_is_said() -> None:
    df = sequenced(3, drift=0.0)
    assert "no 'position' column" in order_check(df.drop(columns="position"), "y", ["robot"], "p").sentence
    assert "does not vary" in order_check(df.assign(y=1.0), "y", ["robot", "kitchen"], "p").sentence
    assert order_check(df[df["p"] < 2], "y", ["robot", "kitchen"], "p").order_effect is None


def test_one_order_for_everyone_is_named_as_confounding() -> None:
    df = sequenced(4, drift=1.0)
    cells = {("a", "k1"): 1, ("a", "k2"): 2, ("b", "k1"): 3, ("b", "k2"): 4}
    df["position"] = [cells[(r, k)] for r, k in zip(df["robot"], df["kitchen"], strict=True)]
    check = order_check(df, "y", ["robot", "kitchen"], "p")
    assert check.order_effect is None
    assert "position is confounded with condition" in check.sentence and "singular" not in check.sentence
