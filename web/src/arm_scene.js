// The 3-D scene every eye draws: the ghost arm (the plan being rehearsed), the reported arm
// (where the robot says it is) and, in VR, the workspace's objects. Built once from the
// `model` message; each `state` message only moves parts (T_base_part per part) and changes
// looks. One THREE.Scene shared by every renderer (both eye canvases and the headset): each
// renderer keeps its own GL copy of the same geometry.
//
// The looks are the console's (render/ar_view.hpp, draw_options.hpp). The ghost: tinted blue,
// lit, translucent -- a depth-only pass, then colour blended where the depth is the nearest
// surface's, so only its front surface shows over the video (no see-through inner faces) --
// the links in contact red; wire-frame draws the parts' line lists unlit. The reported arm
// in AR: a yellow outline (its line lists), so that it reads apart from the ghost and leaves
// the real arm in the video visible; in VR (no video): opaque in its own colours, with the
// workspace's objects, the ghost over it.

import * as THREE from 'three';
import {decodeMesh, matrixAt} from './protocol.js';
import {kHighlightColour, surfaceMaterial} from './shaders.js';

const kGhostColour = new THREE.Color(0.2, 0.75, 1.0);     // ArViewOptions::ghost_colour
const kReportedColour = new THREE.Color(1.0, 0.85, 0.2);  // ArViewOptions::reported_colour
const kDefaultOpacity = 0.55;

// three.js draws opaque objects first, then transparent ones; renderOrder sorts inside each.
const kOrderReal = 0;
const kOrderObjects = 0;
const kOrderGhostDepth = 1;
const kOrderGhostColour = 2;

function geometryOf(mesh) {
  const buffer = new THREE.InterleavedBuffer(mesh.vertices, 9);
  const surface = new THREE.BufferGeometry();
  surface.setAttribute('position', new THREE.InterleavedBufferAttribute(buffer, 3, 0));
  surface.setAttribute('normal', new THREE.InterleavedBufferAttribute(buffer, 3, 3));
  surface.setAttribute('a_colour', new THREE.InterleavedBufferAttribute(buffer, 3, 6));
  surface.setIndex(new THREE.BufferAttribute(mesh.triangles, 1));
  // The same vertices (one GL buffer) with the line list as index.
  const lines = new THREE.BufferGeometry();
  for (const name of ['position', 'normal', 'a_colour']) lines.setAttribute(name, surface.getAttribute(name));
  lines.setIndex(new THREE.BufferAttribute(mesh.lines, 1));
  return {surface, lines};
}

function placed(object, renderOrder) {
  object.matrixAutoUpdate = false;
  object.frustumCulled = false;  // parts move every state; bounds would need recomputing
  object.renderOrder = renderOrder;
  return object;
}

// T_base_part, column-major. The scene root never changes, so three.js recomputes a child's
// matrixWorld only when asked.
function setPose(object, matrix) {
  object.matrix.fromArray(matrix);
  object.matrixWorldNeedsUpdate = true;
}

export class ArmScene {
  constructor() {
    this.scene = new THREE.Scene();
    this.scene.matrixAutoUpdate = false;
    this.materials = {
      ghostDepth: surfaceMaterial(),
      ghost: surfaceMaterial({colour: kGhostColour}),
      ghostContact: surfaceMaterial({colour: kHighlightColour}),
      ghostLines: surfaceMaterial({lit: false, colour: kGhostColour}),
      ghostLinesContact: surfaceMaterial({lit: false, colour: kHighlightColour}),
      realLines: surfaceMaterial({lit: false, colour: kReportedColour}),
      realSurface: surfaceMaterial(),
      objects: surfaceMaterial(),
    };
    const m = this.materials;
    m.ghostDepth.colorWrite = false;
    for (const material of [m.ghost, m.ghostContact, m.ghostLines, m.ghostLinesContact]) {
      material.transparent = true;
      material.depthWrite = false;
      material.depthFunc = THREE.LessEqualDepth;
    }
    this.parts = [];    // {ghost: Group, real: Group, ghostSurface, ghostDepth, ghostLines, realLines}
    this.objects = [];  // Mesh
    this.geometries = [];
    this.look = {style: 'solid', opacity: kDefaultOpacity, showReported: true, vr: false, contacts: new Set()};
    this.hasGhostPose = false;
    this.ghostOnlyMode = false;
    // Bumped at every change of what the scene shows: a pipeline redraws its region target
    // only then (a new video frame alone needs just the composite).
    this.version = 0;
    this.stateKey = '';
  }

  get ready() {
    return this.parts.length > 0 && this.hasGhostPose;
  }

  // The `model` message; throws with the part's name on a malformed mesh (nothing changes).
  setModel(model) {
    const parts = (model.parts || []).map((p, i) => ({name: p.name || `part ${i}`, mesh: decodeMesh(p, `model part '${p.name}'`)}));
    const objects = (model.objects || []).map((o, i) => ({
      name: o.name || `object ${i}`,
      mesh: decodeMesh(o, `model object '${o.name}'`),
      pose: matrixAt(o.pose) || new THREE.Matrix4().toArray(),
    }));
    this.clear();
    for (const part of parts) {
      const g = geometryOf(part.mesh);
      this.geometries.push(g.surface, g.lines);
      const m = this.materials;
      const entry = {
        name: part.name,
        ghost: placed(new THREE.Group(), 0),
        real: placed(new THREE.Group(), 0),
        ghostDepth: placed(new THREE.Mesh(g.surface, m.ghostDepth), kOrderGhostDepth),
        ghostSurface: placed(new THREE.Mesh(g.surface, m.ghost), kOrderGhostColour),
        ghostLines: placed(new THREE.LineSegments(g.lines, m.ghostLines), kOrderGhostColour),
        realLines: placed(new THREE.LineSegments(g.lines, m.realLines), kOrderReal),
        realSurface: placed(new THREE.Mesh(g.surface, m.realSurface), kOrderReal),
      };
      entry.ghost.add(entry.ghostDepth, entry.ghostSurface, entry.ghostLines);
      entry.real.add(entry.realLines, entry.realSurface);
      entry.real.visible = false;
      entry.ghost.visible = false;
      this.scene.add(entry.ghost, entry.real);
      this.parts.push(entry);
    }
    for (const object of objects) {
      const g = geometryOf(object.mesh);
      this.geometries.push(g.surface, g.lines);
      const mesh = placed(new THREE.Mesh(g.surface, this.materials.objects), kOrderObjects);
      mesh.name = object.name;
      setPose(mesh, object.pose);
      mesh.visible = false;
      this.scene.add(mesh);
      this.objects.push(mesh);
    }
    this.hasGhostPose = false;
    this.stateKey = '';
    this.applyLook();
  }

  clear() {
    for (const entry of this.parts) this.scene.remove(entry.ghost, entry.real);
    for (const mesh of this.objects) this.scene.remove(mesh);
    for (const geometry of this.geometries) geometry.dispose();
    this.parts = [];
    this.objects = [];
    this.geometries = [];
    this.hasGhostPose = false;
  }

  // The `state` message's ghost and reported matrices, contacts and view options. Returns
  // whether the picture changes: at rest (most states) nothing moves, and the page then draws
  // only when a video frame arrives.
  applyState(state) {
    const key = JSON.stringify([state.ghost, state.real, state.view, state.display, state.contact_parts]);
    if (key === this.stateKey) return false;
    this.stateKey = key;
    const ghost = Array.isArray(state.ghost) ? state.ghost : null;
    const real = Array.isArray(state.real) ? state.real : null;
    this.parts.forEach((entry, i) => {
      const g = ghost ? matrixAt(ghost, 16 * i) : null;
      if (g) setPose(entry.ghost, g);
      entry.ghostPlaced = g !== null;
      const r = real ? matrixAt(real, 16 * i) : null;
      if (r) setPose(entry.real, r);
      entry.realPlaced = r !== null;
    });
    this.hasGhostPose = this.parts.length > 0 && this.parts.every((e) => e.ghostPlaced);
    const view = state.view || {};
    const opacity = Number(view.opacity);
    this.look = {
      style: view.style === 'wire' ? 'wire' : 'solid',
      opacity: Number.isFinite(opacity) ? Math.min(1, Math.max(0, opacity)) : kDefaultOpacity,
      showReported: view.show_reported !== false,
      vr: state.display === 'vr',
      contacts: new Set(Array.isArray(state.contact_parts) ? state.contact_parts : []),
    };
    this.applyLook();
    return true;
  }

  applyLook() {
    this.version += 1;
    const look = this.ghostOnlyMode
      ? {style: 'solid', opacity: 1, showReported: false, vr: false, contacts: new Set()}
      : this.look;
    const m = this.materials;
    for (const material of [m.ghost, m.ghostContact, m.ghostLines, m.ghostLinesContact]) {
      material.uniforms.u_alpha.value = look.opacity;
    }
    const solid = look.style === 'solid';
    this.parts.forEach((entry, i) => {
      const contact = look.contacts.has(i);
      entry.ghost.visible = entry.ghostPlaced === true;
      entry.ghostDepth.visible = solid;
      entry.ghostSurface.visible = solid;
      entry.ghostSurface.material = contact ? m.ghostContact : m.ghost;
      entry.ghostLines.visible = !solid;
      entry.ghostLines.material = contact ? m.ghostLinesContact : m.ghostLines;
      // VR shows the reported arm whatever show_reported says: it is the only arm there is.
      entry.real.visible = (look.vr || look.showReported) && entry.realPlaced === true;
      entry.realLines.visible = !look.vr;
      entry.realSurface.visible = look.vr;
    });
    for (const mesh of this.objects) mesh.visible = look.vr;
  }

  // Runs fn with the scene showing the ghost alone, opaque and solid (window.telear.ghostOnly);
  // the live look comes back afterwards.
  withGhostOnly(fn) {
    this.ghostOnlyMode = true;
    this.applyLook();
    try {
      return fn();
    } finally {
      this.ghostOnlyMode = false;
      this.applyLook();
    }
  }
}
