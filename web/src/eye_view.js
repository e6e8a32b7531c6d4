// An eye's canvas: a WebGL2 renderer of its own, sized to the camera's image in canvas pixels
// (CSS may scale it), drawing the eye's pipeline. Also the tests' read-backs of the same
// pipeline (window.telear.ghostOnly, videoOnly).

import * as THREE from 'three';
import {EyePipeline, kVrBackground} from './eye_pipeline.js';

// No colour management anywhere: vertex colours and video bytes go to the framebuffer as they
// are, as in the native renderer.
THREE.ColorManagement.enabled = false;

export class EyeView {
  constructor(canvas, index) {
    this.canvas = canvas;
    this.index = index;  // 0 left, 1 right: the video's and the look-up tables' order
    this.renderer = new THREE.WebGLRenderer({canvas, antialias: false, alpha: false, powerPreference: 'high-performance'});
    this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    this.renderer.setPixelRatio(1);
    this.pipeline = null;
  }

  // An entry of the cameras message, the image size and the eye's video texture.
  setCamera(eye, width, height, videoTexture, lutTexture) {
    if (this.pipeline) this.pipeline.dispose();
    // Drawing buffer = the camera's pixels; updateStyle false leaves the CSS size to app.css.
    this.renderer.setSize(width, height, false);
    this.pipeline = new EyePipeline(this.renderer, eye, width, height, videoTexture);
    this.pipeline.setLookUpTable(lutTexture);
  }

  setLookUpTable(texture) {
    if (this.pipeline) this.pipeline.setLookUpTable(texture);
  }

  render(armScene, showVideo) {
    if (!this.pipeline) return false;
    this.pipeline.render(armScene, null, {showVideo, background: showVideo ? 0x000000 : kVrBackground});
    return true;
  }

  // The ghost alone through the same pipeline, W x H, on transparent black; a PNG data URL.
  ghostOnly(armScene) {
    if (!this.pipeline) throw new Error('ghostOnly: no cameras message yet');
    if (!armScene.ready) throw new Error('ghostOnly: no model or no state with the ghost yet');
    const {width, height} = this.pipeline;
    const target = new THREE.WebGLRenderTarget(width, height, {depthBuffer: false, generateMipmaps: false});
    try {
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

  // The video alone as drawn into the canvas pipeline, and the same frame's bitmap drawn by
  // the 2-D canvas: the tests check that image pixel (i, j) lands on canvas pixel (i, j).
  videoOnly(bitmap) {
    if (!this.pipeline) throw new Error('videoOnly: no cameras message yet');
    if (!bitmap) throw new Error('videoOnly: no video frame yet');
    const {width, height} = this.pipeline;
    const target = new THREE.WebGLRenderTarget(width, height, {depthBuffer: false, generateMipmaps: false});
    try {
      const composite = this.pipeline.composite;
      composite.visible = false;
      try {
        this.pipeline.render({scene: new THREE.Scene()}, target, {showVideo: true});
      } finally {
        composite.visible = true;
      }
      const pixels = new Uint8Array(width * height * 4);
      this.renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
      const reference = document.createElement('canvas');
      reference.width = width;
      reference.height = height;
      const ctx = reference.getContext('2d');
      ctx.drawImage(bitmap, 0, 0);
      return {drawn: pngFromBottomUp(pixels, width, height), decoded: reference.toDataURL('image/png')};
    } finally {
      this.renderer.setRenderTarget(null);
      target.dispose();
    }
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
