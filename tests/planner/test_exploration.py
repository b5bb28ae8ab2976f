"""The FOV-aware robots' first move (:mod:`planner.exploration`; docs/domain.md §5 step 2), in the onion scene of
``test_planner_behaviour_onion.py``: the robot holds an onion the person has not seen. The default robot's candidates
(the direct move, the other first moves on a shortest path, the show plan) are each scored by the team's progress in
the same rollouts; without exploration the direct move is taken as it is."""

from __future__ import annotations

from dataclasses import replace

from planner.flicker import FlickerWatch
from planner.geometry import Action, Direction
from planner.kb import initial_kb
from planner.moment import Moment
from planner.objects import ONION
from planner.qmdp import QmdpRobot, make_qmdp_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("side_2")
LIKELY = ((Subtask.PICKUP_ONION, 0.5), (Subtask.PICKUP_PLATE, 0.5))


def scene(name: str, explores: bool = True) -> tuple[QmdpRobot, Moment]:
    before = replace(initial_state(LAYOUT, RULES), human=AgentState((9, 2), Direction.NORTH), grills=(0,),
                     robot=AgentState((6, 2), Direction.NORTH))
    now = replace(before, robot=AgentState((6, 2), Direction.NORTH, ONION), tick=1)
    robot = make_qmdp_robot(name, LAYOUT, RULES)
    robot.reset(before)
    m = Moment(now, initial_kb(before), LIKELY, 3, 42, 0, False, explores, None, FlickerWatch())
    return robot, m


def test_every_candidate_is_scored_by_the_teams_progress_and_the_best_is_taken():
    robot, m = scene("fov_aware")
    values = robot.valuation.options(m, (Subtask.DROP_ONION,))
    scored = []
    original = robot.valuation.sampled

    def spy(m, human_subtask, robot_subtask, prefix=(), knowing=False):
        value = original(m, human_subtask, robot_subtask, prefix, knowing)
        scored.append((prefix, knowing, value))
        return value

    robot.valuation.sampled = spy  # type: ignore[method-assign]
    action, explored = robot.exploration.first_move(m, Subtask.DROP_ONION, values)
    plans = list(dict.fromkeys(prefix for prefix, _, _ in scored))
    assert explored == len(plans) + 1 >= 2, "the direct move's score is the subtask's, the others rolled out"
    assert not any(knowing for _, knowing, _ in scored), "the default values nothing but progress"
    scores = {(): values.value[Subtask.DROP_ONION]}
    for plan in plans:
        runs = [v for prefix, _, v in scored if prefix == plan]
        scores[plan] = sum(p * v for v, (_, p) in zip(runs, LIKELY, strict=True))
    chosen = max(scores, key=lambda plan: (scores[plan], plan == ()))
    direct = robot.valuation.rollout(m).robot_move(m.world, Subtask.DROP_ONION)
    assert action is (chosen[0] if chosen else direct)


def test_without_exploration_the_direct_move_is_taken():
    robot, m = scene("fov_aware", explores=False)
    values = robot.valuation.options(m, (Subtask.DROP_ONION,))
    action, explored = robot.exploration.first_move(m, Subtask.DROP_ONION, values)
    assert explored == 0 and action is robot.valuation.rollout(m).robot_move(m.world, Subtask.DROP_ONION)


def test_the_showing_robot_scores_its_candidates_with_the_value_of_being_seen():
    robot, m = scene("fov_aware_showing")
    assert robot.walks is not None and robot.valuation.knowing
    values = robot.valuation.options(m, (Subtask.DROP_ONION,))
    assert values.known, "the knowing value is kept for the direct move"
    _, explored = robot.exploration.first_move(m, Subtask.DROP_ONION, values)
    assert explored >= 1
    assert Action.INTERACT not in {robot.exploration.first_move(m, Subtask.DROP_ONION, values)[0]}
