/**
 * The cells of the kitchen in 3D (docs/domain.md §1): a checkered floor tile, waist-high counters, and the
 * stations on them — onion and meat crates, the plate rack, grill, chopping board, sink and serving counter —
 * each with a silhouette of its own and the colours of the top-down drawing. `terrainModel` is the fixed
 * part of a cell (built once, the first time the cell is in view); `contentsModel` is what changes: the
 * object on a counter and a station's status (steak cooking, onion chopped once, plate washed), with the
 * top-down view's segmented progress bar and check floating above the station, facing the camera.
 */

import * as THREE from "../../vendor/three/three.module.js";
import { COLORS } from "../game/palette.js";
import { BAR_COLOR, drawCheck } from "../game/stations.js";
import { STATIONS } from "../labels.js";
import { COUNTER, FLOOR, STATE, isDone, isEmpty } from "../vocabulary.js";
import { COUNTER_TOP, bake, ball, box, cylinder, dome } from "./kit.js";
import { dirtyPlate, cleanPlate, garnish, itemModel, meat, onion } from "./items.js";

const BODY_H = COUNTER_TOP - 0.05;

function counter(g, body = COLORS.counter, top = COLORS.counterTop) {
  box(g, body, 0.98, BODY_H, 0.98);
  box(g, COLORS.counterEdge, 1.0, 0.012, 1.0, 0, BODY_H);
  box(g, top, 0.96, 0.04, 0.96, 0, BODY_H + 0.01);
}

function floor(g, x, y) {
  const tone = (x + y) % 2 === 0 ? COLORS.floor : COLORS.floorLine;
  box(g, tone, 1, 0.02, 1, 0, -0.02);
}

function crate(g, fill) {
  counter(g);
  box(g, COLORS.crate, 0.76, 0.2, 0.76, 0, COUNTER_TOP);
  box(g, COLORS.crateLine, 0.8, 0.04, 0.8, 0, COUNTER_TOP + 0.2);
  fill(g);
}

function onionCrate(g) {
  crate(g, (c) => {
    for (const [x, z] of [[-0.17, -0.15], [0.15, -0.17], [-0.12, 0.16], [0.17, 0.13], [0.0, 0.0]]) onion(c, x, z, COUNTER_TOP + 0.12);
  });
}

function meatCrate(g) {
  crate(g, (c) => {
    meat(c, -0.12, -0.12, COUNTER_TOP + 0.22);
    meat(c, 0.12, 0.1, COUNTER_TOP + 0.22);
    meat(c, -0.05, 0.13, COUNTER_TOP + 0.28);
  });
}

function plateRack(g) {
  counter(g);
  box(g, COLORS.crateLine, 0.6, 0.03, 0.6, 0, COUNTER_TOP);
  for (let i = 0; i < 4; i += 1) dirtyPlate(g, 0, 0, COUNTER_TOP + 0.03 + i * 0.05);
  for (const [x, z] of [[-0.28, -0.28], [0.28, -0.28], [-0.28, 0.28], [0.28, 0.28]]) {
    cylinder(g, COLORS.tap, 0.015, 0.3, x, COUNTER_TOP, z, { sides: 5 });
  }
}

function grill(g) {
  box(g, COLORS.grillBody, 0.98, BODY_H + 0.05, 0.98);
  box(g, COLORS.grillBar, 0.86, 0.03, 0.86, 0, COUNTER_TOP);
  for (let i = -3; i <= 3; i += 1) box(g, COLORS.tap, 0.8, 0.02, 0.025, 0, COUNTER_TOP + 0.03, i * 0.11);
  for (const x of [-0.32, 0.32]) cylinder(g, COLORS.ink, 0.04, 0.04, x, BODY_H - 0.25, 0.5, { sides: 8 });
}

function board(g) {
  counter(g);
  box(g, COLORS.boardEdge, 0.72, 0.03, 0.56, 0, COUNTER_TOP);
  box(g, COLORS.board, 0.68, 0.012, 0.52, 0, COUNTER_TOP + 0.03);
  box(g, COLORS.knife, 0.05, 0.012, 0.28, 0.3, COUNTER_TOP + 0.045, 0.02);
  box(g, COLORS.ink, 0.05, 0.025, 0.1, 0.3, COUNTER_TOP + 0.045, 0.2);
}

const BASIN = BODY_H - 0.1;

function sink(g) {
  box(g, COLORS.counter, 0.98, BASIN, 0.98);
  const rim = COUNTER_TOP - BASIN;
  box(g, COLORS.counterTop, 0.98, rim, 0.17, 0, BASIN, -0.405);
  box(g, COLORS.counterTop, 0.98, rim, 0.17, 0, BASIN, 0.405);
  box(g, COLORS.counterTop, 0.17, rim, 0.64, -0.405, BASIN, 0);
  box(g, COLORS.counterTop, 0.17, rim, 0.64, 0.405, BASIN, 0);
  box(g, COLORS.sinkBasin, 0.64, 0.02, 0.64, 0, BASIN);
  cylinder(g, COLORS.tap, 0.025, 0.3, 0, COUNTER_TOP, -0.4, { sides: 6 });
  box(g, COLORS.tap, 0.05, 0.05, 0.2, 0, COUNTER_TOP + 0.27, -0.32);
}

function serve(g) {
  box(g, COLORS.serveEdge, 0.98, BODY_H, 0.98);
  box(g, COLORS.serve, 0.98, 0.05, 0.98, 0, BODY_H);
  cylinder(g, COLORS.plateRim, 0.26, 0.02, 0, COUNTER_TOP, 0, { sides: 14 });
  dome(g, COLORS.knife, 0.22, 0, COUNTER_TOP + 0.02, 0);
  ball(g, COLORS.plateRim, 0.03, 0, COUNTER_TOP + 0.25, 0);
}

/** The fixed part of each terrain, by the protocol's terrain name (`state.cells[].terrain`). */
export const TERRAIN = {
  floor: (g, x, y) => floor(g, x, y),
  counter: (g) => counter(g),
  onion: onionCrate,
  meat: meatCrate,
  plate: plateRack,
  grill,
  board,
  sink,
  serve,
};

const signs = new Map();

/** A station's name (labels.js, the words of the instructions' legend) as a sprite texture, cached. */
function signTexture(text) {
  if (!signs.has(text)) {
    const canvas = document.createElement("canvas");
    canvas.width = 512;
    canvas.height = 96;
    const ctx = canvas.getContext("2d");
    ctx.font = "600 44px system-ui, 'DejaVu Sans', sans-serif";
    const width = Math.min(ctx.measureText(text).width + 40, 512);
    ctx.fillStyle = "rgba(20, 24, 28, 0.72)";
    ctx.beginPath();
    ctx.roundRect((512 - width) / 2, 14, width, 68, 18);
    ctx.fill();
    ctx.fillStyle = "#FFFFFF";
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    ctx.fillText(text, 256, 50);
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    signs.set(text, texture);
  }
  return signs.get(text);
}

const SIGN_MATERIALS = new Map();

/** The model of a cell's terrain at grid (x, y): floor under everything, then the terrain's own model, and
 * above a station (not a plain counter) its name, so a station is known by name as well as by shape. */
export function terrainModel(terrain, x, y) {
  const group = new THREE.Group();
  group.name = `terrain:${terrain}`;
  group.position.set(x, 0, y);
  (TERRAIN[terrain] || TERRAIN.counter)(group, x, y);
  if (terrain !== FLOOR && terrain !== COUNTER && STATIONS[terrain]) {
    if (!SIGN_MATERIALS.has(terrain)) {
      SIGN_MATERIALS.set(terrain, new THREE.SpriteMaterial({ map: signTexture(STATIONS[terrain].replace(/ \(.*\)$/, "")) }));
    }
    const sign = new THREE.Sprite(SIGN_MATERIALS.get(terrain));
    sign.scale.set(1.0, 0.19, 1);
    sign.position.set(0, 1.72, 0);
    group.add(sign);
  }
  return bake(group);
}

function grillContents(g, station) {
  if (isEmpty(station)) return;
  box(g, COLORS.grillHot, 0.6, 0.012, 0.5, 0, COUNTER_TOP + 0.03, 0, { emissive: COLORS.grillHot });
  meat(g, 0, 0, COUNTER_TOP + 0.05, station.progress / Math.max(station.total, 1));
}

function boardContents(g, station) {
  if (isEmpty(station)) return;
  if (station.state === STATE.READY) {
    garnish(g, -0.05, 0, COUNTER_TOP + 0.045);
    return;
  }
  onion(g, -0.05, 0, COUNTER_TOP + 0.04);
  for (let i = 0; i < station.progress; i += 1) box(g, COLORS.plate, 0.23, 0.006, 0.012, -0.05, COUNTER_TOP + 0.2, -0.04 + i * 0.06);
}

function sinkContents(g, station) {
  if (isEmpty(station)) return;
  if (station.state === STATE.CLEAN) {
    cleanPlate(g, 0, 0.02, BASIN + 0.02);
    return;
  }
  dirtyPlate(g, 0, 0.02, BASIN + 0.02);
  for (let i = 0; i < station.progress; i += 1) ball(g, COLORS.plate, 0.05, -0.12 + i * 0.12, BASIN + 0.14, 0.05 - i * 0.05);
}

const CONTENTS = { grill: grillContents, board: boardContents, sink: sinkContents };

const bars = new Map();

/**
 * A station's progress as in the top-down view (game/stations.js): a segmented bar, one segment per cook
 * tick, chop or wash, green with a check when done; a sprite texture, cached per status.
 */
function progressTexture(terrain, station) {
  const key = `${terrain}:${station.state}:${station.progress}/${station.total}`;
  if (!bars.has(key)) {
    const [w, h] = [192, 48];
    const canvas = document.createElement("canvas");
    canvas.width = w;
    canvas.height = h;
    const ctx = canvas.getContext("2d");
    const done = isDone(station);
    const barW = w - h - 8;
    ctx.fillStyle = COLORS.barBack;
    ctx.fillRect(0, 10, barW, h - 20);
    ctx.fillStyle = done ? COLORS.badge : BAR_COLOR[terrain] || COLORS.barCook;
    ctx.fillRect(3, 13, (barW - 6) * Math.min(station.progress / station.total, 1), h - 26);
    ctx.fillStyle = COLORS.barBack;
    for (let i = 1; i < station.total; i += 1) ctx.fillRect((barW * i) / station.total - 1, 10, 2, h - 20);
    if (done) drawCheck(ctx, w - h / 2, h / 2, h / 2 - 2);
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    bars.set(key, texture);
  }
  return bars.get(key);
}

/** A signature of what `contentsModel` draws for a cell, to rebuild it only when it changes. */
export function contentsKey(cell) {
  const s = cell.station;
  return `${cell.object || ""}|${s ? `${s.state}:${s.progress}/${s.total}` : ""}`;
}

/** What changes on a cell: the object on a counter, the station's status and its progress bar. */
export function contentsModel(cell) {
  const group = new THREE.Group();
  group.name = `contents:${cell.x},${cell.y}`;
  group.position.set(cell.x, 0, cell.y);
  if (cell.object) {
    const item = itemModel(cell.object);
    item.position.y = COUNTER_TOP;
    group.add(item);
  }
  const station = cell.station;
  if (station && CONTENTS[cell.terrain]) {
    CONTENTS[cell.terrain](group, station);
    if (!isEmpty(station) && station.total) {
      const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: progressTexture(cell.terrain, station) }));
      sprite.scale.set(0.56, 0.14, 1);
      sprite.position.set(0, COUNTER_TOP + 0.5, 0);
      group.add(sprite);
    }
  }
  return bake(group);
}
