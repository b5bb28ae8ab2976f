"""Headless trials: the simulated human (FOV-limited, with its KB) plays with a robot policy to the end.

One ``numpy.random.Generator`` per trial from the seed; the human and the robot each draw from their own
child stream (``Generator.spawn``), so the same seed gives the same trial whatever the robot consumes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from planner.behaviours import Behaviours, Frame, HandsGap, frame_of, hands_gap, measure
from planner.decision import Robot
from planner.events import Event
from planner.flicker import FlickerWatch
from planner.geometry import Action, manhattan
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout
from planner.partner import HumanPolicy, SimulatedPartner
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.rules import Rules
from planner.state import WorldState, initial_state, is_done
from planner.step import step
from planner.summary import GAP_COMPONENTS, info_diff, kb_diff_trial, kb_gap_components, state_info
from planner.work_share import WorkShare


@dataclass(frozen=True, slots=True)
class TrialSettings:
    """The human's field of view (degrees) and KB delay (ticks), and the kitchen's numbers."""

    angle: float = FOV_ANGLE
    kb_delay: int = KB_DELAY
    rules: Rules = field(default_factory=Rules)


@dataclass(frozen=True, slots=True)
class TrialResult:
    layout: str
    seed: int
    ticks: int
    finished: bool
    delivered: int
    score: int
    kb_gap_mean: float
    kb_gap_ticks_pct: float
    gap_component_pct: dict[str, float]
    robot_in_fov_pct: float
    final: WorldState
    actions: tuple[tuple[Action, Action], ...] = ()
    decision_ms: tuple[float, ...] = ()
    timed_out: int = 0
    cycles_broken: int = 0
    """Joint cycles the robot broke (:mod:`planner.cycle`)."""
    behaviours: Behaviours = field(default_factory=Behaviours)
    """The paper's two robot behaviours in this trial (:mod:`planner.behaviours`)."""
    hands: HandsGap = field(default_factory=HandsGap)
    """The ticks the person's KB was wrong about the robot's hands, by why (:func:`planner.behaviours.hands_gap`)."""
    robot_place_cells: float = 0.0
    """Mean over ticks of how far (cells, Manhattan) the person's KB places the robot from where it is."""
    robot_place_wrong_pct: float = 0.0
    """% of ticks at which the person's KB places the robot elsewhere than where it is."""
    kb_diff_freq: float = 0.0
    """The reference's KB gap (:mod:`planner.summary`): % of ticks with any gap."""
    kb_diff_avg: float | None = None
    """The reference's mean gap over the ticks that have one (``None`` when none has)."""
    kb_diff_mean: float = 0.0
    """The reference's mean gap over all ticks."""
    flickers: int = 0
    """Times the robot undid its own last touch of a counter in an unchanged scene (:mod:`planner.flicker`)."""
    work: WorkShare = field(default_factory=WorkShare)
    """Who delivered and who did the task steps (:mod:`planner.work_share`)."""

    def to_dict(self) -> dict[str, object]:
        return {
            "layout": self.layout, "seed": self.seed, "ticks": self.ticks, "finished": self.finished,
            "delivered": self.delivered, "score": self.score, "kb_gap_mean": round(self.kb_gap_mean, 4),
            "kb_gap_ticks_pct": round(self.kb_gap_ticks_pct, 2),
            "gap_component_pct": {k: round(v, 2) for k, v in self.gap_component_pct.items()},
            "robot_in_fov_pct": round(self.robot_in_fov_pct, 2),
            "kb_diff_freq": round(self.kb_diff_freq, 2),
            "kb_diff_avg": None if self.kb_diff_avg is None else round(self.kb_diff_avg, 4),
            "kb_diff_mean": round(self.kb_diff_mean, 4),
        }


def run_trial(layout: Layout, seed: int, settings: TrialSettings = TrialSettings(),
              robot: Robot | None = None, record: bool = False,
              before_human: Callable[[KnowledgeBase, HumanMemory, np.random.Generator], None] | None = None,
              human: HumanPolicy | None = None) -> TrialResult:
    """Play one trial to the end (all orders delivered or the horizon). ``before_human`` (diagnostics,
    e.g. ``benchmarks/planner/clairvoyant.py``) is shown the simulated person's KB, memory and random
    stream each tick before it acts; it must not consume the stream. ``human`` plays the human's avatar
    instead of the simulated human (e.g. :class:`planner.adversary.AdversarialHuman`)."""
    rules = settings.rules
    human_rng, robot_rng = np.random.default_rng(seed).spawn(2)
    world = initial_state(layout, rules)
    kb = initial_kb(world)
    human_model: HumanPolicy = human if human is not None else HumanModel(layout, rules)
    memory = HumanMemory()
    partner: Robot = robot if robot is not None else SimulatedPartner(layout, rules)
    partner.reset(world)
    events: tuple[Event, ...] = ()
    gap_ticks = gap_sum = place_cells = place_wrong = 0
    component_ticks = dict.fromkeys(GAP_COMPONENTS, 0)
    diffs: list[dict[str, int]] = []
    actions: list[tuple[Action, Action]] = []
    decision_ms: list[float] = []
    frames: list[Frame] = []
    timed_out = cycles_broken = 0
    touches = FlickerWatch()
    work = WorkShare()
    while not is_done(world, rules):
        if before_human is not None:
            before_human(kb, memory, human_rng)
        h_action, memory = human_model.act(world, kb, memory, human_rng)
        decision = partner.decide(world, events, robot_rng)
        r_action = decision.action
        if robot is not None:
            decision_ms.append(decision.elapsed_ms)
            timed_out += decision.timed_out
            cycles_broken += decision.cycle_broken
        before = world
        world, events = step(layout, world, {"human": h_action, "robot": r_action}, rules)
        touches = touches.observe(before, events, rules)
        work = work.observe(events)
        kb = update_kb(kb, layout, world, angle=settings.angle, kb_delay=settings.kb_delay,
                       own_events=[e for e in events if e.agent == "human"])
        gaps = kb_gap_components(kb, world, rules)
        diffs.append(info_diff(state_info(kb), state_info(world)))
        total = sum(gaps.values())
        gap_sum += total
        gap_ticks += total > 0
        for name, value in gaps.items():
            component_ticks[name] += value
        frames.append(frame_of(layout, world, events, settings.angle, kb))
        if kb.robot is not None:
            off = manhattan(kb.robot.pos, world.robot.pos)
            place_cells += off
            place_wrong += off > 0
        if record:
            actions.append((h_action, r_action))
    ticks = max(world.tick, 1)
    diff_freq, diff_avg, diff_mean = kb_diff_trial(diffs)
    return TrialResult(
        layout=layout.name, seed=seed, ticks=world.tick, finished=world.orders_left == 0,
        delivered=rules.orders - world.orders_left, score=world.score,
        kb_gap_mean=gap_sum / ticks, kb_gap_ticks_pct=100.0 * gap_ticks / ticks,
        gap_component_pct={k: 100.0 * v / ticks for k, v in component_ticks.items()},
        robot_in_fov_pct=100.0 * sum(f.seen for f in frames) / ticks, final=world, actions=tuple(actions),
        decision_ms=tuple(decision_ms), timed_out=timed_out, cycles_broken=cycles_broken,
        behaviours=measure(frames, settings.kb_delay), hands=hands_gap(frames, settings.kb_delay),
        robot_place_cells=place_cells / ticks, robot_place_wrong_pct=100.0 * place_wrong / ticks,
        kb_diff_freq=diff_freq, kb_diff_avg=diff_avg, kb_diff_mean=diff_mean,
        flickers=touches.flickers, work=work,
    )
