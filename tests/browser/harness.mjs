// What the browser tests and measurements share: starting `floe serve` on free ports with this
// checkout's viewer, headless Chromium on software GL, and reading the page.

import { spawn } from 'node:child_process';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import net from 'node:net';
import { chromium } from 'playwright-core';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

export const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

/** The server binary: FLOE_BIN, else the debug build (`release`: the release build). */
export function floeBinary(release = false) {
  return process.env.FLOE_BIN ?? path.join(root, release ? 'target/release/floe' : 'target/debug/floe');
}

/** A TCP port free on the loopback interface now. */
export function freePort() {
  return new Promise((resolve, reject) => {
    const s = net.createServer();
    s.on('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

/** A new empty directory for a server's data (its database and checkpoints). */
export function tempDataDir() {
  return mkdtempSync(path.join(tmpdir(), 'floe-browser-'));
}

/**
 * Starts the server (`binary`, by default {@link floeBinary}; HTTP on `http`, gRPC on `grpc`, the
 * start-up scene `scene` (default none),
 * this checkout's web/ or FLOE_WEB, its data in `dataDir`, by default a new temporary directory;
 * `presetSize` and `backend`, where given, as `--preset-size` and `--backend`, over the
 * environment's FLOE_PRESET_SIZE and FLOE_BACKEND)
 * and resolves with `{child, url}` once it prints the viewer's URL; `child.exited` resolves when
 * it ends.
 */
export function startServer({
  http = '127.0.0.1:0', grpc = '127.0.0.1:0', release = false, quiet = false, dataDir = tempDataDir(), scene = 'none',
  binary = floeBinary(release), presetSize = null, backend = null,
} = {}) {
  const web = process.env.FLOE_WEB ?? path.join(root, 'web');
  const options = [['--preset-size', presetSize], ['--backend', backend]].filter(([, v]) => v).flat();
  const child = spawn(binary,
    ['serve', '--http', http, '--grpc', grpc, '--scene', scene, '--web', web, '--data-dir', dataDir, ...options],
    { cwd: root, stdio: ['ignore', 'pipe', quiet ? 'ignore' : 'inherit'] });
  return new Promise((resolve, reject) => {
    let out = '';
    child.on('error', reject);
    child.on('exit', (code) => reject(new Error(`floe serve exited with ${code}`)));
    child.exited = new Promise((done) => child.on('exit', done));
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/Floe viewer: (http:\/\/\S+)/);
      if (m) resolve({ child, url: m[1] });
    });
  });
}

/** Headless Chromium (Debian's, or CHROMIUM) drawing WebGL with SwiftShader on the CPU. */
export function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-quic',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
}

/**
 * Collects what a user would see go wrong on a page: uncaught errors, console errors, failed
 * requests and HTTP errors (a missing favicon included).
 * @returns {string[]} filled as the page runs
 */
export function watchProblems(page) {
  const problems = [];
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()} (${r.failure()?.errorText})`));
  page.on('response', (r) => { if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`); });
  return problems;
}

/** Creates a scene from a preset over REST; resolves with the server's JSON. */
export async function createScene(url, preset, overrides = []) {
  const r = await fetch(new URL('/api/v1/scenes', url), {
    method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ preset, overrides }),
  });
  if (r.status !== 201) throw new Error(`creating ${preset}: ${r.status} ${await r.text()}`);
  return r.json();
}

/** Reads a number after `label` in the stats overlay (NaN when absent). */
export async function stat(page, label) {
  const text = await page.textContent('#stats');
  const m = text.match(new RegExp(`${label}\\s+([\\d.]+)`));
  return m ? Number(m[1]) : NaN;
}

/** Waits until the overlay's number after `label` is at least `least`. */
export function statAtLeast(page, label, least, timeout = 60_000) {
  return page.waitForFunction(([l, n]) => Number(new RegExp(`${l}\\s+([\\d.]+)`).exec(document.querySelector('#stats').textContent)?.[1]) >= n,
    [label, least], { timeout });
}

/**
 * The canvas's pixels as RGBA bytes (rows bottom first), read in the page and handed to the test
 * for counting.
 * @returns {Promise<Uint8Array>}
 */
export async function canvasPixels(page) {
  const b64 = await page.evaluate(() => {
    const c = document.querySelector('#view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let s = '';
    for (let i = 0; i < px.length; i += 0x8000) s += String.fromCharCode(...px.subarray(i, i + 0x8000));
    return btoa(s);
  });
  return new Uint8Array(Buffer.from(b64, 'base64'));
}

/**
 * What the canvas shows, measured in the page (in CSS pixels, y down): `fluid` pixels (blue or
 * teal: blue over red by 20 or more, as water and particles are drawn; background, floor and
 * walls are grey), their bounding `box`, `gaps` (grey pixels between the first and last fluid
 * pixel of a row, where something behind shows through the fluid), `scene`: the bounding box
 * of everything not background (floor and walls included), and the fluid's mean colour.
 */
export function canvasSummary(page) {
  return page.evaluate(() => {
    const c = document.querySelector('#view');
    const gl = c.getContext('webgl2');
    const w = c.width, h = c.height, px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const isFluid = (i) => px[i + 2] - px[i] >= 20;
    const isBackground = (i) => Math.abs(px[i] - 16) + Math.abs(px[i + 1] - 20) + Math.abs(px[i + 2] - 24) <= 12;
    const box = () => ({ x0: Infinity, x1: -Infinity, y0: Infinity, y1: -Infinity });
    const grow = (b, x, y) => { b.x0 = Math.min(b.x0, x); b.x1 = Math.max(b.x1, x); b.y0 = Math.min(b.y0, y); b.y1 = Math.max(b.y1, y); };
    const fluidBox = box(), sceneBox = box(), mean = [0, 0, 0];
    let fluid = 0, gaps = 0;
    for (let y = 0; y < h; y++) {
      let first = -1, last = -1, inRow = 0;
      for (let x = 0; x < w; x++) {
        const i = 4 * (y * w + x);
        if (!isBackground(i)) grow(sceneBox, x, y);
        if (!isFluid(i)) continue;
        inRow++;
        for (let k = 0; k < 3; k++) mean[k] += px[i + k];
        if (first < 0) first = x;
        last = x;
      }
      if (inRow === 0) continue;
      fluid += inRow;
      gaps += last - first + 1 - inRow;
      grow(fluidBox, first, y);
      grow(fluidBox, last, y);
    }
    // Rows read bottom first: flip y, and scale to CSS pixels (the canvas may be drawn at a lower
    // resolution while the picture moves, web/js/resolution.js).
    const k = c.clientWidth / w;
    const css = (b) => (b.x1 < 0 ? null : { x0: b.x0 * k, x1: b.x1 * k, y0: (h - 1 - b.y1) * k, y1: (h - 1 - b.y0) * k });
    return { width: w * k, height: h * k, fluid: fluid * k * k, gaps: gaps * k * k, box: css(fluidBox), scene: css(sceneBox),
      colour: mean.map((m) => m / Math.max(fluid, 1)) };
  });
}

/**
 * How many pixels the scene's other sets (grids, probes, flakes) colour: the canvas in the spheres
 * view with them shown against with them hidden (`#other-sets`), which is left shown again.
 * @returns {Promise<number>} pixels whose RGB differ by more than 30 in all
 */
export async function otherSetsPixels(page) {
  await page.selectOption('#view-mode', 'spheres');
  await page.waitForTimeout(1500);
  const shown = await canvasPixels(page);
  await page.click('#other-sets');
  await page.waitForTimeout(1500);
  const hidden = await canvasPixels(page);
  let differ = 0;
  for (let i = 0; i < shown.length; i += 4) {
    if (Math.abs(shown[i] - hidden[i]) + Math.abs(shown[i + 1] - hidden[i + 1]) + Math.abs(shown[i + 2] - hidden[i + 2]) > 30) differ += 1;
  }
  await page.click('#other-sets');
  await page.waitForTimeout(500);
  return differ;
}
