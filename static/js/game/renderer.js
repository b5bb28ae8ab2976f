/**
 * The kitchen canvas. It draws exactly one server `state` message: the cells it lists (the participant's
 * field of view at that tick), the robot if the message has it, and the participant's cook. Every other
 * cell is painted black — nothing is remembered from earlier ticks, so a black cell never shows stale
 * terrain, objects or the robot.
 *
 * The grid is fitted to its container at a whole number of device pixels per cell (devicePixelRatio
 * aware), so lines stay crisp at any zoom. Drawing happens in requestAnimationFrame, only when a new
 * message arrived or the size changed, so input handling never waits for it.
 */

import { OUT_OF_VIEW } from "./palette.js";
import { drawCell } from "./stations.js";
import { drawAgent } from "./agents.js";
import { heldLabel } from "../labels.js";

export class KitchenView {
  constructor(canvas, container, { maxCell = 96 } = {}) {
    this.canvas = canvas;
    this.container = container;
    this.ctx = canvas.getContext("2d", { alpha: false });
    this.maxCell = maxCell;
    this.width = 0;
    this.height = 0;
    this.state = null;
    this.frame = 0;
    this.resizer = new ResizeObserver(() => this.invalidate());
    this.resizer.observe(container);
    this.onDpr = () => this.invalidate();
    window.addEventListener("resize", this.onDpr);
  }

  setGrid(width, height) {
    this.width = width;
    this.height = height;
    this.invalidate();
  }

  /** Show the state of one tick (a `state` message); the previous one is forgotten entirely. */
  update(state) {
    this.state = state;
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
    const cssCell = Math.min(availW / this.width, availH / this.height, this.maxCell);
    const cell = Math.max(8, Math.floor(cssCell * dpr));
    return { dpr, cell };
  }

  draw() {
    if (!this.width || !this.height) return;
    const { dpr, cell } = this.geometry();
    const w = cell * this.width;
    const h = cell * this.height;
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
    }
    this.canvas.style.width = `${w / dpr}px`;
    this.canvas.style.height = `${h / dpr}px`;
    paintState(this.ctx, this.width, this.height, this.state, cell);
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
    d.cell = String(cell / dpr);
    d.dpr = String(dpr);
    if (!state) return;
    d.tick = String(state.tick);
    d.you = `${state.you.x},${state.you.y},${state.you.facing}`;
    d.held = state.you.held || "";
    d.robot = state.robot ? `${state.robot.x},${state.robot.y},${state.robot.facing}` : "";
    d.visible = String(state.cells.length);
    const robot = state.robot ? "The robot is in view." : "The robot is out of view.";
    const label = `Kitchen, ${this.width} by ${this.height} cells. You face ${state.you.facing}, holding ` +
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
 * everywhere, then the listed cells, the robot if present, and the participant's cook.
 */
export function paintState(ctx, width, height, state, cell) {
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = OUT_OF_VIEW;
  ctx.fillRect(0, 0, cell * width, cell * height);
  if (!state) return;
  for (const c of state.cells) {
    if (c.x < 0 || c.y < 0 || c.x >= width || c.y >= height) continue;
    clipped(ctx, c.x * cell, c.y * cell, cell, () => drawCell(ctx, c, c.x * cell, c.y * cell, cell));
  }
  if (state.robot) {
    const r = state.robot;
    clipped(ctx, r.x * cell, r.y * cell, cell, () => drawAgent(ctx, "robot", r, r.x * cell, r.y * cell, cell));
  }
  if (state.you) {
    const you = state.you;
    clipped(ctx, you.x * cell, you.y * cell, cell, () => drawAgent(ctx, "human", you, you.x * cell, you.y * cell, cell));
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
