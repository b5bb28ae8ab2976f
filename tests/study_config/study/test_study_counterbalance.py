"""Condition orders: balanced Latin squares (Williams designs), all permutations, a fixed order."""

from __future__ import annotations

import itertools
import math
from collections import Counter

import pytest

from study_config.study.counterbalance import condition_orders


def ids(n: int) -> list[str]:
    return [f"robot{i}@kitchen" for i in range(n)]


def position_counts(orders: list[tuple[str, ...]]) -> list[Counter[str]]:
    return [Counter(order[pos] for order in orders) for pos in range(len(orders[0]))]


def successor_counts(orders: list[tuple[str, ...]]) -> Counter[tuple[str, str]]:
    return Counter(pair for order in orders for pair in itertools.pairwise(order))


@pytest.mark.parametrize("n", [2, 4, 6])
def test_latin_square_even_is_a_williams_square(n: int) -> None:
    conditions = ids(n)
    orders = condition_orders(conditions, "latin_square")
    assert len(orders) == n
    assert all(sorted(order) == sorted(conditions) for order in orders)
    for counts in position_counts(orders):
        assert counts == Counter(dict.fromkeys(conditions, 1))
    pairs = successor_counts(orders)
    assert pairs == Counter({(a, b): 1 for a in conditions for b in conditions if a != b})


@pytest.mark.parametrize("n", [3, 5])
def test_latin_square_odd_adds_the_mirror_to_balance_carry_over(n: int) -> None:
    conditions = ids(n)
    orders = condition_orders(conditions, "latin_square")
    assert len(orders) == 2 * n
    assert len(set(orders)) == 2 * n
    assert all(sorted(order) == sorted(conditions) for order in orders)
    for counts in position_counts(orders):
        assert counts == Counter(dict.fromkeys(conditions, 2))
    pairs = successor_counts(orders)
    assert pairs == Counter({(a, b): 2 for a in conditions for b in conditions if a != b})


def test_latin_square_of_one_condition_is_one_order() -> None:
    assert condition_orders(["fov_aware@none_3"], "latin_square") == [("fov_aware@none_3",)]


def test_latin_square_starts_with_the_study_order() -> None:
    conditions = ["fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3", "baseline@mid_2"]
    orders = condition_orders(conditions, "latin_square")
    assert orders[0][0] == "fov_aware@none_3"
    assert {order[0] for order in orders} == set(conditions)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_full_gives_every_permutation_once(n: int) -> None:
    conditions = ids(n)
    orders = condition_orders(conditions, "full")
    assert len(orders) == math.factorial(n)
    assert len(set(orders)) == len(orders)
    assert all(sorted(order) == sorted(conditions) for order in orders)


def test_full_refuses_an_unmanageable_number_of_orders() -> None:
    with pytest.raises(ValueError, match="latin_square"):
        condition_orders(ids(9), "full")


def test_fixed_is_the_given_order() -> None:
    conditions = ["a@k", "b@k", "c@k"]
    assert condition_orders(conditions, "fixed", ["c@k", "a@k", "b@k"]) == [("c@k", "a@k", "b@k")]


@pytest.mark.parametrize("order", [None, ["a@k", "b@k"], ["a@k", "b@k", "b@k"], ["a@k", "b@k", "x@k"]])
def test_fixed_must_be_a_permutation_of_the_conditions(order: list[str] | None) -> None:
    with pytest.raises(ValueError, match="every condition exactly once"):
        condition_orders(["a@k", "b@k", "c@k"], "fixed", order)


def test_unknown_scheme_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown counterbalancing scheme 'random'"):
        condition_orders(["a@k", "b@k"], "random")
