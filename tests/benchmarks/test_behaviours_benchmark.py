"""The behaviours benchmark's trial arguments (benchmarks/planner/behaviours.py): generated kitchens of a chosen grid
size, for tuning on kitchens as small as some shipped ones, and a usage error for a size that is not one."""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "benchmarks" / "planner"))
behaviours = importlib.import_module("behaviours")  # the benchmark script, as dish_bound.py imports it


def parsed(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    behaviours.trial_arguments(parser, "baseline")
    return parser.parse_args(list(argv))


def test_generated_kitchens_of_a_given_size():
    kitchens = behaviours.kitchens_of(parsed("--shipped", "", "--generator-seeds", "3-4", "--generator-size", "10x8"))
    assert kitchens == ["gen_3_10x8", "gen_4_10x8"]
    layout = behaviours.kitchen_layout(kitchens[0])
    assert (layout.width, layout.height) == (10, 8)
    assert behaviours.kitchen_layout("gen_3").rows != layout.rows  # without a size, one is drawn


def test_without_a_size_each_generated_kitchen_draws_its_own():
    assert behaviours.kitchens_of(parsed("--shipped", "none_3", "--generator-seeds", "3")) == ["none_3", "gen_3"]


def test_a_size_that_is_not_one_is_a_usage_error(capsys):
    with pytest.raises(SystemExit):
        parsed("--generator-size", "ten")
    assert "--generator-size" in capsys.readouterr().err
