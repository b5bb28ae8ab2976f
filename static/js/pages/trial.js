/**
 * A practice or main round: an intro card with a start button, then the game — HUD, the kitchen
 * canvas, interrupt buttons under it, task buttons beside it — and a summary card when the round ends.
 *
 * A round that was started in this tab resumes without the intro card after a refresh (sessionStorage),
 * with a "reconnecting" cover over the kitchen until the server's hello arrives.
 */

import { h, show } from "../dom.js";
import { GameConnection, Link } from "../game/connection.js";
import { kitchenViewFor } from "../game/views.js";
import { Hud, roundLabel } from "../game/hud.js";
import { Controls } from "../game/controls.js";
import { Activity } from "../game/activity.js";
import { listenKeys } from "../game/keys.js";
import { subtaskLabel } from "../labels.js";

const IDLE_MS = 30000;

function playingKey(session) {
  const t = session.trial;
  return `steakhouse.playing.${session.participant_id}.${t.kind}.${t.index}`;
}

function remember(key, on) {
  try {
    if (on) window.sessionStorage.setItem(key, "1");
    else window.sessionStorage.removeItem(key);
  } catch {
    /* storage disabled: the intro card shows again after a refresh */
  }
}

function started(key) {
  try {
    return window.sessionStorage.getItem(key) === "1";
  } catch {
    return false;
  }
}

export function trialPage(root, ctx) {
  const { session } = ctx;
  const key = playingKey(session);
  let stopGame = null;
  const start = () => {
    remember(key, true);
    stopGame = playRound(root, ctx, () => remember(key, false));
  };
  if (started(key)) start();
  else intro(root, session.trial, start);
  return () => stopGame && stopGame();
}

function intro(root, trial, onStart) {
  const practice = trial.kind === "practice";
  const button = h("button", { type: "button", class: "primary", id: "start-round", onclick: onStart },
    practice ? "Start practice" : "Start round");
  show(root, h("section", { class: "card narrow", "aria-labelledby": "round-title" },
    h("h1", { id: "round-title", tabindex: "-1" }, practice ? "Practice round" : roundLabel(trial)),
    practice ? h("p", { class: "muted", id: "round-number" }, roundLabel(trial)) : null,
    practice
      ? h("p", {}, "Try the controls: choose tasks with the buttons on the right, interrupt with the keys or the " +
          "buttons under the kitchen. This round is for practice; its result does not count.")
      : h("p", {}, "Work with the robot to deliver the orders as quickly as you can." +
          (trial.view === "first_person" ? "" : " Remember: black cells are outside your view.")),
    trial.view === "first_person"
      ? h("p", { id: "first-person-note" }, "In this round you see the kitchen through the cook's eyes; what is " +
          "outside your view is dark. ↑ or W steps forward, ← → or A D turn left and right (stepping that way " +
          "when the floor is free), ↓ or S turns around, Space interacts with what you face.")
      : null,
    h("p", { class: "muted" }, "The round starts as soon as you press the button."),
    h("div", { class: "actions" }, button)), button);
}

function playRound(root, ctx, onFinished) {
  const hud = new Hud();
  const canvas = h("canvas", { id: "kitchen", class: "kitchen-canvas", role: "img", "aria-label": "Kitchen" });
  const cover = h("div", { class: "stage-cover", id: "stage-cover", role: "status" },
    h("p", { class: "cover-text" }, "Connecting…"));
  const stage = h("div", { class: "stage", id: "stage" }, canvas, cover);
  const announce = h("p", { class: "visually-hidden", "aria-live": "polite", id: "task-announce" });
  const main = h("div", { class: "play-main" }, stage, h("div", { class: "interrupts-slot" }));
  const side = h("aside", { class: "play-side" });
  const layout = h("section", { class: "play", "aria-label": "Game" }, hud.node, h("div", { class: "play-body" }, main, side), announce);
  show(root, layout);
  document.body.classList.add("playing");

  let view = null;
  let controls = null;
  let removeKeys = null;
  let lastTask = null;
  let tickMs = 200;

  const setCover = (text, action) => {
    cover.hidden = !text;
    cover.replaceChildren();
    if (text) cover.append(h("p", { class: "cover-text" }, text));
    if (action) cover.append(action);
  };
  const sendInterrupt = (key) => {
    const action = view.interruptFor(key);
    const seq = conn.send("interrupt", { action });
    view.interruptSent(seq);
    if (seq === null) return;
    controls.flash(key);
    if (action === "stop") controls.setCurrent(null, true);
  };
  const select = (subtask) => {
    if (conn.send("select_subtask", { subtask }) !== null) controls.setCurrent(subtask, true);
  };
  const taskChanged = (subtask) => {
    hud.setTask(subtask);
    if (subtask !== lastTask) {
      lastTask = subtask;
      announce.textContent = subtask ? `Task: ${subtaskLabel(subtask)}` : "No task";
    }
  };

  const conn = new GameConnection(ctx.api.token, {
    onHello(hello) {
      tickMs = 1000 / hello.tick_rate_hz;
      if (!view) view = kitchenViewFor(hello.view, stage, canvas, { xr: true, onInterrupt: (a) => sendInterrupt(a) });
      view.configure(hello);
      hud.setRound(hello.trial);
      canvas.dataset.trial = String(hello.trial.id);
      if (!controls) {
        controls = new Controls({ subtasks: hello.subtasks, interrupts: hello.interrupts, onSelect: select,
                                  onInterrupt: sendInterrupt, labels: view.interruptLabels });
        main.querySelector(".interrupts-slot").replaceWith(controls.interrupts);
        side.append(controls.tasks);
        removeKeys = listenKeys(document, sendInterrupt, { repeatMs: tickMs });
      }
      controls.setEnabled(true);
      controls.setCurrent(null);
      setCover(null);
      if (hello.resumed && hello.tick > 0) hud.notice("Welcome back: the round continues where you left it.");
      activity.resync();
    },
    onState(state) {
      if (view) view.update(state);
      hud.update(state);
      taskChanged(state.subtask);
      if (controls && !controls.pending) controls.setCurrent(state.subtask);
    },
    onAck(ack) {
      if (controls) controls.setCurrent(ack.subtask);
      taskChanged(ack.subtask);
    },
    onLatency(ms) {
      hud.setLatency(ms);
    },
    onLink(link, info) {
      hud.setLink(link, info);
      layout.dataset.link = link;
      if (controls) controls.setEnabled(link === Link.OPEN);
      if (link === Link.CONNECTING) setCover("Connecting…");
      if (link === Link.RECONNECTING) setCover("Reconnecting… the game is paused until you are back.");
      if (link === Link.REPLACED) {
        const here = h("button", { type: "button", class: "primary", onclick: () => conn.connect() }, "Play here instead");
        setCover("This round is open in another window or tab.", here);
        here.focus();
      }
      if (link === Link.UNAUTHORIZED) setCover("Your session was not found. Please open your study link again.");
      if (link === Link.NO_TRIAL) finish(null);
    },
    onEnd(end) {
      finish(end);
    },
    onError(error) {
      if (error.code === "queue_full") hud.notice("Too many moves queued: wait a moment", "warn");
    },
  });
  const activity = new Activity((type, fields) => conn.send(type, fields), { idleMs: IDLE_MS });

  function cleanup() {
    conn.stop();
    if (view) view.destroy();
    activity.destroy();
    if (removeKeys) removeKeys();
    document.body.classList.remove("playing");
  }

  function finish(end) {
    cleanup();
    onFinished();
    if (!end) {
      ctx.route();
      return;
    }
    summary(root, end, ctx);
  }

  conn.connect();
  return cleanup;
}

function summary(root, end, ctx) {
  const title = end.status === "abandoned" ? "This round has ended" : "Round complete";
  const text = end.status === "abandoned"
    ? "The round ended because the connection was lost for too long. You can continue with the study."
    : end.reason === "delivered" ? `All orders delivered in ${end.ticks} steps.` : "Time is up for this round.";
  const next = { questionnaire: "Next: a few questions about this round.", practice: "Next: another practice round.",
                 trial: "Next: the next round.", done: "That was the last round." }[end.next] || "";
  const button = h("button", { type: "button", class: "primary", id: "continue", onclick: () => ctx.route() }, "Continue");
  show(root, h("section", { class: "card narrow", id: "round-summary", "aria-labelledby": "summary-title" },
    h("h1", { id: "summary-title" }, title),
    h("p", {}, text),
    h("dl", { class: "summary" },
      h("dt", {}, "Dishes delivered"), h("dd", { id: "summary-delivered" }, String(end.delivered)),
      h("dt", {}, "Score"), h("dd", { id: "summary-score" }, String(end.score))),
    next ? h("p", { class: "muted" }, next) : null,
    h("div", { class: "actions" }, button)), button);
}
