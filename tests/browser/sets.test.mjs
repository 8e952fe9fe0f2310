// Every set of a scene drawn: `floe_traced` (floe with the tests' tracer module compiled in,
// `cargo build -p floe-tests --example floe_traced`) runs a dam break whose tracer adds four
// probes and a grid of 8 x 1 x 8 columns counting the particles above each cell. The viewer
// streams both beside the particles, lists them in its overlay as their frames arrive, draws them
// (the picture differs with them hidden), and the grid's frames follow the scene's steps.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { createScene, launchBrowser, otherSetsPixels, root, startServer, statAtLeast, watchProblems } from './harness.mjs';

const traced = process.env.FLOE_TRACED_BIN ?? path.join(root, 'target/debug/examples/floe_traced');

/** The step of the latest frame of set `name`, as the overlay lists it (-1 when absent). */
async function setStep(page, name) {
  const text = await page.textContent('#stats');
  const m = text.match(new RegExp(`${name}\\s+.* \\(step (\\d+)\\)`));
  return m ? Number(m[1]) : -1;
}

test('the viewer draws a scene\'s probes and grid beside its particles', { timeout: 120_000 }, async () => {
  const { child, url } = await startServer({ binary: traced });
  const browser = await launchBrowser();
  try {
    await createScene(url, 'dam_break', ['particle_spacing=0.05', 'modules=["fluid","tracer"]']);
    const page = await browser.newPage({ viewport: { width: 900, height: 600 } });
    const problems = watchProblems(page);
    await page.goto(url);
    await statAtLeast(page, 'particles', 1000);
    await page.waitForFunction(() => /columns\s+8 x 1 x 8 cells/.test(document.querySelector('#stats').textContent),
      null, { timeout: 30_000 });
    await page.waitForFunction(() => /probes\s+4 particles/.test(document.querySelector('#stats').textContent),
      null, { timeout: 30_000 });
    // The grid's frames follow the scene as it runs.
    await page.click('#play');
    await page.waitForFunction(() => Number(/columns\s+.* \(step (\d+)\)/.exec(document.querySelector('#stats').textContent)?.[1]) > 20,
      null, { timeout: 60_000 });
    await page.click('#pause');
    assert.ok(await setStep(page, 'columns') > 20);
    // Drawn: hiding the other sets changes the picture.
    const differ = await otherSetsPixels(page);
    assert.ok(differ > 500, `only ${differ} pixels show the grid and probes`);
    await page.screenshot({ path: path.join(root, 'target/viewer-sets.png') });
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    child.kill();
    await child.exited;
  }
});
