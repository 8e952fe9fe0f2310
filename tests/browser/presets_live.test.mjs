// Presets sized to the machine, as a new user meets them: `floe serve --backend cpu
// --preset-size auto` with no scene, the viewer creating bunny, ice_melting and avalanche from
// its own preset menu and Create button, then Play (at the page's real-time factor, 1). Each
// must keep up with at least half of real time (simulated over wall seconds, from the scene's
// sim_time over REST) while the page draws it, here where the server and software GL share the
// machine's cores, and the overlay says at what resolution it was sized and how fast it runs.
// The Full size button then opens the bunny at its own resolution. Screenshots go to
// target/viewer-live-*.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { launchBrowser, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

/**
 * The real-time factor asserted: half of what sizing aims at (1, the scene stepped alone), the
 * rest of the machine going to the page's drawing and the server's streaming.
 */
const LEAST_RTF = 0.5;
/** Wall time (ms) the achieved factor is measured over, after the run has started. */
const MEASURE_MS = 4000;

/** The scene, over REST. */
async function sceneInfo(url, id) {
  const r = await fetch(new URL(`/api/v1/scenes/${id}`, url));
  assert.equal(r.status, 200);
  return r.json();
}

/** The scene's simulated time (s). */
const simTime = async (url, id) => (await sceneInfo(url, id)).sim_time;

test('presets sized for the machine run at half of real time or more in the viewer', { timeout: 90_000 }, async (t) => {
  const { child: server, url } = await startServer({ quiet: true, presetSize: 'auto', backend: 'cpu' });
  const browser = await launchBrowser();
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const problems = watchProblems(page);
    await page.goto(url);
    await page.waitForFunction(() => document.querySelector('#preset').options.length > 0);
    const measured = {}, ids = {};
    for (const preset of ['bunny', 'ice_melting', 'avalanche']) {
      await page.selectOption('#preset', preset);
      await page.click('#create');
      // The new scene opens (the server sizes a preset the first time it is asked for, a second
      // or two) and the overlay says how it was sized.
      await page.waitForFunction((p) => document.querySelector('#scenes').selectedOptions[0]?.text.includes(`: ${p} `),
        preset, { timeout: 30_000 });
      await statAtLeast(page, 'frames', 1, 20_000);
      await page.waitForFunction(() => /size\s+[\d,]+ of [\d,]+ particles \([\d.]+ cm spacing, full size [\d.]+ cm\), sized for this machine/
        .test(document.querySelector('#stats').textContent), null, { timeout: 10_000 });
      const id = Number(await page.inputValue('#scenes'));
      ids[preset] = id;
      assert.equal(await page.isVisible('#full-size'), true, 'the full size is offered');

      await page.click('#play');
      await page.waitForFunction(() => /\(running\)/.test(document.querySelector('#stats').textContent), null, { timeout: 10_000 });
      // The first step and the first frames drawn, then the measured span.
      await page.waitForTimeout(1000);
      const [sim0, wall0] = [await simTime(url, id), performance.now()];
      await page.waitForTimeout(MEASURE_MS);
      const [sim1, wall1] = [await simTime(url, id), performance.now()];
      const rtf = (sim1 - sim0) / ((wall1 - wall0) / 1000);
      // The overlay's achieved factor, beside the one measured when sizing.
      await page.waitForFunction(() => /real time\s+[\d.e-]+ of 1\.0 asked.*; sized for [\d.]+/
        .test(document.querySelector('#stats').textContent), null, { timeout: 5_000 });
      const overlay = await page.textContent('#stats');
      await page.screenshot({ path: path.join(root, `target/viewer-live-${preset}.png`) });
      await page.click('#pause');
      measured[preset] = rtf;
      t.diagnostic(`${preset}: ${rtf.toFixed(2)} x real time over ${((wall1 - wall0) / 1000).toFixed(1)} s; `
        + overlay.split('\n').filter((l) => /^(particles|size|real time|render)/.test(l)).join(' | '));
    }

    // The bunny at its full size, in one click: a scene of its own, sized by its creator.
    const { sizing } = await sceneInfo(url, ids.bunny);
    await page.selectOption('#scenes', String(ids.bunny));
    await page.click('#full-size');
    await page.waitForFunction((n) => document.querySelector('#scenes').selectedOptions[0]?.text.endsWith(`: bunny (${n} particles)`),
      sizing.full_particles, { timeout: 30_000 });
    const full = await sceneInfo(url, Number(await page.inputValue('#scenes')));
    assert.equal(full.particle_spacing, sizing.full_spacing);
    assert.equal(full.sizing, undefined);
    await statAtLeast(page, 'particles', sizing.full_particles, 20_000);
    assert.equal(await page.isHidden('#sizing'), true, 'no smaller size to leave');
    assert.doesNotMatch(await page.textContent('#stats'), /sized for this machine/);

    for (const [preset, rtf] of Object.entries(measured)) {
      assert.ok(rtf >= LEAST_RTF, `${preset} ran at ${rtf.toFixed(2)} x real time (all: ${JSON.stringify(measured)})`);
    }
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
    await server.exited;
  }
});
