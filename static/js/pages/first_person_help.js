/**
 * The instructions for rounds seen in first person (docs/client.md, "The first-person view"): the keys as they
 * act there, relative to where the cook faces (firstperson/steering.js), and the example kitchen drawn by the
 * game's own 3D view from the cook's eyes, so "dark = outside your view" is shown the way the round shows it.
 * The 3D module is loaded only for these studies; without WebGL the page says so in words instead.
 */

import { h } from "../dom.js";
import { INTERRUPTS } from "../labels.js";
import { RELATIVE_LABELS } from "../firstperson/steering.js";
import { exampleScenes, loadExample } from "../game/picture.js";

const RELATIVE_WHAT = {
  up: "walk one cell ahead (if a counter is ahead, nothing happens)",
  left: "turn to your left, and step there when the floor is free",
  right: "turn to your right, and step there when the floor is free",
  down: "turn around, and step back when the floor behind you is free",
  interact: "pick up, put down or use what you face",
  stay: "wait one moment",
  stop: "cancel your current task",
};

/** The keys of a first-person round: what each does, relative to where you face. */
export function firstPersonKeys() {
  return h("table", { class: "keys-table", id: "keys-first-person" },
    h("thead", {}, h("tr", {}, h("th", { scope: "col" }, "Action"), h("th", { scope: "col" }, "Keys"),
      h("th", { scope: "col" }, "What it does"))),
    h("tbody", {}, INTERRUPTS.map((i) => h("tr", { dataset: { interrupt: i.id } },
      h("td", {}, RELATIVE_LABELS[i.id] || i.label),
      h("td", {}, i.keys.map((k, n) => [n ? " or " : "", h("kbd", {}, k)])),
      h("td", {}, RELATIVE_WHAT[i.id] || "")))));
}

function exampleHello(scenes, angle) {
  return { fov_angle: angle, tick_rate_hz: 5, trial: { id: 0 }, width: scenes.width, height: scenes.height };
}

/**
 * The example kitchen as the cook sees it in first person with the study's field of view `angle`: the cells
 * in view drawn, everything else dark. Returns `[figure, destroy]`: the figure at once (the 3D view fills it
 * when loaded), and what frees the view when the page is left.
 */
export function firstPersonPicture(angle) {
  let view = null;
  let gone = false;
  const stage = h("div", { class: "fp-picture-stage", id: "fp-picture-stage" },
    h("p", { class: "muted" }, "Loading the picture…"));
  const figure = h("figure", { class: "fp-picture", id: "fp-picture" }, stage,
    h("figcaption", {}, "What you see in a round: the kitchen ahead of you. Everything outside your view is dark, " +
      "even what you saw a moment ago; here the robot, behind you, is out of view."));
  Promise.all([loadExample(), import("../firstperson/view.js")]).then(([example, { FirstPersonView }]) => {
    if (gone) return;
    const scenes = exampleScenes(example, angle);
    stage.replaceChildren();
    view = new FirstPersonView(stage, { id: "fp-picture-canvas", label: () => "The example kitchen seen " +
      "through the cook's eyes: the grill, the chopping board and the sink ahead are lit; the rest is dark." });
    view.configure(exampleHello(scenes, angle));
    view.update({ tick: 0, ...scenes.view });
    figure.dataset.ready = "true";
  }).catch(() => {
    stage.replaceChildren(h("p", { class: "muted" }, "The picture could not be shown in this browser: in a round " +
      "you see the kitchen ahead of you, and everything outside your view is dark."));
    figure.dataset.ready = "false";
  });
  return [figure, () => {
    gone = true;
    if (view) view.destroy();
  }];
}
