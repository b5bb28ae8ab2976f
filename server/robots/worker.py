"""The body of one robot worker process: a loop over requests on a pipe, holding its trials' planners.

Requests (pickled tuples): ``("open", req, trial_id, robot, layout, rules, setup, world, kb)`` builds the
planner with the factory (``factory(robot, layout, rules, setup)``, :func:`planner.robot_catalog.build`) and resets
it on the world and the person's modelled KB the trial starts or resumes from; ``("decide", req, trial_id, world,
events, seed, tick, deadline)`` answers the action; ``("close", req, trial_id)`` drops the planner; ``("stop",)``
ends the process. Replies are ``(req, "ok", payload, sent)`` or ``(req, "error", message, sent)``, ``sent`` being the
``server.robots.deadline.now()`` just before the reply is written (the server judges deadlines on it); an error's
message says what the robot did (``planner.robot_guard.describe``: raised, illegal decision, hung). Requests are
served one at a time, so a trial's planner is never used concurrently. A decision still running ``HANG_GRACE_S``
past its deadline (a building or reset still running after ``OPEN_LIMIT_S``) is stopped
(``planner.robot_guard.time_limit``): its robot is dropped, and every later decision of its trial answers that
it hung, so one hanging robot holds up the other trials of its worker for seconds, never for good. The process
ignores SIGINT (the server shuts it down) and exits when the pipe closes (the server died). It runs at the server's CPU
priority: at a lower one (nice +5) the game loop's ticks went first on a saturated machine, but the workers
then starved whenever the server and other work were busy together (trial ends and starts), and decisions
missed their deadlines in bursts (docs/operations.md §2).
"""

from __future__ import annotations

import gc
import signal
from multiprocessing.connection import Connection
from typing import Any

from planner.decision import Robot
from planner.robot_catalog import RobotFactory
from planner.robot_guard import DecisionHung, describe, time_limit
from server.robots import deadline as clock
from server.robots.choice import load_factory, run_decision

FREEZE_EVERY = 100
"""Requests between two ``gc.freeze()`` calls (see :func:`worker_main`)."""
HANG_GRACE_S = 5.0
"""A decision still running this long after its deadline is stopped as hung (its answer is long discarded)."""
OPEN_LIMIT_S = 30.0
"""Building a trial's robot and resetting it is stopped as hung after this long."""


def worker_main(conn: Connection, factory_path: str) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    factory = load_factory(factory_path)
    policies: dict[int, Robot] = {}
    hung: dict[int, str] = {}
    served = 0
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            break
        if message[0] == "stop":
            break
        op, req = message[0], message[1]
        try:
            payload = _serve(op, message, policies, factory, hung)
        except (Exception, DecisionHung) as exc:  # report every planner failure to the server
            if isinstance(exc, DecisionHung) and op in ("open", "decide"):
                policies.pop(message[2], None)
                hung[message[2]] = describe(exc)
            reply: tuple[Any, ...] = (req, "error", describe(exc))
        else:
            reply = (req, "ok", payload)
        try:
            conn.send((*reply, clock.now()))
        except (BrokenPipeError, OSError):
            break
        served += 1
        if op == "open" or served % FREEZE_EVERY == 0:
            # The planner's caches grow all trial long; a full garbage collection walked them between two
            # decisions and held one up for 60–270 ms (measured with gc.callbacks at 60 trials: every deadline
            # miss after warm-up). Frozen objects are left to reference counting alone, which frees all the
            # planner makes: its state is acyclic (immutable dataclasses, tuples, caches).
            gc.freeze()
    conn.close()


class RobotHung(RuntimeError):
    """A later decision of a trial whose robot hung."""


def _serve(op: str, message: tuple[Any, ...], policies: dict[int, Robot], factory: RobotFactory,
           hung: dict[int, str]) -> Any:
    if op == "open":
        _, _, trial_id, robot, layout, rules, setup, world, kb = message
        hung.pop(trial_id, None)
        with time_limit(OPEN_LIMIT_S, f"building robot {robot!r}"):
            policy = factory(robot, layout, rules, setup)
            policy.reset(world, kb)
        policies[trial_id] = policy
        return None
    if op == "decide":
        _, _, trial_id, world, events, seed, tick, deadline = message
        found = policies.get(trial_id)
        if found is None:
            if trial_id in hung:
                raise RobotHung(f"the robot stands still for the rest of the trial: it {hung[trial_id]}")
            raise LookupError(f"trial {trial_id} has no planner in this worker")
        with time_limit(clock.left(deadline) + HANG_GRACE_S, f"the decision of tick {tick}"):
            return run_decision(found, world, events, seed, tick, deadline)
    if op == "close":
        policies.pop(message[2], None)
        hung.pop(message[2], None)
        return None
    raise ValueError(f"unknown request {op!r}")
