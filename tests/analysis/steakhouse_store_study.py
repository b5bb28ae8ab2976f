"""Stored studies for the analysis tests, written through the server's own store and flow functions.

:func:`play_stored_trial` runs one trial the way the live game loop does (``TrialEngine``, the participant
controller, ``tick_row``) with a simulated participant, and writes its ticks and events with the store's
batch writer and ends it with the flow service; :func:`hand_trial` writes hand-made ticks and events.
No network: fast enough to run on SQLite and PostgreSQL in every test.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from planner.geometry import Action
from planner.partner import SimulatedPartner
from planner.robots import StayRobot
from planner.state import WorldState
from server.flow import service
from server.flow.progress import Move
from server.game.engine import TrialEngine
from server.game.records import tick_row
from server.game.resume import prepare_trial
from server.protocol.interrupts import Interrupt
from server.robots.choice import RobotChoice, run_decision
from store import trials
from store.engine import Store
from store.tables import ParticipantRow
from store.types import utcnow
from store.writer import write_batch
from study_config.catalog import LoadedStudy
from study_config.study.questionnaire import Item

INTERRUPTS = tuple(Interrupt)


def study_robots(name: str, layout: Any, rules: Any, config: Any = None) -> Any:
    """Robot factory for test studies: ``stay`` stands still, any other name is the simulated partner
    (it works in the kitchen, so the two robots differ in ticks, KB gap and robot-in-FOV)."""
    return StayRobot() if name == "stay" else SimulatedPartner(layout, rules)


DECISION_S = 600.0
"""The robot's decision deadline while a stored study is played: one no machine reaches. The planner stops valuing
options at its deadline, so with a short one (it was 1 s) a loaded machine could store other trials than a quiet one
(a loaded run once found a wide-file cell empty that quiet runs fill): the stored studies must be the same anywhere."""


def study_overrides(**extra: object) -> dict[str, object]:
    """A fast 2 robots × 2 kitchens study: one practice trial, one order, short horizon, 30 Hz (no trial is ever
    robot-invalid for missed deadlines nor low-engagement for how its scripted participants chose: ``write_study``'s
    defaults). The robot's flicker rule is off here too: on a loaded machine the baseline robot of a live round was
    once flagged for putting an item down and picking it up again (the analysis is what these tests check;
    tests/server/game/test_game_health.py tests the rule)."""
    values: dict[str, object] = {
        "validity": {"max_robot_flickers": 1000},
        "robots": ["stay", "baseline"], "kitchens": ["none_3", "mid_2"], "factors": ["robot", "kitchen"],
        "practice": [{"kitchen": "practice", "robot": "stay", "count": 1}],
        "world": {"orders": 1, "horizon": 120, "kb_delay": 1},
        "questionnaires": [
            {"id": "q", "items": [{"id": "a", "text": "A", "scale": {"min": 1, "max": 5}},
                                  {"id": "b", "text": "B", "scale": {"min": 1, "max": 5}, "required": False}]},
            {"id": "end", "when": "end_of_study", "items": [{"id": "age", "text": "Age group",
                                                              "scale": {"min": 1, "max": 6}}]},
        ],
    }
    values.update(extra)
    return values


@dataclass
class Participant:
    """A simulated participant: picks a random available subtask when idle and sends a random interrupt
    with probability ``interrupt_rate`` per tick."""

    seed: int
    interrupt_rate: float = 0.05
    rng: np.random.Generator = field(init=False)

    def __post_init__(self) -> None:
        self.rng = np.random.default_rng(self.seed)


def join(store: Store, loaded: LoadedStudy, recruit: str | None = None, test_run: bool = False) -> int:
    """A participant who joined, consented and read the instructions; returns their row id."""
    names = loaded.study.recruiting.url_parameters
    recruiting = {names[0]: recruit} if recruit and names else {}
    joined = service.join(store, loaded, recruiting, test_run)
    service.move(store, joined.participant.id, Move.ACCEPT_CONSENT)
    service.move(store, joined.participant.id, Move.FINISH_INSTRUCTIONS)
    return joined.participant.id


def current_step(store: Store, participant_id: int) -> Any:
    with store.transaction() as session:
        row = session.get(ParticipantRow, participant_id)
        assert row is not None
        return service.progress_of(row)


def play_stored_trial(store: Store, loaded: LoadedStudy, participant_id: int, who: Participant) -> int:
    """Play the participant's current trial step to the end and store it; returns the trial id."""
    step = current_step(store, participant_id).current
    prepared = prepare_trial(store, loaded, participant_id, step)
    row, study = prepared.trial, loaded.study
    layout, rules = loaded.layout(row.kitchen), loaded.rules
    engine = TrialEngine(layout, rules, angle=study.trial_angle(row.fov_angle), kb_delay=study.world.kb_delay,
                         seed=row.seed,
                         world=WorldState.from_dict(row.initial_state))
    policy = study_robots(row.robot, layout, rules)
    policy.reset(engine.world)
    ticks: list[dict[str, Any]] = []
    events = [_event(participant_id, row.id, 0, "trial_start", {"attempt": row.attempt})]
    controller = engine.controller
    while not engine.done:
        if controller.subtask is None:
            options = controller.available(engine.world, engine.kb)
            choice = options[int(who.rng.integers(len(options)))]
            controller.select(choice)
            events.append(_event(participant_id, row.id, engine.tick, "select_subtask",
                                 {"subtask": choice.value, "available": True}))
        if who.rng.random() < who.interrupt_rate:
            which = INTERRUPTS[int(who.rng.integers(len(INTERRUPTS)))]
            if controller.interrupt(which):
                events.append(_event(participant_id, row.id, engine.tick, "interrupt", {"action": which.value}))
        start = time.perf_counter()
        action, info = run_decision(policy, engine.world, engine.last_events, row.seed, engine.tick,
                                    time.monotonic() + DECISION_S)
        choice_ = RobotChoice(Action(action), decision_ms=(time.perf_counter() - start) * 1000, info=info)
        outcome = engine.advance(choice_.action)
        # Under the round's lease (store/lease.py): rows of another epoch would be refused.
        ticks.append(tick_row(row.id, outcome, choice_, 1.5, controller.to_dict(), engine.tick / 10, prepared.epoch))
    world = engine.world
    reason = "delivered" if world.orders_left == 0 else "horizon"
    events.append(_event(participant_id, row.id, world.tick, "trial_end", {"status": "finished", "reason": reason}))
    write_batch(store, ticks, events)
    service.end_trial(store, participant_id, row.id, row.kind, row.index, status="finished", reason=reason,
                      ticks=world.tick, delivered=rules.orders - world.orders_left, score=world.score)
    return row.id


def abandon_current_trial(store: Store, loaded: LoadedStudy, participant_id: int) -> int:
    """Start the participant's current trial and let the reconnect grace window expire at tick 0."""
    step = current_step(store, participant_id).current
    row = prepare_trial(store, loaded, participant_id, step).trial
    service.end_trial(store, participant_id, row.id, row.kind, row.index, status="abandoned",
                      reason="grace_expired")
    return row.id


def answer(store: Store, loaded: LoadedStudy, participant_id: int, values: dict[str, int]) -> None:
    questionnaire = current_step(store, participant_id).current.questionnaire
    service.submit_questionnaire(store, loaded, participant_id, questionnaire, values)


def play_participant(store: Store, loaded: LoadedStudy, participant_id: int, who: Participant,
                     main_trials: int | None = None) -> list[int]:
    """Play practice, then ``main_trials`` main trials (all by default) with their questionnaires."""
    played: list[int] = []
    mains = 0
    while True:
        progress = current_step(store, participant_id)
        step = progress.current
        if step.kind == "trial":
            if step.trial_kind == "main":
                if main_trials is not None and mains >= main_trials:
                    return played
                mains += 1
            played.append(play_stored_trial(store, loaded, participant_id, who))
        elif step.kind == "questionnaire":
            items = next(q for q in loaded.study.questionnaires if q.id == step.questionnaire).items
            answer(store, loaded, participant_id, {item.id: _rating(item, who.rng) for item in items})
        else:
            return played


def _rating(item: Item, rng: np.random.Generator) -> int:
    """A random answer to a rating item (the test studies ask only rating items)."""
    assert item.scale is not None, f"item {item.id!r} is not a rating item"
    return int(rng.integers(item.scale.min, item.scale.max + 1))


def _event(participant_id: int, trial_id: int, tick: int, kind: str, payload: dict[str, Any]) -> dict[str, Any]:
    return {"participant_id": participant_id, "trial_id": trial_id, "tick": tick, "kind": kind, "payload": payload,
            "created_at": utcnow()}


def hand_trial(store: Store, loaded: LoadedStudy, participant_id: int, initial: dict[str, Any],
               ticks: Sequence[dict[str, Any]], events: Sequence[tuple[int, str, dict[str, Any]]], *,
               status: str = "finished", reason: str = "delivered", delivered: int = 1, score: int = 20,
               kind: str = "main", index: int = 0) -> int:
    """A trial with hand-made tick rows (``tick`` numbered 1..n) and ``(tick, kind, payload)`` events."""
    with store.transaction() as session:
        row = trials.create(session, study_id=loaded.id, participant_id=participant_id, kind=kind, index=index,
                            condition_id="stay@practice", kitchen="practice", robot="stay", seed=7,
                            config_hash=loaded.study.config_hash(), initial_state=initial)
        trial_id = row.id
    now = utcnow()
    write_batch(store, [{"trial_id": trial_id, "recorded_at": now, **t} for t in ticks],
                [_event(participant_id, trial_id, tick, kind_, payload) for tick, kind_, payload in events])
    with store.transaction() as session:
        trials.end(session, trial_id, status=status, reason=reason, ticks=len(ticks), delivered=delivered,
                   score=score)
    return trial_id
