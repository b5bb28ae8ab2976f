"""Between-participants groups: the least-filled group first, then its least-filled order; joins at once stay
balanced across groups and, inside each group, across its within orders."""

from __future__ import annotations

from collections import Counter

import pytest

from server.flow import service
from store.group_assignment import least_filled_grouped
from store.studies import sync_study
from study_config.catalog import load_one


def test_the_least_filled_group_then_its_least_filled_order():
    groups = [0, 0, 1, 1]
    assert least_filled_grouped([1, 0, 0, 0], groups) == 2, "group 1 has fewer participants"
    assert least_filled_grouped([1, 1, 1, 0], groups) == 3
    assert least_filled_grouped([1, 1, 2, 0], groups) == 0, "equal groups: the lowest, then its least order"
    assert least_filled_grouped([2, 1, 1], []) == 1, "no groups: the least-filled order"


@pytest.fixture
def between(study_file, store):
    loaded = load_one(study_file("between_view", robots=["stay", "fov_aware"], kitchens=["practice"],
                                 factors=["robot"], views=["top_down", "first_person"], between=["view"]))
    with store.transaction() as session:
        sync_study(session, loaded.study)
    return loaded


def test_a_between_view_study_has_a_group_per_view_with_its_own_orders(between):
    study = between.study
    assert [c.id for c in study.conditions] == ["stay@practice@top_down", "fov_aware@practice@top_down",
                                                "stay@practice@first_person", "fov_aware@practice@first_person"]
    assert between.order_groups == (0, 0, 1, 1)
    for order, group in zip(between.orders, between.order_groups, strict=True):
        assert {cid.rsplit("@", 1)[1] for cid in order} == {("top_down", "first_person")[group]}


def test_joins_fill_the_groups_in_turn_and_the_orders_inside_them(store, between):
    indexes = [service.join(store, between, {}, False).assignment.order_index for _ in range(8)]
    assert indexes == [0, 2, 1, 3, 0, 2, 1, 3]


def test_concurrent_joins_keep_groups_and_orders_balanced(between, join_at_once):
    results = join_at_once(between, 22)
    tally = Counter(results)
    groups = Counter(between.order_groups[i] for i in results)
    assert sorted(groups.values()) == [11, 11]
    assert max(tally.values()) - min(tally[i] for i in range(4)) <= 1
