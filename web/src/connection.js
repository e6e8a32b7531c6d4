// The page's one WebSocket to `telear web` (ws(s)://HOST:PORT/ws, docs/web.md): it opens,
// reconnects by itself when the socket closes, numbers the commands and matches each `result`
// to its command, and pings every second for the clock offset. What the messages mean is
// main.js's business; this file only moves them.

import {ClockSync} from './clock.js';

const kPingPeriodMs = 1000;
const kReconnectMinMs = 500;
const kReconnectMaxMs = 5000;
// A command the server never answers (the socket died under it) fails after this long
// instead of leaving its button's promise pending forever.
const kCommandTimeoutMs = 15000;

// The page clock of every message we send: the same clock as `shown_ms` (ms since the epoch,
// sub-millisecond).
export function pageNowMs() {
  return performance.timeOrigin + performance.now();
}

export class Connection {
  // handlers: onSocket(open: bool), onMessage(json), onBinary(ArrayBuffer)
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers;
    this.clock = new ClockSync();
    this.socket = null;
    this.nextId = 1;
    this.pending = new Map();  // command id -> {resolve, timer, line}
    this.reconnectMs = kReconnectMinMs;
    this.pingTimer = null;
  }

  get open() {
    return this.socket !== null && this.socket.readyState === WebSocket.OPEN;
  }

  start() {
    const socket = new WebSocket(this.url);
    socket.binaryType = 'arraybuffer';
    this.socket = socket;
    socket.onopen = () => {
      this.reconnectMs = kReconnectMinMs;
      this.pingTimer = setInterval(() => this.ping(), kPingPeriodMs);
      this.ping();
      this.handlers.onSocket(true);
    };
    socket.onmessage = (event) => this.receive(event.data);
    socket.onclose = () => {
      if (this.socket !== socket) return;
      this.socket = null;
      clearInterval(this.pingTimer);
      this.failPending('the connection to telear web closed');
      this.handlers.onSocket(false);
      setTimeout(() => this.start(), this.reconnectMs);
      this.reconnectMs = Math.min(kReconnectMaxMs, this.reconnectMs * 2);
    };
    // onerror is always followed by onclose, which reconnects.
    socket.onerror = () => {};
  }

  send(message) {
    if (!this.open) return false;
    this.socket.send(JSON.stringify(message));
    return true;
  }

  // One action line (docs/console.md's vocabulary); resolves with the server's `result`
  // ({id, ok, message}) or a local failure when there is no socket.
  command(line) {
    const id = this.nextId++;
    if (!this.send({type: 'command', id, line})) {
      return Promise.resolve({type: 'result', id, ok: false, message: 'not connected to telear web', line});
    }
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        this.pending.delete(id);
        resolve({type: 'result', id, ok: false, message: `no answer to '${line}' within ${kCommandTimeoutMs / 1000} s`, line});
      }, kCommandTimeoutMs);
      this.pending.set(id, {resolve, timer, line});
    });
  }

  ping() {
    this.send({type: 'ping', id: this.nextId++, page_ms: pageNowMs()});
  }

  receive(data) {
    if (data instanceof ArrayBuffer) {
      this.handlers.onBinary(data);
      return;
    }
    let message;
    try {
      message = JSON.parse(data);
    } catch (e) {
      console.warn('telear: a text message that is not JSON:', e.message);
      return;
    }
    if (message === null || typeof message !== 'object') return;
    if (message.type === 'pong') {
      this.clock.addPong(message.page_ms, pageNowMs(), message.server_ms);
    } else if (message.type === 'result') {
      const waiting = this.pending.get(message.id);
      if (waiting) {
        this.pending.delete(message.id);
        clearTimeout(waiting.timer);
        waiting.resolve({...message, line: waiting.line});
      }
    }
    this.handlers.onMessage(message);
  }

  failPending(why) {
    for (const [id, waiting] of this.pending) {
      clearTimeout(waiting.timer);
      waiting.resolve({type: 'result', id, ok: false, message: why, line: waiting.line});
    }
    this.pending.clear();
  }
}
