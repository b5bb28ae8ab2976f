"""The trial engine: a participant choosing subtasks delivers a dish; the modelled KB, gap and FOV facts
of each tick; determinism by seed; a stored tick resumes to the same future."""

from __future__ import annotations

from planner.geometry import Action
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.rules import Rules
from planner.state import WorldState
from planner.summary import gap_components, summarize
from server.game.controller import ParticipantController
from server.game.engine import TickOutcome, TrialEngine
from study_config import load_layout

RULES = Rules(orders=1, horizon=200)


def play(engine: TrialEngine, limit: int = 200) -> list[TickOutcome]:
    outcomes: list[TickOutcome] = []
    while not engine.done and len(outcomes) < limit:
        if engine.controller.subtask is None:
            engine.controller.select(engine.controller.available(engine.world, engine.kb)[0], engine.world.human.held)
        outcomes.append(engine.advance(Action.STAY))
    return outcomes


def test_choosing_available_subtasks_delivers_the_order():
    layout = load_layout("practice")
    engine = TrialEngine(layout, RULES, angle=120.0, kb_delay=3, seed=5)
    outcomes = play(engine)
    assert engine.done and engine.world.orders_left == 0 and engine.world.score == 20
    assert [o.tick for o in outcomes] == list(range(1, len(outcomes) + 1))
    assert {o.source for o in outcomes} == {"subtask"}


def test_each_tick_reports_the_kb_the_gap_and_the_robot_in_view():
    layout = load_layout("none_3")
    engine = TrialEngine(layout, RULES, angle=120.0, kb_delay=3, seed=1)
    kb = initial_kb(engine.world)
    for outcome in play(engine, limit=60):
        kb = update_kb(kb, layout, outcome.world, angle=120.0, kb_delay=3,
                       own_events=[e for e in outcome.events if e.agent == "human"])
        assert outcome.kb == kb
        assert outcome.gap == gap_components(summarize(kb, RULES), summarize(outcome.world, RULES))
        assert outcome.kb_summary == summarize(kb, RULES).to_dict()
        human = outcome.world.human
        from planner.fov import view

        assert outcome.robot_in_fov == (outcome.world.robot.pos in view(layout, human.pos, human.facing, 120.0).cells)


def test_same_seed_same_trial_and_resume_from_a_stored_tick():
    layout = load_layout("mid_2")
    first = TrialEngine(layout, RULES, angle=120.0, kb_delay=3, seed=9)
    full = play(first, limit=80)
    again = TrialEngine(layout, RULES, angle=120.0, kb_delay=3, seed=9)
    assert [o.world for o in play(again, limit=80)] == [o.world for o in full]
    stored = full[29]
    resumed = TrialEngine(layout, RULES, angle=120.0, kb_delay=3, seed=9,
                          world=WorldState.from_dict(stored.world.to_dict()),
                          kb=KnowledgeBase.from_dict(stored.kb.to_dict()),
                          controller=ParticipantController.from_dict(
                              {"subtask": stored.subtask.value if stored.subtask and not stored.subtask_finished
                               else None, "last": stored.subtask.value if stored.subtask else None},
                              layout, RULES, 120.0))
    assert resumed.kb == stored.kb
    assert [o.world for o in play(resumed, limit=50)] == [o.world for o in full[30:80]]
