/**
 * The replay of a stored trial: every tick's whole world with the participant's field of view (dimmed
 * outside it), the kitchen as the participant's modelled knowledge had it, and what was recorded at that
 * tick — actions, subtask, knowledge gap, the robot's belief and decision, lateness. A timeline scrubber
 * (drag, or arrow keys on it), step buttons, play / pause at a chosen speed of the study's tick rate.
 * Keys elsewhere on the page: Space plays / pauses, ← and → step.
 */

import { h, show } from "../../js/dom.js";
import { subtaskLabel } from "../../js/labels.js";
import { beliefPanel, decisionPanel, facts, gapPanel } from "./panels.js";
import { Stage, beliefLabel, beliefState, worldLabel, worldState } from "./scene.js";
import { ParticipantCamera } from "./camera.js";
import { badge, errorText, ms, pageFrame, who } from "./ui.js";

const PAGE = 2000;
const SPEEDS = [0.25, 0.5, 1, 2, 4, 8];

async function loadFrames(api, trialId, onProgress) {
  let data = await api.frames(trialId, 0, PAGE);
  const frames = [...data.frames];
  while (data.next_start !== null) {
    onProgress(frames.length);
    data = await api.frames(trialId, data.next_start, PAGE);
    frames.push(...data.frames);
  }
  return { ...data, frames };
}

function metaLine(replay) {
  const t = replay.trial;
  return h("p", { class: "trial-meta", id: "replay-meta" },
    who(t.recruit_id, t.participant_id), ` · ${t.study_id} · ${t.kind} ${t.index + 1} · ${t.condition} · ` +
    `${t.view.replace("_", "-")} view · seed ${t.seed} · ` +
    `${t.status}${t.end_reason ? ` (${t.end_reason})` : ""} · ${t.delivered} delivered · score ${t.score}`,
    replay.config_changed ? [" ", badge("study file changed since this trial", "warn")] : null);
}

function tickFacts(f) {
  const source = f.action_source ? ` (${f.action_source})` : "";
  return facts("tick-panel", "This tick", [
    ["Tick", String(f.tick), "replay-tick"],
    ["Participant's action", f.human_action ? `${f.human_action}${source}` : "–", "human-action"],
    ["Robot's action", f.robot_action ? `${f.robot_action}${f.robot_missed ? " (deadline missed: stayed)" : ""}` : "–"],
    ["Subtask", f.subtask ? subtaskLabel(f.subtask) : "none"],
    ["Robot in view", f.robot_in_fov ? "yes" : "no", "replay-robot-in-fov"],
    ["Orders left", String(f.orders_left)],
    ["Score", String(f.score)],
    ["Tick lateness", ms(f.lateness_ms)],
    ["Decision round trip", ms(f.decision_ms)],
  ]);
}

export function replayPage(root, { api, args }) {
  const trialId = args[0];
  const frame = pageFrame(`Replay · trial ${trialId}`, { id: "replay",
    controls: [h("a", { href: "#/trials" }, "All trials")] });
  frame.body.append(h("p", { class: "muted", id: "replay-loading" }, "Loading the ticks…"));
  show(root, frame.node);
  let timer = 0;
  let left = false;
  let removeKeys = () => {};
  const world = new Stage("admin-kitchen");
  const belief = new Stage("belief-kitchen", { maxCell: 60, className: "model", label: beliefLabel });
  const camera = new ParticipantCamera();

  loadFrames(api, trialId, (n) => { frame.body.firstChild.textContent = `Loading the ticks… ${n}`; })
    .then((replay) => { if (!left) removeKeys = build(replay); })
    .catch((exc) => {
      frame.body.replaceChildren();
      frame.status.textContent = exc.status === 404 ? "There is no stored trial with this id." : errorText(exc);
    });

  function build(replay) {
    const frames = replay.frames;
    const last = frames.length - 1;
    world.label = worldLabel(replay.fov_angle);
    const scrubber = h("input", { type: "range", id: "scrubber", min: "0", max: String(last), step: "1", value: "0",
                                  "aria-label": "Tick", class: "scrubber" });
    const label = h("output", { id: "tick-label", for: "scrubber", class: "tick-label" });
    const play = h("button", { type: "button", id: "play", class: "small primary", "aria-pressed": "false" }, "Play");
    const back = h("button", { type: "button", id: "step-back", class: "small secondary", "aria-label": "Step back" }, "◀ Step");
    const forward = h("button", { type: "button", id: "step-forward", class: "small secondary", "aria-label": "Step forward" }, "Step ▶");
    const first = h("button", { type: "button", id: "to-start", class: "small secondary", "aria-label": "To the first tick" }, "|◀ Start");
    const speed = h("select", { id: "speed", "aria-label": "Speed" },
      SPEEDS.map((s) => h("option", { value: String(s), selected: s === 1 }, `${s}× (${Math.round(s * replay.tick_rate_hz * 100) / 100} ticks/s)`)));
    const side = h("div", { class: "viewer-side" });
    const caption = h("p", { class: "muted caption" }, `Dimmed cells are outside the participant's ${replay.fov_angle}° field of view ` +
      "(yellow border). A dashed ring marks the robot when it is out of view.");
    const status = h("p", { class: "muted", id: "download-status", role: "status" });
    const download = (label, path, file) => h("button", { type: "button", class: "small secondary", onclick: async () => {
      try {
        await api.download(path, file);
        status.textContent = `Downloaded ${file}.`;
      } catch (exc) {
        status.textContent = `The download failed: ${errorText(exc)}`;
      }
    } }, label);
    let index = 0;
    const firstPerson = replay.trial.view === "first_person";

    function draw() {
      const f = frames[index];
      scrubber.value = String(index);
      label.value = `Tick ${f.tick} of ${frames[last].tick}`;
      label.textContent = label.value;
      label.dataset.tick = String(f.tick);
      world.show(replay.grid, worldState(replay.grid, f), { fov: f.fov });
      belief.show(replay.grid, beliefState(replay.grid, f));
      if (firstPerson) camera.show(replay.grid, f, replay.fov_angle, 1000 / (replay.tick_rate_hz * Number(speed.value)));
      side.replaceChildren(tickFacts(f), gapPanel(f.kb_summary, f.world_summary, f.kb_gap, f.kb_gap_total),
        beliefPanel(f.decision, f.subtask), decisionPanel(f.decision));
    }
    function go(i) {
      index = Math.min(Math.max(i, 0), last);
      draw();
    }
    function pause() {
      window.clearInterval(timer);
      timer = 0;
      play.textContent = "Play";
      play.setAttribute("aria-pressed", "false");
    }
    function start() {
      if (index >= last) go(0);
      play.textContent = "Pause";
      play.setAttribute("aria-pressed", "true");
      timer = window.setInterval(() => {
        if (index >= last) pause();
        else go(index + 1);
      }, 1000 / (replay.tick_rate_hz * Number(speed.value)));
    }
    const toggle = () => (timer ? pause() : start());
    play.addEventListener("click", toggle);
    back.addEventListener("click", () => { pause(); go(index - 1); });
    forward.addEventListener("click", () => { pause(); go(index + 1); });
    first.addEventListener("click", () => { pause(); go(0); });
    scrubber.addEventListener("input", () => { pause(); go(Number(scrubber.value)); });
    speed.addEventListener("change", () => { if (timer) { pause(); start(); } });
    const onKey = (event) => {
      if (event.ctrlKey || event.altKey || event.metaKey || event.target.closest("input, select, textarea, button, a")) return;
      if (event.key === " ") toggle();
      else if (event.key === "ArrowLeft") { pause(); go(index - 1); }
      else if (event.key === "ArrowRight") { pause(); go(index + 1); }
      else return;
      event.preventDefault();
    };
    document.addEventListener("keydown", onKey);

    frame.body.replaceChildren(metaLine(replay),
      h("div", { class: "timeline", role: "group", "aria-label": "Timeline" }, first, back, play, forward, scrubber, label, speed),
      h("div", { class: "viewer" },
        h("div", { class: "viewer-main" }, world.node, caption, firstPerson ? camera.node : null,
          h("h3", {}, "The kitchen as the participant's model had it"), belief.node,
          h("div", { class: "actions tight" }, download("Download ticks (JSON)", `/api/admin/trials/${trialId}`, `trial-${trialId}-ticks.json`),
            download("Download events (JSON)", `/api/admin/trials/${trialId}/events`, `trial-${trialId}-events.json`)), status),
        side));
    go(0);
    return () => document.removeEventListener("keydown", onKey);
  }

  return () => {
    left = true;
    window.clearInterval(timer);
    removeKeys();
    world.destroy();
    belief.destroy();
    camera.destroy();
  };
}
