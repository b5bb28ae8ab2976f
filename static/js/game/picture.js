/**
 * The instructions page's pictures, drawn by the game's own painter: the example kitchen as a whole
 * and as the cook sees it (black outside the field of view), and a legend of every station, object and
 * agent. The example's visible cells are data (static/data/example_view.json), checked against the
 * planner's FOV function by the tests, so the picture shows the same rule the game applies.
 */

import { h } from "../dom.js";
import { STATIONS } from "../labels.js";
import { paintState } from "./renderer.js";
import { drawCell } from "./stations.js";
import { drawAgent } from "./agents.js";
import { drawObject } from "./items.js";

const TERRAIN = { X: "counter", " ": "floor", O: "onion", M: "meat", D: "plate", P: "grill", B: "board", W: "sink",
                  S: "serve" };

export async function loadExample() {
  const response = await fetch("/data/example_view.json", { cache: "no-store" });
  if (!response.ok) throw new Error("the example picture could not be loaded");
  return response.json();
}

/** The whole example kitchen as a `state`-shaped scene, and the same scene limited to what is in view. */
export function exampleScenes(example) {
  const objects = new Map(example.objects.map((o) => [`${o.x},${o.y}`, o.object]));
  const stations = new Map(example.stations.map((s) => [`${s.x},${s.y}`, s]));
  const cells = [];
  example.rows.forEach((row, y) => [...row].forEach((ch, x) => {
    const key = `${x},${y}`;
    const station = stations.get(key);
    cells.push({ x, y, terrain: TERRAIN[ch] || "floor", object: objects.get(key) || null,
                 station: station ? { state: station.state, progress: station.progress, total: station.total } : null });
  }));
  const seen = new Set(example.visible.map(([x, y]) => `${x},${y}`));
  const robotSeen = seen.has(`${example.robot.x},${example.robot.y}`);
  return {
    width: example.rows[0].length,
    height: example.rows.length,
    whole: { cells, you: example.you, robot: example.robot },
    view: { cells: cells.filter((c) => seen.has(`${c.x},${c.y}`)), you: example.you, robot: robotSeen ? example.robot : null },
  };
}

function sceneCanvas(width, height, state, cssCell, label) {
  const dpr = window.devicePixelRatio || 1;
  const cell = Math.round(cssCell * dpr);
  const canvas = h("canvas", { class: "picture-canvas", role: "img", "aria-label": label });
  canvas.width = cell * width;
  canvas.height = cell * height;
  canvas.style.width = `${(cell * width) / dpr}px`;
  canvas.style.height = `${(cell * height) / dpr}px`;
  paintState(canvas.getContext("2d", { alpha: false }), width, height, state, cell);
  return canvas;
}

export function examplePicture(example, cssCell = 40) {
  const scenes = exampleScenes(example);
  return h("div", { class: "picture-pair" },
    h("figure", {},
      sceneCanvas(scenes.width, scenes.height, scenes.whole, cssCell,
                  "The whole example kitchen: the robot holds an onion behind you; a dirty plate lies on the island."),
      h("figcaption", {}, "The whole kitchen (you never see this)")),
    h("figure", {},
      sceneCanvas(scenes.width, scenes.height, scenes.view, cssCell,
                  "What you see: you face east; everything behind and beside you is black, including the robot."),
      h("figcaption", {}, "What you see: facing right, everything else is black")));
}

function icon(draw, cssSize = 44) {
  const dpr = window.devicePixelRatio || 1;
  const s = Math.round(cssSize * dpr);
  const canvas = h("canvas", { class: "legend-icon", "aria-hidden": "true" });
  canvas.width = s;
  canvas.height = s;
  canvas.style.width = `${s / dpr}px`;
  canvas.style.height = `${s / dpr}px`;
  draw(canvas.getContext("2d"), s);
  return canvas;
}

const OBJECT_LEGEND = [
  ["onion", "Onion"], ["meat", "Raw meat"], ["dirty_plate", "Dirty plate"], ["clean_plate", "Clean plate"],
  ["steak_plate", "Plated steak"], ["dish", "Dish: steak + chopped onion, ready to serve"],
];

/** A legend: every station (with its progress bar), object and agent, drawn by the game's painters. */
export function legend() {
  const floorUnder = (ctx, s) => drawCell(ctx, { terrain: "floor" }, 0, 0, s);
  const items = [
    ...["counter", "onion", "meat", "plate"].map((t) => [STATIONS[t], (ctx, s) => drawCell(ctx, { terrain: t }, 0, 0, s)]),
    ["Grill, steak cooking (bar: cook time)", (ctx, s) => drawCell(ctx, { terrain: "grill", station: { state: "cooking", progress: 4, total: 10 } }, 0, 0, s)],
    ["Chopping board, onion chopped once", (ctx, s) => drawCell(ctx, { terrain: "board", station: { state: "chopping", progress: 1, total: 2 } }, 0, 0, s)],
    ["Sink, plate clean (✓ means done)", (ctx, s) => drawCell(ctx, { terrain: "sink", station: { state: "clean", progress: 2, total: 2 } }, 0, 0, s)],
    [STATIONS.serve, (ctx, s) => drawCell(ctx, { terrain: "serve" }, 0, 0, s)],
    ...OBJECT_LEGEND.map(([kind, text]) => [text, (ctx, s) => { floorUnder(ctx, s); drawObject(ctx, kind, s / 2, s / 2, s * 0.32); }]),
    ["You (the pointer shows where you face)", (ctx, s) => { floorUnder(ctx, s); drawAgent(ctx, "human", { facing: "east" }, 0, 0, s); }],
    ["The robot (its visor shows where it faces)", (ctx, s) => { floorUnder(ctx, s); drawAgent(ctx, "robot", { facing: "west" }, 0, 0, s); }],
    ["Out of your view", (ctx, s) => { ctx.fillStyle = "#000"; ctx.fillRect(0, 0, s, s); }],
  ];
  return h("ul", { class: "legend" }, items.map(([text, draw]) => h("li", {}, icon(draw), h("span", {}, text))));
}
