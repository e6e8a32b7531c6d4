// The headset: with an emulated WebXR runtime (iwer's Meta Quest 3, injected before the page
// loads), `enter-vr` shows and starts an immersive-vr session, and each XR view is drawn
// with THAT CAMERA's calibrated projection and view from the `cameras` message -- not the
// headset's pose or IPD (the stereo baseline is the camera rig's).

import assert from 'node:assert/strict';
import {readFileSync} from 'node:fs';
import {createRequire} from 'node:module';
import path from 'node:path';
import {connect, runTest, selector, waitFor, webRoot} from './harness.mjs';

const kTolerance = 1e-5;

async function emulatorScript(scratch) {
  const esbuild = await import(createRequire(path.join(webRoot, 'package.json')).resolve('esbuild'));
  const outfile = path.join(scratch, 'iwer_runtime.js');
  await esbuild.build({
    stdin: {
      // forceInstall: Chromium has a navigator.xr of its own (with no headset behind it).
      contents: "import {XRDevice, metaQuest3} from 'iwer';\n" +
                'const device = new XRDevice(metaQuest3, {stereoEnabled: true});  // a headset: both eyes drawn\n' +
                'device.installRuntime({forceInstall: true});\n' +
                'window.__iwerDevice = device;\n',
      resolveDir: webRoot,
      loader: 'js',
    },
    nodePaths: [path.join(webRoot, 'node_modules')],
    bundle: true,
    format: 'iife',
    target: ['es2022'],
    outfile,
    logLevel: 'warning',
  });
  return readFileSync(outfile, 'utf8');
}

await runTest('web_webxr_test', async ({server, open, scratch, log}) => {
  const page = await open({initScript: {content: await emulatorScript(scratch)}});
  await connect(page, server.token);
  await waitFor(page, 'the cameras, both look-up tables and a state', () => {
    const t = window.telear;
    return t.cameras && t.lookUpTablesLoaded === 2 && t.state && Array.isArray(t.state.ghost);
  }, null, 30000);
  const button = page.locator(selector('enter-vr'));
  await waitFor(page, 'the enter-vr button to be shown and enabled',
                (s) => { const b = document.querySelector(s); return b && !b.hidden && !b.disabled; }, selector('enter-vr'), 10000);
  await button.click();
  const views = await waitFor(page, 'window.telear.xrViews of an XR frame', () => {
    const v = window.telear.xrViews;
    return Array.isArray(v) && v.length === 2 ? v : null;
  }, null, 20000);
  const cameras = await page.evaluate(() => window.telear.cameras);

  assert.deepEqual(views.map((v) => v.eye).sort(), ['left', 'right'], `the XR views should be a left and a right eye, got ${views.map((v) => v.eye)}`);
  for (const view of views) {
    const eye = cameras.eyes.find((e) => e.name === view.eye);
    assert.ok(eye, `the cameras message has no '${view.eye}' eye`);
    for (const what of ['projection', 'view']) {
      assert.equal(view[what].length, 16, `${view.eye} ${what} should have 16 numbers`);
      view[what].forEach((v, i) => assert.ok(Math.abs(v - eye[what][i]) <= kTolerance * Math.max(1, Math.abs(eye[what][i])),
        `the ${view.eye} XR view's ${what}[${i}] = ${v}, the ${view.eye} camera's is ${eye[what][i]}`));
    }
    assert.ok(view.viewport[2] > 0 && view.viewport[3] > 0, `${view.eye} viewport ${view.viewport} is empty`);
  }
  const [left, right] = ['left', 'right'].map((e) => views.find((v) => v.eye === e));
  assert.notDeepEqual(left.view, right.view, "the two eyes' views should differ by the rig's baseline");
  assert.notDeepEqual(left.viewport, right.viewport, 'each eye should draw into its own viewport');
  // Still drawing: a second XR frame records the views again.
  await page.evaluate(() => { window.telear.xrViews = null; });
  await waitFor(page, 'another XR frame', () => Array.isArray(window.telear.xrViews), null, 10000);
  log(`XR views: ${views.map((v) => `${v.eye} viewport [${v.viewport.join(', ')}]`).join('; ')} use the cameras' matrices`);
});
