// Ice that melts in headless Chromium: the ice cube of ice_cube_in_glass (1 cm) laid on water at
// 350 K. The page opens it coloured by none and asks for the material and the liquid fraction;
// the ice is drawn in the ice's pale look and the water blue, in the default surface view (the
// ice as spheres over the water's surface) and in the spheres view, and as it melts without a
// page error. A colour map chosen for it is not kept for the next scene opened, which starts on
// none again (the floating blocks: their ice-look bodies told from the water by the material
// alone; drawn alone when the "Particles" menu picks the set `solid`), and the bunny, all ice, is an ice surface. Leaves screenshots in target/viewer-phases*.png. Needs a server with the heat and
// solid modules (FLOE_BIN, or a current target/debug/floe).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { createScene, launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

/**
 * Pixels by hue: pale (ice: red close to blue), bright pale (lit ice, brighter than the walls'
 * grey lines) and blue (water: blue well above red).
 */
function hues(page) {
  return page.evaluate(() => {
    const c = document.querySelector('#view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let pale = 0, bright = 0, blue = 0;
    for (let i = 0; i < px.length; i += 4) {
      const [r, g, b] = [px[i], px[i + 1], px[i + 2]];
      if (r + g + b < 150) continue;
      if (b - r > 60) blue++;
      else if (b - r < 45 && r > 90) {
        pale++;
        if (r > 130) bright++;
      }
    }
    return { pale, bright, blue };
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
    const blocks = await createScene(url, 'floating_blocks', ['particle_spacing=0.04']);
    const bunny = await createScene(url, 'bunny', ['particle_spacing=0.02']);
    const page = await browser.newPage({ viewport: { width: 900, height: 640 } });
    const problems = watchProblems(page);
    const streams = [];
    page.on('websocket', (ws) => {
      const u = new URL(ws.url());
      if (!u.searchParams.has('set')) streams.push(u.searchParams.get('channels'));
    });
    await page.goto(`${url}#scene=${scene.scene_id}`);
    await statAtLeast(page, 'particles', scene.particles, 20_000);
    assert.equal(await page.inputValue('#colour'), 'none', 'a melting scene opens coloured by none');
    assert.deepEqual(streams.at(-1).split(','), ['material', 'liquid_fraction']);
    // The default view: the water's surface, the ice over it in its own look.
    assert.equal(await page.inputValue('#view-mode'), 'surface');
    await page.waitForTimeout(800);
    const surface = await hues(page);
    await page.screenshot({ path: path.join(root, 'target/viewer-phases-surface.png') });
    assert.ok(surface.bright > 1000 && surface.blue > 1000, `surface view: ice ${surface.bright} pixels, water ${surface.blue}`);
    await page.selectOption('#view-mode', 'spheres');
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

    // Another scene opens on none, asking for the material of its ice-look bodies.
    await page.selectOption('#scenes', String(blocks.scene_id));
    await statAtLeast(page, 'particles', blocks.particles, 20_000);
    assert.equal(await page.inputValue('#colour'), 'none', 'the colour map is not carried to another scene');
    assert.equal(streams.at(-1), 'material');
    await page.selectOption('#view-mode', 'surface');
    await page.waitForTimeout(800);
    const floating = await hues(page);
    await page.screenshot({ path: path.join(root, 'target/viewer-phases-blocks.png') });
    assert.ok(floating.bright > 1000 && floating.blue > 1000, `floating blocks: ice ${floating.bright} pixels, water ${floating.blue}`);
    // The solid's particles alone: the "Particles" menu streams the set `solid`, and the water goes.
    assert.equal(await page.isVisible('#part-section'), true);
    assert.deepEqual(await page.$$eval('#part option', (o) => o.map((x) => x.value)), ['particles', 'solid', 'fluid']);
    const solidSet = blocks.sets.find((s) => s.name === 'solid');
    assert.equal(solidSet.part_of, 'particles');
    const parts = [];
    page.on('websocket', (ws) => parts.push(new URL(ws.url()).searchParams.get('set')));
    await page.selectOption('#part', 'solid');
    await page.waitForFunction((n) => Number(/particles\s+([\d.]+)/.exec(document.querySelector('#stats').textContent)?.[1]) === n,
      solidSet.count, { timeout: 20_000 });
    assert.ok(parts.includes('solid'), `streams opened: ${parts}`);
    await page.waitForTimeout(800);
    const bodies = await hues(page);
    assert.ok(bodies.bright > 300 && bodies.blue < bodies.bright / 10, `the solid set: ice ${bodies.bright} pixels, water ${bodies.blue}`);
    await page.selectOption('#part', 'particles');
    await statAtLeast(page, 'particles', blocks.particles, 20_000);

    // A body all of ice is an ice surface, not water.
    await page.selectOption('#scenes', String(bunny.scene_id));
    await statAtLeast(page, 'particles', bunny.particles, 20_000);
    await page.waitForTimeout(800);
    const ice = await hues(page);
    await page.screenshot({ path: path.join(root, 'target/viewer-phases-bunny.png') });
    assert.ok(ice.bright > 1000 && ice.blue < ice.bright / 10, `the bunny: ice ${ice.bright} pixels, water ${ice.blue}`);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
  }
});
