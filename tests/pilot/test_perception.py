"""The simulated participant knows only what its frames show, and knows it as the study's KB rule says."""

from __future__ import annotations

from dataclasses import replace

import pytest
from offline import play_offline

from pilot.client import respond
from pilot.config import ParticipantConfig
from pilot.mind import Mind
from pilot.perception import Perception, UnknownKitchen
from planner.fov import view
from planner.geometry import Direction
from planner.state import AgentState, initial_state
from server.game import snapshot
from server.game.engine import TrialEngine
from server.game.needs import NEEDS


@pytest.mark.parametrize("kitchen", ["none_3", "mid_2"])
@pytest.mark.parametrize("seed", [1, 2])
def test_the_kb_built_from_frames_is_the_servers_model_of_the_participant(paper, kitchen: str, seed: int) -> None:
    """On every cell the frame shows, the KB it builds from the masked frames alone agrees with the KB the server
    models for the participant (stations occupied or not, objects on counters, the robot's cargo and where it was
    last seen while the robot is in view). Not always out of view: the
    reference's rule, which the server models, follows objects the frames do not show (docs/domain.md §3: what a
    watched robot lets go of is guessed to have become the last object of a kind, even one out of view; an object
    carried off unseen is tracked by its identity)."""
    trial = play_offline(paper, kitchen, ParticipantConfig(), seed)
    layout = paper.layout(kitchen)
    assert len(trial.perceptions) > 20
    for tick, (seen, server, frame) in enumerate(zip(trial.perceptions, trial.server_kbs, trial.frames, strict=True)):
        mine = seen.kb
        assert mine is not None
        shown = {(c["x"], c["y"]) for c in frame["cells"]}
        differing = {cell for name, cells in (("grills", layout.grills), ("boards", layout.boards),
                                              ("sinks", layout.sinks))
                     for cell, a, b in zip(cells, getattr(mine, name), getattr(server, name), strict=True)
                     if (a is None) != (b is None)}
        differing |= set(dict(mine.objects).items() ^ dict(server.objects).items())
        differing = {c[0] if isinstance(c[0], tuple) else c for c in differing}
        assert not differing & shown, (tick, differing & shown)
        if frame.get("robot") is not None:
            assert (mine.robot.pos, mine.robot.held) == (server.robot.pos, server.robot.held), tick


def test_worlds_that_differ_only_out_of_view_get_the_same_answer(paper) -> None:
    """Two worlds identical in the participant's view but not behind them: the frames are equal, and so is what
    the simulated participant does (it has nothing else to go on)."""
    layout = paper.layout("none_3")
    engine = TrialEngine(layout, paper.rules, angle=120, kb_delay=3, seed=0)
    world = engine.world
    hidden = [p for p in layout.counters if p not in view(layout, world.human.pos, world.human.facing, 120).cells]
    other = replace(world, objects=((hidden[0], "onion"),), grills=(5,) + world.grills[1:],
                    robot=AgentState(world.robot.pos, Direction.SOUTH, "meat")
                    if world.robot.pos not in view(layout, world.human.pos, world.human.facing, 120).cells
                    else world.robot)
    answers = []
    for w in (world, other):
        engine.world = w
        frame = snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json")
        seen = Perception(layout.width, layout.height, tuple(paper.layouts.values()))
        import numpy as np
        needs = {s.value: n for s, n in NEEDS.items()}
        _, _, body = respond(Mind(), seen, frame, needs, paper, ParticipantConfig(decision_latency_ticks=0),
                             np.random.default_rng(7))
        answers.append((frame, body))
    assert answers[0][0] == answers[1][0]
    assert answers[0][1] == answers[1][1]


def test_it_recognises_its_kitchen_from_the_walls_it_sees(paper) -> None:
    for kitchen in ("none_3", "mid_2"):
        layout = paper.layout(kitchen)
        engine = TrialEngine(layout, paper.rules, angle=120, kb_delay=3, seed=0,
                             world=initial_state(layout, paper.rules))
        frame = snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json")
        seen = Perception(layout.width, layout.height, tuple(paper.layouts.values())).observe(frame, 120, 3)
        assert seen.layout.name == layout.name


def test_a_kitchen_not_in_the_study_is_reported(paper) -> None:
    layout = paper.layout("none_3")
    engine = TrialEngine(layout, paper.rules, angle=120, kb_delay=3, seed=0)
    frame = snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json")
    others = tuple(v for k, v in paper.layouts.items() if k != "none_3" and v.text() != layout.text())
    with pytest.raises(UnknownKitchen):
        Perception(layout.width, layout.height, others).observe(frame, 120, 3)
