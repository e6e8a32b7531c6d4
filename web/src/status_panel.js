// The Status panel (docs/console.md, "Status"): what the session's `state` says -- fps,
// latency per stage, AR / VR and why, ages, control, e-stop, mode, the last message -- plus
// what only the page knows: frames it showed per second, the ping round trip and the
// capture -> shown latency. The panel keeps no state of its own beyond the event log; it is
// redrawn from the last state at most once per animation frame, touching only text that
// changed (a 2-core machine renders the video in software at the same time).

const kMaxEvents = 50;

function fixed(value, digits) {
  return Number.isFinite(value) ? value.toFixed(digits) : '–';
}

function setText(element, text) {
  if (element.textContent !== text) element.textContent = text;
}

export class StatusPanel {
  constructor(root) {
    this.root = root;
    this.fps = root.querySelector('[data-telear="fps"]');
    this.facts = root.querySelector('[data-role="facts"]');
    this.latency = root.querySelector('[data-role="latency"] tbody');
    this.message = root.querySelector('[data-role="message"]');
    this.events = root.querySelector('[data-role="events"]');
    this.factRows = new Map();
    this.latencyRows = new Map();
  }

  fact(name) {
    let dd = this.factRows.get(name);
    if (!dd) {
      const dt = document.createElement('dt');
      dt.textContent = name;
      dd = document.createElement('dd');
      this.facts.append(dt, dd);
      this.factRows.set(name, dd);
    }
    return dd;
  }

  setFact(name, text, className = '') {
    const dd = this.fact(name);
    setText(dd, text);
    if (dd.className !== className) dd.className = className;
  }

  // page: {framesPerSecond, roundTripMs, captureToShownP50Ms, connection}
  update(state, page) {
    // The video's rate as the session measures it (the state's fps), first, as a number.
    setText(this.fps, `${fixed(state ? Number(state.fps) : 0, 1)} fps`);
    if (state) {
      const display = state.display === 'vr' ? 'VR' : state.display === 'ar' ? 'AR' : String(state.display ?? '–');
      this.setFact('view', `${display}${state.display_reason ? ` (${state.display_reason})` : ''}`,
                   state.display === 'vr' ? 'vr' : state.display === 'ar' ? 'ar' : '');
      this.setFact('frame age', `${fixed(state.frame_age_ms, 0)} ms`);
      this.setFact('robot state age', `${fixed(state.state_age_ms, 0)} ms`);
      this.setFact('robot', state.robot_connected ? 'connected' : 'not connected', state.robot_connected ? 'ar' : 'bad');
      this.setFact('video', state.vision_connected ? 'connected' : 'not connected', state.vision_connected ? 'ar' : 'bad');
      this.setFact('in control', state.in_control ? 'yes (this tab holds the lease)' : 'no');
      this.setFact('mode', String(state.mode ?? '–'), state.mode === 'estop' ? 'bad' : '');
      this.setFact('e-stop', state.estop ? 'ENGAGED' : 'off', state.estop ? 'bad' : '');
      // The page draws the raw video only (the server sends the raw-to-pinhole table, not the
      // undistort maps); say so rather than silently ignore `view video undistorted`.
      this.setFact('video view', state.view?.undistorted ? 'raw (undistorted is the console\'s only)' : 'raw');
    }
    this.setFact('page fps', `${fixed(page.framesPerSecond, 1)} shown`);
    this.setFact('ping', page.roundTripMs === null ? '–' : `${fixed(page.roundTripMs, 1)} ms round trip`);
    this.setFact('capture → shown', page.captureToShownP50Ms === null ? 'not measured yet'
                                                                     : `${fixed(page.captureToShownP50Ms, 0)} ms p50`);
    if (state) {
      this.updateLatency(state.latency_ms);
      setText(this.message, String(state.message ?? ''));
      this.message.classList.toggle('failed', state.message_failed === true);
    }
  }

  updateLatency(latency) {
    if (!latency || typeof latency !== 'object') return;
    const names = Object.keys(latency);  // the server's order: the stages as the frame passes them
    const current = [...this.latencyRows.keys()];
    if (names.length !== current.length || names.some((n, i) => n !== current[i])) {
      this.latency.replaceChildren();
      this.latencyRows.clear();
      for (const name of names) {
        const tr = document.createElement('tr');
        const label = document.createElement('td');
        label.textContent = name.replaceAll('_', ' ');
        const value = document.createElement('td');
        tr.append(label, value);
        this.latency.append(tr);
        this.latencyRows.set(name, value);
      }
    }
    for (const name of names) setText(this.latencyRows.get(name), fixed(Number(latency[name]), 1));
  }

  // The state's `events` (those since the previous state): appended, the last kMaxEvents kept.
  addEvents(events) {
    if (!Array.isArray(events) || events.length === 0) return;
    for (const event of events) {
      const li = document.createElement('li');
      li.className = String(event.kind ?? '');
      li.textContent = `${fixed(Number(event.t), 1)} s  ${event.kind ?? ''}  ${event.message ?? ''}`;
      this.events.append(li);
    }
    while (this.events.childElementCount > kMaxEvents) this.events.firstElementChild.remove();
    this.events.scrollTop = this.events.scrollHeight;
  }
}
