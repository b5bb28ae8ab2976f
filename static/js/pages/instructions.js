/**
 * Instructions: the study's text (Markdown), the recipe (the same strip the trial page shows above the
 * kitchen), then a picture of what the black cells mean drawn by the game's own painter (the whole kitchen
 * beside the participant's view with the study's field-of-view angle, `session.fov_angle`), a legend of
 * everything in the kitchen, and the keys. The button finishes the step. Rounds seen in first person
 * (`session.views`) get their own picture, drawn by the 3D view, and their own keys, relative to where the
 * cook faces (first_person_help.js); a study with both views teaches both.
 *
 * The angle is the study's, sent in every session view (docs/protocol.md §1). Without a valid one the page
 * says so where the cone would be explained and keeps the button disabled: a participant is never told a
 * field of view the study did not set.
 */

import { h, show } from "../dom.js";
import { renderMarkdown } from "../markdown.js";
import { INTERRUPTS } from "../labels.js";
import { examplePicture, legend, loadExample } from "../game/picture.js";
import { RecipeStrip } from "../game/recipe.js";
import { firstPersonKeys, firstPersonPicture } from "./first_person_help.js";
import { actionError } from "./common.js";

function coneText(angle) {
  if (angle >= 360) return "In this study you see the whole kitchen, so no cell is black.";
  return `You see what is in front of you, in a cone of ${angle}° as in the picture below, and the cells right ` +
    "beside you. Everything else is drawn black — even things you saw a moment ago, because they may have " +
    "changed. Turn or walk to look again. The robot may be in a black cell. " + ROBOT_SEES;
}

const ROBOT_SEES = "The robot sees the whole kitchen all the time, including you and what you hold.";

/** The study's field of view in degrees from the session view, or null when it is missing or out of (0, 360]. */
export function studyAngle(session) {
  const angle = session.fov_angle;
  return typeof angle === "number" && angle > 0 && angle <= 360 ? angle : null;
}

function coneSection(angle) {
  if (angle === null) {
    return [h("p", { class: "error", role: "alert", id: "fov-error" },
      "This page could not load the study's field of view, so it cannot show you what you will see. Please " +
      "reload the page; if this message stays, contact the researcher.")];
  }
  const picture = h("div", { class: "picture", id: "instructions-picture" }, h("p", { class: "muted" }, "Loading the picture…"));
  loadExample().then((example) => picture.replaceChildren(examplePicture(example, 40, angle))).catch(() => {
    picture.replaceChildren(h("p", { class: "muted" }, "The picture could not be loaded; the text above explains it."));
  });
  return [h("p", { id: "fov-text", dataset: { angle: String(angle) } }, coneText(angle)), picture];
}

function firstPersonSection(angle) {
  if (angle === null) return [[], () => {}];
  const [picture, destroy] = firstPersonPicture(angle);
  const text = angle >= 360 ? "In first-person rounds you see the kitchen through the cook's eyes, all around you."
    : `In first-person rounds you see the kitchen through the cook's eyes, in a cone of ${angle}° ahead of you. ` +
      "What is outside your view is dark — even things you saw a moment ago, because they may have changed. Turn " +
      "or walk to look again. The robot may be in the dark. " + ROBOT_SEES;
  return [[h("p", { id: "fp-text" }, text), picture], destroy];
}

const TOP_DOWN_KEYS_NOTE = "A move turns you toward that direction and walks one cell if it is free floor. ";
const KEYS_NOTE = "Interrupts act at once, one per key press; afterwards your task continues from where you are. " +
  "Stop cancels the task. A task that cannot work with what you hold is greyed out, and the reason shows when you " +
  "point at it. The keys 1–9, 0, - and = choose a task: each task's key is shown on its button.";

function topDownKeys() {
  return h("table", { class: "keys-table", id: "keys-top-down" },
    h("thead", {}, h("tr", {}, h("th", { scope: "col" }, "Action"), h("th", { scope: "col" }, "Keys"))),
    h("tbody", {}, INTERRUPTS.map((i) => h("tr", {}, h("td", {}, i.label),
      h("td", {}, i.keys.map((k, n) => [n ? " or " : "", h("kbd", {}, k)]))))));
}

export function instructionsPage(root, ctx) {
  const angle = studyAngle(ctx.session);
  const views = ctx.session.views && ctx.session.views.length ? ctx.session.views : ["top_down"];
  const topDown = views.includes("top_down");
  const firstPerson = views.includes("first_person");
  const both = topDown && firstPerson;
  const [fpSection, destroyPicture] = firstPerson ? firstPersonSection(angle) : [[], () => {}];
  const error = h("p", { class: "error", role: "alert", id: "instructions-error" });
  const next = h("button", { type: "button", class: "primary", id: "instructions-done", disabled: angle === null },
    "I have read this: continue");
  next.addEventListener("click", async () => {
    next.disabled = true;
    try {
      ctx.route(await ctx.api.instructionsDone());
    } catch (exc) {
      if (!actionError(exc, error, ctx)) next.disabled = false;
    }
  });

  show(root, h("section", { class: "card prose wide", id: "instructions", "aria-label": "Instructions" },
    renderMarkdown(ctx.session.instructions),
    h("h2", {}, "The recipe"),
    h("p", {}, "Each dish is made in four lines of work, in this order; during a round the step you are at is " +
      "highlighted from what you hold."),
    new RecipeStrip({ id: "instructions-recipe", compact: false, icon: 30 }).node,
    topDown ? [h("h2", {}, both ? "What the black cells mean (rounds seen from above)" : "What the black cells mean"),
      coneSection(angle)] : [h("h2", {}, "What you see"), firstPerson && angle === null ? coneSection(angle) : []],
    both ? h("h2", {}, "What you see in first-person rounds") : null,
    fpSection,
    h("h2", {}, "What is in the kitchen"),
    firstPerson ? h("p", {}, "Everything has the same colours seen from above and through the cook's eyes.") : null,
    legend(),
    topDown ? [h("h2", {}, both ? "Keys in rounds seen from above" : "Keys"), topDownKeys()] : null,
    firstPerson ? [h("h2", {}, both ? "Keys in first-person rounds" : "Keys"), firstPersonKeys()] : null,
    h("p", { id: "keys-note" }, (topDown ? TOP_DOWN_KEYS_NOTE : "") + KEYS_NOTE),
    h("div", { class: "actions" }, next), error));
  return destroyPicture;
}
