// The stereo video: each binary frame's two JPEGs decoded off the main thread
// (createImageBitmap, both at once) into one ImageBitmap per eye, which the eyes' video layers
// draw (eye_view.js) and the headset's pipelines upload as textures (webxr.js: only they
// upload). Latest wins, as on the server: while a frame decodes, or waits to be drawn, a newer
// one waits in a single slot and replaces any older waiting one, so a slow machine shows (and
// decodes) fewer frames rather than older ones.

import * as THREE from 'three';

// No colour-space conversion or premultiplication: the pixel values of the JPEG are the
// pixel values drawn, as the native console's decoder gives them.
const kBitmapOptions = {colorSpaceConversion: 'none', premultiplyAlpha: 'none', imageOrientation: 'from-image'};

function eyeTexture() {
  const texture = new THREE.Texture();
  // An ImageBitmap is uploaded top row first whatever UNPACK_FLIP_Y says; flipY = false keeps
  // three.js from asking (and warning). The shaders read row 0 as the image's top row.
  texture.flipY = false;
  texture.generateMipmaps = false;
  texture.minFilter = THREE.LinearFilter;
  texture.magFilter = THREE.LinearFilter;
  texture.colorSpace = THREE.NoColorSpace;
  texture.premultiplyAlpha = false;
  return texture;
}

export class VideoStream {
  // onFrame(header): a frame's textures have been replaced (called on the main thread).
  constructor(onFrame) {
    this.onFrame = onFrame;
    this.textures = [eyeTexture(), eyeTexture()];
    this.bitmaps = [null, null];
    this.header = null;   // the header of the frame in the textures
    this.waiting = null;  // the newest frame not decoded yet
    this.decoding = false;
    this.undrawn = false;  // the decoded frame has not been drawn yet (drawn())
    this.errors = 0;
    this.lastError = '';
  }

  get hasFrame() {
    return this.header !== null;
  }

  push(frame) {
    this.waiting = frame;
    if (!this.decoding && !this.undrawn) this.decodeNext();
  }

  // The decoded frame has been drawn (or nothing shows video now): the next one may decode.
  // Until then a newer frame waits in the slot undecoded, so a page that draws fewer frames
  // than arrive spends no time decoding frames that it would never show.
  drawn() {
    this.undrawn = false;
    if (!this.decoding && this.waiting) this.decodeNext();
  }

  async decodeNext() {
    this.decoding = true;
    while (this.waiting && !this.undrawn) {
      const frame = this.waiting;
      this.waiting = null;
      try {
        const bitmaps = await Promise.all([frame.left, frame.right].map((jpeg) =>
          createImageBitmap(new Blob([jpeg], {type: 'image/jpeg'}), kBitmapOptions)));
        this.show(frame.header, bitmaps);
      } catch (e) {
        this.errors += 1;
        this.lastError = `frame ${frame.header.frame_id}: ${e.message}`;
      }
    }
    this.decoding = false;
  }

  show(header, bitmaps) {
    bitmaps.forEach((bitmap, eye) => {
      // The video layers draw, and every renderer that uploads this texture (the headset's)
      // uploads, the new bitmap from now on: the old one is no longer needed by any of them.
      if (this.bitmaps[eye]) this.bitmaps[eye].close();
      this.bitmaps[eye] = bitmap;
      this.textures[eye].image = bitmap;
      this.textures[eye].needsUpdate = true;
    });
    this.header = header;
    this.undrawn = true;
    this.onFrame(header);
  }

  // The current frame's bitmap of one eye (what the eye's video layer draws), or null.
  bitmap(eye) {
    return this.bitmaps[eye];
  }
}
