/**
 * The short message in the HUD, beside "your task", that says why a task did nothing ("The onion is not
 * chopped yet"), or, when the team has got nothing done for a while, a hint ("You are standing where the board
 * is used"); never over the kitchen, whose cells it would hide. A polite live region, so screen readers
 * announce it too. A task that ended itself keeps its message a little longer than a passing notice.
 */

import { h } from "../dom.js";
import { blockedText } from "./reasons.js";
import { subtaskLabel } from "../labels.js";

const NOTICE_MS = 3500;
const ENDED_MS = 6000;
const HINT_MS = 8000;
const WARNING_MS = 20000;

/** Why the round would not count if it ended now (server/flow/engagement.py's rules), and what to do. */
export const WARNINGS = {
  no_actions: "Take part, or this round will not count: choose a task.",
  idle: "Choose your next task, or this round will not count.",
  task_steps: "The robot is doing all the work: choose tasks, or this round will not count.",
  refused_tasks: "Most of your tasks could not work: look at the kitchen before you choose, or this round will not count.",
};

export class TaskNote {
  constructor() {
    this.text = h("span", { class: "task-note-text" });
    this.node = h("p", { class: "task-note", id: "task-note", role: "status", "aria-live": "polite", hidden: true },
      this.text);
    this.timer = 0;
    this.waits = false;
  }

  /** Say `text` (`kind`: `info` or `blocked`) for `ms` milliseconds. */
  say(text, kind = "info", ms = NOTICE_MS) {
    window.clearTimeout(this.timer);
    this.text.textContent = text;
    this.node.dataset.kind = kind;
    this.node.hidden = false;
    this.timer = window.setTimeout(() => this.clear(), ms);
  }

  /** A server `blocked` message: why the current task did nothing, or why it stopped. On the paper's clock
   * (`waits`: the kitchen waits for the participant) a cooking steak needs the participant to let time pass. */
  blocked(message) {
    const why = blockedText(message);
    const wait = this.waits && message.reason === "steak_cooking" ? " Press . (stay) to let it cook." : "";
    const text = (message.ended ? `${subtaskLabel(message.subtask)} stopped: ${why}.` : `${why}.`) + wait;
    this.node.dataset.reason = message.reason;
    this.say(text, "blocked", message.ended ? ENDED_MS : NOTICE_MS);
  }

  /** A server `warning`: the round so far would not count (its `rule`); said until the participant acts. */
  warning(message) {
    this.node.dataset.reason = `would_not_count:${message.rule}`;
    this.say(WARNINGS[message.rule] || WARNINGS.no_actions, "warning", WARNING_MS);
  }

  /** A server `stall_hint`: the team got nothing done for a while; a hint from what the participant knows. */
  hint(message) {
    this.node.dataset.reason = message.code;
    this.say(message.text, "hint", HINT_MS);
  }

  clear() {
    window.clearTimeout(this.timer);
    this.node.hidden = true;
    this.text.textContent = "";
    delete this.node.dataset.reason;
  }

  destroy() {
    window.clearTimeout(this.timer);
  }
}
