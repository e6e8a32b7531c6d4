// The headset (WebXR immersive-vr): each eye of the headset shows THAT camera's picture --
// its video and the ghost through its calibrated projection and T_cam_base, as on the eye
// canvases -- not a view rendered from the headset's pose and IPD. The stereo baseline is the
// camera rig's, as on the seed's stereo HMD display: the operator looks through the cameras.
//
// Own frame loop rather than three.js's renderer.xr, which would replace the cameras by the
// headset's views. Per XR frame and view: the base layer's viewport for that view, and the
// eye's pipeline (eye_pipeline.js) drawn into it through an externally managed render target
// (WebGLRenderer.setRenderTargetFramebuffer, as three.js's own XR manager binds the layer).
// These pipelines are the only users of the video textures (video.js): the page's eyes draw
// the decoded bitmaps into their video layers, so a frame is uploaded only while a session
// runs.

import * as THREE from 'three';
import {EyePipeline} from './eye_pipeline.js';

const kEyeIndex = {left: 0, right: 1};

export class XrPresenter {
  // host: {armScene, video, cameras(), lookUpTable(eye), showVideo(), onViews(views), onShown()}
  constructor(button, host) {
    this.button = button;
    this.host = host;
    this.session = null;
    this.renderer = null;
    this.pipelines = null;
    this.camerasKey = null;
    button.addEventListener('click', () => (this.session ? this.session.end() : this.enter()));
  }

  async probe() {
    let supported = false;
    try {
      supported = navigator.xr ? await navigator.xr.isSessionSupported('immersive-vr') : false;
    } catch {
      supported = false;
    }
    this.button.hidden = !supported;
    this.button.disabled = !supported;
    return supported;
  }

  async enter() {
    if (this.session || !navigator.xr) return;
    this.button.disabled = true;
    try {
      const session = await navigator.xr.requestSession('immersive-vr');
      await this.start(session);
    } catch (e) {
      console.warn('telear: WebXR session refused:', e.message);
      this.host.onError?.(`VR: ${e.message}`);
    } finally {
      this.button.disabled = false;
    }
  }

  async start(session) {
    if (!this.renderer) {
      const canvas = document.createElement('canvas');
      this.renderer = new THREE.WebGLRenderer({canvas, antialias: false, alpha: false});
      this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
      this.renderer.autoClear = false;
    }
    const gl = this.renderer.getContext();
    await gl.makeXRCompatible();
    const layer = new XRWebGLLayer(session, gl);
    await session.updateRenderState({baseLayer: layer});
    const space = await session.requestReferenceSpace('local');
    this.session = session;
    this.layer = layer;
    this.space = space;
    this.target = new THREE.WebGLRenderTarget(layer.framebufferWidth, layer.framebufferHeight, {depthBuffer: true});
    this.button.textContent = 'Exit VR';
    session.addEventListener('end', () => {
      this.session = null;
      this.button.textContent = 'Enter VR';
    });
    session.requestAnimationFrame((t, frame) => this.frame(t, frame));
  }

  // The pipelines follow the cameras message (a new one after a reconnection).
  ensurePipelines() {
    const cameras = this.host.cameras();
    if (!cameras) return null;
    if (this.camerasKey !== cameras) {
      if (this.pipelines) this.pipelines.forEach((p) => p.dispose());
      this.pipelines = cameras.eyes.map((eye, i) =>
        new EyePipeline(this.renderer, eye, cameras.width, cameras.height, this.host.video.textures[i]));
      this.camerasKey = cameras;
    }
    this.pipelines.forEach((p, i) => p.setLookUpTable(this.host.lookUpTable(i)));
    return this.pipelines;
  }

  frame(time, frame) {
    const session = frame.session;
    if (session !== this.session) return;
    session.requestAnimationFrame((t, f) => this.frame(t, f));
    const pose = frame.getViewerPose(this.space);
    const pipelines = this.ensurePipelines();
    if (!pose || !pipelines) return;
    const layer = session.renderState.baseLayer;
    this.renderer.setRenderTargetFramebuffer(this.target, layer.framebuffer);
    const used = [];
    for (const view of pose.views) {
      // A mono view ('none') shows the left camera.
      const index = kEyeIndex[view.eye] ?? 0;
      const pipeline = pipelines[index] ?? pipelines[0];
      const vp = layer.getViewport(view);
      // Viewport and scissor: each eye's clear must leave the other eye's half alone.
      this.target.viewport.set(vp.x, vp.y, vp.width, vp.height);
      this.target.scissor.set(vp.x, vp.y, vp.width, vp.height);
      this.target.scissorTest = true;
      pipeline.render(this.host.armScene, this.target, {showVideo: this.host.showVideo()});
      used.push({
        eye: view.eye,
        projection: pipeline.camera.projectionMatrix.toArray(),
        view: pipeline.camera.matrixWorldInverse.toArray(),
        viewport: [vp.x, vp.y, vp.width, vp.height],
      });
    }
    this.renderer.setRenderTarget(null);
    // The headset drew the frame: the next may decode (the page's own animation frames may
    // be paused while the headset presents).
    this.host.video.drawn();
    this.host.onViews(used);
  }
}
