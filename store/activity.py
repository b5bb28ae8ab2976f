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
- ``task_steps`` / ``robot_task_steps``: each agent's interactions that changed the world (every world event of
  theirs but a blocked move: a pick-up, a put-down, a chop, a delivery, …), the team's work split between them.
- ``stand_ticks``: the stored steps in which the participant had no executable action (``ticks.controller.step``
  ``stand`` or ``idle``, :data:`StepKind`; a tick stored before steps were recorded counts when its
  ``action_source`` is ``idle``). The paper's clock does not step for them (docs/protocol.md, "The paper's clock").
- ``think_seconds``: wall-clock seconds the cook had nothing to do while the participant was connected — the
  waited seconds of a ``wait_for_participant`` round, the idle ticks at the tick rate of a ``fixed_rate`` one: the
  time they took to decide.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from sqlalchemy import func, select, update
from sqlalchemy.orm import Session

from store.tables import EventRow, TickRow, TrialRow

KEY_ACTIONS = frozenset({"up", "down", "left", "right", "stay", "interact"})

StepKind = Literal["key", "walk", "work", "wait", "look", "stand", "idle"]
"""What the participant's cook did in a world step (``ticks.controller.step``, written by ``server.game.steps``)."""
NOT_EXECUTABLE: frozenset[str] = frozenset({"stand", "idle"})
"""The steps in which the participant had no executable action."""


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
    task_steps: int = 0
    robot_task_steps: int = 0
    stand_ticks: int = 0

    @property
    def actions(self) -> int:
        """The participant's actions: task choices and interrupts."""
        return self.selections + self.interrupts

    @property
    def think_seconds(self) -> float:
        """Seconds the cook had nothing to do while the participant was connected (deciding)."""
        return self.waited_seconds + self.idle_ticks / self.tick_rate_hz

    @property
    def task_step_share(self) -> float | None:
        """The participant's share of the team's task steps, in % (``None`` when neither made one)."""
        team = self.task_steps + self.robot_task_steps
        return 100.0 * self.task_steps / team if team else None

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
    steps = {"human": 0, "robot": 0}
    stand = 0
    for events, source, controller in session.execute(select(TickRow.world_events, TickRow.action_source,
                                                             TickRow.controller).where(TickRow.trial_id == trial_id)):
        for event in events or ():
            agent, kind = event.get("agent"), event.get("kind")
            if agent in steps and kind != "blocked":
                steps[agent] += 1
                delivered[agent] += kind == "deliver"
        step = (controller or {}).get("step") or ("idle" if source == "idle" else None)
        stand += step in NOT_EXECUTABLE
    return Activity(selections=counts.get("select_subtask", 0), interrupts=counts.get("interrupt", 0),
                    key_actions=int(keys), ticks=ticks, idle_ticks=idle, waited_seconds=waited,
                    refused_steps=counts.get("subtask_blocked", 0), delivered_by_participant=delivered["human"],
                    delivered_by_robot=delivered["robot"], tick_rate_hz=tick_rate_hz, task_steps=steps["human"],
                    robot_task_steps=steps["robot"], stand_ticks=stand)


def record(session: Session, trial_id: int, activity: Activity, engagement_reason: str | None) -> None:
    """Store ``activity`` and the low-engagement reason (if any) on the trial row."""
    idle = activity.idle_pct
    session.execute(update(TrialRow).where(TrialRow.id == trial_id).values(
        selections=activity.selections, interrupts=activity.interrupts, key_actions=activity.key_actions,
        idle_pct=None if idle is None else round(idle, 2), refused_steps=activity.refused_steps,
        delivered_by_participant=activity.delivered_by_participant,
        delivered_by_robot=activity.delivered_by_robot, task_steps=activity.task_steps,
        robot_task_steps=activity.robot_task_steps, stand_ticks=activity.stand_ticks,
        think_seconds=round(activity.think_seconds, 3),
        engagement_reason=None if engagement_reason is None else engagement_reason[:200]))
