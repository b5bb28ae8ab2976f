/**
 * A small, safe Markdown renderer for the study's consent and instructions texts: headings (# is the
 * page's h1, ## h2, ### h3),
 * paragraphs, bullet and numbered lists, **bold**, *italic* / _italic_, `code` and [links](https://…).
 * It builds DOM nodes (never innerHTML), so a study file cannot inject markup or scripts.
 */

import { h } from "./dom.js";

export function renderMarkdown(text) {
  const out = document.createDocumentFragment();
  const lines = String(text || "").replace(/\r\n?/g, "\n").split("\n");
  let paragraph = [];
  let list = null;

  const flushParagraph = () => {
    if (paragraph.length) out.append(h("p", {}, inline(paragraph.join(" "))));
    paragraph = [];
  };
  const flushList = () => {
    if (list) out.append(list);
    list = null;
  };

  for (const raw of lines) {
    const line = raw.trimEnd();
    const heading = /^(#{1,3})\s+(.*)$/.exec(line);
    const bullet = /^\s*[-*+]\s+(.*)$/.exec(line);
    const numbered = /^\s*\d+[.)]\s+(.*)$/.exec(line);
    if (!line.trim()) {
      flushParagraph();
      flushList();
    } else if (heading) {
      flushParagraph();
      flushList();
      out.append(h(`h${heading[1].length}`, {}, inline(heading[2])));
    } else if (bullet || numbered) {
      flushParagraph();
      const tag = bullet ? "ul" : "ol";
      if (!list || list.tagName.toLowerCase() !== tag) {
        flushList();
        list = h(tag);
      }
      list.append(h("li", {}, inline((bullet || numbered)[1])));
    } else if (list && /^\s{2,}\S/.test(raw)) {
      list.lastElementChild.append(" ", ...inline(line.trim()));
    } else {
      flushList();
      paragraph.push(line.trim());
    }
  }
  flushParagraph();
  flushList();
  return out;
}

const INLINE = /(\*\*[^*]+\*\*|__[^_]+__|\*[^*\s][^*]*\*|_[^_\s][^_]*_|`[^`]+`|\[[^\]]+\]\([^)\s]+\))/;

/** Inline spans of one line as DOM nodes. */
export function inline(text) {
  const nodes = [];
  for (const part of String(text).split(INLINE)) {
    if (!part) continue;
    if (/^(\*\*|__)/.test(part) && part.length > 4) nodes.push(h("strong", {}, inline(part.slice(2, -2))));
    else if (/^[*_]/.test(part) && part.length > 2 && /[*_]$/.test(part)) nodes.push(h("em", {}, inline(part.slice(1, -1))));
    else if (part.startsWith("`") && part.length > 2) nodes.push(h("code", {}, part.slice(1, -1)));
    else if (part.startsWith("[")) nodes.push(link(part));
    else nodes.push(document.createTextNode(part));
  }
  return nodes;
}

function link(part) {
  const match = /^\[([^\]]+)\]\(([^)\s]+)\)$/.exec(part);
  if (!match || !/^(https?:\/\/|mailto:)/i.test(match[2])) return document.createTextNode(part);
  return h("a", { href: match[2], target: "_blank", rel: "noopener noreferrer" }, match[1]);
}
