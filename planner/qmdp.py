"""The hierarchical QMDP robots (paper §IV–V; docs/domain.md §5): ``fov_aware``, ``fov_aware_showing``, ``baseline``,
``no_rollout``.

Each tick the robot

1. updates its model of the person (:class:`planner.person_model.PersonModel`: the modelled KB with the person's
   angle and delay, the baseline's person seeing everything, and the belief over the person's subtask), its watch of
   its own last touch (:mod:`planner.flicker`) and its standoff and cycle watches;
2. builds the decision's one frozen :class:`planner.moment.Moment`;
3. gives way when the person is in its way (:mod:`planner.giving_way`), or values every subtask it could take by
   rollouts of the team's progress (:mod:`planner.valuation`) and takes the best;
4. explores first moves toward it for how they change what the person knows (:mod:`planner.exploration`; the
   FOV-aware robots only), the default robot by the team's progress alone, the showing robot also for being seen;
5. never undoes its own last touch of a counter while nothing else has changed (:mod:`planner.flicker`): an
   interact that would is replaced by the way to another target of the subtask, or by the next best subtask.

The robots differ only in their model of the person and what they explore: ``fov_aware`` models the study's view
and delay and explores; ``fov_aware_showing`` is the same plus the value of being seen and the dish and hands walks
(:mod:`planner.showing_walks`); ``baseline`` models a person who sees everything; ``no_rollout`` models the study's
person but explores nothing (the reference's "aware-not-act"). Randomness: each decision draws one rollout seed
from the ``rng`` it is handed (the trial's stream: same trial seed, same decisions); a ``deadline``
(``time.perf_counter()``) stops the valuation and the exploration with the best found so far (``timed_out``).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from planner.belief import Belief
from planner.cycle import watch, without_avoided
from planner.decision import Decision
from planner.events import Event, EventKind
from planner.exploration import Exploration
from planner.flicker import FlickerWatch, undoes
from planner.geometry import Action
from planner.giving_way import GivingWay, Stance
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.moment import TICKS_PER_SUBTASK, Moment
from planner.person_model import PersonModel
from planner.planner_config import PlannerConfig
from planner.rollout import RobotTasker, potential
from planner.rules import Rules
from planner.show_plan import ShowPlan
from planner.showing_walks import ShowingWalks
from planner.standoff import advance, out_of_the_way, unaided
from planner.state import WorldState
from planner.subtasks import NOTHING_NEEDED, Subtask
from planner.valuation import Valuation


class QmdpRobot:
    """One robot of the module docstring: what it keeps from tick to tick (``person``, ``stance``, ``touches``, the show
    plan it follows, the showing robot's dish trip and leg) and the parts its decision is made of (``valuation``,
    ``exploration``, ``giving_way``). ``explore``: it explores first moves; ``showing``: it is the showing robot."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig, explore: bool,
                 showing: bool = False) -> None:
        self.layout, self.rules, self.cfg, self.explore = layout, rules, config, explore
        self.tasker = RobotTasker(layout, rules)
        self.person = PersonModel(layout, rules, config)
        self.valuation = self.make_valuation(showing)
        walk = config.view_detour if showing else config.exploration_depth
        self.show = ShowPlan(layout, config.human_angle, config.human_delay, walk + max(config.human_delay - 1, 0))
        self.walks = ShowingWalks(layout, rules, config, self.valuation.team) if showing else None
        self.exploration = Exploration(layout, self.tasker, self.valuation, self.show, self.walks)
        self.giving_way = GivingWay(layout, rules, config, self.tasker, self.valuation.team)
        self.stance = Stance()
        self.touches = FlickerWatch()
        self.world_before: WorldState | None = None
        self.held_before: str | None = None

    def make_valuation(self, showing: bool) -> Valuation:
        """The robot's valuation (a diagnostic robot may value otherwise, ``benchmarks/planner/clairvoyant.py``)."""
        return Valuation(self.layout, self.rules, self.cfg, knowing=showing and self.cfg.shown_value > 0)

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        """Start on ``world`` (:meth:`planner.decision.Robot.reset`): the model of the person's KB is ``kb`` (a resumed
        trial's restored KB) or :func:`planner.kb.initial_kb`."""
        self.person.reset(world, kb)
        self.show.reset()
        if self.walks is not None:
            self.walks.reset()
        self.valuation.averages.reset()
        self.stance = Stance()
        self.touches = FlickerWatch()
        self.world_before = None
        self.held_before = world.robot.held

    @property
    def kb(self) -> KnowledgeBase | None:
        """The person's KB as the robot models it."""
        return self.person.kb

    @property
    def belief(self) -> Belief | None:
        """The robot's belief over the person's subtask."""
        return self.person.belief

    def observe(self, world: WorldState, events: Sequence[Event]) -> None:
        """Take in the world after a step: the person, the robot's last touch, its standoff and cycle watches, and
        whether its subtask is done or gone."""
        if self.person.kb is None:
            self.reset(world)
        moved = self.person.observe(world, events)
        if self.world_before is not None and self.world_before.tick != world.tick:
            self.touches = self.touches.observe(self.world_before, events, self.rules)
        stance, robot_before = self.stance, self.world_before.robot if self.world_before is not None else None
        target = self.tasker.targets(stance.current, world) if stance.current is not None else ()
        phi = potential(world, self.cfg)
        standoff = advance(stance.standoff, self.layout, robot_before, world, target, moved, phi)
        robot_moved = (robot_before is not None and robot_before != world.robot) or any(
            e.agent == "robot" and e.kind is EventKind.BLOCKED for e in events)
        cycle = watch(stance.cycle, world, phi, self.cfg.cycle_window, robot_moved)
        current = stance.current
        judged = unaided(world) if standoff.stalled(self.cfg.stall_ticks) or self.person.alone else world
        if current is not None and (self.tasker.done(current, self.held_before, world)
                                    or current not in self.tasker.options(judged, current)):
            current = None
        self.stance = Stance(current, standoff, cycle)
        self.world_before = world
        self.held_before = world.robot.held
        if self.walks is not None:
            self.walks.observe(world)

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        decision = self.choose(world, events, rng, deadline)
        if decision.action is Action.INTERACT and undoes(self.touches, self.layout, world, self.rules):
            decision = replace(decision, action=Action.STAY)  # never reached by the planner's own paths
        return replace(decision, elapsed_ms=(time.perf_counter() - start) * 1000)

    def choose(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None) -> Decision:
        self.observe(world, events)
        belief, kb = self.person.belief, self.person.kb
        assert belief is not None and kb is not None
        self.valuation.averages.restart_on((world.robot.held, world.orders_left))
        likely = belief.likely(self.cfg.belief_threshold, self.cfg.max_subtasks)
        seed = int(rng.integers(2**31))
        person_task = belief.likely(0.0, 1)[0][0]
        cycles = self.stance.cycle.broken
        yielded, self.stance = self.giving_way.break_cycle(world, self.stance, person_task)
        if yielded is not None:
            if self.stance.cycle.broken > cycles:
                self.show.reset()
            return Decision(action=yielded, belief=belief.as_dict(), cycle_broken=self.stance.cycle.broken > cycles)
        alone = self.person.alone
        if alone:  # planner.alone: plan for one agent beside a person who stays where they stand
            world, likely = unaided(world), ((likely[0][0], 1.0),)
        m = Moment(world, kb, likely, seed, self.cfg.search_depth * TICKS_PER_SUBTASK, self.person.human_still,
                   alone, self.explore and self.cfg.exploration_depth > 0 and not alone, self.stance.current,
                   self.touches, deadline)
        followed = self.show.follow(world, kb)
        if followed is not None:
            return Decision(action=followed, belief=belief.as_dict())
        self.show.reset()
        if self.walks is not None:
            self.walks.begin_trip(world, self.walks.at_ready_garnish(world))
        around, self.stance = self.giving_way.around_standoff(m, self.stance, person_task,
                                                              self.tasker.options(world, self.stance.current))
        if isinstance(around, Action):
            return Decision(action=around, belief=belief.as_dict())
        options = without_avoided(around, self.stance.cycle, world.tick)
        if world.robot.held is None and options == NOTHING_NEEDED:  # planner.subtasks.beyond_orders
            return self.idle(m, person_task, belief)
        values = self.valuation.options(m, options)
        for best in values.ranked(options, m.current):
            action, explored = self.exploration.first_move(m, best, values)
            action = self.giving_way.yield_if_blocking(m, best, action)
            if action is Action.INTERACT and undoes(self.touches, self.layout, world, self.rules):
                other = self.elsewhere(m, best)
                if other is None:
                    continue
                action = other
            self.stance = replace(self.stance, current=best)
            return Decision(action=action, q_values={r.value: v for r, v in values.q.items()},
                            belief=belief.as_dict(), explored_kbs=explored, timed_out=values.timed_out)
        return self.idle(m, person_task, belief)

    def idle(self, m: Moment, person_task: Subtask, belief: Belief) -> Decision:
        """Nothing to do (:data:`planner.subtasks.NOTHING_NEEDED`, or every option would undo the last touch): stay,
        or step out of the person's way."""
        self.stance = replace(self.stance, current=None)
        action = out_of_the_way(self.layout, m.world, self.giving_way.person_cells(m.world, person_task),
                                m.human_still >= 1)
        return Decision(action=action, belief=belief.as_dict())

    def elsewhere(self, m: Moment, subtask: Subtask) -> Action | None:
        """The way toward ``subtask``'s targets other than the counter the robot faces, whose interact would undo its
        last touch (:mod:`planner.flicker`); ``None`` when the subtask has no other target."""
        world = m.world
        faced = world.robot.facing.ahead(world.robot.pos)
        others = tuple(c for c in self.tasker.targets(subtask, world) if c != faced)
        return self.valuation.rollout(m).move_to(world, others, m.parked) if others else None


def make_qmdp_robot(name: str, layout: Layout, rules: Rules, config: PlannerConfig | None = None) -> QmdpRobot:
    cfg = config or PlannerConfig()
    if name == "baseline":
        return QmdpRobot(layout, rules, cfg.omniscient_human(), explore=False)
    if name == "no_rollout":
        return QmdpRobot(layout, rules, replace(cfg, exploration_depth=0), explore=False)
    if name == "fov_aware":
        return QmdpRobot(layout, rules, cfg, explore=True)
    if name == "fov_aware_showing":
        return QmdpRobot(layout, rules, cfg, explore=True, showing=True)
    raise ValueError(f"unknown QMDP robot {name!r}")
