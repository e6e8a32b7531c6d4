// Two operators (two browser contexts: two sessions on the same servers): the first takes
// control; the second's take-control is refused because the first holds the lease, yet it
// still sees the video and the reported arm -- which moves when the first one's plan runs,
// whatever the second one's ghost does.

import assert from 'node:assert/strict';
import {connect, runTest, typeCommand, waitFor} from './harness.mjs';

async function ok(page, line) {
  const r = await typeCommand(page, line);
  assert.equal(r.ok, true, `'${line}' should succeed, got: ${r.message}`);
}

await runTest('web_two_browsers_test', async ({server, open, log}) => {
  const first = await open();
  const second = await open();
  await Promise.all([connect(first, server.token), connect(second, server.token)]);
  for (const page of [first, second]) {
    await waitFor(page, 'a state with the reported arm', () => Array.isArray(window.telear.state?.real_q_deg), null, 30000);
  }

  await ok(first, 'take-control');
  await waitFor(first, 'the first tab in control', () => window.telear.state?.in_control === true, null, 10000);
  const refused = await typeCommand(second, 'take-control');
  assert.equal(refused.ok, false, `the second take-control should be refused while the first holds the lease, got ${JSON.stringify(refused)}`);
  assert.match(refused.message, /lease|control|held|holds/i, `the refusal should say the lease is held, got '${refused.message}'`);
  const secondState = await second.evaluate(() => window.telear.state);
  assert.equal(secondState.in_control, false, 'the second tab should not be in control');
  log(`second take-control refused: ${refused.message}`);

  // The second still gets video.
  const shown = await second.evaluate(() => window.telear.framesShown);
  await waitFor(second, 'video frames in the second tab', (n) => window.telear.framesShown >= n + 3, shown, 20000);

  // The second moves only its ghost; the first runs a plan; the second sees the real arm move.
  await ok(second, 'ghost reset');
  await ok(second, 'ghost joint 1 +20deg');
  const before = await second.evaluate(() => window.telear.state.real_q_deg);
  await ok(first, 'ghost reset');
  await ok(first, 'plan add 0.5 a');
  await ok(first, 'ghost joint 3 -8deg');
  await ok(first, 'plan add 1.0 b');
  await ok(first, 'validate');
  await ok(first, 'execute');
  const after = await waitFor(second, "the second tab to see joint 3 move by the first's plan (-8 deg)",
                              (q3) => { const q = window.telear.state.real_q_deg; return Math.abs(q[2] - q3) <= 0.5 ? q : null; },
                              before[2] - 8, 30000);
  assert.ok(Math.abs(after[0] - before[0]) <= 0.5,
            `joint 1 should not move (the second tab's ghost is not the robot): ${before[0]} -> ${after[0]}`);
  const ghost = await second.evaluate(() => window.telear.state.ghost_q_deg);
  assert.ok(Math.abs(ghost[0] - (before[0] + 20)) <= 0.01, `the second tab's ghost joint 1 should stay at +20 deg: ${ghost[0]}`);
  log(`second tab saw joint 3 go ${before[2].toFixed(2)} -> ${after[2].toFixed(2)} deg`);
});
