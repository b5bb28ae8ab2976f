"""The data dictionary: every column of every exported file, with its type and meaning.

The export builds its tables in the column order given here, so a column cannot be exported undocumented.
Columns that depend on the study (questionnaire items, the between factors, the wide file's
``<measure>__<robot>__<kitchen>`` per within cell) are generated from the study's stored configuration.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from analysis.exports.dictionary_items import md_cell, questionnaire_items, questionnaire_markdown, questionnaire_scales
from analysis.measures.trial_measures import CONDUCT_COUNTS, TRIAL_MEASURES
from analysis.source.naming import item_key as item_column
from planner.summary import GAP_COMPONENTS


@dataclass(frozen=True, slots=True)
class Column:
    name: str
    type: str
    description: str


INT, NUM, TEXT, FLAG, TIME = "integer", "number", "text", "0/1", "timestamp (UTC, ISO 8601)"
WIDE_SEPARATOR = "__"

MEASURES: dict[str, Column] = {c.name: c for c in (
    Column("ticks", INT, "world steps played; the horizon when the orders were not all delivered (censored)"),
    Column("finished", FLAG, "1 when every order was delivered before the horizon"),
    Column("delivered", INT, "dishes delivered"),
    Column("score", INT, "score at the end (delivery reward per dish)"),
    Column("kb_diff_freq", NUM, "the paper's KB gap as its code computes it (docs/domain.md §6): % of ticks with a "
           "gap between the participant's modelled KB and the world in any of grill, board, sink, robot's held object"),
    Column("kb_diff_avg", NUM, "the paper's KB gap: mean gap over the ticks that have one (grill 0/1, board and sink "
           "|chop / wash count difference| with −1 for empty and a KB 3 above the world counting 1, robot's held "
           "object 0/1); empty when no tick has a gap"),
    Column("kb_diff_mean", NUM, "the paper's KB gap: mean gap over all ticks (= kb_diff_freq / 100 × kb_diff_avg)"),
    Column("kb_gap_mean", NUM, "our older status KB gap (secondary): mean per tick of the number of components "
           "(grill, board, sink status, robot's held object) where the participant's modelled KB differs from the "
           "world (docs/domain.md §6)"),
    Column("kb_gap_ticks_pct", NUM, "% of ticks with a KB gap in any component"),
    *(Column(f"kb_gap_{c}_pct", NUM, f"% of ticks where the {c.replace('_', ' ')} component of the KB differs "
                                     f"from the world (= its mean gap per tick × 100)") for c in GAP_COMPONENTS),
    Column("interrupts", INT, "interrupt actions the participant sent and the server accepted (up, down, left, "
                              "right, stay, interact, stop)"),
    Column("selections", INT, "subtasks the participant chose"),
    Column("interrupts_per_selection", NUM, "100 × interrupts / (interrupts + selections); empty when both are 0"),
    Column("robot_in_fov_pct", NUM, "% of ticks with the robot's cell in the participant's field of view"),
    Column("subtask_switches", INT, "times the participant replaced an unfinished, uncancelled subtask by another "
                                    "(see docs/analysis.md)"),
    Column("redundant_actions", INT, "pickups of meat / onion / dirty plate while every station for it was "
                                     "occupied and one had been loaded by the robot (see docs/analysis.md)"),
    Column("human_prep_pct", NUM, "% of the prep work the participant did: meat onto a grill, onion onto a "
                                  "board, dirty plate into a sink, chop and wash presses (the robot did the rest)"),
    Column("human_plating_pct", NUM, "% of the plating work the participant did: plating the steak, adding the "
                                     "garnish, delivering the dish"),
    Column("collisions", INT, "steps in which a move was cancelled because the participant and the robot would "
                              "have met"),
    Column("decision_ms_mean", NUM, "mean robot decision time in ms (request to answer, as the game loop saw it)"),
    Column("decision_ms_p95", NUM, "95th percentile of the robot decision time in ms"),
    Column("lateness_ms_mean", NUM, "mean tick lateness in ms (actual − scheduled start of a step)"),
    Column("lateness_ms_p99", NUM, "99th percentile of the tick lateness in ms"),
    Column("deadline_misses", INT, "ticks where the robot's decision missed its deadline (the robot stayed)"),
    Column("disconnects", INT, "times the participant's connection dropped during the trial"),
    Column("blurs", INT, "times the game tab lost focus during the trial"),
    Column("idle_events", INT, "idle reports from the participant's browser during the trial"),
    Column("errors", INT, "error events during the trial (rejected messages, robot errors)"),
    Column("stall_hints", INT, "hints the participant got because the team had got nothing done for "
           "timing.stall_hint_seconds"),
)}

UNITS: dict[str, str] = {
    "ticks": "world steps", "delivered": "dishes", "score": "points", "kb_gap_mean": "components",
    "kb_diff_freq": "%", "kb_diff_avg": "gap", "kb_diff_mean": "gap",
    "interrupts": "actions", "selections": "choices", "interrupts_per_selection": "%", "subtask_switches": "switches",
    "redundant_actions": "pickups", "collisions": "steps", "deadline_misses": "ticks",
    **{name: "%" for name in MEASURES if name.endswith("_pct")},
    **{name: "ms" for name in MEASURES if name.startswith(("decision_ms", "lateness_ms"))},
    **dict.fromkeys(CONDUCT_COUNTS, "events"),
}
"""Unit of each measure (axis labels of the analysis plots; the ``unit`` column of the dictionary)."""

_PARTICIPANT = Column("participant", TEXT, "participant's public id (random; not the recruiting id)")
_TRIAL_ID = Column("trial_id", INT, "trial attempt id in the store (trials.csv, ticks.csv)")
_ROBOT = Column("robot", TEXT, "robot planner of the condition (within factor)")
_KITCHEN = Column("kitchen", TEXT, "kitchen of the condition (within factor)")
_VIEW = Column("view", TEXT, "how the participant saw the kitchen: top_down or first_person (within factor when "
                             "the study lists views)")
_CONDITION_ID = ("condition id robot@kitchen (robot@kitchen@view with a view factor, …@angle with a field-of-view "
                 "factor)")
_FOV_ANGLE = Column("fov_angle", NUM, "the participant's field of view in degrees (a factor when the study lists "
                                      "fov_angles; empty for a trial stored before angles were recorded whose study "
                                      "has changed since)")

TICK_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT, _TRIAL_ID,
    Column("kind", TEXT, "practice or main"),
    Column("index", INT, "trial index within its kind (0-based, in the participant's order)"),
    Column("attempt", INT, "attempt number at this trial (a restarted trial has several)"),
    _ROBOT, _KITCHEN, _VIEW, _FOV_ANGLE,
    Column("tick", INT, "world step (1, 2, …)"),
    Column("human_action", TEXT, "the participant's avatar action in this step"),
    Column("robot_action", TEXT, "the robot's action in this step"),
    Column("action_source", TEXT, "where the avatar action came from: subtask, interrupt or idle"),
    Column("subtask", TEXT, "the participant's subtask when the step began (empty: none)"),
    Column("subtask_switch", FLAG, "1 when the participant switched subtask at this tick"),
    Column("redundant_action", FLAG, "1 when the participant started work the robot had already done"),
    Column("human_held", TEXT, "what the participant's avatar holds after the step"),
    Column("robot_held", TEXT, "what the robot holds after the step"),
    Column("grill", TEXT, "grill status(es) after the step: empty / cooking / ready, '|' between stations"),
    Column("board", TEXT, "board status(es): empty / chopping / ready"),
    Column("sink", TEXT, "sink status(es): empty / washing / clean"),
    Column("kb_robot_held", TEXT, "what the participant's modelled KB says the robot holds"),
    Column("kb_grill", TEXT, "grill status(es) in the participant's modelled KB"),
    Column("kb_board", TEXT, "board status(es) in the participant's modelled KB"),
    Column("kb_sink", TEXT, "sink status(es) in the participant's modelled KB"),
    Column("kb_diff_total", INT, "the paper's KB gap at this tick: the sum of kb_diff_<component> (0-8)"),
    *(Column(f"kb_diff_{c}", INT, f"the paper's KB gap in the {c.replace('_', ' ')} component at this tick "
                                  f"(docs/domain.md §6)") for c in GAP_COMPONENTS),
    Column("kb_gap_total", INT, "our status KB gap at this tick: number of differing components (0-4)"),
    *(Column(f"kb_gap_{c}", FLAG, f"1 when the KB's {c.replace('_', ' ')} differs from the world")
      for c in GAP_COMPONENTS),
    Column("robot_in_fov", FLAG, "1 when the robot's cell is in the participant's field of view"),
    Column("lateness_ms", NUM, "tick lateness in ms"),
    Column("decision_ms", NUM, "robot decision time in ms (empty: no decision)"),
    Column("robot_missed", FLAG, "1 when the robot's decision missed its deadline"),
    Column("recorded_at", TIME, "when the step was played"),
    Column("round_seconds", NUM, "seconds the round had run by this step while the participant was connected (what "
                                 "timing.max_round_seconds limits); empty for ticks stored before it was kept"),
    Column("world_events", TEXT, "what the step did, as agent:event (start_cooking, load_board, load_sink, chop, "
                                 "wash, plate_steak, garnish, deliver, pick_up, put_down, swap, dispense, blocked), "
                                 "';' between events; empty for ticks stored before events were kept"),
)

PARTICIPATION_COLUMNS: tuple[Column, ...] = (
    Column("trial_status", TEXT, "running, abandoned, low_engagement (finished without the participant taking "
                                 "part), robot_invalid (finished, robot decisions past their deadline) or finished"),
    Column("key_actions", INT, "the participant's one-step key actions (moves, stay, interact) among the "
                               "interrupts (empty: not recorded)"),
    Column("idle_pct", NUM, "% of the trial's tick periods in which the cook had nothing to do (no task, no key "
                            "waiting); in wait_for_participant the time the world waited counts at the tick rate"),
    Column("refused_steps", INT, "the participant's tasks refused or ended because they could not work (what "
                                 "they needed was gone, taken or busy, often because the robot had done it)"),
    Column("delivered_by_participant", INT, "dishes the participant's cook delivered"),
    Column("delivered_by_robot", INT, "dishes the robot delivered"),
    Column("task_steps", INT, "the participant's task steps: their cook's interactions that changed the world "
                              "(picked up, put down, chopped, washed, plated, delivered); empty: not recorded"),
    Column("robot_task_steps", INT, "the robot's task steps (the team's other share)"),
    Column("stand_ticks", INT, "world steps in which the participant had no executable action (a task standing "
                               "with nothing it could do, or no task at all); the paper's clock steps none"),
    Column("think_seconds", NUM, "wall-clock seconds the cook had nothing to do while the participant was "
                                 "connected: the waited time (wait_for_participant) or the idle ticks at the "
                                 "tick rate (fixed_rate)"),
    Column("engagement_reason", TEXT, "why the server marked the main trial low_engagement (the rule and its "
                                      "measured value: too few actions, too idle, too small a share of the team's "
                                      "task steps, …: validity in docs/operations.md); such trials are not in "
                                      "cells.csv unless exported with --include-invalid"),
)
"""The participant's part in the trial (:mod:`analysis.measures.participation`)."""

TRIAL_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT, _TRIAL_ID, *TICK_COLUMNS[2:5],
    Column("condition", TEXT, _CONDITION_ID), _ROBOT, _KITCHEN, _VIEW, _FOV_ANGLE,
    Column("seed", INT, "the trial's random seed"),
    Column("status", TEXT, "finished, abandoned or running"),
    Column("end_reason", TEXT, "delivered, horizon, grace_expired or restarted"),
    Column("started_at", TIME, "start of the attempt"),
    Column("ended_at", TIME, "end of the attempt"),
    Column("config_hash", TEXT, "hash of the resolved study configuration the trial ran under"),
    Column("in_cells", FLAG, "1 when this attempt is the one in cells.csv (main trial, finished, latest "
                             "attempt, not invalid unless exported with --include-invalid, participant neither "
                             "test run nor excluded)"),
    Column("participant_test_run", FLAG, "1 when the participant is flagged as a test run"),
    Column("participant_excluded", FLAG, "1 when the participant is excluded by the experimenter"),
    *(MEASURES[m] for m in TRIAL_MEASURES),
    Column("ticks_stored", INT, "tick rows stored for the attempt (equals ticks unless data were lost)"),
    *(MEASURES[m] for m in CONDUCT_COUNTS),
    Column("decisions", INT, "robot decisions the server asked for (one per world step; empty: not recorded)"),
    Column("missed_decisions", INT, "of these, decisions that missed their deadline (the robot stood still)"),
    Column("missed_decisions_pct", NUM,
           "% of the decisions that missed their deadline (missed_decisions / decisions × 100)"),
    Column("invalid_reason", TEXT, "why the server marked the trial invalid (more missed decisions than the "
                                   "study's validity.max_missed_decisions_pct); empty when valid. Invalid trials "
                                   "are not in cells.csv unless exported with --include-invalid"),
    *PARTICIPATION_COLUMNS,
)

CELL_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT, _ROBOT, _KITCHEN, _VIEW, _FOV_ANGLE,
    Column("condition", TEXT, _CONDITION_ID),
    _TRIAL_ID,
    Column("position", INT, "position of the condition in the participant's order (1 = first main trial)"),
    *(MEASURES[m] for m in TRIAL_MEASURES),
)

ANSWER_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT,
    Column("questionnaire", TEXT, "questionnaire id"),
    Column("item", TEXT, "item id"),
    Column("value", INT, "a rating as given on the item's scale (reverse-coded items are not reversed here), or "
                         "the 0-based index of the chosen option of a choice item (empty: not answered, or a text "
                         "item)"),
    Column("text", TEXT, "a free-text answer, or the chosen option's text of a choice item (empty: a rating or "
                         "not answered). Quoted as CSV needs (commas, quotes, line breaks); text beginning with =, "
                         "+, -, @, a tab or a carriage return is written with a leading ' so that spreadsheets "
                         "show it instead of running it as a formula (the store keeps it as written)"),
    Column("after_trial", INT, "main trial index the questionnaire followed (empty: end of study)"),
    Column("trial_status", TEXT, "status of that trial (analysis.measures.participation): finished, low_engagement, "
                                 "robot_invalid, or abandoned for answers stored before the questionnaire after "
                                 "an abandoned round was skipped"),
    Column("condition", TEXT, "condition of that trial"), _ROBOT, _KITCHEN, _VIEW, _FOV_ANGLE,
    _TRIAL_ID,
    Column("answered_at", TIME, "when the answer was submitted"),
    Column("test_run", FLAG, "1 when the participant is flagged as a test run"),
    Column("excluded", FLAG, "1 when the participant is excluded by the experimenter"),
)

PARTICIPANT_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT,
    Column("recruit_id", TEXT, "recruiting platform id (the study's first URL parameter, e.g. PROLIFIC_PID)"),
    Column("recruiting", TEXT, "all recruiting URL parameters (JSON)"),
    Column("order_index", INT, "counterbalancing order assigned (index into the study's orders)"),
    Column("condition_order", TEXT, "the assigned condition ids, ';' between them"),
    Column("status", TEXT, "in_progress, completed or screened_out"),
    Column("state", TEXT, "current step of the participant flow"),
    Column("step", INT, "current step number"),
    Column("steps", INT, "number of steps in the participant's plan"),
    Column("test_run", FLAG, "1 when flagged as a test run"),
    Column("pilot", FLAG, "1 for a simulated pilot participant (steakhouse pilot; its answers are simulated); "
                          "pilots are exported only with --include-pilot"),
    Column("excluded", FLAG, "1 when excluded by the experimenter"),
    Column("exclusion_reason", TEXT, "the experimenter's reason"),
    Column("created_at", TIME, "when the participant joined"),
    Column("finished_at", TIME, "when the participant finished or was screened out"),
    Column("practice_trials_finished", INT, "practice trials finished"),
    Column("main_trials_finished", INT, "main trials finished"),
    Column("cells", INT, "rows of this participant in cells.csv"),
    Column("complete", FLAG, "1 when the participant has a cell in every condition and is not flagged"),
)

EXCLUDED_COLUMNS: tuple[Column, ...] = (
    _PARTICIPANT,
    Column("category", TEXT, "test_run, excluded (by the experimenter), invalid (a main trial the server marked "
                             "invalid, left out of cells.csv), low_engagement (a main trial played without the "
                             "participant taking part) or incomplete (missing cells)"),
    Column("reason", TEXT, "why the participant is not in the complete-case analysis"),
    Column("in_cells", FLAG, "1 when the participant's available cells are still in cells.csv"),
)


def wide_column(measure: str, *levels: str) -> str:
    """``measure__robot__kitchen`` (``…__view``, ``…__angle`` appended when the view, the angle are factors)."""
    return WIDE_SEPARATOR.join((measure, *levels))


def item_columns(items: Iterable[tuple[str, str, str]]) -> list[Column]:
    """Columns for ``(questionnaire, item, text)`` triples."""
    return [Column(item_column(q, i), INT, f"answer to {q}.{i}: “{text}”") for q, i, text in items]


GROUPS = {"robot": "robot planner", "kitchen": "kitchen", "view": "view (top_down or first_person)",
          "fov_angle": "field of view in degrees"}
"""What a between factor's level is, for the description of its column."""


def between_columns(between: Sequence[str]) -> list[Column]:
    """One column per factor between participants: the participant's level (their group)."""
    return [Column(f, TEXT, f"the participant's group: their {GROUPS.get(f, f)}, a factor between participants")
            for f in between]


def participant_columns(between: Sequence[str] = ()) -> tuple[Column, ...]:
    """``participants.csv``'s columns: :data:`PARTICIPANT_COLUMNS` with the between factors after
    ``condition_order``."""
    cut = [c.name for c in PARTICIPANT_COLUMNS].index("condition_order") + 1
    return (*PARTICIPANT_COLUMNS[:cut], *between_columns(between), *PARTICIPANT_COLUMNS[cut:])


def wide_columns(measures: Sequence[Column], cells: Sequence[tuple[str, ...]],
                 end_items: Sequence[Column], fields: Sequence[str] = ("robot", "kitchen"),
                 between: Sequence[str] = ()) -> list[Column]:
    """``wide.csv``'s columns: the participant, their level of each between factor, then one column per measure and
    within cell (``cells``: the levels of the within ``fields``), then the end-of-study items and scales."""
    columns = [
        _PARTICIPANT,
        *between_columns(between),
        Column("order_index", INT, "counterbalancing order assigned"),
        Column("complete", FLAG, "1 when the participant has a cell in every condition"),
    ]
    for measure in measures:
        for cell in cells:
            named = ", ".join(f"{factor} {level}" for factor, level in zip(fields, cell, strict=True))
            columns.append(Column(wide_column(measure.name, *cell), measure.type,
                                  f"{measure.description} — {named}"))
    return columns + list(end_items)


FILE_NOTES: dict[str, str] = {
    "ticks.csv": "one row per stored world step of every trial attempt (practice included, flagged participants "
                 "included: join trials.csv on trial_id for the flags)",
    "trials.csv": "one row per trial attempt, practice and main, every participant, with its measures",
    "cells.csv": "the ANOVA input: one row per participant × condition (main trials only; participants "
                 "flagged as test run or excluded are left out and listed in excluded.csv)",
    "wide.csv": "one row per participant of cells.csv: one column per factor between participants (the "
                "participant's group) and one per measure × within cell (for JASP / SPSS; wide.sav is the same file "
                "for SPSS)",
    "answers.csv": "one row per questionnaire item answered, every participant",
    "participants.csv": "one row per participant of the study, with flags and progress",
    "excluded.csv": "participants not in the complete-case analysis, with the reason",
}


def render_markdown(files: Mapping[str, Sequence[Column]], study_id: str, exported_at: str,
                    config: Mapping[str, Any] | None = None) -> str:
    """``data_dictionary.md``: a section per file with a table of its columns, then the questionnaires' items and
    scales from the study's ``config``."""
    lines = [f"# Data dictionary: study {study_id}", "", f"Exported {exported_at}.", "",
             "Empty cells are missing values. Flags are 0/1. Times are UTC (ISO 8601). Measures are defined in "
             "docs/analysis.md (docs/domain.md §6).", ""]
    for name, columns in files.items():
        lines += [f"## {name}", "", FILE_NOTES.get(name, ""), "", "| column | type | unit | description |",
                  "|---|---|---|---|"]
        lines += [f"| {c.name} | {c.type} | {UNITS.get(c.name, '')} | {md_cell(c.description)} |" for c in columns]
        lines.append("")
    return "\n".join(lines + questionnaire_markdown(config or {}))


def rows(files: Mapping[str, Sequence[Column]], config: Mapping[str, Any] | None = None) -> list[dict[str, str]]:
    """``data_dictionary.csv``: one row per file and column; then one row per questionnaire item (file
    ``items``) and per named scale (file ``scales``) of the study's ``config``."""
    out = [{"file": name, "column": c.name, "type": c.type, "unit": UNITS.get(c.name, ""),
            "description": c.description} for name, columns in files.items() for c in columns]
    out += [{"file": "items", "column": i.column, "type": i.kind, "unit": "", "description": i.description}
            for i in questionnaire_items(config or {})]
    out += [{"file": "scales", "column": sc.column, "type": NUM, "unit": "", "description": sc.description}
            for sc in questionnaire_scales(config or {})]
    return out
