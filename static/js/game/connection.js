/**
 * The game websocket (protocol v1, server/protocol/) as an explicit state machine:
 *
 *   connecting ──hello──▶ open ──close──▶ reconnecting ──timer──▶ connecting …
 *   open ──trial_end──▶ ended        close 4000 / error "replaced" ──▶ replaced
 *   close 4401 ──▶ unauthorized      close 4409 (not at a trial) ──▶ no_trial      stop() ──▶ closed
 *   connecting ──waiting──▶ queued ──hello──▶ open    error "server_full" / close 4503 ──▶ server_full
 *   error "moved" (the resume link was used on another device) ──▶ moved
 *   error "device_refused" / close 4403 ──▶ no_trial (the page shows the device check again)
 *
 * `queued`: the server runs as many rounds as it can hold on time and this one starts when a slot is free;
 * `waiting` messages (every 2 s at least) carry the place in line and the expected wait.
 *
 * Reconnects back off exponentially (0.25 s doubling to 8 s, ±20 % jitter) and retry at once when the
 * browser comes back online. A heartbeat every 2 s measures the round trip (pong echoes our clock); a
 * connection silent for 6 s is treated as dropped. Client messages carry `seq` 1, 2, … per connection,
 * and are only sent while open (the world is paused while we are away, so nothing is queued).
 */

export const Link = Object.freeze({
  CONNECTING: "connecting", OPEN: "open", RECONNECTING: "reconnecting", ENDED: "ended",
  REPLACED: "replaced", UNAUTHORIZED: "unauthorized", NO_TRIAL: "no_trial", CLOSED: "closed",
  QUEUED: "queued", SERVER_FULL: "server_full", MOVED: "moved",
});

const FINAL = new Set([Link.ENDED, Link.REPLACED, Link.UNAUTHORIZED, Link.NO_TRIAL, Link.CLOSED, Link.SERVER_FULL,
  Link.MOVED]);
const HEARTBEAT_MS = 2000;
const SILENCE_MS = 6000;
const BACKOFF_MIN_MS = 250;
const BACKOFF_MAX_MS = 8000;

export function backoffDelay(attempt, random = Math.random) {
  const base = Math.min(BACKOFF_MAX_MS, BACKOFF_MIN_MS * 2 ** Math.max(0, attempt));
  return Math.round(base * (0.8 + 0.4 * random()));
}

export class GameConnection {
  /** `handlers`: onHello, onState, onAck, onBlocked, onError, onEnd, onLink(state, info), onLatency(ms). */
  constructor(token, handlers) {
    this.token = token;
    this.handlers = handlers;
    this.link = Link.CLOSED;
    this.ws = null;
    this.seq = 0;
    this.attempt = 0;
    this.timer = 0;
    this.beat = 0;
    this.lastHeard = 0;
    this.flags = {};
    this.onOnline = () => {
      if (this.link === Link.RECONNECTING) this.connect();
    };
    window.addEventListener("online", this.onOnline);
  }

  get isOpen() {
    return this.link === Link.OPEN;
  }

  url() {
    const scheme = window.location.protocol === "https:" ? "wss" : "ws";
    return `${scheme}://${window.location.host}/ws/play`;
  }

  /** The token travels as a subprotocol, not in the URL: URLs end up in proxy and server logs. */
  protocols() {
    return ["steakhouse.v1", `token.${this.token}`];
  }

  setLink(link, info = {}) {
    this.link = link;
    if (this.handlers.onLink) this.handlers.onLink(link, info);
  }

  /** Open (or reopen) the connection now. */
  connect() {
    window.clearTimeout(this.timer);
    this.timer = 0;
    this.drop();
    this.flags = {};
    this.seq = 0;
    this.setLink(this.attempt === 0 ? Link.CONNECTING : Link.RECONNECTING, { attempt: this.attempt, waiting: false });
    let ws;
    try {
      ws = new WebSocket(this.url(), this.protocols());
    } catch {
      this.retry();
      return;
    }
    this.ws = ws;
    this.lastHeard = performance.now();
    ws.onmessage = (event) => this.receive(ws, event.data);
    ws.onclose = (event) => this.closed(ws, event.code);
    ws.onerror = () => {};
    this.startHeartbeat();
  }

  /** Send one client message; returns its seq, or null when not connected. */
  send(type, fields = {}) {
    if (!this.isOpen || !this.ws || this.ws.readyState !== WebSocket.OPEN) return null;
    this.seq += 1;
    this.ws.send(JSON.stringify({ v: 1, seq: this.seq, type, ...fields }));
    return this.seq;
  }

  receive(ws, data) {
    if (ws !== this.ws) return;
    this.lastHeard = performance.now();
    let message;
    try {
      message = JSON.parse(data);
    } catch {
      return;
    }
    const on = this.handlers;
    switch (message.type) {
      case "hello":
        this.attempt = 0;
        this.setLink(Link.OPEN, { resumed: message.resumed });
        this.send("heartbeat", { client_time: performance.now() });
        if (on.onHello) on.onHello(message);
        break;
      case "state":
        if (on.onState) on.onState(message);
        break;
      case "ack":
        if (on.onAck) on.onAck(message);
        break;
      case "blocked":
        if (on.onBlocked) on.onBlocked(message);
        break;
      case "nudge":
        if (on.onNudge) on.onNudge(message);
        break;
      case "countdown":
        if (on.onCountdown) on.onCountdown(message);
        break;
      case "warning":
        if (on.onWarning) on.onWarning(message);
        break;
      case "stall_hint":
        if (on.onStallHint) on.onStallHint(message);
        break;
      case "pong":
        if (on.onLatency) on.onLatency(Math.max(0, performance.now() - message.client_time));
        break;
      case "waiting":
        this.attempt = 0;
        this.setLink(Link.QUEUED, { position: message.position, eta_s: message.eta_s });
        break;
      case "trial_end":
        this.flags.ended = true;
        this.setLink(Link.ENDED, message);
        if (on.onEnd) on.onEnd(message);
        break;
      case "error":
        const final = ["replaced", "unauthorized", "no_trial", "server_full", "moved", "device_refused"];
        if (final.includes(message.code)) this.flags[message.code] = true;
        else if (on.onError) on.onError(message);
        break;
      default:
        break;
    }
  }

  closed(ws, code) {
    if (ws !== this.ws) return;
    this.ws = null;
    this.stopHeartbeat();
    if (FINAL.has(this.link)) return;
    if (this.flags.ended) return;
    if (this.flags.moved) this.setLink(Link.MOVED);
    else if (this.flags.replaced || code === 4000) this.setLink(Link.REPLACED);
    else if (this.flags.unauthorized || code === 4401) this.setLink(Link.UNAUTHORIZED);
    else if (this.flags.no_trial || this.flags.device_refused || code === 4409 || code === 4403) {
      this.setLink(Link.NO_TRIAL);
    }
    else if (this.flags.server_full || code === 4503) this.setLink(Link.SERVER_FULL);
    else this.retry();
  }

  retry() {
    const delay = backoffDelay(this.attempt);
    this.attempt += 1;
    this.setLink(Link.RECONNECTING, { attempt: this.attempt, delay, waiting: true });
    this.timer = window.setTimeout(() => this.connect(), delay);
  }

  startHeartbeat() {
    this.stopHeartbeat();
    this.beat = window.setInterval(() => {
      const ws = this.ws;
      if (!ws) return;
      if (performance.now() - this.lastHeard > SILENCE_MS) {
        this.drop();
        if (!FINAL.has(this.link)) this.retry();
        return;
      }
      this.send("heartbeat", { client_time: performance.now() });
    }, HEARTBEAT_MS);
  }

  stopHeartbeat() {
    window.clearInterval(this.beat);
    this.beat = 0;
  }

  /** Forget the current socket (its late events are ignored) and close it. */
  drop() {
    const ws = this.ws;
    this.ws = null;
    this.stopHeartbeat();
    if (!ws) return;
    ws.onmessage = null;
    ws.onclose = null;
    if (ws.readyState === WebSocket.CONNECTING) {
      ws.onopen = () => ws.close(1000, "client left");
    } else if (ws.readyState === WebSocket.OPEN) {
      ws.close(1000, "client left");
    }
  }

  /** Close for good (leaving the page). */
  stop() {
    window.clearTimeout(this.timer);
    window.removeEventListener("online", this.onOnline);
    this.setLink(Link.CLOSED);
    this.drop();
  }
}
