/**
 * A practice or main round: an intro card with a start button, then the game — HUD (with a note that says why
 * a task did nothing), the recipe strip, the kitchen canvas, interrupt buttons under it, task buttons beside
 * it — and a summary card when the round ends.
 *
 * A round that was started in this tab resumes without the intro card after a refresh (sessionStorage),
 * with a "reconnecting" cover over the kitchen until the server's hello arrives. While a round is played,
 * leaving or reloading the page asks for confirmation first.
 */

import { h, show } from "../dom.js";
import { GameConnection, Link } from "../game/connection.js";
import { kitchenViewFor } from "../views.js";
import { Hud } from "../game/hud.js";
import { Controls } from "../game/controls.js";
import { Activity } from "../game/activity.js";
import { listenKeys } from "../game/keys.js";
import { RecipeStrip } from "../game/recipe.js";
import { TaskNote } from "../game/notes.js";
import { subtaskLabel } from "../labels.js";
import { introCard, summaryCard } from "./round_cards.js";

const IDLE_MS = 30000;
const NOT_RUNNING = "That did nothing: the game is paused until the connection is back.";

/** Why a key that is not a game key did nothing, and which keys are. */
export function otherKeyText(key) {
  const name = key === " " ? "Space" : key.toUpperCase();
  return `${name} is not a game key: move with the arrows or W A S D, Space interacts, 1–9, 0, - and = choose tasks.`;
}

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
  if (started(key) && session.trial.status === "in_progress") start();
  else introCard(root, session.trial, start);
  return () => stopGame && stopGame();
}

/** Ask before leaving the page while a round is played (the browser shows its own confirmation). */
function confirmLeaving(event) {
  event.preventDefault();
  event.returnValue = "";
}

/** The waiting cover: when the round starts and the place in line, nothing about the round itself. */
export function waitingText({ position, eta_s: eta }) {
  const when = eta > 0 ? `in about ${eta} s` : "shortly";
  const place = position > 1 ? ` You are number ${position} in line.` : " You are next.";
  return `The study is busy: your round starts ${when} — keep this tab open.${place}`;
}

function playRound(root, ctx, onFinished) {
  const hud = new Hud();
  const recipe = new RecipeStrip();
  const note = new TaskNote();
  hud.place(note.node);
  const canvas = h("canvas", { id: "kitchen", class: "kitchen-canvas", role: "img", "aria-label": "Kitchen" });
  const cover = h("div", { class: "stage-cover", id: "stage-cover", role: "status" },
    h("p", { class: "cover-text" }, "Connecting…"));
  const stage = h("div", { class: "stage", id: "stage" }, canvas, cover);
  const announce = h("p", { class: "visually-hidden", "aria-live": "polite", id: "task-announce" });
  const main = h("div", { class: "play-main" }, stage, h("div", { class: "interrupts-slot" }));
  const side = h("aside", { class: "play-side" });
  const layout = h("section", { class: "play", "aria-label": "Game" }, hud.node, recipe.node,
    h("div", { class: "play-body" }, main, side), announce);
  show(root, layout);
  document.body.classList.add("playing");
  window.addEventListener("beforeunload", confirmLeaving);

  let view = null;
  let controls = null;
  let removeKeys = null;
  let lastTask = null;
  let hello = null;

  const setCover = (text, action) => {
    cover.hidden = !text;
    cover.replaceChildren();
    if (text) cover.append(h("p", { class: "cover-text" }, text));
    if (action) cover.append(action);
  };
  const sendInterrupt = (key) => {
    if (!conn.isOpen || !view) {
      note.say(NOT_RUNNING, "blocked");
      return;
    }
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
    onHello(message) {
      hello = message;
      if (!view) view = kitchenViewFor(message.view, stage, canvas, { xr: true, onInterrupt: (a) => sendInterrupt(a) });
      view.configure(message);
      hud.setRound(message.trial);
      note.waits = message.mode === "wait_for_participant";
      canvas.dataset.trial = String(message.trial.id);
      if (!controls) {
        controls = new Controls({ subtasks: message.subtasks, interrupts: message.interrupts, needs: message.needs,
                                  onSelect: select, onInterrupt: sendInterrupt, labels: view.interruptLabels,
                                  onRefused: (id, reason) => note.say(`${subtaskLabel(id)}: ${reason}.`, "blocked") });
        main.querySelector(".interrupts-slot").replaceWith(controls.interrupts);
        side.append(controls.tasks);
        removeKeys = listenKeys(document, sendInterrupt, {
          repeat: message.mode !== "wait_for_participant",
          repeatMs: 1000 / message.tick_rate_hz,
          onTask: (index) => {
            if (!conn.isOpen) note.say(NOT_RUNNING, "blocked");
            else if (!controls.chooseKey(index)) note.say("No task has this key.", "blocked");
          },
          onOtherKey: (key) => note.say(otherKeyText(key), "blocked"),
        });
      }
      controls.setEnabled(true);
      controls.setCurrent(null);
      setCover(null);
      if (message.resumed && message.tick > 0) hud.notice("Welcome back: the round continues where you left it.");
      activity.resync();
    },
    onState(state) {
      if (view) view.update(state);
      hud.update(state);
      recipe.update(state.you.held, state.subtask);
      taskChanged(state.subtask);
      if (controls) {
        controls.setHeld(state.you.held);
        if (!controls.pending) controls.setCurrent(state.subtask);
      }
    },
    onAck(ack) {
      if (controls) controls.setCurrent(ack.subtask);
      taskChanged(ack.subtask);
    },
    onBlocked(message) {
      note.blocked(message);
    },
    onNudge(message) {
      note.say(message.text, "nudge", 8000);
    },
    onCountdown(message) {
      hud.countDown(message.seconds_left);
    },
    onWarning(message) {
      note.warning(message);
    },
    onStallHint(message) {
      note.hint(message);
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
        window.removeEventListener("beforeunload", confirmLeaving);
        const here = h("button", { type: "button", class: "primary", onclick: () => {
          window.addEventListener("beforeunload", confirmLeaving);
          conn.connect();
        } }, "Play here instead");
        setCover("This round is open in another window or tab.", here);
        here.focus();
      }
      if (link === Link.UNAUTHORIZED) setCover("Your session was not found. Please open your study link again.");
      if (link === Link.MOVED) {
        window.removeEventListener("beforeunload", confirmLeaving);
        setCover("Your study continues on another device. You can close this tab.");
      }
      if (link === Link.QUEUED) setCover(waitingText(info));
      if (link === Link.NO_TRIAL || link === Link.SERVER_FULL) finish(null);
    },
    onEnd(end) {
      finish(end);
    },
    onError(error) {
      if (error.code === "queue_full") note.say("That key did nothing: three moves are already waiting.", "blocked");
      if (error.code === "rate_limited") note.say("That did nothing: too many key presses at once.", "blocked");
    },
  });
  const activity = new Activity((type, fields) => conn.send(type, fields), { idleMs: IDLE_MS });

  function cleanup() {
    hud.pauseCountdown();
    window.removeEventListener("beforeunload", confirmLeaving);
    conn.stop();
    if (view) view.destroy();
    note.destroy();
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
    const timed = hello && hello.mode === "fixed_rate";
    summaryCard(root, end, { scored: ctx.session.trial.scored !== false,
                             seconds: timed ? end.ticks / hello.tick_rate_hz : null, onContinue: () => ctx.route() });
  }

  conn.connect();
  return cleanup;
}
