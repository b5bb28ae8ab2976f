/**
 * The heads-up display above the kitchen: round, orders left, time left, score, the current task and
 * what the cook holds; on the paper's clock, in the round's last minute, "Round ends in 0:42"; and the
 * connection pill (connected, reconnecting, …; "Slow connection" beside it when
 * the round trip to the server is slow).
 * Text nodes are only touched when their value changes, so 30 updates a second cost nothing.
 */

import { h } from "../dom.js";
import { heldLabel, subtaskLabel } from "../labels.js";

function stat(label, id) {
  const value = h("span", { class: "hud-value", id });
  return { node: h("div", { class: "hud-item" }, h("span", { class: "hud-label" }, label), value), value };
}

/**
 * "Practice 1 of 1" or "Round 2 of 4": the trial's place among the trials of its kind (`kind_number`,
 * `kind_total` of the protocol's trial info), so practice rounds never shift the numbering of the real ones.
 */
export function roundLabel(trial) {
  return `${trial.kind === "practice" ? "Practice" : "Round"} ${trial.kind_number} of ${trial.kind_total}`;
}

export function formatTime(seconds) {
  const s = Math.max(0, Math.ceil(seconds));
  return `${Math.floor(s / 60)}:${String(s % 60).padStart(2, "0")}`;
}

/** The last seconds of a wait-for-participant round's wall-clock limit that the HUD counts down. */
export const COUNTDOWN_SECONDS = 60;

/** Time left in wait-for-participant mode, where the game moves only when the cook does: moves, not seconds. */
export function movesLeft(count) {
  return `${count} move${count === 1 ? "" : "s"}`;
}

export class Hud {
  constructor() {
    this.round = h("span", { class: "hud-round", id: "hud-round" });
    this.items = {
      orders: stat("Orders left", "hud-orders"),
      time: stat("Time left", "hud-time"),
      score: stat("Score", "hud-score"),
      task: stat("Your task", "hud-task"),
      held: stat("Holding", "hud-held"),
    };
    this.pill = h("span", { class: "link-pill", id: "link-status", role: "status", "aria-live": "polite" });
    this.latency = h("span", { class: "latency", id: "latency", title: "Round trip to the server" });
    this.countdown = h("span", { class: "hud-countdown", id: "hud-countdown", role: "timer", hidden: true });
    this.countdownEnd = null;
    this.countdownTimer = 0;
    this.note = h("span", { class: "hud-note", id: "hud-note", "aria-live": "polite" });
    this.link = h("div", { class: "hud-link" }, this.countdown, this.note, this.pill, this.latency);
    this.node = h("div", { class: "hud", role: "group", "aria-label": "Game status" },
      this.round, Object.values(this.items).map((i) => i.node), this.link);
  }

  /** Put `node` (e.g. the task note) in the HUD, after what the cook holds. */
  place(node) {
    this.node.insertBefore(node, this.link);
  }

  setText(el, text) {
    if (el.textContent !== text) el.textContent = text;
  }

  /** The round's label; an unscored round (practice) shows no score. */
  setRound(trial) {
    this.setText(this.round, roundLabel(trial));
    this.items.score.node.hidden = trial.scored === false;
  }

  update(state) {
    const hud = state.hud;
    this.setText(this.items.orders.value, String(hud.orders_left));
    this.setText(this.items.time.value,
      hud.seconds_left === null || hud.seconds_left === undefined ? movesLeft(hud.ticks_left) : formatTime(hud.seconds_left));
    this.setText(this.items.score.value, String(hud.score));
    this.setTask(state.subtask);
    this.setText(this.items.held.value, heldLabel(state.you.held));
    this.items.time.node.classList.toggle("hud-urgent", hud.seconds_left !== null && hud.seconds_left <= 10);
    const left = hud.round_seconds_left;
    if (left !== null && left !== undefined && left <= COUNTDOWN_SECONDS) this.countDown(left);
  }

  /** The paper's clock: the round's wall-clock limit is `seconds` away (its last minute): show it, counting down
   * each second on this page until the limit, a newer count, or a lost connection (the server's limit then
   * pauses too). */
  countDown(seconds) {
    this.countdownEnd = performance.now() + seconds * 1000;
    this.countdown.hidden = false;
    const tick = () => {
      const left = Math.max(0, (this.countdownEnd - performance.now()) / 1000);
      this.setText(this.countdown, `Round ends in ${formatTime(left)}`);
      this.countdown.classList.toggle("hud-urgent", left <= 10);
    };
    tick();
    window.clearInterval(this.countdownTimer);
    this.countdownTimer = window.setInterval(tick, 250);
  }

  /** Stop counting down (the connection is lost, or the page leaves): the shown time stays. */
  pauseCountdown() {
    window.clearInterval(this.countdownTimer);
    this.countdownTimer = 0;
  }

  setTask(subtask) {
    this.setText(this.items.task.value, subtask ? subtaskLabel(subtask) : "none");
    this.items.task.node.dataset.subtask = subtask || "";
  }

  setLink(link, info = {}) {
    const text = {
      connecting: "Connecting…",
      open: "Connected",
      reconnecting: info.attempt > 3 ? "Reconnecting… check your internet connection" : "Reconnecting…",
      ended: "Round over",
      replaced: "Open in another window",
      unauthorized: "Session not found",
      no_trial: "Not in a round",
      queued: "Waiting for your round",
      server_full: "Study busy",
      moved: "Continued on another device",
      closed: "Disconnected",
    }[link] || link;
    this.setText(this.pill, text);
    this.pill.dataset.link = link;
    if (link !== "open") {
      this.setText(this.latency, "");
      this.pauseCountdown();
    }
  }

  /** A short message next to the connection pill that fades after a few seconds. */
  notice(text, kind = "info") {
    this.setText(this.note, text);
    this.note.dataset.kind = kind;
    window.clearTimeout(this.noteTimer);
    this.noteTimer = window.setTimeout(() => this.setText(this.note, ""), 3000);
  }

  /** The round trip to the server: said only when it is slow enough to notice (in words; the ms on hover). */
  setLatency(ms) {
    const rounded = Math.round(ms);
    const quality = rounded < 150 ? "good" : rounded < 400 ? "fair" : "poor";
    this.setText(this.latency, quality === "good" ? "" : quality === "fair" ? "Slow connection" : "Very slow connection");
    this.latency.dataset.quality = quality;
    this.latency.dataset.ms = String(rounded);
    this.latency.title = `Round trip to the server: ${rounded} ms`;
  }
}
