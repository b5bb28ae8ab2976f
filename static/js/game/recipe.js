/**
 * The recipe, always in sight: the dish's steps as a compact strip (meat → grill; onion → board → chop;
 * plate → sink → wash → pick up (the "Pick up clean plate" task); clean plate → steak → garnish → serve; docs/domain.md §1), each with the
 * game's own drawing. The participant's current step is highlighted from what the cook holds (always known to
 * them) or, with empty hands, from the task they chose; nothing else about the world is used.
 *
 * Used by the trial page above the kitchen, by the instructions, and by the first-person page.
 */

import { h } from "../dom.js";
import { STATE } from "../vocabulary.js";
import { objectIcon, stationIcon } from "./icons.js";

export const RECIPE = [
  { id: "steak", title: "Steak", steps: [
    { id: "meat", label: "Meat", icon: (px) => objectIcon("meat", px) },
    { id: "grill", label: "Grill", icon: (px) => stationIcon("grill", { state: STATE.COOKING, progress: 5, total: 10 }, px) },
  ] },
  { id: "garnish", title: "Garnish", steps: [
    { id: "onion", label: "Onion", icon: (px) => objectIcon("onion", px) },
    { id: "board", label: "Board", icon: (px) => stationIcon("board", null, px) },
    { id: "chop", label: "Chop", icon: (px) => stationIcon("board", { state: STATE.CHOPPING, progress: 1, total: 2 }, px) },
  ] },
  { id: "plate", title: "Plate", steps: [
    { id: "plate", label: "Plate", icon: (px) => objectIcon("dirty_plate", px) },
    { id: "sink", label: "Sink", icon: (px) => stationIcon("sink", null, px) },
    { id: "wash", label: "Wash", icon: (px) => stationIcon("sink", { state: STATE.WASHING, progress: 1, total: 2 }, px) },
    { id: "take_out", label: "Pick up", icon: (px) => objectIcon("clean_plate", px) },
  ] },
  { id: "serve", title: "Serve", steps: [
    { id: "clean_plate", label: "Clean plate", icon: (px) => objectIcon("clean_plate", px) },
    { id: "steak", label: "Steak", icon: (px) => objectIcon("steak_plate", px) },
    { id: "garnish", label: "Garnish", icon: (px) => objectIcon("dish", px) },
    { id: "serve", label: "Serve", icon: (px) => stationIcon("serve", null, px) },
  ] },
];

/** What the cook holds → the step it is at (the place that object goes next). */
const BY_HELD = {
  meat: "steak.grill", onion: "garnish.board", dirty_plate: "plate.sink",
  clean_plate: "serve.steak", steak_plate: "serve.garnish", dish: "serve.serve",
};

/** With empty hands, the chosen task → its step. */
const BY_TASK = {
  pickup_meat: "steak.meat", pickup_onion: "garnish.onion", chop_onion: "garnish.chop",
  pickup_plate: "plate.plate", wash_plate: "plate.wash", pickup_clean_plate: "plate.take_out",
};

/** The step (`"line.step"`) the participant is at, or null. */
export function currentStep(held, subtask) {
  if (held) return BY_HELD[held] || null;
  return BY_TASK[subtask] || null;
}

export class RecipeStrip {
  /** `compact`: one row, line titles for screen readers only (the trial page); `icon`: icon size in CSS px. */
  constructor({ id = "recipe", compact = true, icon = 22 } = {}) {
    this.steps = new Map();
    this.current = null;
    const lines = RECIPE.map((line) => h("li", { class: "recipe-line", dataset: { line: line.id } },
      h("span", { class: compact ? "visually-hidden" : "recipe-title" }, `${line.title}:`),
      h("ol", { class: "recipe-steps" }, line.steps.map((step, i) => {
        const key = `${line.id}.${step.id}`;
        const node = h("span", { class: "recipe-step" }, step.icon(icon), h("span", { class: "recipe-label" }, step.label));
        this.steps.set(key, node);
        return h("li", { class: "recipe-item", dataset: { step: key } },
          i ? h("span", { class: "recipe-arrow", "aria-hidden": "true" }, "→") : null, node);
      }))));
    this.node = h("section", { class: `recipe${compact ? " compact" : ""}`, id, "aria-label": "Recipe" },
      h("ol", { class: "recipe-lines" }, lines));
  }

  /** Highlight the step for what the cook holds (`held`) and the current task (`subtask`). */
  update(held, subtask) {
    const step = currentStep(held, subtask);
    if (step === this.current) return;
    this.current = step;
    for (const [key, node] of this.steps) {
      const on = key === step;
      node.classList.toggle("current", on);
      if (on) node.parentElement.setAttribute("aria-current", "step");
      else node.parentElement.removeAttribute("aria-current");
    }
    this.node.dataset.current = step || "";
  }
}
