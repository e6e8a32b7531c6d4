// The README's picture of the browser operator (docs/images/web.png): `telear web` on the
// embedded simulated servers, the page in Debian's Chromium, a short rehearsal typed into its
// command line (the ghost moved off the real arm, two waypoints, the plan validated), then a
// screenshot of the whole page. Not a test; run it by hand when the page changes:
//
//   node tests/web/screenshot_page.mjs [--telear build/telear]      # writes docs/images/web.png

import path from 'node:path';

import {connect, runTest, sourceRoot, typeCommand, waitFor} from './harness.mjs';

const output = path.join(sourceRoot, 'docs', 'images', 'web.png');

await runTest('screenshot_page', async ({server, open, log}) => {
  const page = await open();
  await page.setViewportSize({width: 1500, height: 950});
  await connect(page, server.token);
  await waitFor(page, 'video frames', () => window.telear.framesShown >= 5, null, 30000);
  for (const line of ['take-control', 'plan add 1.0 start', 'ghost joint 2 -25deg', 'ghost joint 3 +20deg',
                      'ghost joint 5 +30deg', 'plan add 1.5 reach', 'validate']) {
    const result = await typeCommand(page, line);
    if (!result.ok) throw new Error(`'${line}' failed: ${result.message}`);
  }
  await page.waitForTimeout(1500);  // a few frames and states after the last line
  await page.screenshot({path: output});
  log(`wrote ${output}`);
});
