// The operator page of `telear web` (docs/web.md): wires the socket's messages to the
// eyes, the panels and the headset, and runs the render loop. The page holds no robot logic:
// every button and the command line send an action line that the server runs through the
// native console's code; the page draws what the `state` says.

import * as THREE from 'three';
import {ArmScene} from './arm_scene.js';
import {LatencyWindow} from './clock.js';
import {CommandLine} from './command_line.js';
import {Connection, pageNowMs} from './connection.js';
import {installDebugHooks} from './debug_hooks.js';
import {EyeView} from './eye_view.js';
import {PlanPanel} from './plan_panel.js';
import {parseBinary} from './protocol.js';
import {StatusPanel} from './status_panel.js';
import {VideoStream} from './video.js';
import {XrPresenter} from './webxr.js';

const $ = (selector) => document.querySelector(selector);
const kStatusPeriodMs = 250;  // the page's own figures; state-driven text follows each state
const kMergeMs = 50;          // how long a change other than a video frame waits for one

class App {
  constructor() {
    this.armScene = new ArmScene();
    this.video = new VideoStream((header) => this.frameDecoded(header));
    this.eyes = [new EyeView($('[data-telear="eye-left"]'), 0), new EyeView($('[data-telear="eye-right"]'), 1)];
    this.lookUpTables = [null, null];  // THREE.DataTexture per eye
    this.cameras = null;
    this.state = null;
    this.token = null;  // in memory only: sent again when the socket reconnects
    this.sessionConnected = false;
    // Page ms of the oldest change not on screen yet other than a video frame (a state, the
    // model, the cameras, a look-up table, the page's own figures), or null: it goes on screen
    // with the next video frame, or on its own once it has waited kMergeMs (animate).
    this.pendingSince = pageNowMs();
    this.newFrame = null;         // header of a decoded frame not drawn yet
    this.drawnFrames = [];        // drawn in the last animation frame: on screen at the next one
    this.shownTimes = [];         // page ms of recent shown frames, for the page's fps
    this.captureToShown = new LatencyWindow();
    this.lastStatusMs = 0;

    const debug = installDebugHooks(this);
    this.hooks = debug.hooks;
    this.stateArrived = debug.stateArrived;

    this.connectionText = $('[data-telear="connection"]');
    this.status = new StatusPanel($('[data-telear="status"]'));
    this.plan = new PlanPanel($('[data-role="plan"]'), (line) => this.sendLine(line));
    this.commandLine = new CommandLine($('.command-line'), (line) => this.sendLine(line));
    this.displayBadge = $('[data-role="display"]');
    this.eyesBox = $('.eyes');
    $('[data-telear="estop"]').addEventListener('click', () => this.sendLine('estop'));
    // The console's shortcuts (docs/console.md, "Keyboard"): Esc always, Space when no text
    // field is being edited. Capture phase: no other handler can swallow them first.
    window.addEventListener('keydown', (event) => {
      const editing = event.target instanceof HTMLInputElement || event.target instanceof HTMLTextAreaElement;
      if (event.key === 'Escape' || (event.key === ' ' && !editing)) {
        event.preventDefault();
        this.sendLine('estop');
      }
    }, {capture: true});
    $('.login').addEventListener('submit', (event) => {
      event.preventDefault();
      this.connect($('[data-telear="token"]').value.trim());
    });

    this.xr = new XrPresenter($('[data-telear="enter-vr"]'), {
      armScene: this.armScene,
      video: this.video,
      cameras: () => this.cameras,
      lookUpTable: (i) => this.lookUpTables[i],
      showVideo: () => this.showVideo(),
      onViews: (views) => { this.hooks.xrViews = views; },
      onError: (message) => this.commandLine.showResult({line: 'enter-vr', ok: false, message}),
    });
    this.xr.probe();

    const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
    this.connection = new Connection(`${scheme}://${location.host}/ws`, {
      onSocket: (open) => this.socketChanged(open),
      onMessage: (message) => this.message(message),
      onBinary: (buffer) => this.binary(buffer),
    });
    this.connection.start();
    requestAnimationFrame((t) => this.animate(t));
  }

  // [SECTION] actions

  connect(token) {
    this.token = token;
    if (!this.connection.send({type: 'connect', token})) {
      this.setConnection('disconnected (waiting for the socket to telear web; the token will be sent)');
    }
  }

  sendLine(line) {
    this.commandLine.showPending(line);
    return this.connection.command(line).then((result) => {
      this.hooks.lastResult = result;
      this.commandLine.showResult(result);
      return result;
    });
  }

  // [SECTION] messages

  socketChanged(open) {
    if (open) {
      if (this.token !== null) this.connection.send({type: 'connect', token: this.token});
    } else {
      this.sessionConnected = false;
      this.changed();
      this.setConnection('disconnected (no socket to telear web; reconnecting)');
    }
  }

  setConnection(text) {
    this.connectionText.textContent = text;
    this.connectionText.className = `connection ${text.split(/[ :]/)[0]}`;
    this.hooks.connection = text;
  }

  message(m) {
    switch (m.type) {
      case 'hello':
        this.hooks.hello = m;
        if (Array.isArray(m.joint_names) && m.joint_names.length > 0) this.plan.setJoints(m.joint_names);
        else if (Number.isInteger(m.dof)) this.plan.setJoints(Array.from({length: m.dof}, (_, i) => `joint ${i + 1}`));
        break;
      case 'connection': {
        const state = String(m.state ?? 'disconnected');
        this.sessionConnected = state === 'connected';
        this.changed();
        this.setConnection(state === 'refused' ? `refused: ${m.reason ?? ''}` : `${state}${m.reason ? ` (${m.reason})` : ''}`);
        break;
      }
      case 'model':
        try {
          this.armScene.setModel(m);
          this.hooks.model = m;
          if (this.state) this.armScene.applyState(this.state);  // setModel forgot the last one
        } catch (e) {
          this.commandLine.showResult({line: 'model', ok: false, message: e.message});
        }
        this.changed();
        break;
      case 'cameras':
        this.setCameras(m);
        break;
      case 'state':
        this.state = m;
        this.armScene.applyState(m);  // bumps its version when the picture changes
        this.status.addEvents(m.events);
        this.stateArrived(m);
        this.changed();
        break;
      default:
        break;  // result and pong are the connection's; unknown types are ignored
    }
  }

  setCameras(m) {
    const eyes = Array.isArray(m.eyes) ? m.eyes : [];
    const valid = Number.isInteger(m.width) && Number.isInteger(m.height) && m.width > 0 && m.height > 0 && eyes.length >= 1 &&
                  eyes.every((e) => e.projection?.length === 16 && e.view?.length === 16 && e.region_projection?.length === 16 &&
                                    e.region && e.region.width > 0 && e.region.height > 0);
    if (!valid) {
      this.commandLine.showResult({line: 'cameras', ok: false, message: 'malformed cameras message (docs/web.md)'});
      return;
    }
    this.cameras = m;
    this.hooks.cameras = m;
    this.eyes.forEach((view, i) => {
      const eye = eyes[i] ?? eyes[0];
      const lut = this.lookUpTables[i];
      const fits = lut && lut.image.width === m.width && lut.image.height === m.height;
      view.setCamera(eye, m.width, m.height, fits ? lut : null);
    });
    this.changed();
  }

  binary(buffer) {
    let message;
    try {
      message = parseBinary(buffer);
    } catch (e) {
      console.warn(`telear: ${e.message}`);
      return;
    }
    if (message.kind === 'video') {
      this.video.push(message);
    } else if (message.kind === 'lut') {
      const texture = new THREE.DataTexture(message.uv, message.width, message.height, THREE.RGFormat, THREE.FloatType);
      // Exact texels (texelFetch); row 0 of the data = the image's top row = texel row 0.
      texture.minFilter = THREE.NearestFilter;
      texture.magFilter = THREE.NearestFilter;
      texture.generateMipmaps = false;
      texture.flipY = false;
      texture.needsUpdate = true;
      this.lookUpTables[message.eye]?.dispose();
      this.lookUpTables[message.eye] = texture;
      this.hooks.lookUpTablesLoaded = this.lookUpTables.filter((t) => t !== null).length;
      const fits = !this.cameras || (this.cameras.width === message.width && this.cameras.height === message.height);
      if (fits) this.eyes[message.eye].setLookUpTable(texture);
      this.changed();
    }
  }

  frameDecoded(header) {
    this.newFrame = header;
  }

  changed() {
    this.pendingSince ??= pageNowMs();
  }

  // [SECTION] render loop

  showVideo() {
    return this.video.hasFrame && this.state?.display !== 'vr';
  }

  animate() {
    requestAnimationFrame((t) => this.animate(t));
    const now = pageNowMs();
    // What was drawn in the previous animation frame has been composited since.
    for (const header of this.drawnFrames) this.reportShown(header, now);
    this.drawnFrames = [];

    // Every picture the browser composites costs it a pass over the page (where it composites
    // through SwiftShader, ~15 ms of CPU for a 1400 x 900 page: as much as the video's own
    // layers), so the other changes ride along with the video frames: a change waits for the
    // next frame, at most kMergeMs, or draws at once when no video is shown.
    const showVideo = this.showVideo();
    const frame = showVideo && this.newFrame !== null && this.eyes.every((eye) => eye.ready);
    if (this.pendingSince === null && now - this.lastStatusMs > kStatusPeriodMs) this.pendingSince = now;
    const due = this.pendingSince !== null && (frame || !showVideo || now - this.pendingSince >= kMergeMs);
    if (frame || due) {
      // The ghost layers draw only when their picture changed (eye_view.js); a video frame is
      // a copy into each eye's video layer.
      for (const eye of this.eyes) eye.render(this.armScene, showVideo);
      if (frame) {
        this.eyes.forEach((eye, i) => eye.showFrame(this.video.bitmap(i)));
        this.drawnFrames.push(this.newFrame);
        this.hooks.framesShown += 1;
        this.shownTimes.push(now);
        this.newFrame = null;
      }
    }
    // Drawn, or no eye shows video now (VR): the next frame may decode.
    if (frame || !showVideo) this.video.drawn();
    while (this.shownTimes.length && now - this.shownTimes[0] > 1000) this.shownTimes.shift();
    if (due) {
      this.pendingSince = null;
      this.updatePanels(now);
    }
  }

  // docs/web.md's `shown` (frame id and page clock), plus the page's own capture -> shown
  // once the clock offset is known: the server keeps no offset of its own.
  reportShown(header, shownMs) {
    const message = {type: 'shown', frame_id: header.frame_id, shown_ms: shownMs};
    const capture = this.connection.clock.pageFromServer(Number(header.capture_ms_left));
    if (capture !== null) {
      message.latency_ms = shownMs - capture;
      this.captureToShown.add(message.latency_ms);
    }
    this.connection.send(message);
  }

  updatePanels(now) {
    this.lastStatusMs = now;
    const clock = this.connection.clock;
    this.status.update(this.state, {
      framesPerSecond: this.shownTimes.length,
      roundTripMs: clock.lastRoundTripMs,
      captureToShownP50Ms: this.captureToShown.percentile(50),
    });
    if (this.state) {
      this.plan.update(this.state);
      // The console's frame around the eyes: green live AR, amber VR, red when the picture
      // claims AR without live video behind it.
      const vr = this.state.display === 'vr';
      const live = this.sessionConnected && this.video.hasFrame && this.state.vision_connected;
      const look = vr ? 'vr' : live ? 'ar' : 'stale';
      const text = vr ? 'VR' : live ? 'AR' : 'AR (no live video)';
      if (this.displayBadge.textContent !== text) {
        this.displayBadge.textContent = text;
        this.displayBadge.className = `display-badge ${look}`;
        this.eyesBox.className = `eyes ${look}`;
      }
    }
  }
}

window.addEventListener('DOMContentLoaded', () => new App());
