// The avalanche in the viewer: snow drawn white on its terrain (spheres and surface), coloured by
// viscosity or shear rate on request. Leaves screenshots in target/viewer-avalanche*.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { canvasPixels, launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

/** Pixels close to white (the snow's plain colour). */
async function whitePixels(page) {
  const px = await canvasPixels(page);
  let n = 0;
  for (let i = 0; i < px.length; i += 4) if (px[i] > 170 && px[i + 1] > 170 && px[i + 2] > 170) n++;
  return n;
}

test('snow is white and can be coloured by viscosity and shear rate', { timeout: 120_000 }, async () => {
  const { child: server, url } = await startServer();
  const browser = await launchBrowser();
  try {
    const r = await fetch(new URL('/api/v1/scenes', url), {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify({ preset: 'avalanche', overrides: ['particle_spacing=0.05'] }),
    });
    assert.equal(r.status, 201, await r.clone().text());
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const problems = watchProblems(page);
    await page.goto(url);
    await statAtLeast(page, 'frames', 1);
    // The surface view draws the snow as an opaque white body, not as blue water.
    await page.selectOption('#view-mode', 'surface');
    await page.waitForTimeout(800);
    await page.screenshot({ path: path.join(root, 'target/viewer-avalanche-surface.png') });
    const surface = await whitePixels(page);
    assert.ok(surface > 500, `snow's surface drawn white: ${surface} white pixels`);
    await page.selectOption('#view-mode', 'spheres');
    const modes = await page.$$eval('#colour option', (o) => o.map((x) => x.value));
    assert.ok(modes.includes('viscosity') && modes.includes('shear_rate'), `colour modes ${modes}`);
    await page.selectOption('#colour', 'none');
    await page.waitForTimeout(800);
    await page.screenshot({ path: path.join(root, 'target/viewer-avalanche.png') });
    const white = await whitePixels(page);
    await page.selectOption('#colour', 'viscosity');
    // The page reopens its stream for the new channel; one step gives every particle its
    // viscosity (zero before the first evaluation).
    await statAtLeast(page, 'frames', 2);
    await page.click('#step');
    await statAtLeast(page, 'frames', 3);
    await page.waitForTimeout(800);
    await page.screenshot({ path: path.join(root, 'target/viewer-avalanche-viscosity.png') });
    const coloured = await whitePixels(page);
    assert.ok(white > 500 && coloured < white / 4, `snow drawn white: ${white} white pixels, ${coloured} when coloured`);
    assert.equal(await page.isHidden('#legend'), false, 'the legend shows the viscosity range');
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill();
    await server.exited;
  }
});
