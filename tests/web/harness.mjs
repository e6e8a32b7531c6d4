// What every browser test of the operator page shares (docs/web.md): the real `telear web`
// with its embedded simulated robot and cameras, Debian's Chromium driven by playwright-core
// (headless, WebGL through SwiftShader), and clear failures: each test is one CTest entry
// that exits non-zero with the reason, the server's stderr and the page's console.
//
//   node tests/web/X_test.mjs --telear build/telear [--resolution WxH] [--web-root DIR] [--keep DIR]
//
// (--keep DIR: the images a test compares are written there, and its scratch folder kept.)
// The page is bundled from web/ into a scratch folder first (web/build.mjs, well under a
// second) and served from there (TELEAR_WEB_ROOT), so a test always checks the sources it
// sits beside; --web-root DIR (or $TELEAR_WEB_ROOT) serves a bundle already built instead.
// $TELEAR_CHROMIUM (the browser) and $TELEAR_CHROMIUM_ARGS (more switches, space-separated).

import assert from 'node:assert/strict';
import {spawn, spawnSync} from 'node:child_process';
import {existsSync} from 'node:fs';
import {mkdtemp, rm} from 'node:fs/promises';
import {createRequire} from 'node:module';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';
import {fileURLToPath} from 'node:url';

export const sourceRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
export const webRoot = path.join(sourceRoot, 'web');
const kChromium = process.env.TELEAR_CHROMIUM || '/usr/bin/chromium';
const kServerStartS = 60;
const kStopGraceMs = 5000;

export function parseArgs(argv = process.argv.slice(2)) {
  const args = {telear: process.env.TELEAR || path.join(sourceRoot, 'build', 'telear'), resolution: null,
                webRoot: process.env.TELEAR_WEB_ROOT || null, keep: process.env.TELEAR_WEB_TEST_KEEP || null};
  for (let i = 0; i < argv.length; ++i) {
    const value = () => {
      if (i + 1 >= argv.length) throw new Error(`${argv[i]} needs a value`);
      return argv[++i];
    };
    switch (argv[i]) {
      case '--telear': args.telear = value(); break;
      case '--resolution': args.resolution = value(); break;
      case '--web-root': args.webRoot = value(); break;
      case '--keep': args.keep = value(); break;  // a folder for the test's images
      default: throw new Error(`unknown argument '${argv[i]}' (expected --telear PATH, --resolution WxH, --web-root DIR, --keep DIR)`);
    }
  }
  return args;
}

// [SECTION] the server

export async function bundlePage(scratch) {
  const out = path.join(scratch, 'web');
  const build = spawnSync(process.execPath, [path.join(webRoot, 'build.mjs'), out], {encoding: 'utf8'});
  if (build.status !== 0) {
    throw new Error(`web/build.mjs failed (exit ${build.status}):\n${build.stderr}${build.stdout}`);
  }
  return out;
}

// Starts `telear web --listen 127.0.0.1:0` and reads its two first lines: the URL and the token.
export async function startServer(args, scratch, extra = []) {
  if (!existsSync(args.telear)) {
    throw new Error(`no telear program at '${args.telear}': build it (cmake --build build) or pass --telear PATH`);
  }
  const pageRoot = args.webRoot || await bundlePage(scratch);
  const argv = ['web', '--listen', '127.0.0.1:0'];
  if (args.resolution) argv.push('--resolution', args.resolution);
  argv.push(...extra);
  const child = spawn(args.telear, argv, {
    cwd: sourceRoot,
    env: {...process.env, TELEAR_WEB_ROOT: pageRoot},
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  const server = {child, stderr: '', url: null, token: null, exited: null};
  child.stderr.setEncoding('utf8');
  child.stderr.on('data', (chunk) => {
    server.stderr += chunk;
    if (server.stderr.length > 200000) server.stderr = server.stderr.slice(-100000);
  });
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => {
    server.exited = {code, signal};
    resolve(server.exited);
  }));
  server.whenExited = exited;
  // docs/web.md: the first line is the URL, the second the token. Other lines before them (the
  // embedded servers' logs) are tolerated with a warning, so the page's checks still run.
  const lines = readline.createInterface({input: child.stdout});
  const found = new Promise((resolve, reject) => {
    const got = [];
    let listening = null;
    let done = false;
    lines.on('line', (line) => {
      if (done) return;  // the servers' logs, read only so that the pipe never fills
      got.push(line);
      if (listening === null && /^listening on /.test(line)) {
        listening = got.length;
      } else if (listening !== null && /^token: /.test(line)) {
        if (listening !== 1 || got.length !== 2) {
          console.warn(`warning: telear web printed ${listening - 1} other line(s) before 'listening on' and ` +
                       `${got.length - listening - 1} between it and 'token:' (docs/web.md: they are the first two lines); ` +
                       `first: ${JSON.stringify(got[0])}`);
        }
        done = true;
        resolve([got[listening - 1], line]);
      }
    });
    exited.then((e) => reject(new Error(`telear web exited (${e.code ?? e.signal}) before printing its URL and token; ` +
                                        `stdout: ${JSON.stringify(got.slice(0, 10))}\nstderr:\n${server.stderr}`)));
    setTimeout(() => reject(new Error(`telear web printed ${JSON.stringify(got.slice(0, 10))} in ${kServerStartS} s, ` +
                                      `expected 'listening on http://...' and 'token: T'\nstderr:\n${server.stderr}`)),
               kServerStartS * 1000);
  });
  try {
    const [listening, token] = await found;
    const url = /^listening on (https?:\/\/\S+)$/.exec(listening);
    const t = /^token: (\S+)$/.exec(token);
    assert.ok(url, `telear web's first line should be 'listening on http://HOST:PORT', got '${listening}'`);
    assert.ok(t, `telear web's second line should be 'token: T', got '${token}'`);
    server.url = url[1].replace(/\/$/, '');
    server.token = t[1];
  } catch (e) {
    await stopServer(server);
    throw e;
  }
  return server;
}

export async function stopServer(server) {
  if (!server || server.exited) return;
  server.child.kill('SIGTERM');
  const timer = setTimeout(() => server.child.kill('SIGKILL'), kStopGraceMs);
  await server.whenExited;
  clearTimeout(timer);
}

// [SECTION] the browser

export async function launchBrowser() {
  if (!existsSync(kChromium)) {
    throw new Error(`no Chromium at ${kChromium}: the browser tests need Debian's chromium (apt-get install chromium)`);
  }
  let chromium;
  try {
    const require = createRequire(path.join(webRoot, 'package.json'));
    const module = await import(require.resolve('playwright-core'));  // CommonJS: under default
    chromium = module.chromium ?? module.default.chromium;
  } catch (e) {
    throw new Error(`playwright-core is not installed in web/node_modules (${e.message}): ` +
                    'run npm ci --prefix web --ignore-scripts --no-audit --no-fund');
  }
  return chromium.launch({
    executablePath: kChromium,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
           ...(process.env.TELEAR_CHROMIUM_ARGS ?? '').split(/\s+/).filter(Boolean)],
  });
}

// A tab on the page, its console and errors kept for the failure message.
export async function openPage(browser, url, {initScript = null} = {}) {
  const context = await browser.newContext({viewport: {width: 1400, height: 900}});
  if (initScript) await context.addInitScript(initScript);
  const page = await context.newPage();
  const log = [];
  page.on('console', (m) => {
    if (m.type() === 'error' || m.type() === 'warning') log.push(`console.${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => log.push(`page error: ${e.message}`));
  page.telearLog = log;
  await page.goto(url, {waitUntil: 'load'});
  return page;
}

export const selector = (name) => `[data-telear="${name}"]`;

export async function text(page, name) {
  return (await page.locator(selector(name)).textContent()) ?? '';
}

// Waits for fn(arg) to be truthy in the page; a timeout names what was awaited and shows
// `describe`(arg)'s view of the page at that moment.
export async function waitFor(page, what, fn, arg, timeoutMs = 20000, describe = null) {
  try {
    const handle = await page.waitForFunction(fn, arg, {timeout: timeoutMs, polling: 50});
    return await handle.jsonValue();
  } catch (e) {
    let seen = '';
    try {
      seen = describe ? JSON.stringify(await page.evaluate(describe, arg)) : await page.evaluate(() =>
        JSON.stringify({connection: window.telear?.connection, lastResult: window.telear?.lastResult}));
    } catch {}
    throw new Error(`waited ${timeoutMs / 1000} s for ${what}; the page had ${seen}\n(${e.message.split('\n')[0]})`);
  }
}

export async function connect(page, token, timeoutMs = 30000) {
  await page.locator(selector('token')).fill(token);
  await page.locator(selector('connect')).click();
  await waitFor(page, "the connection text to begin with 'connected'",
                (s) => document.querySelector(s)?.textContent.startsWith('connected'), selector('connection'), timeoutMs);
}

// Types a line into the command line, presses Enter and returns the `result` it got.
export async function typeCommand(page, line, timeoutMs = 20000) {
  const before = await page.evaluate(() => window.telear.lastResult?.id ?? 0);
  const input = page.locator(selector('command'));
  await input.fill(line);
  await input.press('Enter');
  return waitFor(page, `the result of '${line}'`,
                 ([l, b]) => { const r = window.telear.lastResult; return r && r.id > b && r.line === l ? r : null; },
                 [line, before], timeoutMs);
}

export async function state(page) {
  return page.evaluate(() => window.telear.state);
}

// [SECTION] running one test

// Runs body({args, server, browser, scratch, log}) and exits: 0 when it returns, 1 with the
// reason (and the server's stderr tail, the pages' console) when anything throws.
export async function runTest(name, body, {serverArgs = [], args: given = null} = {}) {
  const started = Date.now();
  let args;
  try {
    args = given ?? parseArgs();
  } catch (e) {
    console.error(`${name}: ${e.message}`);
    process.exit(2);
  }
  const scratch = await mkdtemp(path.join(os.tmpdir(), `telear-${name}-`));
  const pages = [];
  let server = null;
  let browser = null;
  let failure = null;
  const log = (message) => console.log(`${name} [${((Date.now() - started) / 1000).toFixed(1)} s] ${message}`);
  try {
    // Both at once (each takes seconds), but a server that started is stopped below even when
    // the browser failed, and the other way round.
    const [s, b] = await Promise.allSettled([startServer(args, scratch, serverArgs), launchBrowser()]);
    server = s.status === 'fulfilled' ? s.value : null;
    browser = b.status === 'fulfilled' ? b.value : null;
    if (s.status === 'rejected') throw s.reason;
    if (b.status === 'rejected') throw b.reason;
    log(`telear web at ${server.url}`);
    const track = async (p) => { pages.push(p); return p; };
    await body({args, server, browser, scratch, log, open: async (opts) => track(await openPage(browser, server.url, opts))});
  } catch (e) {
    failure = e;
  }
  if (failure) {
    console.error(`${name}: FAILED: ${failure.stack || failure.message}`);
    for (const [i, p] of pages.entries()) {
      if (p.telearLog.length) console.error(`--- page ${i + 1} console:\n${p.telearLog.slice(-30).join('\n')}`);
    }
    if (server) console.error(`--- telear web stderr (tail):\n${server.stderr.slice(-4000)}`);
  }
  await browser?.close().catch(() => {});
  await stopServer(server).catch(() => {});
  if (!args.keep) await rm(scratch, {recursive: true, force: true});
  console.log(`${name}: ${failure ? 'FAILED' : 'passed'} in ${((Date.now() - started) / 1000).toFixed(1)} s`);
  process.exit(failure ? 1 : 0);
}
