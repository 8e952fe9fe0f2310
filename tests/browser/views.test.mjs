// A scene larger than the viewer's particle budget, in headless Chromium: the page (with
// `?budget=1000`) streams the camera's view of the 8,000-particle dam break, the overlay says
// how many of the scene's particles it draws, and as the camera pans away from the water and back
// (the scene paused) the frames it receives follow: none of the water where the camera looks
// away, the budget again once it is framed. Counts are read from each received frame's header.
// Leaves target/viewer-views.png. Needs a server (FLOE_BIN, or a current target/debug/floe).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { createScene, launchBrowser, root, startServer, watchProblems } from './harness.mjs';

const BUDGET = 1000;

test('the viewer streams the camera view of a scene larger than its budget', { timeout: 120_000 }, async () => {
  const { child: server, url } = await startServer({ quiet: true });
  const browser = await launchBrowser();
  try {
    const scene = await createScene(url, 'dam_break', ['particle_spacing=0.025']);
    assert.equal(scene.particles, 8000);
    const page = await browser.newPage({ viewport: { width: 900, height: 640 } });
    const problems = watchProblems(page);
    /** Particles of each frame received on the scene's own socket (the header's count, bytes 12..16). */
    const counts = [];
    page.on('websocket', (ws) => {
      if (new URL(ws.url()).searchParams.has('set')) return;
      ws.on('framereceived', (f) => {
        if (typeof f.payload !== 'string') counts.push(f.payload.readUInt32LE(12));
      });
    });
    const frameWhere = async (ok, what) => {
      const from = counts.length;
      for (let k = 0; k < 200; k++) {
        if (counts.slice(from).some(ok)) return counts.slice(from).find(ok);
        await page.waitForTimeout(100);
      }
      assert.fail(`no frame with ${what} (received ${counts.slice(from).join(', ')})`);
    };
    await page.goto(`${url}?budget=${BUDGET}#scene=${scene.scene_id}`);
    await frameWhere((n) => n === BUDGET, `the budget's ${BUDGET} particles`);
    await page.waitForFunction(() => document.querySelector('#stats').textContent.includes("of 8000 (the camera's view)"));
    // Pan (shift-drag) far to the side: the camera looks past the water.
    const box = await page.locator('#view').boundingBox();
    const [x0, y0] = [box.x + box.width / 2, box.y + box.height / 2];
    await page.keyboard.down('Shift');
    for (let k = 0; k < 4; k++) {
      await page.mouse.move(x0 + 50, y0);
      await page.mouse.down();
      await page.mouse.move(x0 + 350, y0, { steps: 5 });
      await page.mouse.up();
    }
    await page.keyboard.up('Shift');
    await frameWhere((n) => n < BUDGET / 10, 'the water out of view');
    // Framed again (F): the budget again.
    await page.locator('#view').click();
    await page.keyboard.press('f');
    await frameWhere((n) => n === BUDGET, 'the water framed again');
    await page.screenshot({ path: path.join(root, 'target/viewer-views.png') });
    assert.ok(counts.every((n) => n <= BUDGET), `every frame within the budget: ${counts.join(', ')}`);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill();
  }
});
