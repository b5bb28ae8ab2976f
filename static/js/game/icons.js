/**
 * Small pictures drawn by the game's own painters (a station, an object, an agent) for legends, the recipe
 * strip and the instructions, crisp at the screen's pixel ratio.
 */

import { h } from "../dom.js";
import { FLOOR } from "../vocabulary.js";
import { drawCell } from "./stations.js";
import { drawObject } from "./items.js";

/** A `cssSize` square canvas drawn by `draw(ctx, sizeInDevicePixels)`; decorative (aria-hidden). */
export function iconCanvas(draw, cssSize = 44, className = "legend-icon") {
  const dpr = window.devicePixelRatio || 1;
  const s = Math.round(cssSize * dpr);
  const canvas = h("canvas", { class: className, "aria-hidden": "true" });
  canvas.width = s;
  canvas.height = s;
  canvas.style.width = `${s / dpr}px`;
  canvas.style.height = `${s / dpr}px`;
  draw(canvas.getContext("2d"), s);
  return canvas;
}

/** An object (onion, meat, plates, dish) on a floor tile. */
export function objectIcon(kind, cssSize, className) {
  return iconCanvas((ctx, s) => {
    drawCell(ctx, { terrain: FLOOR }, 0, 0, s);
    drawObject(ctx, kind, s / 2, s / 2, s * 0.36);
  }, cssSize, className);
}

/** A station (`terrain` as in `state.cells`) with an optional status. */
export function stationIcon(terrain, station = null, cssSize, className) {
  return iconCanvas((ctx, s) => drawCell(ctx, { terrain, station }, 0, 0, s), cssSize, className);
}
