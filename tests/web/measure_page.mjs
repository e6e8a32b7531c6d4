// The browser operator's video against the native console's, in the same run (docs/web.md,
// "Measured"): one robot server and one vision server (the synthetic source at 30 fps with its
// frame code, at the asked size), then
//   1. the page in Debian's Chromium through `telear web` (headless, WebGL through SwiftShader):
//      the frames it drew per second and capture -> shown (the page's `shown` reports, the
//      state's shown_ms: the last 2 s);
//   2. `telear console --headless` on the same servers: its last line's frames shown and
//      capture -> shown (read back from the frame code it drew, the last 2 s).
// Not a test (nothing is asserted): a measurement, printed as one JSON object.
//
//   node tests/web/measure_page.mjs [--telear build/telear] [--seconds 10] [--resolution 640x480]
//
// The page is bundled from web/ first, as the tests do (or $TELEAR_WEB_ROOT is served);
// $TELEAR_CHROMIUM_ARGS adds Chromium switches (harness.mjs), e.g. --disable-gpu-compositing.

import {spawn} from 'node:child_process';
import {randomBytes} from 'node:crypto';
import {mkdtemp, readFile, rm, writeFile} from 'node:fs/promises';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';

import {bundlePage, connect, launchBrowser, openPage, sourceRoot} from './harness.mjs';

const options = {telear: path.join(sourceRoot, 'build', 'telear'), seconds: 10, resolution: '640x480'};
for (let i = 2; i < process.argv.length; i += 2) {
  const key = process.argv[i].replace(/^--/, '');
  if (!(key in options) || i + 1 >= process.argv.length) {
    console.error(`measure_page: unknown or incomplete option '${process.argv[i]}' (--telear, --seconds, --resolution)`);
    process.exit(2);
  }
  options[key] = key === 'seconds' ? Number(process.argv[i + 1]) : process.argv[i + 1];
}

const children = [];
// User + system CPU seconds of a process so far (/proc/PID/stat, clock ticks of 1/100 s).
async function cpuSeconds(pid) {
  const fields = (await readFile(`/proc/${pid}/stat`, 'utf8')).split(') ')[1].split(' ');
  return (Number(fields[11]) + Number(fields[12])) / 100;
}
// Starts `telear ARGS` and resolves with the first line of its output matching `pattern`.
function start(args, pattern, env = process.env) {
  const child = spawn(options.telear, args, {cwd: sourceRoot, env, stdio: ['ignore', 'pipe', 'pipe']});
  children.push(child);
  return new Promise((resolve, reject) => {
    for (const stream of [child.stdout, child.stderr]) {
      readline.createInterface({input: stream}).on('line', (line) => {
        const match = pattern.exec(line);
        if (match) resolve(match);
      });
    }
    child.on('exit', (code) => reject(new Error(`telear ${args[0]} exited (${code}) before printing ${pattern}`)));
  });
}

function run(args) {
  return new Promise((resolve, reject) => {
    const child = spawn(options.telear, args, {cwd: sourceRoot, stdio: ['ignore', 'pipe', 'pipe']});
    let output = '';
    child.stdout.on('data', (d) => { output += d; });
    child.stderr.on('data', (d) => { output += d; });
    child.on('exit', (code) => (code === 0 ? resolve(output) : reject(new Error(`telear ${args[0]} exited ${code}:\n${output}`))));
  });
}

const scratch = await mkdtemp(path.join(os.tmpdir(), 'telear-measure-page-'));
const tokenFile = path.join(scratch, 'token');
const token = randomBytes(16).toString('hex');
await writeFile(tokenFile, `${token}\n`);
const calibration = path.join(sourceRoot, 'data', 'cameras', 'puma560_stereo.yaml');
let browser = null;
try {
  const robot = await start(['robot-server', '--listen', '127.0.0.1:0', '--token-file', tokenFile],
                           /robot server listening on (\S+)/);
  const vision = await start(['vision-server', '--listen', '127.0.0.1:0', '--source', 'synthetic', '--frame-code',
                              '--fps', '30', '--resolution', options.resolution, '--token-file', tokenFile],
                             /vision server listening on (\S+)/);
  const servers = ['--robot', robot[1], '--vision', vision[1], '--token-file', tokenFile,
                   '--calibration', calibration, '--resolution', options.resolution];

  // 1. The page.
  const pageRoot = process.env.TELEAR_WEB_ROOT || await bundlePage(scratch);
  const web = await start(['web', '--listen', '127.0.0.1:0', ...servers], /^listening on (\S+)/,
                          {...process.env, TELEAR_WEB_ROOT: pageRoot});
  const webProcess = children[children.length - 1];
  browser = await launchBrowser();
  const page = await openPage(browser, web[1]);
  await connect(page, token);
  await page.waitForTimeout(3000);  // warm-up: the first frames, the clock offset
  const before = await page.evaluate(() => window.telear.framesShown);
  const cpuBefore = await cpuSeconds(webProcess.pid);
  await page.waitForTimeout(options.seconds * 1000);
  const cpuAfter = await cpuSeconds(webProcess.pid);
  const after = await page.evaluate(() => ({frames: window.telear.framesShown, state: window.telear.state}));
  await browser.close();
  browser = null;
  const pageFigures = {
    frames_drawn_per_s: (after.frames - before) / options.seconds,
    video_fps_decoded_by_telear_web: after.state.fps,
    capture_to_shown_ms: after.state.shown_ms,
    // telear web's own cost of the stream (forwarding the JPEG pairs, its session's decode to
    // planes): CPU ms per video frame, and the video's bytes per second on the socket.
    telear_web_cpu_ms_per_frame: (cpuAfter - cpuBefore) * 1000 / (after.state.fps * options.seconds),
    video_megabytes_per_s: after.state.video_bytes_per_s / 1e6,
  };

  // 2. The native console on the same servers.
  const frames = Math.round((options.seconds + 3) * 60);  // its frames are paced at 60 per second
  const consoleOutput = await run(['console', '--headless', ...servers, '--frames', String(frames),
                                   '--size', '1280x800']);
  const line = consoleOutput.split('\n').find((l) => l.includes(' fps decoded, '));
  const figures = /video ([\d.]+) fps decoded, (\d+) frames shown with their code in 2 s(?:, capture -> shown p50 ([\d.]+) ms, p99 ([\d.]+) ms)?/.exec(line ?? '');
  const consoleFigures = figures ? {
    frames_shown_per_s: Number(figures[2]) / 2,
    video_fps_decoded: Number(figures[1]),
    capture_to_shown_ms: {p50: figures[3] ? Number(figures[3]) : null, p99: figures[4] ? Number(figures[4]) : null},
  } : {unreadable: line ?? consoleOutput.slice(-2000)};
  console.log(JSON.stringify({resolution: options.resolution, seconds: options.seconds, page: pageFigures,
                              console: consoleFigures}, null, 2));
} finally {
  if (browser) await browser.close();
  for (const child of children) child.kill('SIGTERM');
  await rm(scratch, {recursive: true, force: true});
}
