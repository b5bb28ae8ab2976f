"""Shared synthetic data for the analysis tests: a robot × kitchen within design."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pandas as pd
import pytest

ROBOTS = ("baseline", "fov_aware")
KITCHENS = ("none_3", "mid_2")


def make_cells(n_subjects: int = 12, seed: int = 0) -> pd.DataFrame:
    """One row per participant × robot × kitchen, with two measures and a real robot effect."""
    rng = np.random.default_rng(seed)
    rows = []
    for s in range(1, n_subjects + 1):
        skill = rng.normal(100.0, 15.0)
        for r, robot in enumerate(ROBOTS):
            for k, kitchen in enumerate(KITCHENS):
                rows.append(
                    {
                        "participant": f"P{s:02d}",
                        "robot": robot,
                        "kitchen": kitchen,
                        "ticks": skill - 10.0 * r - 4.0 * r * k + rng.normal(0.0, 4.0),
                        "interrupts": float(rng.poisson(3 + 2 * r)),
                    }
                )
    return pd.DataFrame(rows)


@pytest.fixture
def cells() -> Callable[..., pd.DataFrame]:
    """Factory for the synthetic long table (see ``make_cells``)."""
    return make_cells
