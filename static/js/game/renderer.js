/**
 * The kitchen canvas. It draws exactly one server `state` message: the cells it lists (the participant's
 * field of view at that tick), the robot if the message has it, and the participant's cook. Every other
 * cell is painted black — nothing is remembered from earlier ticks, so a black cell never shows stale
 * terrain, objects or the robot.
 *
 * Only the part of the grid worth drawing is shown (`hello.bounds`: every floor cell and station plus one ring
 * of cells), fitted to its container at a whole number of device pixels per cell (devicePixelRatio aware), so
 * the kitchen fills the space and lines stay crisp at any zoom. Drawing happens in requestAnimationFrame, only when a new
 * message arrived or the size changed, so input handling never waits for it.
 *
 * The admin dashboard draws the whole kitchen with the same painter and passes an overlay: the
 * participant's field of view, shown as a translucent mask over the cells outside it (see `paintOverlay`).
 * The participant's client never passes one.
 */

import { COLORS, OUT_OF_VIEW } from "./palette.js";
import { drawCell } from "./stations.js";
import { drawAgent } from "./agents.js";
import { heldLabel } from "../labels.js";

export class KitchenView {
  constructor(canvas, container, { maxCell = 96, label = null } = {}) {
    this.bounds = null;
    this.canvas = canvas;
    this.container = container;
    this.ctx = canvas.getContext("2d", { alpha: false });
    this.maxCell = maxCell;
    this.label = label;
    this.width = 0;
    this.height = 0;
    this.state = null;
    this.overlay = null;
    this.frame = 0;
    this.resizer = new ResizeObserver(() => this.invalidate());
    this.resizer.observe(container);
    this.onDpr = () => this.invalidate();
    window.addEventListener("resize", this.onDpr);
  }

  /** The grid's size, and the part of it to draw (`{left, top, width, height}`; default: all of it). */
  setGrid(width, height, bounds = null) {
    this.width = width;
    this.height = height;
    this.bounds = bounds || { left: 0, top: 0, width, height };
    this.invalidate();
  }

  /**
   * Show the state of one tick (a `state` message); the previous one is forgotten entirely. `overlay`
   * (admin only): `{fov: [[x, y], …]}` masks the cells outside the participant's view.
   */
  update(state, overlay = null) {
    this.state = state;
    this.overlay = overlay;
    this.invalidate();
  }

  invalidate() {
    if (this.frame) return;
    this.frame = window.requestAnimationFrame(() => {
      this.frame = 0;
      this.draw();
    });
  }

  geometry() {
    const dpr = window.devicePixelRatio || 1;
    const availW = Math.max(this.container.clientWidth, 1);
    const availH = Math.max(this.container.clientHeight, 1);
    const cssCell = Math.min(availW / this.bounds.width, availH / this.bounds.height, this.maxCell);
    const cell = Math.max(8, Math.floor(cssCell * dpr));
    return { dpr, cell };
  }

  draw() {
    if (!this.width || !this.height) return;
    const { dpr, cell } = this.geometry();
    const w = cell * this.bounds.width;
    const h = cell * this.bounds.height;
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
    }
    this.canvas.style.width = `${w / dpr}px`;
    this.canvas.style.height = `${h / dpr}px`;
    paintState(this.ctx, this.width, this.height, this.state, cell, this.overlay, this.bounds);
    this.place(w / dpr, h / dpr);
    this.describe(this.state, cell, dpr);
  }

  /**
   * Centre the canvas in its container with its corner on a whole device pixel of the page (a fractional
   * position would resample, and blur, every line).
   */
  place(cssW, cssH) {
    const dpr = window.devicePixelRatio || 1;
    const box = this.container.getBoundingClientRect();
    const innerX = box.left + this.container.clientLeft;
    const innerY = box.top + this.container.clientTop;
    const snap = (origin, free) => Math.round((origin + Math.max(0, free / 2)) * dpr) / dpr - origin;
    this.canvas.style.left = `${snap(innerX, this.container.clientWidth - cssW)}px`;
    this.canvas.style.top = `${snap(innerY, this.container.clientHeight - cssH)}px`;
  }

  /** Data attributes of what was drawn (for tests and tools) and a text alternative for screen readers. */
  describe(state, cell, dpr) {
    const d = this.canvas.dataset;
    d.grid = `${this.width}x${this.height}`;
    const b = this.bounds;
    d.bounds = `${b.left},${b.top},${b.width},${b.height}`;
    d.cell = String(cell / dpr);
    d.dpr = String(dpr);
    if (!state) return;
    d.tick = String(state.tick);
    d.you = `${state.you.x},${state.you.y},${state.you.facing}`;
    d.held = state.you.held || "";
    d.robot = state.robot ? `${state.robot.x},${state.robot.y},${state.robot.facing}` : "";
    d.visible = String(state.cells.length);
    if (this.overlay) d.fov = String(this.overlay.fov.length);
    if (this.label) {
      const text = this.label(state, this.width, this.height);
      if (this.canvas.getAttribute("aria-label") !== text) this.canvas.setAttribute("aria-label", text);
      return;
    }
    const robot = state.robot ? "The robot is in view." : "The robot is out of view.";
    // No grid size: the canvas draws only the kitchen's reachable part (hello.bounds), and "cells" is our word.
    const label = `The kitchen from above. You face ${state.you.facing}, holding ` +
      `${heldLabel(state.you.held)}. ${robot} Black cells are outside your view.`;
    if (this.canvas.getAttribute("aria-label") !== label) this.canvas.setAttribute("aria-label", label);
  }

  destroy() {
    this.resizer.disconnect();
    window.removeEventListener("resize", this.onDpr);
    if (this.frame) window.cancelAnimationFrame(this.frame);
    this.frame = 0;
  }
}

/**
 * Paint one state message on a grid of `width` × `height` cells of `cell` device pixels: black
 * everywhere, then the listed cells, the `overlay` if any, the robot if present, and the participant's
 * cook. With an overlay the agents stay unmasked, and a robot outside the field of view gets a dashed ring.
 * `bounds` (`{left, top, width, height}`) paints only that part of the grid, its top-left cell at (0, 0).
 */
export function paintState(ctx, width, height, state, cell, overlay = null, bounds = null) {
  const b = bounds || { left: 0, top: 0, width, height };
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = OUT_OF_VIEW;
  ctx.fillRect(0, 0, cell * b.width, cell * b.height);
  if (!state) return;
  ctx.setTransform(1, 0, 0, 1, -b.left * cell, -b.top * cell);
  const inside = (x, y) => x >= b.left && y >= b.top && x < b.left + b.width && y < b.top + b.height;
  for (const c of state.cells) {
    if (c.x < 0 || c.y < 0 || c.x >= width || c.y >= height || !inside(c.x, c.y)) continue;
    clipped(ctx, c.x * cell, c.y * cell, cell, () => drawCell(ctx, c, c.x * cell, c.y * cell, cell));
  }
  if (overlay) paintOverlay(ctx, width, height, overlay, cell);
  if (state.robot) {
    const r = state.robot;
    clipped(ctx, r.x * cell, r.y * cell, cell, () => drawAgent(ctx, "robot", r, r.x * cell, r.y * cell, cell));
    if (overlay && !overlay.fov.some(([x, y]) => x === r.x && y === r.y)) hiddenRing(ctx, r.x * cell, r.y * cell, cell);
  }
  if (state.you) {
    const you = state.you;
    clipped(ctx, you.x * cell, you.y * cell, cell, () => drawAgent(ctx, "human", you, you.x * cell, you.y * cell, cell));
  }
  ctx.setTransform(1, 0, 0, 1, 0, 0);
}

/** A dashed white ring around an agent the participant cannot see. */
function hiddenRing(ctx, x0, y0, s) {
  ctx.save();
  ctx.setLineDash([Math.max(3, s / 10), Math.max(2, s / 14)]);
  ctx.lineWidth = Math.max(1.5, s / 24);
  ctx.strokeStyle = "#FFFFFF";
  ctx.beginPath();
  ctx.arc(x0 + s / 2, y0 + s / 2, s * 0.46, 0, Math.PI * 2);
  ctx.stroke();
  ctx.restore();
}

/**
 * The participant's field of view over a fully drawn kitchen: every cell outside `overlay.fov` under a
 * translucent black mask (`overlay.alpha`, default 0.6, so what the participant cannot see stays readable
 * but dim), and the border of the field of view traced in yellow.
 */
export function paintOverlay(ctx, width, height, overlay, cell) {
  const seen = new Set(overlay.fov.map(([x, y]) => y * width + x));
  const inside = (x, y) => x >= 0 && y >= 0 && x < width && y < height && seen.has(y * width + x);
  ctx.fillStyle = `rgba(0, 0, 0, ${overlay.alpha ?? 0.6})`;
  for (let y = 0; y < height; y += 1) {
    for (let x = 0; x < width; x += 1) {
      if (!inside(x, y)) ctx.fillRect(x * cell, y * cell, cell, cell);
    }
  }
  const line = Math.max(2, Math.round(cell / 16));
  ctx.fillStyle = overlay.edge || COLORS.fovEdge;
  for (let y = 0; y < height; y += 1) {
    for (let x = 0; x < width; x += 1) {
      if (!inside(x, y)) continue;
      const x0 = x * cell;
      const y0 = y * cell;
      if (!inside(x, y - 1)) ctx.fillRect(x0, y0, cell, line);
      if (!inside(x, y + 1)) ctx.fillRect(x0, y0 + cell - line, cell, line);
      if (!inside(x - 1, y)) ctx.fillRect(x0, y0, line, cell);
      if (!inside(x + 1, y)) ctx.fillRect(x0 + cell - line, y0, line, cell);
    }
  }
}

function clipped(ctx, x, y, s, draw) {
  ctx.save();
  ctx.beginPath();
  ctx.rect(x, y, s, s);
  ctx.clip();
  draw();
  ctx.restore();
}
