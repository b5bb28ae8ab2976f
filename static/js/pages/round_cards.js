/**
 * The cards around a round: the intro before it starts (or when it is already in progress in another tab,
 * ended while the participant was away, or starts again), and the summary after it. Never steps or ticks:
 * times are seconds, and a practice round that is not scored shows no score.
 */

import { h, show } from "../dom.js";
import { roundLabel } from "../game/hud.js";

const INTRO = {
  new: {
    practice: ["Try the controls: choose tasks with the buttons on the right, interrupt with the keys or the " +
      "buttons under the kitchen. This round is for practice; its result does not count.",
    "The round starts as soon as you press the button."],
    main: ["Work with the robot to deliver the orders as quickly as you can. Remember: black cells are " +
      "outside your view.", "The round starts as soon as you press the button."],
    main_first_person: ["Work with the robot to deliver the orders as quickly as you can.",
      "The round starts as soon as you press the button."],
    button: { practice: "Start practice", main: "Start round" },
  },
  in_progress: {
    text: ["This round is already in progress: it was started before this page was reloaded, or in another tab " +
      "or window.", "Continue it here; any other tab stops showing it."],
    button: "Continue the round",
  },
  ended_away: {
    text: ["This round ended while you were away: the connection was lost for longer than the study allows.",
      "You can continue with the study."],
    button: "Continue",
  },
  restart: {
    text: ["You were away from this round for too long, so it starts again from the beginning."],
    button: "Start the round again",
  },
};

/** The card before a round; `onStart` connects to it. */
export function introCard(root, trial, onStart) {
  const practice = trial.kind === "practice";
  const status = INTRO[trial.status] ? trial.status : "new";
  const words = INTRO[status];
  const firstPerson = trial.view === "first_person";
  const text = status === "new" ? words[practice ? "practice" : firstPerson ? "main_first_person" : "main"]
    : words.text;
  const label = status === "new" ? words.button[practice ? "practice" : "main"] : words.button;
  const button = h("button", { type: "button", class: "primary", id: "start-round", onclick: onStart }, label);
  show(root, h("section", { class: "card narrow", id: "round-intro", dataset: { status },
                            "aria-labelledby": "round-title" },
    h("h1", { id: "round-title", tabindex: "-1" }, practice ? "Practice round" : roundLabel(trial)),
    practice ? h("p", { class: "muted", id: "round-number" }, roundLabel(trial)) : null,
    text.slice(0, 1).map((t) => h("p", { id: "round-text" }, t)),
    firstPerson
      ? h("p", { id: "first-person-note" }, "In this round you see the kitchen through the cook's eyes; what is " +
          "outside your view is dark. ↑ or W steps forward, ← → or A D turn left and right (stepping that way " +
          "when the floor is free), ↓ or S turns around, Space interacts with what you face.")
      : null,
    status === "new" && trial.kitchen_waits
      ? h("p", { id: "clock-note" }, "The kitchen waits for you: the robot and the steaks move only while your " +
          "cook moves or works. To let time pass while a steak cooks, press . (stay).")
      : null,
    text.slice(1).map((t) => h("p", { class: "muted" }, t)),
    h("div", { class: "actions" }, button)), button);
}

/** How the round ended, in words (`seconds`: its length, or null when the clock waited for the participant). */
export function endText(end, seconds) {
  if (end.status === "abandoned") {
    return "The connection was lost for longer than the study allows, so the round was ended. You can continue " +
      "with the study.";
  }
  if (end.reason === "time_limit") {
    return "This round reached its time limit while the kitchen was waiting for your next task, so it ended.";
  }
  if (end.reason !== "delivered") return "The time for this round ran out before every order was delivered.";
  return seconds === null ? "All orders delivered." : `All orders delivered in ${Math.round(seconds)} seconds.`;
}

/** The card after a round. `scored`: show the score; `seconds`: the round's length or null. */
export function summaryCard(root, end, { scored, seconds, onContinue }) {
  const title = end.status === "abandoned" ? "This round ended while you were away"
    : end.reason === "delivered" ? "Round complete" : "Time is up";
  const next = { questionnaire: "Next: a few questions about this round.", practice: "Next: another practice round.",
                 trial: "Next: another round.", done: "That was the last round." }[end.next] || "";
  const button = h("button", { type: "button", class: "primary", id: "continue", onclick: onContinue }, "Continue");
  show(root, h("section", { class: "card narrow", id: "round-summary", "aria-labelledby": "summary-title" },
    h("h1", { id: "summary-title" }, title),
    h("p", { id: "summary-text" }, endText(end, seconds)),
    h("dl", { class: "summary" },
      h("dt", {}, "Dishes delivered"), h("dd", { id: "summary-delivered" }, String(end.delivered)),
      scored ? [h("dt", {}, "Score"), h("dd", { id: "summary-score" }, String(end.score))] : null),
    scored ? null : h("p", { class: "muted" }, "Practice rounds are not scored."),
    next ? h("p", { class: "muted" }, next) : null,
    h("div", { class: "actions" }, button)), button);
}
