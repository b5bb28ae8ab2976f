/**
 * The experimenter's dashboard at /admin/: a login form for the admin token, then studies (condition
 * orders, recruiting links, downloads), participants (progress, flags, answers), live trials, stored
 * trials and their replays. Pages are chosen from the address's hash (#/studies, #/live/12, …), so the
 * server serves one file and a refresh stays on the page.
 *
 * Nothing but the login form is shown until the server accepts the token; any 401 later (e.g. the server
 * restarted with another token) forgets it and shows the form again.
 */

import { h, show } from "../../js/dom.js";
import { AdminApi } from "./api.js";
import { forgetToken, storedToken, storeToken } from "./auth.js";
import { studiesPage } from "./studies.js";
import { participantsPage } from "./participants.js";
import { liveListPage, liveTrialPage } from "./live.js";
import { trialsPage } from "./trials.js";
import { replayPage } from "./replay.js";

const root = document.getElementById("admin-app");
const nav = document.getElementById("admin-nav");
const logout = document.getElementById("logout");

const NAV = [["studies", "Studies"], ["participants", "Participants"], ["live", "Live"], ["trials", "Trials"]];
const PAGES = {
  studies: studiesPage,
  participants: participantsPage,
  live: (r, ctx) => (ctx.args[0] ? liveTrialPage(r, ctx) : liveListPage(r, ctx)),
  trials: trialsPage,
  replay: replayPage,
};

let cleanup = null;
let api = null;

/** `#/live/12?x=1` → {page: "live", args: ["12"], params: URLSearchParams("x=1")}. */
export function parseHash(hash) {
  const [path, search = ""] = hash.replace(/^#\/?/, "").split("?");
  const [page = "", ...args] = path.split("/").filter(Boolean).map(decodeURIComponent);
  return { page: page || "studies", args, params: new URLSearchParams(search) };
}

function stop() {
  if (cleanup) cleanup();
  cleanup = null;
}

function signedOut(message) {
  stop();
  api = null;
  forgetToken();
  nav.hidden = true;
  nav.replaceChildren();
  logout.hidden = true;
  document.body.dataset.auth = "out";
  loginPage(message);
}

function loginPage(message = "") {
  const input = h("input", { type: "password", id: "admin-token", name: "token", autocomplete: "current-password",
                             required: true, spellcheck: "false" });
  const error = h("p", { class: "error", role: "alert", id: "login-error" }, message);
  const button = h("button", { type: "submit", class: "primary", id: "login-submit" }, "Log in");
  const form = h("form", { id: "login-form", class: "card narrow", "aria-labelledby": "login-title" },
    h("h1", { id: "login-title" }, "Admin login"),
    h("p", { class: "muted" }, "Enter the admin token of this server (STEAKHOUSE_ADMIN_TOKEN; when it is not set, the " +
      "server logs a generated one at start). It is kept in this tab only."),
    h("label", { for: "admin-token", class: "field-label" }, "Admin token"), input,
    h("div", { class: "actions" }, button), error);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const token = input.value.trim();
    if (!token) return;
    button.disabled = true;
    error.textContent = "";
    const ok = await signIn(token, (text) => { error.textContent = text; });
    if (!ok) {
      button.disabled = false;
      input.select();
    }
  });
  show(root, form, input);
}

async function signIn(token, fail) {
  const candidate = new AdminApi(token);
  try {
    await candidate.studies();
  } catch (exc) {
    fail(exc.status === 401 ? "This token is not valid for this server." : `The server could not check the token (${exc.message}).`);
    return false;
  }
  storeToken(token);
  api = new AdminApi(token, () => signedOut("Your admin session is no longer valid: log in again."));
  document.body.dataset.auth = "in";
  nav.replaceChildren(...NAV.map(([id, label]) => h("a", { href: `#/${id}`, id: `nav-${id}`, dataset: { page: id } }, label)));
  nav.hidden = false;
  logout.hidden = false;
  route();
  return true;
}

function route() {
  if (!api) return;
  stop();
  const where = parseHash(window.location.hash);
  const section = where.page === "replay" ? "trials" : where.page;
  for (const link of nav.querySelectorAll("a")) {
    if (link.dataset.page === section) link.setAttribute("aria-current", "page");
    else link.removeAttribute("aria-current");
  }
  const page = PAGES[where.page];
  if (!page) {
    show(root, h("section", { class: "card narrow" }, h("h1", {}, "Not found"),
      h("p", {}, "This dashboard has no such page. "), h("a", { href: "#/studies" }, "Back to the studies")));
    return;
  }
  cleanup = page(root, { api, args: where.args, params: where.params, go: (hash) => { window.location.hash = hash; } }) || null;
}

window.addEventListener("hashchange", route);
logout.addEventListener("click", () => signedOut(""));

async function boot() {
  const token = storedToken();
  if (!token) {
    signedOut("");
    return;
  }
  await signIn(token, (text) => signedOut(text));
}

boot();
