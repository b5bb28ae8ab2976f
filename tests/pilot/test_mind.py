"""The simulated participant's choices: latency, the simulated human's rule, and interrupts as the paper's
participants made them (stop or replace a subtask that what it now sees makes pointless; one-step corrections;
stepping aside from the robot)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
from offline import play_offline

from pilot.client import respond
from pilot.config import ParticipantConfig
from pilot.mind import Mind, belief_of, decide, read_refusal, told_refused
from pilot.perception import Perception
from planner.geometry import DIRECTIONS, Direction, Pos
from planner.layout import Layout
from planner.objects import MEAT
from planner.state import AgentState
from planner.subtasks import Subtask
from server.game import snapshot
from server.game.engine import TrialEngine
from server.game.needs import NEEDS
from study_config.catalog import LoadedStudy

NEEDS_BY_NAME = {s.value: n for s, n in NEEDS.items()}


def beside(layout: Layout, target: Pos) -> tuple[Pos, Direction]:
    """A floor cell next to ``target`` and the direction that faces it."""
    for d in DIRECTIONS:
        cell = (target[0] - d.vector[0], target[1] - d.vector[1])
        if 0 <= cell[0] < layout.width and 0 <= cell[1] < layout.height and layout.is_floor(cell):
            return cell, d
    raise AssertionError(f"no floor next to {target}")


def frames_until_reply(loaded: LoadedStudy, engine: TrialEngine, config: ParticipantConfig,
                       frames: int) -> list[dict[str, Any]]:
    """The messages answering ``frames`` frames, one a tick, of a world that stands still (the participant
    watching)."""
    layout = engine.layout
    seen = Perception(layout.width, layout.height, tuple(loaded.layouts.values()))
    mind = Mind(last=engine.controller.subtask)
    rng = np.random.default_rng(3)
    out = []
    for tick in range(frames):
        frame = {**snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json"), "tick": tick}
        seen, mind, body = respond(mind, seen, frame, NEEDS_BY_NAME, loaded, config, rng)
        out.append(body)
    return out


def idle_on_the_paper_clock(loaded: LoadedStudy, engine: TrialEngine,
                            **believed: Any) -> tuple[dict[str, Any], Perception]:
    """The frame of a cook with no task running on the paper's clock (tick 7), and what it knows from it, with the
    station statuses in ``believed`` (e.g. ``grills=(10,)``) taken as known."""
    engine.controller.subtask = None
    layout = engine.layout
    frame = {**snapshot.state(engine, mode="wait_for_participant", rate=5.0, ack=0).model_dump(mode="json"),
             "tick": 7}
    seen = Perception(layout.width, layout.height, tuple(loaded.layouts.values())).observe(frame, 120.0, 3)
    assert seen.kb is not None
    return frame, replace(seen, kb=replace(seen.kb, **believed))


def carrying_meat_to_a_busy_grill(loaded: LoadedStudy) -> TrialEngine:
    layout = loaded.layout("none_3")
    engine = TrialEngine(layout, loaded.rules, angle=120, kb_delay=3, seed=0)
    pos, facing = beside(layout, layout.grills[0])
    world = engine.world
    engine.world = replace(world, human=AgentState(pos, facing, MEAT), grills=(4,) * len(layout.grills))
    engine.controller.select(Subtask.DROP_MEAT, MEAT)
    return engine


def test_it_stops_a_subtask_once_it_sees_the_grill_is_busy(paper) -> None:
    engine = carrying_meat_to_a_busy_grill(paper)
    config = ParticipantConfig(notice_probability=1.0, stop_weight=1, replace_weight=0, correct_weight=0)
    delay = paper.study.world.kb_delay
    replies = frames_until_reply(paper, engine, config, delay + 1)
    assert [r["type"] for r in replies[:delay - 1]] == ["heartbeat"] * (delay - 1), "the KB needs kb_delay frames"
    assert replies[delay - 1] == {"type": "interrupt", "action": "stop"}


def test_it_replaces_a_pointless_subtask_with_one_that_fits_its_hands(paper) -> None:
    engine = carrying_meat_to_a_busy_grill(paper)
    config = ParticipantConfig(notice_probability=1.0, stop_weight=0, replace_weight=1, correct_weight=0,
                               error_rate=0.0)
    reply = frames_until_reply(paper, engine, config, 3)[2]
    assert reply == {"type": "select_subtask", "subtask": "drop_on_counter"}


def test_it_corrects_in_one_step_by_putting_the_meat_on_a_free_counter(paper) -> None:
    """It has seen the grill busy; now facing a free counter with the meat, it puts the meat down there."""
    engine = carrying_meat_to_a_busy_grill(paper)
    layout = engine.layout
    seen = Perception(layout.width, layout.height, tuple(paper.layouts.values()))
    mind, rng = Mind(last=Subtask.DROP_MEAT), np.random.default_rng(3)
    watching = ParticipantConfig(notice_probability=0.0)
    for tick in range(3):
        frame = {**snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json"), "tick": tick}
        seen, mind, _ = respond(mind, seen, frame, NEEDS_BY_NAME, paper, watching, rng)
    counter = next(c for c in layout.counters if _reachable_side(layout, c))
    pos, facing = beside(layout, counter)
    engine.world = replace(engine.world, human=AgentState(pos, facing, MEAT))
    frame = {**snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json"), "tick": 3}
    correcting = ParticipantConfig(notice_probability=1.0, stop_weight=0, replace_weight=0, correct_weight=1)
    _, _, body = respond(mind, seen, frame, NEEDS_BY_NAME, paper, correcting, rng)
    assert body == {"type": "interrupt", "action": "interact"}


def _reachable_side(layout: Layout, cell: Pos) -> bool:
    return any(0 <= cell[0] - d.vector[0] < layout.width and 0 <= cell[1] - d.vector[1] < layout.height
               and layout.is_floor((cell[0] - d.vector[0], cell[1] - d.vector[1])) for d in DIRECTIONS)


def test_it_waits_its_decision_latency_before_choosing(paper) -> None:
    layout = paper.layout("mid_2")
    engine = TrialEngine(layout, paper.rules, angle=120, kb_delay=3, seed=0)
    replies = frames_until_reply(paper, engine, ParticipantConfig(decision_latency_ticks=4, error_rate=0.0), 4)
    assert [r["type"] for r in replies] == ["heartbeat"] * 3 + ["select_subtask"]
    assert replies[3]["subtask"] in {"pickup_meat", "pickup_onion", "pickup_plate"}


def test_whole_trials_have_interrupts_and_get_the_dishes_out(paper) -> None:
    """Over a few offline trials with the default parameters it interrupts (the paper's second measure is
    not all zeros) and still delivers."""
    interrupts, delivered = 0, 0
    for seed in range(4):
        for kitchen in ("none_3", "mid_2"):
            trial = play_offline(paper, kitchen, ParticipantConfig(), seed)
            interrupts += sum(1 for s in trial.sent if s["type"] == "interrupt")
            delivered += paper.rules.orders - trial.engine.world.orders_left
    assert interrupts > 0
    assert delivered >= 8


def test_a_frame_sent_again_at_the_same_tick_teaches_nothing(paper) -> None:
    """The paper's clock tells a refused step with the unchanged state: the KB rule counts ticks, not frames."""
    engine = carrying_meat_to_a_busy_grill(paper)
    layout = engine.layout
    seen = Perception(layout.width, layout.height, tuple(paper.layouts.values()))
    frame = snapshot.state(engine, mode="wait_for_participant", rate=5.0, ack=0).model_dump(mode="json")
    once = seen.observe(frame, 120.0, 3)
    assert once.observe(frame, 120.0, 3) is once


def test_a_task_the_page_refused_is_not_chosen_again_while_it_believes_the_same_of_its_places(paper) -> None:
    """Holding a clean plate its rule offers only Pick up steak; told the robot took the steak, it does something
    else that fits its hands for as long as it believes what it believed then of the grills, and chooses the task
    again once it knows something new of them (it saw the grill)."""
    engine = carrying_meat_to_a_busy_grill(paper)
    engine.world = replace(engine.world, human=replace(engine.world.human, held="clean_plate"))
    layout = engine.layout
    frame, seen = idle_on_the_paper_clock(paper, engine, grills=(10,) * len(layout.grills))  # a steak is there
    config = ParticipantConfig(error_rate=0.0, decision_latency_ticks=0)

    def chosen(mind: Mind, state: dict[str, Any], seed: int, knows: Perception = seen) -> tuple[str, Mind]:
        reply, after = decide(mind, knows, state, NEEDS_BY_NAME, paper.rules, config, np.random.default_rng(seed))
        return str(reply.body()["subtask"]), after

    assert chosen(Mind(), frame, 0)[0] == "pickup_steak", "its rule offers only this"
    assert seen.kb is not None
    told = told_refused(Mind(), Subtask.PICKUP_STEAK, belief_of(layout, paper.rules, seen.kb, Subtask.PICKUP_STEAK))
    assert {chosen(told, {**frame, "tick": tick}, seed)[0] for tick in (7, 8, 30) for seed in range(10)} == {
        "drop_on_counter"}, "the note holds while nothing new is known of the grills"
    saw = replace(seen, kb=replace(seen.kb, grills=(3,) * len(layout.grills)))  # it saw a new steak cooking there
    again, mind = chosen(told, {**frame, "tick": 31}, 0, saw)
    assert again == "pickup_steak" and not mind.refused


def test_after_waiting_at_an_onion_nobody_chops_it_asks_for_the_garnish_again_only_once_it_is_chopped(paper) -> None:
    """Holding a steak plate its rule offers only Pick up garnish; on the paper's clock the page says the onion is not
    chopped yet, and it waits. If nothing changed at the board meanwhile (nobody chopped), it does something else that
    fits its hands rather than ask again (a loaded run once asked 15 times in a round, pressing "." 243 times, and was
    screened out for refused tasks); once it sees the onion chopped it asks again. Where the world goes on without
    it, the refusal is not noted: time answers it."""
    engine = carrying_meat_to_a_busy_grill(paper)
    layout = engine.layout
    pos, facing = beside(layout, layout.boards[0])
    engine.world = replace(engine.world, human=AgentState(pos, facing, "steak_plate"),
                           boards=(0,) * len(layout.boards))
    frame, seen = idle_on_the_paper_clock(paper, engine, boards=(0,) * len(layout.boards))  # an onion, not chopped
    config = ParticipantConfig(error_rate=0.0, decision_latency_ticks=0)

    def chosen(mind: Mind, knows: Perception, seed: int) -> str:
        reply, _ = decide(mind, knows, {**frame, "tick": 30}, NEEDS_BY_NAME, paper.rules, config,
                          np.random.default_rng(seed))
        return str(reply.body()["subtask"])

    assert chosen(Mind(), seen, 0) == "pickup_garnish", "its rule offers only this"
    waited = read_refusal(Mind(), seen, Subtask.PICKUP_GARNISH, "not_chopped", paper.rules, waits=True)
    assert {chosen(waited, seen, seed) for seed in range(10)} == {"drop_on_counter"}
    assert seen.kb is not None
    chopped = replace(seen, kb=replace(seen.kb, boards=(paper.rules.chop_time,) * len(layout.boards)))
    assert chosen(waited, chopped, 0) == "pickup_garnish", "the onion is chopped now: it asks again"
    world_goes_on = read_refusal(Mind(), seen, Subtask.PICKUP_GARNISH, "not_chopped", paper.rules, waits=False)
    assert world_goes_on == Mind() and chosen(world_goes_on, seen, 0) == "pickup_garnish"
