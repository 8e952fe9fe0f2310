// Oriented particles in headless Chromium: an elastic drop with `solid.oriented` on (thin
// ellipsoids, 0.5 x 0.25 x 0.25 spacings) and one without. The page asks for the orientation
// channel only for the first, whatever the colour; coloured by speed in the spheres view the thin ellipsoids leave gaps the spheres of
// the second close; the oriented drop plays and is drawn, in both views, without a page error.
// Leaves a screenshot in target/viewer-ellipsoids.png. Needs a server with oriented particles
// (FLOE_BIN, or a current target/debug/floe).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { canvasSummary, createScene, launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

/** Waits for the next frames to be drawn. */
const settle = (page) => page.waitForTimeout(800);

/**
 * Colours the particles by speed (each scene opens on none) and waits for the page to ask for
 * `channels` on scene `id`'s stream.
 */
async function colourBySpeed(page, streams, id, channels) {
  await page.selectOption('#colour', 'velocity');
  for (let k = 0; k < 50 && streams[id] !== channels; k++) await page.waitForTimeout(100);
  assert.equal(streams[id], channels);
}

test('oriented particles are drawn as ellipsoids in the spheres view', { timeout: 90_000 }, async () => {
  const { child: server, url } = await startServer({ quiet: true });
  const browser = await launchBrowser();
  try {
    const oriented = await createScene(url, 'elastic_drop', ['solid.oriented={"radii":[0.5,0.25,0.25]}']);
    const plain = await createScene(url, 'elastic_drop');
    assert.ok(oriented.channels.some((c) => c.name === 'orientation'), 'the oriented scene streams orientations');
    assert.ok(!plain.channels.some((c) => c.name === 'orientation'));
    const page = await browser.newPage({ viewport: { width: 900, height: 640 } });
    const problems = watchProblems(page);
    // The particle streams the page opens (not the other sets'), by scene.
    const streams = {};
    page.on('websocket', (ws) => {
      const u = new URL(ws.url());
      const id = /scenes\/(\d+)\/ws/.exec(u.pathname)?.[1];
      if (id && !u.searchParams.has('set')) streams[id] = u.searchParams.get('channels');
    });
    await page.goto(`${url}#scene=${oriented.scene_id}`);
    await page.selectOption('#view-mode', 'spheres');
    await statAtLeast(page, 'particles', oriented.particles, 20_000);
    await page.waitForFunction(() => /oriented\s+ellipsoids 10 x 5\.0 x 5\.0 mm\n/.test(`${document.querySelector('#stats').textContent}\n`),
      null, { timeout: 10_000 });
    assert.equal(streams[oriented.scene_id], 'orientation', 'orientations, coloured by none');
    await colourBySpeed(page, streams, oriented.scene_id, 'velocity,orientation');
    await statAtLeast(page, 'frames', 2, 10_000);
    await settle(page);
    const thin = await canvasSummary(page);

    // The same drop without oriented particles: spheres, no orientation asked for.
    await page.selectOption('#scenes', String(plain.scene_id));
    await page.waitForFunction(() => !/oriented/.test(document.querySelector('#stats').textContent), null, { timeout: 10_000 });
    assert.equal(streams[plain.scene_id], '');
    await colourBySpeed(page, streams, plain.scene_id, 'velocity');
    await settle(page);
    const round = await canvasSummary(page);
    assert.ok(round.fluid > 1000, `only ${round.fluid} particle pixels for spheres`);
    // Seen from the default camera the cube of 10 x 10 x 10 is a few pixels a particle: the rods
    // (full width along x, half across) cover less (about 0.88 of the spheres' pixels here) and
    // let the background through between them (about ten times the spheres' gaps).
    assert.ok(thin.fluid > 0.5 * round.fluid && thin.fluid < 0.95 * round.fluid,
      `thin ellipsoids cover ${thin.fluid} pixels, spheres ${round.fluid}`);
    assert.ok(thin.gaps > 3 * round.gaps + 100, `gaps between ellipsoids ${thin.gaps}, between spheres ${round.gaps}`);

    // Back to the oriented drop: it plays, and its turning particles are drawn.
    await page.selectOption('#scenes', String(oriented.scene_id));
    await page.waitForFunction(() => /oriented/.test(document.querySelector('#stats').textContent), null, { timeout: 10_000 });
    await page.click('#play');
    await statAtLeast(page, 'frames', 15, 30_000);
    await settle(page);
    const played = await canvasSummary(page);
    assert.ok(played.fluid > 200, `only ${played.fluid} particle pixels after playing`);
    await page.screenshot({ path: path.join(root, 'target/viewer-ellipsoids.png') });
    // The surface view still draws them (as spheres), and back in the spheres view ellipsoids.
    await page.selectOption('#view-mode', 'surface');
    await page.waitForFunction(() => /oriented .* \(spheres view\)/.test(document.querySelector('#stats').textContent), null, { timeout: 10_000 });
    await settle(page);
    assert.ok((await canvasSummary(page)).scene, 'the surface view draws the scene');
    await page.selectOption('#view-mode', 'spheres');
    await settle(page);
    assert.ok((await canvasSummary(page)).fluid > 200, 'ellipsoids drawn again');
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
  }
});
