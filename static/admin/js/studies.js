/**
 * Studies: for each study its conditions and timing, how its condition orders are filled (target vs
 * achieved), its recruiting links and its downloads.
 *
 * Achieved is `counted`, what assignment balances: completed participants plus those in progress within
 * the study's window, without test runs, excluded or screened-out participants. The target of each order
 * is ceil(N / orders), N being the planned number of participants typed here (kept in this browser) or,
 * when none is planned, the participants counted so far (the target of the current block).
 */

import { h, show } from "../../js/dom.js";
import { exportPath } from "./api.js";
import { badge, copyButton, errorText, pageFrame, table } from "./ui.js";

const PLANNED = "steakhouse.admin.planned.";

function planned(studyId) {
  try {
    return Number(window.localStorage.getItem(PLANNED + studyId)) || 0;
  } catch {
    return 0;
  }
}

function setPlanned(studyId, value) {
  try {
    if (value > 0) window.localStorage.setItem(PLANNED + studyId, String(value));
    else window.localStorage.removeItem(PLANNED + studyId);
  } catch {
    /* not remembered */
  }
}

/** Per order: the target count, given the counts and the planned number of participants. */
export function targets(orders, plannedN) {
  const counted = orders.reduce((sum, o) => sum + o.counted, 0);
  const n = Math.max(plannedN || 0, counted);
  return orders.map(() => Math.ceil(n / Math.max(orders.length, 1)));
}

function ordersTable(study, plannedN) {
  const goal = targets(study.orders, plannedN);
  const counted = study.orders.map((o) => o.counted);
  const spread = Math.max(...counted) - Math.min(...counted);
  const next = counted.indexOf(Math.min(...counted));
  const rows = study.orders.map((o, i) => ({ ...o, target: goal[i] }));
  return h("div", {},
    table([
      ["Order", (o) => String(o.index + 1)],
      ["Conditions in order", (o) => h("ol", { class: "inline-list" }, o.conditions.map((c) => h("li", {}, c)))],
      ["Target", (o) => String(o.target), "num"],
      ["Achieved", (o) => h("span", { class: o.counted < o.target ? "short" : "met" }, String(o.counted)), "num"],
      ["Completed", (o) => String(o.completed), "num"],
      ["In progress", (o) => String(o.in_progress), "num"],
      ["Screened out", (o) => String(o.screened_out), "num"],
      ["Test runs", (o) => String(o.test_runs), "num"],
      ["Excluded", (o) => String(o.excluded), "num"],
      ["Not counted", (o) => String(o.uncounted ?? 0), "num"],
      ["Simulated pilots", (o) => String(o.pilots ?? 0), "num"],
    ], rows, { id: `orders-${study.id}`,
               rowAttrs: (o) => ({ dataset: { order: String(o.index), counted: String(o.counted), target: String(o.target) } }) }),
    h("p", { class: "muted" }, `Balance: max − min of achieved = ${spread}. The next participant gets order ${next + 1} ` +
      "(the least filled). Achieved counts completed participants and those in progress within " +
      "the assignment window; test runs, excluded and screened-out participants do not count, nor those with a " +
      "main round that cannot become a cell (abandoned, low engagement, robot-invalid) or a refused device."));
}

function plannedInput(study, redraw) {
  const input = h("input", { type: "number", min: "0", step: "1", id: `planned-${study.id}`, class: "planned",
                             value: planned(study.id) || "" });
  input.addEventListener("change", () => {
    setPlanned(study.id, Math.max(0, Math.floor(Number(input.value) || 0)));
    redraw();
  });
  return h("label", { class: "inline-field" }, "Planned participants ", input);
}

function linkRow(label, id, url, note) {
  return h("div", { class: "link-row" },
    h("span", { class: "link-label" }, label),
    h("input", { type: "text", readonly: true, id, value: url, class: "link-input", "aria-label": label,
                 onfocus: (e) => e.target.select() }),
    ...copyButton(url),
    note ? h("p", { class: "muted link-note" }, note) : null);
}

function linksPanel(links) {
  const origin = window.location.origin;
  const ending = (name, info) => h("div", { class: "ending" },
    h("dt", {}, name),
    h("dd", {}, info.code ? h("code", {}, info.code) : h("span", { class: "muted" }, "no code"),
      info.redirect_url
        ? [" → ", h("a", { href: info.redirect_url, rel: "noreferrer", target: "_blank" }, info.redirect_url)]
        : h("span", { class: "muted" }, " · no redirect")));
  return h("section", { class: "panel links", "aria-label": `Recruiting links of ${links.study_id}` },
    h("h3", {}, "Recruiting links"),
    linkRow("Participant link", `link-participant-${links.study_id}`, origin + links.participant.path,
      `Use as the study URL on Prolific: ${links.url_parameters.map((p) => `{{%${p}%}}`).join(", ")} are filled in per participant.`),
    linkRow("Test run", `link-test-${links.study_id}`, origin + links.test_run.path,
      `Signed for you, valid until ${new Date(links.test_link_expires_at).toLocaleString()}: only this link makes a test run (not counted for assignment, left out of exports, its end page shows TEST-RUN instead of the completion code). This browser resumes its test session; the link below always starts a new one (a refresh then starts over too). Reload the page for a fresh link.`),
    h("div", { class: "link-row" }, h("span", { class: "link-label" }, ""),
      h("span", { class: "link-actions" },
        h("a", { href: origin + links.test_run.path, target: "_blank", rel: "noopener", id: `open-test-${links.study_id}` }, "Open a test run"),
        " · ",
        h("a", { href: origin + links.fresh_test_run.path, target: "_blank", rel: "noopener" }, "Start a fresh test run"))),
    h("dl", { class: "endings" }, ending("Completion", links.completion), ending("Screen-out", links.screen_out)));
}

function downloads(study, api) {
  const id = encodeURIComponent(study.id);
  const status = h("p", { class: "muted download-status", role: "status", id: `download-status-${study.id}` });
  const get = (path, file) => async () => {
    status.textContent = "Preparing the download…";
    status.classList.remove("error");
    try {
      await api.download(path, file);
      status.textContent = `Downloaded ${file}.`;
    } catch (exc) {
      status.classList.add("error");
      status.textContent = exc.status === 404
        ? "The export is not available on this server (404): this version has no export endpoint yet."
        : `The download failed: ${errorText(exc)}`;
    }
  };
  return h("section", { class: "panel downloads", "aria-label": `Downloads of ${study.id}` },
    h("h3", {}, "Downloads"),
    h("div", { class: "actions tight" },
      h("button", { type: "button", id: `export-${study.id}`, onclick: get(exportPath(study.id), `${study.id}-export.zip`) },
        "Export (zip: tidy CSVs)"),
      h("button", { type: "button", class: "secondary",
                    onclick: get(`/api/admin/participants?study_id=${id}`, `${study.id}-participants.json`) },
        "Participants (JSON)"),
      h("button", { type: "button", class: "secondary",
                    onclick: get(`/api/admin/trials?study_id=${id}`, `${study.id}-trials.json`) },
        "Trials (JSON)")),
    status);
}

/** The study file's warnings (e.g. no completion code), shown prominently at the top of its card. */
function warningsPanel(study) {
  const warnings = study.warnings || [];
  if (!warnings.length) return null;
  const noCode = warnings.some((w) => w.code === "no_completion_code" || w.code === "placeholder_code");
  return h("section", { class: "study-warnings", id: `warnings-${study.id}`, role: "note",
                        "aria-label": `Warnings about ${study.id}` },
    h("h3", {}, noCode ? "No usable completion code" : "Check this study"),
    h("ul", {}, warnings.map((w) => h("li", { dataset: { code: w.code } }, h("code", {}, w.path), `: ${w.reason}`))));
}

function studyCard(study, links, api) {
  const orders = h("div", {});
  const redraw = () => orders.replaceChildren(ordersTable(study, planned(study.id)));
  redraw();
  const rate = study.timing.tick_rate_hz;
  const timing = study.timing.mode === "fixed_rate" ? `${rate} Hz` : `waits for the participant (≤ ${rate} Hz)`;
  return h("article", { class: "card study", id: `study-${study.id}`, "aria-labelledby": `study-title-${study.id}` },
    h("div", { class: "study-head" },
      h("h2", { id: `study-title-${study.id}` }, study.title, " ", h("code", { class: "study-id" }, study.id)),
      study.live_trials ? h("a", { href: "#/live", class: "badge live" }, `${study.live_trials} live`) : badge("none live"),
      h("a", { href: `#/participants?study=${encodeURIComponent(study.id)}` }, "Participants"),
      h("a", { href: `#/trials?study=${encodeURIComponent(study.id)}` }, "Trials")),
    warningsPanel(study),
    h("p", { class: "muted" }, `Conditions: ${study.conditions.join(", ")} · ${timing} · config ${study.config_hash.slice(0, 12)}`),
    study.notes ? h("p", { class: "notes" }, study.notes) : null,
    h("div", { class: "orders-head" }, h("h3", {}, "Condition orders"), plannedInput(study, redraw)),
    orders,
    h("div", { class: "panels-row" }, linksPanel(links), downloads(study, api)));
}

export function studiesPage(root, { api }) {
  const frame = pageFrame("Studies", { id: "studies" });
  show(root, frame.node);
  (async () => {
    try {
      const studies = await api.studies();
      const links = await Promise.all(studies.map((s) => api.links(s.id)));
      frame.body.replaceChildren(...studies.map((s, i) => studyCard(s, links[i], api)));
      if (!studies.length) frame.body.append(h("p", { class: "muted" }, "This server serves no study."));
    } catch (exc) {
      frame.status.textContent = errorText(exc);
    }
  })();
}
