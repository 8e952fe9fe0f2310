// The viewer in a real browser: start `floe serve` on free ports (its data in a
// temporary directory), open the page in headless Chromium, create a dam break, watch
// frames arrive and particles drawn, pause and check frames stop, restart the server
// and watch the viewer find the scene again. Leaves a screenshot in target/viewer.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';
import { fileURLToPath } from 'node:url';
import path from 'node:path';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const floe = process.env.FLOE_BIN ?? path.join(root, 'target/debug/floe');
const browserPath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const dataDir = mkdtempSync(path.join(tmpdir(), 'floe-viewer-'));

/** Starts the server (HTTP on `http`) and resolves with the viewer's URL it prints. */
function startServer(http = '127.0.0.1:0') {
  const args = ['serve', '--http', http, '--grpc', '127.0.0.1:0', '--scene', 'none', '--data-dir', dataDir];
  const child = spawn(floe, args, {
    cwd: root, stdio: ['ignore', 'pipe', 'inherit'],
  });
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

/** Reads a number after `label` in the stats overlay. */
async function stat(page, label) {
  const text = await page.textContent('#stats');
  const m = text.match(new RegExp(`${label}\\s+(\\d+)`));
  return m ? Number(m[1]) : NaN;
}

test('the viewer streams, draws and pauses a dam break', { timeout: 120_000 }, async () => {
  const { child, url } = await startServer();
  let server = child;
  const browser = await chromium.launch({
    executablePath: browserPath,
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-quic',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(url);
    await page.selectOption('#preset', 'dam_break');
    // A small dam break keeps software rendering quick: create it over REST as the page does.
    const scene = await page.evaluate(async () => {
      const r = await fetch('/api/v1/scenes', {
        method: 'POST', headers: { 'content-type': 'application/json' },
        body: JSON.stringify({ preset: 'dam_break', overrides: ['particle_spacing=0.03125'] }),
      });
      return r.json();
    });
    assert.equal(scene.particles, 4096);
    await page.reload();
    await page.click('#play');
    await page.waitForFunction(() => /frames\s+(\d+)/.exec(document.querySelector('#stats').textContent)?.[1] >= 10,
      null, { timeout: 60_000 });
    assert.equal(await stat(page, 'particles'), 4096);

    // Particles were drawn: pixels that are not the background colour.
    const drawn = await page.evaluate(() => {
      const c = document.querySelector('#view');
      const gl = c.getContext('webgl2');
      const px = new Uint8Array(c.width * c.height * 4);
      gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
      let n = 0;
      for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - 16) + Math.abs(px[i + 1] - 20) + Math.abs(px[i + 2] - 24) > 30) n++;
      return n;
    });
    assert.ok(drawn > 500, `only ${drawn} non-background pixels`);

    // Pause: frames stop arriving.
    await page.click('#pause');
    await page.waitForTimeout(1500);
    const before = await stat(page, 'frames');
    await page.waitForTimeout(2000);
    const after = await stat(page, 'frames');
    assert.equal(after, before, `frames kept arriving after pause (${before} -> ${after})`);
    await page.screenshot({ path: path.join(root, 'target/viewer.png') });

    // Reset: the scene goes back to t = 0 (the overlay polls the status every second).
    await page.click('#reset');
    await page.waitForFunction(() => /sim time\s+0\.000 s/.test(document.querySelector('#stats').textContent),
      null, { timeout: 10_000 });
    // A slider changes a live setting: the server reports the new gravity.
    await page.evaluate(() => {
      const g = document.querySelector('#gravity');
      g.value = '-1.6';
      g.dispatchEvent(new Event('change'));
    });
    await page.waitForFunction(async () => {
      const s = await (await fetch('/api/v1/scenes/1')).json();
      return Math.abs(s.scene.gravity[1] + 1.6) < 1e-6;
    }, null, { timeout: 10_000 });

    // The server restarts under the page (same address, same data): scene 1 comes
    // back from its checkpoint with its live settings, and the viewer finds it again
    // by itself and streams it once it runs.
    server.kill('SIGTERM');
    await server.exited;
    const framesBefore = await stat(page, 'frames');
    server = (await startServer(new URL(url).host)).child;
    const restored = await (await fetch(new URL('/api/v1/scenes/1', url))).json();
    assert.equal(restored.particles, 4096);
    assert.ok(Math.abs(restored.scene.gravity[1] + 1.6) < 1e-6, `gravity ${restored.scene.gravity}`);
    const run = await fetch(new URL('/api/v1/scenes/1/run', url), {
      method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ real_time_factor: 1 }),
    });
    assert.equal(run.status, 200);
    await page.waitForFunction((n) => /frames\s+(\d+)/.exec(document.querySelector('#stats').textContent)?.[1] > n,
      framesBefore, { timeout: 30_000 });
    const reconnected = await stat(page, 'frames');
    await page.waitForFunction((n) => /frames\s+(\d+)/.exec(document.querySelector('#stats').textContent)?.[1] >= n + 5,
      reconnected, { timeout: 30_000 });
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
    rmSync(dataDir, { recursive: true, force: true });
  }
});
