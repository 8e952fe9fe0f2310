// The viewer in a real browser: start `floe serve` on free ports (its data in a
// temporary directory), open the page in headless Chromium, create a dam break, watch
// frames arrive and particles drawn, pause and check frames stop, reset, change settings,
// restart the server and watch the viewer find the scene again with its settings. Leaves a
// screenshot in target/viewer.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { rmSync } from 'node:fs';
import {
  canvasSummary, createScene, launchBrowser, root, startServer, stat, statAtLeast, tempDataDir, watchProblems,
} from './harness.mjs';

const dataDir = tempDataDir();

test('the viewer streams, draws and pauses a dam break', { timeout: 120_000 }, async () => {
  const { child, url } = await startServer({ dataDir });
  let server = child;
  const browser = await launchBrowser();
  try {
    // A small dam break keeps software rendering quick.
    const scene = await createScene(url, 'dam_break', ['particle_spacing=0.03125']);
    assert.equal(scene.particles, 4096);
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const problems = watchProblems(page);
    await page.goto(url);
    await statAtLeast(page, 'particles', 4096);
    await page.click('#play');
    await statAtLeast(page, 'frames', 10);
    assert.equal(await stat(page, 'particles'), 4096);

    // Particles were drawn.
    const drawn = await canvasSummary(page);
    assert.ok(drawn.fluid > 500, `only ${drawn.fluid} fluid pixels`);

    // Pause: frames stop arriving (once those on their way are drawn; the overlay counts them
    // once a second).
    await page.click('#pause');
    let before = await stat(page, 'frames');
    for (let i = 0; i < 8; i++) {
      await page.waitForTimeout(1200);
      const now = await stat(page, 'frames');
      if (now === before) break;
      before = now;
    }
    await page.waitForTimeout(2000);
    const after = await stat(page, 'frames');
    assert.equal(after, before, `frames kept arriving after pause (${before} -> ${after})`);
    await page.screenshot({ path: path.join(root, 'target/viewer.png') });

    // Reset: the scene goes back to t = 0 (the overlay polls the status).
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
    // The module's bounded settings get sliders from the scene's tunables.
    await page.evaluate(() => {
      const x = document.querySelector('input[data-path="fluids[0].xsph"]');
      x.value = '0.25';
      x.dispatchEvent(new Event('change'));
    });
    await page.waitForFunction(async () => {
      const s = await (await fetch('/api/v1/scenes/1')).json();
      return Math.abs(s.scene.fluids[0].xsph - 0.25) < 1e-6;
    }, null, { timeout: 10_000 });
    assert.deepEqual(problems, [], 'nothing went wrong on the page before the restart');

    // An address naming a scene that does not exist says so and opens the list's first.
    const lost = await browser.newPage({ viewport: { width: 600, height: 400 } });
    const lostProblems = watchProblems(lost);
    await lost.goto(`${url}#scene=999`);
    await lost.waitForFunction(() => /^scene 999: .*999/.test(document.querySelector('#view-error').textContent),
      null, { timeout: 10_000 });
    await lost.waitForFunction(() => document.querySelector('#scenes').value === '1', null, { timeout: 10_000 });
    await statAtLeast(lost, 'particles', 4096);
    // The browser logs the 404 it was answered, and nothing else went wrong.
    assert.ok(lostProblems.includes(`HTTP 404: ${new URL('/api/v1/scenes/999', url)}`), lostProblems.join('\n'));
    assert.deepEqual(lostProblems.filter((p) => !/404/.test(p)), []);
    await lost.close();

    // The server restarts under the page (same address, same data): scene 1 comes
    // back from its checkpoint with its live settings, and the viewer finds it again
    // by itself and streams it once it runs.
    server.kill('SIGTERM');
    await server.exited;
    const framesBefore = await stat(page, 'frames');
    server = (await startServer({ http: new URL(url).host, dataDir })).child;
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
    await statAtLeast(page, 'frames', reconnected + 5, 30_000);
    // While the server was down, the page's reconnection attempts failed as they should; only
    // page errors would be bugs.
    assert.deepEqual(problems.filter((p) => p.startsWith('page error')), []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
    rmSync(dataDir, { recursive: true, force: true });
  }
});
