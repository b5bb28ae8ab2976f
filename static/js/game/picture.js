/**
 * The instructions page's pictures, drawn by the game's own painter: the example kitchen as a whole
 * and as the cook sees it (black outside the field of view), and a legend of every station, object and
 * agent. The example's visible cells are data (static/data/example_view.json), checked against the
 * planner's FOV function by the tests, so the picture shows the same rule the game applies. A study with
 * another angle gets the cells from `inView`, the planner's rule (planner/fov.py `in_view`) for this picture
 * only — the game itself never computes a view in the browser; the tests compare the two for every cell,
 * facing and a range of angles.
 */

import { h } from "../dom.js";
import { STATIONS } from "../labels.js";
import { FLOOR, STATE, TERRAIN_OF_CHAR } from "../vocabulary.js";
import { paintState } from "./renderer.js";
import { drawCell } from "./stations.js";
import { drawAgent, FACING } from "./agents.js";
import { drawObject } from "./items.js";
import { iconCanvas as icon } from "./icons.js";

export async function loadExample() {
  const response = await fetch("/data/example_view.json", { cache: "no-store" });
  if (!response.ok) throw new Error("the example picture could not be loaded");
  return response.json();
}

/**
 * Whether `cell` is in view from `origin` facing `facing` with a field of view of `angle` degrees: the own
 * cell, the two cells beside it, and every cell within half the angle of the facing (docs/domain.md §2).
 */
export function inView(origin, facing, cell, angle) {
  if (angle >= 360) return true;
  const vx = cell[0] - origin[0];
  const vy = cell[1] - origin[1];
  if (vx === 0 && vy === 0) return true;
  const [dx, dy] = FACING[facing];
  const dot = vx * dx + vy * dy;
  if (Math.abs(vx) + Math.abs(vy) === 1 && dot === 0) return true;
  return dot >= Math.hypot(vx, vy) * Math.cos(((angle / 2) * Math.PI) / 180) - 1e-9;
}

/** The example's cells in view at `angle` (the stored ones at the example's own angle). */
export function exampleVisible(example, angle = example.fov_angle) {
  if (angle === example.fov_angle) return example.visible;
  const you = [example.you.x, example.you.y];
  const out = [];
  example.rows.forEach((row, y) => [...row].forEach((_, x) => {
    if (inView(you, example.you.facing, [x, y], angle)) out.push([x, y]);
  }));
  return out;
}

/**
 * The whole example kitchen as a `state`-shaped scene, and the same scene limited to what is in view with
 * a field of view of `angle` degrees (default: the example's own).
 */
export function exampleScenes(example, angle = example.fov_angle) {
  const objects = new Map(example.objects.map((o) => [`${o.x},${o.y}`, o.object]));
  const stations = new Map(example.stations.map((s) => [`${s.x},${s.y}`, s]));
  const cells = [];
  example.rows.forEach((row, y) => [...row].forEach((ch, x) => {
    const key = `${x},${y}`;
    const station = stations.get(key);
    cells.push({ x, y, terrain: TERRAIN_OF_CHAR[ch] || FLOOR, object: objects.get(key) || null,
                 station: station ? { state: station.state, progress: station.progress, total: station.total } : null });
  }));
  const seen = new Set(exampleVisible(example, angle).map(([x, y]) => `${x},${y}`));
  const robotSeen = seen.has(`${example.robot.x},${example.robot.y}`);
  return {
    width: example.rows[0].length,
    height: example.rows.length,
    whole: { cells, you: example.you, robot: example.robot },
    view: { cells: cells.filter((c) => seen.has(`${c.x},${c.y}`)), you: example.you, robot: robotSeen ? example.robot : null },
    robotSeen,
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

export function examplePicture(example, cssCell = 40, angle = example.fov_angle) {
  const scenes = exampleScenes(example, angle);
  const robot = scenes.robotSeen ? "the robot is in view." : "everything behind and beside you is black, including the robot.";
  return h("div", { class: "picture-pair" },
    h("figure", {},
      sceneCanvas(scenes.width, scenes.height, scenes.whole, cssCell,
                  "The whole example kitchen: the robot holds an onion behind you; a dirty plate lies on the island."),
      h("figcaption", {}, "The whole kitchen (you never see this)")),
    h("figure", {},
      sceneCanvas(scenes.width, scenes.height, scenes.view, cssCell,
                  `What you see with a ${angle}° field of view: you face east; ${robot}`),
      h("figcaption", {}, angle >= 360 ? "What you see: everything, in this study"
        : "What you see: facing right, everything else is black")));
}

const OBJECT_LEGEND = [
  ["onion", "Onion"], ["meat", "Raw meat"], ["dirty_plate", "Dirty plate"], ["clean_plate", "Clean plate"],
  ["steak_plate", "Plated steak"], ["dish", "Dish: steak + chopped onion, ready to serve"],
];

/** A legend: every station (with its progress bar), object and agent, drawn by the game's painters. */
export function legend() {
  const floorUnder = (ctx, s) => drawCell(ctx, { terrain: FLOOR }, 0, 0, s);
  const items = [
    ...["counter", "onion", "meat", "plate"].map((t) => [STATIONS[t], (ctx, s) => drawCell(ctx, { terrain: t }, 0, 0, s)]),
    ["Grill, steak cooking (bar: cook time)", (ctx, s) => drawCell(ctx, { terrain: "grill", station: { state: STATE.COOKING, progress: 4, total: 10 } }, 0, 0, s)],
    ["Chopping board, onion chopped once", (ctx, s) => drawCell(ctx, { terrain: "board", station: { state: STATE.CHOPPING, progress: 1, total: 2 } }, 0, 0, s)],
    ["Sink, plate clean (✓ means done)", (ctx, s) => drawCell(ctx, { terrain: "sink", station: { state: STATE.CLEAN, progress: 2, total: 2 } }, 0, 0, s)],
    [STATIONS.serve, (ctx, s) => drawCell(ctx, { terrain: "serve" }, 0, 0, s)],
    ...OBJECT_LEGEND.map(([kind, text]) => [text, (ctx, s) => { floorUnder(ctx, s); drawObject(ctx, kind, s / 2, s / 2, s * 0.32); }]),
    ["You (the pointer shows where you face)", (ctx, s) => { floorUnder(ctx, s); drawAgent(ctx, "human", { facing: "east" }, 0, 0, s); }],
    ["The robot (its visor shows where it faces)", (ctx, s) => { floorUnder(ctx, s); drawAgent(ctx, "robot", { facing: "west" }, 0, 0, s); }],
    ["Out of your view", (ctx, s) => { ctx.fillStyle = "#000"; ctx.fillRect(0, 0, s, s); }],
  ];
  return h("ul", { class: "legend" }, items.map(([text, draw]) => h("li", {}, icon(draw), h("span", {}, text))));
}
