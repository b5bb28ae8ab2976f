"""The server's own CPU per trial tick, phase by phase, without network, clock or robot planner.

    .venv/bin/python benchmarks/load/server_share.py [--trials 60] [--ticks 300] [--profile 25]

Steps ``--trials`` trials in one process as the live loop does (``server.game.live``), with a participant
who picks a random subtask from ``state.available`` whenever idle and a robot that takes a random action
(the planner's own time is not the server's: ``benchmarks/planner``). Each tick of each trial is timed per
phase:

- ``step``: the world step with the participant's controller and modelled KB (``TrialEngine.advance``);
- ``record``: the stored row (``server.game.records.tick_row``);
- ``mask``: the participant's masked ``state`` message (``server.game.snapshot.state``);
- ``json``: its serialisation (``model_dump_json``, as ``Connection.send`` does);
- ``to_worker``: pickling the decision request for the robot worker and unpickling it there (its IPC share);
- ``store``: committing the rows every 0.5 s of trial time (a temporary SQLite file, as ``BatchWriter``),
  with the renewal of every trial's lease (``store.lease``; ``--no-lease`` leaves it out, to see what it costs),
  per tick.

With ``--robot NAME`` (e.g. ``fov_aware``) the robot is that planner, run in this process, and two more
phases show the robot worker's share: ``robot`` (the decision, ``server.robots.choice.run_decision``) and
``reply`` (pickling its answer and unpickling it in the server).

Prints CPU µs per tick for each phase (``time.thread_time``: CPU time of this thread, so other work on a
busy machine does not count; median over 5 repetitions of the whole run) and what the total means
at 5 Hz: the share of one core that ``--trials`` trials cost the server process apart from websockets and
asyncio. ``--profile N`` prints the N most expensive functions (cProfile, cumulative) instead.
"""

from __future__ import annotations

import argparse
import cProfile
import pickle
import pstats
import random
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))

from planner.geometry import ACTIONS, Action  # noqa: E402
from planner.layout import parse_layout  # noqa: E402
from planner.rules import Rules  # noqa: E402
from planner.subtasks import Subtask  # noqa: E402
from server.game import snapshot  # noqa: E402
from server.game.engine import TrialEngine  # noqa: E402
from server.game.records import tick_row  # noqa: E402
from server.robots.choice import RobotChoice, run_decision  # noqa: E402
from store.engine import Store  # noqa: E402
from store.lease import Beat  # noqa: E402
from store.writer import write_batch  # noqa: E402

PHASES = ("step", "record", "mask", "json", "to_worker", "store")
ROBOT_PHASES = ("robot", "reply")
KITCHENS = ("none_3", "mid_2")


def make_trials(count: int, seed: int) -> list[TrialEngine]:
    rules = Rules(orders=2, horizon=400)
    folder = HERE.parents[1] / "study_config" / "layouts"
    layouts = [parse_layout((folder / f"{name}.layout").read_text(encoding="utf-8"), name=name) for name in KITCHENS]
    return [TrialEngine(layouts[i % len(layouts)], rules, angle=120.0, kb_delay=3, seed=seed + i)
            for i in range(count)]


def run(trials: int, ticks: int, seed: int, store: Store, timer: Callable[[], float] = time.thread_time,
        robot: str | None = None, lease: bool = True) -> dict[str, float]:
    """Seconds spent per phase over ``ticks`` ticks of ``trials`` trials (``trial_id`` 1..trials)."""
    rng = random.Random(seed)
    engines = make_trials(trials, seed)
    policies = []
    if robot is not None:
        from planner.robots import make_robot

        for engine in engines:
            policy = make_robot(robot, engine.layout, engine.rules)
            policy.reset(engine.world)
            policies.append(policy)
    spent = dict.fromkeys(PHASES + (ROBOT_PHASES if robot else ()), 0.0)
    rows: list[dict[str, Any]] = []
    flush_every = 3  # 0.5 s at 5 Hz
    for tick in range(ticks):
        for trial_id, engine in enumerate(engines, start=1):
            if engine.done:
                continue
            t0 = timer()
            payload = pickle.dumps(("decide", tick, trial_id, engine.world, engine.last_events, seed, tick, 0.0),
                                   protocol=pickle.HIGHEST_PROTOCOL)
            pickle.loads(payload)
            spent["to_worker"] += timer() - t0
            action = rng.choice(ACTIONS)
            if policies:
                r0 = timer()
                value, info = run_decision(policies[trial_id - 1], engine.world, engine.last_events, seed, tick,
                                           time.monotonic() + 60.0)
                r1 = timer()
                pickle.loads(pickle.dumps((tick, "ok", (value, info)), protocol=pickle.HIGHEST_PROTOCOL))
                spent["robot"] += r1 - r0
                spent["reply"] += timer() - r1
                action = Action(value)
            t1 = timer()
            outcome = engine.advance(action)
            t2 = timer()
            rows.append(tick_row(trial_id, outcome, RobotChoice(ACTIONS[0], decision_ms=3.0, info=None), 1.0,
                                 engine.controller.to_dict(), tick / 5.0))
            t3 = timer()
            message = snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=tick)
            t4 = timer()
            message.seq = tick + 1
            text = message.model_dump_json()
            t5 = timer()
            spent["step"] += t2 - t1
            spent["record"] += t3 - t2
            spent["mask"] += t4 - t3
            spent["json"] += t5 - t4
            assert text
            if engine.controller.subtask is None and message.available and rng.random() < 0.5:
                engine.controller.select(Subtask(rng.choice(message.available)), engine.world.human.held)
        if tick % flush_every == flush_every - 1 and rows:
            beats = [Beat(trial_id, 0, None, tick / 5.0, None) for trial_id, engine in enumerate(engines, start=1)
                     if not engine.done] if lease else []
            t0 = timer()
            write_batch(store, rows, [], beats)
            spent["store"] += timer() - t0
            rows = []
    return spent


def prepared_store(folder: Path, trials: int) -> Store:
    """A migrated SQLite store with one study, participant and trial row per simulated trial."""
    from store.tables import ParticipantRow, StudyRow, TrialRow

    store = Store(f"sqlite:///{folder / 'share.sqlite3'}")
    store.migrate()
    with store.transaction() as session:
        session.add(StudyRow(id="share", title="share", config_hash="x", config={}, orders=[]))
        session.flush()
        for i in range(1, trials + 1):
            session.add(ParticipantRow(id=i, public_id=f"p{i}", study_id="share", token_hash=f"t{i}",
                                       config_hash="x", plan=[], state="trial"))
            session.flush()
            session.add(TrialRow(id=i, study_id="share", participant_id=i, kind="main", index=0, condition_id="c",
                                 kitchen="k", robot="r", seed=i, config_hash="x", initial_state={}))
    return store


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description="The server's CPU per trial tick, phase by phase.")
    p.add_argument("--trials", type=int, default=60)
    p.add_argument("--ticks", type=int, default=300)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--profile", type=int, default=0, metavar="N", help="print the N top functions instead")
    p.add_argument("--robot", default=None, help="run this robot planner in-process (e.g. fov_aware)")
    p.add_argument("--no-lease", action="store_true", help="store the rows without renewing the trials' leases")
    args = p.parse_args(argv)
    results: list[dict[str, float]] = []
    with tempfile.TemporaryDirectory(prefix="steakhouse-share-") as tmp:
        for repeat in range(1 if args.profile else args.repeat):
            folder = Path(tmp) / str(repeat)
            folder.mkdir()
            store = prepared_store(folder, args.trials)
            profiler = cProfile.Profile() if args.profile else None
            if profiler is not None:
                profiler.enable()
            spent = run(args.trials, args.ticks, args.seed, store, robot=args.robot, lease=not args.no_lease)
            if profiler is not None:
                profiler.disable()
                pstats.Stats(profiler).sort_stats("cumulative").print_stats(args.profile)
                return 0
            store.dispose()
            results.append(spent)
    steps = args.trials * args.ticks
    per_tick = {phase: statistics.median(r[phase] for r in results) / steps * 1e6 for phase in results[0]}
    total = sum(per_tick[phase] for phase in PHASES)
    print(f"# {args.trials} trials × {args.ticks} ticks, median of {args.repeat} runs; CPU µs per trial tick"
          f"{' (leases not renewed)' if args.no_lease else ''}")
    for phase in PHASES:
        print(f"{phase:<10}{per_tick[phase]:>9.1f}")
    print(f"{'total':<10}{total:>9.1f}")
    print(f"at 5 Hz: {args.trials} trials cost {total * args.trials * 5 / 1e4:.1f} % of one core "
          "(server process, before websockets and asyncio)")
    if args.robot:
        robot = per_tick["robot"] + per_tick["reply"]
        for phase in ROBOT_PHASES:
            print(f"{phase:<10}{per_tick[phase]:>9.1f}")
        print(f"at 5 Hz: the {args.robot} robots of {args.trials} trials cost {robot * args.trials * 5 / 1e4:.1f} % "
              "of one core (robot workers, with their pickling; the server pickles its side in to_worker)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
