// An eye on the page: two stacked canvases of the camera's size (CSS may scale them, both
// alike) in the element that carries data-telear="eye-left" / "eye-right":
//
//   - the video layer: the decoded frame itself, drawn by a 2-D canvas (drawImage of the
//     ImageBitmap: a copy, no shader pass), so a new video frame costs no WebGL work at all;
//   - the ghost layer above it: a transparent WebGL2 canvas (premultiplied alpha) with a
//     three.js renderer of its own that draws the eye's pipeline without the video -- the
//     scene's region pass and the lens composite -- and that the browser composites over the
//     video exactly as the composite's blend did (colour + video * (1 - alpha)). It is redrawn
//     only when what it shows changes: the scene (ArmScene.version), AR / VR, the cameras or a
//     look-up table; a canvas that is not drawn keeps showing its last picture.
//
// In VR (no live video) the video layer is hidden and the ghost layer draws the opaque dark
// background, the arm and the objects. Also the tests' read-backs (window.telear.ghostOnly,
// videoOnly).

import * as THREE from 'three';
import {EyePipeline, kVrBackground} from './eye_pipeline.js';

// No colour management anywhere: vertex colours and video bytes go to the framebuffer as they
// are, as in the native renderer.
THREE.ColorManagement.enabled = false;

export class EyeView {
  // element: the eye's container, holding canvas.eye-video and canvas.eye-ghost.
  constructor(element, index) {
    this.element = element;
    this.index = index;  // 0 left, 1 right: the video's and the look-up tables' order
    this.videoCanvas = element.querySelector('canvas.eye-video');
    this.ghostCanvas = element.querySelector('canvas.eye-ghost');
    // A 2-D context that "reads back often" is kept in memory rather than in a GL texture:
    // drawImage of the decoded (CPU) bitmap is then a plain copy. Measured in headless
    // Chromium with SwiftShader, two such canvases at 30 fps cost its GPU process 15-25 % less
    // than accelerated 2-D canvases or 'bitmaprenderer' ones (transferFromImageBitmap), and
    // the bitmap stays usable by the headset's textures.
    this.video = this.videoCanvas.getContext('2d', {alpha: false, willReadFrequently: true});
    this.renderer = new THREE.WebGLRenderer({canvas: this.ghostCanvas, antialias: false, alpha: true,
                                             premultipliedAlpha: true, powerPreference: 'high-performance'});
    this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    this.renderer.setPixelRatio(1);
    this.pipeline = null;
    this.lookUpTable = null;
    this.drawnKey = null;      // what the ghost layer shows: [pipeline, version, showVideo, table]
    this.videoShown = true;    // the video layer's visibility
  }

  get ready() {
    return this.pipeline !== null;
  }

  // An entry of the cameras message, the image size and the eye's look-up table.
  setCamera(eye, width, height, lutTexture) {
    if (this.pipeline) this.pipeline.dispose();
    // Both layers = the camera's pixels; updateStyle false leaves the CSS size to app.css.
    if (this.videoCanvas.width !== width) this.videoCanvas.width = width;
    if (this.videoCanvas.height !== height) this.videoCanvas.height = height;
    this.renderer.setSize(width, height, false);
    this.drawnKey = null;
    // No video texture: the video is the other layer's (the headset's pipelines have their own).
    this.pipeline = new EyePipeline(this.renderer, eye, width, height, null);
    this.setLookUpTable(lutTexture);
  }

  setLookUpTable(texture) {
    this.lookUpTable = texture;
    if (this.pipeline) this.pipeline.setLookUpTable(texture);
  }

  // Puts a decoded frame (ImageBitmap, the camera's size) on the video layer, pixel for pixel.
  showFrame(bitmap) {
    if (!this.pipeline || !bitmap) return false;
    this.video.drawImage(bitmap, 0, 0);
    return true;
  }

  // The ghost layer, redrawn only when its picture changes. Returns whether it drew.
  render(armScene, showVideo) {
    if (!this.pipeline) return false;
    if (this.videoShown !== showVideo) {
      this.videoShown = showVideo;
      this.videoCanvas.style.visibility = showVideo ? '' : 'hidden';
    }
    const key = [this.pipeline, armScene.version, showVideo, this.lookUpTable];
    if (this.drawnKey && key.every((v, i) => v === this.drawnKey[i])) return false;
    this.drawnKey = key;
    // Over the video: transparent black, so the layer holds the ghost's premultiplied colour
    // alone; in VR: the opaque background.
    this.pipeline.render(armScene, null, showVideo ? {showVideo: false, background: 0x000000, backgroundAlpha: 0}
                                                   : {showVideo: false, background: kVrBackground, backgroundAlpha: 1});
    return true;
  }

  // The ghost alone through the same pipeline, W x H, on transparent black; a PNG data URL.
  ghostOnly(armScene) {
    if (!this.pipeline) throw new Error('ghostOnly: no cameras message yet');
    if (!armScene.ready) throw new Error('ghostOnly: no model or no state with the ghost yet');
    const {width, height} = this.pipeline;
    const target = new THREE.WebGLRenderTarget(width, height, {depthBuffer: false, generateMipmaps: false});
    try {
      // withGhostOnly bumps the scene's version: the live layer's region pass runs again at
      // its next draw; the layer itself (the canvas) is not drawn here.
      armScene.withGhostOnly(() => {
        this.pipeline.render(armScene, target, {showVideo: false, background: 0x000000, backgroundAlpha: 0});
      });
      const pixels = new Uint8Array(width * height * 4);
      this.renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
      return pngFromBottomUp(pixels, width, height);
    } finally {
      this.renderer.setRenderTarget(null);
      target.dispose();
    }
  }

  // The video layer as drawn (read back from its canvas), and the same frame's bitmap drawn by
  // a fresh 2-D canvas: the tests check that image pixel (i, j) lands on canvas pixel (i, j).
  videoOnly(bitmap) {
    if (!this.pipeline) throw new Error('videoOnly: no cameras message yet');
    if (!bitmap) throw new Error('videoOnly: no video frame yet');
    const {width, height} = this.pipeline;
    this.showFrame(bitmap);  // the newest frame: the one the layer shows at the next animation frame
    const drawn = this.videoCanvas.toDataURL('image/png');
    const reference = document.createElement('canvas');
    reference.width = width;
    reference.height = height;
    reference.getContext('2d').drawImage(bitmap, 0, 0);
    return {drawn, decoded: reference.toDataURL('image/png')};
  }
}

// GL read-back rows start at the bottom; an image's at the top.
function pngFromBottomUp(pixels, width, height) {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const ctx = canvas.getContext('2d');
  const image = ctx.createImageData(width, height);
  const row = width * 4;
  for (let y = 0; y < height; ++y) {
    image.data.set(pixels.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  }
  ctx.putImageData(image, 0, 0);
  return canvas.toDataURL('image/png');
}
