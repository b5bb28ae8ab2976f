"""What a live trial stores: the row for each tick (see ``store.tables.TickRow`` for the columns' meaning) and its
events, written through the store's batch writer."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Any

from server.flow import service
from server.game.engine import TickOutcome, TrialEngine
from server.game.meta import TrialMeta
from server.game.taking_part import TakingPart
from server.protocol.server import Error, TrialEnd
from server.robots import RobotChoice
from store.engine import Store
from store.types import utcnow
from store.writer import BatchWriter
from study_config.study import Study

EventLog = Callable[[str, dict[str, Any]], None]
"""How a part of the game stores an event: ``log(kind, payload)`` (:meth:`TrialRecords.event`)."""


def tick_row(trial_id: int, outcome: TickOutcome, choice: RobotChoice, lateness_ms: float,
             controller: dict[str, Any], round_seconds: float, epoch: int = 0) -> dict[str, Any]:
    """Joint action, the subtask the participant's action came from, modelled KB and world summaries, the
    KB-gap components and their sum, robot in the participant's FOV, lateness and decision time, the robot's
    decision record (or why it failed), the full world, KB and controller state (replay and resume read them), the
    step's world events (who loaded, chopped, washed, plated, delivered, or bumped into the other), what the
    participant's cook did in the step (``controller.step``: ``server.game.steps``), the seconds the round has run
    while the participant was connected (its limit's clock), and the lease epoch it was stepped under
    (``store.lease``: the store keeps it only while the epoch is the round's)."""
    return {
        "trial_id": trial_id, "tick": outcome.tick, "recorded_at": utcnow(),
        "human_action": outcome.human_action.value, "robot_action": outcome.robot_action.value,
        "action_source": outcome.source, "subtask": outcome.subtask.value if outcome.subtask else None,
        "kb_summary": outcome.kb_summary, "world_summary": outcome.world_summary, "kb_gap": outcome.gap,
        "kb_gap_total": sum(outcome.gap.values()), "robot_in_fov": outcome.robot_in_fov,
        "lateness_ms": round(lateness_ms, 3),
        "decision_ms": None if choice.decision_ms is None else round(choice.decision_ms, 3),
        "robot_missed": choice.missed, "robot_info": choice.info,
        "robot_error": choice.error[:300] if choice.failed and choice.error is not None else None,
        "world_state": outcome.world.to_dict(),
        "kb_state": outcome.kb.to_dict(), "controller": {**controller, "step": outcome.step},
        "world_events": [event.to_dict() for event in outcome.events], "round_seconds": round(round_seconds, 3),
        "epoch": epoch,
    }


class TrialRecords:
    """What one live trial stores as it runs: an event row per :meth:`event` and a tick row per :meth:`tick`, each
    shown to the round's taking part (``server.game.taking_part``) as it is written."""

    def __init__(self, writer: BatchWriter, meta: TrialMeta, engine: TrialEngine, part: TakingPart) -> None:
        self.writer, self.meta, self.engine, self.part = writer, meta, engine, part

    def event(self, kind: str, payload: dict[str, Any]) -> None:
        """Store one ``kind`` event at the engine's current tick."""
        self.part.note(kind, payload)
        self.writer.add_event({"participant_id": self.meta.participant_id, "trial_id": self.meta.trial_id,
                               "tick": self.engine.tick, "kind": kind, "payload": payload,
                               "created_at": utcnow(), "epoch": self.meta.epoch})

    def tick(self, outcome: TickOutcome, choice: RobotChoice, lateness_ms: float, round_seconds: float) -> None:
        """Store the step just taken (:func:`tick_row`)."""
        self.part.stepped(outcome)
        self.writer.add_tick(tick_row(self.meta.trial_id, outcome, choice, lateness_ms,
                                      self.engine.controller.to_dict(), round_seconds, self.meta.epoch))

    async def store_end(self, store: Store, study: Study, status: str, reason: str) -> tuple[int, Error | TrialEnd]:
        """Store the trial's end (``finished`` or ``abandoned``, with ``reason``) and its event together under this
        process's lease, moving the participant on, or not at all (the round was taken over by another process
        meanwhile: it ends there, once); the close code and last message the participant's connection gets."""
        world, meta = self.engine.world, self.meta
        delivered = self.engine.rules.orders - world.orders_left
        progress = await asyncio.to_thread(
            service.end_trial, store, meta.participant_id, meta.trial_id, meta.kind, meta.index, status=status,
            reason=reason, ticks=world.tick, delivered=delivered, score=world.score, study=study, epoch=meta.epoch,
            end_event={"status": status, "reason": reason, "ticks": world.tick})
        if progress is None:
            return 4000, Error(code="replaced", message="this round continues in another window")
        return 1000, TrialEnd(status=status, reason=reason, ticks=world.tick, delivered=delivered,  # type: ignore[arg-type]
                              score=world.score, next=progress.phase.value)
