/**
 * The landing step: which study the link is for, the recruiting parameters it carries, and the
 * participant's token (kept in this browser so a refresh or a reopened tab resumes where they were).
 *
 * URL scheme (see docs/client.md):  /?study=<study id>&PROLIFIC_PID=…&STUDY_ID=…&SESSION_ID=…
 *   #test=…      an experimenter's signed test-run link from the dashboard (not counted for assignment, excluded
 *                from exports, no real completion code; in the fragment, so it never reaches a server log).
 *                A bare `test_run=1` no longer makes a test run: the page asks for the dashboard's link
 *   new=1        forget the session stored in this browser for this study and join again
 *   #handoff=…   the hand-off code a phone showed after the device check refused it: this computer continues
 *                the phone's session (without it, the page asks for the code)
 *   #resume=…    a one-time resume link from the researcher (moving to a new device; in the fragment, so it
 *                never reaches a server log): this browser takes over the participant's session
 * Only the parameters the study lists in `recruiting.url_parameters` are sent to the server. A recruiting id
 * already started in another browser is refused (409 `already_started`): only the browser holding the
 * participant's token continues (docs/protocol.md §1).
 */

import { Api } from "./api.js";

const STORE_PREFIX = "steakhouse.session.";
const RESERVED = new Set(["study", "test_run", "new"]);

export function readLink(location = window.location) {
  const params = new URLSearchParams(location.search);
  const study = (params.get("study") || "").trim();
  const raw = {};
  for (const [key, value] of params) {
    if (!RESERVED.has(key) && !(key in raw)) raw[key] = value.slice(0, 200);
  }
  const fragment = new URLSearchParams((location.hash || "").replace(/^#/, ""));
  return {
    study,
    raw,
    testRun: ["1", "true", "yes"].includes((params.get("test_run") || "").toLowerCase()),
    testLink: fragment.get("test") || "",
    handoff: fragment.get("handoff") || "",
    fresh: ["1", "true", "yes"].includes((params.get("new") || "").toLowerCase()),
    resume: fragment.get("resume") || "",
  };
}

function dropResumeFragment() {
  try {
    window.history.replaceState(null, "", window.location.pathname + window.location.search);
  } catch {
    /* the link stays in the address bar; it is used up anyway */
  }
}

function storageKey(study) {
  return STORE_PREFIX + study;
}

function loadStored(study) {
  try {
    const data = JSON.parse(window.localStorage.getItem(storageKey(study)) || "null");
    return data && typeof data.token === "string" ? data : null;
  } catch {
    return null;
  }
}

function saveStored(study, data) {
  try {
    window.localStorage.setItem(storageKey(study), JSON.stringify(data));
  } catch {
    /* storage disabled: the session still works until the page is closed */
  }
}

export function forgetStored(study) {
  try {
    window.localStorage.removeItem(storageKey(study));
  } catch {
    /* nothing stored */
  }
}

function sameParameters(a, b) {
  const keys = new Set([...Object.keys(a || {}), ...Object.keys(b || {})]);
  return [...keys].every((k) => (a || {})[k] === (b || {})[k]);
}

/**
 * Resolve the link to a participant: reuse the token stored for the same study and the same recruiting
 * parameters, or join. Returns `{api, session}`; throws `ApiError` (e.g. 404 for an unknown study).
 */
export async function enter(link) {
  const api = new Api();
  const info = await api.study(link.study);
  const recruiting = {};
  for (const name of info.url_parameters) {
    if (name in link.raw) recruiting[name] = link.raw[name];
  }
  if (link.resume) {
    const moved = await api.resume(link.study, link.resume);
    dropResumeFragment();
    api.token = moved.token;
    saveStored(link.study, { token: moved.token, recruiting, participant: moved.participant_id });
    return { api, session: await api.session(), info };
  }
  if (link.fresh) forgetStored(link.study);
  let stored = loadStored(link.study);
  if (stored && sameParameters(stored.recruiting, recruiting)) {
    api.token = stored.token;
    try {
      return { api, session: await api.session(), info };
    } catch (exc) {
      if (exc.status !== 401) throw exc;
      forgetStored(link.study);
      stored = null;
    }
  }
  // A token stored for this study goes with the join: the server resumes its participant when the recruiting
  // id is theirs, and keeps the token.
  api.token = stored ? stored.token : "";
  const joined = await api.join(link.study, recruiting, link.testLink, link.handoff);
  api.token = joined.token;
  saveStored(link.study, { token: joined.token, recruiting, participant: joined.participant_id });
  return { api, session: await api.session(), info };
}
