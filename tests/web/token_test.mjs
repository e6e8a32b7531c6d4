// The bearer token: a wrong one is refused (the page says `refused: wrong token`, no state
// arrives and a command is answered with an error); the right one connects and the video
// plays (the state's fps > 0, frames drawn in the page).

import assert from 'node:assert/strict';
import {connect, runTest, selector, text, typeCommand, waitFor} from './harness.mjs';

await runTest('web_token_test', async ({server, open, log}) => {
  const page = await open();
  assert.ok((await text(page, 'connection')).startsWith('disconnected'),
            `before any connect the connection text should begin with 'disconnected', got '${await text(page, 'connection')}'`);
  for (const name of ['token', 'connect', 'status', 'fps', 'eye-left', 'eye-right', 'estop', 'command', 'enter-vr']) {
    assert.equal(await page.locator(selector(name)).count(), 1, `the page should have one [data-telear="${name}"]`);
  }
  assert.equal(await page.locator(selector('token')).getAttribute('type'), 'password', 'the token field should be a password input');

  // A wrong token.
  await page.locator(selector('token')).fill(`${server.token}-wrong`);
  await page.locator(selector('connect')).click();
  await waitFor(page, "'refused: wrong token'", (s) => document.querySelector(s)?.textContent.startsWith('refused: wrong token'),
                selector('connection'), 30000);
  assert.ok(!page.url().includes(server.token), 'the token must never be put into the URL');
  const result = await typeCommand(page, 'real jog joint 1 +5deg');
  assert.equal(result.ok, false, `a command without a session should fail, got ${JSON.stringify(result)}`);
  await page.waitForTimeout(1000);
  const refused = await page.evaluate(() => ({state: window.telear.state, connection: window.telear.connection}));
  assert.equal(refused.state, null, `no state should arrive on a refused connection, got one with real_q_deg ${JSON.stringify(refused.state?.real_q_deg)}`);
  assert.ok(refused.connection.startsWith('refused: wrong token'), `still refused after a second, got '${refused.connection}'`);
  log(`wrong token refused; '${result.line}' answered: ${result.message}`);

  // The right token.
  await connect(page, server.token);
  const fps = await waitFor(page, 'the fps text to show a rate > 0', (s) => {
    const v = parseFloat(document.querySelector(s)?.textContent ?? '');
    return v > 0 ? v : null;
  }, selector('fps'), 30000);
  const shown0 = await page.evaluate(() => window.telear.framesShown);
  await waitFor(page, 'framesShown to grow by 3', (n) => window.telear.framesShown >= n + 3, shown0, 20000);
  const s = await page.evaluate(() => window.telear.state);
  assert.ok(s.robot_connected && s.vision_connected, `connected state should have robot and video, got ${JSON.stringify({r: s.robot_connected, v: s.vision_connected})}`);
  // The text follows the state at the next animation frame: poll until they agree.
  await waitFor(page, "the fps text to be the state's fps ('29.8 fps')",
                (sel) => document.querySelector(sel)?.textContent === `${window.telear.state.fps.toFixed(1)} fps`, selector('fps'), 5000,
                (sel) => ({text: document.querySelector(sel)?.textContent, fps: window.telear.state.fps}));
  // The page reports each frame it drew (`shown`); the server's capture -> shown statistics
  // (the state's shown_ms, where the server sends them) then fill.
  if (s.shown_ms !== undefined) {
    const p50 = await waitFor(page, "the server's capture -> shown statistics to have samples",
                              () => (window.telear.state.shown_ms?.samples > 0 ? window.telear.state.shown_ms.p50 : null), null, 10000,
                              () => window.telear.state.shown_ms);
    log(`the server's capture -> shown p50: ${Number(p50).toFixed(0)} ms`);
  }
  log(`connected: ${fps} fps, ${await page.evaluate(() => window.telear.framesShown)} frames drawn`);
});
