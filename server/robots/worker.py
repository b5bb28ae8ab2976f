"""The body of one robot worker process: a loop over requests on a pipe, holding its trials' planners.

Requests (pickled tuples): ``("open", req, trial_id, robot, layout, rules, config, world, kb)`` builds the
planner with the factory (``factory(robot, layout, rules, config)``) and resets it on the world and the
person's modelled KB the trial starts or resumes from; ``("decide", req, trial_id, world, events, seed, tick,
deadline)`` answers the action; ``("close", req, trial_id)`` drops the planner; ``("stop",)`` ends the
process. Replies are ``(req, "ok", payload, sent)`` or ``(req, "error", message, sent)``, ``sent`` being the
``server.robots.deadline.now()`` just before the reply is written (the server judges deadlines on it). Requests are
served one at a time, so a trial's planner is never used concurrently. The process ignores SIGINT (the
server shuts it down) and exits when the pipe closes (the server died). It runs at the server's CPU
priority: at a lower one (nice +5) the game loop's ticks went first on a saturated machine, but the workers
then starved whenever the server and other work were busy together (trial ends and starts), and decisions
missed their deadlines in bursts (docs/operations.md §2).
"""

from __future__ import annotations

import gc
import signal
from multiprocessing.connection import Connection
from typing import Any

from planner.decision import Robot, RobotFactory
from server.robots import deadline as clock
from server.robots.choice import load_factory, run_decision

FREEZE_EVERY = 100
"""Requests between two ``gc.freeze()`` calls (see :func:`worker_main`)."""


def worker_main(conn: Connection, factory_path: str) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    factory = load_factory(factory_path)
    policies: dict[int, Robot] = {}
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
            payload = _serve(op, message, policies, factory)
        except Exception as exc:  # report every planner failure to the server
            reply: tuple[Any, ...] = (req, "error", f"{type(exc).__name__}: {exc}")
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


def _serve(op: str, message: tuple[Any, ...], policies: dict[int, Robot], factory: RobotFactory) -> Any:
    if op == "open":
        _, _, trial_id, robot, layout, rules, config, world, kb = message
        policy = factory(robot, layout, rules, config)
        policy.reset(world, kb)
        policies[trial_id] = policy
        return None
    if op == "decide":
        _, _, trial_id, world, events, seed, tick, deadline = message
        found = policies.get(trial_id)
        if found is None:
            raise LookupError(f"trial {trial_id} has no planner in this worker")
        return run_decision(found, world, events, seed, tick, deadline)
    if op == "close":
        policies.pop(message[2], None)
        return None
    raise ValueError(f"unknown request {op!r}")
