// Ice that melts in headless Chromium: the ice cube of ice_cube_in_glass (1 cm) laid on water at
// 350 K. The page opens it coloured by none and asks for the material and the liquid fraction;
// the ice is drawn in the ice's pale look and the water blue (the spheres view), and as it melts
// without a page error. Leaves a screenshot in target/viewer-phases.png. Needs a server with
// the heat and solid modules (FLOE_BIN, or a current target/debug/floe).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { createScene, launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

/** Pixels by hue: pale (ice: red close to blue) and blue (water: blue well above red). */
function hues(page) {
  return page.evaluate(() => {
    const c = document.querySelector('#view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let pale = 0, blue = 0;
    for (let i = 0; i < px.length; i += 4) {
      const [r, g, b] = [px[i], px[i + 1], px[i + 2]];
      if (r + g + b < 150) continue;
      if (b - r > 60) blue++;
      else if (b - r < 45 && r > 90) pale++;
    }
    return { pale, blue };
  });
}

test('ice is drawn as ice and water as water', { timeout: 90_000 }, async () => {
  const { child: server, url } = await startServer({ quiet: true });
  const browser = await launchBrowser();
  try {
    const scene = await createScene(url, 'ice_cube_in_glass', [
      'particle_spacing=0.01',
      'heat.fluids[0].temperature=350',
      'fluids[1].blocks[0].min=[0.03,0.08,0.03]',
      'fluids[1].blocks[0].max=[0.07,0.12,0.07]',
    ]);
    const page = await browser.newPage({ viewport: { width: 900, height: 640 } });
    const problems = watchProblems(page);
    const streams = [];
    page.on('websocket', (ws) => {
      const u = new URL(ws.url());
      if (!u.searchParams.has('set')) streams.push(u.searchParams.get('channels'));
    });
    await page.goto(`${url}#scene=${scene.scene_id}`);
    await page.selectOption('#view-mode', 'spheres');
    await statAtLeast(page, 'particles', scene.particles, 20_000);
    assert.equal(await page.inputValue('#colour'), 'none', 'a melting scene opens coloured by none');
    assert.deepEqual(streams.at(-1).split(','), ['material', 'liquid_fraction']);
    await page.waitForTimeout(800);
    const still = await hues(page);
    assert.ok(still.pale > 200 && still.blue > 1000, `ice ${still.pale} pixels, water ${still.blue}`);
    await page.click('#play');
    await statAtLeast(page, 'frames', 15, 30_000);
    await page.waitForTimeout(800);
    const melting = await hues(page);
    assert.ok(melting.blue > 1000, `water ${melting.blue} pixels while melting`);
    await page.screenshot({ path: path.join(root, 'target/viewer-phases.png') });
    // Coloured by temperature, the page asks for the temperature alone: the colour map replaces the phases.
    await page.selectOption('#colour', 'temperature');
    for (let k = 0; k < 50 && streams.at(-1) !== 'temperature'; k++) await page.waitForTimeout(100);
    assert.equal(streams.at(-1), 'temperature');
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
  }
});
