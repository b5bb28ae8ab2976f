/**
 * Drawings of the objects (planner/objects.py): onion, meat (raw or cooked), dirty plate, clean plate,
 * plated steak, finished dish, and the chopped onion garnish. Each fits a circle of radius `r` around
 * (cx, cy), in device pixels, and has a distinct silhouette.
 */

import { COLORS } from "./palette.js";

function ellipse(ctx, cx, cy, rx, ry, fill, stroke, width = 1) {
  ctx.beginPath();
  ctx.ellipse(cx, cy, Math.max(rx, 0.5), Math.max(ry, 0.5), 0, 0, Math.PI * 2);
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

export function drawOnion(ctx, cx, cy, r) {
  const w = Math.max(1, r * 0.09);
  ctx.beginPath();
  ctx.moveTo(cx, cy - r);
  ctx.bezierCurveTo(cx + r * 0.2, cy - r * 0.6, cx + r * 0.9, cy - r * 0.45, cx + r * 0.85, cy + r * 0.2);
  ctx.bezierCurveTo(cx + r * 0.8, cy + r * 0.8, cx - r * 0.8, cy + r * 0.8, cx - r * 0.85, cy + r * 0.2);
  ctx.bezierCurveTo(cx - r * 0.9, cy - r * 0.45, cx - r * 0.2, cy - r * 0.6, cx, cy - r);
  ctx.fillStyle = COLORS.onion;
  ctx.fill();
  ctx.strokeStyle = COLORS.onionLine;
  ctx.lineWidth = w;
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(cx, cy - r * 0.75);
  ctx.quadraticCurveTo(cx - r * 0.45, cy, cx - r * 0.2, cy + r * 0.6);
  ctx.moveTo(cx, cy - r * 0.75);
  ctx.quadraticCurveTo(cx + r * 0.45, cy, cx + r * 0.2, cy + r * 0.6);
  ctx.stroke();
}

export function drawMeat(ctx, cx, cy, r, cooked = 0) {
  const t = Math.min(Math.max(cooked, 0), 1);
  const fill = mix(COLORS.meatRaw, COLORS.meatCooked, t);
  ctx.beginPath();
  ctx.moveTo(cx - r * 0.9, cy - r * 0.1);
  ctx.bezierCurveTo(cx - r * 0.9, cy - r * 0.8, cx + r * 0.2, cy - r * 0.85, cx + r * 0.55, cy - r * 0.55);
  ctx.bezierCurveTo(cx + r * 1.0, cy - r * 0.2, cx + r * 0.95, cy + r * 0.6, cx + r * 0.3, cy + r * 0.7);
  ctx.bezierCurveTo(cx - r * 0.3, cy + r * 0.8, cx - r * 0.9, cy + r * 0.55, cx - r * 0.9, cy - r * 0.1);
  ctx.fillStyle = fill;
  ctx.fill();
  ctx.strokeStyle = "rgba(40, 15, 5, 0.8)";
  ctx.lineWidth = Math.max(1, r * 0.08);
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(cx - r * 0.5, cy - r * 0.35);
  ctx.quadraticCurveTo(cx + r * 0.1, cy - r * 0.1, cx + r * 0.45, cy + r * 0.35);
  ctx.strokeStyle = COLORS.fat;
  ctx.lineWidth = Math.max(1, r * 0.14);
  ctx.stroke();
  if (t >= 1) {
    ctx.strokeStyle = "rgba(20, 8, 2, 0.9)";
    ctx.lineWidth = Math.max(1, r * 0.08);
    for (const dx of [-0.35, 0.05]) {
      ctx.beginPath();
      ctx.moveTo(cx + r * (dx - 0.15), cy + r * 0.35);
      ctx.lineTo(cx + r * (dx + 0.3), cy - r * 0.3);
      ctx.stroke();
    }
  }
}

function drawPlate(ctx, cx, cy, r, rim) {
  ellipse(ctx, cx, cy, r, r, COLORS.plate, rim, Math.max(1.5, r * 0.16));
  ellipse(ctx, cx, cy, r * 0.62, r * 0.62, null, "rgba(0, 0, 0, 0.18)", Math.max(1, r * 0.05));
}

export function drawDirtyPlate(ctx, cx, cy, r) {
  drawPlate(ctx, cx, cy, r, COLORS.plateRim);
  ctx.fillStyle = COLORS.dirt;
  for (const [dx, dy, s] of [[-0.3, -0.2, 0.17], [0.25, 0.15, 0.21], [0.05, -0.45, 0.1], [-0.15, 0.4, 0.12]]) {
    ellipse(ctx, cx + dx * r, cy + dy * r, s * r, s * r * 0.8, COLORS.dirt);
  }
}

export function drawCleanPlate(ctx, cx, cy, r) {
  drawPlate(ctx, cx, cy, r, COLORS.cleanRim);
  sparkle(ctx, cx + r * 0.25, cy - r * 0.25, r * 0.28, COLORS.cleanRim);
}

export function drawGarnish(ctx, cx, cy, r) {
  const s = Math.max(2, r * 0.32);
  const spots = [[-0.45, -0.3], [0.1, -0.45], [0.45, -0.05], [-0.2, 0.25], [0.3, 0.4], [-0.55, 0.35]];
  for (const [dx, dy] of spots) {
    ctx.fillStyle = COLORS.onion;
    ctx.fillRect(cx + dx * r - s / 2, cy + dy * r - s / 2, s, s);
    ctx.strokeStyle = COLORS.onionLine;
    ctx.lineWidth = Math.max(1, r * 0.06);
    ctx.strokeRect(cx + dx * r - s / 2, cy + dy * r - s / 2, s, s);
  }
}

export function drawSteakPlate(ctx, cx, cy, r) {
  drawPlate(ctx, cx, cy, r, COLORS.cleanRim);
  drawMeat(ctx, cx, cy + r * 0.05, r * 0.62, 1);
}

export function drawDish(ctx, cx, cy, r) {
  drawPlate(ctx, cx, cy, r, COLORS.cleanRim);
  drawMeat(ctx, cx - r * 0.12, cy + r * 0.08, r * 0.55, 1);
  drawGarnish(ctx, cx + r * 0.35, cy - r * 0.35, r * 0.4);
  ctx.beginPath();
  ctx.moveTo(cx + r * 0.55, cy + r * 0.1);
  ctx.lineTo(cx + r * 0.75, cy - r * 0.15);
  ctx.strokeStyle = COLORS.garnish;
  ctx.lineWidth = Math.max(1.5, r * 0.12);
  ctx.stroke();
}

export function sparkle(ctx, cx, cy, r, color) {
  ctx.beginPath();
  ctx.moveTo(cx, cy - r);
  ctx.lineTo(cx + r * 0.25, cy - r * 0.25);
  ctx.lineTo(cx + r, cy);
  ctx.lineTo(cx + r * 0.25, cy + r * 0.25);
  ctx.lineTo(cx, cy + r);
  ctx.lineTo(cx - r * 0.25, cy + r * 0.25);
  ctx.lineTo(cx - r, cy);
  ctx.lineTo(cx - r * 0.25, cy - r * 0.25);
  ctx.closePath();
  ctx.fillStyle = color;
  ctx.fill();
}

const DRAW = {
  onion: drawOnion,
  meat: (ctx, cx, cy, r) => drawMeat(ctx, cx, cy, r, 0),
  dirty_plate: drawDirtyPlate,
  clean_plate: drawCleanPlate,
  steak_plate: drawSteakPlate,
  dish: drawDish,
};

/** Draw object `kind`; an unknown kind is drawn as a labelled grey disc rather than dropped. */
export function drawObject(ctx, kind, cx, cy, r) {
  const draw = DRAW[kind];
  if (draw) {
    draw(ctx, cx, cy, r);
    return;
  }
  ellipse(ctx, cx, cy, r * 0.8, r * 0.8, "#BBBBBB", COLORS.ink, 1);
  ctx.fillStyle = COLORS.ink;
  ctx.font = `${Math.round(r)}px sans-serif`;
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  ctx.fillText("?", cx, cy);
}

function mix(a, b, t) {
  const pa = [1, 3, 5].map((i) => parseInt(a.slice(i, i + 2), 16));
  const pb = [1, 3, 5].map((i) => parseInt(b.slice(i, i + 2), 16));
  const c = pa.map((v, i) => Math.round(v + (pb[i] - v) * t));
  return `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
}
