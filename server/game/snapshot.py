"""Messages and views built from a live trial: ``hello``, the masked per-tick ``state``, the admin's
spectator view (the full world, the participant's FOV, the modelled KB and its gap, the robot's decision)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Literal, cast

from planner.geometry import ACTIONS
from planner.subtasks import SUBTASKS
from planner.summary import gap_components, summarize
from server.game.blocked import Blocked
from server.game.engine import TrialEngine
from server.game.meta import TrialMeta
from server.game.needs import NEEDS
from server.game.view import agent_view, drawn_bounds, visible_world
from server.protocol.interrupts import Interrupt
from server.protocol.server import Blocked as BlockedMessage
from server.protocol.server import Bounds, Hello, Hud, State, TrialInfo
from study_config.study.views import ViewName

TrialKind = Literal["practice", "main"]
Mode = Literal["fixed_rate", "wait_for_participant"]


def hello(meta: TrialMeta, engine: TrialEngine, *, mode: str, rate: float, resumed: bool, limit: int) -> Hello:
    layout, rules = engine.layout, engine.rules
    left, top, width, height = drawn_bounds(layout)
    return Hello(
        trial=TrialInfo(id=meta.trial_id, kind=cast(TrialKind, meta.kind), index=meta.index, number=meta.number,
                        total=meta.total, kind_number=meta.index + 1, kind_total=meta.kind_total,
                        scored=meta.kind == "main"),
        width=layout.width, height=layout.height, subtasks=[s.value for s in SUBTASKS],
        interrupts=[i.value for i in Interrupt], mode=cast(Mode, mode), tick_rate_hz=rate, fov_angle=engine.angle,
        horizon=rules.horizon, orders=rules.orders, tick=engine.tick, resumed=resumed, max_message_bytes=limit,
        bounds=Bounds(left=left, top=top, width=width, height=height), needs={s.value: NEEDS[s] for s in SUBTASKS},
        view=cast(ViewName, meta.view))


def blocked_message(blocked: Blocked) -> BlockedMessage:
    return BlockedMessage(subtask=blocked.subtask.value if blocked.subtask else None, reason=blocked.reason.code,
                          item=blocked.reason.item, place=blocked.reason.place, ended=blocked.ended)


def state(engine: TrialEngine, *, mode: str, rate: float, ack: int, round_left: float | None = None) -> State:
    """What the participant sees now (``round_left``: the wall-clock seconds left of a wait-for-participant
    round's limit)."""
    world, rules = engine.world, engine.rules
    cells, robot = visible_world(engine.layout, world, rules, engine.angle)
    ticks_left = max(rules.horizon - world.tick, 0)
    controller = engine.controller
    return State(
        tick=world.tick, you=agent_view(world.human), robot=robot, cells=cells,
        hud=Hud(tick=world.tick, horizon=rules.horizon, ticks_left=ticks_left,
                seconds_left=round(ticks_left / rate, 2) if mode == "fixed_rate" else None,
                orders_left=world.orders_left, score=world.score,
                round_seconds_left=None if round_left is None else round(round_left, 1)),
        subtask=controller.subtask.value if controller.subtask else None,
        available=[s.value for s in controller.available(world, engine.kb)],
        queued=len(controller.queue), ack=ack)


def percentiles(values: Sequence[float]) -> dict[str, float | int | None]:
    if not values:
        return {"count": 0, "last": None, "p50": None, "p99": None, "max": None}
    ordered = sorted(values)

    def at(q: float) -> float:
        return round(ordered[min(int(q * len(ordered)), len(ordered) - 1)], 2)

    return {"count": len(values), "last": round(values[-1], 2), "p50": at(0.5), "p99": at(0.99),
            "max": round(ordered[-1], 2)}


def spectator(meta: TrialMeta, engine: TrialEngine, extra: dict[str, Any]) -> dict[str, Any]:
    """Everything an experimenter may see of a live trial (admin only; never sent to participants)."""
    world, kb, rules = engine.world, engine.kb, engine.rules
    kb_sum, world_sum = summarize(kb, rules), summarize(world, rules)
    fov = engine.fov()
    return {
        "trial": meta.to_dict(),
        "tick": world.tick,
        "layout": {"name": engine.layout.name, "width": engine.layout.width, "height": engine.layout.height,
                   "rows": engine.layout.text().splitlines()},
        "world": world.to_dict(),
        "fov_angle": engine.angle,
        "fov_cells": sorted([list(c) for c in fov.cells], key=lambda c: (c[1], c[0])),
        "kb": kb.to_dict(),
        "kb_summary": kb_sum.to_dict(),
        "world_summary": world_sum.to_dict(),
        "kb_gap": gap_components(kb_sum, world_sum),
        "robot_in_fov": world.robot.pos in fov.cells,
        "subtask": engine.controller.subtask.value if engine.controller.subtask else None,
        "queued": [i.value for i in engine.controller.queue],
        "actions": [a.value for a in ACTIONS],
        **extra,
    }
