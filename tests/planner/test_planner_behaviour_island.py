"""Paper §VI-C / §VIII, "a longer path around an island to stay visible", in the Island kitchen (mid_2).

The human, on its way west along the top row to the onion dispenser, stands at (5, 1) facing west (it stays
there during the test); the robot, below the island, carries an onion the human has not seen it take (the
human's KB has it empty-handed), so the human may be fetching a second onion for a board the robot is about
to fill. Both ways around the island to the board are equally short. The FOV-aware robot goes around the
island's west end, where the human is looking, and steps a little further out of its way to be seen
long enough (``kb_delay`` ticks) for the human to acknowledge the onion; the baseline, which models an
omniscient human, takes a shortest way around the east end and puts the onion on the board unseen. Checked
for several planner seeds (the rollouts' random streams).

The default FOV-aware robot values nothing but the team's progress (docs/domain.md §5): it takes the west end on
every seed because its rollouts of the person, who knows the robot carries an onion, have them go for something
else than a second onion. The showing robot's hands walk plans on where its model expects the person to look next;
here that model has the person walk on west (they do not in this scene), so it takes the short way round the east
end on every seed.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
from steakhouse_onion_run import carry_onion_to_board

from planner.fov import visible_cells
from planner.geometry import Action, Direction
from planner.kb import initial_kb
from planner.objects import ONION
from planner.paths import distance
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.state import AgentState, initial_state
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("mid_2")
HUMAN = AgentState((5, 1), Direction.WEST)
ROBOT = AgentState((8, 6), Direction.NORTH)
BOARD = (6, 4)
ISLAND_WEST, ISLAND_EAST = 5, 9
ISLAND_ROWS = (4, 5)
SEEDS = range(5)


def situation():
    before = replace(initial_state(LAYOUT, RULES), human=HUMAN, robot=ROBOT)
    now = replace(before, robot=replace(ROBOT, held=ONION), tick=1)
    return before, now




def play_until_the_onion_is_on_the_board(name: str, seed: int, max_ticks: int = 25,
                                         config: PlannerConfig | None = None):
    """The robot's cells after each tick, its actions, and the tick at which the human's KB acknowledged
    the onion (None if never), the human standing still."""
    run = carry_onion_to_board(LAYOUT, RULES, name, seed, *situation(), max_ticks, config)
    return run.cells, run.actions, run.acknowledged


def steps_walked(cells) -> int:
    return sum(a != b for a, b in zip([ROBOT.pos, *cells], cells, strict=False))


def shortest_walk() -> int:
    """Cells walked on a shortest way to the board's front cell (6, 3): round either end of the island."""
    corner = (ISLAND_EAST + 1, BOARD[1] - 1)
    return abs(ROBOT.pos[0] - corner[0]) + abs(ROBOT.pos[1] - corner[1]) + abs(corner[0] - BOARD[0])


def passing_the_island(cells) -> list[int]:
    """The columns in which the robot passed the island's rows."""
    return [x for x, y in cells if y in ISLAND_ROWS]


def test_the_onion_is_out_of_view_and_both_ways_round_are_equally_short():
    _, now = situation()
    assert now.robot.pos not in visible_cells(LAYOUT, HUMAN.pos, HUMAN.facing, 120)
    known = initial_kb(situation()[0]).robot
    assert known is not None and known.held is None
    pose = (ROBOT.pos, ROBOT.facing)
    west = (ISLAND_WEST - 1, ROBOT.pos[1])
    east = (ISLAND_EAST + 1, ROBOT.pos[1])
    via_west = abs(ROBOT.pos[0] - west[0]) + distance(LAYOUT, (west, Direction.WEST), BOARD)
    via_east = abs(ROBOT.pos[0] - east[0]) + distance(LAYOUT, (east, Direction.EAST), BOARD)
    assert via_west == via_east == distance(LAYOUT, pose, BOARD)


def shown_on(config: PlannerConfig | None) -> int:
    """Seeds on which the FOV-aware robot went a longer way and the onion was acknowledged before it was put down."""
    shown = 0
    for seed in SEEDS:
        cells, actions, acknowledged = play_until_the_onion_is_on_the_board("fov_aware", seed, config=config)
        assert passing_the_island(cells) and actions[-1] is Action.INTERACT
        shown += steps_walked(cells) > shortest_walk() and acknowledged is not None and acknowledged < len(actions) - 1
    return shown


def test_fov_aware_robot_mostly_goes_a_longer_way_to_be_seen():
    assert shown_on(PlannerConfig()) >= len(SEEDS) - 1


@pytest.mark.parametrize("seed", SEEDS)
def test_baseline_goes_the_short_way_round_the_east_end_unseen(seed):
    cells, actions, acknowledged = play_until_the_onion_is_on_the_board("baseline", seed)
    columns = passing_the_island(cells)
    assert columns and all(x > ISLAND_EAST for x in columns)
    assert steps_walked(cells) == shortest_walk()
    assert acknowledged is None
    assert actions[-1] is Action.INTERACT
