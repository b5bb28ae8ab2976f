/**
 * Live trials of every server process (another's from its last stored tick): a list (polled every 2 s) and
 * the live view of one trial (polled every 300 ms): the whole kitchen with the participant's field of view
 * as a translucent mask, the kitchen as the participant's modelled knowledge has it, the knowledge gap, the
 * robot's belief over the participant's subtask and its decision, and tick lateness.
 */

import { h, show } from "../../js/dom.js";
import { subtaskLabel } from "../../js/labels.js";
import { beliefPanel, decisionPanel, facts, gapPanel } from "./panels.js";
import { Stage, beliefLabel, beliefState, worldLabel, worldState } from "./scene.js";
import { ParticipantCamera } from "./camera.js";
import { badge, errorText, ms, pageFrame, poll, table, who } from "./ui.js";

const LIST_MS = 2000;
const VIEW_MS = 300;

export function liveListPage(root, { api }) {
  const frame = pageFrame("Live trials", { id: "live" });
  show(root, frame.node);
  return poll(async () => {
    try {
      const games = await api.live();
      frame.status.textContent = "";
      frame.body.replaceChildren(table([
        ["Trial", (g) => h("a", { href: `#/live/${g.trial_id}`, class: "watch" }, `#${g.trial_id}`)],
        ["Participant", (g) => who(g.recruit_id, g.participant)],
        ["Study", (g) => g.study_id],
        ["Round", (g) => `${g.kind} ${g.index + 1} of ${g.kind_total}`],
        ["Condition", (g) => g.condition],
        ["Tick", (g) => String(g.tick), "num"],
        ["Connected", (g) => (g.connected ? "yes" : badge("away", "warn"))],
        ["Lateness p99", (g) => ms(g.lateness_ms.p99), "num"],
        ["Deadline misses", (g) => String(g.deadline_misses), "num"],
        ["Stall hints", (g) => String(g.stall_hints ?? 0), "num"],
        ["Robot health", (g) => healthBadge(g.health)],
        ["", (g) => h("a", { href: `#/live/${g.trial_id}` }, "Watch")],
      ], games, { id: "live-table", empty: "No trial is running.",
                  rowAttrs: (g) => ({ dataset: { trial: String(g.trial_id) } }) }));
    } catch (exc) {
      frame.status.textContent = errorText(exc);
    }
  }, LIST_MS);
}

/** The trial's share of missed robot decisions; "invalid" once past the study's threshold. */
function healthBadge(health) {
  const share = `${health.missed_pct.toFixed(1)} % missed`;
  return health.invalid ? badge(`invalid: ${share}`, "excluded") : h("span", {}, share);
}

function invalidWarning(health) {
  if (!health.invalid) return null;
  return h("p", { class: "notice warn", id: "live-invalid", role: "alert" },
    `This trial is invalid and will be left out of the analysis: ${health.invalid_reason}. ` +
    "The server is overloaded; see the operations guide (docs/operations.md, robot health).");
}

function header(view) {
  const t = view.trial;
  return h("p", { class: "trial-meta", id: "live-meta" },
    who(t.recruit_id, t.participant), ` · ${t.study_id} · ${t.kind} ${t.index + 1} of ${t.kind_total} · ${t.condition}` +
    ` · ${t.view.replace("_", "-")} view · seed ${t.seed}`, t.test_run ? [" ", badge("test run", "test")] : null,
    " ", view.connected ? badge("connected", "ok") : badge("participant away: paused", "warn"));
}

export function liveTrialPage(root, { api, args }) {
  const trialId = args[0];
  const frame = pageFrame(`Live · trial ${trialId}`, { id: "live-view",
    controls: [h("a", { href: "#/live" }, "All live trials")] });
  const world = new Stage("admin-kitchen");
  const belief = new Stage("belief-kitchen", { maxCell: 60, className: "model", label: beliefLabel });
  const meta = h("div", {});
  const side = h("div", { class: "viewer-side" });
  const caption = h("p", { class: "muted caption" });
  const camera = new ParticipantCamera();
  camera.node.hidden = true;
  frame.body.append(meta, h("div", { class: "viewer" },
    h("div", { class: "viewer-main" }, world.node, caption, camera.node,
      h("h3", {}, "The kitchen as the participant's model has it"), belief.node,
      h("p", { class: "muted caption" }, "Objects and stations as last seen (after the KB delay); the robot where it was last seen.")),
    side));
  show(root, frame.node);

  let stopped = false;
  const stop = poll(async () => {
    if (stopped) return;
    try {
      const view = await api.liveTrial(trialId);
      frame.status.textContent = "";
      if (!world.label) world.label = worldLabel(view.fov_angle);
      world.show(view.grid, worldState(view.grid, view.frame), { fov: view.frame.fov });
      belief.show(view.grid, beliefState(view.grid, view.frame));
      camera.node.hidden = view.trial.view !== "first_person";
      if (!camera.node.hidden) camera.show(view.grid, view.frame, view.fov_angle, VIEW_MS);
      world.node.dataset.tick = String(view.tick);
      meta.replaceChildren(header(view), invalidWarning(view.health) || "");
      caption.textContent = `Tick ${view.tick}. Dimmed cells are outside the participant's ${view.fov_angle}° field of view ` +
        "(yellow border); the participant sees only the bright cells. A dashed ring marks the robot when it is out of view.";
      const lateness = view.lateness_ms;
      side.replaceChildren(
        facts("status-panel", "Now", [
          ["Tick", String(view.tick), "live-tick"],
          ["Orders left", String(view.frame.orders_left)],
          ["Score", String(view.frame.score)],
          ["Subtask", view.subtask ? subtaskLabel(view.subtask) : "none", "live-subtask"],
          ["Queued interrupts", view.queued.length ? view.queued.join(", ") : "none"],
          ["Robot in view", view.robot_in_fov ? "yes" : "no", "robot-in-fov"],
          ["Mode", view.mode === "fixed_rate" ? `${view.tick_rate_hz} Hz` : "waits for the participant"],
        ]),
        gapPanel(view.kb_summary, view.world_summary, view.kb_gap, Object.values(view.kb_gap).reduce((a, b) => a + b, 0)),
        beliefPanel(view.decision, view.subtask),
        decisionPanel(view.decision, [h("dt", {}, "Round trip"), h("dd", {}, ms(view.decision_ms))]),
        facts("timing-panel", "Tick lateness", [
          ["Last", ms(lateness.last), "lateness-last"],
          ["Median", ms(lateness.p50)],
          ["p99", ms(lateness.p99), "lateness-p99"],
          ["Max", ms(lateness.max)],
          ["Ticks measured", String(lateness.count)],
          ["Deadline misses", String(view.deadline_misses)],
          ["Missed share", `${view.health.missed_pct.toFixed(1)} % (limit ${view.health.threshold_pct} %)`, "missed-share"],
        ]));
    } catch (exc) {
      if (exc.status === 404) {
        stopped = true;
        frame.status.textContent = "";
        meta.replaceChildren(h("p", { class: "notice", id: "live-ended" }, "This trial is not live any more " +
          "(it ended, or the participant left for longer than the grace window). ",
          h("a", { href: `#/replay/${trialId}` }, "Replay it")));
        return;
      }
      frame.status.textContent = errorText(exc);
    }
  }, VIEW_MS);
  return () => {
    stop();
    world.destroy();
    belief.destroy();
    camera.destroy();
  };
}
