"""The paper's two robot behaviours on the paper's own robots, read from the reference's VR study logs.

The reference repository (SophieHsu/FOV-aware-planner, MIT licence) publishes, under
``overcooked_ai_py/data/logs/vr_study_logs/<participant>/<participant>_<kitchen>_<aware|unaware>.json``, one JSON
log per participant, kitchen (``none`` = ``steak_none_3``, ``mid`` = ``steak_mid_2``) and robot. Key ``i`` is one
past the last decision step; key ``"k"`` (``k`` = 1 … ``i`` − 1) holds the state sent to the reference planner
at decision step ``k`` (``overcooked_state_sent``: ``players[0]`` the robot, ``players[1]`` the person, each
with ``held_object``; ``order_list``) and the headset's samples until the next step (``low_level_logs``: per
sample ``robot_ml`` / ``human_ml`` = ``[y − 1, x − 1, facing letter]`` in the reference's grid, and
``human_ll_ori`` whose third value is the person's yaw in radians, 0 = south, +π/2 = east).

How we read them (docs/domain.md §6, "Behaviours", the reading of the paper's logs): one decision step is one
tick; what the robot holds is the state sent at that step (the reference's names mapped to ours); the robot
counts as in view during a step when it is in the person's view (:func:`planner.fov.in_view_heading`, at the
person's headset heading, the cells of both agents from their ``*_ml`` samples) in most of the step's
samples (a step without samples: the sent state's positions and the person's sent facing); a delivery is the
robot's dish gone with one order fewer. The reference grid is ours shifted (``none_3`` one column left), so
the cells are moved by that shift; the FOV has no range limit and no occlusion, so the shift changes no
reading. Participants the reference's own analysis left out (5, 11, 12) are left out unless
``--include-ignored``. Nothing of the logs is copied into this repository: the script reads the fetched
repository (a bare git directory, read with ``git show``, or a checked-out folder).

    .venv/bin/python benchmarks/planner/vr_logs.py /work/.mirror/SophieHsu+FOV-aware-planner/repo
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planner.behaviours import Behaviours, Frame, measure
from planner.fov import in_view_heading
from planner.geometry import Direction, Pos
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.perception import KB_DELAY
from planner.work_share import Tally, WorkShare

LOG_DIR = "overcooked_ai_py/data/logs/vr_study_logs"
LOG_NAME = re.compile(r"^(\d+)/\1_(none|mid)_(aware|unaware)\.json$")
KITCHENS = {"none": "none_3", "mid": "mid_2"}
SHIFT: dict[str, Pos] = {"none": (1, 0), "mid": (0, 0)}
"""Reference grid → ours: our ``none_3`` has one more counter column on the left."""
IGNORED = frozenset({5, 11, 12})
"""The participants the reference's ``vr_analysis.py`` skipped."""
HELD = {"meat": MEAT, "onion": ONION, "plate": DIRTY_PLATE, "hot_plate": CLEAN_PLATE, "steak": STEAK_PLATE,
        "dish": DISH}
LETTERS = {"N": Direction.NORTH, "S": Direction.SOUTH, "E": Direction.EAST, "W": Direction.WEST}


class LogError(ValueError):
    """A log that does not have the shape this reader expects (the message names the step and field)."""


@dataclass(frozen=True, slots=True)
class LogFile:
    participant: int
    kitchen: str
    robot: str
    path: str


def heading_of(yaw: float) -> tuple[float, float]:
    """The person's heading in grid axes (x east, y south) from the headset yaw (0 = south, +π/2 = east)."""
    return math.sin(yaw), math.cos(yaw)


def _cell(ml: list[Any], shift: Pos) -> Pos:
    return int(ml[1]) + 1 + shift[0], int(ml[0]) + 1 + shift[1]


def _held(player: dict[str, Any], step: int) -> str | None:
    obj = player.get("held_object")
    if obj is None:
        return None
    name = obj.get("name")
    if name not in HELD:
        return None if name == "garnish" else _fail(step, f"held_object {name!r}")
    return HELD[name]


def _fail(step: int, what: str) -> str:
    raise LogError(f"step {step}: unexpected {what}")


def frames_of(log: dict[str, Any], kitchen: str, angle: float) -> list[Frame]:
    """One :class:`Frame` per decision step of a parsed log (module docstring); ``kitchen`` is ``none``/``mid``."""
    shift = SHIFT[kitchen]
    if "i" not in log:
        raise LogError("no key 'i' (the number of decision steps)")
    frames: list[Frame] = []
    orders_before: int | None = None
    for k in range(1, int(log["i"])):
        entry = log.get(str(k))
        if entry is None or "overcooked_state_sent" not in entry:
            continue
        state = entry["overcooked_state_sent"]
        try:
            robot, person = state["players"][0], state["players"][1]
            orders = len(state["order_list"])
        except (KeyError, IndexError, TypeError) as exc:
            raise LogError(f"step {k}: overcooked_state_sent lacks {exc}") from exc
        held = _held(robot, k)
        samples = entry.get("low_level_logs") or []
        if samples:
            seen_samples = sum(in_view_heading(_cell(s["human_ml"], shift), heading_of(float(s["human_ll_ori"][2])),
                                               _cell(s["robot_ml"], shift), angle) for s in samples)
            seen = 2 * seen_samples > len(samples)
        else:
            p, r = person["position"], robot["position"]
            facing = tuple(float(v) for v in person["orientation"])
            seen = in_view_heading((p[0] + shift[0], p[1] + shift[1]), (facing[0], facing[1]),
                                   (r[0] + shift[0], r[1] + shift[1]), angle)
        delivered = (bool(frames) and frames[-1].held == DISH and held is None
                     and orders_before is not None and orders < orders_before)
        frames.append(Frame(held, seen, delivered))
        orders_before = orders
    return frames


def work_of(log: dict[str, Any]) -> WorkShare:
    """Who did the work in a parsed log (:mod:`planner.work_share`): a task step is a change of what an agent holds
    from one decision step to the next (the states sent to the planner; the presses of chopping and washing are not
    seen there, so ``presses`` stays empty), a delivery an agent's dish gone with one order fewer. The logs end
    after the first delivery, so the steps up to it are all of them."""
    if "i" not in log:
        raise LogError("no key 'i' (the number of decision steps)")
    steps, deliveries, first = Tally(), Tally(), Tally()
    before: tuple[list[str | None], int] | None = None
    for k in range(1, int(log["i"])):
        entry = log.get(str(k))
        if entry is None or "overcooked_state_sent" not in entry:
            continue
        state = entry["overcooked_state_sent"]
        try:
            held = [_held(state["players"][i], k) for i in (0, 1)]
            orders = len(state["order_list"])
        except (KeyError, IndexError, TypeError) as exc:
            raise LogError(f"step {k}: overcooked_state_sent lacks {exc}") from exc
        if before is not None:
            for agent, was, now in zip(("robot", "human"), before[0], held, strict=True):
                if now != was:
                    steps = steps.plus(agent)
                    if was == DISH and now is None and orders < before[1]:
                        deliveries = deliveries.plus(agent)
                        first = first if first.total else first.plus(agent)
        before = (held, orders)
    return WorkShare(deliveries=deliveries, steps=steps, steps_to_first=steps, first=first)


def log_files(names: list[str], include_ignored: bool) -> list[LogFile]:
    """The study logs among ``names`` (paths under the log folder), in a stable order."""
    found = []
    for name in sorted(names):
        match = LOG_NAME.match(name)
        if match is None:
            continue
        participant = int(match.group(1))
        if participant in IGNORED and not include_ignored:
            continue
        found.append(LogFile(participant, match.group(2), match.group(3), name))
    return found


class Source:
    """The fetched reference repository: a bare git directory or a checked-out folder."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.bare = (path / "HEAD").is_file() and (path / "objects").is_dir()
        if not self.bare and not (path / LOG_DIR).is_dir():
            raise FileNotFoundError(f"{path}: neither a bare git directory nor a checkout with {LOG_DIR}/")

    def names(self) -> list[str]:
        if self.bare:
            out = subprocess.run(["git", f"--git-dir={self.path}", "ls-tree", "-r", "--name-only", "HEAD", LOG_DIR],
                                 capture_output=True, text=True, check=True).stdout
            return [line[len(LOG_DIR) + 1:] for line in out.splitlines()]
        return [str(p.relative_to(self.path / LOG_DIR)) for p in (self.path / LOG_DIR).rglob("*.json")]

    def read(self, name: str) -> dict[str, Any] | None:
        """The parsed log, or ``None`` when the fetched copy lists the file but lacks its content (a snapshot
        may leave its largest files out)."""
        if self.bare:
            shown = subprocess.run(["git", f"--git-dir={self.path}", "show", f"HEAD:{LOG_DIR}/{name}"],
                                   capture_output=True, text=True)
            if shown.returncode != 0:
                return None
            text = shown.stdout
        else:
            text = (self.path / LOG_DIR / name).read_text(encoding="utf-8")
        parsed: dict[str, Any] = json.loads(text)
        return parsed


def table(results: dict[tuple[str, str, float], Behaviours], files: dict[tuple[str, str], int]) -> str:
    lines = [f"{'kitchen':<8}{'angle':>6}{'robot':>9}{'logs':>6}{'b1 shown':>16}{'b2 trip share':>20}"]
    for (kitchen, robot, angle), b in sorted(results.items(), key=lambda kv: (kv[0][0] != "none", kv[0][2],
                                                                             kv[0][1] != "aware")):
        b1 = f"{b.shown_rate:.2f} ({b.holdings})" if b.shown_rate is not None else "-"
        b2 = f"{b.trip_share:.2f} ({b.trips} trips)" if b.trip_share is not None else "-"
        lines.append(f"{KITCHENS[kitchen]:<8}{angle:>6.0f}{robot:>9}{files[(kitchen, robot)]:>6}{b1:>16}{b2:>20}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference", type=Path,
                        help="the fetched SophieHsu/FOV-aware-planner (bare git dir or checkout)")
    parser.add_argument("--angles", default="120,150")
    parser.add_argument("--include-ignored", action="store_true", help="also participants 5, 11, 12")
    parser.add_argument("--per-log", action="store_true", help="also print every log's counts")
    args = parser.parse_args(argv)
    try:
        source = Source(args.reference)
    except FileNotFoundError as exc:
        parser.error(str(exc))
    angles = [float(a) for a in args.angles.split(",")]
    results: dict[tuple[str, str, float], Behaviours] = {}
    files: dict[tuple[str, str], int] = {}
    absent = []
    for log in log_files(source.names(), args.include_ignored):
        data = source.read(log.path)
        if data is None:
            absent.append(log.path)
            continue
        files[(log.kitchen, log.robot)] = files.get((log.kitchen, log.robot), 0) + 1
        for angle in angles:
            frames = frames_of(data, log.kitchen, angle)
            b = measure(frames, KB_DELAY)
            key = (log.kitchen, log.robot, angle)
            results[key] = results.get(key, Behaviours()) + b
            if args.per_log:
                print(f"{log.path:<28}{angle:>5.0f} steps {len(frames):>4} pickups {b.shown}/{b.holdings} "
                      f"trips {b.trips} share {b.trip_share_sum:.2f}")
    print(f"reference VR logs: {sum(files.values())} logs "
          f"({'all participants' if args.include_ignored else 'without participants 5, 11, 12'}), kb_delay {KB_DELAY}")
    if absent:
        print(f"listed but absent from the fetched copy: {', '.join(absent)}")
    print(table(results, files))
    return 0


if __name__ == "__main__":
    sys.exit(main())
