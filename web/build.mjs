// Bundles the operator page for `telear web`: node web/build.mjs OUTDIR
//
// OUTDIR gets app.js (one minified ES module: the page's src/ and three.js, with
// app.js.map), index.html and app.css; `telear web` serves that folder (docs/web.md). Offline
// and a few seconds: esbuild's JS API from web/node_modules (npm install --prefix web
// --ignore-scripts: esbuild's binary is the @esbuild/<platform> optional dependency, no
// install script needed).

import {copyFile, mkdir} from 'node:fs/promises';
import path from 'node:path';
import {fileURLToPath} from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));

async function main(argv) {
  if (argv.length !== 1 || argv[0].startsWith('-')) {
    console.error('usage: node web/build.mjs OUTDIR');
    return 2;
  }
  const outdir = path.resolve(argv[0]);
  let esbuild;
  try {
    esbuild = await import('esbuild');
  } catch (e) {
    console.error(`web/build.mjs: esbuild is not installed (${e.message}); ` +
                  'run: npm ci --prefix web --ignore-scripts --no-audit --no-fund');
    return 1;
  }
  await mkdir(outdir, {recursive: true});
  try {
    await esbuild.build({
      entryPoints: [path.join(here, 'src', 'main.js')],
      outfile: path.join(outdir, 'app.js'),
      absWorkingDir: here,
      nodePaths: [path.join(here, 'node_modules')],
      bundle: true,
      format: 'esm',
      // WebGL2, ES modules, top-level await and Uint8Array.fromBase64 feature tests: any
      // browser with WebXR is newer than this.
      target: ['es2022'],
      minify: true,
      sourcemap: true,
      legalComments: 'eof',
      logLevel: 'warning',
    });
  } catch {
    // esbuild has printed the errors with their file and line.
    return 1;
  }
  await Promise.all(['index.html', 'app.css'].map((f) => copyFile(path.join(here, f), path.join(outdir, f))));
  return 0;
}

process.exitCode = await main(process.argv.slice(2));
