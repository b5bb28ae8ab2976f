/**
 * The participant's first-person camera for the live view and the replay of a `first_person` trial, shown on
 * request beside the top-down picture. It draws exactly what the participant's screen drew at that tick —
 * the cells in their field of view (the frame's `fov`), the robot only when it is in view — with the
 * participant's own 3D view (../../js/firstperson/), so the experimenter sees what the participant could see;
 * the top-down picture next to it already shows the whole world. three.js is loaded only when the camera is
 * first shown.
 */

import { h } from "../../js/dom.js";
import { cellsOf } from "./scene.js";

/** The frame as the participant's `state` message had it: only the cells in view, the robot if in view. */
export function participantState(grid, frame) {
  const seen = new Set(frame.fov.map(([x, y]) => `${x},${y}`));
  const robot = frame.robot && seen.has(`${frame.robot.x},${frame.robot.y}`) ? frame.robot : null;
  return { tick: frame.tick, you: frame.human, robot, cells: cellsOf(grid, frame).filter((c) => seen.has(`${c.x},${c.y}`)) };
}

export class ParticipantCamera {
  constructor() {
    this.box = h("div", { class: "camera-box", id: "participant-camera", hidden: true });
    this.button = h("button", { type: "button", class: "small secondary", id: "camera-toggle", "aria-pressed": "false",
                                 "aria-controls": "participant-camera", onclick: () => this.toggle() },
      "Show the participant's camera");
    this.node = h("div", { class: "camera-panel" }, this.button, this.box);
    this.view = null;
    this.loading = null;
    this.last = null;
    this.gone = false;
  }

  toggle() {
    const on = this.box.hidden;
    this.box.hidden = !on;
    this.button.setAttribute("aria-pressed", String(on));
    this.button.textContent = on ? "Hide the participant's camera" : "Show the participant's camera";
    if (on && this.last) this.show(...this.last);
  }

  /** Draw the participant's camera at `frame` (`fov` degrees, gliding over `tickMs`) when it is shown. */
  show(grid, frame, fov, tickMs) {
    this.last = [grid, frame, fov, tickMs];
    if (this.box.hidden) return;
    if (!this.view) {
      this.loading ||= import("../../js/firstperson/view.js").then(({ FirstPersonView }) => {
        if (this.gone) return;
        this.view = new FirstPersonView(this.box, { id: "camera-canvas", label: (s) =>
          `The participant's first-person view at tick ${s.tick}: what their screen showed.` });
        this.show(...this.last);
      });
      return;
    }
    this.view.tickMs = tickMs;
    this.view.setFov(fov);
    this.view.setGrid(grid.width, grid.height);
    this.view.update(participantState(grid, frame));
  }

  destroy() {
    this.gone = true;
    if (this.view) this.view.destroy();
  }
}
