/**
 * Small pieces the dashboard pages share: tables, times, badges, copy buttons, a page frame with a
 * status line, and a poller that never overlaps its own requests and stops with the page.
 */

import { h } from "../../js/dom.js";

/** A table: `columns` are [header, (row) => cell content, className?]. */
export function table(columns, rows, { id, empty = "Nothing yet.", rowAttrs = () => ({}) } = {}) {
  if (!rows.length) return h("p", { class: "muted empty", id }, empty);
  return h("div", { class: "table-wrap" }, h("table", { class: "data", id },
    h("thead", {}, h("tr", {}, columns.map(([head, , cls]) => h("th", { scope: "col", class: cls }, head)))),
    h("tbody", {}, rows.map((row) => h("tr", rowAttrs(row), columns.map(([, cell, cls]) => h("td", { class: cls }, cell(row))))))));
}

export function when(iso) {
  if (!iso) return "–";
  const date = new Date(iso);
  return Number.isNaN(date.getTime()) ? iso : date.toLocaleString(undefined, { dateStyle: "short", timeStyle: "medium" });
}

export function ms(value) {
  return value === null || value === undefined ? "–" : `${Number(value).toFixed(1)} ms`;
}

/**
 * Who a participant is, for the experimenter: the recruiting id (what the recruiting platform shows, e.g.
 * PROLIFIC_PID) with the random public id in its tooltip; the public id when there is no recruiting id.
 */
export function who(recruitId, publicId) {
  if (!recruitId) return h("code", { class: "who" }, publicId || "–");
  return h("span", { class: "who", title: `public id ${publicId || "–"}` }, recruitId);
}

export function badge(text, kind = "") {
  return h("span", { class: `badge ${kind}`.trim() }, text);
}

export function copyButton(text, label = "Copy") {
  const status = h("span", { class: "muted copy-status", role: "status" });
  const button = h("button", { type: "button", class: "small", onclick: async () => {
    try {
      await navigator.clipboard.writeText(text);
      status.textContent = "Copied.";
    } catch {
      status.textContent = "Select the text and copy it by hand.";
    }
  } }, label);
  return [button, status];
}

/** A page: a title row (with optional controls), a status line for problems, and the body. */
export function pageFrame(title, { id, controls = [] } = {}) {
  const status = h("p", { class: "error", role: "alert", id: id ? `${id}-status` : undefined });
  const body = h("div", { class: "page-body" });
  const node = h("section", { class: "page", id, "aria-labelledby": id ? `${id}-title` : undefined },
    h("div", { class: "page-head" }, h("h1", { id: id ? `${id}-title` : undefined, tabindex: "-1" }, title), ...controls),
    status, body);
  return { node, status, body };
}

/** Call `task` now and then every `intervalMs` after each run finished, until the returned stop(). */
export function poll(task, intervalMs) {
  let timer = 0;
  let stopped = false;
  const run = async () => {
    try {
      await task();
    } catch {
      /* the task shows its own problems; polling goes on */
    } finally {
      if (!stopped) timer = window.setTimeout(run, intervalMs);
    }
  };
  run();
  return () => {
    stopped = true;
    window.clearTimeout(timer);
  };
}

export function errorText(exc) {
  if (exc.status === 0) return "The server could not be reached; retrying.";
  return exc.message || String(exc);
}
