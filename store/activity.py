"""The participant's activity in one trial, counted from its stored ticks and events when it ends (so a trial
resumed after a restart is counted whole), and stored on the trial row (docs/operations.md, "Engagement").

- ``selections``: task choices (``select_subtask`` events, refused ones included); ``interrupts``: accepted
  interrupts (``interrupt`` events: keys and the stop button); ``key_actions``: of these, the one-step keys
  (moves, stay, interact). The participant's actions are ``selections + interrupts``.
- ``idle_pct`` = 100 · (idle ticks + waited seconds × tick rate) / (ticks + waited seconds × tick rate): idle
  ticks are steps in which the cook had nothing to do (``action_source = 'idle'``, the ``fixed_rate`` clock);
  waited seconds are the stretches a ``wait_for_participant`` world stood still for the participant (``wait``
  events), counted as the ticks that clock would have stepped meanwhile. ``None`` for a trial with neither.
- ``refused_steps``: the participant's tasks refused or ended because they could not work (``subtask_blocked``
  events: what they needed was gone, taken or busy, often because the robot had done it).
- ``delivered_by_participant`` / ``delivered_by_robot``: ``deliver`` world events of each agent.
"""

from __future__ import annotations

from dataclasses import dataclass

from sqlalchemy import func, select, update
from sqlalchemy.orm import Session

from store.tables import EventRow, TickRow, TrialRow

KEY_ACTIONS = frozenset({"up", "down", "left", "right", "stay", "interact"})


@dataclass(frozen=True, slots=True)
class Activity:
    selections: int
    interrupts: int
    key_actions: int
    ticks: int
    idle_ticks: int
    waited_seconds: float
    refused_steps: int
    delivered_by_participant: int
    delivered_by_robot: int
    tick_rate_hz: float

    @property
    def actions(self) -> int:
        """The participant's actions: task choices and interrupts."""
        return self.selections + self.interrupts

    @property
    def idle_pct(self) -> float | None:
        waited = self.waited_seconds * self.tick_rate_hz
        total = self.ticks + waited
        return 100.0 * (self.idle_ticks + waited) / total if total > 0 else None


def measure(session: Session, trial_id: int, tick_rate_hz: float) -> Activity:
    """The activity of trial ``trial_id`` from its stored ticks and events."""
    counts: dict[str, int] = {}
    keys = waited = 0.0
    for kind, payload in session.execute(select(EventRow.kind, EventRow.payload).where(
            EventRow.trial_id == trial_id,
            EventRow.kind.in_(("select_subtask", "interrupt", "subtask_blocked", "wait")))):
        counts[kind] = counts.get(kind, 0) + 1
        if kind == "interrupt" and (payload or {}).get("action") in KEY_ACTIONS:
            keys += 1
        elif kind == "wait":
            waited += float((payload or {}).get("seconds", 0.0))
    ticks = int(session.scalar(select(func.count()).where(TickRow.trial_id == trial_id)) or 0)
    idle = int(session.scalar(select(func.count()).where(TickRow.trial_id == trial_id,
                                                        TickRow.action_source == "idle")) or 0)
    delivered = {"human": 0, "robot": 0}
    for (events,) in session.execute(select(TickRow.world_events).where(TickRow.trial_id == trial_id)):
        for event in events or ():
            if event.get("kind") == "deliver" and event.get("agent") in delivered:
                delivered[event["agent"]] += 1
    return Activity(selections=counts.get("select_subtask", 0), interrupts=counts.get("interrupt", 0),
                    key_actions=int(keys), ticks=ticks, idle_ticks=idle, waited_seconds=waited,
                    refused_steps=counts.get("subtask_blocked", 0), delivered_by_participant=delivered["human"],
                    delivered_by_robot=delivered["robot"], tick_rate_hz=tick_rate_hz)


def record(session: Session, trial_id: int, activity: Activity, engagement_reason: str | None) -> None:
    """Store ``activity`` and the low-engagement reason (if any) on the trial row."""
    idle = activity.idle_pct
    session.execute(update(TrialRow).where(TrialRow.id == trial_id).values(
        selections=activity.selections, interrupts=activity.interrupts, key_actions=activity.key_actions,
        idle_pct=None if idle is None else round(idle, 2), refused_steps=activity.refused_steps,
        delivered_by_participant=activity.delivered_by_participant,
        delivered_by_robot=activity.delivered_by_robot,
        engagement_reason=None if engagement_reason is None else engagement_reason[:200]))
