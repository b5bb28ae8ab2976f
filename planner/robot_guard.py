"""What happens when a robot misbehaves (docs/robots.md, "When a robot fails"): a decision that raised, answered
something other than a :class:`~planner.decision.Decision` with one of the six actions, or hung, is a **fault**.
The robot stays that tick and the fault is counted (robot health), never raised into the game and never hidden.

:func:`checked` judges one answer; :func:`time_limit` stops a decision that runs past a limit (a timer signal, so
only on a process's main thread: the robot worker processes and headless trials; elsewhere it does nothing);
:class:`GuardedRobot` does both for a headless trial and keeps the faults. A robot stopped by the time limit is
dropped for the rest of its trial (its state is unknown) and stays.
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time
from collections.abc import Iterator, Sequence
from types import FrameType

import numpy as np

from planner.decision import Decision, Robot
from planner.events import Event
from planner.geometry import ACTIONS, Action
from planner.kb import KnowledgeBase
from planner.state import WorldState

HANG_S = 10.0
"""A headless decision still running after this many seconds is stopped as hung (the shipped planners decide in
milliseconds; ``steakhouse pilot`` gives a decision 10 s)."""
_REPEAT_S = 1.0
"""The stop is raised again this often until the robot's code lets it through."""


class IllegalDecision(ValueError):
    """A robot's answer that is not a legal decision."""


class DecisionHung(BaseException):
    """A decision stopped by :func:`time_limit`. A ``BaseException``, so that a robot's own ``except Exception``
    cannot swallow it."""


def checked(answer: object) -> Decision:
    """``answer`` when it is a legal decision: a :class:`Decision` whose action is one of the six
    :class:`~planner.geometry.Action` s and whose record can be stored; else :class:`IllegalDecision` saying
    what it was."""
    if not isinstance(answer, Decision):
        raise IllegalDecision(f"answered {type(answer).__name__} {_short(answer)}, not a planner.robot_api.Decision")
    if not isinstance(answer.action, Action):
        raise IllegalDecision(f"answered the action {_short(answer.action)}, not one of "
                              f"{', '.join('Action.' + a.name for a in ACTIONS)}")
    try:
        answer.to_dict()
    except (TypeError, ValueError, AttributeError) as exc:
        raise IllegalDecision(f"answered a decision whose record cannot be stored: {exc}") from None
    return answer


def describe(exc: BaseException) -> str:
    """One line for a fault: what kind, and the robot's own message."""
    if isinstance(exc, IllegalDecision):
        return f"illegal decision: {exc}"
    if isinstance(exc, DecisionHung):
        return f"hung: {exc}"
    return f"raised {type(exc).__name__}: {exc}"


@contextlib.contextmanager
def time_limit(seconds: float | None, what: str = "the decision") -> Iterator[None]:
    """Raise :class:`DecisionHung` in the code under the ``with`` once it has run ``seconds`` (and every second
    after, until it stops). Does nothing with ``None``, off the main thread, or without ``setitimer``."""
    if seconds is None or threading.current_thread() is not threading.main_thread() or not hasattr(signal,
                                                                                                   "setitimer"):
        yield
        return

    def stop(signum: int, frame: FrameType | None) -> None:
        raise DecisionHung(f"{what} was still running after {seconds:g} s and was stopped")

    previous = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, max(seconds, 1e-3), _REPEAT_S)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


class GuardedRobot:
    """``robot`` in a headless trial: each fault makes the robot stay that tick and is kept (:attr:`faults`, the
    first one's description in :attr:`first_fault`). A robot that hung, or whose ``reset`` failed, stays for the
    rest of the trial (:attr:`dead`)."""

    def __init__(self, robot: Robot, hang_s: float | None = HANG_S) -> None:
        self.robot, self.hang_s = robot, hang_s
        self.faults = 0
        self.first_fault: str | None = None
        self.dead = False

    def _fault(self, tick: int, exc: BaseException) -> None:
        self.faults += 1
        if self.first_fault is None:
            self.first_fault = f"tick {tick}: {describe(exc)}"

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        try:
            with time_limit(self.hang_s, "reset"):
                self.robot.reset(world, kb)
        except (Exception, DecisionHung) as exc:
            self._fault(world.tick, exc)
            self.dead = True

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        if not self.dead:
            try:
                with time_limit(self.hang_s):
                    answer = self.robot.decide(world, events, rng, deadline)
                return checked(answer)
            except (Exception, DecisionHung) as exc:
                self._fault(world.tick, exc)
                self.dead = isinstance(exc, DecisionHung)
        else:
            self.faults += 1
        return Decision(Action.STAY, elapsed_ms=(time.perf_counter() - start) * 1000)
