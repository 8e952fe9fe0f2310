// Snowfall in the viewer: a scene with no SPH particles at all, only flakes (a set of their own)
// and the snow cover (a grid set of cells). The viewer lists both as their frames arrive, follows
// the scene as it runs, draws them, and reports nothing wrong on the way.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { createScene, launchBrowser, otherSetsPixels, root, startServer, watchProblems } from './harness.mjs';

test('the viewer draws falling flakes and the snow cover of a scene without particles', { timeout: 120_000 }, async () => {
  const { child, url } = await startServer();
  const browser = await launchBrowser();
  try {
    await createScene(url, 'snow_roof', ['snowfall.intensity={"flakes_per_m2_s":20}', 'snowfall.flutter=1']);
    const page = await browser.newPage({ viewport: { width: 900, height: 600 } });
    const problems = watchProblems(page);
    await page.goto(url);
    const listed = (re) => page.waitForFunction((s) => new RegExp(s).test(document.querySelector('#stats').textContent),
      re.source, { timeout: 30_000 });
    await listed(/snow_cover\s+64 x 1 x 16 cells/);
    await listed(/flakes\s+\d+ particles/);
    await page.click('#play');
    await page.waitForFunction(() => Number(/snow_cover\s+.* \(step (\d+)\)/.exec(document.querySelector('#stats').textContent)?.[1]) > 30,
      null, { timeout: 60_000 });
    await page.click('#pause');
    const differ = await otherSetsPixels(page);
    assert.ok(differ > 500, `only ${differ} pixels show the flakes and the cover`);
    await page.screenshot({ path: path.join(root, 'target/viewer-snowfall.png') });
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    child.kill();
    await child.exited;
  }
});
