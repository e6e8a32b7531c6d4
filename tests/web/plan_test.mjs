// A plan rehearsed in the page and executed on the (simulated) robot through the command
// line, as in the console: take control, two waypoints 10 degrees apart on joint 2,
// validate, execute; the robot ends 10 degrees further, and the executed plan is the one
// that was validated (same hash). Then the E-STOP button stops a second execution: the
// state reports the e-stop within 500 ms of the click (measured in the page).

import assert from 'node:assert/strict';
import {connect, runTest, selector, state, typeCommand, waitFor} from './harness.mjs';

async function ok(page, line) {
  const r = await typeCommand(page, line);
  assert.equal(r.ok, true, `'${line}' should succeed, got: ${r.message}`);
  return r;
}

const describe = () => {
  const s = window.telear.state;
  return s && {plan: {...s.plan, waypoints: s.plan.waypoints.length}, real_q_deg: s.real_q_deg, mode: s.mode,
               estop: s.estop, in_control: s.in_control, message: s.message};
};

await runTest('web_plan_test', async ({server, open, log}) => {
  const page = await open();
  await connect(page, server.token);
  await waitFor(page, 'a state with the reported arm', () => Array.isArray(window.telear.state?.real_q_deg), null, 30000);

  await ok(page, 'take-control');
  await waitFor(page, 'in_control', () => window.telear.state?.in_control === true, null, 10000, describe);
  await ok(page, 'ghost reset');
  await waitFor(page, 'the ghost at the reported arm', () => {
    const s = window.telear.state;
    return s.ghost_q_deg.every((g, i) => Math.abs(g - s.real_q_deg[i]) < 0.01);
  }, null, 10000, describe);
  const start = (await state(page)).real_q_deg;
  await ok(page, 'plan add 1.0 start');
  await ok(page, 'ghost joint 2 +10deg');
  await ok(page, 'plan add 1.0 end');
  await ok(page, 'validate');
  await ok(page, 'execute');
  log(`executing from joint 2 = ${start[1].toFixed(3)} deg`);
  const done = await waitFor(page, "the plan's execution to complete", () => {
    const s = window.telear.state;
    return s && !s.plan.executing && s.plan.last_result === 'completed' ? s : null;
  }, null, 30000, describe);
  assert.equal(done.plan.waypoints.length, 2, 'the plan should hold the two waypoints added');
  assert.ok(done.plan.hash.length > 0, 'the plan should have a hash');
  assert.equal(done.plan.executed_hash, done.plan.hash, "the executed plan's hash should be the plan's");
  // The robot's final position is reached once the execution completes; the state may lag a
  // few updates behind the session's own result.
  const arrived = await waitFor(page, 'joint 2 at start + 10 deg (0.5 deg)', (target) => {
    const q = window.telear.state.real_q_deg;
    return Math.abs(q[1] - target) <= 0.5 ? q : null;
  }, start[1] + 10, 10000, describe);
  for (const i of [0, 2, 3, 4, 5]) {
    assert.ok(Math.abs(arrived[i] - start[i]) <= 0.5, `joint ${i + 1} should not move: ${start[i]} -> ${arrived[i]}`);
  }
  log(`completed: joint 2 = ${arrived[1].toFixed(3)} deg, hash ${done.plan.hash.slice(0, 12)} executed`);

  // E-STOP during a second execution.
  await ok(page, 'plan clear');
  await ok(page, 'plan add 1.0 back-start');
  await ok(page, 'ghost joint 2 -10deg');
  await ok(page, 'plan add 2.0 back-end');
  await ok(page, 'validate');
  await ok(page, 'execute');
  await waitFor(page, 'the second execution to start', () => window.telear.state?.plan.executing === true, null, 10000, describe);
  const estopMs = await page.evaluate((estopSelector) => new Promise((resolve) => {
    let t0 = 0;
    const off = window.telear.onState((s) => {
      if (t0 > 0 && (s.estop === true || s.mode === 'estop')) {
        off();
        resolve(performance.now() - t0);
      }
    });
    setTimeout(() => { off(); resolve(null); }, 5000);
    t0 = performance.now();
    document.querySelector(estopSelector).click();
  }), selector('estop'));
  assert.notEqual(estopMs, null, 'no state reported the e-stop within 5 s of the click');
  assert.ok(estopMs <= 500, `the e-stop was reported ${estopMs.toFixed(0)} ms after the click, more than 500 ms`);
  const stopped = await waitFor(page, 'the execution to end after the e-stop', () => {
    const s = window.telear.state;
    return !s.plan.executing ? s : null;
  }, null, 10000, describe);
  assert.notEqual(stopped.plan.last_result, 'completed', 'an e-stopped execution should not report completed');
  log(`E-STOP reported ${estopMs.toFixed(0)} ms after the click; last result: ${stopped.plan.last_result}`);
});
