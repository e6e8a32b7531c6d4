// The server's monotonic clock seen from the page, and the capture -> shown latency it makes
// measurable. Frame headers stamp the capture in server ms; the page stamps the moment it
// showed the frame in page ms; the offset between the two clocks comes from pings.
//
// Offset estimate (NTP's minimum-delay filter): a pong that took round trip r was stamped by
// the server somewhere inside that round trip, so
//     offset = server_ms - (sent + received) / 2     with an error of at most r / 2;
// the sample with the smallest r over the recent window is the most precise, and a window
// (rather than all time) follows a slow drift between the two clocks.

const kWindow = 60;          // pongs, one per second
const kLatencySamples = 300;  // frames, ~10 s of video

export class ClockSync {
  constructor() {
    this.samples = [];  // {rttMs, offsetMs}
    this.best = null;
  }

  addPong(sentPageMs, receivedPageMs, serverMs) {
    if (![sentPageMs, receivedPageMs, serverMs].every(Number.isFinite)) return;
    const rttMs = receivedPageMs - sentPageMs;
    if (rttMs < 0) return;
    this.samples.push({rttMs, offsetMs: serverMs - (sentPageMs + receivedPageMs) / 2});
    if (this.samples.length > kWindow) this.samples.shift();
    this.best = this.samples.reduce((a, b) => (b.rttMs < a.rttMs ? b : a));
  }

  // server ms - page ms, or null before the first pong.
  get offsetMs() {
    return this.best ? this.best.offsetMs : null;
  }
  get roundTripMs() {
    return this.best ? this.best.rttMs : null;
  }
  get lastRoundTripMs() {
    return this.samples.length ? this.samples[this.samples.length - 1].rttMs : null;
  }

  pageFromServer(serverMs) {
    return this.best ? serverMs - this.best.offsetMs : null;
  }
}

// The distribution of capture -> shown over the last frames (ms).
export class LatencyWindow {
  constructor(size = kLatencySamples) {
    this.size = size;
    this.values = [];
  }
  add(ms) {
    if (!Number.isFinite(ms)) return;
    this.values.push(ms);
    if (this.values.length > this.size) this.values.shift();
  }
  percentile(p) {
    if (this.values.length === 0) return null;
    const sorted = [...this.values].sort((a, b) => a - b);
    const i = Math.min(sorted.length - 1, Math.max(0, Math.round((p / 100) * (sorted.length - 1))));
    return sorted[i];
  }
}
