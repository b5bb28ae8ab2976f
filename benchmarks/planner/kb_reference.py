"""Our KB and KB gap against the reference implementation's own functions, state by state.

The reference (SophieHsu/FOV-aware-planner, MIT licence; fetched, never copied here) keeps the person's KB in
``SteakLimitVisionHumanModel.update`` (``overcooked_ai_py/agents/agent.py``), reduces it with ``get_kb_key`` /
``kb_to_state_info``, reduces the world with ``update_world_kb_log`` (``overcooked_ai_py/planning/planners.py``)
and measures the gap with ``kb_diff_measure`` (``overcooked_ai_py/vr_analysis.py``). This script runs those
functions, imported from the fetched repository, on

* **our trials** (``--kitchens``, ``--robots``, ``--seeds``, ``--delays``): each played headless
  (:func:`planner.play.run_trial`), replayed with :func:`planner.step.step` and every state converted to the
  reference's state format (object identities from both agents' step events, objects in the order they arrived
  where they lie, ``players = [robot, person]``), and
* **the paper's VR study logs** (``overcooked_ai_py/data/logs/vr_study_logs``, read as
  ``benchmarks/planner/vr_logs.py`` reads them): each decision step's state as the reference's own replay
  (``VRtoOvercookedMapper``) makes it, converted to our world state on the reference's own grid;

and compares, state by state, the KB and the world as the reference reduces them (grill, board, sink, what the
robot holds) and the gap's four components, with ours (:func:`planner.kb.update_kb`,
:mod:`planner.summary`), and each trial's ``kb_diff_freq`` / ``kb_diff_avg``. The reference's in-view test is
given the half-angle ``acos(1/√3)`` (``--vision-bound`` 109.47°), at which it sees exactly the cells of our 120°
cone (checked over every offset up to 20 cells before anything runs).

It needs an environment with the reference's imports (numpy < 2, scipy, pandas < 2.3, gym 0.26, tqdm, pygame,
toml; ``torch``, imported by ``agent.py`` but never used on this path, is given an empty module) and this
repository on ``PYTHONPATH``; ``PYTHONHASHSEED`` fixes the reference's set order (its rule can depend on it).

    PYTHONHASHSEED=0 PYTHONPATH=. SCRATCH/venv/bin/python benchmarks/planner/kb_reference.py \\
        /work/scratch/ref --fixture tests/planner/kb_reference.json

``--fixture`` writes our trials' actions with the reference's outputs (``tests/planner/test_kb_reference.py``
replays them through our functions); the VR logs are only compared and counted.
"""

from __future__ import annotations

import argparse
import ast
import json
import math
import subprocess
import sys
import types
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from benchmarks.planner.vr_logs import Source, log_files
from planner.events import Event, EventKind
from planner.fov import in_view
from planner.geometry import Action, Direction
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout, Terrain, parse_layout
from planner.planner_config import PlannerConfig
from planner.play import TrialSettings, run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.step import step
from planner.summary import kb_diff, kb_diff_trial, reference_key
from study_config import load_layout

VISION_BOUND = 2 * math.degrees(math.acos(1 / math.sqrt(3)))
REF_NAMES = {"meat": "meat", "onion": "onion", "dirty_plate": "plate", "clean_plate": "hot_plate",
             "steak_plate": "steak", "dish": "dish"}
OUR_NAMES = {v: k for k, v in REF_NAMES.items()}
ACTION_CODES = {a: a.value[0] if a is not Action.STAY else "x" for a in Action}
ACTION_OF_CODE = {c: a for a, c in ACTION_CODES.items()}
VR_KITCHENS = {"none": "steak_none_3", "mid": "steak_mid_2"}


def load_reference(path: Path) -> types.SimpleNamespace:
    """The reference's modules and functions, imported from the fetched repository at ``path``."""
    sys.modules.setdefault("torch", types.ModuleType("torch"))
    sys.path.insert(0, str(path))
    from overcooked_ai_py.agents import agent
    from overcooked_ai_py.mdp import overcooked_mdp
    from overcooked_ai_py.planning import planners

    source = (path / "overcooked_ai_py/vr_analysis.py").read_text(encoding="utf-8")
    namespace: dict[str, Any] = {"np": __import__("numpy"), "OvercookedState": overcooked_mdp.OvercookedState}
    tree = ast.parse(source)
    wanted: list[ast.stmt] = [n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))
                              and n.name in ("kb_diff_measure", "VRtoOvercookedMapper")]
    exec(compile(ast.Module(body=wanted, type_ignores=[]), str(path / "overcooked_ai_py/vr_analysis.py"), "exec"),
         namespace)
    commit = subprocess.run(["git", "-C", str(path), "rev-parse", "HEAD"], capture_output=True, text=True).stdout
    return types.SimpleNamespace(agent=agent, mdp=overcooked_mdp, planners=planners, ns=namespace,
                                 commit=commit.strip())


def check_fov(ref: types.SimpleNamespace) -> None:
    """The reference's in-view test at ``VISION_BOUND`` sees exactly our 120° cone (every offset up to 20)."""
    model = object.__new__(ref.agent.SteakLimitVisionHumanModel)
    model.agent_index = 1
    for facing in Direction:
        player = ref.mdp.PlayerState((30, 30), facing.vector)
        state = types.SimpleNamespace(players=(player, player))
        for dx in range(-20, 21):
            for dy in range(-20, 21):
                theirs = bool(model.in_bound(state, (30 + dx, 30 + dy), vision_bound=VISION_BOUND / 2))
                ours = in_view((30, 30), facing, (30 + dx, 30 + dy), 120.0)
                if theirs != ours:
                    raise SystemExit(f"FOV differs at offset {(dx, dy)} facing {facing.value}")


class Ids:
    """Object identities as the reference's world assigns them, from both agents' step events."""

    def __init__(self) -> None:
        self.lying: dict[tuple[int, int], list[Any]] = {}
        self.hands: dict[str, list[Any] | None] = {"robot": None, "human": None}
        self.count = 0

    def new(self, name: str) -> list[Any]:
        self.count += 1
        return [self.count - 1, name]

    def apply(self, events: tuple[Event, ...]) -> None:
        for e in events:
            a, pos, k = e.agent, e.pos, e.kind
            if k is EventKind.PICK_UP or k is EventKind.TAKE_CLEAN_PLATE or k is EventKind.PLATE_STEAK:
                self.hands[a] = self.lying.pop(pos)
            elif k is EventKind.PUT_DOWN:
                self.lying[pos] = self.hands[a]  # type: ignore[assignment]
                self.hands[a] = None
            elif k is EventKind.SWAP:
                there = self.lying.pop(pos)
                self.lying[pos] = self.hands[a]  # type: ignore[assignment]
                self.hands[a] = there
            elif k is EventKind.DISPENSE:
                self.hands[a] = self.new(REF_NAMES[str(e.obj)])
            elif k in (EventKind.START_COOKING, EventKind.LOAD_BOARD, EventKind.LOAD_SINK):
                self.hands[a] = None
                name = {EventKind.START_COOKING: "steak", EventKind.LOAD_BOARD: "garnish"}.get(k, "hot_plate")
                self.lying[pos] = self.new(name)
            elif k is EventKind.GARNISH:
                self.lying.pop(pos)
                self.hands[a] = self.new("dish")
            elif k is EventKind.DELIVER:
                self.hands[a] = None

    def state(self, layout: Layout, world: WorldState) -> dict[str, Any]:
        """The reference's ``OvercookedState.to_dict()`` of ``world``."""
        counts = {c: v for cells, vals in ((layout.grills, world.grills), (layout.boards, world.boards),
                                           (layout.sinks, world.sinks)) for c, v in zip(cells, vals, strict=True)}
        objects = []
        for pos, (ident, name) in self.lying.items():
            value = counts.get(pos)
            state = ("steak", 1, value) if name == "steak" else value
            objects.append({"id": ident, "name": name, "position": pos, "state": state})
            if value is None and pos in counts:
                raise AssertionError(f"tick {world.tick}: {name} at an empty station {pos}")
        if len(objects) != len(world.objects) + sum(v is not None for v in counts.values()):
            raise AssertionError(f"tick {world.tick}: identities disagree with the world")
        return {"players": [self._player(world.robot, "robot"), self._player(world.human, "human")],
                "objects": objects, "order_list": ["steak"] * world.orders_left}

    def _player(self, agent: AgentState, name: str) -> dict[str, Any]:
        held = self.hands[name]
        if (held is None) != (agent.held is None) or (held is not None and held[1] != REF_NAMES[str(agent.held)]):
            raise AssertionError(f"{name}'s hands: {held} against {agent.held}")
        obj = None
        if held is not None:
            state = ("steak", 1, 10) if held[1] == "steak" else None
            obj = {"id": held[0], "name": held[1], "position": agent.pos, "state": state}
        return {"position": agent.pos, "orientation": agent.facing.vector, "held_object": obj}


@dataclass
class Tally:
    states: int = 0
    kb_same: int = 0
    world_same: int = 0
    gap_same: int = 0
    with_gap: int = 0
    trials: int = 0
    trial_same: int = 0
    examples: list[str] = field(default_factory=list)
    causes: Counter[str] = field(default_factory=Counter)


def grid_of(layout: Layout) -> list[str]:
    rows = [list(r) for r in layout.rows]
    for agent, char in (("robot", "1"), ("human", "2")):
        x, y = layout.start(agent)
        rows[y][x] = char
    return ["".join(r) for r in rows]


def reference_mdp(ref: types.SimpleNamespace, grid: list[str], rules: Rules) -> Any:
    params = {"cook_time": rules.cook_time, "chop_time": rules.chop_time, "wash_time": rules.wash_time,
              "num_items_for_steak": 1, "start_order_list": ["steak"] * rules.orders, "delivery_reward": 20}
    return ref.mdp.SteakHouseGridworld.from_grid(grid, params)


def reference_run(ref: types.SimpleNamespace, mdp: Any, states: list[dict[str, Any]], delay: int,
                  vision_bound: float) -> tuple[list[str], list[str], Any]:
    """The reference's human KB keys and world keys for ``states`` (the first is the start) and its gap."""
    objs = [ref.mdp.OvercookedState.from_dict(s) for s in states]
    human = ref.agent.SteakLimitVisionHumanModel(types.SimpleNamespace(mdp=mdp), objs[0], vision_bound=vision_bound,
                                                 kb_update_delay=delay)
    human.set_agent_index(1)
    world_log = object.__new__(ref.planners.SteakKnowledgeBasePlanner)
    world_log.mdp, world_log.world_kb_log = mdp, []
    for t, state in enumerate(objs[1:], start=1):
        try:
            human.update(state)
        except (IndexError, AttributeError, KeyError, ValueError) as exc:
            raise ReferenceFailed(t, f"{type(exc).__name__}: {exc}") from exc
        human.update_kb_log()
        world_log.update_world_kb_log(state)
    return human.kb_log, world_log.world_kb_log, ref.ns["kb_diff_measure"](human.kb_log, world_log.world_kb_log)


class ReferenceFailed(Exception):
    """The reference's update raised at state ``t`` (1-based) of a run."""

    def __init__(self, t: int, what: str) -> None:
        super().__init__(f"state {t}: {what}")
        self.t = t


def ours(layout: Layout, worlds: list[WorldState], events: list[tuple[Event, ...]], delay: int,
         angle: float = 120.0) -> tuple[list[str], list[str]]:
    kb: KnowledgeBase = initial_kb(worlds[0])
    kbs, ws = [], []
    for world, evs in zip(worlds[1:], events, strict=True):
        kb = update_kb(kb, layout, world, angle=angle, kb_delay=delay,
                       own_events=[e for e in evs if e.agent == "human"])
        kbs.append(reference_key(kb))
        ws.append(reference_key(world))
    return kbs, ws


def compare(tally: Tally, label: str, our_kb: list[str], our_w: list[str], ref_kb: list[str], ref_w: list[str],
            ref_gap: Any) -> None:
    tally.trials += 1
    tally.with_gap += sum(any(r) for r in ref_gap[0])
    ok = True
    for t, (a, b, c, d) in enumerate(zip(our_kb, ref_kb, our_w, ref_w, strict=True)):
        tally.states += 1
        tally.kb_same += a == b
        tally.world_same += c == d
        same_gap = list(kb_diff(a, c).values()) == [int(v) for v in ref_gap[0][t]]
        tally.gap_same += same_gap
        if a != b or c != d or not same_gap:
            ok = False
            if len(tally.examples) < 12:
                tally.examples.append(f"{label} t={t + 1}: ours kb {a} world {c}; reference kb {b} world {d}")
    freq, avg, _mean = kb_diff_trial([kb_diff(a, c) for a, c in zip(our_kb, our_w, strict=True)])
    ref_avg = ref_gap[3] if any(sum(r) for r in ref_gap[0]) else None
    same_trial = round(freq, 2) == ref_gap[2] and (avg is None) == (ref_avg is None) and (
        avg is None or round(avg, 2) == ref_avg)
    tally.trial_same += ok and same_trial


def our_trial(layout: Layout, robot: str, seed: int, delay: int) -> tuple[list[WorldState], list[tuple[Event, ...]],
                                                                          str]:
    settings = TrialSettings(angle=120.0, kb_delay=delay)
    cfg = PlannerConfig(human_angle=120.0, human_delay=delay)
    partner = None if robot == "partner" else make_robot(robot, layout, settings.rules, cfg)
    result = run_trial(layout, seed, settings, robot=partner, record=True)
    world = initial_state(layout, settings.rules)
    worlds, events = [world], []
    for h, r in result.actions:
        world, evs = step(layout, world, {"human": h, "robot": r}, settings.rules)
        worlds.append(world)
        events.append(evs)
    codes = "".join(ACTION_CODES[h] + ACTION_CODES[r] for h, r in result.actions)
    return worlds, events, codes


def run_ours(ref: types.SimpleNamespace, args: argparse.Namespace, tally: Tally) -> list[dict[str, Any]]:
    rules = Rules()
    trials = []
    for kitchen in args.kitchens.split(","):
        layout = load_layout(kitchen)
        mdp = reference_mdp(ref, grid_of(layout), rules)
        for robot in args.robots.split(","):
            for seed in range(args.seeds):
                for delay in (int(d) for d in args.delays.split(",")):
                    worlds, events, codes = our_trial(layout, robot, seed, delay)
                    ids = Ids()
                    states = [ids.state(layout, worlds[0])]
                    for world, evs in zip(worlds[1:], events, strict=True):
                        ids.apply(evs)
                        states.append(ids.state(layout, world))
                    ref_kb, ref_w, gap = reference_run(ref, mdp, states, delay, args.vision_bound)
                    our_kb, our_w = ours(layout, worlds, events, delay)
                    compare(tally, f"{kitchen}/{robot}/{seed}/d{delay}", our_kb, our_w, ref_kb, ref_w, gap)
                    trials.append({"kitchen": kitchen, "robot": robot, "seed": seed, "delay": delay,
                                   "actions": codes, "kb": ref_kb, "world": ref_w,
                                   "diff": "".join(str(int(v)) for row in gap[0] for v in row),
                                   "kb_diff_freq": gap[2], "kb_diff_avg": gap[3] if any(map(sum, gap[0])) else None})
    return trials


def vr_world(layout: Layout, state: Any, rules: Rules) -> WorldState:
    """Our world state of one reference state (on the reference's own grid)."""
    grills, boards, sinks = [None] * len(layout.grills), [None] * len(layout.boards), [None] * len(layout.sinks)
    objects = []
    for pos, obj in state.objects.items():
        terrain = layout.terrain(pos)
        if obj.name == "steak" and terrain is Terrain.GRILL:
            grills[layout.grills.index(pos)] = obj.state[2]
        elif obj.name == "garnish" and terrain is Terrain.BOARD:
            boards[layout.boards.index(pos)] = obj.state
        elif obj.name == "hot_plate" and terrain is Terrain.SINK:
            sinks[layout.sinks.index(pos)] = obj.state
        elif obj.name in OUR_NAMES and terrain is Terrain.COUNTER:
            objects.append((pos, OUR_NAMES[obj.name]))
    facing = {d.vector: d for d in Direction}
    robot, human = (AgentState(p.position, facing[tuple(p.orientation)],
                               None if p.held_object is None else OUR_NAMES.get(p.held_object.name))
                    for p in state.players)
    return WorldState(human=human, robot=robot, objects=tuple(sorted(objects)), grills=tuple(grills),
                      boards=tuple(boards), sinks=tuple(sinks), orders_left=len(state.order_list))


def run_vr(ref: types.SimpleNamespace, args: argparse.Namespace, tally: Tally) -> None:
    source = Source(args.reference)
    rules = Rules()
    for log_file in log_files(source.names(), include_ignored=False):
        log = source.read(log_file.path)
        if log is None:
            continue
        name = VR_KITCHENS[log_file.kitchen]
        grid = __import__("overcooked_ai_py").read_layout_dict(name)["grid"]
        rows = [r.strip() for r in grid.split("\n")]
        layout = parse_layout("\n".join(rows), name)
        mdp = reference_mdp(ref, rows, rules)
        ref.ns["log"] = log
        mapper = ref.ns["VRtoOvercookedMapper"]()
        states = [mdp.get_standard_start_state().to_dict()]
        for i in range(1, int(log["i"]) + 1):
            if str(i) not in log or "overcooked_state_sent" not in log[str(i)]:
                continue
            states.append(mapper.get_overcooked_state(i, mdp).to_dict())
        for delay in (int(d) for d in args.delays.split(",")):
            try:
                ref_kb, ref_w, gap = reference_run(ref, mdp, states, delay, args.vision_bound)
            except ReferenceFailed as failed:
                tally.causes[f"the reference's update raised ({failed}); compared up to the state before"] += 1
                states = states[:failed.t]
                ref_kb, ref_w, gap = reference_run(ref, mdp, states, delay, args.vision_bound)
            worlds = [vr_world(layout, ref.mdp.OvercookedState.from_dict(s), rules) for s in states]
            our_kb, our_w = ours(layout, worlds, [()] * (len(worlds) - 1), delay)
            compare(tally, f"vr {log_file.path}/d{delay}", our_kb, our_w, ref_kb, ref_w, gap)


def report(name: str, t: Tally) -> None:
    print(f"{name}: {t.states} states in {t.trials} trials; same KB {t.kb_same}, same world {t.world_same}, "
          f"same gap {t.gap_same} (states with a gap: {t.with_gap}); trials with every state and "
          f"kb_diff_freq/avg the same: {t.trial_same}")
    for cause, n in t.causes.items():
        print(f"    {n} x {cause}")
    for line in t.examples:
        print("   ", line)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference", type=Path, help="the fetched SophieHsu/FOV-aware-planner (a checkout)")
    parser.add_argument("--kitchens", default="none_3,mid_2,mid_1,side_1,none_1")
    parser.add_argument("--robots", default="fov_aware,baseline",
                        help="planner names, or partner (the simulated partner of planner.partner)")
    parser.add_argument("--seeds", type=int, default=2)
    parser.add_argument("--delays", default="1,3")
    parser.add_argument("--vision-bound", type=float, default=VISION_BOUND)
    parser.add_argument("--no-vr", action="store_true", help="skip the VR study logs")
    parser.add_argument("--fixture", type=Path, help="write our trials' actions and the reference's outputs")
    args = parser.parse_args(argv)
    ref = load_reference(args.reference)
    check_fov(ref)
    tally = Tally()
    trials = run_ours(ref, args, tally)
    report("our trials", tally)
    if not args.no_vr:
        vr = Tally()
        run_vr(ref, args, vr)
        report("VR study logs", vr)
    if args.fixture is not None:
        fixture = {"provenance": {
            "repository": "SophieHsu/FOV-aware-planner", "commit": ref.commit,
            "functions": ["overcooked_ai_py/agents/agent.py: SteakLimitVisionHumanModel.update, update_kb_log",
                          "overcooked_ai_py/planning/planners.py: SteakKnowledgeBasePlanner.update_world_kb_log",
                          "overcooked_ai_py/vr_analysis.py: kb_diff_measure"],
            "vision_bound": args.vision_bound, "command": " ".join(sys.argv),
            "actions": "per tick the person's then the robot's action: n s e w x(stay) i(interact)",
            "kb/world": "per tick the reference's key 'grill.board.sink.robot_held' (kb_log, world_kb_log)",
            "diff": "per tick the four components of kb_diff_measure's diff_measure row (grill, board, sink, robot)",
            "scratch": "venv: numpy<2, scipy<1.14, pandas<2.3, gym==0.26.2, tqdm, pygame, toml; torch stubbed; "
                       "PYTHONHASHSEED=0"},
            "trials": trials}
        args.fixture.write_text(json.dumps(fixture, separators=(",", ":")) + "\n", encoding="utf-8")
        print(f"wrote {args.fixture} ({args.fixture.stat().st_size} bytes)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
