// One eye's picture, drawn by one renderer: the raw video frame, and over it the scene drawn
// as the native overlay's raw mode does (include/telear/render/overlay.hpp, kRaw):
//
//   1. the scene, with `region_projection` (the pinhole camera over the region of the pixel
//      plane that the raw image's rays reach, top-left pixel (x0, y0)), into a transparent
//      region-sized target: premultiplied colour;
//   2. the video (or, in VR, a plain background) into the output;
//   3. a full-screen pass that, for each raw pixel, looks up its pinhole position in the lens
//      look-up table and blends the region target's colour there over the output
//      (src/render/overlay.cpp, kWarpFragment).
//
// So the ghost bends with the lens exactly as the video does and sits on the real arm. The
// output is an eye's ghost layer (step 2 without the video: transparent over the page's
// video layer, eye_view.js), a view's viewport of the headset's framebuffer (with the video
// texture), or (for the tests' ghostOnly) a W x H render target. A renderer is one GL
// context: the eyes' ghost layers and the headset each hold their own pipelines over the
// shared ArmScene and textures.

import * as THREE from 'three';
import {CalibratedCamera} from './calibrated_camera.js';
import {compositeMesh, videoBackgroundMesh} from './shaders.js';

export const kVrBackground = new THREE.Color(0.16, 0.18, 0.22);  // ArViewOptions::vr_background

export class EyePipeline {
  // eye: an entry of the cameras message's `eyes`; width, height: the cameras message's;
  // videoTexture: null where the pipeline never draws the video (an eye's ghost layer).
  constructor(renderer, eye, width, height, videoTexture) {
    this.renderer = renderer;
    this.width = width;
    this.height = height;
    this.name = eye.name;
    this.camera = new CalibratedCamera(eye.projection, eye.view);
    this.regionCamera = new CalibratedCamera(eye.region_projection, eye.view);
    const region = eye.region;
    this.region = {x0: region.x0, y0: region.y0, width: region.width, height: region.height};
    this.regionTarget = new THREE.WebGLRenderTarget(region.width, region.height, {
      depthBuffer: true,
      minFilter: THREE.LinearFilter,
      magFilter: THREE.LinearFilter,
      generateMipmaps: false,
    });
    this.video = videoBackgroundMesh(videoTexture);
    this.composite = compositeMesh();
    const u = this.composite.material.uniforms;
    u.u_scene.value = this.regionTarget.texture;
    u.u_image.value.set(width, height);
    u.u_origin.value.set(region.x0, region.y0);
    u.u_region.value.set(region.width, region.height);
    this.post = new THREE.Scene();
    this.post.add(this.video, this.composite);
    this.postCamera = new THREE.Camera();  // unused by the full-screen shaders
    this.regionVersion = null;
  }

  setLookUpTable(texture) {
    const u = this.composite.material.uniforms;
    u.u_lut.value = texture;
    u.u_has_lut.value = texture !== null;
  }

  // Draws into `target` (null: the canvas; a render target, with its viewport) the scene over
  // the video (showVideo) or over `background` (alpha backgroundAlpha).
  render(armScene, target, {showVideo, background = kVrBackground, backgroundAlpha = 1}) {
    const r = this.renderer;
    const autoClear = r.autoClear;
    r.autoClear = false;

    // The scene's pinhole image changes only with the scene (ArmScene.version); a new video
    // frame reuses it. A scene without a version (a read-back's) always draws, and the next
    // live draw then draws again.
    if (armScene.version === undefined || armScene.version !== this.regionVersion) {
      r.setRenderTarget(this.regionTarget);
      r.setClearColor(0x000000, 0);
      r.clear(true, true, false);
      r.render(armScene.scene, this.regionCamera);
      this.regionVersion = armScene.version;
    }

    r.setRenderTarget(target);
    r.setClearColor(background, backgroundAlpha);
    r.clear(true, true, false);
    this.video.visible = showVideo;
    r.render(this.post, this.postCamera);

    r.autoClear = autoClear;
  }

  dispose() {
    this.regionTarget.dispose();
    this.composite.material.dispose();
    this.video.material.dispose();
  }
}
