"""The KB's acknowledgement rule, tick by tick, as the reference implementation ran it (docs/domain.md §3).

The rule works on the objects of :mod:`planner.kb_things` (each with its identity) and on the robot:

* **Tracked**: everything in the person's view, each with a count of its consecutive ticks in view, capped at
  the delay ``d``. An object keeps its count while it is carried, put down or worked on in view; the robot keeps
  its count whatever its hands do. An object or the robot whose count has reached ``d`` is acknowledged every
  tick: the KB takes where it is and its count (and the robot's pose and hands). What the person holds has count
  ``d`` at once, and so has what they make of it (the steak from their meat, the garnish, the plate in the sink,
  the plated steak, the dish).
* **Untracked**: what left the view, remembered where it was last seen. Once that place is in view again and the
  object is not in view anywhere, it is *to be removed*.
* **To be removed**: a count that grows by one at every tick its remembered place is in view (not necessarily
  consecutive ticks); at ``d`` the KB forgets the object. An object seen to vanish in view (used, or its place in
  view without it) starts at 0; so does an object the robot comes into view holding; one the watched robot picks
  up starts at the robot's count; what the person used up starts at ``d``.
* When the watched robot lets go of what it held, the reference guesses what it became by the held object's
  name (meat → the last steak, onion → the last garnish, dirty plate → the last plate in a sink, clean plate →
  the last steak, plated steak → the last dish), hands the guess the robot's count, and takes the held object
  as to be removed at that count; letting go of a plated steak also takes every tracked garnish as to be
  removed. "Last" is the last of that kind among the objects in the reference's order (:class:`Things`). The
  guess can be wrong (a plate put on a counter hands a steak elsewhere the robot's count); we follow it.

Each tick: the tracked objects and the robot (the robot first), then the robot coming into view, then the
untracked places in view, then the removals, then what the KB acknowledges.
"""

from __future__ import annotations

from dataclasses import dataclass

from planner.geometry import Pos
from planner.kb_things import Thing, Things
from planner.state import AgentState

_BECOMES = {"meat": "steak", "onion": "garnish", "plate": "hot_plate", "hot_plate": "steak", "steak": "dish"}


@dataclass(frozen=True, slots=True)
class Snap:
    """An object as the person last saw it: the cell it was at, its kind and its count."""

    cell: Pos
    kind: str
    state: int | None


@dataclass(frozen=True, slots=True)
class RobotSnap:
    """The robot as the person last saw it, with the identity of what it held."""

    state: AgentState
    held_id: int | None
    held: Snap | None


@dataclass(frozen=True, slots=True)
class Tracking:
    """The rule's memory between ticks (module docstring); ``believed`` are the objects the KB places somewhere
    (on counters, in stations, or in hands where it last acknowledged them), in the order the KB took them."""

    things: Things
    track: tuple[tuple[int, Snap, int], ...] = ()
    held: tuple[int, Snap] | None = None
    robot: tuple[RobotSnap, int] | None = None
    untrack: tuple[tuple[int, Snap], ...] = ()
    robot_untrack: RobotSnap | None = None
    remove: tuple[tuple[int, Snap, int], ...] = ()
    robot_remove: tuple[RobotSnap, int] | None = None
    believed: tuple[tuple[int, Snap], ...] = ()


def snap_of(thing: Thing, human: AgentState, robot: AgentState) -> Snap:
    place = thing.place
    cell = human.pos if place == "human" else robot.pos if place == "robot" else place
    return Snap(cell, thing.kind, thing.state)  # type: ignore[arg-type]


def robot_snap(robot: AgentState, things: Things, human: AgentState) -> RobotSnap:
    held = things.robot
    return RobotSnap(robot, None if held is None else held.id, None if held is None else snap_of(held, human, robot))


def acknowledge(mem: Tracking, things: Things, human: AgentState, robot: AgentState, seen: frozenset[Pos],
                d: int) -> tuple[Tracking, AgentState | None]:
    """One tick of the rule: the new memory and, when the robot is acknowledged, its state (else ``None``)."""
    ordered = things.ordered()
    now = {t.id: t for t in ordered}
    prev_track = {i: (s, n) for i, s, n in mem.track}
    prev_untrack = dict(mem.untrack)
    track = dict(prev_track)
    untrack = dict(prev_untrack)
    remove: dict[int, tuple[Snap, int]] = {i: (s, n) for i, s, n in mem.remove}
    held = mem.held
    robot_track = mem.robot
    robot_untrack, robot_remove = mem.robot_untrack, mem.robot_remove
    dropped: tuple[int, int] | None = None
    used_garnish: int | None = None

    def last(kind: str) -> Thing | None:
        return next((t for t in reversed(ordered) if t.kind == kind), None)

    if mem.robot is not None:
        before, count = mem.robot
        if robot.pos in seen:
            count = min(d, count + 1)
            robot_track = (robot_snap(robot, things, human), count)
            now_held = things.robot
            if before.state.held is None and now_held is not None and now_held.id in prev_untrack:
                remove[now_held.id] = (prev_untrack[now_held.id], count)
            if before.held is not None and before.held_id is not None and now_held is None:
                guess = last(_BECOMES.get(before.held.kind, ""))
                if before.held.kind == "steak" and guess is not None:
                    for i, (s, _n) in prev_track.items():
                        if s.kind == "garnish" and i not in remove:
                            remove[i] = (s, count)
                if guess is not None:
                    remove[before.held_id] = (before.held, count)
                    dropped = (guess.id, count)
                    track[guess.id] = (snap_of(guess, human, robot), count)
        else:
            robot_untrack, robot_track = before, None

    for key in sorted(now.keys() | prev_track.keys()):
        thing = now.get(key)
        snap = snap_of(thing, human, robot) if thing is not None else prev_track[key][0]
        if snap.cell not in seen:
            if key in prev_track:
                untrack[key] = prev_track[key][0]
                del track[key]
            continue
        if used_garnish == key:
            remove[key] = (snap, d)
        elif thing is not None:
            count = 1
            if key in prev_track:
                count = min(d, prev_track[key][1] + 1)
            elif key in track:
                count = track[key][1]
            elif dropped is not None and dropped[0] == key:
                count = dropped[1]
            if thing.place == "human":
                count = d
                held = (key, snap)
            track[key] = (snap, count)
        elif mem.held is not None and key == mem.held[0]:
            remove[key] = (snap, d)
            made = _made_by_person(snap.kind, ordered, seen, human, robot)
            keeps = made is not None and snap.kind in ("hot_plate", "steak")
            held = (made.id, snap_of(made, human, robot)) if keeps and made is not None else None
            if snap.kind == "steak":
                for i, (s, _n) in prev_track.items():
                    if s.kind == "garnish":
                        used_garnish = i
                        remove[i] = (s, d)
            if made is not None:
                track[made.id] = (snap_of(made, human, robot), d)
        elif key not in remove:
            remove[key] = (snap, 0)

    if things.human is not None:
        held = (things.human.id, snap_of(things.human, human, robot))
        track[things.human.id] = (held[1], d)

    if robot_track is None and robot.pos in seen:
        robot_track = (robot_snap(robot, things, human), 1)
        now_held = things.robot
        if (mem.robot_untrack is not None and mem.robot_untrack.state.held is None and now_held is not None
                and now_held.id in prev_untrack):
            remove[now_held.id] = (prev_untrack[now_held.id], 0)

    for key, snap in prev_untrack.items():
        if snap.cell in seen:
            if key in now and key in track:
                untrack.pop(key, None)
            elif key not in remove:
                remove[key] = (snap, 0)
    if mem.robot_untrack is not None and mem.robot_untrack.state.pos in seen:
        if robot_track is not None:
            robot_untrack = None
        elif robot_remove is None:
            robot_remove = (mem.robot_untrack, 0)

    believed = dict(mem.believed)
    kept: list[tuple[int, Snap, int]] = []
    for key, (gone, gone_count) in remove.items():
        track.pop(key, None)
        untrack.pop(key, None)
        gone_count += gone.cell in seen
        if gone_count >= d:
            believed.pop(key, None)
        else:
            kept.append((key, gone, gone_count))
    if robot_remove is not None:
        robot_track, robot_untrack = None, None
        snap_r, count = robot_remove
        count += snap_r.state.pos in seen
        robot_remove = None if count >= d else (snap_r, count)

    for key, (snap, count) in track.items():
        if count >= d:
            believed[key] = snap
    acknowledged = robot_track[0].state if robot_track is not None and robot_track[1] >= d else None
    new = Tracking(things=things, track=tuple((i, s, n) for i, (s, n) in track.items()), held=held,
                   robot=robot_track, untrack=tuple(untrack.items()), robot_untrack=robot_untrack,
                   remove=tuple(kept), robot_remove=robot_remove, believed=tuple(believed.items()))
    return new, acknowledged


def _made_by_person(kind: str, ordered: tuple[Thing, ...], seen: frozenset[Pos], human: AgentState,
                    robot: AgentState) -> Thing | None:
    """What the reference takes the person to have made of their held object of ``kind`` that is gone."""
    if kind == "hot_plate":  # they plated a steak: the last steak in view
        return next((t for t in reversed(ordered) if t.kind == "steak" and snap_of(t, human, robot).cell in seen),
                    None)
    target = _BECOMES.get(kind)
    return None if target is None else next((t for t in reversed(ordered) if t.kind == target), None)
