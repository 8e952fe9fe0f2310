// A terrain scene in the viewer: the page fetches the terrain's height grid once and draws it as
// a lit mesh under the particles. Leaves a screenshot in target/viewer-terrain.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { canvasPixels, launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

// Water over the default mountain slope (1 m high at x = 0, 30 degrees, into a valley at y = 0).
const SCENE = `
particle_spacing = 0.05
[[fluids]]
blocks = [{ min = [0.2, 1.0, 0.3], max = [0.6, 1.3, 0.7] }]
[[boundaries]]
kind = "terrain"
min = [0, 0]
max = [2, 1]
friction = 0.3
`;

/** Whether a pixel's red exceeds its blue by 12 or more: the terrain's earth colour (water,
 *  background, floor and walls are blue or grey). */
const isEarth = (px, i) => px[i] - px[i + 2] >= 12;

test('a terrain is drawn as a lit mesh under the particles', { timeout: 120_000 }, async () => {
  const { child: server, url } = await startServer();
  const browser = await launchBrowser();
  try {
    const r = await fetch(new URL('/api/v1/scenes', url), {
      method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ document: SCENE }),
    });
    assert.equal(r.status, 201, await r.clone().text());
    const { scene_id: id } = await r.json();
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const problems = watchProblems(page);
    const asked = [];
    page.on('request', (q) => { if (q.url().endsWith(`/api/v1/scenes/${id}/terrain`)) asked.push(q.url()); });
    await page.goto(url);
    await statAtLeast(page, 'frames', 1);
    await page.selectOption('#view-mode', 'spheres');
    await page.waitForTimeout(800);
    await page.screenshot({ path: path.join(root, 'target/viewer-terrain.png') });
    assert.deepEqual(problems, []);
    assert.equal(asked.length, 1, 'the height grid is fetched once');
    const px = await canvasPixels(page);
    let earth = 0;
    // Lit: the slope facing the light and the valley differ in brightness.
    const seen = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (!isEarth(px, i)) continue;
      earth++;
      seen.add(px[i] >> 3);
    }
    assert.ok(earth > 20_000, `only ${earth} pixels of terrain drawn`);
    const shades = seen.size;
    assert.ok(shades >= 3, `the terrain is drawn in ${shades} shades only: no lighting`);
  } finally {
    await browser.close();
    server.kill();
    await server.exited;
  }
});
