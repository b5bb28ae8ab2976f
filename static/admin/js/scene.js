/**
 * Drawing a trial for the experimenter with the participant client's own painter
 * (static/js/game/renderer.js): the server sends the kitchen's fixed `grid` (terrain names) once and a
 * `frame` per tick (both agents, objects, station statuses, the participant's field of view `fov`, and
 * `kb`, the kitchen as the participant's modelled knowledge has it). Here they become the `state` shape
 * the painter draws — every cell, nothing masked — and the field of view becomes the painter's overlay.
 */

import { h } from "../../js/dom.js";
import { KitchenView } from "../../js/game/renderer.js";

/** Every cell of `grid` with the objects and station statuses of `contents` (a frame or its `kb`). */
export function cellsOf(grid, contents) {
  const objects = new Map(contents.objects.map((o) => [`${o.x},${o.y}`, o.object]));
  const stations = new Map(contents.stations.map((s) => [`${s.x},${s.y}`, s]));
  const cells = [];
  grid.terrain.forEach((row, y) => row.forEach((terrain, x) => {
    const key = `${x},${y}`;
    const station = stations.get(key);
    cells.push({ x, y, terrain, object: objects.get(key) || null,
                 station: station ? { state: station.state, progress: station.progress, total: station.total } : null });
  }));
  return cells;
}

/** The whole world of a frame, in the painter's `state` shape. */
export function worldState(grid, frame) {
  return { tick: frame.tick, cells: cellsOf(grid, frame), you: frame.human, robot: frame.robot };
}

/** The kitchen as the participant's modelled KB has it: believed objects and stations, the robot where it
 * was last seen (absent if never), the participant's own cook where it is. */
export function beliefState(grid, frame) {
  return { tick: frame.tick, cells: cellsOf(grid, frame.kb), you: frame.human, robot: frame.kb.robot };
}

/** A kitchen canvas fitted to its box; `show(grid, state, overlay)` draws one tick. */
export class Stage {
  constructor(id, { maxCell = 72, className = "", label } = {}) {
    this.canvas = h("canvas", { id, class: "kitchen-canvas", role: "img", "aria-label": "Kitchen" });
    this.node = h("div", { class: `stage admin-stage ${className}`.trim() }, this.canvas);
    this.maxCell = maxCell;
    this.label = label;
    this.view = null;
    this.size = "";
  }

  show(grid, state, overlay = null) {
    if (!this.view) this.view = new KitchenView(this.canvas, this.node, { maxCell: this.maxCell, label: this.label });
    const size = `${grid.width}x${grid.height}`;
    if (size !== this.size) {
      this.size = size;
      this.view.setGrid(grid.width, grid.height);
    }
    this.view.update(state, overlay);
  }

  destroy() {
    if (this.view) this.view.destroy();
    this.view = null;
  }
}

export function worldLabel(angle) {
  return (state, width, height) => `The whole kitchen, ${width} by ${height} cells, at tick ${state.tick}. ` +
    `Cells outside the participant's ${angle}° field of view are dimmed. The participant faces ${state.you.facing}` +
    `${state.robot ? `; the robot is at column ${state.robot.x + 1}, row ${state.robot.y + 1}` : ""}.`;
}

export function beliefLabel(state) {
  return `The kitchen as the participant's modelled knowledge has it at tick ${state.tick}` +
    `${state.robot ? "" : "; the robot's position is unknown to the participant"}.`;
}
