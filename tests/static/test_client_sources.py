"""Checks of the client's files against the server and the planner, without a browser: the instructions'
example view is the planner's FOV, and every protocol name (subtask, interrupt, terrain, object) has a
label and a drawing, so a new one cannot silently fall back to a placeholder; the client's kitchen words are the
planner's, spelled in one module."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import get_args

from planner.fov import visible_cells
from planner.geometry import Direction
from planner.layout import parse_layout
from planner.objects import OBJECTS
from planner.subtasks import SUBTASKS
from planner.vocabulary import TERRAIN_NAMES, StationState
from server.protocol.interrupts import Interrupt
from server.protocol.server import TerrainName

STATIC = Path(__file__).resolve().parents[2] / "static"


def source(name: str) -> str:
    return (STATIC / name).read_text(encoding="utf-8")


def test_the_instructions_example_shows_exactly_the_planners_field_of_view():
    example = json.loads(source("data/example_view.json"))
    rows = [list(row) for row in example["rows"]]
    you, robot = example["you"], example["robot"]
    rows[you["y"]][you["x"]] = "2"
    rows[robot["y"]][robot["x"]] = "1"
    layout = parse_layout("\n".join("".join(r) for r in rows) + "\n", name="example")
    seen = visible_cells(layout, (you["x"], you["y"]), Direction(you["facing"]), example["fov_angle"])
    assert {tuple(c) for c in example["visible"]} == seen
    assert (robot["x"], robot["y"]) not in seen, "the picture's point: the robot is hidden behind the cook"


def test_every_subtask_and_interrupt_has_a_button_label():
    labels = source("js/labels.js")
    block = labels[labels.index("export const SUBTASKS"):labels.index("export function subtaskLabel")]
    assert set(re.findall(r"^  (\w+): \{ label:", block, flags=re.MULTILINE)) == {s.value for s in SUBTASKS}
    groups = labels[labels.index("SUBTASK_GROUPS"):labels.index("export const SUBTASKS")]
    grouped = re.findall(r'"(\w+)"', groups)
    assert sorted(grouped) == sorted(s.value for s in SUBTASKS), "each subtask in exactly one group"
    interrupts = labels[labels.index("export const INTERRUPTS"):labels.index("export const OBJECTS")]
    assert set(re.findall(r'id: "(\w+)"', interrupts)) == {i.value for i in Interrupt}


def test_every_terrain_and_object_has_a_drawing():
    stations = source("js/game/stations.js")
    table = stations[stations.index("const TERRAIN = {"):stations.index("};", stations.index("const TERRAIN = {"))]
    assert set(re.findall(r"^  (\w+): draw", table, flags=re.MULTILINE)) == set(get_args(TerrainName))
    items = source("js/game/items.js")
    table = items[items.index("const DRAW = {"):items.index("};", items.index("const DRAW = {"))]
    assert set(re.findall(r"^  (\w+):", table, flags=re.MULTILINE)) == set(OBJECTS)
    labels = source("js/labels.js")
    objects = labels[labels.index("export const OBJECTS"):labels.index("export function heldLabel")]
    assert set(re.findall(r"^  (\w+):", objects, flags=re.MULTILINE)) == set(OBJECTS)


def test_the_clients_kitchen_words_are_the_planners_and_spelled_once():
    vocabulary = source("js/vocabulary.js")
    states = vocabulary[vocabulary.index("export const STATE"):vocabulary.index("});")]
    assert set(re.findall(r'\b[A-Z]+: "(\w+)"', states)) == set(get_args(StationState))
    constants = dict(re.findall(r'export const (FLOOR|COUNTER) = "(\w+)"', vocabulary))
    start = vocabulary.index("export const TERRAIN_OF_CHAR")
    chars = vocabulary[start:vocabulary.index("});", start)].split("{", 1)[1]
    table = {quoted or bare: constants.get(value, value)
             for quoted, bare, value in re.findall(r'(?:"(.)"|\b(\w)): "?(\w+)"?', chars)}
    assert table == {terrain.value: name for terrain, name in TERRAIN_NAMES.items()}
    words = "|".join(get_args(StationState))
    pattern = rf'state(:| *[!=]==) *"({words})"'
    spelled = [str(path.relative_to(STATIC)) for path in (STATIC / "js").rglob("*.js")
               if path.name != "vocabulary.js" and re.search(pattern, path.read_text(encoding="utf-8"))]
    assert spelled == [], "station states are compared and written through static/js/vocabulary.js"
