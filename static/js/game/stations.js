/**
 * Drawings of the terrain and stations (docs/domain.md §1): floor, counter, onion / meat crates, plate rack,
 * grill, chopping board, sink and serving counter, with what a station holds and its progress (cook
 * ticks, chops, washes). A cell is drawn inside its own square (x0, y0, s) in device pixels.
 */

import { STATE, isDone, isEmpty } from "../vocabulary.js";
import { COLORS } from "./palette.js";
import { drawCleanPlate, drawDirtyPlate, drawGarnish, drawMeat, drawObject, drawOnion } from "./items.js";

function rect(ctx, x, y, w, h, fill, stroke, width = 1) {
  if (fill) {
    ctx.fillStyle = fill;
    ctx.fillRect(x, y, w, h);
  }
  if (stroke) {
    ctx.strokeStyle = stroke;
    ctx.lineWidth = width;
    ctx.strokeRect(x + width / 2, y + width / 2, w - width, h - width);
  }
}

function rounded(ctx, x, y, w, h, r, fill, stroke, width = 1) {
  ctx.beginPath();
  ctx.roundRect(x, y, w, h, r);
  if (fill) {
    ctx.fillStyle = fill;
    ctx.fill();
  }
  if (stroke) {
    ctx.strokeStyle = stroke;
    ctx.lineWidth = width;
    ctx.stroke();
  }
}

export function drawFloor(ctx, x0, y0, s) {
  rect(ctx, x0, y0, s, s, COLORS.floor);
  const w = Math.max(1, Math.round(s / 48));
  ctx.fillStyle = COLORS.floorLine;
  ctx.fillRect(x0, y0 + s - w, s, w);
  ctx.fillRect(x0 + s - w, y0, w, s);
}

export function drawCounter(ctx, x0, y0, s) {
  rect(ctx, x0, y0, s, s, COLORS.counter);
  const m = Math.max(1, Math.round(s * 0.06));
  rect(ctx, x0 + m, y0 + m, s - 2 * m, s - 2 * m, COLORS.counterTop, COLORS.counterEdge, Math.max(1, s / 40));
}

function crate(ctx, x0, y0, s) {
  const m = s * 0.14;
  rounded(ctx, x0 + m, y0 + m, s - 2 * m, s - 2 * m, s * 0.06, COLORS.crate, COLORS.crateLine, Math.max(1, s / 30));
  ctx.strokeStyle = COLORS.crateLine;
  ctx.lineWidth = Math.max(1, s / 40);
  for (const f of [0.38, 0.62]) {
    ctx.beginPath();
    ctx.moveTo(x0 + m, y0 + s * f);
    ctx.lineTo(x0 + s - m, y0 + s * f);
    ctx.stroke();
  }
}

function drawOnionCrate(ctx, x0, y0, s) {
  drawCounter(ctx, x0, y0, s);
  crate(ctx, x0, y0, s);
  drawOnion(ctx, x0 + s * 0.36, y0 + s * 0.55, s * 0.17);
  drawOnion(ctx, x0 + s * 0.64, y0 + s * 0.55, s * 0.17);
  drawOnion(ctx, x0 + s * 0.5, y0 + s * 0.36, s * 0.17);
}

function drawMeatCrate(ctx, x0, y0, s) {
  drawCounter(ctx, x0, y0, s);
  crate(ctx, x0, y0, s);
  drawMeat(ctx, x0 + s * 0.5, y0 + s * 0.42, s * 0.22, 0);
  drawMeat(ctx, x0 + s * 0.5, y0 + s * 0.62, s * 0.18, 0);
}

function drawPlateRack(ctx, x0, y0, s) {
  drawCounter(ctx, x0, y0, s);
  for (const [dx, dy] of [[-0.1, 0.08], [0, 0], [0.1, -0.08]]) {
    drawDirtyPlate(ctx, x0 + s * (0.5 + dx), y0 + s * (0.5 + dy), s * 0.27);
  }
}

function drawGrill(ctx, x0, y0, s, station) {
  rect(ctx, x0, y0, s, s, COLORS.counter);
  const m = s * 0.08;
  const hot = !isEmpty(station);
  rounded(ctx, x0 + m, y0 + m, s - 2 * m, s - 2 * m, s * 0.08, COLORS.grillBody, COLORS.grillBar, Math.max(1, s / 30));
  ctx.strokeStyle = hot ? COLORS.grillHot : COLORS.grillBar;
  ctx.lineWidth = Math.max(1.5, s * 0.05);
  for (let i = 1; i <= 4; i += 1) {
    const y = y0 + m + ((s - 2 * m) * i) / 5;
    ctx.beginPath();
    ctx.moveTo(x0 + m * 1.8, y);
    ctx.lineTo(x0 + s - m * 1.8, y);
    ctx.stroke();
  }
  if (hot) {
    const cooked = station.total ? station.progress / station.total : 1;
    drawMeat(ctx, x0 + s * 0.5, y0 + s * 0.47, s * 0.28, station.state === STATE.READY ? 1 : cooked * 0.85);
  }
}

function drawBoard(ctx, x0, y0, s, station) {
  drawCounter(ctx, x0, y0, s);
  const m = s * 0.12;
  rounded(ctx, x0 + m, y0 + m * 1.2, s - 2 * m, s - 2.4 * m, s * 0.08, COLORS.board, COLORS.boardEdge, Math.max(1, s / 30));
  ctx.strokeStyle = COLORS.knife;
  ctx.lineWidth = Math.max(2, s * 0.07);
  ctx.beginPath();
  ctx.moveTo(x0 + s * 0.72, y0 + s * 0.22);
  ctx.lineTo(x0 + s * 0.84, y0 + s * 0.5);
  ctx.stroke();
  ctx.strokeStyle = COLORS.ink;
  ctx.beginPath();
  ctx.moveTo(x0 + s * 0.84, y0 + s * 0.5);
  ctx.lineTo(x0 + s * 0.88, y0 + s * 0.62);
  ctx.stroke();
  if (isEmpty(station)) return;
  if (station.state === STATE.READY) {
    drawGarnish(ctx, x0 + s * 0.42, y0 + s * 0.5, s * 0.24);
    return;
  }
  drawOnion(ctx, x0 + s * 0.42, y0 + s * 0.5, s * 0.22);
  ctx.strokeStyle = COLORS.plate;
  ctx.lineWidth = Math.max(1, s * 0.04);
  for (let i = 0; i < station.progress; i += 1) {
    const x = x0 + s * (0.32 + (0.2 * (i + 1)) / (station.total + 1));
    ctx.beginPath();
    ctx.moveTo(x, y0 + s * 0.3);
    ctx.lineTo(x, y0 + s * 0.7);
    ctx.stroke();
  }
}

function drawSink(ctx, x0, y0, s, station) {
  drawCounter(ctx, x0, y0, s);
  const m = s * 0.14;
  rounded(ctx, x0 + m, y0 + m * 1.4, s - 2 * m, s - 2.2 * m, s * 0.16, COLORS.sinkBasin, COLORS.sinkEdge, Math.max(1, s / 24));
  rounded(ctx, x0 + s * 0.44, y0 + s * 0.06, s * 0.12, s * 0.2, s * 0.04, COLORS.tap, COLORS.ink, Math.max(1, s / 60));
  if (isEmpty(station)) return;
  if (station.state === STATE.CLEAN) {
    drawCleanPlate(ctx, x0 + s * 0.5, y0 + s * 0.56, s * 0.25);
    return;
  }
  drawDirtyPlate(ctx, x0 + s * 0.5, y0 + s * 0.56, s * 0.25);
  ctx.strokeStyle = "rgba(255, 255, 255, 0.9)";
  ctx.lineWidth = Math.max(1, s * 0.03);
  for (let i = 0; i < station.progress; i += 1) {
    ctx.beginPath();
    ctx.arc(x0 + s * (0.26 + 0.48 * (i / Math.max(1, station.total - 1))), y0 + s * 0.36, s * 0.06, 0, Math.PI * 2);
    ctx.stroke();
  }
}

function drawServe(ctx, x0, y0, s) {
  rect(ctx, x0, y0, s, s, COLORS.counter);
  const m = s * 0.08;
  rounded(ctx, x0 + m, y0 + m, s - 2 * m, s - 2 * m, s * 0.08, COLORS.serve, COLORS.serveEdge, Math.max(1, s / 24));
  ctx.fillStyle = COLORS.plate;
  ctx.beginPath();
  ctx.arc(x0 + s * 0.5, y0 + s * 0.6, s * 0.25, Math.PI, 0);
  ctx.closePath();
  ctx.fill();
  ctx.fillRect(x0 + s * 0.2, y0 + s * 0.62, s * 0.6, Math.max(2, s * 0.07));
  ctx.beginPath();
  ctx.arc(x0 + s * 0.5, y0 + s * 0.31, Math.max(1.5, s * 0.05), 0, Math.PI * 2);
  ctx.fill();
}

const TERRAIN = {
  floor: drawFloor,
  counter: drawCounter,
  onion: drawOnionCrate,
  meat: drawMeatCrate,
  plate: drawPlateRack,
  grill: drawGrill,
  board: drawBoard,
  sink: drawSink,
  serve: drawServe,
};

/** Draw a visible cell: its terrain, what its station holds, the object on it and the progress bar. */
export function drawCell(ctx, cell, x0, y0, s) {
  const draw = TERRAIN[cell.terrain] || drawCounter;
  draw(ctx, x0, y0, s, cell.station || null);
  if (cell.object) drawObject(ctx, cell.object, x0 + s / 2, y0 + s / 2, s * 0.3);
  if (cell.station) drawProgress(ctx, cell.terrain, cell.station, x0, y0, s);
}

export const BAR_COLOR = { grill: COLORS.barCook, board: COLORS.barChop, sink: COLORS.barWash };

/** A segmented bar along the cell's bottom edge, and a check badge when the work is done. */
export function drawProgress(ctx, terrain, station, x0, y0, s) {
  if (isEmpty(station) || !station.total) return;
  const done = isDone(station);
  const bx = x0 + s * 0.1;
  const bw = s * 0.8;
  const bh = Math.max(4, Math.round(s * 0.12));
  const by = y0 + s - bh - Math.max(1, Math.round(s * 0.04));
  rect(ctx, bx, by, bw, bh, COLORS.barBack);
  const fraction = Math.min(station.progress / station.total, 1);
  rect(ctx, bx + 1, by + 1, Math.max(0, (bw - 2) * fraction), bh - 2, done ? COLORS.badge : BAR_COLOR[terrain] || COLORS.barCook);
  if (station.total <= 10) {
    ctx.fillStyle = COLORS.barBack;
    for (let i = 1; i < station.total; i += 1) ctx.fillRect(bx + (bw * i) / station.total - 0.5, by, 1, bh);
  }
  if (done) drawCheck(ctx, x0 + s * 0.8, y0 + s * 0.2, s * 0.16);
}

export function drawCheck(ctx, cx, cy, r) {
  ctx.beginPath();
  ctx.arc(cx, cy, r, 0, Math.PI * 2);
  ctx.fillStyle = COLORS.badge;
  ctx.fill();
  ctx.strokeStyle = COLORS.plate;
  ctx.lineWidth = Math.max(1.5, r * 0.28);
  ctx.beginPath();
  ctx.moveTo(cx - r * 0.5, cy);
  ctx.lineTo(cx - r * 0.1, cy + r * 0.4);
  ctx.lineTo(cx + r * 0.55, cy - r * 0.4);
  ctx.stroke();
}
