"""Robot planners for live trials, off the event loop: a pool of worker processes, each trial pinned to
one worker that holds its (stateful) planner for the whole trial, or a single in-process thread (tests)."""

from server.robots.choice import RobotChoice
from server.robots.inprocess import InProcessRobots
from server.robots.pool import ProcessRobots, RobotPool, make_pool

__all__ = ["InProcessRobots", "ProcessRobots", "RobotChoice", "RobotPool", "make_pool"]
