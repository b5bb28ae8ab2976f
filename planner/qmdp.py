"""The hierarchical QMDP robot (paper §IV–V; docs/domain.md §5): ``fov_aware``, ``baseline``, ``no_rollout``.

Each tick the robot

1. updates its model of the human's KB with the FOV rules (:func:`planner.kb.update_kb`, the human's
   angle and delay; the baseline models an omniscient human: 360°, delay 0) and its belief over the human's
   subtask (:mod:`planner.belief`);
2. for every subtask the robot could take and every likely human subtask ``s`` (belief ≥ threshold),
   simulates the joint system forward (:class:`planner.rollout.Rollout`) with the human choosing from its
   modelled KB, and scores the shaping-potential progress;
3. combines them QMDP-style, ``Q(b, r) = Σ_s b(s) V(r, s)``, averages each ``Q(b, r)`` with its value at
   the previous ticks (``value_smoothing``: an exponential average, restarted when the robot's held object
   or the orders left change — one seeded rollout per hypothesis is noisy, and a robot that flips between
   subtasks on noise can leave the human stuck), adds a small bonus for keeping its current subtask, and
   takes ``r* = argmax Q``;
4. **exploration** (FOV-aware only, depth ``k``): it rolls out, besides the direct move toward ``r*``
   (whose score is the one already computed for ``Q``), every other first move on a shortest path and,
   when the modelled KB does not know what the robot holds, a *show plan*: the cheapest walk toward ``r*``
   after which the robot has stood ``kb_delay`` consecutive ticks in the human's current view, through the
   view on the way when it can, else into it and waiting there (:func:`planner.view_route.show_walk`; it
   replaces the plain candidate with the same first move, scoring both measured worse; the robot follows it
   while the human neither moves nor turns); it keeps the one whose value, the rollout's progress plus what
   the person comes to know (docs/domain.md §5, "The person's knowing"), is highest (ties: the direct move).
   This produces the staircase paths that stay in the FOV and the robot walking alongside the human to show
   what it carries (paper §VI-C). With a dish, or with a plated steak at a ready garnish, it instead plans the
   dish walk on the person's predicted poses (:meth:`QmdpRobot.dish_walk`, :mod:`planner.dish_walk`): the way
   to the serving counter, waits included, whose trip the person is expected to see most, within the trip's
   detour. By default (``hands_walk``), while the modelled KB is wrong about what the robot holds, the hands walk
   (:meth:`QmdpRobot.hands_walk`, :mod:`planner.hands_walk`) replaces the show plan: the way to ``r*``'s station,
   waits included, on which the person is expected to acknowledge the robot's hands soonest, on the same
   predicted poses, within the leg's detour; with ``walk_rollout`` (off by default) a move of it off the direct
   way is taken only when the rollouts that play it score higher than the direct move's
   (:meth:`QmdpRobot.walk_or_direct`). The no-rollout robot (depth 0) and the baseline take the direct move.

The lookahead horizon is ``search_depth`` subtasks × 6 ticks (default 7: 42 ticks).
``PlannerConfig(lookahead="abstract")`` replaces steps 2–4 by docs/domain.md §5 as the reference planned
(:mod:`planner.reference`: Q per low-level action from motion-sequence exploration and a heuristic search
over abstract states). Measured on all kitchens × seeds 0–9 it is far worse (FOV-aware 146.8 ticks, 8 of
100 trials unfinished; baseline 135.4, 3 unfinished; no significant difference) and needs up to ~300 ms
per decision, so the rollouts are the default: they keep the human's FOV-limited KB for the whole
lookahead, where the abstraction drops it after ``k + 1`` ticks. Randomness: each decision draws one
rollout seed from the ``rng`` it is handed (the trial's stream: same trial seed, same decisions; another
seed, other rollouts) and every candidate of that tick uses it (common random numbers across candidates). A
``deadline`` (``time.perf_counter()`` value) stops the search and returns the best action so far (``timed_out``).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from planner.alone import solo_rollout
from planner.belief import Belief
from planner.cycle import CycleWatch, broken, watch, without_avoided
from planner.decision import Decision
from planner.dish_walk import Future, dish_walk
from planner.events import Event, EventKind
from planner.geometry import DIRECTIONS, Action, Pos, manhattan, move_action
from planner.hands_walk import hands_walk
from planner.human import HumanMemory
from planner.kb import KnowledgeBase, omniscient_kb
from planner.layout import Layout
from planner.objects import DISH, STEAK_PLATE
from planner.paths import UNREACHABLE, best_moves, distance, nearest_distances
from planner.person_model import PersonModel
from planner.planner_config import PlannerConfig
from planner.reference import ReferenceLookahead
from planner.reuse import Trace, follow, traced
from planner.rollout import RobotTasker, Rollout, potential
from planner.rules import Rules
from planner.showing import Showing
from planner.smoothing import ValueAverages
from planner.standoff import (
    Standoff,
    advance,
    alternatives,
    arrive,
    beside,
    committed,
    give_up,
    hold_aside,
    in_the_way,
    out_of_the_way,
    step_aside,
    take_over,
    unaided,
    visit_done,
    within_reach,
)
from planner.state import AgentState, WorldState
from planner.subtasks import NOTHING_NEEDED, Subtask, targets

TICKS_PER_SUBTASK = 6


class QmdpRobot:
    """One robot of the module docstring. Its parts, one job each: ``person`` (:class:`planner.person_model.
    PersonModel`: the modelled KB, the belief over the person's subtask, how long the person has stood still),
    ``showing`` (:class:`planner.showing.Showing`: the show plan being followed, the dish trip, this decision's
    value of the person's knowing), ``values`` (:class:`planner.smoothing.ValueAverages`: the running averages of
    the subtask values), the rollouts (``team_rollout``, ``solo_rollout`` beside a person who has stopped, the kept
    ``traces`` of :mod:`planner.reuse`), and the robot's own progress (``current`` subtask, ``standoff``,
    ``cycle``). The robot itself makes the choice: :meth:`decide`."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig, explore: bool) -> None:
        self.layout, self.rules, self.cfg, self.explore = layout, rules, config, explore
        self.rollout = self.team_rollout = Rollout(layout, rules, config)
        self.solo_rollout = solo_rollout(layout, rules, config)
        showing_hands = replace(config, shown_empty=config.shown_value)  # a load and empty hands alike
        self.walk_judges = ((Rollout(layout, rules, showing_hands), solo_rollout(layout, rules, showing_hands))
                            if config.walk_rollout else None)
        self.reference = ReferenceLookahead(layout, rules, config) if config.lookahead == "abstract" else None
        self.tasker = RobotTasker(layout, rules)
        self.person = PersonModel(layout, rules, config)
        self.showing = Showing(layout, config)
        self.values = ValueAverages(config.value_smoothing)
        self.current: Subtask | None = None
        self.held_before: str | None = None
        self.cycle = CycleWatch()
        self.standoff = Standoff()
        self.robot_before: AgentState | None = None
        self.traces: dict[tuple[Subtask, Subtask], Trace] = {}
        self.next_traces: dict[tuple[Subtask, Subtask], Trace] = {}
        self.followed: dict[tuple[Subtask, Subtask], Trace] = {}

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        """Start on ``world`` (:meth:`planner.decision.Robot.reset`): the model of the person's KB is ``kb``
        (a resumed trial's restored KB) or, at a trial's start or for a model that sees everything at once
        (the baseline's: its KB is the world), :func:`initial_kb`."""
        self.person.reset(world, kb)
        self.showing.reset()
        self.values.reset()
        self.current = None
        self.held_before = world.robot.held
        self.cycle = CycleWatch()
        self.standoff = Standoff()
        self.robot_before = None
        self.traces, self.next_traces = {}, {}

    @property
    def kb(self) -> KnowledgeBase | None:
        """The person's KB as the robot models it (:class:`planner.person_model.PersonModel`)."""
        return self.person.kb

    @property
    def belief(self) -> Belief | None:
        """The robot's belief over the person's subtask (:class:`planner.person_model.PersonModel`)."""
        return self.person.belief

    @property
    def human_still(self) -> int:
        """Ticks the person has stood in one cell (:class:`planner.person_model.PersonModel`)."""
        return self.person.human_still

    @property
    def pending(self) -> tuple[Action, ...]:
        """The rest of the show plan the robot follows (:class:`planner.showing.Showing`)."""
        return self.showing.pending

    def observe(self, world: WorldState, events: Sequence[Event]) -> None:
        if self.person.kb is None:
            self.reset(world)
        moved = self.person.observe(world, events)
        target = self.tasker.targets(self.current, world) if self.current is not None else ()
        phi = potential(world, self.cfg)
        self.standoff = advance(self.standoff, self.layout, self.robot_before, world, target, moved, phi)
        robot_moved = (self.robot_before is not None and self.robot_before != world.robot) or any(
            e.agent == "robot" and e.kind is EventKind.BLOCKED for e in events)
        self.cycle = watch(self.cycle, world, phi, self.cfg.cycle_window, robot_moved)
        self.robot_before = world.robot
        judged = unaided(world) if self.standoff.stalled(self.cfg.stall_ticks) or self.alone else world
        if self.current is not None and (self.tasker.done(self.current, self.held_before, world)
                                         or self.current not in self.tasker.options(judged, self.current)):
            self.current = None
        self.held_before = world.robot.held
        self.showing.observe(world)

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        self.observe(world, events)
        assert self.kb is not None and self.belief is not None
        self.values.restart_on((world.robot.held, world.orders_left))
        likely = self.belief.likely(self.cfg.belief_threshold, self.cfg.max_subtasks)
        seed = int(rng.integers(2**31))
        cycles = self.cycle.broken
        yielded = self.break_cycle(world)
        if yielded is not None:
            return Decision(action=yielded, belief=self.belief.as_dict(), cycle_broken=self.cycle.broken > cycles,
                            elapsed_ms=(time.perf_counter() - start) * 1000)
        self.rollout = self.solo_rollout if self.alone else self.team_rollout
        if self.alone:  # planner.alone: plan for one agent beside a person who stays where they stand
            world, likely = unaided(world), ((likely[0][0], 1.0),)
        if self.reference is not None:
            by_action, explored, cut = self.reference.q_values(world, self.kb, likely, seed, deadline)
            return Decision(action=max(by_action, key=lambda a: by_action[a]),
                            q_values={a.value: v for a, v in by_action.items()}, belief=self.belief.as_dict(),
                            explored_kbs=explored, elapsed_ms=(time.perf_counter() - start) * 1000,
                            timed_out=cut)
        followed = self.showing.follow(world, self.kb)
        if followed is not None:
            return Decision(action=followed, belief=self.belief.as_dict(),
                            elapsed_ms=(time.perf_counter() - start) * 1000)
        self.showing.start(world, self.at_ready_garnish(world))
        self.traces, self.next_traces = self.next_traces, {}
        options = self.tasker.options(world, self.current)
        around = self.around_standoff(world, options)
        if isinstance(around, Action):
            return Decision(action=around, belief=self.belief.as_dict(),
                            elapsed_ms=(time.perf_counter() - start) * 1000)
        options = without_avoided(around, self.cycle, world.tick)
        if world.robot.held is None and options == NOTHING_NEEDED:  # planner.subtasks.beyond_orders
            self.current = None
            action = out_of_the_way(self.layout, world, self.human_targets(world), self.human_still >= 1)
            if action is Action.STAY and self.shows_itself and self.cfg.shown_empty:
                # Nothing to do: show the person the empty hands their KB does not know of (no tick lost).
                action = next(iter(self.showing.show_plan(world, self.kb, ())), Action.STAY)
            return Decision(action=action, belief=self.belief.as_dict(),
                            elapsed_ms=(time.perf_counter() - start) * 1000)
        horizon = self.plan_horizon(world, options, likely)
        q: dict[Subtask, float] = {}
        values: dict[Subtask, float] = {}
        timed_out = False
        for r in options:
            if deadline is not None and q and time.perf_counter() > deadline:
                timed_out = True
                break
            values[r] = sum(p * self.sampled(world, s, r, horizon, seed) for s, p in likely)
            q[r] = self.cfg.gamma * self.values.fold(r, values[r]) + (
                self.cfg.commitment_bonus if r is self.current else 0.0)
        best = max(q, key=lambda r: (q[r], r is self.current, -options.index(r)))
        self.current = best
        action, explored = self.first_move(world, best, likely, horizon, seed, deadline, values[best])
        action = self.yield_if_blocking(world, best, action)
        return Decision(action=action, q_values={r.value: v for r, v in q.items()},
                        belief=self.belief.as_dict(), explored_kbs=explored,
                        elapsed_ms=(time.perf_counter() - start) * 1000, timed_out=timed_out)

    @property
    def alone(self) -> bool:
        """Whether the person has stopped (:mod:`planner.alone`): the robot plans as if it were alone."""
        return self.person.alone

    @property
    def shows_itself(self) -> bool:
        """Whether this decision explores first moves for what the person would come to know of the robot: the
        FOV-aware robot, except beside a person who has stopped (:mod:`planner.alone`), whom nothing is shown."""
        return self.explore and self.cfg.exploration_depth > 0 and not self.alone

    def human_targets(self, world: WorldState) -> tuple[Pos, ...]:
        """The cells of the person's most likely subtask."""
        assert self.belief is not None
        return targets(self.layout, self.belief.likely(0.0, 1)[0][0], world, self.rules)

    def break_cycle(self, world: WorldState) -> Action | None:
        """:mod:`planner.cycle`: in a joint cycle the robot yields (steps aside off the person's way, then holds
        still ``cycle_hold`` ticks); ``None`` when it plans as usual."""
        if world.tick < self.cycle.hold_until:
            return Action.STAY
        if not self.cycle.cycling(self.cfg.cycle_returns):
            return None
        assert self.belief is not None
        human_cells = self.human_targets(world)
        self.cycle = broken(self.cycle, self.current, world.tick, self.cfg.cycle_hold)
        self.current = None
        self.showing.pending = ()
        return step_aside(self.layout, world, human_cells)

    def plan_horizon(self, world: WorldState, options: tuple[Subtask, ...],
                     likely: tuple[tuple[Subtask, float], ...]) -> int:
        """This decision's lookahead in ticks: ``search_depth`` subtasks, shortened for every rollout alike when
        the new rollouts it needs would pass ``rollout_budget`` simulated ticks. Also follows last tick's
        rollouts (:func:`planner.reuse.follow`) into ``self.followed``."""
        full = self.cfg.search_depth * TICKS_PER_SUBTASK
        self.followed = {}
        assert self.kb is not None
        if self.cfg.reuse_rollouts and self.cfg.rollout_samples <= 1:
            for key, kept in self.traces.items():
                if key[0] in options and any(key[1] is s for s, _ in likely):
                    trace = follow(self.rollout, kept, world, self.kb, key[1], key[0], self.human_still)
                    if trace is not None:
                        self.followed[key] = trace
        budget = self.cfg.rollout_budget
        if budget <= 0:
            return full
        kept_full = sum(1 for t in self.followed.values() if t.length >= full)
        explore = (2 * len(likely)) if self.shows_itself else 0
        fresh = (len(options) * len(likely) - kept_full) * max(self.cfg.rollout_samples, 1) + explore
        if fresh * full <= budget:
            return full
        return max(budget // fresh, TICKS_PER_SUBTASK)

    def around_standoff(self, world: WorldState, options: tuple[Subtask, ...]) -> tuple[Subtask, ...] | Action:
        """:mod:`planner.standoff`: after ``standoff_ticks`` without progress behind the person, the person's
        stalled work (taken over: the move toward it), else a step aside when the robot is in the person's
        way, else the other reachable options, else a step aside (the action). A person who has not moved for
        ``visit_ticks`` is then visited (:meth:`visit_still_person`). While a given-up subtask is avoided the
        options are the reachable others (:func:`planner.standoff.alternatives`); when there are none the robot
        holds its place (stays) until the person moves. In a team stall (no progress for ``stall_ticks``) the
        options are judged without the person's load and the robot keeps its subtask
        (:func:`planner.standoff.committed`), moving toward the targets it can reach without passing the
        person when some cannot be (the move)."""
        assert self.belief is not None
        cells = self.tasker.targets
        if self.standoff.stuck >= self.cfg.standoff_ticks:
            given_up = self.current
            self.standoff = give_up(self.standoff, given_up, world.tick, self.cfg.standoff_ticks)
            choices = alternatives(self.layout, world, options, given_up, cells)
            human_task = self.belief.likely(0.0, 1)[0][0]
            taken = take_over(human_task, choices) if self.human_still >= self.cfg.standoff_ticks else None
            if taken is not None:
                self.current = taken
                return self.rollout.robot_move(world, taken, True)
            human_cells = self.human_targets(world)
            if not choices or in_the_way(self.layout, world, human_cells):
                self.current = None
                self.standoff = hold_aside(self.standoff, world.tick, self.cfg.standoff_ticks)
                return step_aside(self.layout, world, human_cells)
            return choices
        if world.tick < self.standoff.hold_until:
            return Action.STAY
        visit = self.visit_still_person(world)
        if visit is not None:
            return visit
        if self.standoff.stalled(self.cfg.stall_ticks):
            options = committed(self.tasker.options(unaided(world), self.current), self.current)
            if options == (self.current,):
                targets = self.tasker.targets(options[0], world)
                clear = within_reach(self.layout, world, targets)
                if clear and clear != targets:
                    return self.rollout.move_to(world, clear, self.human_still >= 2)
        avoided = self.standoff.avoided(world.tick)
        if avoided is None or avoided not in options:
            return options
        rest = alternatives(self.layout, world, options, avoided, cells)
        return rest if rest else Action.STAY

    def visit_still_person(self, world: WorldState) -> Action | None:
        """:mod:`planner.standoff`, still person: once the person has stood in one cell for ``visit_ticks``
        ticks, the robot walks to a cell beside it (around it) and holds there ``standoff_ticks`` ticks, once
        until the person moves again; ``None`` when no visit is under way."""
        if self.human_still < self.cfg.visit_ticks or self.standoff.visited:
            return None
        if beside(world):
            self.standoff = arrive(self.standoff, world.tick, self.cfg.standoff_ticks)
            if world.tick < self.standoff.beside_until:
                return Action.STAY
            self.standoff = visit_done(self.standoff)
            return None
        move = self.rollout.move_to(world, (world.human.pos,), True)
        if move in (Action.STAY, Action.INTERACT):
            self.standoff = visit_done(self.standoff)
            return None
        return move

    def first_move(self, world: WorldState, subtask: Subtask, likely: tuple[tuple[Subtask, float], ...], horizon: int,
                   seed: int, deadline: float | None, direct_value: float) -> tuple[Action, int]:
        """Exploration: the direct first move toward ``subtask`` against the first moves of plans that
        show the robot to the human first (every first move on a shortest path, and the way into the
        human's view held for ``kb_delay`` ticks), each scored by a rollout that tracks the modelled KB; with a dish
        on its way (or a plated steak at a ready garnish), the first action of the dish walk instead
        (:meth:`dish_walk`). ``direct_value`` is the direct move's score, already computed for ``Q`` (same
        rollouts, same seeds)."""
        default = self.rollout.robot_move(world, subtask, self.human_still >= 2)
        if not self.shows_itself:
            return default, 0
        garnish = default is Action.INTERACT and subtask is Subtask.PICKUP_GARNISH and self.at_ready_garnish(world)
        if garnish or (world.robot.held == DISH and subtask is Subtask.DELIVER_DISH and default is not Action.STAY):
            plan = self.dish_walk(world, subtask, likely, seed, garnish)
            if plan:
                return plan[0], len(likely)
        if default is Action.INTERACT:
            return default, 0
        cells = self.tasker.targets(subtask, world)
        assert self.kb is not None
        if self.cfg.hands_walk and self.kb.robot is not None and self.kb.robot.held != world.robot.held:
            walk = self.hands_walk(world, subtask, likely, seed, cells)
            if walk:
                return self.walk_or_direct(world, subtask, likely, horizon, seed, deadline, walk, default)
        candidates: dict[Action, tuple[Action, ...]] = {default: ()}
        pose = (world.robot.pos, world.robot.facing)
        if cells:
            nearest = min(cells, key=lambda c: distance(self.layout, pose, c))
            for move in best_moves(self.layout, pose, nearest, world.human.pos):
                candidates.setdefault(move, ())
        show = self.showing.show_plan(world, self.kb, cells)
        if show:
            candidates[show[0]] = show[1:]
        plans = list(candidates.items())
        if len(plans) < 2:
            return default, 0
        scored: list[tuple[float, bool, int]] = []
        for i, (move, rest) in enumerate(plans):
            if deadline is not None and scored and time.perf_counter() > deadline:
                break
            if move is default and not rest:
                v = direct_value + sum(p * self.showing.known.get((subtask, s), 0.0) for s, p in likely)
            else:
                plan = (move,) + rest
                v = sum(p * self.sampled(world, s, subtask, horizon, seed, plan, self.cfg.values_knowing)
                        for s, p in likely)
            scored.append((v, move is default and not rest, i))
        move, rest = plans[max(scored, key=lambda t: (t[0], t[1]))[2]]
        self.showing.keep(rest, world)
        return move, len(scored)

    def walk_or_direct(self, world: WorldState, subtask: Subtask, likely: tuple[tuple[Subtask, float], ...],
                       horizon: int, seed: int, deadline: float | None, walk: tuple[Action, ...],
                       default: Action) -> tuple[Action, int]:
        """The hands walk's first move, or the direct move when the walk turns off the direct way and its rollouts
        are worth less (``walk_rollout``; docs/domain.md §5, "The person's knowing"). The hands walk prices an extra
        tick at ``hands_price`` ticks of the person's KB being wrong, blind to what the robot's delay does to the
        team; so, like the other candidates of the exploration, the walk and the direct move are scored by rollouts
        on the same seeds, the walk as their prefix: the team's progress plus ``shown_value`` at the tick the
        modelled KB acknowledges the robot's hands, a load or empty hands alike (the hands walk shows both), under
        the hands walk's hypotheses of the person (:meth:`kept_pose`: the likely subtasks, and a person who has
        stood still keeping their pose, :func:`planner.alone.solo_rollout`). Ties keep the direct move; a passed
        ``deadline`` the walk (as without ``walk_rollout``). Also answers the candidates explored."""
        if walk[0] is default or not self.cfg.walk_rollout or (deadline is not None and time.perf_counter() > deadline):
            return walk[0], len(likely)
        assert self.kb is not None and self.walk_judges is not None
        team, still = self.walk_judges
        kept = self.kept_weight()
        hypotheses = [(team, s, p * (1 - kept)) for s, p in likely] + ([(still, likely[0][0], kept)] if kept else [])
        direct, shown = (sum(p * judge.value(world, self.kb, s, subtask, horizon, seed, plan, self.human_still, True)
                             for judge, s, p in hypotheses) for plan in ((), walk))
        return (walk[0] if shown > direct else default), 2 * len(hypotheses)

    def sampled(self, world: WorldState, human_subtask: Subtask, robot_subtask: Subtask, horizon: int,
                seed: int, prefix: tuple[Action, ...] = (), knowing: bool = False) -> float:
        """The mean rollout value over ``rollout_samples`` seeded futures (the same seeds for every
        candidate, so candidates are compared on common random numbers); ``knowing`` adds the value of the
        person's knowing (:meth:`planner.rollout.Rollout.knowing`)."""
        assert self.kb is not None
        n = max(self.cfg.rollout_samples, 1)
        if not prefix and not knowing and n == 1 and self.cfg.reuse_rollouts:
            key = (robot_subtask, human_subtask)
            trace = self.followed.get(key)
            if trace is None or trace.length < horizon:
                trace = traced(self.rollout, world, self.kb, human_subtask, robot_subtask, horizon, seed,
                               self.human_still)
            self.next_traces[key] = trace
            return trace.value(self.cfg.tick_discount, horizon)
        if not prefix and self.shows_itself and self.cfg.values_knowing:
            # The subtask's value is the progress alone; the same rollouts' knowing is kept for its first move.
            sums = [self.rollout.parts(world, self.kb, HumanMemory(subtask=human_subtask, held=world.human.held),
                                       np.random.default_rng(seed + 7919 * i), robot_subtask, horizon,
                                       parked_for=self.human_still, knowing=True)
                    for i in range(n)]
            self.showing.known[(robot_subtask, human_subtask)] = sum(k for _, k in sums) / n
            return sum(v for v, _ in sums) / n
        return sum(self.rollout.value(world, self.kb, human_subtask, robot_subtask, horizon, seed + 7919 * i,
                                      prefix=prefix, parked_for=self.human_still, knowing=knowing)
                   for i in range(n)) / n

    def yield_if_blocking(self, world: WorldState, subtask: Subtask, action: Action) -> Action:
        """The human model's yield rule for the robot: waiting at a station (steak not ready, garnish not
        chopped) next to a human that has not moved for two ticks, it steps aside (the first free move
        away from the human)."""
        if action is not Action.INTERACT or not self.rollout.robot_model.waiting(subtask, omniscient_kb(world)):
            return action
        if self.human_still < 2 or manhattan(world.robot.pos, world.human.pos) != 1:
            return action
        for d in sorted(DIRECTIONS, key=lambda d: -manhattan(d.ahead(world.robot.pos), world.human.pos)):
            target = d.ahead(world.robot.pos)
            if target in self.layout.floor and target != world.human.pos:
                return move_action(d)
        return action

    def at_ready_garnish(self, world: WorldState) -> bool:
        """The robot holds a plated steak and faces a board with a chopped garnish: an interact makes the dish."""
        if world.robot.held != STEAK_PLATE:
            return False
        faced = world.robot.facing.ahead(world.robot.pos)
        return any(cell == faced and self.rules.chopped(status)
                   for cell, status in zip(self.layout.boards, world.boards, strict=True))

    def dish_walk(self, world: WorldState, subtask: Subtask, likely: tuple[tuple[Subtask, float], ...],
                  seed: int, garnish: bool) -> tuple[Action, ...]:
        """Behaviour 2's plan for the dish (:func:`planner.dish_walk.dish_walk`; ``garnish``: the robot stands with a
        plated steak at a ready garnish): the person's poses are predicted tick by tick, one rollout per likely
        subtask of theirs (:meth:`predicted_worlds`, the robot going on with ``subtask``), within what is left of
        the trip's detour. Planned anew every tick."""
        budget = self.showing.walk_budget(world, garnish)
        pose = (world.robot.pos, world.robot.facing)
        shortest = nearest_distances(self.layout, self.layout.serves).get(pose, UNREACHABLE)
        if shortest >= UNREACHABLE:
            return ()
        ticks = shortest + budget + 2  # as far ahead as the walk's programme looks (the garnish's interact too)
        futures = self.person_futures(world, subtask, likely, seed, ticks)
        return dish_walk(self.layout, self.cfg.human_angle, pose, futures, budget, self.cfg.walk_price, garnish,
                         self.showing.trip_seen)

    def hands_walk(self, world: WorldState, subtask: Subtask, likely: tuple[tuple[Subtask, float], ...], seed: int,
                   cells: tuple[Pos, ...]) -> tuple[Action, ...]:
        """The way to ``cells`` that shows the person what the robot holds (:func:`planner.hands_walk.hands_walk`),
        the person's poses predicted as for the dish walk, and, for a person who has stood in one cell ``n`` ticks,
        the hypothesis that they keep their pose, weighted ``n / (n + hands_still)``; within what is left of the leg's
        detour (:meth:`planner.showing.Showing.leg_budget`). Planned anew every tick."""
        assert self.kb is not None
        pose = (world.robot.pos, world.robot.facing)
        shortest = nearest_distances(self.layout, cells).get(pose, UNREACHABLE)
        if shortest == 0 or shortest >= UNREACHABLE:
            return ()
        budget = self.showing.leg_budget(world, cells, shortest)
        futures = self.kept_pose(world, self.person_futures(world, subtask, likely, seed, shortest + budget))
        return hands_walk(self.layout, self.cfg.human_angle, pose, cells, futures, self.cfg.human_delay,
                          self.showing.streak(world, self.kb), budget, self.cfg.hands_price)

    def person_futures(self, world: WorldState, subtask: Subtask, likely: tuple[tuple[Subtask, float], ...], seed: int,
                       ticks: int) -> list[Future]:
        """The person's poses over the next ``ticks`` ticks, one hypothesis per likely subtask of theirs (a rollout with
        the robot going on with ``subtask``, :meth:`predicted_worlds`), weighted by the belief."""
        return [(p, [(w.human.pos, w.human.facing) for w in self.predicted_worlds(world, s, subtask, ticks, seed)])
                for s, p in likely]

    def kept_weight(self) -> float:
        """How likely the person keeps their pose: ``n / (n + hands_still)`` after ``n`` ticks standing in one cell."""
        return self.human_still / (self.human_still + self.cfg.hands_still) if self.human_still else 0.0

    def kept_pose(self, world: WorldState, futures: list[Future]) -> list[Future]:
        """``futures`` and, for a person who has stood in one cell ``n`` ticks, the hypothesis that they keep their
        pose, weighted ``n / (n + hands_still)``: the longer a person has stood, the likelier they stay, whatever the
        model expects next (the hands walk's; the dish walk measured no better with it, docs/domain.md §5)."""
        if not self.human_still:
            return futures
        kept = self.kept_weight()
        return [(p * (1 - kept), poses) for p, poses in futures] + [(kept, [(world.human.pos, world.human.facing)])]

    def predicted_worlds(self, world: WorldState, human_subtask: Subtask, robot_subtask: Subtask, ticks: int,
                         seed: int) -> list[WorldState]:
        """The world after each of the next ``ticks`` ticks of the rollout of the hypothesis (the same rollout as
        :meth:`sampled`'s with ``seed``), until the orders are done."""
        assert self.kb is not None
        trace = traced(self.rollout, world, self.kb, human_subtask, robot_subtask, ticks, seed, self.human_still)
        return [state.world for state in trace.states[1:]] + [trace.end.world]


def make_qmdp_robot(name: str, layout: Layout, rules: Rules, config: PlannerConfig | None = None) -> QmdpRobot:
    cfg = config or PlannerConfig()
    if name == "baseline":
        return QmdpRobot(layout, rules, cfg.omniscient_human(), explore=False)
    if name == "no_rollout":
        return QmdpRobot(layout, rules, replace(cfg, exploration_depth=0), explore=False)
    if name == "fov_aware":
        return QmdpRobot(layout, rules, cfg, explore=True)
    raise ValueError(f"unknown QMDP robot {name!r}")

