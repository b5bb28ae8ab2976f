"""Shortest paths over (cell, facing): the ways around the other agent are every shortest path that avoids
its cell, checked against a plain breadth-first search from the agent's pose."""

from __future__ import annotations

import random

import pytest

from planner.geometry import DIRECTIONS, Action, move_action
from planner.paths import Pose, detour_moves, distances_to, next_pose
from study_config import load_layout


def first_moves_by_search(layout, pose, target, blocked):
    """Every first move of a shortest walk from ``pose`` to a pose facing ``target`` that never steps on
    ``blocked``: a forward search that carries each pose's first moves."""
    goal = distances_to(layout, target)
    if goal.get(pose) == 0:
        return ()
    layer: dict[Pose, set[Action]] = {pose: set()}
    seen = {pose}
    while layer:
        nxt: dict[Pose, set[Action]] = {}
        for here, firsts in layer.items():
            for d in DIRECTIONS:
                after = next_pose(layout, here, d)
                if after[0] == blocked or after in seen:
                    continue
                nxt.setdefault(after, set()).update(firsts or {move_action(d)})
        reached = {a for p, moves in nxt.items() if goal.get(p) == 0 for a in moves}
        if reached:
            return tuple(sorted(reached, key=lambda a: a.value))
        seen.update(nxt)
        layer = nxt
    return ()


@pytest.mark.parametrize("kitchen", ["mid_1", "none_3", "side_2"])
def test_detours_are_every_shortest_way_around_the_other_agent(kitchen):
    layout = load_layout(kitchen)
    rnd = random.Random(7)
    floor, targets = sorted(layout.floor), sorted(layout.stations)
    checked = 0
    for _ in range(400):
        cell, blocked = rnd.sample(floor, 2)
        pose, target = (cell, rnd.choice(DIRECTIONS)), rnd.choice(targets)
        expected = first_moves_by_search(layout, pose, target, blocked)
        assert detour_moves(layout, pose, target, blocked) == expected, (pose, target, blocked)
        checked += bool(expected)
    assert checked > 50


def test_a_detour_never_steps_on_the_blocked_cell():
    layout = load_layout("mid_1")
    for cell in sorted(layout.floor):
        for blocked in sorted(layout.floor):
            if blocked == cell:
                continue
            for move in detour_moves(layout, (cell, DIRECTIONS[0]), layout.grills[0], blocked):
                direction = next(d for d in DIRECTIONS if move_action(d) is move)
                assert next_pose(layout, (cell, DIRECTIONS[0]), direction)[0] != blocked
                assert move is not Action.STAY


def test_detours_agree_with_the_search_for_every_pose_and_blocked_cell_of_a_kitchen():
    layout = load_layout("practice")
    target = layout.boards[0]
    for cell in sorted(layout.floor):
        for blocked in sorted(layout.floor - {cell}):
            for facing in DIRECTIONS:
                pose = (cell, facing)
                assert detour_moves(layout, pose, target, blocked) == first_moves_by_search(
                    layout, pose, target, blocked), (pose, blocked)
