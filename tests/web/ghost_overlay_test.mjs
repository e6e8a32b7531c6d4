// The page draws the ghost where the native renderer does: the ghost alone as the page's
// pipeline draws it (window.telear.ghostOnly: region target + lens look-up table, the live
// view's path) against `telear render` of the same configuration through the same camera
// (the embedded rig's true cameras, data/cameras/puma560_stereo.yaml, with their distortion)
// -- silhouettes, IoU >= 0.9 per eye. And the video: the pipeline's background must put image
// pixel (i, j) on canvas pixel (i, j), so the drawn video equals the decoded JPEG.
//
// The camera file is the one the simulated rig reproduces exactly (docs/simulation.md); the
// test first checks that the cameras message's projection and view are that file's, so a
// different calibration fails here with its own message rather than as a poor IoU.

import assert from 'node:assert/strict';
import {spawnSync} from 'node:child_process';
import {readFileSync, writeFileSync, mkdirSync} from 'node:fs';
import {createRequire} from 'node:module';
import path from 'node:path';
import {connect, runTest, sourceRoot, typeCommand, waitFor, webRoot} from './harness.mjs';

const {PNG} = createRequire(path.join(webRoot, 'package.json'))('pngjs');

const kCameraFile = path.join(sourceRoot, 'data', 'cameras', 'puma560_stereo.yaml');
const kBodyFile = path.join(sourceRoot, 'data', 'robots', 'puma560.body.yaml');
const kMinIoU = 0.9;
const kMagenta = [255, 0, 255];  // render's background: no colour of the arm comes near it

// [SECTION] the camera file, read just enough for the check

function cameraOf(yaml, eye) {
  const block = yaml.split(/^(?=left:|right:)/m).find((b) => b.startsWith(`${eye}:`));
  const data = (key) => {
    const m = new RegExp(`${key}:[\\s\\S]*?data:\\s*\\[([^\\]]*)\\]`).exec(block);
    assert.ok(m, `${kCameraFile}: no ${eye}.${key}`);
    return m[1].split(',').map(Number);
  };
  const number = (key) => Number(new RegExp(`${key}:\\s*(\\d+)`).exec(block)[1]);
  return {K: data('camera_matrix'), T: data('T_cam_base'), width: number('image_width'), height: number('image_height')};
}

// render/camera_projection.hpp's matrix, column-major; only the entries that K sets.
function expectedProjection({K, width: W, height: H}) {
  const [fx, s, cx, , fy, cy] = K;
  return {0: 2 * fx / W, 4: 2 * s / W, 8: 2 * (cx + 0.5) / W - 1, 5: -2 * fy / H, 9: 1 - 2 * (cy + 0.5) / H, 11: 1};
}

function checkCameras(cameras, yaml) {
  cameras.eyes.forEach((eye) => {
    const file = cameraOf(yaml, eye.name);
    assert.equal(cameras.width, file.width, `cameras width ${cameras.width}, the camera file's ${file.width}`);
    assert.equal(cameras.height, file.height, `cameras height ${cameras.height}, the camera file's ${file.height}`);
    for (const [i, v] of Object.entries(expectedProjection(file))) {
      assert.ok(Math.abs(eye.projection[i] - v) < 1e-5,
                `${eye.name} projection[${i}] = ${eye.projection[i]}, the camera file gives ${v}: the server's cameras are not ${kCameraFile}`);
    }
    // T_cam_base row-major in the file, column-major in the message.
    for (let r = 0; r < 4; ++r) {
      for (let c = 0; c < 4; ++c) {
        assert.ok(Math.abs(eye.view[c * 4 + r] - file.T[r * 4 + c]) < 1e-5,
                  `${eye.name} view(${r},${c}) = ${eye.view[c * 4 + r]}, the camera file's T_cam_base ${file.T[r * 4 + c]}`);
      }
    }
  });
}

// [SECTION] images

function decodeDataUrl(url) {
  assert.ok(url.startsWith('data:image/png;base64,'), `expected a PNG data URL, got '${url.slice(0, 40)}...'`);
  return PNG.sync.read(Buffer.from(url.slice('data:image/png;base64,'.length), 'base64'));
}

function silhouette(png, isArm) {
  const mask = new Uint8Array(png.width * png.height);
  for (let i = 0; i < mask.length; ++i) mask[i] = isArm(png.data.subarray(4 * i, 4 * i + 4)) ? 1 : 0;
  return mask;
}

function iou(a, b) {
  let both = 0;
  let either = 0;
  for (let i = 0; i < a.length; ++i) {
    both += a[i] & b[i];
    either += a[i] | b[i];
  }
  return {iou: either ? both / either : 0, both, either, a: a.reduce((s, v) => s + v, 0), b: b.reduce((s, v) => s + v, 0)};
}

function maskPng(page, native, width, height) {
  // Green: both; red: the page only; blue: telear render only.
  const png = new PNG({width, height});
  for (let i = 0; i < page.length; ++i) {
    const colour = page[i] && native[i] ? [0, 200, 0] : page[i] ? [255, 0, 0] : native[i] ? [0, 0, 255] : [0, 0, 0];
    png.data.set([...colour, 255], 4 * i);
  }
  return PNG.sync.write(png);
}

await runTest('web_ghost_overlay_test', async ({args, server, open, scratch, log}) => {
  const out = args.keep ? path.resolve(args.keep) : scratch;
  mkdirSync(out, {recursive: true});
  const page = await open();
  await connect(page, server.token);
  await waitFor(page, 'the model, the cameras, both look-up tables and a state', () => {
    const t = window.telear;
    return t.model && t.cameras && t.lookUpTablesLoaded === 2 && t.state && Array.isArray(t.state.ghost);
  }, null, 30000);
  const cameras = await page.evaluate(() => window.telear.cameras);
  checkCameras(cameras, readFileSync(kCameraFile, 'utf8'));

  // A pose that spreads the arm over the image: the silhouettes then test more than a stick.
  for (const line of ['ghost reset', 'ghost joint 1 +30deg', 'ghost joint 2 -35deg', 'ghost joint 3 +60deg', 'ghost joint 5 -45deg']) {
    const r = await typeCommand(page, line);
    assert.equal(r.ok, true, `'${line}' should succeed, got: ${r.message}`);
  }
  await page.waitForTimeout(300);  // a state with the last jog
  const state = await page.evaluate(() => window.telear.state);
  const maxOpening = Number(/max_opening_m:\s*([\d.]+)/.exec(readFileSync(kBodyFile, 'utf8'))[1]);
  const gripperM = Math.min(1, Math.max(0, state.gripper)) * maxOpening;  // the wire's fraction in metres (core::ArmBody)
  const q = state.ghost_q_deg.map((v) => v.toFixed(9)).join(',');
  log(`ghost q = [${state.ghost_q_deg.map((v) => v.toFixed(2)).join(', ')}] deg, gripper ${gripperM.toFixed(4)} m`);

  // The background that render draws the arm over.
  const background = new PNG({width: cameras.width, height: cameras.height});
  for (let i = 0; i < cameras.width * cameras.height; ++i) background.data.set([...kMagenta, 255], 4 * i);
  const backgroundFile = path.join(scratch, 'magenta.png');
  writeFileSync(backgroundFile, PNG.sync.write(background));

  for (const eye of ['left', 'right']) {
    const ghostFile = path.join(out, `ghost_page_${eye}.png`);
    const pagePng = decodeDataUrl(await page.evaluate((e) => window.telear.ghostOnly(e), eye));
    writeFileSync(ghostFile, PNG.sync.write(pagePng));
    assert.equal(pagePng.width, cameras.width, 'ghostOnly should be the camera width');
    assert.equal(pagePng.height, cameras.height, 'ghostOnly should be the camera height');

    const nativeFile = path.join(out, `ghost_render_${eye}.png`);
    const render = spawnSync(args.telear, ['render', '--q', q, '--deg', '--camera', kCameraFile, '--eye', eye,
                                           '--background', backgroundFile, '--gripper', String(gripperM), '-o', nativeFile],
                             {cwd: sourceRoot, encoding: 'utf8', timeout: 60000});
    assert.equal(render.status, 0, `telear render failed (${render.status}):\n${render.stderr}`);
    const nativePng = PNG.sync.read(readFileSync(nativeFile));
    assert.equal(nativePng.width, pagePng.width, 'render and the page should have the same width');

    const pageMask = silhouette(pagePng, (p) => p[3] > 127);
    const nativeMask = silhouette(nativePng, (p) => Math.max(Math.abs(p[0] - kMagenta[0]), Math.abs(p[1] - kMagenta[1]),
                                                             Math.abs(p[2] - kMagenta[2])) > 127);
    const score = iou(pageMask, nativeMask);
    writeFileSync(path.join(out, `ghost_diff_${eye}.png`), maskPng(pageMask, nativeMask, pagePng.width, pagePng.height));
    log(`${eye}: IoU ${score.iou.toFixed(4)} (page ${score.a} px, render ${score.b} px, both ${score.both})`);
    assert.ok(score.b > 2000, `telear render drew only ${score.b} arm pixels in the ${eye} eye: the pose is off screen?`);
    assert.ok(score.iou >= kMinIoU,
              `${eye} eye: the page's ghost and telear render's differ: IoU ${score.iou.toFixed(4)} < ${kMinIoU} ` +
              `(page ${score.a} px, render ${score.b} px; see ${path.join(out, `ghost_diff_${eye}.png`)} with --keep DIR)`);
  }

  // The video background, pixel for pixel.
  await waitFor(page, 'a video frame', () => window.telear.framesShown > 0, null, 20000);
  for (const eye of ['left', 'right']) {
    const {drawn, decoded} = await page.evaluate((e) => window.telear.videoOnly(e), eye);
    const a = decodeDataUrl(drawn);
    const b = decodeDataUrl(decoded);
    let worst = 0;
    let variation = 0;
    for (let i = 0; i < a.data.length; i += 4) {
      for (let c = 0; c < 3; ++c) worst = Math.max(worst, Math.abs(a.data[i + c] - b.data[i + c]));
      variation = Math.max(variation, Math.abs(b.data[i] - b.data[0]));
    }
    if (worst > 2) {
      writeFileSync(path.join(out, `video_drawn_${eye}.png`), PNG.sync.write(a));
      writeFileSync(path.join(out, `video_decoded_${eye}.png`), PNG.sync.write(b));
    }
    assert.ok(variation > 20, `the ${eye} video frame is nearly uniform: the comparison would prove nothing`);
    assert.ok(worst <= 2, `${eye} eye: the drawn video differs from the decoded JPEG by up to ${worst} grey levels: ` +
                          'image pixel (i, j) is not on canvas pixel (i, j)');
    log(`${eye}: video drawn = decoded JPEG (max difference ${worst})`);
  }
});
