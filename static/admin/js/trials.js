/**
 * Stored trials (newest first), filtered by study or participant from the address
 * (#/trials?study=…&participant=…), each with a link to its replay (and to the live view while running).
 */

import { h, show } from "../../js/dom.js";
import { badge, errorText, pageFrame, table, when, who } from "./ui.js";

export function trialsPage(root, { api, params }) {
  const filters = { study_id: params.get("study") || undefined, participant_id: params.get("participant") || undefined };
  const scope = [filters.study_id && `study ${filters.study_id}`, filters.participant_id && `participant ${filters.participant_id}`]
    .filter(Boolean).join(", ");
  const frame = pageFrame(scope ? `Trials of ${scope}` : "Trials", { id: "trials",
    controls: scope ? [h("a", { href: "#/trials" }, "All trials")] : [] });
  show(root, frame.node);
  (async () => {
    try {
      const trials = await api.trials(filters);
      frame.body.replaceChildren(table([
        ["Trial", (t) => h("a", { href: `#/replay/${t.trial_id}` }, `#${t.trial_id}`)],
        ["Participant", (t) => h("a", { href: `#/trials?participant=${encodeURIComponent(t.participant_id)}` },
          who(t.recruit_id, t.participant_id))],
        ["Study", (t) => t.study_id],
        ["Kind", (t) => `${t.kind} ${t.index + 1}${t.attempt > 1 ? ` (attempt ${t.attempt})` : ""}`],
        ["Condition", (t) => t.condition],
        ["Status", (t) => (t.status === "running" ? badge("running", "live") : `${t.status}${t.end_reason ? ` (${t.end_reason})` : ""}`)],
        ["Valid", (t) => (t.invalid ? [badge("invalid", "excluded"), h("span", { class: "reason" }, t.invalid_reason)]
          : t.low_engagement ? [badge("low engagement", "excluded"), h("span", { class: "reason" }, t.engagement_reason)]
          : h("span", { class: "muted" }, t.missed_decisions_pct === null ? "–" : `${t.missed_decisions_pct} % missed`))],
        ["Participant / robot dishes", (t) => (t.delivered_by_participant === null ? "–"
          : `${t.delivered_by_participant} / ${t.delivered_by_robot}`), "num"],
        ["Refused steps", (t) => (t.refused_steps === null ? "–" : String(t.refused_steps)), "num"],
        ["Ticks", (t) => String(t.ticks), "num"],
        ["Delivered", (t) => String(t.delivered), "num"],
        ["Score", (t) => String(t.score), "num"],
        ["Started", (t) => when(t.started_at)],
        ["", (t) => [h("a", { href: `#/replay/${t.trial_id}`, class: "replay-link" }, "Replay"),
                     t.status === "running" ? [" · ", h("a", { href: `#/live/${t.trial_id}` }, "Live")] : null]],
      ], trials, { id: "trials-table", empty: "No trial stored yet.", rowAttrs: (t) => ({ dataset: { trial: String(t.trial_id) } }) }));
    } catch (exc) {
      frame.status.textContent = errorText(exc);
    }
  })();
}
