/**
 * Participants: who joined which study, their order and progress, their flags, and their questionnaire
 * answers. Flags go through the admin API: mark / unmark as a test run, exclude with a reason (required),
 * include again. The list refreshes every 10 s unless an exclusion form is open. Simulated pilot participants
 * (`steakhouse pilot`) are listed apart, below the real ones, in a table of their own.
 */

import { h, show } from "../../js/dom.js";
import { badge, errorText, pageFrame, poll, table, when } from "./ui.js";

const STATES = { consent: "consent", instructions: "instructions", quiz: "quiz", practice: "practice", trial: "trial",
                 questionnaire: "questionnaire", done: "done", screened_out: "screened out" };

function progress(p) {
  const bar = h("progress", { max: String(Math.max(p.steps - 1, 1)), value: String(p.step), "aria-label": `Step ${p.step + 1} of ${p.steps}` });
  return h("div", { class: "progress-cell" }, bar, h("span", {}, `${STATES[p.state] || p.state} · step ${p.step + 1}/${p.steps}`));
}

function flags(p) {
  const out = [];
  if (p.pilot) out.push(badge("simulated pilot", "test"));
  if (p.test_run) out.push(badge("test run", "test"));
  if (p.excluded) out.push(badge("excluded", "excluded"), h("span", { class: "reason" }, p.exclusion_reason || ""));
  if (p.invalid_trials) {
    out.push(h("a", { href: `#/trials?participant=${encodeURIComponent(p.participant_id)}`, class: "invalid-trials" },
      badge(`${p.invalid_trials} invalid trial${p.invalid_trials > 1 ? "s" : ""}`, "excluded")));
  }
  if (p.low_engagement_trials) {
    out.push(h("a", { href: `#/trials?participant=${encodeURIComponent(p.participant_id)}`, class: "low-engagement" },
      badge(`${p.low_engagement_trials} low-engagement trial${p.low_engagement_trials > 1 ? "s" : ""}`, "excluded")));
  }
  if (p.screen_out_reason) {
    out.push(badge(`screened out: ${p.screen_out_reason.replaceAll("_", " ")}`, "excluded"));
  }
  if (p.uncounted_reason) {
    out.push(h("span", { class: "reason uncounted", title: "not counted toward the condition order" },
      `not counted: ${p.uncounted_reason}`));
  }
  return out.length ? out : h("span", { class: "muted" }, "–");
}

function answersBlock(data) {
  if (!data.questionnaires.length) return h("p", { class: "muted" }, "No answers yet.");
  return data.questionnaires.map((q) => h("div", { class: "answers" },
    h("h4", {}, q.title || q.questionnaire_id,
      h("span", { class: "muted" }, q.after_trial === null ? " · end of study" : ` · after round ${q.after_trial + 1}`,
        ` · ${when(q.answered_at)}`)),
    table([
      ["Item", (i) => i.text || i.id],
      ["Answer", answerCell],
      ["Scale", (i) => (i.scale ? `${i.scale.min}–${i.scale.max}` : i.type || "–"), "num"],
    ], q.items)));
}

/** A rating's value, a choice's option, or a free text (shown as text, never as markup). */
function answerCell(item) {
  if (item.value === null && item.answer_text === null) return h("span", { class: "muted" }, "no answer");
  if (item.answer_text !== null && item.answer_text !== undefined) {
    return h("span", { class: "answer-text" }, item.value !== null ? `${item.value}: ${item.answer_text}` : item.answer_text);
  }
  return String(item.value);
}

/** The last device check: ok, or what stopped the device. */
function deviceCell(p) {
  if (!p.device) return h("span", { class: "muted" }, "–");
  const d = p.device;
  const size = `${d.screen_width}×${d.screen_height}`;
  return d.problems.length ? badge(`${d.problems.join(", ").replaceAll("_", " ")} (${size})`, "excluded")
    : h("span", { title: `window ${d.viewport_width}×${d.viewport_height}` }, size);
}

function recruitCell(p) {
  const id = Object.values(p.recruiting)[0];
  return id ? h("span", { class: "recruit-id", title: id }, id) : h("span", { class: "muted" }, "–");
}

/** "3 Dec 07:53": the day and minute a participant joined (the full time on hover). */
function shortWhen(iso) {
  const date = new Date(iso);
  if (!iso || Number.isNaN(date.getTime())) return "–";
  return date.toLocaleString(undefined, { day: "numeric", month: "short", hour: "2-digit", minute: "2-digit" });
}

export function participantsPage(root, { api, params, go }) {
  const studyId = params.get("study") || "";
  const select = h("select", { id: "participants-study", "aria-label": "Study" }, h("option", { value: "" }, "All studies"));
  select.addEventListener("change", () => go(select.value ? `#/participants?study=${encodeURIComponent(select.value)}` : "#/participants"));
  const refresh = h("button", { type: "button", class: "small secondary", id: "participants-refresh" }, "Refresh");
  const frame = pageFrame("Participants", { id: "participants", controls: [select, refresh] });
  show(root, frame.node);
  const open = new Map();
  const resumeLinks = new Map();
  let editing = null;

  api.studies().then((studies) => {
    for (const s of studies) select.append(h("option", { value: s.id, selected: s.id === studyId }, `${s.title} (${s.id})`));
  }).catch(() => {});

  async function setFlags(p, body, problem) {
    try {
      await api.setFlags(p.participant_id, body);
      editing = null;
      await load();
    } catch (exc) {
      problem.textContent = errorText(exc);
    }
  }

  function excludeForm(p, problem) {
    const reason = h("input", { type: "text", id: `reason-${p.participant_id}`, class: "reason-input", maxlength: "1000",
                                placeholder: "Reason (required)", "aria-label": "Reason for excluding" });
    const form = h("form", { class: "exclude-form" }, reason,
      h("button", { type: "submit", class: "small primary" }, "Exclude"),
      h("button", { type: "button", class: "small secondary", onclick: () => { editing = null; load(); } }, "Cancel"));
    form.addEventListener("submit", (event) => {
      event.preventDefault();
      if (!reason.value.trim()) {
        problem.textContent = "Give a reason for excluding this participant.";
        reason.focus();
        return;
      }
      setFlags(p, { excluded: true, reason: reason.value.trim() }, problem);
    });
    window.setTimeout(() => reason.focus(), 0);
    return form;
  }

  function actions(p) {
    const problem = h("span", { class: "error inline", role: "alert" });
    const id = p.participant_id;
    const buttons = [
      h("button", { type: "button", class: "small secondary", dataset: { action: "test-run" },
                    onclick: () => setFlags(p, { test_run: !p.test_run }, problem) }, p.test_run ? "Not a test run" : "Mark test run"),
      p.excluded
        ? h("button", { type: "button", class: "small secondary", dataset: { action: "include" },
                        onclick: () => setFlags(p, { excluded: false }, problem) }, "Include again")
        : h("button", { type: "button", class: "small secondary", dataset: { action: "exclude" },
                        onclick: () => { editing = id; render(last); } }, "Exclude…"),
      h("button", { type: "button", class: "small secondary", dataset: { action: "answers" }, "aria-expanded": String(open.has(id)),
                    onclick: () => toggleAnswers(p) }, open.has(id) ? "Hide answers" : "Answers"),
      h("a", { href: `#/trials?participant=${encodeURIComponent(id)}` }, "Trials"),
      h("button", { type: "button", class: "small secondary", dataset: { action: "resume-link" },
                    title: "A link that moves this participant to a new device (works once; their old browser stops)",
                    onclick: () => makeResumeLink(p, problem) }, "Resume link"),
    ];
    const link = resumeLinks.get(id);
    const shown = link ? h("div", { class: "resume-link" },
      h("input", { type: "text", readonly: "", value: link.url, id: `resume-link-${id}`, "aria-label": "Resume link",
                   onfocus: (event) => event.target.select() }),
      h("span", { class: "muted" }, ` works once, until ${when(link.expires_at)}`)) : null;
    return h("div", { class: "row-actions" }, editing === id ? excludeForm(p, problem) : buttons, shown, problem);
  }

  async function makeResumeLink(p, problem) {
    try {
      resumeLinks.set(p.participant_id, await api.resumeLink(p.participant_id));
      render(last);
    } catch (exc) {
      problem.textContent = errorText(exc);
    }
  }

  async function toggleAnswers(p) {
    if (open.has(p.participant_id)) open.delete(p.participant_id);
    else {
      try {
        open.set(p.participant_id, await api.answers(p.participant_id));
      } catch (exc) {
        frame.status.textContent = errorText(exc);
      }
    }
    render(last);
  }

  let last = [];
  function render(people) {
    last = people;
    // Compact enough for 1280 px with the actions in view: the public id is cut to 8 characters (the whole id
    // on hover), the study is named only when every study is listed, the progress cell says the state.
    const columns = [
      ["Participant", (p) => h("code", { title: p.participant_id }, p.participant_id.slice(0, 8))],
      ...(studyId ? [] : [["Study", (p) => p.study_id]]),
      ["Order", (p) => (p.order_index === null ? "–" : h("span", { title: p.condition_order.join(" → ") }, String(p.order_index + 1)))],
      ["Progress", progress],
      ["Recruiting id", recruitCell],
      ["Device", deviceCell],
      ["Joined", (p) => h("span", { class: "nowrap", title: when(p.created_at) }, shortWhen(p.created_at))],
      ["Flags", flags],
      ["", actions],
    ];
    const real = people.filter((p) => !p.pilot);
    const pilots = people.filter((p) => p.pilot);
    const parts = [real.length ? peopleTable(real, columns, "participants-table")
      : h("p", { class: "muted" }, "No participant has joined yet.")];
    if (pilots.length) {
      parts.push(h("h3", { id: "pilot-heading" }, `Simulated pilot participants (${pilots.length})`),
        h("p", { class: "muted" }, "Run by steakhouse pilot: never counted for assignment, left out of exports and analyses unless asked (--include-pilot); their answers are simulated."),
        peopleTable(pilots, columns, "pilot-participants-table"));
    }
    frame.body.replaceChildren(...parts);
  }

  function peopleTable(people, columns, id) {
    const rows = [];
    for (const p of people) {
      rows.push(p);
      if (open.has(p.participant_id)) rows.push({ answersOf: p.participant_id });
    }
    return h("div", { class: "table-wrap" }, h("table", { class: "data", id },
      h("thead", {}, h("tr", {}, columns.map(([head]) => h("th", { scope: "col" }, head)))),
      h("tbody", {}, rows.map((row) => (row.answersOf
        ? h("tr", { class: "answers-row", id: `answers-${row.answersOf}` },
          h("td", { colspan: String(columns.length) }, answersBlock(open.get(row.answersOf))))
        : h("tr", { dataset: { participant: row.participant_id, excluded: String(row.excluded), testRun: String(row.test_run) } },
          columns.map(([, cell]) => h("td", {}, cell(row)))))))));
  }

  async function load() {
    try {
      render(await api.participants(studyId || undefined));
      frame.status.textContent = "";
    } catch (exc) {
      frame.status.textContent = errorText(exc);
    }
  }

  refresh.addEventListener("click", () => load());
  const stop = poll(async () => {
    if (editing === null) await load();
  }, 10000);
  return stop;
}
